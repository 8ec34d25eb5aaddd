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
from sensorkit.loading.input_findings import (
    duplicate_findings,
    encoding_finding,
    limit_finding,
    prefixed_root_finding,
    xml_finding,
)
from sensorkit.loading.marks import LOC_ATTR, forbid_entities
from sensorkit.loading.packages import PackageResolver

if TYPE_CHECKING:
    from sensorkit.loading.cache import ExpansionCache
    from sensorkit.loading.untrusted import Untrusted
    from sensorkit.loading.xacro_expand import ExpandOutcome

MAX_FILE_BYTES = 64 * 1024 * 1024
# Bounds on what a description may hold, checked before the model is built (issue 25:
# validate within 60 s and 1 GB on any input the loader accepts). From the corpus
# (tests/corpus, tests/realworld): the largest expanded robot, PR2 (pr2.urdf.xacro), has
# 2,623 elements; the longest name is 67 characters (osrf/vrx's wamv_gazebo) and the
# longest attribute value 119. The caps are 23x and 61x those. Measured at the cap: 60,000
# elements that are each a finding took 9 s / 150 MB (text) and 19 s / 400 MB (sarif);
# 20,000 <gazebo> blocks each with a sensor 17 s / 450 MB (sarif); 2,000,000 elements
# took 92 s / 4.4 GB, hence not higher. That cap stays for --untrusted input
# (MAX_ELEMENTS_UNTRUSTED). Trusted input (issue 36): plain URDF validation grows about
# 20 us and 1.8 KiB per element, so 500,000 stays within 60 s and 1 GB; a user raises
# (or lowers) it with --max-elements or the settings key max-elements (set_max_elements).
MAX_ELEMENTS = 500_000
MAX_ELEMENTS_UNTRUSTED = 60_000
_GIVEN_MAX_ELEMENTS: list[int | None] = [None]
MAX_NAME_CHARS = 4096
# The attributes that name a link, joint, sensor or frame (kept whole as keys).
_NAME_ATTRS = ("name", "reference", "link", "joint")
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


_STRICT: dict[str, bool] = {
    "resolve_entities": False,
    "no_network": True,
    "load_dtd": False,
    "dtd_validation": False,
    # Large comments and text nodes (over libxml2's 10 MB default) must parse; the
    # limits huge_tree lifts also guard entity expansion, which is off here and whose
    # DTDs are refused before parsing (forbid_entities). Files stay under MAX_FILE_BYTES,
    # with at most MAX_ELEMENTS elements (parse_bounded).
    "huge_tree": True,
    "remove_blank_text": False,
    "recover": False,
}


def strict_parser() -> etree.XMLParser:
    """The only XML parser sensorkit uses on user files: strict and offline."""
    return etree.XMLParser(**_STRICT)


class OverLimit(Exception):
    """A description over one of the bounds (MAX_ELEMENTS, MAX_NAME_CHARS)."""

    def __init__(self, message: str, line: int | None = None) -> None:
        super().__init__(message)
        self.line = line


def set_max_elements(limit: int | None) -> None:
    """The element bound of this process (``--max-elements``; None: the defaults)."""
    _GIVEN_MAX_ELEMENTS[0] = limit


def max_elements(untrusted: bool = False) -> int:
    """The element bound: as set (``set_max_elements``), else MAX_ELEMENTS, or
    MAX_ELEMENTS_UNTRUSTED for untrusted input."""
    given = _GIVEN_MAX_ELEMENTS[0]
    if given is not None:
        return given
    return MAX_ELEMENTS_UNTRUSTED if untrusted else MAX_ELEMENTS


def parse_bounded(data: bytes, limit: int | None = None) -> etree._Element:
    """``data`` parsed by strict_parser, refused with OverLimit past ``limit`` elements
    (default :func:`max_elements`; counted while parsing: a 15-million-element file stops
    at the cap) or with a name longer than MAX_NAME_CHARS. Raises XMLSyntaxError for
    malformed XML."""
    limit = max_elements() if limit is None else limit
    # Every element starts with "<" that no "</" is: an upper bound, one pass in C.
    if data.count(b"<") - data.count(b"</") <= limit:
        root = etree.fromstring(data, strict_parser(), base_url=None)
    else:
        root = _count_parse(data, limit)
    _check_names(root)
    return root


