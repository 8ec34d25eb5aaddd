"""The macro an add calls and the attributes of the call.

For a xacro robot the call uses the macro file in ``sensors/`` beside the robot: the
user's copy when there is one (left as it is, even modified), else sensorkit's, copied
there by the add. A URDF robot gets the macro's expansion, from sensorkit's own file.
The attributes are checked against the parameters of the macro actually used.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from sensorkit.base.errors import EditRefused, InputError, UsageError
from sensorkit.edit.kinds import MacroInfo, SensorKind, read_macro, shipped_macro
from sensorkit.edit.request import AddRequest
from sensorkit.loading.document import display_path

SENSORS_DIR = "sensors"
_RESERVED = ("name", "parent")


@dataclass
class MacroChoice:
    """The macro file an add's call uses, and the copy of it the add writes, if any."""

    path: Path  # the macro file the call will use
    info: MacroInfo
    copy_to: Path | None  # where the shipped file must be copied (xacro only), or None
    copy_data: bytes = b""
    notes: list[str] = field(default_factory=list)
    # the file holds sensorkit's own macro, byte for byte (not a user's modified copy)
    ours: bool = True


def _read_ours(path: Path, kind: SensorKind, shipped: Path) -> MacroInfo:
    """The macro of ``kind`` in ``path``, a file that holds sensorkit's ``shipped`` one."""
    info = read_macro(path, kind.macro_name)
    if info is None:
        msg = f"sensorkit's {shipped} defines no macro {kind.macro_name}"
        raise InputError(msg)
    return info


def choose_macro(kind: SensorKind, xacro_style: bool, target: Path) -> MacroChoice:
    """The macro file an add of ``kind`` to ``target`` uses (see the module doc)."""
    shipped = shipped_macro(kind)
    if not xacro_style:
        return MacroChoice(path=shipped, info=_read_ours(shipped, kind, shipped), copy_to=None)
    local = target.parent / SENSORS_DIR / kind.macro_file
    shipped_data = shipped.read_bytes()
    if local.exists() or local.is_symlink():
        if not local.is_file():
            msg = f"{display_path(local)} is not a file; move it away to add a {kind.label}"
            raise EditRefused(msg)
        if local.read_bytes() == shipped_data:
            return MacroChoice(path=local, info=_read_ours(local, kind, shipped), copy_to=None)
        info = read_macro(local, kind.macro_name)
        if info is None:
            msg = (
                f"{display_path(local)} differs from sensorkit's and defines no macro "
                f"{kind.macro_name}; rename it or remove it so sensorkit can copy its own"
            )
            raise EditRefused(msg)
        note = (
            f"{display_path(local)} differs from sensorkit's {kind.macro_file}: "
            "left as it is and used (your modified copy)"
        )
        return MacroChoice(path=local, info=info, copy_to=None, notes=[note], ours=False)
    info = _read_ours(shipped, kind, shipped)
    return MacroChoice(path=shipped, info=info, copy_to=local, copy_data=shipped_data)


def _macro_label(info: MacroInfo) -> str:
    from sensorkit.base.resources import macros_dir

    if info.path.resolve().parent == macros_dir().resolve():
        return f"sensorkit's {info.name} macro"
    return f"the {info.name} macro in {display_path(info.path)}"


def call_attributes(
    req: AddRequest, info: MacroInfo, params: Mapping[str, str]
) -> list[tuple[str, str]]:
    """The attributes of the macro call, in the macro's order: name, parent, then the
    parameters given. A parameter the macro lacks, or one it needs and lacks a value
    for, is a usage error; a macro without name, parent or an origin block is refused."""
    known = info.names()
    label = _macro_label(info)
    for key in params:
        if key in _RESERVED or key not in known:
            offered = ", ".join(n for n in known if n not in _RESERVED)
            msg = f"{label} has no parameter {key!r} (it takes: {offered}); check the spelling, or leave it out"
            raise UsageError(msg)
    for needed in _RESERVED:
        if needed not in known:
            msg = f"{label} takes no {needed!r} parameter"
            raise EditRefused(msg)
    if "origin" not in info.blocks:
        msg = f"{label} takes no *origin block"
        raise EditRefused(msg)
    attrs = [("name", req.name), ("parent", req.parent)]
    attrs += [(n, params[n]) for n in known if n in params]
    missing = [p.name for p in info.params if p.default is None and p.name not in dict(attrs)]
    if missing:
        given = " ".join(f"--param {m}=VALUE" for m in missing)
        msg = f"{label} needs {', '.join(missing)} (no default): pass {given}"
        raise UsageError(msg)
    return attrs
