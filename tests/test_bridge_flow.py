"""Issue 35 item 7: bridge entries that carry a sensor's data nowhere (SK617, SK618, SK619),
judged by the consequence model: a sensor whose data reaches ROS by no entry is an error.

Sources: gazebosim/ros_gz@humble 5cc92f8 and @jazzy 739cb42 (cited per case).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from builders import gz_robot
from test_launch_e2e import KINDS, _workspace

from sensorkit.lint.engine import FileReport, Options, validate_file
from sensorkit.loading.launch_facts import LaunchFacts


def _entry(gz: str, ros_type: str, gz_type: str, direction: str = "GZ_TO_ROS") -> str:
    return (
        f"- ros_topic_name: {gz.strip('/')}\n  gz_topic_name: {gz}\n  ros_type_name: {ros_type}\n"
        f"  gz_type_name: {gz_type}\n  direction: {direction}\n"
    )


IMAGE = ("sensor_msgs/msg/Image", "gz.msgs.Image")
INFO = ("sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo")
SCAN = ("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan")


# A launch file that starts the bridge with that YAML as its config_file: what the launch
# files start is then known, and a sensor no entry carries publishes nothing to ROS.
LAUNCH = """\
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([Node(
        package='ros_gz_bridge',
        executable='parameter_bridge',
        parameters=[{{'config_file': '{yaml}'}}],
    )])
