"""SK101 findings about the input itself, before any robot is read: XML that is not well
formed, a file past a size bound, an encoding ROS's readers refuse, a prefixed root element.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from lxml import etree

from sensorkit.base.findings import Finding, Severity, SourceRef

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable, Sequence
    from pathlib import Path

    from sensorkit.loading.packages import Duplicate, PackageResolver

    Show = Callable[[str | Path], str]

__all__ = [
    "duplicate_finding",
    "duplicate_findings",
    "encoding_finding",
    "limit_finding",
    "prefixed_root_finding",
    "xml_finding",
]


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


KEEP_ONE = "keep one copy"  # the fix of a package found twice: nothing is missing


def duplicate_finding(dup: Duplicate, where: SourceRef, display_path: Show) -> Finding:
    """SK103 for a package the robot uses that is in one searched folder twice: colcon
    refuses to build such a workspace (an error: nothing of it is installed); around a
    file in no colcon workspace, which copy a build would use is unknown (info).
    ``display_path`` shows a path (document.display_path)."""
    from sensorkit.loading.packages import COLCON_DUPLICATE_SOURCE

    copies = " and ".join(display_path(f) for f in dup.folders)
    used = display_path(dup.used) + (" (the package holding this file)" if dup.own else "")
    if dup.workspace:
        sev = Severity.ERROR
        said = (
            f"package {dup.name!r} is in {display_path(dup.root)} twice: {copies}; colcon "
            f"refuses to build such a workspace (\"Duplicate package names not supported\", "
            f"{COLCON_DUPLICATE_SOURCE}), so nothing of it is installed; sensorkit read {used}"
        )
    else:
        sev = Severity.INFO
        said = (
            f"package {dup.name!r} is found twice around this file: {copies}; which one a "
            f"build installs is unknown; sensorkit read {used}"
        )
    return Finding(
        "SK103",
        sev,
        said,
        where,
        fix=(
            f"{KEEP_ONE}: delete the other, or put an empty COLCON_IGNORE file in its "
            f"folder (colcon and sensorkit then skip it); or choose one with --package-path "
            f"{dup.name}=DIR"
        ),
    )


def duplicate_findings(
    resolver: PackageResolver, names: Iterable[str], files: Sequence[str], display_path: Show
) -> list[Finding]:
    """:func:`duplicate_finding` of each package of ``names`` found twice, located at the
    first ``$(find NAME)`` or ``package://NAME/`` of ``files`` (the expansion's files)."""
    out = []
    for name in sorted(set(names)):
        dup = resolver.duplicate(name)
        if dup is None:
            continue
        where = SourceRef(display_path(files[0]) if files else "")
        for file in files:
            line = _line_naming(file, (f"$(find {name})", f"package://{name}/"))
            if line is not None:
                where = SourceRef(display_path(file), line)
                break
        out.append(duplicate_finding(dup, where, display_path))
    return out


def _line_naming(file: str, needles: tuple[str, ...]) -> int | None:
    try:
        with open(file, encoding="utf-8", errors="replace") as f:
            for i, line in enumerate(f, 1):
                if any(n in line for n in needles):
                    return i
    except OSError:
        pass
    return None
