"""SK101 findings about the input itself, before any robot is read: XML that is not well
formed, a file past a size bound, an encoding ROS's readers refuse, a prefixed root element.
"""

from __future__ import annotations

from lxml import etree

from sensorkit.base.findings import Finding, Severity, SourceRef

__all__ = ["encoding_finding", "limit_finding", "prefixed_root_finding", "xml_finding"]


def xml_finding(file: str, message: str, line: int | None, column: int | None) -> Finding:
    return Finding(
        "SK101",
        Severity.ERROR,
        f"not well-formed XML: {message}",
        SourceRef(file, line),
        column=column,
        fix="fix the XML at that line and column (an unclosed tag, a stray '<' or '&', a bad attribute quote)",
    )


def limit_finding(rule: str, file: str, message: str, line: int | None) -> Finding:
    return Finding(
        rule,
        Severity.ERROR,
        message,
        SourceRef(file, line),
        fix="this is not a robot description sensorkit can check: look for generated or "
        "corrupted content (a runaway macro or a loop in a script that wrote the file)",
    )


# Byte order marks of the encodings ROS's own readers refuse: xacro opens the file as
# UTF-8 text (xacro 2.0.8 __init__.py parse: open(filename), "'utf-8' codec can't decode
# byte 0xff"), and urdfdom's TinyXML-2 reads UTF-8 only (check_urdf on a UTF-16 file:
# "Error document empty"). UTF-32 first: its little-endian mark starts as UTF-16's does.
_FOREIGN_BOMS = (
    (b"\xff\xfe\x00\x00", "UTF-32"),
    (b"\x00\x00\xfe\xff", "UTF-32"),
    (b"\xff\xfe", "UTF-16"),
    (b"\xfe\xff", "UTF-16"),
)


def encoding_finding(where: str, data: bytes) -> Finding | None:
    """SK101 for a file in UTF-16 or UTF-32 (a byte order mark, or a NUL in its first
    bytes), which xacro, check_urdf, robot_state_publisher and libsdformat refuse."""
    name = next((enc for bom, enc in _FOREIGN_BOMS if data.startswith(bom)), None)
    if name is None and b"\x00" in data[:4]:
        name = "UTF-16"
    if name is None:
        return None
    return Finding(
        "SK101",
        Severity.ERROR,
        f"the file is {name}: xacro, check_urdf and robot_state_publisher read UTF-8 only and "
        "refuse it",
        SourceRef(where, 1),
        column=1,
        fix="save the file as UTF-8 (iconv -f " + name + " -t UTF-8 FILE > NEW, or your editor's encoding menu)",
    )


def prefixed_root_finding(root: etree._Element, where: str) -> Finding | None:
    """SK101 for a ``<urdf:robot xmlns:urdf=...>`` root: urdfdom looks for an element named
    exactly ``robot`` (check_urdf: "Could not find the 'robot' element in the xml file")."""
    if not isinstance(root.tag, str) or not root.prefix:
        return None
    local = etree.QName(root).localname
    if local not in ("robot", "sdf"):
        return None
    tool = "check_urdf and robot_state_publisher (urdfdom)" if local == "robot" else "libsdformat"
    return Finding(
        "SK101",
        Severity.ERROR,
        f"the root element is <{root.prefix}:{local}>: {tool} look for an element named "
        f"exactly '{local}' and refuse the file (\"Could not find the '{local}' element\")",
        SourceRef(where, root.sourceline),
        fix=f"write the root as <{local}> with no prefix (a default xmlns=\"...\" is fine)",
    )
