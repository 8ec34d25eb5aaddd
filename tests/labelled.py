"""The labelled real-world corpora: run validate on every robot and compare with labels.

The robots are public files fetched from other repositories; they live beside the project
in ../shared/corpus (and its real-world set ../shared/corpus/realworld), never in it. The
project keeps its own work on them in tests/corpus and tests/realworld: ``robots.yaml``
(which files to validate, with args, target and bridge files, as a user would; paths
relative to the corpus folder, or to the run list's folder for a path starting ``../``,
the project's own wrappers) and ``labels.yaml``: for each robot, every finding validate
reports, with its verdict (true or false) and why. Findings are keyed by (rule, file,
line), the file named ``corpus/...``, ``realworld/...`` or, for the project's own files,
relative to tests/. SK104 (missing meshes) is left out: the corpora copy no meshes, so
every mesh reference is missing by construction.

A robot still to be fetched is listed in tests/realworld/wanted.yaml and marked
``pending: true`` in robots.yaml: until its files are in the corpus it is skipped.

An entry may name the robot's launch files (``launch:``, paths like ``bridge:``; XML and
YAML ones only: Python launch files are code and are not copied into the corpus). It is
run with them (``--launch``), and an entry without ``launch:`` is run with none, so that a
launch file landing beside a robot does not change its plain entry. The entry with launch
files is keyed by its file, args and ``launch:PATH`` items; its labels are the plain
entry's (same file and args) with its own block on top: a finding the launch files add is
labelled there, and one they remove is repeated there with ``gone:`` saying why. An entry
whose launch files have not landed is ``pending: true`` like a robot still to be fetched.

A true label also says its ``impact``: ``defect`` when what the finding names changes what
the robot does (a sensor that publishes nothing, in the wrong frame, with a wrong
calibration), ``minor`` when it is true but harmless. An error is a promise that the
sensor will not work as written, so an error labelled ``minor`` fails the tests. A
``defect`` label also says its ``consequence``: one line naming what ROS receives and what
it should receive (issue 35).

A ``defect`` label may also say its ``consequence``: one line naming what ROS receives and
what it should receive (issue 35), e.g. "camera_info P[0][3] = -38.8 on a monocular camera;
should be 0". Only a true defect carries one (``consequence_problem``).

A finding that stops being reported keeps its label, with ``gone:`` saying why (the rule
change and its source): the tests then hold that it stays gone, and the label is the
record of why it went.

Used by test_realworld.py (no unlabelled finding, no stale label, precision >= 95 %, no
minor error) and by benchmarks/corpus_precision.py (figures, and a skeleton for new
findings to label).
"""

from __future__ import annotations

import functools
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from conftest import CORPUS, REALWORLD, corpus_package_paths

TESTS = Path(__file__).resolve().parent
IGNORED = ("SK104",)

Key = tuple[str, str, "int | None"]


@dataclass(frozen=True)
class Corpus:
    """One labelled corpus: its robot files under ``root``, its run list and labels in
    tests/NAME."""

    name: str
    root: Path

    @property
    def lists(self) -> Path:
        return TESTS / self.name


CORPORA = (Corpus("corpus", CORPUS), Corpus("realworld", REALWORLD))


@dataclass
class Robot:
    corpus: Corpus
    file: str
    flavour: str = ""
    kind: str = ""
    args: dict[str, str] = field(default_factory=dict)
    target: str = "auto"
    bridge: list[str] = field(default_factory=list)
    # NAME -> folder (relative to the corpus): a package this robot must find before the
    # corpora's own (two repositories here ship a package of one name, e.g. velodyne_description
    # in its ROS 2 port in the corpus and its ROS 1 original in the real-world set).
    packages: dict[str, str] = field(default_factory=dict)
    pending: bool = False
    launch: list[str] = field(default_factory=list)

    @property
    def path(self) -> Path:
        if self.file.startswith("../"):  # the project's own wrapper beside the run list
            return (self.corpus.lists / self.file).resolve()
        return (self.corpus.root / self.file).resolve()

    @property
    def plain_key(self) -> str:
        """The file, then its xacro args: the entry run with no launch file."""
        return " ".join([self.file, *(f"{k}:={v}" for k, v in sorted(self.args.items()))])

    @property
    def key(self) -> str:
        """How labels.yaml names this robot: the file, then its xacro args (one file may be
        listed twice with different args), then its launch files."""
        return " ".join([self.plain_key, *(f"launch:{p}" for p in self.launch)])

    @property
    def id(self) -> str:
        return f"{self.corpus.name}/{self.key}"

    @property
    def present(self) -> bool:
        return self.path.is_file() and all((self.corpus.root / p).is_file() for p in self.launch)


@dataclass
class Outcome:
    robot: Robot
    keys: Counter[Key]
    messages: dict[Key, str]
    error: str | None


