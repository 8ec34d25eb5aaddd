"""What the shipped xacro files offer: sensor macros, robot bases, their parameters.

Nothing here is a hand-kept table. The sensor types are the ``macros/*.urdf.xacro``
files that define a macro ``sensorkit_<stem>``; the bases are the
``templates/*.urdf.xacro`` files that define ``sensorkit_<stem>_base``. Parameter names
and defaults are read with xacro's own parser from each macro's ``params``, so a
parameter the macro author adds is accepted by ``sensorkit new`` the moment it ships.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Literal

from lxml import etree

from sensorkit.base.resources import macros_dir, templates_dir

XACRO_NS = "http://www.ros.org/wiki/xacro"

ParamKind = Literal["int", "float", "bool", "str", "vector"]

#: Parameters the generator sets itself, from the top level of the robot YAML.
SHARED_PARAMS = ("sim", "gz_version", "namespace")
#: Parameters a sensor entry sets with its own keys (name, parent, xyz/rpy).
SENSOR_KEY_PARAMS = ("name", "parent")

NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")
"""A decimal number as YAML and xacro write it (``1``, ``-0.5``, ``.5``, ``1e-3``)."""
_INT = re.compile(r"^[-+]?\d+$")
_LINK_NAME = re.compile(r"^(\$\{name\})?[A-Za-z0-9_]*$")


@dataclass(frozen=True)
class Param:
    """One macro parameter: its name, default text and the value kind it expects."""

    name: str
    default: str | None
    kind: ParamKind
    size: int = 1  # number of components for a "vector" (e.g. size:='0.1 0.2 0.3')


@dataclass(frozen=True)
class MacroInfo:
    """A shipped xacro macro: which file, which macro, what it takes and what links it makes."""

    kind: str  # sensor type ("camera", ...) or base name ("diff_drive", ...)
    file: Path
    macro: str
    params: dict[str, Param]
    blocks: tuple[str, ...]  # block parameters, e.g. ("origin",)
    link_patterns: tuple[str, ...]  # link names as written, literal or "${name}_..."

    def links_for(self, name: str) -> list[str]:
        """The link names this macro creates when called with ``name``."""
        return [p.replace("${name}", name) for p in self.link_patterns]

    def settable(self) -> list[str]:
        """Parameters a robot YAML may set through ``options`` / ``base_params``."""
        return [p for p in self.params if p not in SHARED_PARAMS and p not in SENSOR_KEY_PARAMS]


def _kind_of(default: str | None) -> tuple[ParamKind, int]:
    if default is None:
        return "str", 1
    text = default.strip()
    if text in ("true", "false", "True", "False"):
        return "bool", 1
    if _INT.match(text):
        return "int", 1
    if NUMBER.match(text) or (text.startswith("${") and text.endswith("}")):
        return "float", 1
    parts = text.split()
    if len(parts) > 1 and all(NUMBER.match(p) for p in parts):
        return "vector", len(parts)
    return "str", 1


def parse_params(params: str) -> tuple[dict[str, Param], tuple[str, ...]]:
    """Split a macro ``params`` attribute with xacro's own parser.

    Returns the value parameters (with defaults and kinds) and the block parameters.
    """
    import xacro

    values: dict[str, Param] = {}
    blocks: list[str] = []
    rest = params
    while rest.strip():
        name, spec, rest = xacro.parse_macro_arg(rest)
        if name.startswith("*"):
            blocks.append(name.lstrip("*"))
            continue
        default = None if spec is None else spec[1]
        if default is not None and len(default) >= 2 and default[0] == default[-1] == "'":
            default = default[1:-1]
        kind, size = _kind_of(default)
        values[name] = Param(name, default, kind, size)
    return values, tuple(blocks)


def _read_macro(path: Path, macro_name: str, kind: str) -> MacroInfo | None:
    parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_comments=True)
    try:
        root = etree.parse(str(path), parser).getroot()
    except (OSError, etree.XMLSyntaxError):
        return None
    for macro in root.iter(f"{{{XACRO_NS}}}macro"):
        if macro.get("name") != macro_name:
            continue
        params, blocks = parse_params(macro.get("params") or "")
        links: list[str] = []
        for link in macro.iter("link"):
            name = link.get("name") or ""
            if _LINK_NAME.match(name) and name not in links:
                links.append(name)
        return MacroInfo(kind, path, macro_name, params, blocks, tuple(links))
    return None


@lru_cache(maxsize=16)
def _macros(folder: Path, macro_name: str) -> dict[str, MacroInfo]:
    """Stem -> macro, for every ``*.urdf.xacro`` in ``folder`` that defines the macro
    ``macro_name`` names (``{stem}`` stands for the file's stem)."""
    found: dict[str, MacroInfo] = {}
    for path in sorted(folder.glob("*.urdf.xacro")):
        stem = path.name[: -len(".urdf.xacro")]
        info = _read_macro(path, macro_name.format(stem=stem), stem)
        if info is not None:
            found[stem] = info
    return found


def sensor_macros() -> dict[str, MacroInfo]:
    """Sensor type -> macro, for every macro shipped in ``macros/``."""
    return _macros(macros_dir(), "sensorkit_{stem}")


def base_templates() -> dict[str, MacroInfo]:
    """Base name -> macro, for every base template shipped in ``templates/``."""
    return _macros(templates_dir(), "sensorkit_{stem}_base")
