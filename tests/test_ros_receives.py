"""Issue 35: rules judged by what ROS receives (SK607, SK612, SK605, SK502 on gz), each with
a trigger and a near miss, no corpus needed.

Sources, cited beside the code too:
- ros_gz_bridge creates one bridge per entry of its config_file, for that entry's gz topic
  only (gazebosim/ros_gz@jazzy 739cb42:ros_gz_bridge/src/ros_gz_bridge.cpp:54-62, :88-102):
  a gz topic no entry names never reaches ROS;
- a gazebo_ros plugin in the sensor creates its ROS publisher (ros-simulation/
  gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:189-202,
  gazebo_ros_ray_sensor.cpp:119-133, gazebo_ros_imu_sensor.cpp:95): with none, Gazebo
  Classic publishes nothing to ROS;
- a depth camera's points are computed x-forward, z up (gazebosim/gz-rendering@gz-rendering8
  ff0c5b8:ogre2/src/media/materials/programs/GLSL/depth_camera_fs.glsl:112-113;
  @ign-rendering6 c39b130: :106-107) and stamped with the image's frame
  (gazebosim/gz-sensors@gz-sensors8 c8159af:src/DepthCameraSensor.cc:446-448; @ign-sensors6
  7cfaddf: :553-555).
"""

from __future__ import annotations

from pathlib import Path

from builders import bridge_entry as _entry
from builders import camera_sensor, gz_robot, joint, lidar_sensor, link, robot
from test_consequence_rules import _gz_two_cameras

from sensorkit.base.consequence import UNKNOWN
from sensorkit.base.findings import Severity
from sensorkit.lint.engine import FileReport, Options, validate_file
from sensorkit.loading.launch_facts import LaunchFacts


def _of(report: FileReport, rule: str) -> list:  # type: ignore[type-arg]
    return [f for f in report.findings if f.rule == rule]


SCAN = _entry("/scan", "sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan")
POINTS = ("sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked")
IMAGE = ("sensor_msgs/msg/Image", "gz.msgs.Image")
INFO = ("sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo")


def _validate(tmp_path: Path, text: str, bridge: str | None, *, name: str = "rover.urdf") -> FileReport:
    tmp_path.mkdir(parents=True, exist_ok=True)
    path = tmp_path / name
    path.write_text(text)
    bridges: tuple[str, ...] = ()
    if bridge is not None:
        (tmp_path / "bridge.yaml").write_text(bridge)
        bridges = (str(tmp_path / "bridge.yaml"),)
    report = validate_file(path, Options(target="harmonic", bridges=bridges, launch_facts=LaunchFacts()))
    assert not report.internal_errors and report.error is None, report.error
    return report


# --- SK607 on Gazebo Classic: meant for ROS, or cannot tell -------------------------------


def test_sk607_classic_sensor_without_plugin_where_nothing_says_ros_is_info(check) -> None:
    # No gazebo_ros plugin anywhere and no package.xml: what the author meant is not known.
    bare = robot(camera=camera_sensor(plugin=""), lidar=lidar_sensor(plugin=""))
    found = _of(check(bare, target="classic"), "SK607")
    assert [f.severity for f in found] == [Severity.INFO, Severity.INFO]
    assert "cannot tell" in found[0].message and found[0].consequence.intended is UNKNOWN
    # near miss: the camera's gazebo_ros plugin says the robot is meant for ROS: the lidar
    # that publishes nothing to ROS is an error, stating both values
    found = _of(check(robot(lidar=lidar_sensor(plugin="")), target="classic"), "SK607")
    assert [f.severity for f in found] == [Severity.ERROR]
    assert "libgazebo_ros_camera.so" in found[0].message
    assert "written its data in ROS; the simulator uses nothing" in found[0].message


def test_sk607_classic_ros_package_is_meant_for_ros(tmp_path: Path) -> None:
    pkg = tmp_path / "rover_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text(
        '<?xml version="1.0"?><package format="3"><name>rover_description</name><version>0.0.0</version>'
        "<description>d</description><maintainer email='a@b.c'>a</maintainer><license>MIT</license>"
        "<buildtool_depend>ament_cmake</buildtool_depend></package>"
    )
    path = pkg / "urdf" / "rover.urdf"
    path.write_text(robot(camera=camera_sensor(plugin=""), lidar=lidar_sensor(plugin="")))
    report = validate_file(path, Options(target="classic"))
    found = _of(report, "SK607")
    assert [f.severity for f in found] == [Severity.ERROR, Severity.ERROR]
    assert "ament_cmake" in found[0].message


# --- SK607 on Gazebo Sim: a known bridge ------------------------------------------------


def test_sk607_gz_sensor_no_entry_names_is_an_error_saying_what_the_bridge_carries(tmp_path: Path) -> None:
    report = _validate(tmp_path / "a", gz_robot(), _entry("/front_camera/image_raw", *IMAGE))
    (f,) = _of(report, "SK607")
    assert (f.sensor, f.severity) == ("laser", Severity.ERROR)
    assert "ROS receives nothing from it (the bridge carries /front_camera/image_raw)" in f.message
    # near miss: only the camera's camera_info is bridged, from a YAML with no launch file
    # read: an image_bridge may carry the image, cannot tell (info)
    info_only = _entry("/front_camera/camera_info", *INFO) + SCAN
    (f,) = _of(_validate(tmp_path / "b", gz_robot(), info_only), "SK607")
    assert (f.sensor, f.severity) == ("front_camera", Severity.INFO)
    assert f.consequence is not None and f.consequence.effective is UNKNOWN


