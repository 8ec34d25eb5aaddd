"""Validating a robot as the editor holds it: its unsaved buffers in place of the disk.

:func:`load` is the one place the server loads and expands a robot (diagnostics and hover
both go through it), so an expansion cache is plugged in here with one line. Quick fixes
plan with :func:`sensorkit.fix.apply.plan_file`, which loads through
:func:`sensorkit.lint.engine.load_as` as ``validate`` does.
"""

from __future__ import annotations

import dataclasses
import gc
import os
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from sensorkit.base.errors import InputError, SensorkitError
from sensorkit.base.findings import Finding
from sensorkit.lint.engine import FileReport, Options, load_as, validate_loaded
from sensorkit.model import Loaded
from sensorkit.model.robot import Robot

__all__ = ["Analysis", "analyse", "heap_frozen", "load", "source_path"]


@contextmanager
def heap_frozen() -> Iterator[None]:
    """Every object of the server in the collector's permanent generation while a robot
    is loaded: the xacro child forked meanwhile then never walks the server's heap (its
    imports, the open robots) in its own collections, writing to each object's header
    and so copying every page of it. On turtlebot4 that walk cost each edit ~0.1 s of
    CPU once the server held numpy. A caller that froze objects itself keeps its freeze
    (as :func:`sensorkit.lint.fleet` does)."""
    ours = not gc.get_freeze_count()
    if ours:
        gc.freeze()
    try:
        yield
    finally:
        if ours:
            gc.unfreeze()


def load(path: Path, options: Options) -> Loaded:
    """Load and model ``path`` as ``options`` say (``options.overlay``: the open buffers).

    Every load of the server goes through here. Raises InputError for unreadable input.
    """
    with heap_frozen():
        return load_as(path, options)


def source_path(file: str | None, top: Path) -> str:
    """The absolute path of a finding's file (a display path, relative to the working
    folder), or the top-level file's when the finding names none."""
    return os.path.abspath(file) if file else os.path.abspath(top)


@dataclass
class Analysis:
    """One top-level file validated: its findings by the file holding each element."""

    top: Path
    options: Options
    report: FileReport | None = None
    robot: Robot | None = None
    by_file: dict[str, list[Finding]] = field(default_factory=dict)
    sources: set[str] = field(default_factory=set)  # absolute paths of the files read
    error: str | None = None  # could not be validated at all (the settings, the file)
    memo: dict[str, object] = field(default_factory=dict)  # what hover worked out, kept

    @property
    def target(self) -> str | None:
        return self.report.target if self.report is not None else None


def analyse(top: Path, options: Options, overlay: Mapping[str, bytes]) -> Analysis:
    """Validate ``top`` with the open buffers of ``overlay`` read instead of the disk."""
    options = dataclasses.replace(options, overlay=dict(overlay))
    out = Analysis(top=top, options=options, sources={os.path.abspath(top)})
    try:
        loaded = load(top, options)
    except InputError as exc:
        out.error = str(exc)
        return out
    except RecursionError:
        out.error = f"{top}: the document nests too deeply to read"
        return out
    try:
        report = validate_loaded(top, loaded, options, same_load=True)
    except SensorkitError as exc:  # a bad bridge or launch file: a usage error
        out.error = str(exc)
        return out
    out.report = report
    out.robot = report.robot
    if report.robot is not None:
        document = report.robot.document
        out.sources |= {os.path.abspath(f) for f in (*document.source_files(), *document.reads)}
    if report.error:
        out.error = report.error
    for f in report.findings:
        out.by_file.setdefault(source_path(f.file, top), []).append(f)
    out.sources |= set(out.by_file)  # an include that cannot be parsed is still one
    return out
