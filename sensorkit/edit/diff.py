"""Unified diffs that ``patch`` and ``git apply`` accept, of text whose line ends are kept
as they are (``\\n``, ``\\r\\n``, a missing final newline)."""

from __future__ import annotations

import difflib
import re


def _diff_lines(text: str) -> list[str]:
    """Lines with their own terminators (\\n or \\r\\n kept), for difflib."""
    return re.findall(r"[^\n]*\n|[^\n]+\Z", text)


def unified_diff(old: str, new: str, old_label: str, new_label: str) -> str:
    """A unified diff that ``patch``/``git apply`` accept (marks a missing final newline)."""
    out: list[str] = []
    for line in difflib.unified_diff(_diff_lines(old), _diff_lines(new), old_label, new_label):
        if line.endswith("\n"):
            out.append(line)
        else:
            out.append(line + "\n\\ No newline at end of file\n")
    return "".join(out)
