"""``sensorkit add-camera | add-depth-camera | add-lidar | add-stereo | add-imu``.

Each command maps its options onto the parameters of one sensor macro and calls
``sensorkit.edit.add_sensor``. Options left out keep the macro's defaults. ``add-lidar``
uses the 2D macro unless ``--3d`` is given; the vertical options need ``--3d``.

The options are declared once, in ``edit_options``; each command is made from its row
of that table by ``_add_command``.
"""

from __future__ import annotations

import enum
import inspect
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import typer

from sensorkit.cli.common import (
    RobotFlags,
    collector_off,
    die,
    handle_errors,
    note,
    refuse_stdin,
    robot_flags,
    settings,
    target_simulator,
    use_color,
)
from sensorkit.cli.edit_options import (
    CAMERA,
    DEPTH_CAMERA,
    IMU,
    LIDAR,
    SHARED_MACRO,
    STEREO_CAMERA,
    VERTICAL,
    Vec3,
    parameters,
)
from sensorkit.cli.options import Command, examples, with_parameters

if TYPE_CHECKING:
    from sensorkit.cli.common import Settings
    from sensorkit.edit import AddResult
    from sensorkit.lint.engine import Options


@dataclass
class _Given:
    """The values of an add-* command's options, but those that are macro parameters."""

    file: Path
    name: str
    parent: str
    xyz: Vec3
    rpy: Vec3
    param: list[str] | None
    diff: bool
    output: Path | None
    flags: RobotFlags
    quiet: bool
    color: str


def _add_command(
    command: str, kind: str, doc: str, own: tuple[inspect.Parameter, ...]
) -> Callable[..., None]:
    """The add-* command ``command``, adding a ``kind`` sensor: ``own`` are its sensor
    options (``edit_options``), ``doc`` its --help text."""
    macro_keys = [p.name for p in own if p.name != "three_d"] + list(SHARED_MACRO)

    def add(**values: Any) -> None:
        chosen = _lidar_kind(values.pop("three_d"), values) if "three_d" in values else kind
        options = {key: values.pop(key) for key in macro_keys}
        _run(command, chosen, options, _Given(flags=robot_flags(values), **values))

    add.__name__ = add.__qualname__ = command.replace("-", "_")
    add.__doc__ = doc
    return handle_errors(with_parameters(add, parameters(own, command)))


def _lidar_kind(three_d: bool, values: dict[str, Any]) -> str:
    """add-lidar's macro: the 3D one with --3d, which the vertical options need."""
    given = [k for k in VERTICAL if values[k] is not None]
    if given and not three_d:
        die(
            f"--{given[0].replace('_', '-')} needs --3d (the 2D lidar has one horizontal scan line)"
        )
    return "lidar_3d" if three_d else "lidar_2d"


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


def _run(command: str, kind: str, options: dict[str, object], given: _Given) -> None:
    """Check the options, add the sensor (with --diff, only plan it) and say what was done."""
    from sensorkit.edit import AddRequest, add_sensor

    refuse_stdin(given.file, f"{command} edits the robot file in place")
    use_color(given.color)  # checked; nothing printed is coloured
    _check_radians(given.rpy)
    params = _macro_params(options, given.param)
    # Validate the way `sensorkit validate` would here: the settings file applies.
    st = settings(given.file, given.flags, target=None)
    if "sim" not in params and st.config.target:  # the project's simulator, unless --sim says
        for key, value in target_simulator(st.config.target).items():
            params.setdefault(key, value)
    st.say_where(quiet=given.quiet)
    req = AddRequest(
        path=given.file,
        kind=kind,
        name=given.name,
        parent=given.parent,
        xyz=given.xyz,
        rpy=given.rpy,
        params=params,
        output=given.output,
        args=st.args,
        package_paths=st.package_paths,
        validation=_validation(st),
    )
    from sensorkit.cli import leave_quickly

    with collector_off():
        result = add_sensor(req, dry_run=given.diff)
    leave_quickly()  # every write is done (add_sensor returned): skip freeing the model
    _say_done(result, diff=given.diff, quiet=given.quiet)


def _check_radians(rpy: Vec3) -> None:
    for angle in rpy:
        if abs(angle) > 2 * math.pi:  # 90 means degrees, by habit: a quarter turn is 1.5708
            die(
                f"--rpy {' '.join(f'{a:g}' for a in rpy)}: {angle:g} is more than 2π; angles are "
                f"in radians (radians? {angle:g}° is {math.radians(angle):.6g})"
            )


