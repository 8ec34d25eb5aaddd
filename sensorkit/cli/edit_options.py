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
from typing import Annotated

import typer

from sensorkit.cli.options import (
    ArgOpt,
    ColorOpt,
    ConfigOpt,
    EnvOpt,
    FileArg,
    PackagePathOpt,
    QuietOpt,
    UntrustedOpt,
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


def _option(name: str, annotation: object, default: object = None) -> inspect.Parameter:
    """Parameter ``name`` of an add-* command: ``annotation`` says which option fills it."""
    return inspect.Parameter(
        name, inspect.Parameter.KEYWORD_ONLY, annotation=annotation, default=default
    )


_REQUIRED = inspect.Parameter.empty
_ORIGIN = (0.0, 0.0, 0.0)

MOUNT = (
    _option("file", FileArg, _REQUIRED),
    _option("name", NameOpt, _REQUIRED),
    _option("parent", ParentOpt, _REQUIRED),
    _option("xyz", XyzOpt, _ORIGIN),
    _option("rpy", RpyOpt, _ORIGIN),
)
# the sensor options of each command, in --help order
CAMERA = (
    _option("update_rate", UpdateRateOpt),
    _option("width", WidthOpt),
    _option("height", HeightOpt),
    _option("hfov", HfovOpt),
    _option("format", FormatOpt),
    _option("near", NearOpt),
    _option("far", FarOpt),
    _option("noise_stddev", NoiseOpt),
)
DEPTH_CAMERA = (*CAMERA, _option("min_depth", MinDepthOpt), _option("max_depth", MaxDepthOpt))
STEREO_CAMERA = (*CAMERA, _option("baseline", BaselineOpt))
LIDAR = (
    _option("three_d", ThreeDOpt, False),
    _option("update_rate", UpdateRateOpt),
    _option("samples", SamplesOpt),
    _option("resolution", ResolutionOpt),
    _option("min_angle", MinAngleOpt),
    _option("max_angle", MaxAngleOpt),
    _option("range_min", RangeMinOpt),
    _option("range_max", RangeMaxOpt),
    _option("range_resolution", RangeResOpt),
    _option("noise_stddev", NoiseOpt),
    _option("vertical_samples", VSamplesOpt),
    _option("vertical_min_angle", VMinOpt),
    _option("vertical_max_angle", VMaxOpt),
)
IMU = (
    _option("update_rate", UpdateRateOpt),
    _option("gyro_noise_stddev", GyroOpt),
    _option("accel_noise_stddev", AccelOpt),
)
# the options every add-* takes after its own
SHARED = (
    _option("mass", MassOpt),
    _option("size", SizeOpt),
    _option("sim", SimOpt),
    _option("gz_version", GzVersionOpt),
    _option("namespace", NamespaceOpt),
    _option("param", ParamOpt),
    _option("diff", DiffOpt, False),
    _option("output", OutOpt),
    _option("arg", ArgOpt),
    _option("package_path", PackagePathOpt),
    _option("untrusted", UntrustedOpt, False),
    _option("env", EnvOpt),
    _option("config", ConfigOpt),
    _option("quiet", QuietOpt, False),
    _option("color", ColorOpt, "auto"),
)
# the shared options that are macro parameters too, in the order the macro call lists them
SHARED_MACRO = ("sim", "gz_version", "namespace", "mass", "size")
# add-lidar's options that only the 3D macro takes
VERTICAL = ("vertical_samples", "vertical_min_angle", "vertical_max_angle")


def parameters(own: tuple[inspect.Parameter, ...]) -> list[inspect.Parameter]:
    """Every parameter of an add-* command whose sensor options are ``own``, in order."""
    return [*MOUNT, *own, *SHARED]
