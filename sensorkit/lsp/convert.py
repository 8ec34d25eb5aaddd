"""Findings as LSP diagnostics, and byte diffs as text edits.

Positions are computed on ``str`` indices (code points) and turned into the client's
units (UTF-16 unless the client chose otherwise) by the ``units`` function the server
passes: ``units(line_text, index) -> character``.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence

from lsprotocol import types as lsp

from sensorkit.base.findings import Finding, Severity

__all__ = ["SEVERITY", "diagnostic", "element_span", "text_edit", "to_text"]

Units = Callable[[str, int], int]

SEVERITY = {
    Severity.ERROR: lsp.DiagnosticSeverity.Error,
    Severity.WARNING: lsp.DiagnosticSeverity.Warning,
    Severity.INFO: lsp.DiagnosticSeverity.Information,
}
SOURCE = "sensorkit"

_START_TAG = re.compile(r"<(?![/!?])[^\s/>]+")


def to_text(data: bytes) -> str:
    """A file's bytes as the editor shows them (UTF-8; a stray byte as U+FFFD)."""
    return data.decode("utf-8", errors="replace")


def element_span(line: str, column: int | None = None) -> tuple[int, int]:
    """Where on ``line`` a finding points: the start tag of an element (the first one at
    or after ``column``, 1-based, when given) up to its ``>`` on that line, else the
    line's non-blank text. A line that is all blank: ``(0, 0)``."""
    from_ = max(column - 1, 0) if column else 0
    m = _START_TAG.search(line, from_) or _START_TAG.search(line)
    if m is not None:
        end = _tag_end(line, m.start())
        return m.start(), end
    stripped = line.strip()
    if not stripped:
        return 0, 0
    start = len(line) - len(line.lstrip())
    return start, start + len(stripped)


def _tag_end(line: str, start: int) -> int:
    """The index after the ``>`` closing the tag at ``start`` (quotes skipped), or the
    end of the line's text when the tag goes on."""
    quote = ""
    for i in range(start + 1, len(line)):
        c = line[i]
        if quote:
            if c == quote:
                quote = ""
        elif c in "\"'":
            quote = c
        elif c == ">":
            return i + 1
    return len(line.rstrip())


def diagnostic(f: Finding, lines: Sequence[str], units: Units) -> lsp.Diagnostic:
    """The diagnostic of ``f`` in a file of ``lines`` (without their line ends)."""
    row = max((f.line or 1) - 1, 0)
    if row >= len(lines):  # the file is shorter now than when it was read
        row = max(len(lines) - 1, 0)
    text = lines[row] if lines else ""
    start, end = element_span(text, f.column)
    message = " ".join(f.message.split())
    if f.fix:
        message += f"\nfix: {f.fix}"
    return lsp.Diagnostic(
        range=lsp.Range(
            start=lsp.Position(line=row, character=units(text, start)),
            end=lsp.Position(line=row, character=units(text, end)),
        ),
        message=message,
        severity=SEVERITY[f.severity],
        code=f.rule or None,
        source=SOURCE,
    )


def _position(text: str, index: int, units: Units) -> lsp.Position:
    line = text.count("\n", 0, index)
    start = text.rfind("\n", 0, index) + 1
    end = text.find("\n", start)
    row = text[start : len(text) if end < 0 else end]
    return lsp.Position(line=line, character=units(row, index - start))


def text_edit(old: str, new: str, units: Units) -> lsp.TextEdit | None:
    """The one edit turning ``old`` into ``new``: the span between their common prefix
    and suffix (None when they are the same)."""
    if old == new:
        return None
    n = min(len(old), len(new))
    head = 0
    while head < n and old[head] == new[head]:
        head += 1
    tail = 0
    while tail < n - head and old[-1 - tail] == new[-1 - tail]:
        tail += 1
    # keep a CRLF pair whole
    while head > 0 and old[head - 1] == "\r":
        head -= 1
    return lsp.TextEdit(
        range=lsp.Range(
            start=_position(old, head, units), end=_position(old, len(old) - tail, units)
        ),
        new_text=new[head : len(new) - tail],
    )
