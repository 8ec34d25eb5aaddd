"""Apply fixes: compute, check, and publish them, in rounds.

A round validates the current text (in memory: edited files are handed to the loader and
to xacro instead of their disk bytes), asks each fixer for its fix, keeps the fixes that
do not collide (overlapping bytes, or a ``claim`` on one element), and applies them
together. The result is validated again: when it holds an error the text before did not
(compared by rule and what the finding is about, see :func:`~sensorkit.fix.registry.
subject`), the fixes are split in halves until the culprit is found and left out. The
next round starts from the new text, so a fix that needed another one first (a
``<ros>`` block made by one, filled by the next) lands then. Rounds end when one
applies nothing. Only then is anything written: atomically, under the folder lock that
``add-*`` takes, and only files of the package being validated.
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
from collections import Counter
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from sensorkit.base.atomic import check_editable, editing, write_bytes
from sensorkit.base.errors import EditRefused, InputError
from sensorkit.base.findings import Finding, Severity
from sensorkit.fix.registry import FIXERS, Deferred, Fix, FixContext, NotFixable, subject
from sensorkit.fix.source import Edit, apply_edits, overlaps
from sensorkit.lint.engine import FileReport, Options, validate_file
from sensorkit.lint.rules.base import Context
from sensorkit.loading.document import display_path
from sensorkit.loading.packages import own_package, package_name, workspace_roots
from sensorkit.model.frames import sensor_frames
from sensorkit.model.sdf import convert

MAX_ROUNDS = 12


# ----------------------------------------------------------------------------- validating


def check(path: Path, options: Options, overlay: Mapping[str, bytes]) -> FileReport:
    """``validate_file`` on the text in ``overlay`` where it holds a file, else the disk."""
    merged = {**options.overlay, **overlay}
    return validate_file(path, dataclasses.replace(options, overlay=merged))


def context_of(report: FileReport, options: Options) -> Context:
    """The rules' context of a checked robot (what fixers read besides the text)."""
    robot = report.robot
    assert robot is not None and report.target is not None
    conv = convert(robot)
    ctx = Context(robot=robot, target=report.target, conversion=conv, auto=options.target == "auto")
    for s in robot.sensors:
        ctx.frames[id(s)] = sensor_frames(robot, s, report.target, conv)
    return ctx


# ----------------------------------------------------------------------------- scope


def edit_scope(top: Path) -> Callable[[str], str | None]:
    """Why a file may not be edited when fixing ``top`` (None: it may).

    Files of the package ``top`` belongs to may be edited (an included xacro too); files
    of any other package may not, even when ``top`` includes them: they are someone else's.
    ``top`` in no package: files in no package under its workspace (its folder, or the
    ``src`` around it).
    """
    top_pkg = own_package(top)
    roots = [] if top_pkg is not None else [r.resolve() for r in workspace_roots(top)]

    def why_not(file: str) -> str | None:
        p = Path(file).resolve()
        pkg = own_package(p)
        if top_pkg is not None and pkg == top_pkg:
            return None
        if top_pkg is None and pkg is None and any(p.is_relative_to(r) for r in roots):
            return None
        if pkg is not None:
            other = package_name(pkg / "package.xml") or pkg.name
            mine = package_name(top_pkg / "package.xml") if top_pkg is not None else None
            but = f", not to {mine!r}" if mine else ""
            return (
                f"{display_path(file)} belongs to package {other!r}{but}: sensorkit edits only "
                "the package being validated (fix it there, or validate that package)"
            )
        return (
            f"{display_path(file)} is outside the workspace of {display_path(top)}: left as it is"
        )

    return why_not


# ----------------------------------------------------------------------------- outcome


@dataclass
class Note:
    """Why a finding of a fixable rule was not fixed: ``kind`` is unfixable, deferred,
    unsafe (needs --unsafe-fixes) or rejected (it would add an error)."""

    finding: Finding
    kind: str
    text: str


