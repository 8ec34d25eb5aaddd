"""Every top-level file of the real-robot corpus: no crash, true findings only."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import CORPUS, REALWORLD, corpus_package_paths, needs_corpus

from sensorkit.base.findings import Severity
from sensorkit.lint.engine import Options, validate_file

pytestmark = needs_corpus

FILES = sorted(
    p for p in CORPUS.rglob("*") if p.suffix in (".urdf", ".xacro", ".sdf") and REALWORLD not in p.parents
)


def test_corpus_is_there() -> None:
    assert len(FILES) > 90


@pytest.mark.parametrize("path", FILES, ids=[str(p.relative_to(CORPUS)) for p in FILES])
def test_no_crash(path: Path) -> None:
    report = validate_file(path)
    assert not report.internal_errors
    assert report.error is None, report.error  # SDF too, .sdf.xacro expanded first (issue 28)
    if path.suffix == ".sdf" or path.name.endswith(".sdf.xacro"):
        assert report.robot is not None and report.robot.sdf is not None and report.robot.links
    for f in report.findings:
        assert f.file and f.message and f.fix, f


def _report(rel: str, **kw: object):  # type: ignore[no-untyped-def]
    report = validate_file(CORPUS / rel, Options(**kw))  # type: ignore[arg-type]
    assert not report.internal_errors and report.error is None
    return report


@pytest.mark.parametrize("path", sorted((CORPUS / "IntelRealSense__realsense-ros").rglob("test_*.urdf.xacro")), ids=lambda p: p.name)
def test_realsense_test_robots_have_no_error(path: Path) -> None:
    report = validate_file(path)
    assert report.robot is not None and len(report.robot.links) > 1  # really expanded via $(find)
    assert [f for f in report.findings if f.severity == Severity.ERROR] == []
    assert {f.rule for f in report.findings} <= {"SK104"}  # meshes are not in the corpus: true


LINOROBOT_ROS1 = {"alwaysOn", "updateRate", "topicName", "bodyName", "frameName", "updateRateHZ", "gaussianNoise", "xyzOffset", "rpyOffset"}


@pytest.mark.parametrize("robot", ["2wd", "4wd", "mecanum", "turtlebot", "vattenkar"])
def test_linorobot2_ros1_tags_reported(robot: str) -> None:
    report = _report(f"linorobot__linorobot2/linorobot2_description/urdf/robots/{robot}.urdf.xacro")
    tags = {f.message.split(">")[0].lstrip("<") for f in report.findings if f.rule == "SK602"}
    assert tags >= LINOROBOT_ROS1
    where = {Path(f.file or "").name for f in report.findings if f.rule == "SK602"}
    assert {"laser.urdf.xacro", "imu.urdf.xacro"} <= where


def test_sam_bot_ros1_tags_reported() -> None:
    report = _report("ros-navigation__navigation2_tutorials/sam_bot_description/src/description/sam_bot_description.urdf")
    tags = {f.message.split(">")[0].lstrip("<") for f in report.findings if f.rule == "SK602"}
    expected = {"alwaysOn", "updateRate", "pointCloudCutoff", "pointCloudCutoffMax", "distortionK1", "distortionK2",
                "distortionK3", "distortionT1", "distortionT2", "CxPrime", "Cx", "Cy", "focalLength", "hackBaseline", "baseline"}
    assert expected <= tags
    assert any("<remap from=" in f.message for f in report.findings if f.rule == "SK602")
    # camera_depth_frame is optical but not named so; base_footprint's mass 0 is lumped (no SK301).
    assert "SK506" in {f.rule for f in report.findings}
    assert "SK301" not in {f.rule for f in report.findings}
    depth = next(s for s in report.robot.sensors if s.name == "depth_camera")  # type: ignore[union-attr]
    assert depth.source.line == 353


def test_turtlebot3_approximate_optical_rotation() -> None:
    report = _report("ROBOTIS-GIT__turtlebot3/turtlebot3_description/urdf/turtlebot3_waffle.urdf")
    joints = {f.joint for f in report.findings if f.rule == "SK505"}
    assert joints == {"camera_rgb_optical_joint", "camera_depth_optical_joint"}


def test_flir_blackfly_under_gz_reports_the_classic_plugin_and_misplaced_frame_tag(tmp_path: Path) -> None:
    pkg = CORPUS / "clearpathrobotics__clearpath_common/clearpath_sensors_description"
    robot = tmp_path / "cam.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find clearpath_sensors_description)/urdf/flir_blackfly.urdf.xacro"/>'
        '<link name="base_link"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'
        '<xacro:flir_blackfly name="cam" parent_link="base_link"><origin xyz="0 0 0" rpy="0 0 0"/></xacro:flir_blackfly>'
        "</robot>"
    )
    report = validate_file(robot, Options(target="fortress", args={"namespace": "r"}, package_paths=(f"clearpath_sensors_description={pkg}",)))
    assert not report.internal_errors and report.error is None, report.error
    rules = {f.rule for f in report.findings}
    assert "SK601" in rules  # libgazebo_ros_camera.so never loads in Gazebo Sim
    assert "SK608" in rules  # <ignition_frame_id> inside <camera> is never read
    assert "SK105" in rules  # <intertial> with <mass values=...>


REAL_FILES = sorted(p for p in REALWORLD.rglob("*") if p.suffix in (".urdf", ".xacro"))


def test_realworld_is_there() -> None:
    assert len(REAL_FILES) > 300


@pytest.mark.parametrize("path", REAL_FILES, ids=[str(p.relative_to(REALWORLD)) for p in REAL_FILES])
def test_no_crash_on_any_realworld_file(path: Path) -> None:
    # Every file on its own, as a user might point validate at it: macro files, files that
    # need args. Findings are expected; a crash or an internal error never is.
    report = validate_file(path, Options(package_paths=corpus_package_paths()))
    assert not report.internal_errors, report.internal_errors
    for f in report.findings:
        assert f.file and f.message and f.fix, f
