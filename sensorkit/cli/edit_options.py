"""The options of ``sensorkit add-*``, each declared once, and the table that lists, per
command, which it takes and in what order (the order ``--help`` shows them).

Every add-* command takes the mount options first, then its own sensor options, then
those all of them share: ``parameters`` puts them together into the command's
signature, which typer reads.
"""

from __future__ import annotations

import copy
import enum
import inspect
from pathlib import Path
from typing import Annotated, Any, get_args

import typer

from sensorkit.cli.options import OUTPUT, PRINTING, ROBOT_FLAGS, FileArg, parameter


class Sim(str, enum.Enum):
    classic = "classic"
    gz = "gz"
    none = "none"


class GzVersion(str, enum.Enum):
    fortress = "fortress"
    harmonic = "harmonic"
    jetty = "jetty"


Vec3 = tuple[float, float, float]
_SENSOR = "Sensor"
_MOUNT = "Mount"
_OUT = OUTPUT


def _sensor(flag: str, help: str, metavar: str | None = None) -> Any:
    """An option of the sensor panel. Left out, the macro's default holds: the command
    shows the shipped macro's (``parameters``)."""
    return typer.Option(
        flag, help=help, metavar=metavar, show_default=False, rich_help_panel=_SENSOR
    )


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
        help="simulator the sensor block is for",
        show_default="the robot's: its other sensors' sim expression, else what --target auto "
        "sees, else classic",
        rich_help_panel=_SENSOR,
    ),
]
GzVersionOpt = Annotated[
    GzVersion | None,
    typer.Option(
        "--gz-version",
        help="Gazebo Sim version (frame tag)",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
NamespaceOpt = Annotated[
    str | None,
    typer.Option(
        "--namespace",
        help="ROS namespace of the sensor's topics",
        show_default=False,
        rich_help_panel=_SENSOR,
    ),
]
MassOpt = Annotated[float | None, _sensor("--mass", "sensor body mass (kg)")]
SizeOpt = Annotated[Vec3 | None, _sensor("--size", "sensor body box size (m)", "X Y Z")]
UpdateRateOpt = Annotated[float | None, _sensor("--update-rate", "Hz")]
WidthOpt = Annotated[int | None, _sensor("--width", "image width (px)")]
HeightOpt = Annotated[int | None, _sensor("--height", "image height (px)")]
HfovOpt = Annotated[float | None, _sensor("--hfov", "horizontal field of view (rad)")]
FormatOpt = Annotated[str | None, _sensor("--format", "pixel format, e.g. R8G8B8")]
NearOpt = Annotated[float | None, _sensor("--near", "near clip (m)")]
FarOpt = Annotated[float | None, _sensor("--far", "far clip (m)")]
NoiseOpt = Annotated[float | None, _sensor("--noise-stddev", "gaussian noise stddev")]
MinDepthOpt = Annotated[float | None, _sensor("--min-depth", "depth/point cloud min (m)")]
MaxDepthOpt = Annotated[float | None, _sensor("--max-depth", "depth/point cloud max (m)")]
BaselineOpt = Annotated[float | None, _sensor("--baseline", "distance between the two cameras (m)")]
SamplesOpt = Annotated[int | None, _sensor("--samples", "horizontal beams")]
ResolutionOpt = Annotated[float | None, _sensor("--resolution", "horizontal resolution factor")]
MinAngleOpt = Annotated[float | None, _sensor("--min-angle", "horizontal start angle (rad)")]
MaxAngleOpt = Annotated[float | None, _sensor("--max-angle", "horizontal end angle (rad)")]
RangeMinOpt = Annotated[float | None, _sensor("--range-min", "minimum range (m)")]
RangeMaxOpt = Annotated[float | None, _sensor("--range-max", "maximum range (m)")]
RangeResOpt = Annotated[float | None, _sensor("--range-resolution", "range resolution (m)")]
ThreeDOpt = Annotated[
    bool,
    typer.Option(
        "--3d",
        help="a 3D (multi-layer) lidar: uses the sensorkit_lidar_3d macro",
        rich_help_panel=_SENSOR,
    ),
]
VSamplesOpt = Annotated[int | None, _sensor("--vertical-samples", "vertical beams (needs --3d)")]
VMinOpt = Annotated[float | None, _sensor("--vertical-min-angle", "lowest beam (rad, needs --3d)")]
VMaxOpt = Annotated[float | None, _sensor("--vertical-max-angle", "highest beam (rad, needs --3d)")]
GyroOpt = Annotated[float | None, _sensor("--gyro-noise-stddev", "rad/s")]
AccelOpt = Annotated[float | None, _sensor("--accel-noise-stddev", "m/s^2")]
ParamOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--param",
        help="any other macro parameter NAME=VALUE (repeatable)",
        metavar="NAME=VALUE",
        show_default="none",
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
        show_default="FILE, edited in place",
        rich_help_panel=_OUT,
    ),
]

