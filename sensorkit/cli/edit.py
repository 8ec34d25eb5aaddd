"""``sensorkit add-camera | add-depth-camera | add-lidar | add-stereo | add-imu``.

Each command maps its options onto the parameters of one sensor macro and calls
``sensorkit.edit.add_sensor``. Options left out keep the macro's defaults. ``add-lidar``
uses the 2D macro unless ``--3d`` is given; the vertical options need ``--3d``.
"""

from __future__ import annotations

import enum
import math
from pathlib import Path
from typing import Annotated

import typer

from sensorkit.cli.common import (
    ArgOpt,
    ColorOpt,
    ConfigOpt,
    EnvOpt,
    FileArg,
    PackagePathOpt,
    QuietOpt,
    UntrustedOpt,
    collector_off,
    die,
    handle_errors,
    note,
    refuse_stdin,
    settings,
    use_color,
)


class Sim(str, enum.Enum):
    classic = "classic"
    gz = "gz"
    none = "none"


class GzVersion(str, enum.Enum):
    fortress = "fortress"
    harmonic = "harmonic"
    jetty = "jetty"


Vec3 = tuple[float, float, float]
_SENSOR = "sensor"
_MOUNT = "mount"
_OUT = "output"

NameOpt = Annotated[
    str,
    typer.Option(
        "--name",
        help="sensor name: becomes NAME_link, NAME_joint, topics NAME/...",
        show_default=False,
        rich_help_panel=_MOUNT,
    ),
]
ParentOpt = Annotated[
    str,
    typer.Option(
        "--parent",
        help="existing link to mount the sensor on",
        show_default=False,
        rich_help_panel=_MOUNT,
    ),
]
XyzOpt = Annotated[
    Vec3,
    typer.Option(
        "--xyz",
        help="mount position in the parent link (m)",
        metavar="X Y Z",
        rich_help_panel=_MOUNT,
    ),
]
RpyOpt = Annotated[
    Vec3,
    typer.Option(
        "--rpy",
        help="mount roll pitch yaw in the parent link (rad)",
        metavar="R P Y",
        rich_help_panel=_MOUNT,
    ),
]
SimOpt = Annotated[
    Sim | None,
    typer.Option(
        "--sim",
        help="simulator the sensor block is for [default: the robot's: its other sensors' "
        "sim expression, else what --target auto sees, else classic]",
        show_default=False,
    ),
]
GzVersionOpt = Annotated[
    GzVersion | None,
    typer.Option(
        "--gz-version",
        help="Gazebo Sim version (frame tag) [macro default: harmonic]",
        show_default=False,
    ),
]
NamespaceOpt = Annotated[
    str | None,
    typer.Option("--namespace", help="ROS namespace of the sensor's topics", show_default=False),
]
MassOpt = Annotated[
    float | None,
    typer.Option(
        "--mass", help="sensor body mass (kg)", show_default=False, rich_help_panel=_SENSOR
    ),
]
SizeOpt = Annotated[
    Vec3 | None,
    typer.Option(
        "--size",
        help="sensor body box size (m)",
        metavar="X Y Z",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
UpdateRateOpt = Annotated[
    float | None,
    typer.Option("--update-rate", help="Hz", show_default=False, rich_help_panel=_SENSOR),
]
WidthOpt = Annotated[
    int | None,
    typer.Option("--width", help="image width (px)", show_default=False, rich_help_panel=_SENSOR),
]
HeightOpt = Annotated[
    int | None,
    typer.Option("--height", help="image height (px)", show_default=False, rich_help_panel=_SENSOR),
]
HfovOpt = Annotated[
    float | None,
    typer.Option(
        "--hfov", help="horizontal field of view (rad)", show_default=False, rich_help_panel=_SENSOR
    ),
]
FormatOpt = Annotated[
    str | None,
    typer.Option(
        "--format", help="pixel format, e.g. R8G8B8", show_default=False, rich_help_panel=_SENSOR
    ),
]
NearOpt = Annotated[
    float | None,
    typer.Option("--near", help="near clip (m)", show_default=False, rich_help_panel=_SENSOR),
]
FarOpt = Annotated[
    float | None,
    typer.Option("--far", help="far clip (m)", show_default=False, rich_help_panel=_SENSOR),
]
NoiseOpt = Annotated[
    float | None,
    typer.Option(
        "--noise-stddev", help="gaussian noise stddev", show_default=False, rich_help_panel=_SENSOR
    ),
]
MinDepthOpt = Annotated[
    float | None,
    typer.Option(
        "--min-depth", help="depth/point cloud min (m)", show_default=False, rich_help_panel=_SENSOR
    ),
]
MaxDepthOpt = Annotated[
    float | None,
    typer.Option(
        "--max-depth", help="depth/point cloud max (m)", show_default=False, rich_help_panel=_SENSOR
    ),
]
BaselineOpt = Annotated[
    float | None,
    typer.Option(
        "--baseline",
        help="distance between the two cameras (m)",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
SamplesOpt = Annotated[
    int | None,
    typer.Option("--samples", help="horizontal beams", show_default=False, rich_help_panel=_SENSOR),
]
ResolutionOpt = Annotated[
    float | None,
    typer.Option(
        "--resolution",
        help="horizontal resolution factor",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
MinAngleOpt = Annotated[
    float | None,
    typer.Option(
        "--min-angle",
        help="horizontal start angle (rad)",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
MaxAngleOpt = Annotated[
    float | None,
    typer.Option(
        "--max-angle",
        help="horizontal end angle (rad)",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
RangeMinOpt = Annotated[
    float | None,
    typer.Option(
        "--range-min", help="minimum range (m)", show_default=False, rich_help_panel=_SENSOR
    ),
]
RangeMaxOpt = Annotated[
    float | None,
    typer.Option(
        "--range-max", help="maximum range (m)", show_default=False, rich_help_panel=_SENSOR
    ),
]
RangeResOpt = Annotated[
    float | None,
    typer.Option(
        "--range-resolution",
        help="range resolution (m)",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
ThreeDOpt = Annotated[
    bool,
    typer.Option(
        "--3d",
        help="a 3D (multi-layer) lidar: uses the sensorkit_lidar_3d macro",
        rich_help_panel=_SENSOR,
    ),
]
VSamplesOpt = Annotated[
    int | None,
    typer.Option(
        "--vertical-samples",
        help="vertical beams (needs --3d)",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
VMinOpt = Annotated[
    float | None,
    typer.Option(
        "--vertical-min-angle",
        help="lowest beam (rad, needs --3d)",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
VMaxOpt = Annotated[
    float | None,
    typer.Option(
        "--vertical-max-angle",
        help="highest beam (rad, needs --3d)",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
GyroOpt = Annotated[
    float | None,
    typer.Option("--gyro-noise-stddev", help="rad/s", show_default=False, rich_help_panel=_SENSOR),
]
AccelOpt = Annotated[
    float | None,
    typer.Option("--accel-noise-stddev", help="m/s^2", show_default=False, rich_help_panel=_SENSOR),
]
ParamOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--param",
        help="any other macro parameter NAME=VALUE (repeatable)",
        metavar="NAME=VALUE",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
DiffOpt = Annotated[
    bool,
    typer.Option("--diff", help="print the unified diff and write nothing", rich_help_panel=_OUT),
]
OutOpt = Annotated[
    Path | None,
    typer.Option(
        "-o",
        "--output",
        help="write the result here instead of editing FILE in place",
        show_default=False,
        rich_help_panel=_OUT,
    ),
]


def _text(value: object) -> str:
    from sensorkit.edit.render import format_number

    if isinstance(value, enum.Enum):
        return str(value.value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return format_number(value)
    if isinstance(value, tuple):
        return " ".join(_text(v) for v in value)
    return str(value)


def _run(
    kind: str,
    options: dict[str, object],
    *,
    file: Path,
    name: str,
    parent: str,
    xyz: Vec3,
    rpy: Vec3,
    param: list[str] | None,
    diff: bool,
    output: Path | None,
    arg: list[str] | None,
    package_path: list[str] | None,
    untrusted: bool = False,
    env: list[str] | None = None,
    config: Path | None = None,
    quiet: bool = False,
    color: str = "auto",
) -> None:
    from sensorkit.edit import AddRequest, add_sensor
    from sensorkit.lint.engine import Options
    from sensorkit.loading.document import display_path

    command = {"depth_camera": "add-depth-camera", "stereo_camera": "add-stereo", "imu": "add-imu",
               "camera": "add-camera"}.get(kind, "add-lidar")  # fmt: skip
    refuse_stdin(file, f"{command} edits the robot file in place")
    use_color(color)  # checked; nothing printed is coloured
    for angle in rpy:
        if abs(angle) > 2 * math.pi:  # 90 means degrees, by habit: a quarter turn is 1.5708
            die(
                f"--rpy {' '.join(f'{a:g}' for a in rpy)}: {angle:g} is more than 2π; angles are "
                f"in radians (radians? {angle:g}° is {math.radians(angle):.6g})"
            )
    params = {key: _text(value) for key, value in options.items() if value is not None}
    for item in param or []:
        key, sep, value = item.partition("=")
        if not sep or not key:
            die(f"--param {item!r}: expected NAME=VALUE")
        if key in params:
            die(f"--param {key}: already set by its own option")
        params[key] = value
    # Validate the way `sensorkit validate` would here: the settings file applies.
    st = settings(
        file,
        config=config,
        target=None,
        package_path=package_path,
        arg=arg,
        untrusted=untrusted,
        env=env,
    )
    cfg = st.config
    if "sim" not in params and cfg.target:  # the project's simulator, unless --sim says
        from sensorkit.model.targets import is_gz

        params["sim"] = "gz" if is_gz(cfg.target) else "classic"
        if is_gz(cfg.target) and "gz_version" not in params:
            params["gz_version"] = cfg.target
    st.say_where(quiet=quiet)
    args = st.args
    package_paths = st.package_paths
    trust = st.untrusted
    validation = Options(
        target=st.target,
        select=tuple(cfg.select),
        ignore=tuple(cfg.ignore),
        args=args,
        package_paths=package_paths,
        untrusted=trust,
    )
    req = AddRequest(
        path=file,
        kind=kind,
        name=name,
        parent=parent,
        xyz=xyz,
        rpy=rpy,
        params=params,
        output=output,
        args=args,
        package_paths=package_paths,
        validation=validation,
    )
    from sensorkit.cli import leave_quickly

    with collector_off():
        result = add_sensor(req, dry_run=diff)
    leave_quickly()  # every write is done (add_sensor returned): skip freeing the model
    if result.simulator:
        note(f"sensorkit: {result.simulator}", quiet)
    for said in result.notes:
        note(f"sensorkit: note: {said}", quiet)
    if diff:
        typer.echo(result.diff, nl=False)
        return
    made = ", ".join(result.links)
    where = display_path(result.target)
    label = result.kind.label
    note(f"sensorkit: added {label} '{result.name}' to {where} ({made})", quiet)
    for w in result.package_files:
        verb = "wrote" if w.original is None else "updated"
        why = f" ({w.why})" if w.why else ""
        note(f"sensorkit: {verb} {display_path(w.path)}{why}", quiet)


def _common(
    sim: Sim | None,
    gz_version: GzVersion | None,
    namespace: str | None,
    mass: float | None,
    size: Vec3 | None,
) -> dict[str, object]:
    return {
        "sim": sim,
        "gz_version": gz_version,
        "namespace": namespace,
        "mass": mass,
        "size": size,
    }


@handle_errors
def add_camera(
    file: FileArg,
    name: NameOpt,
    parent: ParentOpt,
    xyz: XyzOpt = (0.0, 0.0, 0.0),
    rpy: RpyOpt = (0.0, 0.0, 0.0),
    update_rate: UpdateRateOpt = None,
    width: WidthOpt = None,
    height: HeightOpt = None,
    hfov: HfovOpt = None,
    format: FormatOpt = None,
    near: NearOpt = None,
    far: FarOpt = None,
    noise_stddev: NoiseOpt = None,
    mass: MassOpt = None,
    size: SizeOpt = None,
    sim: SimOpt = None,
    gz_version: GzVersionOpt = None,
    namespace: NamespaceOpt = None,
    param: ParamOpt = None,
    diff: DiffOpt = False,
    output: OutOpt = None,
    arg: ArgOpt = None,
    package_path: PackagePathOpt = None,
    untrusted: UntrustedOpt = False,
    env: EnvOpt = None,
    config: ConfigOpt = None,
    quiet: QuietOpt = False,
    color: ColorOpt = "auto",
) -> None:
    """Add a pinhole RGB camera (sensorkit_camera macro) to FILE."""
    options = {
        "update_rate": update_rate, "width": width, "height": height, "hfov": hfov,
        "format": format, "near": near, "far": far, "noise_stddev": noise_stddev,
        **_common(sim, gz_version, namespace, mass, size),
    }  # fmt: skip
    _run(
        "camera",
        options,
        file=file,
        name=name,
        parent=parent,
        xyz=xyz,
        rpy=rpy,
        param=param,
        diff=diff,
        output=output,
        arg=arg,
        package_path=package_path,
        untrusted=untrusted,
        env=env,
        config=config,
        quiet=quiet,
        color=color,
    )


@handle_errors
def add_depth_camera(
    file: FileArg,
    name: NameOpt,
    parent: ParentOpt,
    xyz: XyzOpt = (0.0, 0.0, 0.0),
    rpy: RpyOpt = (0.0, 0.0, 0.0),
    update_rate: UpdateRateOpt = None,
    width: WidthOpt = None,
    height: HeightOpt = None,
    hfov: HfovOpt = None,
    format: FormatOpt = None,
    near: NearOpt = None,
    far: FarOpt = None,
    noise_stddev: NoiseOpt = None,
    min_depth: MinDepthOpt = None,
    max_depth: MaxDepthOpt = None,
    mass: MassOpt = None,
    size: SizeOpt = None,
    sim: SimOpt = None,
    gz_version: GzVersionOpt = None,
    namespace: NamespaceOpt = None,
    param: ParamOpt = None,
    diff: DiffOpt = False,
    output: OutOpt = None,
    arg: ArgOpt = None,
    package_path: PackagePathOpt = None,
    untrusted: UntrustedOpt = False,
    env: EnvOpt = None,
    config: ConfigOpt = None,
    quiet: QuietOpt = False,
    color: ColorOpt = "auto",
) -> None:
    """Add an RGB-D camera (sensorkit_depth_camera macro) to FILE."""
    options = {
        "update_rate": update_rate, "width": width, "height": height, "hfov": hfov,
        "format": format, "near": near, "far": far, "noise_stddev": noise_stddev,
        "min_depth": min_depth, "max_depth": max_depth,
        **_common(sim, gz_version, namespace, mass, size),
    }  # fmt: skip
    _run(
        "depth_camera",
        options,
        file=file,
        name=name,
        parent=parent,
        xyz=xyz,
        rpy=rpy,
        param=param,
        diff=diff,
        output=output,
        arg=arg,
        package_path=package_path,
        untrusted=untrusted,
        env=env,
        config=config,
        quiet=quiet,
        color=color,
    )


@handle_errors
def add_lidar(
    file: FileArg,
    name: NameOpt,
    parent: ParentOpt,
    xyz: XyzOpt = (0.0, 0.0, 0.0),
    rpy: RpyOpt = (0.0, 0.0, 0.0),
    three_d: ThreeDOpt = False,
    update_rate: UpdateRateOpt = None,
    samples: SamplesOpt = None,
    resolution: ResolutionOpt = None,
    min_angle: MinAngleOpt = None,
    max_angle: MaxAngleOpt = None,
    range_min: RangeMinOpt = None,
    range_max: RangeMaxOpt = None,
    range_resolution: RangeResOpt = None,
    noise_stddev: NoiseOpt = None,
    vertical_samples: VSamplesOpt = None,
    vertical_min_angle: VMinOpt = None,
    vertical_max_angle: VMaxOpt = None,
    mass: MassOpt = None,
    size: SizeOpt = None,
    sim: SimOpt = None,
    gz_version: GzVersionOpt = None,
    namespace: NamespaceOpt = None,
    param: ParamOpt = None,
    diff: DiffOpt = False,
    output: OutOpt = None,
    arg: ArgOpt = None,
    package_path: PackagePathOpt = None,
    untrusted: UntrustedOpt = False,
    env: EnvOpt = None,
    config: ConfigOpt = None,
    quiet: QuietOpt = False,
    color: ColorOpt = "auto",
) -> None:
    """Add a 2D lidar (sensorkit_lidar_2d macro), or with --3d a 3D one (sensorkit_lidar_3d)."""
    vertical = {
        "vertical_samples": vertical_samples,
        "vertical_min_angle": vertical_min_angle,
        "vertical_max_angle": vertical_max_angle,
    }
    given = [k for k, v in vertical.items() if v is not None]
    if given and not three_d:
        die(
            f"--{given[0].replace('_', '-')} needs --3d (the 2D lidar has one horizontal scan line)"
        )
    options = {
        "update_rate": update_rate, "samples": samples, "resolution": resolution,
        "min_angle": min_angle, "max_angle": max_angle, "range_min": range_min,
        "range_max": range_max, "range_resolution": range_resolution,
        "noise_stddev": noise_stddev,
        **vertical,
        **_common(sim, gz_version, namespace, mass, size),
    }  # fmt: skip
    kind = "lidar_3d" if three_d else "lidar_2d"
    _run(
        kind,
        options,
        file=file,
        name=name,
        parent=parent,
        xyz=xyz,
        rpy=rpy,
        param=param,
        diff=diff,
        output=output,
        arg=arg,
        package_path=package_path,
        untrusted=untrusted,
        env=env,
        config=config,
        quiet=quiet,
        color=color,
    )


@handle_errors
def add_stereo(
    file: FileArg,
    name: NameOpt,
    parent: ParentOpt,
    xyz: XyzOpt = (0.0, 0.0, 0.0),
    rpy: RpyOpt = (0.0, 0.0, 0.0),
    update_rate: UpdateRateOpt = None,
    width: WidthOpt = None,
    height: HeightOpt = None,
    hfov: HfovOpt = None,
    format: FormatOpt = None,
    near: NearOpt = None,
    far: FarOpt = None,
    noise_stddev: NoiseOpt = None,
    baseline: BaselineOpt = None,
    mass: MassOpt = None,
    size: SizeOpt = None,
    sim: SimOpt = None,
    gz_version: GzVersionOpt = None,
    namespace: NamespaceOpt = None,
    param: ParamOpt = None,
    diff: DiffOpt = False,
    output: OutOpt = None,
    arg: ArgOpt = None,
    package_path: PackagePathOpt = None,
    untrusted: UntrustedOpt = False,
    env: EnvOpt = None,
    config: ConfigOpt = None,
    quiet: QuietOpt = False,
    color: ColorOpt = "auto",
) -> None:
    """Add a stereo camera pair (sensorkit_stereo_camera macro) to FILE."""
    options = {
        "update_rate": update_rate, "width": width, "height": height, "hfov": hfov,
        "format": format, "near": near, "far": far, "noise_stddev": noise_stddev,
        "baseline": baseline,
        **_common(sim, gz_version, namespace, mass, size),
    }  # fmt: skip
    _run(
        "stereo_camera",
        options,
        file=file,
        name=name,
        parent=parent,
        xyz=xyz,
        rpy=rpy,
        param=param,
        diff=diff,
        output=output,
        arg=arg,
        package_path=package_path,
        untrusted=untrusted,
        env=env,
        config=config,
        quiet=quiet,
        color=color,
    )


@handle_errors
def add_imu(
    file: FileArg,
    name: NameOpt,
    parent: ParentOpt,
    xyz: XyzOpt = (0.0, 0.0, 0.0),
    rpy: RpyOpt = (0.0, 0.0, 0.0),
    update_rate: UpdateRateOpt = None,
    gyro_noise_stddev: GyroOpt = None,
    accel_noise_stddev: AccelOpt = None,
    mass: MassOpt = None,
    size: SizeOpt = None,
    sim: SimOpt = None,
    gz_version: GzVersionOpt = None,
    namespace: NamespaceOpt = None,
    param: ParamOpt = None,
    diff: DiffOpt = False,
    output: OutOpt = None,
    arg: ArgOpt = None,
    package_path: PackagePathOpt = None,
    untrusted: UntrustedOpt = False,
    env: EnvOpt = None,
    config: ConfigOpt = None,
    quiet: QuietOpt = False,
    color: ColorOpt = "auto",
) -> None:
    """Add an IMU (sensorkit_imu macro) to FILE."""
    options = {
        "update_rate": update_rate,
        "gyro_noise_stddev": gyro_noise_stddev,
        "accel_noise_stddev": accel_noise_stddev,
        **_common(sim, gz_version, namespace, mass, size),
    }
    _run(
        "imu",
        options,
        file=file,
        name=name,
        parent=parent,
        xyz=xyz,
        rpy=rpy,
        param=param,
        diff=diff,
        output=output,
        arg=arg,
        package_path=package_path,
        untrusted=untrusted,
        env=env,
        config=config,
        quiet=quiet,
        color=color,
    )


def register(app: typer.Typer) -> None:
    """Add the five add-* commands to the sensorkit app."""
    panel = "Edit"
    app.command("add-camera", rich_help_panel=panel)(add_camera)
    app.command("add-depth-camera", rich_help_panel=panel)(add_depth_camera)
    app.command("add-lidar", rich_help_panel=panel)(add_lidar)
    app.command("add-stereo", rich_help_panel=panel)(add_stereo)
    app.command("add-imu", rich_help_panel=panel)(add_imu)
