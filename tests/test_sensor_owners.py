"""Sensors read by a model-level plugin (sensorkit.model.owners), SK607 and `topics` alike.

The ownership is data in sensorkit/knowledge/plugins.py (PluginSpec.owns, HARDWARE_SIMS);
each case cites the source line it pins.
"""

from __future__ import annotations

from pathlib import Path

from builders import camera_sensor, robot
from conftest import rules_of

from sensorkit.describe.sensorinfo import describe, load
from sensorkit.knowledge.plugins import HARDWARE_SIMS, lookup

IMU = (
    '<gazebo reference="base_link"><sensor name="{name}" type="imu">'
    "<update_rate>50</update_rate></sensor></gazebo>"
)


def _sk607(report, sensor: str):  # type: ignore[no-untyped-def]
    return [f for f in report.findings if f.rule == "SK607" and f.sensor == sensor]


def _realsense(prefix: str) -> str:
    return (
        '<gazebo><plugin name="rs" filename="librealsense_gazebo_plugin.so">'
        f"<prefix>{prefix}</prefix><colorTopicName>rs/color/image_raw</colorTopicName></plugin></gazebo>"
    )


# --- realsense_gazebo_plugin: <prefix> + color|depth|ired1|ired2 --------------------------


def test_realsense_reads_prefix_plus_stream_name(check) -> None:
    # SensorManager::GetSensor(prefix + "color") etc.
    # (pal-robotics/realsense_gazebo_plugin@melodic-devel 49ab134:src/RealSensePlugin.cpp:135-147;
    # @foxy-devel 73b3061:src/RealSensePlugin.cpp:139-149; names: include/.../RealSensePlugin.h:32-35),
    # matched on the sensor's leaf name
    # (elysia-best/gazebo-classic@upstream/11.10.2+dfsg:gazebo/sensors/SensorManager.cc:550-561, :885)
    bare = camera_sensor(name="rs_color", plugin="")
    for target in ("classic", "ros1"):
        assert not _sk607(check(robot(camera=bare, extra=_realsense("rs_")), target=target), "rs_color")
    # near miss: another prefix reads rs2_color, not rs_color
    f = _sk607(check(robot(camera=bare, extra=_realsense("rs2_")), target="classic"), "rs_color")
    assert [x.severity.label for x in f] == ["error"]


def test_realsense_does_not_read_a_sensor_it_merely_names(check) -> None:
    # Load() throws on a parameter it does not know (RealSensePlugin.cpp:119-120, melodic-devel):
    # <colorCameraName> names no sensor it reads; only prefix + stream does.
    bare = camera_sensor(plugin="")
    model = '<gazebo><plugin name="rs" filename="librealsense_gazebo_plugin.so"><colorCameraName>front_camera</colorCameraName></plugin></gazebo>'
    assert _sk607(check(robot(camera=bare, extra=model), target="classic"), "front_camera")


# --- gazebo_ros_control (ROS 1): what its <robotSimType> reads ------------------------------


def _ros_control(sim_type: str | None) -> str:
    tag = f"<robotSimType>{sim_type}</robotSimType>" if sim_type else ""
    return f'<gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">{tag}</plugin></gazebo>'


def test_pal_hardware_gazebo_may_read_any_imu_so_sk607_is_info(check) -> None:
    # PalHardwareGazebo reads the IMUs named by the ROS parameters imu/<id>/gazebo_sensor_name
    # (pal-robotics/pal_hardware_gazebo@melodic-devel 320e672:src/pal_hardware_gazebo.cpp:263-280),
    # which no URDF holds: sensorkit cannot tell, so it says so (info), not "publishes nothing".
    assert HARDWARE_SIMS["pal_hardware_gazebo/PalHardwareGazebo"] is not None
    extra = IMU.format(name="base_imu") + _ros_control("pal_hardware_gazebo/PalHardwareGazebo")
    f = _sk607(check(robot(extra=extra), target="ros1"), "base_imu")
    assert [x.severity.label for x in f] == ["info"] and "cannot tell" in f[0].message
    assert "pal_hardware_gazebo.cpp:263-280" in f[0].message
    # near miss: it reads IMUs only (force-torque comes from a joint, :175-181), so a bare
    # camera still publishes nothing
    cam = camera_sensor(plugin="")
    f = _sk607(check(robot(camera=cam, extra=_ros_control("pal_hardware_gazebo/PalHardwareGazebo")), target="ros1"), "front_camera")
    assert [x.severity.label for x in f] == ["error"]


