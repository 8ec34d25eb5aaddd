"""Issue 35 items 4 and 5: model-level plugins sensorkit does not know, plugins that look up a
link lumping removed (SK616), and the ROS generation a package.xml says.

Each case cites the source line it pins.
"""

from __future__ import annotations

from pathlib import Path

from builders import camera_sensor, gz_robot, robot

from sensorkit.knowledge.link_lookups import lookups_of
from sensorkit.lint.engine import Options, validate_file

IMU = '<gazebo reference="{link}"><sensor name="{name}" type="imu"><update_rate>50</update_rate>{extra}</sensor></gazebo>'


def _of(report, rule: str, sensor: str | None = None):  # type: ignore[no-untyped-def]
    return [f for f in report.findings if f.rule == rule and (sensor is None or f.sensor == sensor)]


def _ros1_imu(body: str) -> str:
    return (
        '<gazebo><plugin name="imu_plugin" filename="libgazebo_ros_imu.so">'
        f"<bodyName>{body}</bodyName><topicName>imu</topicName><updateRate>50</updateRate></plugin></gazebo>"
    )


# --- SK616: a known plugin's body link that lumping removed ----------------------------------


def test_ros1_imu_body_lumped_away_is_an_error(check) -> None:
    # ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a46:gazebo_plugins/src/gazebo_ros_imu.cpp:
    # 151-162: world_->EntityByName(<bodyName>); no link -> "bodyName: %s does not exist", return:
    # the IMU never publishes. laser_link hangs on a fixed joint: lumping merges it into its parent.
    f = _of(check(robot(extra=_ros1_imu("laser_link")), target="ros1"), "SK616")
    assert [x.severity.label for x in f] == ["error"]
    assert "laser_link" in f[0].message and "gazebo_ros_imu.cpp:151-162" in f[0].message
    assert f[0].consequence is not None and f[0].consequence.effective is None
    assert "preserveFixedJoint" in (f[0].fix or "")


def test_ros1_imu_body_kept_is_quiet(check) -> None:
    # near misses: a link on a moving joint survives; a preserved fixed joint keeps its child;
    # the ROS 2 target reads no <bodyName> (gazebo_ros_imu is ROS 1 only)
    moving = robot(camera_joint_type="revolute", extra=_ros1_imu("camera_link"))
    assert not _of(check(moving, target="ros1"), "SK616")
    kept = _ros1_imu("laser_link") + '<gazebo reference="laser_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
    assert not _of(check(robot(extra=kept), target="ros1"), "SK616")
    assert not _of(check(robot(extra=_ros1_imu("no_such_link")), target="ros1"), "SK616")
    assert not _of(check(robot(extra=_ros1_imu("laser_link")), target="harmonic"), "SK616")


def test_p3d_and_ft_sensor_lookups() -> None:
    # noetic-devel f9e1a46: gazebo_ros_p3d.cpp:73-79 (bodyName), :171-184 (frameName),
    # gazebo_ros_ft_sensor.cpp:75-80 (jointName); ros2 d52f7c4: gazebo_ros_p3d.cpp:118-124,
    # gazebo_ros_ft_sensor.cpp:115-126 (body_name), :129-140 (joint_name, only without body_name)
    assert {x.param for x in lookups_of("libgazebo_ros_p3d.so", "ros1")} == {"bodyName", "frameName"}
    assert {x.param for x in lookups_of("libgazebo_ros_ft_sensor.so", "ros2")} == {"body_name", "joint_name"}
    assert not lookups_of("libgazebo_ros_imu.so", "ros2")
    # tu-darmstadt-ros-pkg/hector_gazebo@melodic-devel de947fb:hector_gazebo_plugins/src/
    # gazebo_ros_imu.cpp:80-96, gazebo_ros_gps.cpp:75-89, gazebo_ros_magnetic.cpp:75-90
    for lib in ("libhector_gazebo_ros_imu.so", "libhector_gazebo_ros_gps.so", "libhector_gazebo_ros_magnetic.so"):
        assert [x.param for x in lookups_of(lib, "ros1")] == ["bodyName"]