"""


def _run(tmp_path: Path, bridge: str, *, launch: bool = True) -> FileReport:
    tmp_path.mkdir(parents=True, exist_ok=True)
    path = tmp_path / "rover.urdf"
    path.write_text(gz_robot())
    yaml = tmp_path / "bridge.yaml"
    yaml.write_text(bridge)
    if launch:
        (tmp_path / "sim.launch.py").write_text(LAUNCH.format(yaml=yaml))
        options = Options(target="harmonic", launch=(str(tmp_path / "sim.launch.py"),))
    else:  # the YAML alone: a launch file may bridge the image some other way
        options = Options(target="harmonic", bridges=(str(yaml),), launch_facts=LaunchFacts())
    report = validate_file(path, options)
    assert not report.internal_errors and report.error is None, report.error
    return report


def _of(report: FileReport, rule: str) -> list:  # type: ignore[type-arg]
    return [f for f in report.findings if f.rule == rule]


# --- SK617: ROS_TO_GZ on a sensor's topic ----------------------------------------------------


def test_ros_to_gz_on_a_sensor_topic_is_an_error(tmp_path: Path) -> None:
    # ROS_TO_GZ creates only the ROS->GZ handle (ros_gz_bridge/src/ros_gz_bridge.cpp:74-110 on
    # humble, :79-104 on jazzy): the image never reaches ROS.
    bridge = _entry("/front_camera/image_raw", *IMAGE, "ROS_TO_GZ") + _entry("/front_camera/camera_info", *INFO) + _entry("/scan", *SCAN)
    f = _of(_run(tmp_path / "a", bridge), "SK617")
    assert [x.severity.label for x in f] == ["error"] and f[0].sensor == "front_camera"
    assert "GZ_TO_ROS" in (f[0].fix or "") and "publishes nothing to ROS" in f[0].message
    # the YAML alone, no launch file read: an image_bridge may carry the image (info)
    f = _of(_run(tmp_path / "b", bridge, launch=False), "SK617")
    assert [x.severity.label for x in f] == ["info"] and "image_bridge" in f[0].message


def test_ros_to_gz_near_misses(tmp_path: Path) -> None:
    # GZ_TO_ROS and BIDIRECTIONAL carry it; a ROS_TO_GZ entry on a topic no sensor publishes
    # (a command topic) is what ROS_TO_GZ is for
    ok = _entry("/front_camera/image_raw", *IMAGE, "BIDIRECTIONAL") + _entry("/scan", *SCAN)
    assert not _of(_run(tmp_path / "a", ok), "SK617")
    cmd = _entry("/front_camera/image_raw", *IMAGE) + _entry("/scan", *SCAN) + _entry("/cmd_vel", "geometry_msgs/msg/Twist", "gz.msgs.Twist", "ROS_TO_GZ")
    assert not _of(_run(tmp_path / "b", cmd), "SK617")
    # another entry carries the same topic to ROS: nothing is lost (info)
    both = _entry("/front_camera/image_raw", *IMAGE, "ROS_TO_GZ") + _entry("/front_camera/image_raw", *IMAGE) + _entry("/scan", *SCAN)
    f = _of(_run(tmp_path / "c", both), "SK617")
    assert [x.severity.label for x in f] == ["info"]


# --- SK618: a misspelt gz topic while a sensor of its type stays unbridged --------------------


def test_misspelt_topic_is_an_error_with_did_you_mean(tmp_path: Path) -> None:
    bridge = _entry("/front_camera/image_rwa", *IMAGE) + _entry("/front_camera/camera_info", *INFO) + _entry("/scan", *SCAN)
    report = _run(tmp_path / "a", bridge)
    f = _of(report, "SK618")
    assert [x.severity.label for x in f] == ["error"]
    assert "did you mean 'front_camera/image_raw'" in f[0].message and f[0].sensor == "front_camera"
    # SK612 does not say the same entry again
    assert not [x for x in _of(report, "SK612") if "image_rwa" in x.message]
    # the YAML alone: another bridge may carry the image (info, as SK607 says of it)
    f = _of(_run(tmp_path / "b", bridge, launch=False), "SK618")
    assert [x.severity.label for x in f] == ["info"]


def test_misspelt_topic_near_misses(tmp_path: Path) -> None:
    # the image is bridged by another entry: the stray entry names nothing, SK612's info
    stray = _entry("/front_camera/image_rwa", *IMAGE) + _entry("/front_camera/image_raw", *IMAGE) + _entry("/scan", *SCAN)
    report = _run(tmp_path / "a", stray)
    assert not _of(report, "SK618") and [x.severity.label for x in _of(report, "SK612")] == ["info"]
    # another message type (a LaserScan entry cannot be meant for the camera's image)
    other = _entry("/front_camera/image_rwa", *SCAN) + _entry("/scan", *SCAN)
    assert not _of(_run(tmp_path / "b", other), "SK618")


# --- SK619: a parameter_bridge that exits on one bad argument --------------------------------


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_a_bad_bridge_argument_kills_the_whole_bridge(tmp_path: Path, kind: str) -> None:
    # "@sensor_msgs/msg/LaserScan[gz.msgs.LaserScan": the '@' at 0 makes parameter_bridge print
    # its usage and return -1 (ros_gz_bridge/src/parameter_bridge.cpp:92-98, humble and jazzy),
    # before rclcpp::spin (:173): the camera's entries, well formed, do not exist either.
    report = validate_file(_workspace(tmp_path, kind, scan=""), Options(target="harmonic"))
    assert not report.internal_errors and report.error is None
    f = _of(report, "SK619")
    assert [x.severity.label for x in f] == ["error"], report.findings
    # the laser's own entry is the bad argument; the camera's well-formed entries die with it
    assert "sensor 'front_camera' publishes nothing to ROS" in f[0].message
    assert f[0].file is not None and f[0].file.endswith(KINDS[kind][0])


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_a_well_formed_bridge_is_alive(tmp_path: Path, kind: str) -> None:
    report = validate_file(_workspace(tmp_path, kind), Options(target="harmonic"))
    assert not _of(report, "SK619") and not _of(report, "SK607")


def test_a_bad_bridge_argument_on_an_sdf_model(tmp_path: Path) -> None:
    # The same parameter_bridge exit (parameter_bridge.cpp:92-98) for a model read from SDF.
    here = Path(__file__).parent / "robots" / "sdf" / "sensors"
    launch = tmp_path / "sim.launch.py"
    bad = KINDS["py"][1].format(scan="", name="m", tf="").replace("/front_camera/image_raw", "/cam")
    launch.write_text(bad)
    report = validate_file(here / "bridged.sdf", Options(target="harmonic", launch=(str(launch),)))
    f = _of(report, "SK619")
    assert [x.severity.label for x in f] == ["error"] and "'cam'" in f[0].message
    # near miss: the well-formed bridge carries cam
    launch.write_text(KINDS["py"][1].format(scan="/scan", name="m", tf="").replace("/front_camera/image_raw", "/cam"))
    report = validate_file(here / "bridged.sdf", Options(target="harmonic", launch=(str(launch),)))
    assert not _of(report, "SK619")