def test_default_robot_hw_sim_reads_no_sensor(check) -> None:
    # <robotSimType> defaults to DefaultRobotHWSim (ros-simulation/gazebo_ros_pkgs@noetic-devel
    # f9e1a46:gazebo_ros_control/src/gazebo_ros_control_plugin.cpp:105-111), which looks up no
    # sensor (default_robot_hw_sim.cpp): the bare IMU publishes nothing to ROS, which the
    # gazebo_ros plugins show it is meant for (error, issue 35).
    assert HARDWARE_SIMS["gazebo_ros_control/DefaultRobotHWSim"] is None
    for sim in (None, "gazebo_ros_control/DefaultRobotHWSim"):
        f = _sk607(check(robot(extra=IMU.format(name="imu") + _ros_control(sim)), target="ros1"), "imu")
        assert [x.severity.label for x in f] == ["error"]


def test_unknown_robot_sim_type_is_not_assumed_either_way(check) -> None:
    # An unknown class is created by name (gazebo_ros_control_plugin.cpp:181) and may read
    # sensors: not "reads it", not "publishes nothing", but info that sensorkit cannot tell.
    extra = IMU.format(name="imu") + _ros_control("acme_hw/AcmeRobotHWSim")
    f = _sk607(check(robot(extra=extra), target="ros1"), "imu")
    assert [x.severity.label for x in f] == ["info"] and "acme_hw/AcmeRobotHWSim" in f[0].message
    spec = lookup("libgazebo_ros_control.so", "ros1")
    assert spec is not None and spec.owner_class_param == "robotSimType"


# --- gazebo_ros2_control: <ros2_control><sensor name>, IMU and force-torque -----------------


def test_ros2_control_reads_imu_and_force_torque_by_name_only(check) -> None:
    # ros-controls/gazebo_ros2_control@humble 42d875b:gazebo_ros2_control/src/gazebo_system.cpp:
    # 578 (s->Name() != sensor_name), 608 (imu), 619 (force_torque)
    spec = lookup("libgazebo_ros2_control.so", "ros2")
    assert spec is not None and spec.owns is not None
    assert spec.owns.sensor_types == frozenset({"imu", "force_torque"})
    control = (
        '<ros2_control name="s" type="system"><hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>'
        '<sensor name="front_camera"/></ros2_control>'
        '<gazebo><plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control"/></gazebo>'
    )
    # a camera named in <ros2_control> is not read (only imu / force_torque are)
    f = _sk607(check(robot(camera=camera_sensor(plugin=""), extra=control), target="classic"), "front_camera")
    assert [x.severity.label for x in f] == ["error"]


# --- `sensorkit topics` agrees with SK607 ---------------------------------------------------


def _notes(tmp_path: Path, text: str, target: str, sensor: str) -> list[str]:
    path = tmp_path / "r.urdf"
    path.write_text(text)
    info = describe(load(path), target)
    return next(s.topic_notes for s in info.sensors if s.name == sensor)


def test_topics_view_names_the_owner_not_publishes_nothing(tmp_path: Path) -> None:
    bare = camera_sensor(name="rs_color", plugin="")
    owned = _notes(tmp_path, robot(camera=bare, extra=_realsense("rs_")), "classic", "rs_color")
    assert owned and "publishes nothing" not in owned[0] and "librealsense_gazebo_plugin.so" in owned[0]
    maybe = _notes(tmp_path, robot(extra=IMU.format(name="imu") + _ros_control("acme_hw/AcmeRobotHWSim")), "ros1", "imu")
    assert maybe and "cannot tell" in maybe[0]
    alone = _notes(tmp_path, robot(camera=bare), "classic", "rs_color")
    assert alone and "publishes nothing" in alone[0]


