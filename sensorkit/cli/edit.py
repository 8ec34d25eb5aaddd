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
from sensorkit.cli.options import with_parameters

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
    return handle_errors(with_parameters(add, parameters(own)))


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


def register(app: typer.Typer) -> None:
    """Add the five add-* commands to the sensorkit app."""
    panel = "Edit"
    app.command("add-camera", rich_help_panel=panel)(add_camera)
    app.command("add-depth-camera", rich_help_panel=panel)(add_depth_camera)
    app.command("add-lidar", rich_help_panel=panel)(add_lidar)
    app.command("add-stereo", rich_help_panel=panel)(add_stereo)
    app.command("add-imu", rich_help_panel=panel)(add_imu)