@dataclass
class FileFix:
    """Fixing one top-level file: what was applied, what was not and why, and the text."""

    path: Path
    originals: dict[str, bytes] = field(default_factory=dict)  # as read, per absolute path
    contents: dict[str, bytes] = field(default_factory=dict)  # as fixed (edited files only)
    before: list[Finding] = field(default_factory=list)
    after: list[Finding] = field(default_factory=list)
    applied: list[Fix] = field(default_factory=list)
    notes: list[Note] = field(default_factory=list)
    revealed: list[Finding] = field(default_factory=list)
    error: str | None = None
    internal_errors: list[str] = field(default_factory=list)
    more: bool = False  # stopped after MAX_ROUNDS with fixes left

    def changed(self) -> dict[str, tuple[bytes, bytes]]:
        return {
            f: (self.originals[f], data)
            for f, data in self.contents.items()
            if f in self.originals and data != self.originals[f]
        }

    @property
    def fixed(self) -> int:
        """Findings before that are gone after (by what they are about)."""
        left = Counter(subject(f) for f in self.after)
        n = 0
        for f in self.before:
            k = subject(f)
            if left[k] > 0:
                left[k] -= 1
            else:
                n += 1
        return n


class Files(Mapping[str, bytes]):
    """The current bytes of every file: edited text first, else the disk (read once).

    The language server gives its fixers the open buffers through it too."""

    def __init__(self, contents: dict[str, bytes], originals: dict[str, bytes]) -> None:
        self.contents = contents
        self.originals = originals

    def __getitem__(self, path: str) -> bytes:
        if path not in self.originals:  # what the disk holds: the diff's left side
            try:
                self.originals[path] = Path(path).read_bytes()
            except OSError as exc:
                if path not in self.contents:
                    raise KeyError(path) from exc
        if path in self.contents:
            return self.contents[path]
        return self.originals[path]

    def __iter__(self) -> Iterator[str]:
        return iter({**self.originals, **self.contents})

    def __len__(self) -> int:
        return len({**self.originals, **self.contents})

    def __contains__(self, path: object) -> bool:
        if not isinstance(path, str):
            return False
        try:
            self[path]
        except KeyError:
            return False
        return True


@dataclass
class _Unit:
    """Fixes that make the same edits (one element shared by several findings)."""

    edits: tuple[Edit, ...]
    fixes: list[Fix]


# ----------------------------------------------------------------------------- planning


def plan_file(
    path: Path,
    options: Options,
    *,
    unsafe: bool = False,
    contents: dict[str, bytes] | None = None,
    allowed: set[str] | None = None,
    originals: Mapping[str, bytes] | None = None,
    only: Callable[[Finding], bool] | None = None,
) -> FileFix:
    """Work out every fix for ``path`` in memory (see the module doc); write nothing.

    ``contents`` (edited text by absolute path) is read and updated in place, so several
    files fixed in one run see each other's edits. ``allowed`` limits the files that may
    be edited (those whose folder lock is held). ``originals`` (absolute path -> bytes)
    is the text to start from instead of the disk's (an editor's unsaved buffers): the
    diff's left side. ``only`` picks the findings to fix (default: every wanted one).
    """
    contents = {} if contents is None else contents
    out = FileFix(path=path, originals=dict(originals or {}))
    files = Files(contents, out.originals)
    everything = dataclasses.replace(options, select=(), ignore=())
    report = check(path, everything, files)
    out.before = _wanted(report, options, only)
    out.after = list(out.before)
    if report.error or report.robot is None:
        out.error = report.error
        return out
    scope = edit_scope(path)
    notes: list[Note] = []
    refused: dict[tuple[object, ...], Note] = {}  # fixes that added an error: not tried again
    for _ in range(MAX_ROUNDS):
        candidates, notes = _candidates(report, options, files, unsafe, scope, allowed, only)
        notes += [_again(refused[c.signature()], c) for c in candidates if c.signature() in refused]
        candidates = [c for c in candidates if c.signature() not in refused]
        units, _waiting = _choose(candidates)
        if not units:
            break
        base = dict(contents)
        accepted, report, rejected = _verify(units, report, path, everything, files, base, out)
        for n, fix in rejected:
            refused[fix.signature()] = n
            notes.append(n)
        for u in accepted:
            out.applied.extend(u.fixes)
    else:
        candidates, notes = _candidates(report, options, files, unsafe, scope, allowed, only)
        out.more = any(c.signature() not in refused for c in candidates)
    out.notes = _final_notes(notes, report, options)
    out.after = _wanted(report, options, only)
    left = {(f.rule, f.sensor, f.message) for f in out.after}
    out.revealed = [f for f in out.revealed if (f.rule, f.sensor, f.message) in left]
    out.internal_errors = list(report.internal_errors)
    out.contents = {f: d for f, d in contents.items() if d != out.originals.get(f)}
    return out


