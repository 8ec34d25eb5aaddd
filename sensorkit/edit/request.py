"""What an add is asked to do (``AddRequest``) and what it plans: the files it writes
(``PlannedWrite``) and the whole of it (``AddResult``), with its diff."""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from sensorkit.edit.diff import unified_diff
from sensorkit.edit.kinds import MacroInfo, SensorKind

if TYPE_CHECKING:
    from sensorkit.lint.engine import Options


@dataclass(frozen=True)
class AddRequest:
    """What to add, where. ``params`` are macro parameters as text (``width="640"``)."""

    path: Path
    kind: str
    name: str
    parent: str
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    params: Mapping[str, str] = field(default_factory=dict)
    output: Path | None = None
    args: Mapping[str, str] = field(default_factory=dict)
    package_paths: tuple[str, ...] = ()
    validation: Options | None = None  # how to validate; default: every rule, target auto

    @property
    def target(self) -> Path:
        """The robot file the add writes: ``output``, else the file itself."""
        return self.output if self.output is not None else self.path


@dataclass(frozen=True)
class PlannedWrite:
    """One file an add writes: ``role`` is ``"robot"``, ``"macro"`` (a new copy of a
    shipped macro) or ``"package"`` (another file of the robot's package, or its robot
    YAML: ``original`` holds its bytes as planned, None for a new file)."""

    path: Path
    data: bytes
    role: str
    mode: int | None = None
    original: bytes | None = None
    why: str = ""


@dataclass
class AddResult:
    """A planned (and, once ``written``, published) add."""

    kind: SensorKind
    name: str
    source: Path
    target: Path
    style: str  # "xacro" (macro call) or "urdf" (expanded elements)
    macro: MacroInfo
    original: bytes
    new: bytes
    writes: list[PlannedWrite]
    # (old text, new text, old label, new label) of each file the add writes
    changes: list[tuple[str, str, str, str]] = field(default_factory=list, repr=False)
    notes: list[str] = field(default_factory=list)
    links: list[str] = field(default_factory=list)
    joints: list[str] = field(default_factory=list)
    sensors: list[str] = field(default_factory=list)
    written: bool = False
    simulator: str = ""  # where sim came from, when --sim did not say (one line)

    @property
    def package_files(self) -> list[PlannedWrite]:
        """The package files the add writes besides the robot file and macro copy."""
        return [w for w in self.writes if w.role == "package"]

    @functools.cached_property
    def diff(self) -> str:
        """The unified diff of every write, worked out when first asked for (``--diff``):
        on a large file comparing the lines costs as much as the rest of the add."""
        return "".join(unified_diff(*change) for change in self.changes)
