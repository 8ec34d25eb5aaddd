"""What an add puts into the robot file, and putting it there without disturbing a byte.

The new text goes just before the closing root tag, indented as the file is: for a
xacro robot a call of the sensor's macro (after an include of the macro file, unless
the robot includes it already), with a ``xmlns:xacro`` declaration added to the root
start tag when it has none; for a URDF robot the macro's expansion under a comment.
``splice_in`` inserts it and proves that the new file parses and holds exactly the
inserted nodes before the closing tag, reading only the end of it.
"""

from __future__ import annotations

import os
import posixpath
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from sensorkit.base.errors import EditRefused
from sensorkit.edit.kinds import XACRO_NS, SensorKind
from sensorkit.edit.layout import Layout
from sensorkit.edit.macrocall import SENSORS_DIR
from sensorkit.edit.render import Lines, fragment_lines, macro_call_lines, render_block
from sensorkit.edit.request import AddRequest
from sensorkit.loading.document import display_path, strict_parser


@dataclass
class Insertion:
    """The lines an add inserts, the nodes they make (``_node_key``s; for xacro, local
    names), the declaration the root start tag needs (or None), and notes."""

    lines: Lines
    keys: list[str]
    ns_decl: str | None = None
    notes: list[str] = field(default_factory=list)


def _node_key(node: etree._Element) -> str:
    """``link|name`` for an element (namespace ignored), ``#comment`` for a comment."""
    if isinstance(node, etree._Comment):
        return "#comment"
    return f"{etree.QName(node).localname}|{node.get('name', '')}"


def _top_level_includes(root: etree._Element) -> list[str]:
    """``filename`` of every ``<xacro:include>`` directly under the root."""
    out: list[str] = []
    for el in root:
        if (
            isinstance(el.tag, str)
            and etree.QName(el).localname == "include"
            and el.prefix == "xacro"
        ):
            out.append(el.get("filename", ""))
    return out


def _relative_include_warnings(root: etree._Element, source: Path, target: Path) -> list[str]:
    """Notes for relative includes that stop resolving when the output moves folder."""
    notes: list[str] = []
    if source.resolve().parent == target.resolve().parent:
        return notes
    for filename in _top_level_includes(root):
        if not filename or filename.startswith(("$", "/", "package://", "file://")):
            continue
        if not (target.parent / filename).exists():
            notes.append(
                f"{display_path(target)} is in another folder than {display_path(source)}: "
                f"its include '{filename}' does not resolve from there"
            )
    return notes


def xacro_insertion(
    req: AddRequest,
    kind: SensorKind,
    root: etree._Element,
    includes: Sequence[str],
    attrs: list[tuple[str, str]],
    expressions: Mapping[str, str],
) -> Insertion:
    """The macro call with ``attrs`` for a xacro robot whose root is ``root`` and whose
    expansion read ``includes``; ``expressions`` are attribute values written as given."""
    source, target = req.path, req.target
    rel = posixpath.join(SENSORS_DIR, kind.macro_file)
    local = (target.parent / SENSORS_DIR / kind.macro_file).resolve()
    present = any(
        f and "$" not in f and (target.parent / f).resolve() == local
        for f in _top_level_includes(root)
    )
    if not present and source.resolve().parent == target.resolve().parent:
        present = str(local) in {os.path.abspath(p) for p in includes}
    include = None if present else rel
    lines = macro_call_lines(kind.macro_name, attrs, req.xyz, req.rpy, include, expressions)
    keys = ([] if include is None else ["include"]) + [kind.macro_name]
    ns_decl = None if "xacro" in root.nsmap else f' xmlns:xacro="{XACRO_NS}"'
    return Insertion(lines, keys, ns_decl, _relative_include_warnings(root, source, target))


def urdf_insertion(req: AddRequest, kind: SensorKind, nodes: list[etree._Element]) -> Insertion:
    """The expanded ``nodes`` for a URDF robot, under a comment naming the macro."""
    header = f"{req.name}: {kind.label} from sensorkit's {kind.macro_name} macro"
    return Insertion(fragment_lines(nodes, header), ["#comment", *[_node_key(n) for n in nodes]])


def splice_in(
    data: bytes, layout: Layout, ins: Insertion, xacro_style: bool, where: str
) -> tuple[bytes, etree._Element]:
    """The robot file's new bytes, ``ins`` in before the closing root tag, and the new
    end of the file parsed (``_check_splice``)."""
    line_start = layout.line_start_before(layout.root_end_at)
    at = line_start if line_start is not None else layout.root_end_at
    block = render_block(
        ins.lines,
        layout,
        at_line_start=line_start is not None,
        blank_before=line_start is not None and not layout.previous_line_blank(line_start),
    )
    new = _splice(data, layout, block, at, ins.ns_decl)
    tail = _check_splice(layout, new, at, ins.ns_decl, ins.keys, xacro_style, where)
    return new, tail


def _splice(data: bytes, layout: Layout, block: str, at: int, ns_decl: str | None) -> bytes:
    """Insert ``block`` at character ``at`` and ``ns_decl`` into the root start tag."""
    edits: list[tuple[int, str]] = [(at, block)]
    if ns_decl is not None:
        end = layout.root_start_end - 1  # the '>'
        while end > layout.root_start_at and layout.text[end - 1] in " \t\r\n":
            end -= 1
        edits.append((end, ns_decl))
    out = data
    for char_at, text in sorted(edits, key=lambda e: e[0], reverse=True):
        off = layout.byte_offset(char_at)
        out = out[:off] + layout.encode(text) + out[off:]
    return out


def _check_splice(
    layout: Layout,
    new: bytes,
    at: int,
    ns_decl: str | None,
    inserted: list[str],
    xacro_style: bool,
    where: str,
) -> etree._Element:
    """A guard: the new file, from the new text on, parses under its root start tag and
    holds exactly the inserted nodes before the closing tag.

    The original parsed and the splice point is at its closing root tag, so this proves
    the whole new file parses, reading only the end of it. The lines before are kept as
    newlines, so the returned root's elements carry the lines they have in the new file.
    """
    text = new[len(layout.bom) :].decode(layout.encoding)
    shift = len(ns_decl) if ns_decl is not None else 0
    start_tag = text[layout.root_start_at : layout.root_start_end + shift]
    at_new = at + shift

    def breaks(t: str) -> int:
        return t.count("\n") + t.count("\r") - t.count("\r\n")

    pad = breaks(text[:at_new]) - breaks(start_tag)
    try:
        tail = etree.fromstring("\n" * pad + start_tag + text[at_new:], strict_parser())
    except etree.XMLSyntaxError as exc:
        msg = f"{where}: internal error, the edit would not parse ({exc.msg}); nothing was written"
        raise EditRefused(msg) from None
    added = [n for n in tail if isinstance(n.tag, str) or isinstance(n, etree._Comment)]
    if xacro_style:
        ok = [
            etree.QName(n).localname if isinstance(n.tag, str) else "#comment" for n in added
        ] == inserted
    else:
        ok = [_node_key(n) for n in added] == inserted
    if not ok:
        msg = f"{where}: internal error, the new text missed the closing tag; nothing was written"
        raise EditRefused(msg)
    return tail