# --- SK612: a bridge entry beside an include sensorkit could not read ---------------------

SDF_MODEL = """<?xml version="1.0"?>
<sdf version="1.9">
  <model name="drone">
    {include}
    <link name="base_link">
      <sensor name="cam" type="camera"><topic>cam</topic><gz_frame_id>base_link</gz_frame_id>
        <camera><horizontal_fov>1</horizontal_fov><image><width>320</width><height>240</height></image>
        <clip><near>0.1</near><far>10</far></clip></camera></sensor>
    </link>
  </model>
</sdf>
"""


def test_sk612_is_silent_when_an_unread_include_may_hold_the_sensor(tmp_path: Path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    # ArduPilot/ardupilot_gz iris_with_lidar: its bridge's IMU entry names imu_sensor of
    # model://iris_with_standoffs, another repository's model sensorkit does not read.
    for var in ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH", "GAZEBO_MODEL_PATH"):
        monkeypatch.delenv(var, raising=False)
    bridge = _entry("/cam", *IMAGE) + _entry("/imu", "sensor_msgs/msg/Imu", "gz.msgs.IMU")
    include = "<include merge='true'><uri>model://sk_standoffs</uri></include>"
    report = _validate(tmp_path / "a", SDF_MODEL.format(include=include), bridge, name="model.sdf")
    assert not _of(report, "SK612")
    (inc,) = _of(report, "SK107")
    assert inc.severity is Severity.INFO and "GZ_SIM_RESOURCE_PATH" in inc.message
    # near miss: the same model with no include: the entry names no sensor sensorkit could
    # know of, and what it carries it cannot tell (info, on the consequence model)
    report = _validate(tmp_path / "b", SDF_MODEL.format(include=""), bridge, name="model.sdf")
    (f,) = _of(report, "SK612")
    assert f.severity is Severity.INFO and "'/imu'" in f.message
    assert f.consequence is not None and f.consequence.effective is UNKNOWN


# --- SK605 on gz: a mixed gz topic no bridge entry carries ------------------------------


def test_sk605_gz_topic_no_entry_bridges_is_a_warning(tmp_path: Path) -> None:
    two = _gz_two_cameras(second_fov="1.2")  # different calibrations on /shared/camera_info
    images = _entry("/cam_a/image", *IMAGE) + _entry("/cam_b/image", *IMAGE) + SCAN
    (f,) = _of(_validate(tmp_path / "a", two, images), "SK605")
    assert f.severity is Severity.WARNING and "only gz subscribers get the mixed stream" in f.message
    # near misses: the shared topic is bridged, or no bridge is known: ROS gets it (error)
    bridged = images + _entry("/shared/camera_info", *INFO)
    assert [x.severity for x in _of(_validate(tmp_path / "b", two, bridged), "SK605")] == [Severity.ERROR]
    assert [x.severity for x in _of(_validate(tmp_path / "c", two, None), "SK605")] == [Severity.ERROR]
    # and the same calibration twice stays info, bridged or not
    same = _gz_two_cameras()
    assert [x.severity for x in _of(_validate(tmp_path / "d", same, images), "SK605")] == [Severity.INFO]


# --- SK502 on gz: a depth camera whose bridge carries only its points ---------------------


def _depth(frame: str, extra: str = "") -> str:
    tags = f"<topic>depth</topic><gz_frame_id>{frame}</gz_frame_id>"
    return gz_robot(camera_tags=tags, camera_type="depth_camera", extra=extra)


def test_sk502_points_only_in_an_x_forward_frame_is_info(tmp_path: Path) -> None:
    points = _entry("/depth/points", *POINTS) + SCAN
    (f,) = _of(_validate(tmp_path / "a", _depth("camera_link"), points), "SK502")
    assert f.severity is Severity.INFO and "only its points (/depth/points)" in f.message
    # near misses: the depth image is bridged too, or no bridge is known: ROS may read the
    # image in the wrong frame (error)
    both = points + _entry("/depth", *IMAGE)
    assert [x.severity for x in _of(_validate(tmp_path / "b", _depth("camera_link"), both), "SK502")] == [Severity.ERROR]
    assert [x.severity for x in _of(_validate(tmp_path / "c", _depth("camera_link"), None), "SK502")] == [Severity.ERROR]
    # a frame turned from the sensor (yawed 180 degrees): the points land turned (error)
    turned = link("back_frame") + joint("back_frame_joint", "camera_link", "back_frame", "0 0 0", "0 0 3.14159265")
    found = _of(_validate(tmp_path / "d", _depth("back_frame", turned), points), "SK502")
    assert [x.severity for x in found] == [Severity.ERROR]


def test_sk618_is_silent_too_when_an_unread_include_may_hold_the_sensor(tmp_path: Path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    # '/cma' may be the image of a camera inside the unread include: "did you mean /cam"
    # cannot be known (the same reason as SK612's)
    for var in ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH", "GAZEBO_MODEL_PATH"):
        monkeypatch.delenv(var, raising=False)
    bridge = _entry("/cma", *IMAGE)
    include = "<include merge='true'><uri>model://sk_standoffs</uri></include>"
    report = _validate(tmp_path / "a", SDF_MODEL.format(include=include), bridge, name="model.sdf")
    assert not _of(report, "SK618") and not _of(report, "SK612")
    # near miss: no include: the misspelt entry is said, with "did you mean"
    report = _validate(tmp_path / "b", SDF_MODEL.format(include=""), bridge, name="model.sdf")
    (f,) = _of(report, "SK618")
    assert "did you mean 'cam'" in f.message
