"""Issue 8's false-positive classes and misses: each with a trigger and a near miss.

Robots are our own, written to reproduce one class each; the real robots that showed
them live in tests/realworld (labelled in test_realworld.py).
"""

from __future__ import annotations

from builders import camera_sensor, inertial, joint, link, robot
from conftest import rules_of

from sensorkit.suggest import closest


def _tree(*parts: str) -> str:
    return '<?xml version="1.0"?><robot name="t">' + "".join(parts) + "</robot>"


TB = '<link name="a">' + inertial() + "</link>"


# --- "did you mean" ranks by shared words, not shortness ---------------------------


def test_did_you_mean_prefers_shared_words() -> None:
    assert closest("gnss_link", ["base_link", "gnss_antenna_link", "imu_link"]) == ["gnss_antenna_link"]
    assert closest("camera_optical_frame", ["base_link", "camera_link_optical"]) == ["camera_link_optical"]
    assert closest("lidar_lnk", ["base_link", "lidar_link"]) == ["lidar_link"]
    assert closest("ghost", ["a", "b"]) == []  # nothing plausible: no suggestion at all


def test_sk202_suggestion_uses_words(check) -> None:
    bad = _tree(TB, link("base_link"), link("gnss_antenna_link"), joint("j", "a", "base_link"),
                joint("g", "gnss_link", "gnss_antenna_link"))
    f = next(f for f in check(bad, target="classic").findings if f.rule == "SK202")
    assert f.fix == "did you mean 'gnss_antenna_link'?"


# --- SK207 only for a moving mimic ------------------------------------------------


def test_sk207_ignores_a_fixed_joint_with_mimic(check) -> None:
    # A fixed joint never moves: nothing reads its <mimic>.
    fixed = _tree(TB, link("b"), link("c"), joint("f", "a", "c"),
                  joint("j", "a", "b", extra='<mimic joint="f"/>'))
    assert "SK207" not in rules_of(check(fixed, target="classic"))
    moving = _tree(TB, link("b"), link("c"), joint("f", "a", "c"),
                   joint("j", "a", "b", type="continuous", extra='<axis xyz="0 0 1"/><mimic joint="f"/>'))
    assert "SK207" in rules_of(check(moving, target="classic"))


# --- SK405 depth precision only where depth is published -------------------------


def test_sk405_precision_only_for_depth(check) -> None:
    clip = "<camera><clip><near>0.001</near><far>100</far></clip></camera>"
    assert "SK405" not in rules_of(check(robot(camera=camera_sensor(camera=clip)), target="classic"))
    assert "SK405" in rules_of(check(robot(camera=camera_sensor(stype="depth", camera=clip)), target="classic"))
