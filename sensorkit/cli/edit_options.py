"""The options of ``sensorkit add-*``, each declared once, and the table that lists, per
command, which it takes and in what order (the order ``--help`` shows them).

Every add-* command takes the mount options first, then its own sensor options, then
those all of them share: ``parameters`` puts them together into the command's
signature, which typer reads.
"""

from __future__ import annotations

import enum
import inspect
from pathlib import Path
from typing import Annotated, Any

import typer

from sensorkit.cli.options import PRINTING, ROBOT_FLAGS, FileArg, parameter


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


def _sensor(flag: str, help: str, metavar: str | None = None) -> Any:
    """An option of the sensor panel. Left out, the macro's default holds: none is shown."""
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
    _sensor("--param", "any other macro parameter NAME=VALUE (repeatable)", "NAME=VALUE"),
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


def parameters(own: tuple[inspect.Parameter, ...]) -> list[inspect.Parameter]:
    """Every parameter of an add-* command whose sensor options are ``own``, in order."""
    return [*MOUNT, *own, *SHARED]