def test_ros2_ft_sensor_joint_lumped_away(check) -> None:
    ft = '<gazebo><plugin name="ft" filename="libgazebo_ros_ft_sensor.so"><joint_name>{j}</joint_name>{b}</plugin></gazebo>'
    f = _of(check(robot(extra=ft.format(j="laser_joint", b="")), target="classic"), "SK616")
    assert [x.severity.label for x in f] == ["error"] and "fixed joint 'laser_joint'" in f[0].message
    # near miss: with <body_name> the joint is never looked up (gazebo_ros_ft_sensor.cpp:115-129)
    with_body = ft.format(j="laser_joint", b="<body_name>base_footprint</body_name>")
    assert not _of(check(robot(extra=with_body), target="classic"), "SK616")


def test_p3d_world_frame_looks_up_nothing(check) -> None:
    p3d = '<gazebo><plugin name="gt" filename="libgazebo_ros_p3d.so"><bodyName>base_footprint</bodyName><frameName>{f}</frameName><topicName>gt</topicName></plugin></gazebo>'
    assert not _of(check(robot(extra=p3d.format(f="world")), target="ros1"), "SK616")
    f = _of(check(robot(extra=p3d.format(f="laser_link")), target="ros1"), "SK616")
    assert [x.severity.label for x in f] == ["error"] and "gazebo_ros_p3d.cpp:171-184" in f[0].message


# --- item 4: a sensor an unknown plugin or a <ros2_control> block names: cannot tell --------

ARDUPILOT = (
    '<gazebo><plugin name="ArduPilotPlugin" filename="ArduPilotPlugin">'
    "<imuName>{imu}</imuName><fdm_addr>127.0.0.1</fdm_addr></plugin></gazebo>"
)
SCAN_ENTRY = """- ros_topic_name: scan
  gz_topic_name: scan
  ros_type_name: sensor_msgs/msg/LaserScan
  gz_type_name: gz.msgs.LaserScan
  direction: GZ_TO_ROS
"""


def _gz_with(tmp_path: Path, extra: str):  # type: ignore[no-untyped-def]
    tmp_path.mkdir(parents=True, exist_ok=True)
    path = tmp_path / "rover.urdf"
    imu = IMU.format(link="base_link", name="imu_sensor", extra="<topic>imu</topic>")
    path.write_text(gz_robot(extra=imu + extra))
    (tmp_path / "bridge.yaml").write_text(SCAN_ENTRY)
    report = validate_file(path, Options(target="harmonic", bridges=(str(tmp_path / "bridge.yaml"),)))
    assert not report.internal_errors and report.error is None
    return report


def test_gz_sensor_an_unknown_plugin_names_is_cannot_tell(tmp_path: Path) -> None:
    # ArduPilot/ardupilot_gazebo@main 082a0fe:src/ArduPilotPlugin.cc:807-812 reads <imuName>
    # and subscribes to that IMU (:1111-1187): its data may reach ROS another way (info).
    f = _of(_gz_with(tmp_path / "a", ARDUPILOT.format(imu="imu_sensor")), "SK607", "imu_sensor")
    assert [x.severity.label for x in f] == ["info"] and "cannot tell" in f[0].message
    # near miss: it names another IMU: the known bridge carries nothing of the sensor to ROS
    # (ros_gz_bridge bridges its entries only: gazebosim/ros_gz@jazzy 739cb42:ros_gz_bridge/
    # src/ros_gz_bridge.cpp:54-62): an error (issue 35)
    f = _of(_gz_with(tmp_path / "b", ARDUPILOT.format(imu="other_imu")), "SK607", "imu_sensor")
    assert [x.severity.label for x in f] == ["error"]


def _control(cls: str, plugin: str = "libgazebo_ros2_control.so") -> str:
    return (
        f'<ros2_control name="s" type="system"><hardware><plugin>{cls}</plugin></hardware>'
        '<sensor name="front_camera"/></ros2_control>'
        + (f'<gazebo><plugin filename="{plugin}" name="control"/></gazebo>' if plugin else "")
    )


