"""Turn a file on disk into an XML tree with source locations, or into findings.

Plain URDF is parsed strictly by lxml (no entity resolution, no network) and keeps exact
lines. Xacro (``.xacro``, or a ``.urdf`` that contains xacro markup, as turtlebot3 and
sam_bot ship) is expanded by the real xacro library (see ``xacro_expand``).
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from sensorkit.base.errors import InputError
from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.loading.marks import LOC_ATTR, forbid_entities
from sensorkit.loading.packages import PackageResolver

if TYPE_CHECKING:
    from sensorkit.loading.untrusted import Untrusted

MAX_FILE_BYTES = 64 * 1024 * 1024
# compiled on first use (by re's cache): a plain URDF never needs it
_XACRO_MARKERS = rb"xmlns:xacro\s*=|<xacro:|\$\{|\$\("


def display_path(path: str | Path) -> str:
    """A path as the user should see it: relative to the working folder when inside it."""
    p = Path(path)
    try:
        rel = os.path.relpath(p)
    except ValueError:
        return str(p)
    ups = len(re.findall(r"(?:^|/)\.\.(?=/|$)", rel))
    return rel if ups <= 3 else str(p)


def strict_parser() -> etree.XMLParser:
    """The only XML parser sensorkit uses on user files: strict and offline."""
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        # Large comments and text nodes (over libxml2's 10 MB default) must parse; the
        # limits huge_tree lifts also guard entity expansion, which is off here and whose
        # DTDs are refused before parsing (forbid_entities). Files stay under MAX_FILE_BYTES.
        huge_tree=True,
        remove_blank_text=False,
        recover=False,
    )


@dataclass
class Document:
    """An XML robot description with a way back to the file and line of each element."""

    path: Path
    root: etree._Element
    files: list[str] = field(default_factory=list)
    expanded: bool = False
    includes: list[str] = field(default_factory=list)

    _display: str | None = field(default=None, repr=False)
    _file_display: dict[int, str] = field(default_factory=dict, repr=False)

    @property
    def display(self) -> str:
        if self._display is None:
            self._display = display_path(self.path)
        return self._display

    def locate(self, el: etree._Element | None) -> SourceRef:
        """File and line an element was written at (nearest stamped ancestor for xacro)."""
        if el is None:
            return SourceRef(self.display)
        if not self.expanded:
            return SourceRef(self.display, el.sourceline)
        cur: etree._Element | None = el
        while cur is not None:
            loc = cur.get(LOC_ATTR)
            if loc:
                idx, _, line = loc.partition(":")
                if idx.isdigit() and int(idx) < len(self.files) and line.isdigit():
                    i = int(idx)
                    if i not in self._file_display:
                        self._file_display[i] = display_path(self.files[i])
                    return SourceRef(self._file_display[i], int(line))
            cur = cur.getparent()
        return SourceRef(self.display)

    def source_files(self) -> list[str]:
        """Every file the description was read from (the top-level file first)."""
        if not self.expanded:
            return [str(self.path)]
        return list(self.files) or [str(self.path)]


@dataclass
class LoadResult:
    """A document, or the findings that say why there is none (SK101..SK103)."""

    document: Document | None
    findings: list[Finding] = field(default_factory=list)


def looks_like_xacro(path: Path, data: bytes) -> bool:
    """True for .xacro files and for .urdf files that really contain xacro markup."""
    if path.name.endswith(".xacro"):
        return True
    # Plain substring tests, each a single pass: much faster than a regex on MBs. A
    # one-byte search (memchr) first, as the two-byte ones cost ten times more.
    if b"$" in data and (b"${" in data or b"$(" in data):
        return True
    if b":" not in data:  # what is left to find (xmlns:xacro=, <xacro:) has a colon
        return False
    return b"xacro" in data and bool(re.search(_XACRO_MARKERS, data))


def read_input(path: Path) -> bytes:
    """The bytes of ``path`` or an InputError that names it and says why."""
    try:
        if path.is_dir():
            msg = f"{display_path(path)}: is a folder, not a URDF or xacro file"
            raise InputError(msg)
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            msg = f"{display_path(path)}: {size} bytes is larger than the {MAX_FILE_BYTES} sensorkit reads"
            raise InputError(msg)
        return path.read_bytes()
    except FileNotFoundError:
        msg = f"{display_path(path)}: no such file"
        raise InputError(msg) from None
    except PermissionError:
        msg = f"{display_path(path)}: permission denied"
        raise InputError(msg) from None
    except OSError as exc:
        msg = f"{display_path(path)}: cannot read ({exc.strerror})"
        raise InputError(msg) from None


def _xml_finding(file: str, message: str, line: int | None, column: int | None) -> Finding:
    return Finding(
        "SK101",
        Severity.ERROR,
        f"not well-formed XML: {message}",
        SourceRef(file, line),
        column=column,
        fix="fix the XML at that line and column (an unclosed tag, a stray '<' or '&', a bad attribute quote)",
    )


def drop_default_namespace(root: etree._Element) -> etree._Element:
    """Remove a default xmlns from element tags, as urdfdom (TinyXML) ignores it too."""
    ns = root.nsmap.get(None)
    if ns:
        prefix = "{" + ns + "}"
        for el in root.iter():
            tag = el.tag
            if isinstance(tag, str) and tag.startswith(prefix):
                el.tag = tag[len(prefix) :]
    return root


def _check_root(root: etree._Element, where: str) -> None:
    tag = root.tag if isinstance(root.tag, str) else ""
    local = etree.QName(root).localname if tag else ""
    if local != "robot":
        if local == "sdf":
            msg = (
                f"{where}: root element is <sdf>: this is an SDF model, and sensorkit "
                "validates URDF/xacro robot descriptions (<robot>)"
            )
        else:
            msg = f"{where}: root element is <{local or '?'}>, not <robot>: not a URDF robot description"
        raise InputError(msg)


def parse_plain(path: Path, data: bytes) -> LoadResult:
    """Parse a plain URDF strictly, with exact lines."""
    where = display_path(path)
    if not data.strip():
        return LoadResult(None, [_xml_finding(where, "the file is empty", 1, 1)])
    reason = forbid_entities(data)
    if reason:
        return LoadResult(None, [_xml_finding(where, reason, 1, 1)])
    try:
        root = etree.fromstring(data, strict_parser(), base_url=None)
    except etree.XMLSyntaxError as exc:
        line, col = exc.position if exc.position else (exc.lineno, exc.offset)
        return LoadResult(None, [_xml_finding(where, str(exc.msg), line, col)])
    _check_root(root, where)
    return LoadResult(Document(path=path, root=drop_default_namespace(root)))


def plain_document(path: Path, root: etree._Element) -> Document:
    """The Document ``parse_plain`` makes, from a tree already parsed with strict_parser."""
    _check_root(root, display_path(path))
    return Document(path=path, root=drop_default_namespace(root))


def load_description(
    path: Path,
    *,
    args: dict[str, str] | None = None,
    resolver: PackageResolver | None = None,
    timeout: float = 60.0,
    untrusted: Untrusted | None = None,
    overlay: Mapping[str, bytes] | None = None,
) -> LoadResult:
    """Read ``path`` (URDF or xacro) into a Document, or findings explaining why not.

    Raises InputError when the file cannot be read or is not a robot description.
    ``overlay`` maps absolute paths to bytes used instead of the files' own (``--fix``
    validates an edit in memory before writing it).
    """
    key = os.path.abspath(path)
    data = overlay[key] if overlay and key in overlay else read_input(path)
    if not looks_like_xacro(path, data):
        return parse_plain(path, data)
    where = display_path(path)
    if not data.strip():
        return LoadResult(None, [_xml_finding(where, "the file is empty", 1, 1)])
    # Strict pre-parse: well-formedness with exact position, and no entities, before xacro.
    plain = parse_plain(path, data)
    if plain.document is None:
        return plain
    resolver = (resolver or PackageResolver()).for_file(path)
    from sensorkit.loading.xacro_expand import expand

    outcome = expand(
        path, dict(args or {}), resolver, timeout=timeout, untrusted=untrusted, overlay=overlay
    )
    if outcome.error_kind is not None:
        return LoadResult(None, [_expansion_finding(path, outcome)])
    assert outcome.xml is not None
    try:
        root = etree.fromstring(outcome.xml.encode("utf-8"), strict_parser())
    except etree.XMLSyntaxError as exc:  # xacro produced something odd; report, don't crash
        return LoadResult(None, [_xml_finding(where, f"xacro output: {exc.msg}", None, None)])
    _check_root(root, where)
    doc = Document(
        path=path,
        root=drop_default_namespace(root),
        files=outcome.files,
        expanded=True,
        includes=outcome.includes,
    )
    return LoadResult(doc)


def _expansion_finding(path: Path, outcome: object) -> Finding:
    from sensorkit.loading.xacro_expand import ExpandOutcome

    assert isinstance(outcome, ExpandOutcome)
    file = display_path(outcome.error_file) if outcome.error_file else display_path(path)
    stack = "; ".join(outcome.stack)
    if outcome.error_kind == "xml":
        return _xml_finding(file, outcome.message, outcome.error_line, outcome.error_column)
    if outcome.error_kind == "package":
        searched = "; ".join(outcome.searched)
        return Finding(
            "SK103",
            Severity.ERROR,
            f"{outcome.message}; searched: {searched}" + (f" ({stack})" if stack else ""),
            SourceRef(file, _find_line(outcome.error_file, f"$(find {outcome.package})")),
            fix=(
                f"pass --package-path {outcome.package}=DIR (the folder holding its package.xml), "
                "or --package-path WORKSPACE/src, or source the workspace (AMENT_PREFIX_PATH)"
            ),
        )
    msg = outcome.message
    fix = "fix the xacro error above"
    m = re.search(r"Undefined substitution argument (\S+)", msg)
    if m:
        fix = f'declare <xacro:arg name="{m.group(1)}" default="..."/> or pass --arg {m.group(1)}:=VALUE'
    elif "include loop" in msg:
        fix = "remove the include that brings a file back into itself"
    elif "not allowed with --untrusted" in msg:
        fix = "pass --env NAME if CI may share that variable, or use $(optenv NAME default)"
    elif "--untrusted:" in msg and "outside the workspace" in msg:
        fix = "keep included files inside the repository, or pass --package-path for a trusted package"
    elif "--untrusted:" in msg:
        fix = "use plain arithmetic, properties and math in expressions (see README, --untrusted)"
    elif outcome.error_kind == "timeout":
        fix = "look for an expression that computes something huge, e.g. ${10**10**10}"
    line = None
    if outcome.macro_file and outcome.error_kind == "xacro":
        # The error is in a macro's body: point at the macro's own file, at the line that
        # names what xacro complains of, else at the macro's definition.
        file = display_path(outcome.macro_file)
        line = _guess_line(outcome.macro_file, msg, after=outcome.macro_line) or outcome.macro_line
    elif outcome.error_file:
        line = _guess_line(outcome.error_file, msg)
    return Finding(
        "SK102",
        Severity.ERROR,
        f"xacro expansion failed: {msg}" + (f" ({stack})" if stack else ""),
        SourceRef(file, line),
        fix=fix,
    )


def _find_line(file: str | None, needle: str, after: int | None = None) -> int | None:
    if not file:
        return None
    try:
        text = Path(file).read_text("utf-8", "replace")
    except OSError:
        return None
    for i, line in enumerate(text.splitlines(), 1):
        if after is not None and i < after:
            continue
        if needle in line and not line.lstrip().startswith("<!--"):
            return i
    return None


def _guess_line(file: str, message: str, after: int | None = None) -> int | None:
    """A best-effort line for a xacro error: the first line naming what it complains of."""
    for pattern in (
        r"(\$\(env [^)\s]+)\)",
        r"--untrusted: (\S+) is outside",
        r"Undefined substitution argument (\S+)",
        r"name '([^']+)' is not defined",
        r"unknown macro name:? (\S+)",
        r"No such file or directory: (\S+)",
    ):
        m = re.search(pattern, message)
        if m:
            token = m.group(1).strip("'\"")
            if "/" in token:
                token = os.path.basename(token)
            return _find_line(file, token, after)
    return None
