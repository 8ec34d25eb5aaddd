"""read_launch: read launch files, and the workspace launch files they include.

Limits (each a LaunchProblem, never a traceback or a hang): a file over 1 MiB or not a
regular file, more than 200 files read or 1,000 includes followed (a file reached on many
paths counts each time: an include "diamond"), includes nested deeper than 8 or in a
cycle, a file that does not parse (or nests too deeply for Python's parser). Each file is
read and parsed once per run.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence
from pathlib import Path

from sensorkit.base.regular import TooLarge, read_regular
from sensorkit.loading.launch.extract import extract
from sensorkit.loading.launch.frontend import Context, read_entities, xml_entities, yaml_entities
from sensorkit.loading.launch.python_launch import FileReading, read_python
from sensorkit.loading.launch.spec import (
    MAX_INCLUDE_DEPTH,
    MAX_INCLUDE_EDGES,
    MAX_LAUNCH_BYTES,
    MAX_LAUNCH_FILES,
    NodeSpec,
    Reading,
    outside_package,
    plain,
)
from sensorkit.loading.launch_facts import LaunchFacts
from sensorkit.loading.packages import scan_packages

# ros_gz launch files outside the workspace that start a bridge from ``config_file``
# (gazebosim/ros_gz@jazzy:ros_gz_bridge/launch/ros_gz_bridge.launch.py:40-41,88;
# ros_gz_sim/launch/ros_gz_sim.launch.py:42-43,97) or spawn a model
# (ros_gz_sim/launch/gz_spawn_model.launch.py:26-29,53-54,64-70: entity_name, topic, file).
_BRIDGE_LAUNCH = {("ros_gz_bridge", "ros_gz_bridge.launch.py"), ("ros_gz_sim", "ros_gz_sim.launch.py"),
                  ("ros_gz_sim", "ros_gz_spawn_model.launch.py")}
_SPAWN_LAUNCH = {("ros_gz_sim", "gz_spawn_model.launch.py"), ("ros_gz_sim", "ros_gz_spawn_model.launch.py")}


def read_launch(paths: Sequence[Path], *, roots: Sequence[Path],
                package_paths: Mapping[str, Path] | None = None) -> LaunchFacts:
    """Read each launch file and the workspace launch files it includes."""
    packages: dict[str, Path] = {}
    for root in roots:
        for name, folder in scan_packages(root).items():
            packages.setdefault(name, folder)
    packages.update(package_paths or {})
    reading = Reading(packages, tuple(roots))
    for path in paths:
        _read(reading, path, {}, (), False)
    return reading.facts


def _read(reading: Reading, path: Path, inherited: dict[str, str | None],
          stack: tuple[Path, ...], ns_pushed: bool) -> None:
    name = reading.display(path)
    real = path.resolve()
    if real in stack:
        reading.problem(name, "include cycle: " + " -> ".join(p.name for p in (*stack, real)))
        return
    if len(stack) > MAX_INCLUDE_DEPTH:
        reading.problem(name, f"includes nested deeper than {MAX_INCLUDE_DEPTH}: not read")
        _unknown_all(reading, name)
        return
    if len(reading.seen) >= MAX_LAUNCH_FILES and real not in reading.seen:
        if not any("more than" in p.message for p in reading.facts.problems):
            reading.problem(name, f"more than {MAX_LAUNCH_FILES} launch files: the rest not read")
        _unknown_all(reading, name)
        return
    reading.seen.add(real)
    if name not in reading.facts.files:
        reading.facts.files.append(name)
    key = (real, tuple(sorted(inherited.items(), key=lambda kv: kv[0])))
    if key not in reading.parsed:
        reading.parsed[key] = _parse(reading, real, path, name, inherited)
    got = reading.parsed[key]
    if got is None:
        _unknown_all(reading, name)
        return
    for spec in map(copy.copy, got.nodes):  # the parse is shared by every path to the file
        spec.file = name
        if ns_pushed or got.pushes_namespace:
            spec.namespace = None
        extract(reading, spec)
    for inc in got.includes:
        _include(reading, path, name, inc.path, {**got.configs, **inc.arguments}, inc.line,
                 (*stack, real), ns_pushed or got.pushes_namespace)


def _bytes(reading: Reading, real: Path, name: str) -> bytes | None:
    """The bytes of the launch file (read once per run), None when it cannot be read."""
    if real not in reading.data:
        reading.data[real] = None
        try:
            reading.data[real] = read_regular(real, MAX_LAUNCH_BYTES)
        except TooLarge:
            reading.problem(name, "could not read: larger than 1 MiB")
        except OSError as exc:
            reading.problem(name, f"could not read: {exc.strerror or type(exc).__name__}")
    return reading.data[real]


def _parse(reading: Reading, real: Path, path: Path, name: str,
           inherited: dict[str, str | None]) -> FileReading | None:
    data = _bytes(reading, real, name)
    if data is None:
        return None
    try:
        ctx = Context(path, reading.share, dict(inherited))
        if path.name.endswith(".py"):
            return read_python(data.decode("utf-8"), name, inherited, reading.share)
        if path.suffix in (".yaml", ".yml"):
            return read_entities(yaml_entities(data.decode("utf-8")), ctx)
        return read_entities(xml_entities(data), ctx)
    except (OSError, UnicodeDecodeError, SyntaxError, ValueError) as exc:
        reading.problem(name, f"could not read: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}")
    except (RecursionError, MemoryError):
        reading.problem(name, "could not read: nests too deeply")
    return None


def _unknown_all(reading: Reading, name: str) -> None:
    """A launch file not read (``name``: it, or the file including it) may start anything:
    nothing may be said to be missing."""
    facts = reading.facts
    facts.bridge_unknown = facts.static_transform_unknown = facts.remap_unknown = True
    if name not in facts.bridge_unknown_in:
        facts.bridge_unknown_in.append(name)


def _include(reading: Reading, parent: Path, name: str, target: str | None,
             args: dict[str, str | None], line: int | None, stack: tuple[Path, ...],
             ns_pushed: bool) -> None:
    reading.edges += 1
    if reading.edges > MAX_INCLUDE_EDGES:
        if reading.edges == MAX_INCLUDE_EDGES + 1:
            reading.problem(name, f"more than {MAX_INCLUDE_EDGES} launch includes: the rest not read", line)
        _unknown_all(reading, name)
        return
    if target is not None and (out := outside_package(target)) is not None:
        key = (out[0], Path(out[1]).name)
        if key in _BRIDGE_LAUNCH and "config_file" in args:
            extract(reading, NodeSpec("ros_gz_bridge", "parameter_bridge", None,
                                      None if ns_pushed else args.get("namespace", ""), [],
                                      params=[{"config_file": args["config_file"]}], file=name, line=line))
        if key in _SPAWN_LAUNCH:
            params: dict[str | None, str | None] = {k: args.get(k, "") for k in ("topic", "file")}
            params["name"] = args.get("entity_name", "")
            extract(reading, NodeSpec("ros_gz_sim", "create", None, "", [], params=[params],
                                      file=name, line=line))
        return  # a launch file of a package outside the workspace: not read
    path = plain(target)
    if path is None or "\x00unknown" in args:
        reading.problem(name, "an included launch file could not be resolved", line)
        _unknown_all(reading, name)
        return
    file = Path(path)  # a relative path depends on where launch is run from: not guessed
    if not file.is_absolute() or not file.is_file() or not reading.inside(file):
        reading.problem(name, f"included launch file not found in the workspace: {path}", line)
        _unknown_all(reading, name)
        return
    _read(reading, file, args, stack, ns_pushed)
