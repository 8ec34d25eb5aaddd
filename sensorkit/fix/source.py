"""Elements as written: a lexical map of a file's bytes, and byte edits on it.

``--fix`` never re-serialises a file. It finds the element a finding is about in the
original text (the start tag at the line the loader recorded), then the attribute value,
text or child to change, and describes the change as a byte :class:`Edit`. The scan is
lexical like ``sensorkit.edit.layout`` (whose tag and DOCTYPE scanners it uses): comments,
CDATA, processing instructions and the DOCTYPE are skipped, quotes are honoured inside
tags, so nothing inside a comment or an attribute value is taken for markup. The file
has passed a strict parse before, so the scan can rely on it being well-formed.

Lines: lxml (plain URDF) records an element at the line of its start tag's ``>`` and
counts only LF; expat (xacro, ``sk_loc_``) records the line of its ``<`` and counts CR,
LF and CRLF. Both are kept per tag so either can be matched.
"""

from __future__ import annotations

import bisect
import html
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property

from sensorkit.base.errors import EditRefused, SensorkitError
from sensorkit.edit.layout import Layout, detect_encoding, read_layout
from sensorkit.edit.layout import _doctype_end as layout_doctype_end
from sensorkit.edit.layout import _tag_end as layout_tag_end


def escape(data: str, entities: dict[str, str] | None = None) -> str:
    """``xml.sax.saxutils.escape``: ``&``, ``<``, ``>`` and each of ``entities``. That
    module imports urllib.request (http, ssl, email: 60 ms), which validate's [*] marks,
    which load the fixers, must not pay for."""
    data = data.replace("&", "&amp;").replace(">", "&gt;").replace("<", "&lt;")
    for key, value in (entities or {}).items():
        data = data.replace(key, value)
    return data

_NAME_RE = re.compile(r"[^\s/>=]+")
_ATTR_RE = re.compile(r"""\s*([^\s=/>]+)\s*=\s*("([^"]*)"|'([^']*)')""")
_ANY_BREAK = re.compile(r"\r\n|\r|\n")


class NotFixable(Exception):
    """A finding sensorkit cannot fix automatically; the message says why."""


class Deferred(NotFixable):
    """Not fixable yet: another fix on the same element must land first."""


@dataclass(frozen=True)
class Edit:
    """Replace bytes ``start:end`` of ``file`` (an absolute path) by ``replacement``."""

    file: str
    start: int
    end: int
    replacement: bytes


@dataclass(frozen=True)
class Attr:
    name: str
    raw: str  # as written between the quotes
    start: int  # the name
    value_start: int  # just after the opening quote
    value_end: int  # the closing quote

    @property
    def value(self) -> str:
        """The value as a parser reports it (references decoded, whitespace normalised)."""
        return normalise_attr(self.raw)


def normalise_attr(raw: str) -> str:
    return html.unescape(re.sub(r"[\t\r\n]", " ", raw))


@dataclass
class Tag:
    """One element as written: its start tag and, unless empty, its end tag."""

    index: int
    name: str  # as written, with a prefix if any
    start: int  # '<'
    head_end: int  # just after the start tag's '>'
    empty: bool  # <x/>
    parent: int | None
    attrs: tuple[Attr, ...]
    children: list[int] = field(default_factory=list)
    close_start: int | None = None  # '<' of </x>
    close_end: int | None = None

    @property
    def local(self) -> str:
        return self.name.rpartition(":")[2]

    @property
    def end(self) -> int:
        """Just after the element (its '/>' or its end tag)."""
        if self.empty or self.close_end is None:
            return self.head_end
        return self.close_end

    def attr(self, name: str) -> Attr | None:
        for a in self.attrs:
            if a.name == name:
                return a
        return None


def _skip(text: str, needle: str, start: int) -> int:
    end = text.find(needle, start)
    if end < 0:
        raise NotFixable(f"unterminated {needle!r} construct")
    return end + len(needle)


def _end_of(construct: Callable[[str, int], int], text: str, start: int) -> int:
    """Where an ``edit.layout`` scanner says the construct at ``start`` ends, refusing as
    a fix does."""
    try:
        return construct(text, start)
    except EditRefused as exc:
        raise NotFixable(str(exc)) from None


