"""The fixer registry, the fix a fixer returns, and what a fixer may read.

A fixer is a pure function ``(FixContext, Finding) -> Fix``: it reads the model (the
rules' :class:`~sensorkit.lint.rules.base.Context`) and the files' bytes as the context holds
them, never the disk, and returns byte edits, or raises :class:`NotFixable` saying why
not. Register it with ``@fixer(rule id, safety, summary)``; ``safety`` is what
``sensorkit rules`` shows: ``safe``, ``unsafe`` or ``safe/unsafe`` (each returned
:class:`Fix` says which it is).

Safe fixes do what the finding's fix says and nothing beyond; unsafe ones change
behaviour beyond the finding (a placeholder mass, a new frame, a rate the sensor did not
have) and run only with ``--unsafe-fixes``.
"""

from __future__ import annotations

import os
import re
from collections import Counter
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from sensorkit.base.findings import Finding
from sensorkit.fix.source import Deferred, Edit, NotFixable, SourceFile, Tag, escape
from sensorkit.loading.document import display_path
from sensorkit.loading.xacro_expand import LOC_ATTR
from sensorkit.model.parse import local

if TYPE_CHECKING:
    from lxml import etree

    from sensorkit.lint.rules.base import Context
    from sensorkit.model.robot import Robot

__all__ = [
    "FIXERS",
    "Deferred",
    "Fix",
    "FixContext",
    "FixerInfo",
    "NotFixable",
    "Written",
    "fixer",
    "is_expr",
    "subject",
]


@dataclass(frozen=True)
class Fix:
    """What fixing one finding takes: byte edits, and what they do.

    ``claims`` names what the fix creates once (a ``<ros>`` block, a frame parameter): two
    fixes with one claim never land together; the second is computed again afterwards.
    ``reveals`` lists rules whose findings on the same sensor this fix may bring to light
    without causing them (a ROS 1 plugin swapped for its ROS 2 form is checked only then).
    """

    finding: Finding
    edits: tuple[Edit, ...]
    title: str
    safe: bool = True
    claims: frozenset[str] = frozenset()
    reveals: frozenset[str] = frozenset()

    def signature(self) -> tuple[object, ...]:
        return (subject(self.finding), tuple(sorted((e.file, e.replacement) for e in self.edits)))


def subject(f: Finding) -> tuple[object, ...]:
    """What a finding is about, beyond its wording: a fix that only rewords it (the frame
    it names changes, the offset shrinks) leaves the same subject."""
    if f.sensor or f.joint or f.link:
        return (f.rule, int(f.severity), f.sensor, f.joint, f.link)
    return (f.rule, int(f.severity), f.message)


FixFunc = Callable[["FixContext", Finding], Fix]


@dataclass(frozen=True)
class FixerInfo:
    rule: str
    safety: str  # "safe", "unsafe" or "safe/unsafe"
    summary: str
    func: FixFunc


FIXERS: dict[str, FixerInfo] = {}


def fixer(rule: str, safety: str, summary: str) -> Callable[[FixFunc], FixFunc]:
    """Register the fixer of rule ``rule``."""

    def deco(func: FixFunc) -> FixFunc:
        if rule in FIXERS:
            msg = f"fixer for {rule} registered twice"
            raise RuntimeError(msg)
        FIXERS[rule] = FixerInfo(rule, safety, summary, func)
        return func

    return deco


@dataclass(frozen=True)
class Written:
    """An element of the model where it is written: a file and its start tag there."""

    file: SourceFile
    tag: Tag

    @property
    def where(self) -> str:
        return f"{self.file.display}:{self.file.line_expat(self.tag.start)}"

    def macro(self) -> int | None:
        """The ``xacro:macro`` whose body holds this element (its tag index), or None."""
        for a in self.file.ancestors(self.tag):
            if a.name == "xacro:macro" or (a.local == "macro" and a.name.startswith("xacro")):
                return a.index
        return None

    def encloses(self, other: Written) -> bool:
        """``other`` is written inside this element, in the same file."""
        if other.file.path != self.file.path:
            return False
        return self.tag.start < other.tag.start and other.tag.end <= self.tag.end


EXPR = re.compile(r"\$[{(]")  # a xacro expression or substitution begins


def is_expr(raw: str | None) -> bool:
    """Text as written holds a xacro expression (``${...}``) or substitution (``$(...)``)."""
    return raw is not None and bool(EXPR.search(raw))