def _count_parse(data: bytes, limit: int) -> etree._Element:
    parser = etree.XMLPullParser(events=("start",), **_STRICT)
    count = 0
    step = 1 << 20
    for at in range(0, len(data), step):
        parser.feed(data[at : at + step])
        for _ in parser.read_events():
            count += 1
        if count > limit:
            msg = (
                f"more than {limit} elements: sensorkit reads descriptions up to that "
                "size (the largest real robot it knows, PR2, has 2,623; --max-elements "
                "or the settings key max-elements raises it)"
            )
            raise OverLimit(msg)
    root: etree._Element = parser.close()
    return root


def _check_names(root: etree._Element) -> None:
    test = " or ".join(f"local-name()='{a}'" for a in _NAME_ATTRS)
    hits = root.xpath(f"(//@*[({test}) and string-length(.) > {MAX_NAME_CHARS}])[1]")
    if not isinstance(hits, list) or not hits:
        return
    value = hits[0]
    el = getattr(value, "getparent", lambda: None)()
    attr = str(getattr(value, "attrname", "name"))
    tag = el.tag if el is not None and isinstance(el.tag, str) else "?"
    from sensorkit.base.quote import clip

    msg = (
        f"<{clip(tag, 60)} {clip(attr, 60)}=...>: a name longer than {MAX_NAME_CHARS} "
        f"characters ({len(str(value))}): sensorkit reads names up to that length"
    )
    raise OverLimit(msg, el.sourceline if el is not None else None)


@dataclass
class Document:
    """An XML robot description with a way back to the file and line of each element."""

    path: Path
    root: etree._Element
    files: list[str] = field(default_factory=list)
    expanded: bool = False
    includes: list[str] = field(default_factory=list)
    # every file the expansion read, when it was recorded (sensorkit.loading.reads):
    # includes, and YAML files read with xacro.load_yaml, which ``files`` does not hold
    reads: list[str] = field(default_factory=list)
    packages: list[str] = field(default_factory=list)  # what $(find) and package:// resolved

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


def _refuse_what_is_not_xml(path: Path, data: bytes) -> None:
    """A file not named ``.urdf``/``.xacro`` whose first character is not ``<`` (XML's
    first, after a byte order mark and white space) is not a robot description: one line
    (a launch file, an image), not an SK101 finding. A ``.urdf``/``.xacro`` file stays a
    broken robot, reported as a finding."""
    if path.name.lower().endswith((".urdf", ".xacro")) or data[:2] in (b"\xff\xfe", b"\xfe\xff"):
        return
    head = data[:1024].removeprefix(b"\xef\xbb\xbf").lstrip()
    if not head or head.startswith(b"<"):
        return
    where = display_path(path)
    if path.name.endswith(".py"):
        msg = f"{where}: not a URDF/xacro: launch files go to `--launch` (validate, topics)"
    else:
        msg = f"{where}: not a URDF/xacro (it is not XML: it does not start with '<')"
    raise InputError(msg)


# Keys only a ros_gz_bridge YAML's entries hold (ros_gz_bridge's README, "Example 4":
# ros_topic_name, gz_topic_name, ros_type_name, gz_type_name, direction).
_BRIDGE_KEYS = re.compile(rb"^\s*-?\s*(ros_topic_name|gz_topic_name|ros_type_name|gz_type_name)\s*:", re.M)


def _yaml_refusal(path: Path) -> str:
    """Where a YAML given as the robot goes: a ros_gz_bridge YAML to ``--bridge``, any
    other (a robot YAML) to ``sensorkit new``."""
    from sensorkit.base.regular import read_regular

    where = display_path(path)
    try:
        head = read_regular(path, MAX_FILE_BYTES)[:65536]
    except OSError:
        head = b""
    if _BRIDGE_KEYS.search(head):
        return (
            f"{where}: not a URDF/xacro: it is a ros_gz_bridge YAML; pass it with "
            f"`--bridge {where}` (validate, topics) beside the robot's URDF/xacro"
        )
    return f"{where}: not a URDF/xacro: robot YAMLs go to `sensorkit new`"