_REQUIRED = inspect.Parameter.empty
_ORIGIN = (0.0, 0.0, 0.0)

MOUNT = (
    parameter("file", FileArg, _REQUIRED),
    parameter("name", NameOpt, _REQUIRED),
    parameter("parent", ParentOpt, _REQUIRED),
    parameter("xyz", XyzOpt, _ORIGIN),
    parameter("rpy", RpyOpt, _ORIGIN),
)
# the sensor options of each command, in --help order
CAMERA = (
    parameter("update_rate", UpdateRateOpt),
    parameter("width", WidthOpt),
    parameter("height", HeightOpt),
    parameter("hfov", HfovOpt),
    parameter("format", FormatOpt),
    parameter("near", NearOpt),
    parameter("far", FarOpt),
    parameter("noise_stddev", NoiseOpt),
)
DEPTH_CAMERA = (
    *CAMERA,
    parameter("min_depth", MinDepthOpt),
    parameter("max_depth", MaxDepthOpt),
)
STEREO_CAMERA = (*CAMERA, parameter("baseline", BaselineOpt))
LIDAR = (
    parameter("three_d", ThreeDOpt, False),
    parameter("update_rate", UpdateRateOpt),
    parameter("samples", SamplesOpt),
    parameter("resolution", ResolutionOpt),
    parameter("min_angle", MinAngleOpt),
    parameter("max_angle", MaxAngleOpt),
    parameter("range_min", RangeMinOpt),
    parameter("range_max", RangeMaxOpt),
    parameter("range_resolution", RangeResOpt),
    parameter("noise_stddev", NoiseOpt),
    parameter("vertical_samples", VSamplesOpt),
    parameter("vertical_min_angle", VMinOpt),
    parameter("vertical_max_angle", VMaxOpt),
)
IMU = (
    parameter("update_rate", UpdateRateOpt),
    parameter("gyro_noise_stddev", GyroOpt),
    parameter("accel_noise_stddev", AccelOpt),
)
# the options every add-* takes after its own
SHARED = (
    parameter("mass", MassOpt),
    parameter("size", SizeOpt),
    parameter("sim", SimOpt),
    parameter("gz_version", GzVersionOpt),
    parameter("namespace", NamespaceOpt),
    parameter("param", ParamOpt),
    parameter("diff", DiffOpt, False),
    parameter("output", OutOpt),
    *ROBOT_FLAGS,
    *PRINTING,
)
# the shared options that are macro parameters too, in the order the macro call lists them
SHARED_MACRO = ("sim", "gz_version", "namespace", "mass", "size")
# add-lidar's options that only the 3D macro takes
VERTICAL = ("vertical_samples", "vertical_min_angle", "vertical_max_angle")


