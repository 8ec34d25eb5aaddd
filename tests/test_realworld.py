"""Precision on robots sensorkit did not write: every finding labelled, precision >= 95 %.

See tests/labelled.py for the format. A new finding on a corpus robot fails here until a
person labels it (``python benchmarks/corpus_precision.py --skeleton`` prints the lines to
fill in), and a label whose finding is gone fails too, so the labels stay the truth.
"""

from __future__ import annotations

import functools

import pytest
import yaml
from conftest import needs_corpus
from labelled import CORPORA, IMPACTS, Outcome, live, robots, run, skeleton, table

pytestmark = needs_corpus

ROBOTS = robots()
# A robot listed in wanted.yaml whose files have not landed in ../shared/corpus yet.
WAITING = {r.id for r in ROBOTS if r.pending and not r.present}


@functools.cache
def outcome(robot_id: str) -> Outcome:
    robot = next(r for r in ROBOTS if r.id == robot_id)
    return run(robot)


def _ready(robot_id: str) -> None:
    if robot_id in WAITING:
        pytest.skip(f"pending: {robot_id} is in wanted.yaml and not yet in ../shared/corpus")


def test_the_corpora_are_wide() -> None:
    real = [r for r in ROBOTS if r.corpus.name == "realworld"]
    repos = {r.file.split("/", 1)[0] for r in real}
    assert len(repos) >= 20, sorted(repos)
    flavours = {r.flavour for r in ROBOTS}
    assert {"ros2-classic", "fortress", "harmonic", "ros1"} <= flavours


@pytest.mark.parametrize("robot_id", [r.id for r in ROBOTS])
def test_every_finding_is_labelled(robot_id: str) -> None:
    _ready(robot_id)
    out = outcome(robot_id)
    assert out.error is None, out.error
    robot = out.robot
    labelled = table(robot)
    known = live(labelled)
    missing = [k for k in out.keys if k not in known]
    assert not missing, f"unlabelled findings on {robot.key}:\n" + skeleton(out, labelled)
    stale = [k for k in known if k not in out.keys]
    assert not stale, f"labels with no finding any more on {robot.key} (mark them gone: WHY): {stale}"
    for key, lab in known.items():
        assert lab.get("verdict") in (True, False), (key, lab)
        assert len(str(lab.get("why", ""))) >= 15, f"say why {key} is {lab.get('verdict')}"
        if lab["verdict"] is True:
            assert lab.get("impact") in IMPACTS, f"say whether {key} is a defect or minor: {lab}"
        if lab.get("impact") == "defect":
            # Issue 35: a defect names what ROS receives and what it should receive.
            assert len(str(lab.get("consequence") or "")) >= 15, f"say the consequence of defect {key}: {lab}"
    for key, lab in labelled.items():
        if "gone" in lab:
            assert len(str(lab["gone"])) >= 15, f"say why {key} went"
            assert key not in out.keys, f"{key} is marked gone but is reported again: {lab['gone']}"


@pytest.mark.parametrize("robot_id", [r.id for r in ROBOTS])
def test_no_error_is_minor(robot_id: str) -> None:
    """An error promises the sensor will not work as written: a true error whose label says
    it changes nothing (minor) breaks that promise, whatever the rule."""
    _ready(robot_id)
    out = outcome(robot_id)
    known = live(table(out.robot))
    minor = [
        (key, out.messages[key][:120])
        for key in out.keys
        if out.messages[key].startswith("error:") and known.get(key, {}).get("impact") == "minor"
    ]
    assert not minor, f"errors labelled minor on {out.robot.key}: {minor}"


def test_precision_is_at_least_95_percent() -> None:
    true = false = 0
    for robot in ROBOTS:
        if robot.id in WAITING:
            continue
        out = outcome(robot.id)
        known = live(table(robot))
        for key, count in out.keys.items():
            lab = known.get(key)
            if lab is None:
                continue  # reported by test_every_finding_is_labelled
            if lab.get("verdict") is True:
                true += count
            else:
                false += count
    assert true + false > 0
    assert true / (true + false) >= 0.95, f"precision {true}/{true + false}"


def test_corpora_exist() -> None:
    assert all(c.root.is_dir() and (c.lists / "robots.yaml").is_file() for c in CORPORA)


def test_only_pending_robots_may_be_missing() -> None:
    missing = [r.id for r in ROBOTS if not r.present and not r.pending]
    assert not missing, f"listed robots with no file in ../shared/corpus: {missing}"


def test_pending_robots_are_wanted() -> None:
    """A robot waits for its files only when wanted.yaml says where to fetch them from."""
    wanted = yaml.safe_load((CORPORA[1].lists / "wanted.yaml").read_text()) or []
    for w in wanted:
        assert {"repo", "commit", "paths", "licence", "why"} <= set(w), w
    # paths are relative to the repository root; the corpus folder is named owner__name
    wanted_paths = {f"{w['repo'].replace('/', '__')}/{p}" for w in wanted for p in w["paths"]}
    for r in ROBOTS:
        if r.pending:
            for f in (r.file, *r.launch):
                if not (r.corpus.root / f).is_file():
                    assert any(f == p or f.startswith(p.rstrip("/") + "/") for p in wanted_paths), (r.id, f)


def test_launch_entries_name_xml_or_yaml_launch_files() -> None:
    """Python launch files are code: the corpus holds XML and YAML launch files only."""
    for r in ROBOTS:
        for f in r.launch:
            assert f.endswith((".launch", ".launch.xml", ".launch.yaml", ".xml", ".yaml")), (r.id, f)


def test_the_project_holds_no_fetched_robot() -> None:
    """Fetched files live in ../shared/corpus only: tests/corpus and tests/realworld hold
    the project's run lists, labels and wanted list, nothing else."""
    for c in CORPORA:
        extra = sorted(p.name for p in c.lists.iterdir() if p.name not in {"robots.yaml", "labels.yaml", "wanted.yaml"})
        assert not extra, f"tests/{c.name} holds {extra}"