@dataclass
class FixContext:
    """What a fixer reads: the rules' context and the bytes of every source file."""

    ctx: Context
    files: Mapping[str, bytes]  # absolute path -> current bytes (nothing else is read)
    _sources: dict[str, SourceFile] = field(default_factory=dict, repr=False)
    _stamps: Counter[tuple[str, str]] | None = field(default=None, repr=False)

    @property
    def robot(self) -> Robot:
        return self.ctx.robot

    @property
    def target(self) -> str:
        return self.ctx.target

    @property
    def xacro(self) -> bool:
        """The description is expanded by xacro (so ``${...}`` may be written)."""
        return self.robot.document.expanded

    def source(self, path: str) -> SourceFile:
        if path not in self._sources:
            if path not in self.files:
                raise NotFixable(f"{display_path(path)} was not read")
            self._sources[path] = SourceFile(path, self.files[path], display_path(path))
        return self._sources[path]

    def _copies(self, stamp: str, name: str) -> int:
        if self._stamps is None:
            self._stamps = Counter(
                (e.get(LOC_ATTR) or "", local(e))
                for e in self.robot.document.root.iter()
                if isinstance(e.tag, str)
            )
        return max(1, self._stamps[(stamp, name)])

    def copies(self, el: etree._Element) -> int:
        """How many elements of the expanded robot come from where ``el`` is written (a
        macro body used three times gives 3); 1 for plain URDF."""
        if not self.xacro:
            return 1
        return self._copies(el.get(LOC_ATTR) or "", local(el))

    def written(self, el: etree._Element) -> Written:
        """Where ``el`` is written: its start tag in the original text (see the module doc
        of :mod:`sensorkit.fix.source` for how lines are matched)."""
        doc = self.robot.document
        name = local(el)
        if doc.expanded:
            loc = el.get(LOC_ATTR) or ""
            idx, _, line_text = loc.partition(":")
            if not (idx.isdigit() and line_text.isdigit() and int(idx) < len(doc.files)):
                raise NotFixable(
                    f"<{name}> is made by xacro (xacro:element or a macro), not written as such"
                )
            path, line, expat = os.path.abspath(doc.files[int(idx)]), int(line_text), True
        else:
            path, line, expat = os.path.abspath(doc.path), el.sourceline or 0, False
        sf = self.source(path)
        cands = [t for t in sf.tags_at(line, expat=expat) if t.local == name]
        if len(cands) > 1 and not expat:
            same = [e for e in doc.root.iter(el.tag) if e.sourceline == el.sourceline]
            k = next((i for i, e in enumerate(same) if e is el), None)
            cands = [cands[k]] if k is not None and k < len(cands) else []
        elif len(cands) > 1:
            cands = [t for t in cands if _compatible(t, el)]
        if len(cands) != 1:
            what = "several" if cands else "no"
            raise NotFixable(
                f"{what} <{name}> start tags at {sf.display}:{line}: cannot tell which to edit"
            )
        return Written(sf, cands[0])

    def written_text(self, el: etree._Element) -> tuple[Written, str]:
        """Where a text-only element is written, and its text as written."""
        w = self.written(el)
        raw = w.file.raw_text(w.tag)
        if raw is None:
            raise NotFixable(f"<{w.tag.name}> at {w.where} holds more than text")
        return w, raw

    def text_for(self, value: str, sources: list[tuple[Written, str]], scope: Written) -> str:
        """Text to write inside ``scope`` that evaluates to ``value``.

        ``sources`` are places whose text evaluates to ``value`` (a link's ``name``, a
        gazebo ``reference``, as written). A literal is written as it is; an expression
        (``${prefix}camera``) is copied only into the same xacro macro body of the same
        file, where it means the same. A macro body that expands to several copies takes
        no literal (each copy would need another name).
        """
        for w, raw in sources:
            if not is_expr(raw):
                if self.copies_of(scope) > 1:
                    continue
                return escape(value)
            if w.file.path == scope.file.path and w.macro() == scope.macro():
                return raw
        if self.copies_of(scope) > 1:
            raise NotFixable(
                f"{scope.where} is in a xacro macro used {self.copies_of(scope)} times and "
                f"{value!r} is not written there: name it in the macro by hand"
            )
        raise NotFixable(
            f"{value!r} is computed by xacro outside {scope.where}: name it there by hand"
        )

    def copies_of(self, w: Written) -> int:
        """How many copies of the element at ``w`` the expanded robot holds."""
        if not self.xacro:
            return 1
        files = [os.path.abspath(f) for f in self.robot.document.files]
        if w.file.path not in files:
            return 1
        stamp = f"{files.index(w.file.path)}:{w.file.line_expat(w.tag.start)}"
        return self._copies(stamp, w.tag.local)


def _compatible(tag: Tag, el: etree._Element) -> bool:
    """The start tag as written could have produced ``el`` (literal attributes agree)."""
    written = {a.name: a for a in tag.attrs if not a.name.startswith("xmlns") and ":" not in a.name}
    have = {str(k) for k in el.attrib if k != LOC_ATTR and not k.startswith("{")}
    if set(written) != have:
        return False
    return all(is_expr(a.raw) or a.value == el.get(n) for n, a in written.items())
