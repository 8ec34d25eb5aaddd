"""Severity is a promise (issue 23): an error means the sensor or robot will not work as
written. Rules whose consequence depends on the target say so per target.

SK302 (inertia): Gazebo Classic takes ixx..izz as written, unchecked
(elysia-best/gazebo-classic@upstream/11.10.2+dfsg:gazebo/physics/Inertial.cc:127-149), so
moments no real body has are a warning there. On Gazebo Sim sdformat reports
LINK_INERTIA_INVALID (gazebosim/sdformat@sdf14:src/Link.cc:302-309) and gz-sim's create
service refuses an entity whose SDF has any error
(gazebosim/gz-sim@gz-sim8:src/systems/user_commands/UserCommands.cc:925-930): an error for a
link that survives fixed-joint lumping.
"""

from __future__ import annotations

from collections.abc import Callable

import pytest
from builders import robot

from sensorkit.lint.engine import FileReport

Check = Callable[..., FileReport]

TRIANGLE = '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3"/></inertial>'
NEGATIVE_MASS = '<inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'


def _sk302(report: FileReport) -> list[str]:
    return [f.severity.label for f in report.findings if f.rule == "SK302"]


@pytest.mark.parametrize(
    ("joint_type", "target", "severity"),
    [
        ("revolute", "classic", "warning"),
        ("revolute", "ros1", "warning"),
        ("revolute", "harmonic", "error"),
        ("revolute", "fortress", "error"),
        ("fixed", "harmonic", "warning"),  # lumped into base_link first: not known to be refused
    ],
)
def test_inertia_shape_by_target(check: Check, joint_type: str, target: str, severity: str) -> None:
    report = check(robot(camera_body=TRIANGLE, camera_joint_type=joint_type), target=target)
    assert _sk302(report) == [severity], report.findings


def test_a_negative_mass_stays_an_error_everywhere(check: Check) -> None:
    for target in ("classic", "harmonic"):
        report = check(robot(camera_body=NEGATIVE_MASS, camera_joint_type="revolute"), target=target)
        assert _sk302(report) == ["error"], report.findings


def test_a_classic_cpu_ray_sweeping_backwards_is_a_warning(check: Check) -> None:
    """MultiRayShape.cc:75-93 (gazebo-classic 11.10.2): beam i at min + i * (max - min) /
    (samples - 1), so min above max sweeps the same arc backwards; a gpu_ray (near miss) and
    Gazebo Sim keep the error."""
    from builders import lidar_sensor

    backwards = dict(min_angle="2.2", max_angle="-2.2")
    cpu = check(robot(lidar=lidar_sensor(**backwards)), target="classic")
    gpu = check(robot(lidar=lidar_sensor(stype="gpu_ray", **backwards)), target="classic")
    gz = check(robot(lidar=lidar_sensor(stype="gpu_lidar", tag="lidar", plugin="", **backwards)), target="harmonic")
    sev = lambda r: [f.severity.label for f in r.findings if f.rule == "SK406"]  # noqa: E731
    assert sev(cpu) == ["warning"] and sev(gpu) == ["error"] and sev(gz) == ["error"]
