"""The label files themselves (no corpus needed): issue 35's ``consequence:`` on defect labels.

tests/labelled.py keeps every key of a label; ``consequence`` says, on one line, what ROS
receives and what it should receive, and only a true defect carries one.
"""

from __future__ import annotations

from typing import Any

import pytest
from labelled import CORPORA, consequence_problem, labels


def _every_label() -> list[tuple[str, tuple[str, str, int | None], dict[str, Any]]]:
    return [
        (robot, key, lab)
        for corpus in CORPORA
        for robot, table in labels(corpus).items()
        for key, lab in table.items()
    ]


def test_every_consequence_sits_on_a_true_defect_and_is_one_line() -> None:
    bad = [
        (robot, key, consequence_problem(lab))
        for robot, key, lab in _every_label()
        if consequence_problem(lab)
    ]
    assert not bad, bad


def test_the_loader_keeps_consequence() -> None:
    with_consequence = [lab for _, _, lab in _every_label() if "consequence" in lab]
    assert with_consequence, "no label carries a consequence: the loader dropped the key"
    assert all(lab["impact"] == "defect" for lab in with_consequence)


GOOD = "camera_info P[0][3] = -38.8 on a monocular camera; should be 0"


@pytest.mark.parametrize(
    ("lab", "ok"),
    [
        ({"verdict": True, "impact": "defect", "consequence": GOOD}, True),
        ({"verdict": True, "impact": "defect"}, True),  # none written: nothing to check here
        ({"verdict": True, "impact": "minor", "consequence": GOOD}, False),
        ({"verdict": False, "consequence": GOOD}, False),
        ({"verdict": True, "impact": "defect", "consequence": "wrong frame"}, False),  # too short to say both
        ({"verdict": True, "impact": "defect", "consequence": GOOD + "\nand more"}, False),
        ({"verdict": True, "impact": "defect", "consequence": ["a list", "of lines"]}, False),
    ],
)
def test_consequence_problem(lab: dict[str, Any], ok: bool) -> None:
    assert (consequence_problem(lab) is None) is ok
