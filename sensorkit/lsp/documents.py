"""The open robots, what each includes, and the diagnostics each file holds.

Every open ``.urdf``/``.xacro`` document is a top-level file validated on its own; the
files it reads (its includes) are remembered, so an edit of an include validates again
every open robot that reads it. Every open buffer (a YAML too) is in the overlay of every
validation: an unsaved include is seen by the robot that includes it.

A file's diagnostics are the findings that land in it from every open robot (an include
read by two robots: both robots' findings, each once). After each validation every file
whose diagnostics changed is published again, a file whose findings are gone with an
empty list.

No protocol here: :class:`Documents` returns :class:`Publish` records and
:mod:`sensorkit.lsp.server` sends them.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from sensorkit.base.errors import UsageError
from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.lint.engine import Options
from sensorkit.lsp.analysis import Analysis, analyse

__all__ = ["ROBOT_SUFFIXES", "Documents", "Publish", "is_robot_file"]

# .urdf.xacro ends with .xacro; SDF models and worlds are read too (issue 28)
ROBOT_SUFFIXES = (".urdf", ".xacro", ".sdf", ".world")
SETTINGS_FILES = ("sensorkit.toml", "pyproject.toml")  # as sensorkit.lint.config finds them


def is_robot_file(path: str) -> bool:
    return path.endswith(ROBOT_SUFFIXES)


@dataclass(frozen=True)
class Publish:
    """The diagnostics of one file: its findings (a file's findings gone: empty)."""

    path: str  # absolute
    version: int | None  # the open document's version, None for a file not open
    findings: tuple[Finding, ...]


@dataclass
class _Open:
    text: str
    version: int | None


@dataclass
class Documents:
    """The open documents and the last validation of each open robot.

    ``options_for(path)`` gives the options a top-level file is validated with (the
    settings file found upward from it); a UsageError from it becomes a diagnostic.
    """

    options_for: Callable[[Path], Options]
    open: dict[str, _Open] = field(default_factory=dict)
    analyses: dict[str, Analysis] = field(default_factory=dict)
    shown: dict[str, tuple[Finding, ...]] = field(default_factory=dict)

    # ------------------------------------------------------------------ events

    def opened(self, path: str, text: str, version: int | None) -> list[Publish]:
        self.open[path] = _Open(text, version)
        return self.validate(self._readers(path), also=_own(path))

    def changed(self, path: str, text: str, version: int | None) -> list[Publish]:
        self.edited(path, text, version)
        return self.refresh(path)

    def edited(self, path: str, text: str, version: int | None) -> None:
        """Take the new text of ``path``; validate later (:meth:`refresh`)."""
        self.open[path] = _Open(text, version)

    def refresh(self, path: str) -> list[Publish]:
        """Validate what reads ``path`` (its new text taken with :meth:`edited`)."""
        return self.validate(self._readers(path), also=_own(path))

    def version(self, path: str) -> int | None:
        doc = self.open.get(path)
        return doc.version if doc is not None else None

    def saved(self, path: str, text: str | None = None) -> list[Publish]:
        doc = self.open.get(path)
        if doc is not None and text is not None:
            doc.text = text
        return self.validate(self._readers(path), also=_own(path))

    def closed(self, path: str) -> list[Publish]:
        """The document is read from disk again; it is no longer a top-level robot."""
        self.open.pop(path, None)
        gone = self.analyses.pop(path, None)
        readers = [t for t, a in self.analyses.items() if path in a.sources]
        return self.validate(readers, also=_own(path) | set(gone.by_file if gone else ()))

    def disk_changed(self, paths: set[str]) -> list[Publish]:
        """Files changed on disk: validate again every robot that reads one that is not
        open (an open one is read from its buffer), or every robot when a settings file
        changed."""
        if any(os.path.basename(p) in SETTINGS_FILES for p in paths):
            return self.validate(list(self.analyses))
        closed = paths - set(self.open)
        return self.validate([t for t, a in self.analyses.items() if a.sources & closed])

    # ------------------------------------------------------------------ validation

    def overlay(self) -> dict[str, bytes]:
        """Every open buffer, as the bytes the loader reads instead of the disk."""
        return {p: d.text.encode("utf-8") for p, d in self.open.items()}

    def _readers(self, path: str) -> list[str]:
        """The robots to validate after ``path`` changed: itself, if open, and every open
        robot that read it."""
        others = [t for t, a in self.analyses.items() if path in a.sources and t != path]
        own = self.analyses.get(path)
        if others and own is not None and own.report is not None and own.report.macro_only:
            return others  # an include of macros: the robots that use them say what they do
        return ([path] if path in self.open and is_robot_file(path) else []) + others

    def validate(self, tops: list[str], also: set[str] | None = None) -> list[Publish]:
        """Validate ``tops`` again; the publications of every file whose diagnostics
        changed (and of ``also``)."""
        overlay = self.overlay()
        touched = set(also or ())
        for top in tops:
            old = self.analyses.get(top)
            if old is not None:
                touched |= set(old.by_file)
            new = self._analyse(top, overlay)
            self.analyses[top] = new
            touched |= set(new.by_file)
        return self._publish(touched)

    def _analyse(self, top: str, overlay: dict[str, bytes]) -> Analysis:
        path = Path(top)
        try:
            options = self.options_for(path)
        except UsageError as exc:
            out = Analysis(top=path, options=Options(), sources={top}, error=str(exc))
            out.by_file[top] = [_error(top, str(exc))]
            return out
        out = analyse(path, options, overlay)
        if out.error and out.report is None:
            out.by_file.setdefault(top, []).append(_error(top, out.error))
        return out

    def findings_of(self, path: str) -> tuple[Finding, ...]:
        """Every open robot's findings in ``path``, each once, in report order."""
        seen: dict[tuple[object, ...], Finding] = {}
        for a in self.analyses.values():
            for f in a.by_file.get(path, ()):
                seen.setdefault((f.rule, f.line, f.column, f.message), f)
        return tuple(sorted(seen.values(), key=Finding.sort_key))

    def _publish(self, paths: set[str]) -> list[Publish]:
        out: list[Publish] = []
        for p in sorted(paths):
            now = self.findings_of(p)
            if p in self.shown and self.shown[p] == now and p not in self.open:
                continue
            self.shown[p] = now
            doc = self.open.get(p)
            out.append(Publish(p, doc.version if doc is not None else None, now))
        return out

    def analyses_of(self, path: str) -> list[Analysis]:
        """The validations whose robot reads ``path`` (its own first)."""
        own = [self.analyses[path]] if path in self.analyses else []
        return own + [a for t, a in self.analyses.items() if t != path and path in a.sources]


def _own(path: str) -> set[str]:
    """A robot file is published after its own event, even with nothing to say."""
    return {path} if is_robot_file(path) else set()


def _error(top: str, message: str) -> Finding:
    """A file that could not be validated at all, as a finding with no rule."""
    return Finding("", Severity.ERROR, message, SourceRef(os.path.relpath(top), 1))