# --- Gazebo Sim: a camera_info bridged without its image ------------------------------------

INFO_ENTRY = """- ros_topic_name: front_camera/camera_info
  gz_topic_name: front_camera/camera_info
  ros_type_name: sensor_msgs/msg/CameraInfo
  gz_type_name: gz.msgs.CameraInfo
  direction: GZ_TO_ROS
"""
IMAGE_ENTRY = INFO_ENTRY.replace("camera_info", "image_raw").replace("CameraInfo", "Image")
SCAN_ENTRY = """- ros_topic_name: scan
  gz_topic_name: scan
  ros_type_name: sensor_msgs/msg/LaserScan
  gz_type_name: gz.msgs.LaserScan
  direction: GZ_TO_ROS
"""


def _gz(tmp_path: Path, bridge: str | None, camera_tags: str | None = None):  # type: ignore[no-untyped-def]
    from builders import gz_robot

    from sensorkit.lint.engine import Options, validate_file

    tmp_path.mkdir(parents=True, exist_ok=True)
    path = tmp_path / "rover.urdf"
    path.write_text(gz_robot(camera_tags=camera_tags))
    bridges: tuple[str, ...] = ()
    if bridge is not None:
        (tmp_path / "bridge.yaml").write_text(bridge)
        bridges = (str(tmp_path / "bridge.yaml"),)
    report = validate_file(path, Options(target="harmonic", bridges=bridges))
    assert not report.internal_errors and report.error is None, report.error
    return report


def test_gz_camera_info_bridged_without_its_image_is_info(tmp_path: Path) -> None:
    # gz-sensors' camera publishes the image on <topic> and camera_info beside it
    # (sensorkit.lint.rules.topic_names.gz_topics): a bridge carrying only camera_info
    # leaves ROS without the image, unless a launch file bridges it with ros_gz_image's
    # image_bridge, as MOGI-ROS/Week-9-10-Simple-arm@425c335:bme_ros2_simple_arm/launch/
    # spawn_robot.launch.py:133-138 does (sensorkit reads no launch file): info, not warning.
    f = _sk607(_gz(tmp_path, INFO_ENTRY + SCAN_ENTRY), "front_camera")
    assert [x.severity.label for x in f] == ["info"]
    assert "camera_info" in f[0].message and "/front_camera/image_raw" in f[0].message


def test_gz_image_bridged_or_no_bridge_known_is_quiet(tmp_path: Path) -> None:
    assert not _sk607(_gz(tmp_path / "a", IMAGE_ENTRY + SCAN_ENTRY), "front_camera")
    assert not _sk607(_gz(tmp_path / "b", IMAGE_ENTRY + INFO_ENTRY + SCAN_ENTRY), "front_camera")
    # neither bridged and no bridge known: a sensor with a <topic> gets nothing
    assert "SK607" not in rules_of(_gz(tmp_path / "c", None))


def test_gz_scoped_camera_info_bridged_without_its_image_is_info(tmp_path: Path) -> None:
    scoped = INFO_ENTRY.replace(
        "gz_topic_name: front_camera/camera_info",
        "gz_topic_name: /world/w/model/m/link/base_link/sensor/front_camera/camera_info",
    )
    tags = "<gz_frame_id>camera_optical_frame</gz_frame_id>"
    f = _sk607(_gz(tmp_path / "a", scoped + SCAN_ENTRY, tags), "front_camera")
    assert [x.severity.label for x in f] == ["info"] and "camera_info" in f[0].message
    both = scoped + scoped.replace("camera_info", "image").replace("CameraInfo", "Image")
    assert not _sk607(_gz(tmp_path / "b", both + SCAN_ENTRY, tags), "front_camera")