def _macro_params(options: dict[str, object], param: list[str] | None) -> dict[str, str]:
    """The macro parameters given, as text: each option set, then each --param NAME=VALUE."""
    params = {key: _text(value) for key, value in options.items() if value is not None}
    for item in param or []:
        key, sep, value = item.partition("=")
        if not sep or not key:
            die(f"--param {item!r}: expected NAME=VALUE")
        if key in params:
            die(f"--param {key}: already set by its own option")
        params[key] = value
    return params


def _validation(st: Settings) -> Options:
    """How the add validates the result: as ``sensorkit validate`` would, with these settings."""
    from sensorkit.lint.engine import Options

    cfg = st.config
    return Options(
        target=st.target,
        select=tuple(cfg.select),
        ignore=tuple(cfg.ignore),
        args=st.args,
        package_paths=st.package_paths,
        untrusted=st.untrusted,
    )


def _say_done(result: AddResult, *, diff: bool, quiet: bool) -> None:
    """The notes (stderr), then the diff (stdout) or what was added and written (stderr)."""
    from sensorkit.loading.document import display_path

    if result.simulator:
        note(f"sensorkit: {result.simulator}", quiet)
    for said in result.notes:
        kind = "" if said.startswith("warning: ") else "note: "
        note(f"sensorkit: {kind}{said}", quiet)
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


add_camera = _add_command(
    "add-camera", "camera", "Add a pinhole RGB camera (sensorkit_camera macro) to FILE.", CAMERA
)
add_depth_camera = _add_command(
    "add-depth-camera",
    "depth_camera",
    "Add an RGB-D camera (sensorkit_depth_camera macro) to FILE.",
    DEPTH_CAMERA,
)
add_lidar = _add_command(
    "add-lidar",
    "lidar_2d",
    "Add a 2D lidar (sensorkit_lidar_2d macro), or with --3d a 3D one (sensorkit_lidar_3d).",
    LIDAR,
)
add_stereo = _add_command(
    "add-stereo",
    "stereo_camera",
    "Add a stereo camera pair (sensorkit_stereo_camera macro) to FILE.",
    STEREO_CAMERA,
)
add_imu = _add_command("add-imu", "imu", "Add an IMU (sensorkit_imu macro) to FILE.", IMU)


CAR = "examples/orbslam3_car/urdf/orbslam3_car.urdf.xacro"
# each add-*'s --help examples: what the first does, its options; then the second's
_EXAMPLES = {
    "add-camera": (
        "A camera 20 cm ahead of base_link and 10 cm up, shown as a diff",
        "--name front_cam --parent base_link --xyz 0.2 0 0.1 --diff",
        "A rear camera at 15 Hz, into a new file",
        "--name rear_cam --parent base_link --rpy 0 0 3.1416 --update-rate 15 -o car_rear.xacro",
    ),
    "add-depth-camera": (
        "An RGB-D camera looking down 0.3 rad, shown as a diff",
        "--name down_cam --parent base_link --xyz 0.2 0 0.2 --rpy 0 0.3 0 --diff",
        "One that sees 0.3 to 5 m, into a new file",
        "--name rgbd --parent base_link --min-depth 0.3 --max-depth 5 -o car_rgbd.xacro",
    ),
    "add-lidar": (
        "A 2D lidar 25 cm up, shown as a diff",
        "--name top_lidar --parent base_link --xyz 0 0 0.25 --diff",
        "A 32-beam 3D lidar, into a new file",
        "--name velo --parent base_link --3d --vertical-samples 32 -o car_3d.xacro",
    ),
    "add-stereo": (
        "A stereo pair with a 12 cm baseline, shown as a diff",
        "--name stereo --parent base_link --xyz 0.2 0 0.1 --diff",
        "A wider one at 15 Hz, into a new file",
        "--name wide --parent base_link --baseline 0.3 --update-rate 15 -o car_stereo.xacro",
    ),
    "add-imu": (
        "An IMU at the base_link origin, shown as a diff",
        "--name imu --parent base_link --diff",
        "A noisier one at 200 Hz, into a new file",
        "--name imu --parent base_link --update-rate 200 --gyro-noise-stddev 0.001 -o car_imu.xacro",
    ),
}


def _epilog(command: str) -> str:
    said, options, said2, options2 = _EXAMPLES[command]
    return examples(
        (said, f"sensorkit {command} {CAR} {options}"),
        (said2, f"sensorkit {command} {CAR} {options2}"),
    )


def register(app: typer.Typer) -> None:
    """Add the five add-* commands to the sensorkit app."""
    for name, command in (
        ("add-camera", add_camera),
        ("add-depth-camera", add_depth_camera),
        ("add-lidar", add_lidar),
        ("add-stereo", add_stereo),
        ("add-imu", add_imu),
    ):
        app.command(name, cls=Command, rich_help_panel="Edit", epilog=_epilog(name))(command)
