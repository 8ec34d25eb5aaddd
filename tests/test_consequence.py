"""Severity computed from consequence (issue 35 item 1): sensorkit.base.consequence is the
one place where what was written, against what the simulator uses, becomes a severity."""

from __future__ import annotations

import json

import pytest

from sensorkit.base.consequence import UNKNOWN, Consequence, Role, Severity, same_value, severity_of
from sensorkit.base.findings import Finding


@pytest.mark.parametrize("role", [Role.FRAME, Role.TOPIC, Role.CALIBRATION, Role.GEOMETRY, Role.OUTPUT])
def test_wrong_data_roles_are_errors_when_they_differ_and_info_when_equal(role: Role) -> None:
    assert severity_of(role, "camera_link", "base_link") is Severity.ERROR
    assert severity_of(role, "camera_link", "camera_link") is Severity.INFO


@pytest.mark.parametrize("role", [Role.RATE, Role.NOISE, Role.LIMIT, Role.FLAG, Role.SIM_TOPIC])
def test_tuning_roles_are_warnings_when_they_differ_and_info_when_equal(role: Role) -> None:
    assert severity_of(role, 30, 10) is Severity.WARNING
    assert severity_of(role, "30", 30.0) is Severity.INFO


def test_cosmetic_and_unknown_are_info() -> None:
    assert severity_of(Role.COSMETIC, "a", "b") is Severity.INFO
    assert severity_of(Role.FRAME, "camera_link", UNKNOWN) is Severity.INFO


def test_numbers_compare_as_numbers_within_a_tolerance_and_just_outside_it_differ() -> None:
    assert same_value("0.1", 0.1)
    assert same_value(1.0, 1.0 + 1e-12)
    assert not same_value(1.0, 1.0 + 1e-6)
    assert same_value([1, 2.0], ("1", "2"))
    assert not same_value([1, 2], [1, 2, 3])


def test_a_rule_may_say_equal_with_a_tolerance_of_its_own() -> None:
    assert severity_of(Role.FRAME, 0.0, 0.0004, equal=True) is Severity.INFO
    assert severity_of(Role.FRAME, 0.0, 0.0004, equal=False) is Severity.ERROR


def test_the_message_and_json_say_both_values() -> None:
    c = Consequence(Role.FRAME, "camera_optical", "camera_link")
    assert c.says() == "written camera_optical; the simulator uses camera_link"
    f = Finding("SK602", c.severity, "m", consequence=c)
    data = json.loads(json.dumps(f.to_dict()))
    assert data["severity"] == "error"
    assert data["consequence"] == {"role": "frame", "intended": "camera_optical", "effective": "camera_link", "known": True}
    same = Consequence(Role.RATE, 30, "30")
    assert same.says().endswith("nothing changes") and same.changes_nothing
    assert "not known" in Consequence(Role.TOPIC, "/a", UNKNOWN).says()