def _again(note: Note, fix: Fix) -> Note:
    """The refusal of an earlier round, said of the finding as it is now."""
    return Note(fix.finding, note.kind, note.text)


def _wanted(
    report: FileReport, options: Options, only: Callable[[Finding], bool] | None = None
) -> list[Finding]:
    return [
        f for f in report.findings if options.wants(f.rule) and (only is None or only(f))
    ]


def _candidates(
    report: FileReport,
    options: Options,
    files: Files,
    unsafe: bool,
    scope: Callable[[str], str | None],
    allowed: set[str] | None,
    only: Callable[[Finding], bool] | None = None,
) -> tuple[list[Fix], list[Note]]:
    fixes: list[Fix] = []
    notes: list[Note] = []
    if report.robot is not None and report.robot.sdf is not None:
        # The fixers edit URDF and xacro text (joint origins, gazebo blocks, macro calls):
        # none is written for SDF, so an SDF finding is never fixed or marked fixable.
        sdf = "--fix edits URDF and xacro files; change the SDF by hand"
        notes = [Note(f, "unfixable", sdf) for f in _wanted(report, options, only) if f.rule in FIXERS]
        return fixes, notes
    fx = FixContext(context_of(report, options), files)
    for f in _wanted(report, options, only):
        info = FIXERS.get(f.rule)
        if info is None:
            continue
        try:
            fix = info.func(fx, f)
        except Deferred as exc:
            notes.append(Note(f, "deferred", str(exc)))
            continue
        except NotFixable as exc:
            notes.append(Note(f, "unfixable", str(exc)))
            continue
        except (EditRefused, InputError, KeyError) as exc:
            notes.append(Note(f, "unfixable", str(exc)))
            continue
        except Exception as exc:  # a bug of ours must not stop the other fixes
            if os.environ.get("SENSORKIT_DEBUG"):
                raise
            notes.append(Note(f, "unfixable", f"internal error in the {f.rule} fixer: {exc!r}"))
            continue
        why = next((w for e in fix.edits if (w := scope(e.file))), None)
        if why is None and allowed is not None:
            why = next(
                (
                    f"{display_path(e.file)} was not locked for writing"
                    for e in fix.edits
                    if e.file not in allowed
                ),
                None,
            )
        edits = fix.edits
        if why is None and any(overlaps(a, b) for i, a in enumerate(edits) for b in edits[i + 1 :]):
            why = f"internal error in the {f.rule} fixer: its edits overlap"
        if why is not None:
            notes.append(Note(f, "unfixable", why))
        elif not fix.edits:
            notes.append(Note(f, "unfixable", "nothing to change"))
        elif not fix.safe and not unsafe:
            notes.append(Note(f, "unsafe", fix.title))
        else:
            fixes.append(fix)
    return fixes, notes


def _choose(candidates: list[Fix]) -> tuple[list[_Unit], list[Fix]]:
    """Fixes that can land together; the others wait for the next round."""
    units: list[_Unit] = []
    claims: set[str] = set()
    waiting: list[Fix] = []
    for fix in candidates:
        same = next((u for u in units if u.edits == fix.edits), None)
        if same is not None:
            same.fixes.append(fix)
            continue
        taken = {x for u in units for x in u.edits}
        clash = any(overlaps(e, x) and e != x for e in fix.edits for x in taken)
        if clash or fix.claims & claims:
            waiting.append(fix)
            continue
        units.append(_Unit(fix.edits, [fix]))
        claims |= fix.claims
    return units, waiting


