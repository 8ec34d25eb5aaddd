"""The sensor kinds ``sensorkit add-*`` knows, and the macros that build them.

Parameter names are never hard-coded here: they are read from the macro file that will
actually be used (the shipped one, or the user's own copy next to the robot), so the
commands follow the macros as they change.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from sensorkit.base.errors import EditRefused, InputError
from sensorkit.loading.document import display_path, strict_parser

XACRO_NS = "http://www.ros.org/wiki/xacro"


@dataclass(frozen=True)
class SensorKind:
    """One kind of sensor: the macro file that ships with sensorkit and its macro name."""

    key: str
    macro_file: str
    macro_name: str
    label: str


KINDS: dict[str, SensorKind] = {
    k.key: k
    for k in (
        SensorKind("camera", "camera.urdf.xacro", "sensorkit_camera", "camera"),
        SensorKind(
            "depth_camera", "depth_camera.urdf.xacro", "sensorkit_depth_camera", "depth camera"
        ),
        SensorKind("lidar_2d", "lidar_2d.urdf.xacro", "sensorkit_lidar_2d", "2D lidar"),
        SensorKind("lidar_3d", "lidar_3d.urdf.xacro", "sensorkit_lidar_3d", "3D lidar"),
        SensorKind(
            "stereo_camera", "stereo_camera.urdf.xacro", "sensorkit_stereo_camera", "stereo camera"
        ),
        SensorKind("imu", "imu.urdf.xacro", "sensorkit_imu", "IMU"),
    )
}
# The add-* command of each kind, for a refusal whose next step names it.
COMMANDS = {"camera": "add-camera", "depth_camera": "add-depth-camera", "lidar_2d": "add-lidar",
            "lidar_3d": "add-lidar", "stereo_camera": "add-stereo", "imu": "add-imu"}  # fmt: skip


@dataclass(frozen=True)
class MacroParam:
    """One macro parameter: its name and default as written (None: required)."""

    name: str
    default: str | None


@dataclass(frozen=True)
class MacroInfo:
    """What a macro file offers: the macro's parameters and its block parameters."""

    path: Path
    name: str
    params: tuple[MacroParam, ...]
    blocks: tuple[str, ...]

    def param(self, name: str) -> MacroParam | None:
        for p in self.params:
            if p.name == name:
                return p
        return None

    def names(self) -> list[str]:
        return [p.name for p in self.params]


def shipped_macro(kind: SensorKind) -> Path:
    """The macro file shipped with sensorkit for ``kind``."""
    from sensorkit.base.resources import macros_dir

    path = macros_dir() / kind.macro_file
    if not path.is_file():
        msg = f"sensorkit's macro {kind.macro_file} is missing from this installation ({path})"
        raise InputError(msg)
    return path


def _split_params(text: str) -> list[tuple[str, str | None]]:
    """xacro's own reading of a ``params`` attribute: [(name, default or None)]."""
    import xacro

    out: list[tuple[str, str | None]] = []
    rest = text
    while rest:
        name, value, rest = xacro.parse_macro_arg(rest)
        default: str | None = None
        if value is not None:
            _forward, default = value
            if (
                default is not None
                and len(default) >= 2
                and default[0] == default[-1]
                and default[0] in "'\""
            ):
                default = default[1:-1]
        out.append((name, default))
    return out


def read_macro(path: Path, macro_name: str) -> MacroInfo | None:
    """The macro ``macro_name`` defined in ``path``, or None if the file has none.

    Raises EditRefused when the file is not well-formed XML.
    """
    try:
        root = etree.parse(str(path), strict_parser()).getroot()
    except (etree.XMLSyntaxError, OSError) as exc:
        msg = f"{display_path(path)}: cannot read the macro file ({exc})"
        raise EditRefused(msg) from None
    for el in root.iter():
        if not isinstance(el.tag, str):
            continue
        q = etree.QName(el)
        if q.localname != "macro" or el.prefix != "xacro" or el.get("name") != macro_name:
            continue
        params: list[MacroParam] = []
        blocks: list[str] = []
        try:
            pairs = _split_params(el.get("params", ""))
        except Exception as exc:  # xacro raises its own exception types
            msg = f"{display_path(path)}: macro {macro_name} has unreadable params ({exc})"
            raise EditRefused(msg) from None
        for name, default in pairs:
            if name.startswith("*"):
                blocks.append(name.lstrip("*"))
            else:
                params.append(MacroParam(name, default))
        return MacroInfo(path=path, name=macro_name, params=tuple(params), blocks=tuple(blocks))
    return None