def scan(text: str) -> list[Tag]:
    """Every element of ``text`` in document order, with spans, attributes and nesting."""
    tags: list[Tag] = []
    stack: list[int] = []
    i = 0
    while True:
        j = text.find("<", i)
        if j < 0:
            break
        if text.startswith("<!--", j):
            i = _skip(text, "-->", j + 4)
        elif text.startswith("<![CDATA[", j):
            i = _skip(text, "]]>", j + 9)
        elif text.startswith("<?", j):
            i = _skip(text, "?>", j + 2)
        elif text.startswith("<!", j):
            i = _end_of(layout_doctype_end, text, j)
        elif text.startswith("</", j):
            k = _end_of(layout_tag_end, text, j)
            if stack:
                t = tags[stack.pop()]
                t.close_start, t.close_end = j, k
            i = k
        else:
            k = _end_of(layout_tag_end, text, j)
            m = _NAME_RE.match(text, j + 1)
            name = m.group(0) if m else ""
            empty = text[k - 2] == "/"
            attrs: list[Attr] = []
            pos = m.end() if m else j + 1
            stop = k - 2 if empty else k - 1
            while True:
                a = _ATTR_RE.match(text, pos, stop)
                if a is None:
                    break
                g = 3 if a.group(3) is not None else 4
                attrs.append(Attr(a.group(1), a.group(g), a.start(1), a.start(g), a.end(g)))
                pos = a.end()
            parent = stack[-1] if stack else None
            tag = Tag(len(tags), name, j, k, empty, parent, tuple(attrs))
            tags.append(tag)
            if parent is not None:
                tags[parent].children.append(tag.index)
            if not empty:
                stack.append(tag.index)
            i = k
    return tags