def _apply(files: Files, base: dict[str, bytes], units: Sequence[_Unit]) -> dict[str, bytes]:
    """``base`` (the round's starting text) with the edits of ``units``."""
    by_file: dict[str, list[Edit]] = {}
    for u in units:
        for e in u.edits:
            group = by_file.setdefault(e.file, [])
            if e not in group:
                group.append(e)
    out = dict(base)
    for file, edits in by_file.items():
        start = base[file] if file in base else files.originals.get(file)
        if start is None:
            start = files[file]
        out[file] = apply_edits(start, edits)
    return out


def _verify(
    units: list[_Unit],
    report: FileReport,
    path: Path,
    everything: Options,
    files: Files,
    base: dict[str, bytes],
    out: FileFix,
) -> tuple[list[_Unit], FileReport, list[tuple[Note, Fix]]]:
    """Apply ``units``, leaving out those that add an error.

    A group that adds one is split: first the fixes about the sensors the new errors
    name are set apart, else it is halved, until each culprit stands alone.
    """
    accepted: list[_Unit] = []
    rejected: list[tuple[Note, Fix]] = []
    current = report
    queue: list[list[_Unit]] = [units]
    while queue:
        group = queue.pop(0)
        trial = _apply(files, base, accepted + group)
        overlay = {**files.originals, **trial}
        rep = check(path, everything, overlay)
        new, revealed = _new_errors(current, rep, group)
        if not new:
            accepted += group
            current = rep
            out.revealed += revealed
            files.contents.clear()
            files.contents.update(trial)
        elif len(group) == 1:
            why = new[0] if isinstance(new[0], str) else _describe(new[0])
            for fix in group[0].fixes:
                note = Note(fix.finding, "rejected", f"{fix.title} would add an error: {why}")
                rejected.append((note, fix))
        else:
            sensors = {f.sensor for f in new if isinstance(f, Finding) and f.sensor}
            suspects = [u for u in group if any(x.finding.sensor in sensors for x in u.fixes)]
            if 0 < len(suspects) < len(group):
                queue[:0] = [[u for u in group if u not in suspects], suspects]
            else:
                half = len(group) // 2
                queue[:0] = [group[:half], group[half:]]
    return accepted, current, rejected


def _describe(f: Finding) -> str:
    text = " ".join(f.message.split())
    return f"{f.rule} {text}"


def _new_errors(
    before: FileReport, after: FileReport, units: list[_Unit]
) -> tuple[list[Finding | str], list[Finding]]:
    """Errors ``after`` has that ``before`` lacks (by subject), and findings the fixes
    brought to light (their ``reveals``)."""
    if after.error:
        return [f"the result cannot be read: {after.error}"], []
    if after.internal_errors:
        return [f"the validator failed on the result: {after.internal_errors[0]}"], []
    budget = Counter(subject(f) for f in before.findings if f.severity >= Severity.ERROR)
    new: list[Finding | str] = []
    revealed: list[Finding] = []
    fixes = [fix for u in units for fix in u.fixes]
    for f in after.findings:
        if f.severity < Severity.ERROR:
            continue
        k = subject(f)
        if budget[k] > 0:
            budget[k] -= 1
        elif f.sensor and any(f.rule in x.reveals and x.finding.sensor == f.sensor for x in fixes):
            revealed.append(f)
        else:
            new.append(f)
    return new, revealed


