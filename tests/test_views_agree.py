"""Issue 35 item 9: ``topics`` and ``frames`` agree with ``validate`` on a robot with a launch
file: the same launch files read (``--launch``), the model name the robot is spawned under
(the MODEL of Gazebo Sim's default frame MODEL::LINK::SENSOR and of scoped topics), and the
bridge node's remappings. Also: ROS 1 absolute topic names are global (not nested under the
camera name), and a sensor whose plugin stamps a frame is never said to "stamp nothing".

The robot and its launch file are built in tmp_path (no ../shared).
"""

from __future__ import annotations

import json
from pathlib import Path

from builders import camera_sensor, gz_robot, robot
from conftest import run_cli

from sensorkit.base.findings import Severity

LAUNCH = """\
<launch>
  <node pkg="ros_gz_bridge" exec="parameter_bridge"
        args="/scan@sensor_msgs/msg/LaserScan[gz.msgs.LaserScan /front_camera/image_raw@sensor_msgs/msg/Image[gz.msgs.Image">
    <remap from="/scan" to="/my_bot/scan"/>
  </node>
  <node pkg="ros_gz_sim" exec="create" args="-name my_bot -topic robot_description"/>
</launch>
"""


def _package(tmp_path: Path) -> tuple[Path, Path]:
    # the lidar has no frame tag: Gazebo Sim stamps it MODEL::base_footprint::laser
    urdf = tmp_path / "rover.urdf"
    urdf.write_text(gz_robot(lidar_tags="<topic>scan</topic>"))
    launch = tmp_path / "sim.launch.xml"
    launch.write_text(LAUNCH)
    return urdf, launch


def test_topics_and_frames_agree_with_validate(tmp_path: Path) -> None:
    urdf, launch = _package(tmp_path)
    common = ("--target", "harmonic", "--launch", str(launch), "-q")
    val = run_cli("validate", str(urdf), *common, "-f", "json")
    assert val.returncode in (0, 1), val.stderr
    sk501 = [f for f in json.loads(val.stdout)["findings"] if f["rule"] == "SK501" and f.get("sensor") == "laser"]
    assert len(sk501) == 1 and sk501[0]["severity"] == Severity.WARNING.label
    stamped = sk501[0]["frame"]
    assert stamped == "my_bot::base_footprint::laser"  # the spawned name, not the URDF's "rover"

    frames = run_cli("frames", str(urdf), *common, "-f", "json")
    assert frames.returncode == 0, frames.stderr
    laser = next(s for s in json.loads(frames.stdout)["sensors"] if s["name"] == "laser")
    assert [t["frame"] for t in laser["frame_ids"]] == [stamped]

    topics = run_cli("topics", str(urdf), *common, "-f", "json")
    assert topics.returncode == 0, topics.stderr
    doc = json.loads(topics.stdout)
    scan = [t for t in doc["topics"] if t["sensor"] == "laser" and t.get("gz_topic") == "/scan"]
    assert len(scan) == 1, doc["topics"]
    # the bridge node's remapping, and the frame validate says the scan is stamped with
    assert scan[0]["topic"] == "/my_bot/scan"
    assert scan[0]["frame_id"] == stamped

    # Near miss: without the launch file (none beside the robot either), MODEL is the
    # URDF's robot name in all three.
    other = tmp_path / "alone"
    other.mkdir()
    alone = other / "rover.urdf"
    alone.write_text(urdf.read_text())
    plain = ("--target", "harmonic", "-q", "-f", "json")
    val = json.loads(run_cli("validate", str(alone), *plain).stdout)
    frame = next(f["frame"] for f in val["findings"] if f["rule"] == "SK501" and f.get("sensor") == "laser")
    assert frame == "rover::base_footprint::laser"
    laser = next(s for s in json.loads(run_cli("frames", str(alone), *plain).stdout)["sensors"] if s["name"] == "laser")
    assert [t["frame"] for t in laser["frame_ids"]] == [frame]


def _topics(path: Path, target: str) -> dict[str, str]:
    from sensorkit.describe.sensorinfo import describe, load
    from sensorkit.describe.topics import robot_topics

    result = robot_topics(describe(load(path), target))
    return {t.role: t.name for t in result.topics if t.name is not None}


def test_ros1_absolute_topic_names_are_global(tmp_path: Path) -> None:
    # ROS 1 camera utils advertise on a NodeHandle in robotNamespace/cameraName
    # (gazebo_ros_pkgs@noetic-devel f9e1a46:gazebo_plugins/src/gazebo_ros_camera_utils.cpp:288,
    # :321-340); a name starting with "/" is global (http://wiki.ros.org/Names).
    params = (
        "<robotNamespace>rover</robotNamespace><cameraName>cam</cameraName>"
        "<imageTopicName>/abs/image_raw</imageTopicName><cameraInfoTopicName>camera_info</cameraInfoTopicName>"
        "<frameName>camera_optical_frame</frameName>"
    )
    path = tmp_path / "r1.urdf"
    path.write_text(robot(camera=camera_sensor(params=params)))
    topics = _topics(path, "ros1")
    assert topics["image"] == "/abs/image_raw"
    # Near miss: a relative name stays under namespace and camera name.
    assert topics["camera_info"] == "/rover/cam/camera_info"


def test_a_plugin_that_stamps_is_never_said_to_stamp_nothing(tmp_path: Path) -> None:
    # A camera plugin sensorkit does not know still stamps its images with some frame.
    path = tmp_path / "unknown.urdf"
    path.write_text(robot(camera=camera_sensor(plugin="libvendor_camera_plugin.so", params="<frame>x</frame>")))
    out = run_cli("frames", str(path), "--target", "classic", "-q")
    assert out.returncode == 0, out.stderr
    line = next(x for x in out.stdout.splitlines() if x.startswith("sensor front_camera"))
    assert "stamps nothing" not in line and "frame_id not known" in line, line
    # Near miss: with no plugin at all, nothing publishes it: it stamps nothing.
    bare = tmp_path / "bare.urdf"
    bare.write_text(robot(camera=camera_sensor(plugin="")))
    out = run_cli("frames", str(bare), "--target", "classic", "-q", "-f", "json")
    cam = next(s for s in json.loads(out.stdout)["sensors"] if s["name"] == "front_camera")
    assert cam["frame_ids"] == [] and cam["stamps_nothing"] is True