class SourceFile:
    """One file's bytes, decoded, with its elements as written and edit helpers.

    Offsets are character offsets into ``text``; every :class:`Edit` it makes is in
    bytes of the original file (BOM and encoding kept).
    """

    def __init__(self, path: str, data: bytes, display: str | None = None) -> None:
        self.path = path
        self.data = data
        self.display = display or path
        try:
            self.encoding, self.bom = detect_encoding(data, self.display)
            self.text = data[len(self.bom) :].decode(self.encoding)
        except (SensorkitError, UnicodeDecodeError) as exc:
            raise NotFixable(f"{self.display}: cannot be edited ({exc})") from None
        if self.text.encode(self.encoding) != data[len(self.bom) :]:
            raise NotFixable(f"{self.display}: its bytes do not round-trip in {self.encoding}")

    # ---- structure ----------------------------------------------------------------------
    @cached_property
    def tags(self) -> list[Tag]:
        return scan(self.text)

    @cached_property
    def _breaks_any(self) -> list[int]:
        return [m.end() for m in _ANY_BREAK.finditer(self.text)]

    @cached_property
    def _breaks_lf(self) -> list[int]:
        return [m.end() for m in re.finditer("\n", self.text)]

    def line_expat(self, at: int) -> int:
        """1-based line of offset ``at`` as expat counts (CR, LF and CRLF)."""
        return bisect.bisect_right(self._breaks_any, at) + 1

    def line_lxml(self, at: int) -> int:
        """1-based line of offset ``at`` as libxml2 counts (LF only)."""
        return bisect.bisect_right(self._breaks_lf, at) + 1

    def _by_line(self, line_of: Callable[[Tag], int]) -> dict[int, list[Tag]]:
        out: dict[int, list[Tag]] = {}
        for t in self.tags:
            out.setdefault(line_of(t), []).append(t)
        return out

    @cached_property
    def _by_expat_line(self) -> dict[int, list[Tag]]:
        return self._by_line(lambda t: self.line_expat(t.start))

    @cached_property
    def _by_lxml_line(self) -> dict[int, list[Tag]]:
        return self._by_line(lambda t: self.line_lxml(t.head_end - 1))

    def tags_at(self, line: int, *, expat: bool) -> list[Tag]:
        """Start tags the loader would record at ``line``."""
        table = self._by_expat_line if expat else self._by_lxml_line
        return list(table.get(line, []))

    def children(self, tag: Tag, local: str | None = None) -> list[Tag]:
        kids = [self.tags[i] for i in tag.children]
        return [k for k in kids if local is None or k.local == local]

    def child(self, tag: Tag, local: str) -> Tag | None:
        kids = self.children(tag, local)
        return kids[0] if kids else None

    def ancestors(self, tag: Tag) -> list[Tag]:
        out: list[Tag] = []
        cur = tag.parent
        while cur is not None:
            out.append(self.tags[cur])
            cur = self.tags[cur].parent
        return out

    def raw_text(self, tag: Tag) -> str | None:
        """The content of an element holding only text (as written), else None."""
        if tag.empty:
            return ""
        if tag.close_start is None:
            return None
        content = self.text[tag.head_end : tag.close_start]
        return None if "<" in content else content

    # ---- layout -------------------------------------------------------------------------
    @cached_property
    def _layout(self) -> Layout | None:
        """How ``edit.layout`` reads the file (None: it cannot; defaults apply)."""
        try:
            return read_layout(self.data, self.display)
        except SensorkitError:
            return None

    @property
    def newline(self) -> str:
        return self._layout.newline if self._layout is not None else "\n"

    @property
    def unit(self) -> str:
        """One level of indentation as the file writes it."""
        return self._layout.unit if self._layout is not None else "  "

    def indent_of(self, at: int) -> str | None:
        """The spaces/tabs before ``at`` when only they precede it on its line, else None."""
        i = self._line_start(at)
        if i == 0 or self.text[i - 1] in "\r\n":
            return self.text[i:at]
        return None

    def _line_start(self, at: int) -> int:
        i = at
        while i > 0 and self.text[i - 1] in " \t":
            i -= 1
        return i

    def _after_line(self, at: int) -> int | None:
        """Just past the line break after ``at`` if only spaces/tabs lie between, else None."""
        i, n = at, len(self.text)
        while i < n and self.text[i] in " \t":
            i += 1
        if i == n:
            return i
        if self.text.startswith("\r\n", i):
            return i + 2
        if self.text[i] in "\r\n":
            return i + 1
        return None

    # ---- edits --------------------------------------------------------------------------
    @cached_property
    def _one_byte(self) -> bool:
        """Every character is one byte (ASCII text in an ASCII-compatible encoding)."""
        return self.text.isascii() and len("a".encode(self.encoding)) == 1

    def byte(self, at: int) -> int:
        """The offset in the original bytes of character ``at`` of ``text``."""
        if self._one_byte:
            return len(self.bom) + at
        return len(self.bom) + len(self.text[:at].encode(self.encoding))

    def edit(self, start: int, end: int, text: str) -> Edit:
        return Edit(
            self.path,
            self.byte(start),
            self.byte(end),
            text.encode(self.encoding, errors="xmlcharrefreplace"),
        )

    def set_attr(self, attr: Attr, raw: str) -> Edit:
        return self.edit(attr.value_start, attr.value_end, raw)

    def set_text(self, tag: Tag, text: str) -> Edit:
        """Replace an element's text, keeping the whitespace around it."""
        content = self.raw_text(tag)
        if content is None or tag.empty or tag.close_start is None:
            raise NotFixable(f"<{tag.name}> holds more than text")
        lead = len(content) - len(content.lstrip())
        trail = len(content) - len(content.rstrip())
        start = tag.head_end + lead
        end = tag.close_start - trail if content.strip() else tag.head_end + lead
        return self.edit(start, max(start, end), text)

    def rename(self, tag: Tag, name: str) -> list[Edit]:
        """Change an element's tag name in its start and end tags."""
        out = [self.edit(tag.start + 1, tag.start + 1 + len(tag.name), name)]
        if not tag.empty and tag.close_start is not None:
            out.append(self.edit(tag.close_start + 2, tag.close_start + 2 + len(tag.name), name))
        return out

    def span(self, tag: Tag) -> tuple[int, int]:
        """What removing ``tag`` takes: the element, with its whole line when it stands
        alone on it."""
        start, end = tag.start, tag.end
        if self.indent_of(start) is not None:
            after = self._after_line(end)
            if after is not None:
                return self._line_start(start), after
        return start, end

    def remove(self, tag: Tag) -> Edit:
        """Delete an element, with its whole line when it stands alone on it."""
        return self.edit(*self.span(tag), "")

    def render(self, lines: list[tuple[int, str]], indent: str) -> list[str]:
        return [indent + self.unit * depth + text for depth, text in lines]

    def replace(self, tag: Tag, lines: list[tuple[int, str]]) -> Edit:
        """Replace an element by ``lines`` (depth, text) at its own indentation."""
        indent = self.indent_of(tag.start)
        if indent is None:
            return self.edit(tag.start, tag.end, _inline(lines))
        body = self.render(lines, indent)
        return self.edit(tag.start, tag.end, self.newline.join(body)[len(indent) :])

    def insert_after(self, tag: Tag, lines: list[tuple[int, str]]) -> Edit:
        """New siblings right after ``tag``, at its indentation."""
        indent = self.indent_of(tag.start)
        if indent is None:
            return self.edit(tag.end, tag.end, _inline(lines))
        after = self._after_line(tag.end)
        body = self.render(lines, indent)
        if after is not None and after > tag.end:
            return self.edit(after, after, "".join(b + self.newline for b in body))
        return self.edit(tag.end, tag.end, "".join(self.newline + b for b in body))

    def insert_before(self, tag: Tag, lines: list[tuple[int, str]]) -> Edit:
        """New siblings right before ``tag``, at its indentation."""
        indent = self.indent_of(tag.start)
        if indent is None:
            return self.edit(tag.start, tag.start, _inline(lines))
        at = self._line_start(tag.start)
        return self.edit(at, at, "".join(b + self.newline for b in self.render(lines, indent)))

    def insert_child(self, tag: Tag, lines: list[tuple[int, str]]) -> Edit:
        """New children at the end of ``tag``, in the indentation of its other children."""
        indent = self.indent_of(tag.start)
        kids = self.children(tag)
        child_indent = None
        for k in kids:
            child_indent = self.indent_of(k.start)
            if child_indent is not None:
                break
        if child_indent is None and indent is not None and (not kids or tag.empty):
            child_indent = indent + self.unit
        if child_indent is None:
            inline = _inline(lines)
            if tag.empty:
                return self._open_empty(tag, ">" + inline + f"</{tag.name}>")
            assert tag.close_start is not None
            return self.edit(tag.close_start, tag.close_start, inline)
        body = self.render(lines, child_indent)
        if tag.empty:
            close = self.newline + (indent or "") + f"</{tag.name}>"
            return self._open_empty(tag, ">" + "".join(self.newline + b for b in body) + close)
        assert tag.close_start is not None
        if self.indent_of(tag.close_start) is not None:
            at = self._line_start(tag.close_start)
            return self.edit(at, at, "".join(b + self.newline for b in body))
        tail = self.newline + (indent or "")
        return self.edit(
            tag.close_start, tag.close_start, "".join(self.newline + b for b in body) + tail
        )

    def _open_empty(self, tag: Tag, text: str) -> Edit:
        """Turn ``<x .../>`` into ``<x ...>`` + ``text`` (which closes it)."""
        slash = self.text.rfind("/", tag.start, tag.head_end)
        return self.edit(slash, tag.head_end, text)


def _inline(lines: list[tuple[int, str]]) -> str:
    """``lines`` (depth, text) written on one line, where the element is not on its own."""
    return "".join(t for _, t in lines)


def apply_edits(data: bytes, edits: list[Edit]) -> bytes:
    """``data`` with ``edits`` applied (checked by :func:`conflicts` beforehand)."""
    out = data
    # Back to front; insertions at one point land in the order given.
    order = sorted(enumerate(edits), key=lambda ie: (ie[1].start, ie[1].end, ie[0]), reverse=True)
    for _, e in order:
        out = out[: e.start] + e.replacement + out[e.end :]
    return out


def overlaps(a: Edit, b: Edit) -> bool:
    """Two edits of one file touch the same bytes (insertions at one point do not)."""
    if a.file != b.file:
        return False
    if a.start == a.end and b.start == b.end:
        return False
    if a.start == a.end:
        return b.start < a.start < b.end
    if b.start == b.end:
        return a.start < b.start < a.end
    return a.start < b.end and b.start < a.end
