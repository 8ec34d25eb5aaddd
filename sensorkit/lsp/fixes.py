"""Quick fixes: what ``validate --fix`` would write, computed in memory, never written.

:func:`plan` runs :func:`sensorkit.fix.apply.plan_file` on the editor's buffers (its
``originals``: the unsaved text, not the disk) with the same fixers, safe fixes only,
for one finding or for all of a robot; the result is each changed file's text before and
after, which the server sends as a WorkspaceEdit for the client to apply.
"""

from __future__ import annotations

import hashlib
import os
from collections import OrderedDict
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

from sensorkit.base.findings import Finding
from sensorkit.fix import fixable
from sensorkit.fix.apply import Files, context_of, plan_file
from sensorkit.fix.registry import FIXERS, FixContext, subject
from sensorkit.lint.engine import Options
from sensorkit.lsp.analysis import Analysis, heap_frozen

__all__ = ["QuickFix", "has_safe_fix", "offer", "plan"]


@dataclass(frozen=True)
class QuickFix:
    """A fix as the client applies it: per changed file (absolute), its text before and after."""

    title: str
    changes: dict[str, tuple[str, str]]
    fixed: int  # findings gone


def has_safe_fix(rule: str) -> bool:
    """The rule has a fixer that ``validate --fix`` applies without ``--unsafe-fixes``."""
    return "safe" in fixable(rule).split("/")


_CACHE: OrderedDict[tuple[object, ...], QuickFix | None] = OrderedDict()
_CACHE_SIZE = 64


def _key(
    top: Path, overlay: Mapping[str, bytes], finding: Finding | None, sources: Iterable[str]
) -> tuple[object, ...]:
    """What a plan depends on: the buffers' bytes, and the size and time of each file read
    from the disk (one changed there, by another program, makes a new plan)."""
    digest = hashlib.blake2b(digest_size=16)
    for path in sorted(overlay):
        digest.update(path.encode("utf-8", "surrogateescape") + b"\0")
        digest.update(hashlib.blake2b(overlay[path], digest_size=16).digest())
    disk: list[tuple[str, int, int]] = []
    for path in sorted(set(sources) - set(overlay)):
        try:
            st = os.stat(path)
        except OSError:
            continue
        disk.append((path, st.st_mtime_ns, st.st_size))
    what = None if finding is None else (subject(finding), finding.file, finding.line)
    return (str(top), digest.digest(), tuple(disk), what)


def plan(
    top: Path,
    options: Options,
    overlay: Mapping[str, bytes],
    finding: Finding | None,
    sources: Iterable[str] = (),
) -> QuickFix | None:
    """The safe fix of ``finding`` (None: of every finding of ``top``), from the text of
    ``overlay`` where it holds a file; None when nothing would change. The same buffers,
    files on disk (``sources``: the files the robot reads) and finding give the same
    answer from a cache (editors ask again on every cursor move)."""
    key = _key(top, overlay, finding, sources)
    if key in _CACHE:
        _CACHE.move_to_end(key)
        return _CACHE[key]
    out = _plan(top, options, overlay, finding)
    _CACHE[key] = out
    while len(_CACHE) > _CACHE_SIZE:
        _CACHE.popitem(last=False)
    return out


def _plan(
    top: Path, options: Options, overlay: Mapping[str, bytes], finding: Finding | None
) -> QuickFix | None:
    only = None
    if finding is not None:
        want = (subject(finding), finding.file)

        def only(f: Finding) -> bool:
            return (subject(f), f.file) == want

    with heap_frozen():  # it loads the robot at least twice
        ff = plan_file(top, options, originals=overlay, only=only)
    changed = ff.changed()
    if ff.error or not ff.applied or not changed:
        return None
    changes: dict[str, tuple[str, str]] = {}
    for path, (old, new) in changed.items():
        try:  # an edit is text: a file that is not UTF-8 is left to ``validate --fix``
            changes[path] = (old.decode("utf-8"), new.decode("utf-8"))
        except UnicodeDecodeError:
            return None
    if finding is not None:
        title = f"sensorkit: {ff.applied[0].title} ({finding.rule})"
    else:
        n = ff.fixed
        title = f"sensorkit: apply every safe fix ({n} finding{'' if n == 1 else 's'})"
    return QuickFix(title, changes, ff.fixed)


def offer(analysis: Analysis, finding: Finding, overlay: Mapping[str, bytes]) -> str | None:
    """The title of the safe fix the fixer of ``finding`` gives on the text as it is, or
    None: the fixer alone, without validating the result (:func:`plan` does that when
    the fix is applied). Cheap enough to answer every cursor move."""
    info = FIXERS.get(finding.rule)
    report = analysis.report
    if info is None or report is None or report.robot is None:
        return None
    fx = analysis.memo.get("fix_context")
    if not isinstance(fx, FixContext):
        fx = FixContext(context_of(report, analysis.options), Files(dict(overlay), {}))
        analysis.memo["fix_context"] = fx
    try:
        fix = info.func(fx, finding)
    except Exception:  # NotFixable, Deferred, a file that cannot be read: no offer
        return None
    return f"sensorkit: {fix.title} ({finding.rule})" if fix.safe and fix.edits else None
