"""Inline suppressions: ``<!-- sensorkit: ignore SK502 SK506 -->``.

A comment suppresses the listed rules (or all, with ``ignore`` alone) for findings on the
comment's own line and on the line right after it (put it just above the element the
finding points at). ``<!-- sensorkit: ignore-file SK104 -->`` anywhere in a file
suppresses those rules for every finding in that file.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from sensorkit.base.findings import Finding

# Compiled on first use (by re's cache): only files that mention sensorkit are searched.
_COMMENT = r"<!--(.*?)-->"
_DIRECTIVE = r"sensorkit\s*:\s*(ignore-file|ignore)\b([^>]*)"
_ID = r"SK\d{3}"
ALL = "*"


@dataclass
class Suppressions:
    """The rules suppressed by line and by file."""

    by_line: dict[tuple[str, int], set[str]] = field(default_factory=dict)
    by_file: dict[str, set[str]] = field(default_factory=dict)

    def add_text(self, file: str, text: str) -> None:
        pos, pos_line = 0, 1  # count lines from the previous comment on: linear in the file
        for m in re.finditer(_COMMENT, text, re.S):
            d = re.search(_DIRECTIVE, m.group(1), re.I)
            if not d:
                continue
            ids = set(re.findall(_ID, d.group(2))) or {ALL}
            if d.group(1).lower() == "ignore-file":
                self.by_file.setdefault(file, set()).update(ids)
                continue
            start = pos_line + text.count("\n", pos, m.start())
            end = start + text.count("\n", m.start(), m.end())
            pos, pos_line = m.end(), end
            for line in (start, end, end + 1):
                self.by_line.setdefault((file, line), set()).update(ids)

    def suppressed(self, f: Finding) -> bool:
        if f.file is None:
            return False
        ids = self.by_file.get(f.file, set())
        if ALL in ids or f.rule in ids:
            return True
        if f.line is None:
            return False
        ids = self.by_line.get((f.file, f.line), set())
        return ALL in ids or f.rule in ids


def collect(
    files: Iterable[tuple[str, Path]], overlay: Mapping[str, bytes] | None = None
) -> Suppressions:
    """Read suppression comments from (display name, path) pairs; ``overlay`` maps
    absolute paths to the text to read instead (a robot read from stdin)."""
    sup = Suppressions()
    for display, path in files:
        data = overlay.get(os.path.abspath(path)) if overlay else None
        try:
            # "sensorkit" is ASCII: in the text exactly when in the bytes, which are
            # searched before anything is decoded (most files hold no directive)
            if b"sensorkit" not in (data if data is not None else path.read_bytes()):
                continue
            text = (
                data.decode("utf-8", "replace")
                if data is not None
                else path.read_text("utf-8", "replace")
            )
        except OSError:
            continue
        sup.add_text(display, text)
    return sup
