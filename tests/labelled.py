"""The labelled real-world corpora: run validate on every robot and compare with labels.

Each corpus folder (tests/corpus, tests/realworld) has ``robots.yaml`` (which files to
validate, with args, target and bridge files, as a user would) and ``labels.yaml``: for
each robot, every finding validate reports, with its verdict (true or false) and why.
Findings are keyed by (rule, file relative to tests/, line). SK104 (missing meshes) is
left out: the corpora copy no meshes, so every mesh reference is missing by construction.

Used by test_realworld.py (no unlabelled finding, no stale label, precision >= 95 %) and
by benchmarks/corpus_precision.py (figures, and a skeleton for new findings to label).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

TESTS = Path(__file__).resolve().parent
CORPORA = (TESTS / "corpus", TESTS / "realworld")
IGNORED = ("SK104",)

Key = tuple[str, str, "int | None"]


@dataclass
class Robot:
    corpus: Path
    file: str
    flavour: str = ""
    kind: str = ""
    args: dict[str, str] = field(default_factory=dict)
    target: str = "auto"
    bridge: list[str] = field(default_factory=list)
    # NAME -> folder (relative to the corpus): a package this robot must find before the
    # corpora's own (two repositories here ship a package of one name, e.g. velodyne_description
    # in its ROS 2 port under tests/corpus and its ROS 1 original under tests/realworld).
    packages: dict[str, str] = field(default_factory=dict)

    @property
    def path(self) -> Path:
        return (self.corpus / self.file).resolve()

    @property
    def key(self) -> str:
        """How labels.yaml names this robot: the file, then its xacro args (one file may be
        listed twice with different args)."""
        return " ".join([self.file, *(f"{k}:={v}" for k, v in sorted(self.args.items()))])

    @property
    def id(self) -> str:
        return f"{self.corpus.name}/{self.key}"


@dataclass
class Outcome:
    robot: Robot
    keys: Counter[Key]
    messages: dict[Key, str]
    error: str | None


def robots() -> list[Robot]:
    out: list[Robot] = []
    for corpus in CORPORA:
        listing = corpus / "robots.yaml"
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
                )
            )
    return out


def _rel(file: str | None) -> str:
    if not file:
        return ""
    p = Path(file)
    if not p.is_absolute():
        p = (Path.cwd() / p).resolve()
    try:
        return str(p.resolve().relative_to(TESTS))
    except ValueError:
        return str(p)


def run(robot: Robot) -> Outcome:
    from sensorkit.engine import Options, validate_file

    options = Options(
        target=robot.target,
        args=dict(robot.args),
        package_paths=(
            *(f"{name}={robot.corpus / folder}" for name, folder in robot.packages.items()),
            *(str(c) for c in CORPORA if c.is_dir()),
        ),
        ignore=IGNORED,
        bridges=tuple(str(robot.corpus / b) for b in robot.bridge),
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


def labels(corpus: Path) -> dict[str, dict[Key, dict[str, Any]]]:
    """robot key (file and args) -> finding key -> label (verdict, why)."""
    path = corpus / "labels.yaml"
    if not path.is_file():
        return {}
    out: dict[str, dict[Key, dict[str, Any]]] = {}
    for entry in yaml.safe_load(path.read_text()) or []:
        table = out.setdefault(entry["robot"], {})
        for lab in entry.get("findings") or []:
            table[(lab["rule"], lab["file"], lab.get("line"))] = lab
    return out


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
            f'verdict: ?, why: ""}}  # {msg[:160]}'
        )
    return "\n".join(lines)
