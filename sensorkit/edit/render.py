"""The new text an add inserts: a xacro macro call, or expanded URDF elements.

Text is produced as ``(depth, line)`` pairs and only turned into characters by
``render_block``, which applies the file's own indentation and newline style.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable, Sequence

from lxml import etree

from sensorkit.base.errors import EditRefused, UsageError
from sensorkit.edit.layout import Layout

Lines = list[tuple[int, str]]

_ATTR_ESCAPES = {
    "&": "&amp;",
    "<": "&lt;",
    ">": "&gt;",
    '"': "&quot;",
    "\t": "&#9;",
    "\n": "&#10;",
    "\r": "&#13;",
}


def format_number(value: float) -> str:
    """The shortest text that reads back as ``value`` (``0.2``, ``1e-05``, ``3``)."""
    v = float(value)
    if not math.isfinite(v):
        msg = f"{value!r} is not a finite number"
        raise UsageError(msg)
    if v == 0.0:
        return "0"
    text = repr(v)
    if text.endswith(".0"):
        text = text[:-2]
    return text


def xml_attr(value: str) -> str:
    """``value`` escaped for a double-quoted XML attribute."""
    return "".join(_ATTR_ESCAPES.get(c, c) for c in value)


def xml_text(value: str) -> str:
    return value.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def xacro_literal(value: str) -> str:
    """``value`` as xacro must see it to produce it verbatim (``${`` and ``$(`` escaped)."""
    return value.replace("${", "$${").replace("$(", "$$(")


def macro_call_lines(
    macro_name: str,
    attributes: Sequence[tuple[str, str]],
    xyz: Sequence[float],
    rpy: Sequence[float],
    include: str | None,
    expressions: Collection[str] = (),
) -> Lines:
    """``[<xacro:include .../>] <xacro:MACRO a="..."><origin .../></xacro:MACRO>``.

    Values are written as literals (``$(`` and ``${`` escaped), except those of the
    attributes named in ``expressions``, which are xacro expressions taken from the
    file itself (``sim="$(arg sim)"``) and written as they are.
    """
    lines: Lines = []
    if include is not None:
        lines.append((0, f'<xacro:include filename="{xml_attr(include)}"/>'))
    attrs = " ".join(
        f'{k}="{xml_attr(v if k in expressions else xacro_literal(v))}"' for k, v in attributes
    )
    lines.append((0, f"<xacro:{macro_name} {attrs}>"))
    lines.append((1, origin_tag(xyz, rpy)))
    lines.append((0, f"</xacro:{macro_name}>"))
    return lines


def origin_tag(xyz: Sequence[float], rpy: Sequence[float]) -> str:
    x = " ".join(format_number(v) for v in xyz)
    r = " ".join(format_number(v) for v in rpy)
    return f'<origin xyz="{x}" rpy="{r}"/>'


def _start_tag(el: etree._Element, close: bool) -> str:
    if not isinstance(el.tag, str) or el.tag.startswith("{"):
        msg = f"the macro produced an element sensorkit cannot write back as plain URDF: {el.tag!r}"
        raise EditRefused(msg)
    attrs = "".join(f' {k}="{xml_attr(v)}"' for k, v in el.attrib.items())
    return f"<{el.tag}{attrs}{'/>' if close else '>'}"


def element_lines(el: etree._Element, depth: int = 0) -> Lines:
    """One expanded element as indented lines (whitespace-only text dropped)."""
    if isinstance(el, etree._Comment):
        text = " ".join((el.text or "").split())
        return [(depth, f"<!-- {text} -->")]
    if not isinstance(el.tag, str):  # processing instruction or entity: not in URDF
        return []
    kids = [c for c in el if isinstance(c.tag, str) or isinstance(c, etree._Comment)]
    text = (el.text or "").strip()
    if not kids:
        if text:
            return [(depth, f"{_start_tag(el, False)}{xml_text(text)}</{el.tag}>")]
        return [(depth, _start_tag(el, True))]
    if text or any((c.tail or "").strip() for c in kids):
        msg = f"the macro produced mixed content in <{el.tag}>, which sensorkit will not reflow"
        raise EditRefused(msg)
    lines: Lines = [(depth, _start_tag(el, False))]
    for c in kids:
        lines.extend(element_lines(c, depth + 1))
    lines.append((depth, f"</{el.tag}>"))
    return lines


def fragment_lines(elements: Iterable[etree._Element], header: str | None) -> Lines:
    """Expanded URDF elements, each at depth 0, after an optional header comment."""
    lines: Lines = []
    if header:
        lines.append((0, f"<!-- {header} -->"))
    for el in elements:
        lines.extend(element_lines(el, 0))
    return lines


def render_block(lines: Lines, layout: Layout, *, at_line_start: bool, blank_before: bool) -> str:
    """The lines in the file's indentation and newline style, ready to splice.

    At a line start (the closing root tag begins its line) the block is a run of whole
    lines, after a blank line when ``blank_before``. Otherwise the closing tag shares
    its line with other content: the block starts on a new line and the closing tag
    moves to the line after it.
    """
    nl = layout.newline
    body = "".join(f"{layout.indent}{layout.unit * d}{text}{nl}" for d, text in lines)
    if not at_line_start:
        return nl + body
    return (nl if blank_before else "") + body
