"""Expand one sensor macro call on its own, into the URDF elements it makes.

The call is wrapped in a tiny robot in a private temporary folder that includes the
macro file by absolute path, and expanded with sensorkit's isolated xacro. The result
says which links, joints and sensors the call creates (for the name checks) and gives
the elements themselves (inserted as text into plain URDF files, appended to the
expanded robot for validation).
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from sensorkit.base.errors import EditRefused
from sensorkit.edit.render import Lines, xacro_literal, xml_attr
from sensorkit.loading.document import strict_parser
from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.xacro_expand import LOC_ATTR, expand, expand_in_process


@dataclass
class Fragment:
    """What one macro call expands to (top-level nodes, comments included)."""

    nodes: list[etree._Element] = field(default_factory=list)
    links: list[str] = field(default_factory=list)
    joints: list[str] = field(default_factory=list)
    sensors: list[str] = field(default_factory=list)

    def created(self) -> list[str]:
        return [*self.links, *self.joints, *self.sensors]

    def elements(self) -> list[etree._Element]:
        return [n for n in self.nodes if isinstance(n.tag, str)]


def _strip_locations(el: etree._Element) -> None:
    for node in el.iter():
        if isinstance(node.tag, str) and LOC_ATTR in node.attrib:
            del node.attrib[LOC_ATTR]


def expand_fragment(
    macro_path: Path,
    macro_name: str,
    call: Lines,
    timeout: float = 60.0,
    *,
    in_process: bool = False,
) -> Fragment:
    """Expand ``call`` (lines of a macro call, without an include) against ``macro_path``.

    ``in_process``: expand in this process rather than in a forked child (with its
    timeout); only for sensorkit's own macro file called with checked values.
    """
    include = f'<xacro:include filename="{xml_attr(xacro_literal(str(macro_path.resolve())))}"/>'
    body = "\n".join("  " * (d + 1) + text for d, text in [(0, include), *call])
    wrapper = (
        '<?xml version="1.0"?>\n'
        '<robot name="sensorkit_fragment" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f"{body}\n</robot>\n"
    )
    with tempfile.TemporaryDirectory(prefix="sensorkit-fragment-") as tmp:
        path = Path(tmp) / "fragment.urdf.xacro"
        path.write_text(wrapper, encoding="utf-8")
        resolver = PackageResolver(use_environment=False)
        if in_process:
            outcome = expand_in_process(path, {}, resolver)
        else:
            outcome = expand(path, {}, resolver, timeout=timeout)
    if outcome.error_kind is not None or outcome.xml is None:
        message = " ".join(outcome.message.split()) or "no output"
        msg = (
            f"the {macro_name} macro does not expand with these settings: {message}; check "
            "the values given to its options and --param"
        )
        raise EditRefused(msg)
    root = etree.fromstring(outcome.xml.encode("utf-8"), strict_parser())
    _strip_locations(root)
    frag = Fragment()
    for node in root:
        if isinstance(node, etree._Comment) or isinstance(node.tag, str):
            node.tail = None
            frag.nodes.append(node)
        if not isinstance(node.tag, str):
            continue
        if node.tag == "link":
            frag.links.append(node.get("name", ""))
        elif node.tag == "joint":
            frag.joints.append(node.get("name", ""))
        for sensor in node.iter("sensor"):
            if sensor.get("name"):
                frag.sensors.append(sensor.get("name", ""))
    if not frag.elements():
        msg = f"the {macro_name} macro produced nothing"
        raise EditRefused(msg)
    return frag
