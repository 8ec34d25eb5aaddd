"""Precision on robots sensorkit did not write: every finding labelled, precision >= 95 %.

See tests/labelled.py for the format. A new finding on a corpus robot fails here until a
person labels it (``python benchmarks/corpus_precision.py --skeleton`` prints the lines to
fill in), and a label whose finding is gone fails too, so the labels stay the truth.
"""

from __future__ import annotations

import functools

import pytest
from labelled import CORPORA, Outcome, labels, robots, run, skeleton

ROBOTS = robots()


@functools.cache
def outcome(robot_id: str) -> Outcome:
    robot = next(r for r in ROBOTS if r.id == robot_id)
    return run(robot)


def test_the_corpora_are_wide() -> None:
    real = [r for r in ROBOTS if r.corpus.name == "realworld"]
    repos = {r.file.split("/", 1)[0] for r in real}
    assert len(repos) >= 20, sorted(repos)
    flavours = {r.flavour for r in ROBOTS}
    assert {"ros2-classic", "fortress", "harmonic", "ros1"} <= flavours


@pytest.mark.parametrize("robot_id", [r.id for r in ROBOTS])
def test_every_finding_is_labelled(robot_id: str) -> None:
    out = outcome(robot_id)
    assert out.error is None, out.error
    robot = out.robot
    known = labels(robot.corpus).get(robot.key, {})
    missing = [k for k in out.keys if k not in known]
    assert not missing, f"unlabelled findings on {robot.key}:\n" + skeleton(out, known)
    stale = [k for k in known if k not in out.keys]
    assert not stale, f"labels with no finding any more on {robot.key}: {stale}"
    for key, lab in known.items():
        assert lab.get("verdict") in (True, False), (key, lab)
        assert len(str(lab.get("why", ""))) >= 15, f"say why {key} is {lab.get('verdict')}"


def test_precision_is_at_least_95_percent() -> None:
    true = false = 0
    for robot in ROBOTS:
        out = outcome(robot.id)
        known = labels(robot.corpus).get(robot.key, {})
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
    assert all(c.is_dir() for c in CORPORA)
