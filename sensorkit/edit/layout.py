"""Read how a robot file is written, from its raw bytes, so new text can match it.

Nothing here re-serialises the user's file. ``read_layout`` finds, in the original
bytes: the encoding (BOM, XML declaration), the newline style, the indentation of the
root's children and of their children, the byte span of the root start tag and the byte
offset of the root's closing tag. The scan is lexical and skips comments, CDATA,
processing instructions and the DOCTYPE (with its internal subset), and honours quotes
inside tags, so a ``</robot>`` inside a comment, a CDATA section or an attribute value
is never taken for the real one. The file has already passed the strict lxml parse, so
the scan can rely on it being well-formed.
"""

from __future__ import annotations

import codecs
import re
from collections import Counter
from dataclasses import dataclass, field

from lxml import etree

from sensorkit.base.errors import EditRefused, InputError

_DECL_RE = re.compile(rb"""^<\?xml[^>]*?encoding\s*=\s*["']([A-Za-z0-9._\-]+)["']""")
_NAME_RE = re.compile(r"[^\s/>]+")
_BOMS: tuple[tuple[bytes, str], ...] = (
    (codecs.BOM_UTF8, "utf-8"),
    (codecs.BOM_UTF32_LE, ""),  # before UTF-16 LE: it starts with the same two bytes
    (codecs.BOM_UTF32_BE, ""),
    (codecs.BOM_UTF16_LE, "utf-16-le"),
    (codecs.BOM_UTF16_BE, "utf-16-be"),
)


@dataclass(frozen=True)
class Layout:
    """How a file is written and where the root element starts and ends.

    Offsets ``*_at`` are character offsets into ``text`` (the file decoded, without
    its BOM); ``byte_offset`` turns them into offsets into the original bytes.
    """

    encoding: str
    bom: bytes
    text: str
    newline: str
    indent: str  # leading whitespace of the root's children
    unit: str  # one more level of nesting
    root_name: str  # as written, with a prefix if any
    root_start_at: int  # '<' of the root start tag
    root_start_end: int  # just after its '>'
    root_end_at: int  # '<' of the closing root tag

    def byte_offset(self, char_at: int) -> int:
        """The offset in the original bytes of character ``char_at`` of ``text``."""
        return len(self.bom) + len(self.text[:char_at].encode(self.encoding))

    def encode(self, text: str) -> bytes:
        """New text in the file's encoding (characters it cannot hold as references)."""
        return text.encode(self.encoding, errors="xmlcharrefreplace")

    def line_start_before(self, at: int) -> int | None:
        """Start of the line holding ``at`` if only spaces/tabs precede it there, else None."""
        i = at
        while i > 0 and self.text[i - 1] in " \t":
            i -= 1
        if i == 0 or self.text[i - 1] in "\r\n":
            return i
        return None

    def previous_line_blank(self, line_start: int) -> bool:
        """True when the line before the one starting at ``line_start`` is blank (or none)."""
        if line_start == 0:
            return True
        end = line_start
        # step over this line's terminator (\n, \r\n or \r)
        if self.text[end - 1] == "\n":
            end -= 1
            if end > 0 and self.text[end - 1] == "\r":
                end -= 1
        elif self.text[end - 1] == "\r":
            end -= 1
        start = max(self.text.rfind("\n", 0, end), self.text.rfind("\r", 0, end)) + 1
        return not self.text[start:end].strip()


def detect_encoding(data: bytes, where: str) -> tuple[str, bytes]:
    """(Python codec name, BOM bytes) of an XML file; InputError for what cannot be edited."""
    for bom, codec in _BOMS:
        if data.startswith(bom):
            if not codec:
                msg = f"{where}: UTF-32 files cannot be edited by sensorkit; convert it to UTF-8"
                raise InputError(msg)
            return codec, bom
    if data[:2] in (b"\x00<", b"<\x00"):
        msg = f"{where}: UTF-16 without a byte order mark cannot be edited; convert it to UTF-8"
        raise InputError(msg)
    m = _DECL_RE.match(data)
    name = m.group(1).decode("ascii") if m else "utf-8"
    try:
        codec = codecs.lookup(name).name
    except LookupError:
        msg = f"{where}: unknown encoding {name!r} in the XML declaration"
        raise InputError(msg) from None
    if codec.startswith(("utf-16", "utf-32")):
        # declared UTF-16 but no BOM and ASCII-looking bytes: libxml2 refuses it as well
        msg = f"{where}: declares {name} but has no byte order mark"
        raise InputError(msg)
    return codec, b""