# The parameters' defaults in the macros sensorkit ships, as written there (--help shows
# them; tests/test_help.py holds them to the macro files). A macro copy beside the robot
# may have its own: the add keeps whichever macro it calls.
MACRO_DEFAULTS: dict[str, dict[str, str]] = {
    "camera": {
        "update_rate": "30",
        "width": "640",
        "height": "480",
        "hfov": "1.3962634",
        "format": "R8G8B8",
        "near": "0.05",
        "far": "50.0",
        "noise_stddev": "0.007",
        "mass": "0.035",
        "size": "0.025 0.09 0.025",
        "namespace": "",
        "gz_version": "harmonic",
    },
    "depth_camera": {
        "update_rate": "30",
        "width": "640",
        "height": "480",
        "hfov": "1.3962634",
        "format": "R8G8B8",
        "near": "0.05",
        "far": "10.0",
        "noise_stddev": "0.007",
        "min_depth": "0.1",
        "max_depth": "10.0",
        "mass": "0.072",
        "size": "0.025 0.09 0.025",
        "namespace": "",
        "gz_version": "harmonic",
    },
    "lidar_2d": {
        "update_rate": "10",
        "samples": "360",
        "resolution": "1",
        "min_angle": "${-pi}",
        "max_angle": "${pi}",
        "range_min": "0.12",
        "range_max": "12.0",
        "range_resolution": "0.01",
        "noise_stddev": "0.01",
        "mass": "0.17",
        "size": "0.07 0.07 0.05",
        "namespace": "",
        "gz_version": "harmonic",
    },
    "lidar_3d": {
        "update_rate": "10",
        "samples": "1800",
        "resolution": "1",
        "min_angle": "${-pi}",
        "max_angle": "${pi}",
        "vertical_samples": "16",
        "vertical_min_angle": "-0.2618",
        "vertical_max_angle": "0.2618",
        "range_min": "0.12",
        "range_max": "100.0",
        "range_resolution": "0.01",
        "noise_stddev": "0.01",
        "mass": "0.83",
        "size": "0.10 0.10 0.07",
        "namespace": "",
        "gz_version": "harmonic",
    },
    "stereo_camera": {
        "update_rate": "30",
        "width": "640",
        "height": "480",
        "hfov": "1.3962634",
        "format": "R8G8B8",
        "near": "0.05",
        "far": "50.0",
        "noise_stddev": "0.007",
        "baseline": "0.12",
        "mass": "0.15",
        "size": "0.03 0.16 0.03",
        "namespace": "",
        "gz_version": "harmonic",
    },
    "imu": {
        "update_rate": "100",
        "gyro_noise_stddev": "2e-4",
        "accel_noise_stddev": "1.7e-2",
        "mass": "0.01",
        "size": "0.02 0.02 0.01",
        "namespace": "",
        "gz_version": "harmonic",
    },
}
# the macros each add-* command calls (add-lidar: the 2D one, the 3D one with --3d)
COMMAND_KINDS = {
    "add-camera": ("camera",),
    "add-depth-camera": ("depth_camera",),
    "add-lidar": ("lidar_2d", "lidar_3d"),
    "add-stereo": ("stereo_camera",),
    "add-imu": ("imu",),
}


def _as_shown(value: str) -> str:
    """A macro default as --help shows it: ``${-pi}`` as -pi, nothing as none."""
    if value.startswith("${") and value.endswith("}"):
        return value[2:-1]
    return value or "none"


def shown_defaults(command: str) -> dict[str, str]:
    """The default --help shows for each macro option of ``command``: the shipped macro's;
    for add-lidar the 2D macro's, with the 3D one's beside it where it differs."""
    first, *more = (MACRO_DEFAULTS[kind] for kind in COMMAND_KINDS[command])
    shown = {name: _as_shown(value) for name, value in first.items()}
    for other in more:  # the 3D lidar's
        for name, value in other.items():
            if name not in shown:
                shown[name] = _as_shown(value)  # a 3D option: its help says "needs --3d"
            elif value != first[name]:
                shown[name] += f"; with --3d {_as_shown(value)}"
    return shown


def _with_default(param: inspect.Parameter, shown: str) -> inspect.Parameter:
    """``param`` whose option --help shows ``[default: shown]`` (its value stays None:
    left out, the macro's default holds)."""
    base, info = get_args(param.annotation)
    info = copy.copy(info)
    info.show_default = shown
    return param.replace(annotation=Annotated[base, info])


def parameters(own: tuple[inspect.Parameter, ...], command: str) -> list[inspect.Parameter]:
    """Every parameter of the add-* ``command`` whose sensor options are ``own``, in order,
    each macro option showing the shipped macro's default."""
    shown = shown_defaults(command)
    return [
        _with_default(p, shown[p.name]) if p.name in shown else p for p in (*MOUNT, *own, *SHARED)
    ]