def _final_notes(notes: list[Note], report: FileReport, options: Options) -> list[Note]:
    """One note per finding still there (the last round's say), in finding order."""
    left = Counter(subject(f) for f in _wanted(report, options))
    seen: set[tuple[object, ...]] = set()
    out: list[Note] = []
    order = {"rejected": 0, "unsafe": 1, "deferred": 2, "unfixable": 3}
    for n in sorted(notes, key=lambda n: (n.finding.sort_key(), order.get(n.kind, 9))):
        k = subject(n.finding)
        key = (k, n.finding.file, n.finding.line, n.finding.message)
        if left[k] <= 0 or key in seen:
            continue
        seen.add(key)
        out.append(n)
    return out


# ----------------------------------------------------------------------------- publishing


@dataclass
class FixRun:
    """Fixing several files: their outcomes, and every file's text before and after."""

    files: list[FileFix] = field(default_factory=list)

    @property
    def fixed(self) -> int:
        return sum(ff.fixed for ff in self.files)

    @property
    def remaining(self) -> int:
        return sum(len(ff.after) for ff in self.files)

    def changed(self) -> dict[str, tuple[bytes, bytes]]:
        out: dict[str, tuple[bytes, bytes]] = {}
        for ff in self.files:
            for f, (old, new) in ff.changed().items():
                out[f] = (out[f][0] if f in out else old, new)
        return out

    def diff(self) -> str:
        """A unified diff of every file that changes (``patch -p1`` applies it)."""
        from sensorkit.edit.diff import unified_diff
        from sensorkit.fix.source import SourceFile

        parts: list[str] = []
        for file, (old, new) in sorted(self.changed().items()):
            a, b = SourceFile(file, old), SourceFile(file, new)
            label = display_path(file)
            parts.append(unified_diff(a.text, b.text, f"a/{label}", f"b/{label}"))
        return "".join(parts)


def publish(ff: FileFix) -> None:
    """Write a planned fix: every edited file atomically, refused if one changed meanwhile.

    If a later file cannot be written, the ones already written get their old bytes back.
    """
    changed = ff.changed()
    for file in changed:
        check_editable(Path(file))
    for file, (old, _) in changed.items():
        try:
            now = Path(file).read_bytes()
        except OSError as exc:
            raise InputError(
                f"{display_path(file)}: cannot read it again ({exc.strerror})"
            ) from None
        if now != old:
            raise EditRefused(
                f"{display_path(file)} changed while sensorkit worked; nothing was written"
            )
    done: list[str] = []
    try:
        for file, (_, new) in changed.items():
            write_bytes(Path(file), new)
            done.append(file)
    except BaseException:
        for file in done:
            with contextlib.suppress(OSError):
                write_bytes(Path(file), changed[file][0])
        raise


def fix_paths(
    paths: Sequence[Path], options: Options, *, unsafe: bool = False, write: bool = True
) -> FixRun:
    """Fix every file of ``paths``; with ``write=False`` only plan (for ``--diff``).

    A file is planned without a lock; when the plan changes anything, the folder lock of
    :func:`sensorkit.base.atomic.editing` is taken for every file it writes, and held to the
    last rename. If one of them changed since it was read, the plan is made again under
    the lock (from what the other writer left), so no update is lost.
    """
    run = FixRun()
    shared: dict[str, bytes] = {}
    for path in paths:
        if not write:
            run.files.append(plan_file(path, options, unsafe=unsafe, contents=shared))
            continue
        if path.exists() and not path.is_dir():
            check_editable(path)
        ff = plan_file(path, options, unsafe=unsafe)
        changed = ff.changed()
        if changed:
            lock = sorted({os.path.abspath(path), *changed})
            with editing(*(Path(f) for f in lock)):
                if any(_read(f) != old for f, (old, _) in changed.items()):
                    ff = plan_file(path, options, unsafe=unsafe, allowed=set(lock))
                publish(ff)
        run.files.append(ff)
    return run


def _read(path: str) -> bytes | None:
    try:
        return Path(path).read_bytes()
    except OSError:
        return None


__all__ = [
    "FileFix",
    "Files",
    "FixRun",
    "Note",
    "check",
    "edit_scope",
    "fix_paths",
    "plan_file",
    "publish",
]