def read_input(path: Path) -> bytes:
    """The bytes of ``path`` or an InputError that names it and says why.

    Only a regular file is read (links followed): a named pipe, a device or a socket is
    refused in one line, and at most MAX_FILE_BYTES are read whatever ``stat`` says
    (``/dev/zero`` says 0). See :mod:`sensorkit.base.regular`."""
    from sensorkit.base.regular import NotRegular, TooLarge, read_regular

    where = display_path(path)
    try:
        if path.is_dir():
            msg = f"{where}: is a folder, not a URDF or xacro file"
            raise InputError(msg)
        if path.suffix.lower() in (".yaml", ".yml"):
            raise InputError(_yaml_refusal(path))
        data = read_regular(path, MAX_FILE_BYTES)
        _refuse_what_is_not_xml(path, data)
        return data
    except FileNotFoundError:
        msg = f"{where}: no such file"
        raise InputError(msg) from None
    except PermissionError:
        msg = f"{where}: permission denied"
        raise InputError(msg) from None
    except (NotRegular, TooLarge) as exc:
        raise InputError(f"{where}: {exc.strerror}") from None
    except OSError as exc:
        msg = f"{where}: cannot read ({exc.strerror})"
        raise InputError(msg) from None


def confine_input(path: Path, resolver: PackageResolver) -> None:
    """``--untrusted``: the input itself, its links resolved, lies inside the readable
    area (computed from where the link sits), else an InputError naming the file as
    given (never where it points)."""
    if not resolver.allows(path):
        msg = (
            f"{display_path(path)}: --untrusted: a link to a file outside its repository "
            "(the readable area); not read"
        )
        raise InputError(msg)


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


def _check_root(root: etree._Element, where: str, sdf: bool = False) -> None:
    tag = root.tag if isinstance(root.tag, str) else ""
    local = etree.QName(root).localname if tag else ""
    if local != "robot" and not (sdf and local == "sdf"):
        if local == "sdf":
            msg = (
                f"{where}: root element is <sdf>: this is an SDF model in a file not named "
                "as one: name it .sdf (or .world) and sensorkit reads it as SDF"
            )
        else:
            msg = f"{where}: root element is <{local or '?'}>, not <robot>: not a URDF robot description"
        raise InputError(msg)


def parse_plain(path: Path, data: bytes, sdf: bool = False, limit: int | None = None) -> LoadResult:
    """Parse a plain URDF strictly, with exact lines (an ``<sdf>`` root too with ``sdf``),
    at most ``limit`` elements (see :func:`parse_bounded`)."""
    where = display_path(path)
    if not data.strip():
        return LoadResult(None, [xml_finding(where, "the file is empty", 1, 1)])
    refused = encoding_finding(where, data)
    if refused is not None:
        return LoadResult(None, [refused])
    reason = forbid_entities(data)
    if reason:
        return LoadResult(None, [xml_finding(where, reason, 1, 1)])
    try:
        root = parse_bounded(data, limit)
    except etree.XMLSyntaxError as exc:
        line, col = exc.position if exc.position else (exc.lineno, exc.offset)
        return LoadResult(None, [xml_finding(where, str(exc.msg), line, col)])
    except OverLimit as exc:
        return LoadResult(None, [limit_finding("SK101", where, str(exc), exc.line)])
    _check_root(root, where, sdf)
    refused = prefixed_root_finding(root, where)
    if refused is not None:
        return LoadResult(None, [refused])
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
    cache: ExpansionCache | None = None,
    sdf: bool = False,
) -> LoadResult:
    """Read ``path`` (URDF or xacro) into a Document, or findings explaining why not.

    With ``sdf`` (a ``.sdf.xacro``), the expansion may give an ``<sdf>`` root: the caller
    reads it as SDF (:mod:`sensorkit.model.sdf_read`).

    Raises InputError when the file cannot be read or is not a robot description.
    ``overlay`` maps absolute paths to bytes used instead of the files' own (``--fix``
    validates an edit in memory before writing it). ``cache`` (see
    ``sensorkit.loading.cache``) gives a xacro expansion whose every input still holds
    instead of expanding again, and keeps a new one; it is not used under ``untrusted``.
    """
    key = os.path.abspath(path)
    if untrusted is not None and not (overlay and key in overlay):
        confine_input(path, _confined(resolver, path))
    data = overlay[key] if overlay and key in overlay else read_input(path)
    limit = max_elements(untrusted is not None)
    if not looks_like_xacro(path, data):
        return parse_plain(path, data, limit=limit)
    where = display_path(path)
    if not data.strip():
        return LoadResult(None, [xml_finding(where, "the file is empty", 1, 1)])
    # Strict pre-parse: well-formedness with exact position, and no entities, before xacro.
    plain = parse_plain(path, data, sdf, limit)
    if plain.document is None:
        return plain
    resolver = (resolver or PackageResolver()).for_file(path)
    if untrusted is not None:
        resolver = _confined(resolver, path)  # $(find) finds only packages inside the area
    outcome = _expansion(path, dict(args or {}), resolver, timeout, untrusted, overlay, cache)
    if outcome.error_kind is not None:
        return LoadResult(None, [_expansion_finding(path, outcome)])
    assert outcome.xml is not None
    xml = outcome.xml.encode("utf-8")
    outcome.xml = None  # the text is not needed again: its memory goes now
    if len(xml) > MAX_FILE_BYTES:
        msg = f"xacro output: {len(xml)} bytes is larger than the {MAX_FILE_BYTES} sensorkit reads"
        return LoadResult(None, [limit_finding("SK102", where, msg, None)])
    try:
        root = parse_bounded(xml, limit)
    except etree.XMLSyntaxError as exc:  # xacro produced something odd; report, don't crash
        return LoadResult(None, [xml_finding(where, f"xacro output: {exc.msg}", None, None)])
    except OverLimit as exc:  # the output's line is not the file's: no line
        return LoadResult(None, [limit_finding("SK102", where, f"xacro output: {exc}", None)])
    del xml
    _check_root(root, where, sdf)
    said = _arg_findings(where, data, args or {}, outcome.files, overlay, root)
    used = [*outcome.packages, *(n for n, f in (outcome.deps.packages if outcome.deps else {}).items() if f)]
    said += duplicate_findings(resolver, used, outcome.files or [str(path)], display_path) if used else []
    doc = Document(
        path=path,
        root=drop_default_namespace(root),
        files=outcome.files,
        expanded=True,
        includes=outcome.includes,
        reads=sorted(outcome.deps.files) if outcome.deps is not None else [],
        packages=used,
    )
    return LoadResult(doc, said)