def test_ros2_control_fork_or_custom_class_is_cannot_tell(check) -> None:
    # gazebo_ros2_control loads each block's <hardware><plugin> class by pluginlib
    # (ros-controls/gazebo_ros2_control@humble 42d875b:gazebo_ros2_control/src/
    # gazebo_ros2_control_plugin.cpp:301-310); only GazeboSystem's reading is known
    # (gazebo_system.cpp:568-619: IMU and force-torque).
    bare = camera_sensor(plugin="")
    for extra in (
        _control("acme_hw/AcmeGazeboSystem"),  # a class of the project's own
        _control("gazebo_ros2_control/GazeboSystem", "libacme_ros2_control.so"),  # a fork's plugin
        _control("gazebo_ros2_control/GazeboSystem", ""),  # a block no plugin sensorkit knows loads
    ):
        for target in ("classic", "ros1"):
            f = _of(check(robot(camera=bare, extra=extra), target=target), "SK607", "front_camera")
            assert [x.severity.label for x in f] == ["info"], (extra, target, f)
    # near miss: the known class on the known plugin reads no camera: nothing publishes it to
    # ROS, which the robot's gazebo_ros plugins show it is meant for (error, issue 35)
    f = _of(check(robot(camera=bare, extra=_control("gazebo_ros2_control/GazeboSystem")), target="classic"), "SK607", "front_camera")
    assert [x.severity.label for x in f] == ["error"]


# --- item 5: --target auto weighs package.xml --------------------------------------------------

PACKAGE = """<?xml version="1.0"?>
<package format="3"><name>rover_description</name><version>0.1.0</version>
<description>d</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>
{tools}</package>
"""
# A ROS 2 camera plugin with its <ros> block, as macros copied from a ROS 2 package hold.
ROS2_CAMERA = camera_sensor(params="<ros><namespace>rover</namespace></ros><frame_name>camera_optical_frame</frame_name>")


def _auto(tmp_path: Path, tools: str | None, text: str):  # type: ignore[no-untyped-def]
    pkg = tmp_path / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    if tools is not None:
        (pkg / "package.xml").write_text(PACKAGE.format(tools=tools))
    path = pkg / "urdf" / "rover.urdf"
    path.write_text(text)
    report = validate_file(path, Options(target="auto"))
    assert not report.internal_errors and report.error is None
    return report


def test_catkin_package_is_ros1_even_with_ros2_blocks(tmp_path: Path) -> None:
    text = robot(camera=ROS2_CAMERA)
    assert "<ros>" in text
    r = _auto(tmp_path / "a", "<buildtool_depend>catkin</buildtool_depend>", text)
    assert r.target == "ros1" and "catkin" in r.target_reason and "package.xml" in r.target_reason
    # near misses: an ament package, no package, a package built for both generations
    r = _auto(tmp_path / "b", "<buildtool_depend>ament_cmake</buildtool_depend>", text)
    assert r.target == "classic" and "ament_cmake" in r.target_reason
    r = _auto(tmp_path / "c", None, text)
    assert r.target == "classic" and "package.xml" not in r.target_reason
    both = (
        '<buildtool_depend condition="$ROS_VERSION == 1">catkin</buildtool_depend>'
        '<buildtool_depend condition="$ROS_VERSION == 2">ament_cmake</buildtool_depend>'
    )
    r = _auto(tmp_path / "d", both, text)
    assert r.target == "classic" and "package.xml" not in r.target_reason


def test_ament_python_build_type_and_gz_evidence(tmp_path: Path) -> None:
    r = _auto(tmp_path / "a", "<export><build_type>ament_python</build_type></export>", robot())
    assert r.target == "classic" and "ament_python" in r.target_reason
    # Gazebo Sim evidence still wins over a catkin package (ROS 1 with Ignition, osrf/subt)
    r = _auto(tmp_path / "b", "<buildtool_depend>catkin</buildtool_depend>", gz_robot())
    assert r.target in ("fortress", "harmonic", "jetty")
