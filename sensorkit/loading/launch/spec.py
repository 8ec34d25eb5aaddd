"""What every launch front end (Python, XML, YAML) reads a node into, and the reading state.

A value is a ``str`` when the reader resolved it and ``None`` when it could not (never a
guess). A path into a package outside the workspace is written with a NUL-delimited marker
(:func:`outside`), so it is recognised (``ros_gz_bridge``'s own launch file) but never
read as a file or taken for a name.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sensorkit.loading.document import display_path
from sensorkit.loading.launch_facts import LaunchFacts, LaunchProblem

MAX_LAUNCH_BYTES = 1 << 20
MAX_LAUNCH_FILES = 200
MAX_INCLUDE_DEPTH = 8
# Includes followed in one run (each path to a file counts: nine files each including the
# next twelve times are 12**8 paths, though no cycle and only nine files).
MAX_INCLUDE_EDGES = 1000
_MARK = "\x00pkg:"


def outside(package: str) -> str:
    """The share folder of a package that is not in the workspace."""
    return f"{_MARK}{package}\x00"


def outside_package(path: str) -> tuple[str, str] | None:
    """(package, rest) of a path into a package outside the workspace, else None."""
    m = re.match(r"\x00pkg:([^\x00]*)\x00/*(.*)", path, re.S)
    return (m.group(1), m.group(2)) if m else None


def plain(value: str | None) -> str | None:
    """A resolved value that names something (not a path outside the workspace)."""
    return None if value is None or "\x00" in value else value


@dataclass
class NodeSpec:
    """A node a launch file starts, its values as resolved (None: unknown)."""

    package: str | None
    executable: str | None
    name: str | None
    namespace: str | None
    # None: the argument list itself is unknown; an element None: that argument is.
    arguments: list[str | None] | None
    # In the order given: a map name -> value (a None key: more keys may be there,
    # unknown), a parameter file's path, or None for a file that could not be resolved.
    params: list[dict[str | None, str | None] | str | None] = field(default_factory=list)
    remaps: list[tuple[str | None, str | None]] = field(default_factory=list)
    remaps_unknown: bool = False
    file: str = ""
    line: int | None = None
    arg_lines: list[int | None] = field(default_factory=list)


@dataclass
class Include:
    """A launch file included (resolved path or None) with the arguments it is given."""

    path: str | None
    arguments: dict[str, str | None]
    line: int | None


@dataclass
class Reading:
    """The state of one read_launch call, shared by the front ends."""

    packages: Mapping[str, Path]
    roots: tuple[Path, ...]
    facts: LaunchFacts = field(default_factory=LaunchFacts)
    seen: set[Path] = field(default_factory=set)
    nodes: list[NodeSpec] = field(default_factory=list)
    # each file read and parsed once per run: its bytes by real path, what it says by
    # (real path, arguments it was given)
    data: dict[Path, bytes | None] = field(default_factory=dict)
    parsed: dict[Any, Any] = field(default_factory=dict)
    edges: int = 0  # includes followed so far (MAX_INCLUDE_EDGES)

    def problem(self, file: str, message: str, line: int | None = None) -> None:
        self.facts.problems.append(LaunchProblem(file, message, line))

    def share(self, package: str) -> str:
        """The folder of ``package`` in the workspace, or the outside marker."""
        folder = self.packages.get(package)
        return str(folder) if folder is not None else outside(package)

    def display(self, path: Path) -> str:
        """``path`` as every other file of a report is shown (sensorkit.loading.document.
        display_path: relative to the working folder, else absolute), so that a finding on a
        launch file or the bridge YAML it names opens from where sensorkit was run, and a
        file read both as --bridge and as a launch file's config_file is one file."""
        return display_path(path)

    def inside(self, path: Path) -> bool:
        """Whether ``path`` lies inside one of the workspace roots (real paths)."""
        try:
            real = path.resolve()
        except (OSError, RuntimeError):
            return False
        for root in self.roots:
            try:
                real.relative_to(root.resolve())
                return True
            except (ValueError, OSError, RuntimeError):
                continue
        return any(real == Path(p).resolve() or _below(real, Path(p)) for p in self.packages.values())


def _below(path: Path, folder: Path) -> bool:
    try:
        path.relative_to(folder.resolve())
        return True
    except (ValueError, OSError, RuntimeError):
        return False