def _arg_findings(
    where: str,
    data: bytes,
    args: Mapping[str, str],
    files: list[str],
    overlay: Mapping[str, bytes] | None,
    root: etree._Element,
) -> list[Finding]:
    """SK102 warnings for given args the robot never declares or reads (xacro ignores
    them) and for arg values with white space that end up in link names."""
    if not args:
        return []
    from sensorkit.loading.xacro_args import arg_findings, file_texts, robot_args, space_findings

    known = robot_args(file_texts(data, files, overlay))
    links = (el.get("name", "") for el in root.iter("link", "{*}link"))
    return arg_findings(where, args, known) + space_findings(where, args, links)


def _confined(resolver: PackageResolver | None, path: Path) -> PackageResolver:
    """``resolver`` (a new one when None) confined to the readable area of ``path``."""
    resolver = resolver or PackageResolver()
    if resolver.confined is None:
        resolver.confine_to(path)
    return resolver


def _expansion(
    path: Path,
    args: dict[str, str],
    resolver: PackageResolver,
    timeout: float,
    untrusted: Untrusted | None,
    overlay: Mapping[str, bytes] | None,
    cache: ExpansionCache | None,
) -> ExpandOutcome:
    """xacro's expansion of ``path``: from ``cache`` when it holds one still true, else
    expanded (and then kept there). Never through the cache under ``untrusted``."""
    from sensorkit.loading.xacro_expand import expand

    if cache is not None and untrusted is None:
        hit = cache.lookup(path, args, resolver, overlay)
        if hit is not None:
            return hit
    outcome = expand(path, args, resolver, timeout=timeout, untrusted=untrusted, overlay=overlay)
    if cache is not None and untrusted is None:
        cache.store(path, args, outcome)
    return outcome


def _expansion_finding(path: Path, outcome: object) -> Finding:
    from sensorkit.loading.xacro_expand import ExpandOutcome

    assert isinstance(outcome, ExpandOutcome)
    file = display_path(outcome.error_file) if outcome.error_file else display_path(path)
    stack = "; ".join(outcome.stack)
    if outcome.error_kind == "xml":
        return xml_finding(file, outcome.message, outcome.error_line, outcome.error_column)
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