def _detect_newline(text: str) -> str:
    crlf = text.count("\r\n")
    lf = text.count("\n") - crlf
    cr = text.count("\r") - crlf
    if crlf and crlf >= lf and crlf >= cr:
        return "\r\n"
    if lf or not cr:
        return "\n"
    return "\r"


def _skip_to(text: str, needle: str, start: int, what: str) -> int:
    end = text.find(needle, start)
    if end < 0:
        msg = f"unterminated {what}"
        raise EditRefused(msg)
    return end + len(needle)


def _doctype_end(text: str, start: int) -> int:
    """End of ``<!DOCTYPE ...>``: brackets, quotes and comments of the internal subset."""
    i = start + 2
    depth = 0
    n = len(text)
    while i < n:
        c = text[i]
        if text.startswith("<!--", i):
            i = _skip_to(text, "-->", i + 4, "comment")
            continue
        if c in "\"'":
            i = _skip_to(text, c, i + 1, "DOCTYPE")
            continue
        if c == "[":
            depth += 1
        elif c == "]":
            depth -= 1
        elif c == ">" and depth <= 0:
            return i + 1
        i += 1
    msg = "unterminated DOCTYPE"
    raise EditRefused(msg)


def _tag_end(text: str, start: int) -> int:
    """Index just after the '>' closing the tag at ``start`` (quotes may hold '>')."""
    i = start + 1
    n = len(text)
    while i < n:
        c = text[i]
        if c == ">":
            return i + 1
        i = _skip_to(text, c, i + 1, "tag") if c in "\"'" else i + 1
    msg = "unterminated tag"
    raise EditRefused(msg)


def _leading_ws(text: str, at: int) -> str | None:
    """The spaces/tabs before ``at`` when the tag at ``at`` starts its line, else None."""
    i = at
    while i > 0 and text[i - 1] in " \t":
        i -= 1
    if i == 0 or text[i - 1] in "\r\n":
        return text[i:at]
    return None


_TAIL_RE = re.compile(r"\s*>(?:\s+|<!--.*?-->|<\?.*?\?>)*\Z", re.S)
_TAIL_ITEM_RE = re.compile(r"<!--.*?-->|<\?.*?\?>", re.S)


def _line_ws(before: str | None) -> str | None:
    """The spaces/tabs that start a tag's line, from the text between it and the node
    before it (None when something else stands before the tag on its line)."""
    if not before:
        return None
    cut = max(before.rfind("\n"), before.rfind("\r"))
    if cut < 0:
        return None
    ws = before[cut + 1 :]
    return ws if not ws.strip(" \t") else None


def _from_tree(
    text: str, root: etree._Element
) -> tuple[tuple[int, int, str], int, Counter[str], list[str]] | None:
    """What the full scan finds, from the parsed tree and two short scans, or None when
    only the full scan can tell (character references, CDATA, a lookalike closing tag).

    Indentation comes from the whitespace text the parser kept between nodes; the root
    start tag from a scan of the prolog; the closing tag is the last one in the file,
    checked to be followed by nothing but comments, processing instructions and space.
    """
    if "&#" in text or "<![CDATA[" in text:
        return None
    head = _scan(text, stop_at_root=True)
    if head.root_start is None or head.root_start[3]:
        return None
    start_at, start_end, name, _ = head.root_start
    end_at = text.rfind("</" + name)
    if end_at < start_end:
        return None
    after = text[end_at + 2 + len(name) :]
    if not _TAIL_RE.match(after):
        return None
    if len(_TAIL_ITEM_RE.findall(after)) != sum(1 for _ in root.itersiblings()):
        return None
    depth1: Counter[str] = Counter()
    depth2: list[str] = []
    before = root.text
    for node in root:
        if isinstance(node.tag, str):
            ws = _line_ws(before)
            if ws is not None:
                depth1[ws] += 1
            inner = node.text
            for sub in node:
                if isinstance(sub.tag, str):
                    ws = _line_ws(inner)
                    if ws is not None:
                        depth2.append(ws)
                inner = sub.tail
        before = node.tail
    return (start_at, start_end, name), end_at, depth1, depth2