def robots() -> list[Robot]:
    out: list[Robot] = []
    for corpus in CORPORA:
        listing = corpus.lists / "robots.yaml"
        if not listing.is_file():
            continue
        for entry in yaml.safe_load(listing.read_text()) or []:
            out.append(
                Robot(
                    corpus=corpus,
                    file=entry["file"],
                    flavour=entry.get("flavour", ""),
                    kind=entry.get("kind", ""),
                    args={k: str(v) for k, v in (entry.get("args") or {}).items()},
                    target=entry.get("target", "auto") or "auto",
                    bridge=list(entry.get("bridge") or []),
                    packages={k: str(v) for k, v in (entry.get("packages") or {}).items()},
                    pending=bool(entry.get("pending", False)),
                    launch=list(entry.get("launch") or []),
                )
            )
    return out


def _rel(file: str | None) -> str:
    """The label key's file: ``realworld/...``, ``corpus/...`` or relative to tests/."""
    if not file:
        return ""
    p = Path(file)
    if not p.is_absolute():
        p = (Path.cwd() / p).resolve()
    p = p.resolve()
    for prefix, root in (("realworld", REALWORLD), ("corpus", CORPUS), ("", TESTS)):
        if p.is_relative_to(root.resolve()):
            rel = str(p.relative_to(root.resolve()))
            return f"{prefix}/{rel}" if prefix else rel
    return str(p)


def run(robot: Robot) -> Outcome:
    from sensorkit.lint.engine import Options, validate_file
    from sensorkit.loading.launch_facts import LaunchFacts

    options = Options(
        target=robot.target,
        args=dict(robot.args),
        package_paths=(
            *(f"{name}={robot.corpus.root / folder}" for name, folder in robot.packages.items()),
            *corpus_package_paths(),
        ),
        ignore=IGNORED,
        bridges=tuple(str(robot.corpus.root / b) for b in robot.bridge),
        launch=tuple(str(robot.corpus.root / p) for p in robot.launch),
        # No launch: named: none read (not the ones validate would find beside the robot).
        launch_facts=None if robot.launch else LaunchFacts(),
    )
    report = validate_file(robot.path, options)
    keys: Counter[Key] = Counter()
    messages: dict[Key, str] = {}
    for f in report.findings:
        key = (f.rule, _rel(f.file), f.line)
        keys[key] += 1
        messages.setdefault(key, f"{f.severity.label}: {f.message}")
    error = report.error or ("; ".join(report.internal_errors) if report.internal_errors else None)
    return Outcome(robot, keys, messages, error)


def labels(corpus: Corpus) -> dict[str, dict[Key, dict[str, Any]]]:
    """robot key (file and args) -> finding key -> label (verdict, why). Read once while
    the file is unchanged (its size and mtime): test_realworld asks for it three times a
    robot, and parsing the real-world labels took ~0.4 s each time. Do not mutate it."""
    path = corpus.lists / "labels.yaml"
    try:
        st = path.stat()
    except FileNotFoundError:
        return {}
    return _labels(str(path), st.st_size, st.st_mtime_ns)


@functools.lru_cache(maxsize=8)
def _labels(path: str, _size: int, _mtime_ns: int) -> dict[str, dict[Key, dict[str, Any]]]:
    out: dict[str, dict[Key, dict[str, Any]]] = {}
    for entry in yaml.safe_load(Path(path).read_text()) or []:
        table = out.setdefault(entry["robot"], {})
        for lab in entry.get("findings") or []:
            table[(lab["rule"], lab["file"], lab.get("line"))] = lab
    return out


def table(robot: Robot) -> dict[Key, dict[str, Any]]:
    """The labels of one entry: with launch files, the plain entry's with its own on top."""
    every = labels(robot.corpus)
    out = dict(every.get(robot.plain_key, {})) if robot.launch else {}
    out.update(every.get(robot.key, {}))
    return out


IMPACTS = ("defect", "minor")


def consequence_problem(lab: dict[str, Any]) -> str | None:
    """What is wrong with a label's ``consequence``, or None: it belongs to a true defect only
    and is one line long enough to name what ROS receives and what it should."""
    if "consequence" not in lab:
        return None
    text = lab["consequence"]
    if lab.get("verdict") is not True or lab.get("impact") != "defect":
        return "a consequence belongs to a true defect label only"
    if not isinstance(text, str) or "\n" in text.strip() or len(text.strip()) < 15:
        return "a consequence is one line naming what ROS receives and what it should receive"
    return None


def live(table: dict[Key, dict[str, Any]]) -> dict[Key, dict[str, Any]]:
    """The labels of findings still reported (not marked ``gone``)."""
    return {k: lab for k, lab in table.items() if "gone" not in lab}


def skeleton(outcome: Outcome, known: dict[Key, dict[str, Any]]) -> str:
    """YAML for the findings that have no label yet (verdict left for a person)."""
    lines = []
    for key in sorted(outcome.keys, key=lambda k: (k[1], k[2] or 0, k[0])):
        if key in known:
            continue
        rule, file, line = key
        msg = outcome.messages[key].replace('"', "'")
        lines.append(
            f"    - {{rule: {rule}, file: {file}, line: {line if line is not None else 'null'}, "
            f'verdict: ?, impact: ?, why: ""}}  # {msg[:160]}'
        )
    return "\n".join(lines)
