"""How a failed xacro expansion is told: its error classified into an ``ExpandOutcome``
(``out``: xml, package, timeout, memory or xacro), the message tidied, and the file and
macro stack it failed in (split from ``xacro_expand``, which fills the outcome)."""

from __future__ import annotations

import os
import re
from typing import Any

from sensorkit.loading.marks import LOC_ATTR


class PackageMissing(Exception):
    """``$(find pkg)`` named a package the resolver could not find."""

    def __init__(self, name: str, searched: list[str]) -> None:
        super().__init__(f"package {name!r} not found")
        self.name = name
        self.searched = searched


def classify(exc: BaseException, out: Any) -> None:
    import xml.parsers.expat

    chain: list[BaseException] = []
    cur: BaseException | None = exc
    while cur is not None and cur not in chain:
        chain.append(cur)
        cur = getattr(cur, "exc", None) or cur.__cause__ or cur.__context__
    for item in chain:
        if isinstance(item, PackageMissing):
            out.error_kind = "package"
            out.package = item.name
            out.searched = item.searched
            out.message = f"$(find {item.name}): package {item.name!r} not found"
            return
    for item in chain:
        if isinstance(item, xml.parsers.expat.ExpatError):
            out.error_kind = "xml"
            out.message = xml.parsers.expat.ErrorString(item.code)
            out.error_line = item.lineno
            out.error_column = item.offset + 1
            return
    if any(isinstance(i, RecursionError) for i in chain):
        out.error_kind = "xacro"
        out.message = "xacro recursed too deep: a macro that calls itself without end?"
        return
    if any(isinstance(i, MemoryError) for i in chain):
        out.error_kind = "memory"
        out.message = "xacro ran out of memory evaluating an expression"
        return
    text = _tidy(str(exc) or repr(exc))
    if os.environ.get("SENSORKIT_DEBUG"):
        import traceback

        text += "\n" + "".join(traceback.format_exception(exc))
    out.error_kind = "xacro"
    out.message = text.strip()


_CLASS_PREFIX = re.compile(r"^<class '[\w.]+'>: ")


def _tidy(text: str) -> str:
    """xacro's wrapped message without the exception class and the repeated text.

    ``XacroException(exc=e)`` prints as ``<class 'X'>: MESSAGE MESSAGE``.
    """
    text = _CLASS_PREFIX.sub("", text.strip())
    head, _, rest = text.partition("\n")
    half = (len(head) - 1) // 2
    if len(head) % 2 == 1 and head[half] == " " and head[:half] == head[half + 1 :]:
        head = head[:half]
    return head + ("\n" + rest if rest else "")


def innermost_macro(macros: list[Any], files: list[str]) -> tuple[str | None, int | None]:
    """File and line of the definition of the macro whose body failed (the innermost)."""
    for m in reversed(macros):
        try:
            loc = m.body.getAttribute(LOC_ATTR)
        except Exception:
            continue
        idx, _, line = (loc or "").partition(":")
        if idx.isdigit() and int(idx) < len(files) and line.isdigit():
            return os.path.abspath(files[int(idx)]), int(line)
    return None, None


def describe_stack(stack_files: list[str], macros: list[Any], files: list[str]) -> list[str]:
    lines: list[str] = []
    for m in reversed(macros):
        try:
            name = m.body.getAttribute("name")
            loc = m.body.getAttribute(LOC_ATTR)
        except Exception:
            continue
        where = ""
        if loc:
            idx, _, line = loc.partition(":")
            if idx.isdigit() and int(idx) < len(files):
                where = f" ({files[int(idx)]}:{line})"
        lines.append(f"in macro {name}{where}")
    for f in reversed(stack_files):
        lines.append(f"in file {f}")
    return lines


def where_failed(out: Any, stack_files: list[str], macros: list[Any], files: list[str]) -> None:
    """The file, include stack and macro a failed expansion was in."""
    if out.error_file is None and stack_files:
        out.error_file = os.path.abspath(stack_files[-1])
    out.stack = describe_stack(stack_files, macros, files)
    out.macro_file, out.macro_line = innermost_macro(macros, files)