@dataclass
class _Scan:
    root_start: tuple[int, int, str, bool] | None = None
    last_end: tuple[int, str] | None = None
    depth1: Counter[str] = field(default_factory=Counter)
    depth2: list[str] = field(default_factory=list)


def _scan(text: str, *, stop_at_root: bool = False) -> _Scan:
    """The lexical scan of the whole text (or of the prolog up to the root start tag)."""
    out = _Scan()
    depth = 0
    i = 0
    n = len(text)
    while True:
        j = text.find("<", i)
        if j < 0:
            break
        if text.startswith("<!--", j):
            i = _skip_to(text, "-->", j + 4, "comment")
        elif text.startswith("<![CDATA[", j):
            i = _skip_to(text, "]]>", j + 9, "CDATA section")
        elif text.startswith("<?", j):
            i = _skip_to(text, "?>", j + 2, "processing instruction")
        elif text.startswith("<!", j):
            i = _doctype_end(text, j)
        elif text.startswith("</", j):
            k = _tag_end(text, j)
            out.last_end = (j, text[j + 2 : k - 1].strip())
            depth -= 1
            i = k
        else:
            k = _tag_end(text, j)
            m = _NAME_RE.match(text, j + 1)
            name = m.group(0) if m else ""
            self_closing = text[k - 2] == "/"
            if out.root_start is None:
                out.root_start = (j, k, name, self_closing)
                if stop_at_root:
                    return out
            ws = _leading_ws(text, j)
            if ws is not None:
                if depth == 1:
                    out.depth1[ws] += 1
                elif depth == 2:
                    out.depth2.append(ws)
            if not self_closing:
                depth += 1
            i = k
        if i >= n:
            break
    return out


def read_layout(data: bytes, where: str, root: etree._Element | None = None) -> Layout:
    """Scan the original bytes of a well-formed XML file (see the module doc).

    ``root``, the file parsed, saves scanning every tag of a large file: the indentation
    is read from the tree instead (same result; the full scan runs when it could differ).
    """
    encoding, bom = detect_encoding(data, where)
    try:
        text = data[len(bom) :].decode(encoding)
    except UnicodeDecodeError as exc:
        msg = f"{where}: not valid {encoding} at byte {exc.start + len(bom)}"
        raise InputError(msg) from None
    # Offsets are computed by re-encoding prefixes: that only works when the codec
    # round-trips this file exactly (true for UTF-8/16 and single-byte codecs).
    if text.encode(encoding) != data[len(bom) :]:
        msg = f"{where}: its {encoding} bytes do not round-trip, so they cannot be kept exactly"
        raise InputError(msg)

    quick = _from_tree(text, root) if root is not None else None
    if quick is not None:
        (start_at, start_end, root_name), root_end_at, depth1, depth2 = quick
    else:
        scan = _scan(text)
        if scan.root_start is None:
            msg = f"{where}: no root element"
            raise EditRefused(msg)
        start_at, start_end, root_name, self_closing = scan.root_start
        last_end = scan.last_end
        if self_closing or last_end is None or last_end[1] != root_name:
            msg = (
                f"{where}: <{root_name}/> has no closing tag to insert before (the robot is empty)"
            )
            raise EditRefused(msg)
        root_end_at, depth1, depth2 = last_end[0], scan.depth1, scan.depth2

    indent = depth1.most_common(1)[0][0] if depth1 else "  "
    deeper = Counter(
        ws[len(indent) :] for ws in depth2 if ws.startswith(indent) and len(ws) > len(indent)
    )
    if deeper:
        unit = deeper.most_common(1)[0][0]
    elif indent:
        unit = indent
    else:
        unit = "  "
    return Layout(
        encoding=encoding,
        bom=bom,
        text=text,
        newline=_detect_newline(text),
        indent=indent,
        unit=unit,
        root_name=root_name,
        root_start_at=start_at,
        root_start_end=start_end,
        root_end_at=root_end_at,
    )
