"""The rules that read what a robot's launch files say (issue 24): SK607, SK614, SK501, SK615.

The launch facts are built here directly (sensorkit.loading.launch_facts), as the launch
reader would fill them from launch files modelled on real simulation packages:
turtlebot/turtlebot4_simulator@humble a238c94:turtlebot4_ignition_bringup/launch/
ros_ign_bridge.launch.py:88-99 bridges the lidar's scoped topic as parameter_bridge
arguments and remaps it to "scan"; turtlebot4_spawn.launch.py:148 spawns the robot with
``-name robot_name`` and :206-212 puts its default lidar frame in TF with a
static_transform_publisher ('rplidar_link' -> [robot_name, '/rplidar_link/rplidar']).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from builders import gz_robot

from sensorkit.base.errors import UsageError
from sensorkit.base.findings import SourceRef
from sensorkit.lint.engine import FileReport, Options, validate_file
from sensorkit.loading.bridge import BridgeTopic
from sensorkit.loading.launch_facts import LaunchFacts, Spawn, StaticTransform

LAUNCH = "launch/sim.launch.py"


def _entry(gz: str, ros_type: str, gz_type: str | None, *, file: str = LAUNCH, line: int = 20) -> BridgeTopic:
    return BridgeTopic(gz=gz, ros=gz, ros_type=ros_type, direction="GZ_TO_ROS", file=file, line=line, gz_type=gz_type)


SCAN = _entry("scan", "sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan")
IMAGE = _entry("front_camera/image_raw", "sensor_msgs/msg/Image", "gz.msgs.Image", line=21)
INFO = _entry("front_camera/camera_info", "sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo", line=22)


def _facts(*bridges: BridgeTopic, **kw: object) -> LaunchFacts:
    return LaunchFacts(files=[LAUNCH], bridges=list(bridges), **kw)  # type: ignore[arg-type]


def _run(
    tmp_path: Path,
    launch: LaunchFacts | None,
    *,
    bridge_text: str | None = None,
    extra: str = "",
    **tags: str,
) -> FileReport:
    tmp_path.mkdir(parents=True, exist_ok=True)
    path = tmp_path / "rover.urdf"
    path.write_text(gz_robot(extra=extra, **tags))  # type: ignore[arg-type]
    bridges: tuple[str, ...] = ()
    if bridge_text is not None:
        (tmp_path / "bridge.yaml").write_text(bridge_text)
        bridges = (str(tmp_path / "bridge.yaml"),)
    report = validate_file(path, Options(target="harmonic", bridges=bridges, launch_facts=launch))
    assert not report.internal_errors and report.error is None, (report.internal_errors, report.error)
    return report


def _of(report: FileReport, rule: str, sensor: str | None = None) -> list:  # type: ignore[type-arg]
    return [f for f in report.findings if f.rule == rule and sensor in (None, f.sensor)]


# --- SK607: bridged from a launch file ------------------------------------------------


def test_sk607_launch_bridge_counts_as_bridged(tmp_path: Path) -> None:
    report = _run(tmp_path, _facts(SCAN, IMAGE, INFO))
    assert not _of(report, "SK607")
    # Near miss: the launch bridges the camera only: the lidar is reported, naming the launch.
    # ROS receives nothing of it (ros_gz_bridge bridges its entries only: gazebosim/ros_gz@
    # jazzy 739cb42:ros_gz_bridge/src/ros_gz_bridge.cpp:54-62): an error (issue 35).
    miss = _of(_run(tmp_path / "b", _facts(IMAGE, INFO)), "SK607")
    assert [f.sensor for f in miss] == ["laser"] and miss[0].severity.label == "error"
    assert LAUNCH in miss[0].message


def test_sk607_unreadable_launch_bridge_is_info_never_not_bridged(tmp_path: Path) -> None:
    report = _run(tmp_path, _facts(IMAGE, INFO, bridge_unknown=True))
    sk607 = _of(report, "SK607")
    assert [f.sensor for f in sk607] == ["laser"] and sk607[0].severity.label == "info"
    assert "could not be read" in sk607[0].message
    # Near miss: the same launch read fully says the lidar is not bridged (error, issue 35).
    assert _of(_run(tmp_path / "b", _facts(IMAGE, INFO)), "SK607")[0].severity.label == "error"
    # issue 38: of several launch files read, the one whose bridge could not be read is named
    facts = LaunchFacts(files=[LAUNCH, "other.launch.py"], bridges=[IMAGE, INFO],
                        bridge_unknown=True, bridge_unknown_in=["other.launch.py"])  # fmt: skip
    (f,) = _of(_run(tmp_path / "c", facts), "SK607")
    assert "a bridge started in other.launch.py could not be read" in f.message, f.message


def test_sk607_camera_info_only_is_an_error_when_the_launch_bridges_are_known(tmp_path: Path) -> None:
    # The YAML carries the camera_info, the launch the scan: nothing carries the image, so
    # ROS receives no image (issue 35: a sensor that publishes nothing to ROS is an error).
    yaml_info = (
        "- gz_topic_name: front_camera/camera_info\n  ros_topic_name: front_camera/camera_info\n"
        "  ros_type_name: sensor_msgs/msg/CameraInfo\n  gz_type_name: gz.msgs.CameraInfo\n"
        "  direction: GZ_TO_ROS\n"
    )
    sk607 = _of(_run(tmp_path, _facts(SCAN), bridge_text=yaml_info), "SK607")
    assert [(f.sensor, f.severity.label) for f in sk607] == [("front_camera", "error")]
    # Near misses: the launch's bridge carries the image (silent); no launch known (info,
    # an image_bridge may carry it: MOGI-ROS/Week-9-10-Simple-arm@425c335, see bridge.py).
    assert not _of(_run(tmp_path / "b", _facts(SCAN, IMAGE), bridge_text=yaml_info), "SK607")
    scan_yaml = yaml_info + (
        "- gz_topic_name: scan\n  ros_topic_name: scan\n  ros_type_name: sensor_msgs/msg/LaserScan\n"
        "  gz_type_name: gz.msgs.LaserScan\n  direction: GZ_TO_ROS\n"
    )
    info = _of(_run(tmp_path / "c", None, bridge_text=scan_yaml), "SK607")
    assert [(f.sensor, f.severity.label) for f in info] == [("front_camera", "info")]


# --- SK614: the launch bridges a depth camera's cloud ---------------------------------


def test_sk614_when_the_launch_bridges_the_cloud(tmp_path: Path) -> None:
    # gz-sensors computes the cloud x-forward and stamps it with the optical frame
    # (gz-sensors#488, sensorkit/knowledge/gazebo_sim.py GZ_XFORWARD_CLOUD_NOTE).
    cloud = _entry("front_camera/image_raw/points", "sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked")
    report = _run(tmp_path, _facts(SCAN, cloud), camera_type="depth_camera")
    assert [f.sensor for f in _of(report, "SK614")] == ["front_camera"]
    # Near miss: the launch bridges the depth image only.
    assert not _of(_run(tmp_path / "b", _facts(SCAN, IMAGE), camera_type="depth_camera"), "SK614")


# --- SK501: gz default frames and the launch -------------------------------------------

NO_FRAME_LIDAR = "<topic>scan</topic>"


def _stf(parent: str, child: str) -> StaticTransform:
    return StaticTransform(parent, child, SourceRef(LAUNCH, 30))


def _spawn(name: str | None) -> Spawn:
    return Spawn("ros_gz_sim create", name, "robot_description", None, SourceRef(LAUNCH, 40))


def test_sk501_static_transform_supplies_the_default_frame(tmp_path: Path) -> None:
    facts = _facts(SCAN, IMAGE, INFO, static_transforms=[_stf("laser_link", "tb/base_footprint/laser")], spawns=[_spawn("tb")])
    assert not _of(_run(tmp_path, facts, lidar_tags=NO_FRAME_LIDAR), "SK501")
    # Near miss: the static transform names the URDF's robot name, but the launch spawns
    # the robot as "tb": the frame is tb/base_footprint/laser, which TF does not have.
    other = _facts(SCAN, static_transforms=[_stf("laser_link", "rover/base_footprint/laser")], spawns=[_spawn("tb")])
    sk501 = _of(_run(tmp_path / "b", other, lidar_tags=NO_FRAME_LIDAR), "SK501")
    assert len(sk501) == 1 and sk501[0].severity.label == "warning"
    assert sk501[0].frame == "tb::base_footprint::laser"


def test_sk501_spawn_name_replaces_the_urdf_robot_name(tmp_path: Path) -> None:
    sk501 = _of(_run(tmp_path, _facts(SCAN, spawns=[_spawn("my_bot")]), lidar_tags=NO_FRAME_LIDAR), "SK501")
    assert sk501[0].frame == "my_bot::base_footprint::laser" and "'my_bot/base_footprint/laser'" in sk501[0].message
    assert "as launch/sim.launch.py spawns it" in sk501[0].message
    # Near miss: no spawn known: MODEL is the URDF's robot name, said so.
    plain = _of(_run(tmp_path / "b", None, lidar_tags=NO_FRAME_LIDAR), "SK501")
    assert plain[0].frame == "rover::base_footprint::laser" and "URDF's robot name" in plain[0].message


def test_sk501_static_frame_with_unknown_model_name_is_silent(tmp_path: Path) -> None:
    # Spawned under a name sensorkit could not resolve: any ".../base_footprint/laser" may be it (the lidar link is lumped into base_footprint).
    facts = _facts(SCAN, static_transforms=[_stf("laser_link", "robot_x/base_footprint/laser")], spawns=[_spawn(None)])
    assert not _of(_run(tmp_path, facts, lidar_tags=NO_FRAME_LIDAR), "SK501")
    near = _facts(SCAN, static_transforms=[_stf("laser_link", "robot_x/laser_link/laser")], spawns=[_spawn(None)])
    assert _of(_run(tmp_path / "b", near, lidar_tags=NO_FRAME_LIDAR), "SK501")


def test_sk501_frame_prefix_applies_to_link_frames(tmp_path: Path) -> None:
    # robot_state_publisher publishes frame_prefix + link (ros/robot_state_publisher@humble
    # 8b5af4f:src/robot_state_publisher.cpp:268-269, :291-292).
    prefixed = "<topic>scan</topic><gz_frame_id>robot/laser_link</gz_frame_id>"
    assert not _of(_run(tmp_path, _facts(SCAN, frame_prefix="robot/"), lidar_tags=prefixed), "SK501", "laser")
    # Near miss: the sensor stamps the bare link, which TF has only as robot/laser_link.
    sk501 = _of(_run(tmp_path / "b", _facts(SCAN, frame_prefix="robot/")), "SK501", "laser")
    assert [f.frame for f in sk501] == ["laser_link"] and sk501[0].severity.label == "error"
    assert "'robot/laser_link'" in sk501[0].message
    # Without launch facts, the prefixed frame is not a link: the error stands as before.
    assert _of(_run(tmp_path / "c", None, lidar_tags=prefixed), "SK501", "laser")


def test_sk501_unknown_frame_prefix_is_silent_on_prefixed_names(tmp_path: Path) -> None:
    prefixed = "<topic>scan</topic><gz_frame_id>robot/laser_link</gz_frame_id>"
    facts = _facts(SCAN, frame_prefix_unknown=True)
    assert not _of(_run(tmp_path, facts, lidar_tags=prefixed), "SK501", "laser")
    assert not _of(_run(tmp_path / "b", facts), "SK501", "laser")  # the bare link: may be right too
    typo = "<topic>scan</topic><gz_frame_id>robot/lazer_link</gz_frame_id>"
    assert _of(_run(tmp_path / "c", facts, lidar_tags=typo), "SK501", "laser")


def test_sk501_static_transform_supplies_a_named_frame(tmp_path: Path) -> None:
    tags = "<topic>scan</topic><gz_frame_id>lidar_mount</gz_frame_id>"
    facts = _facts(SCAN, static_transforms=[_stf("laser_link", "lidar_mount")])
    assert not _of(_run(tmp_path, facts, lidar_tags=tags), "SK501")
    assert _of(_run(tmp_path / "b", _facts(SCAN), lidar_tags=tags), "SK501")


# --- SK615: bridge entry types that do not match the sensor ----------------------------


def test_sk615_image_type_for_a_gpu_lidar_scan(tmp_path: Path) -> None:
    # GpuLidar advertises gz.msgs.LaserScan on its topic (gazebosim/gz-sensors@gz-sensors8
    # c8159af:src/Lidar.cc:130), and ros_gz_bridge's Image pairs with gz.msgs.Image
    # (gazebosim/ros_gz@jazzy 739cb42:ros_gz_bridge/README.md:52): gz-transport runs a
    # callback only for its own type (gazebosim/gz-transport@gz-transport13 e57e131e:
    # src/NodeShared.cc:601-602).
    wrong = _entry("scan", "sensor_msgs/msg/Image", "gz.msgs.Image", line=33)
    sk615 = _of(_run(tmp_path, _facts(wrong, IMAGE, INFO)), "SK615")
    assert len(sk615) == 1 and sk615[0].severity.label == "error" and sk615[0].line == 33
    assert sk615[0].sensor == "laser" and "gz.msgs.LaserScan" in sk615[0].message
    assert sk615[0].fix == "bridge it as sensor_msgs/msg/LaserScan (gz.msgs.LaserScan)"
    # Near miss: the right types.
    assert not _of(_run(tmp_path / "b", _facts(SCAN, IMAGE, INFO)), "SK615")


def test_sk615_ros_type_alone_and_yaml_entries(tmp_path: Path) -> None:
    yaml_text = (
        "- gz_topic_name: scan\n  ros_topic_name: scan\n  ros_type_name: sensor_msgs/msg/PointCloud2\n"
        "  direction: GZ_TO_ROS\n"
        "- gz_topic_name: scan/points\n  ros_topic_name: points\n  ros_type_name: sensor_msgs/msg/PointCloud2\n"
        "  ign_type_name: ignition.msgs.PointCloudPacked\n  direction: GZ_TO_ROS\n"
    )
    sk615 = _of(_run(tmp_path, None, bridge_text=yaml_text), "SK615")
    # The scan topic carries LaserScan (src/Lidar.cc:130); scan/points carries
    # PointCloudPacked (src/GpuLidarSensor.cc:151-155): only the first is wrong.
    assert [f.line for f in sk615] == [1] and "ROS type sensor_msgs/msg/PointCloud2" in sk615[0].message
    # Near miss: a camera_info entry with the CameraInfo types (src/CameraSensor.cc:685).
    assert not _of(_run(tmp_path / "b", _facts(SCAN, INFO)), "SK615")


def test_sk615_silent_on_topics_no_known_sensor_publishes(tmp_path: Path) -> None:
    # A topic of no sensor (SK612's business) or a ROS_TO_GZ entry: not SK615's.
    other = _entry("cmd_vel", "geometry_msgs/msg/Twist", "gz.msgs.Twist")
    back = BridgeTopic("scan", "scan", "sensor_msgs/msg/Image", "ROS_TO_GZ", LAUNCH, 9, "gz.msgs.Image")
    assert not _of(_run(tmp_path, _facts(SCAN, other, back)), "SK615")


# --- topics: the ROS names after bridging and remapping ---------------------------------


def test_topics_ros_name_after_the_launch_remaps_the_bridge(tmp_path: Path) -> None:
    # Modelled on turtlebot4_simulator@humble a238c94:turtlebot4_ignition_bringup/launch/
    # ros_ign_bridge.launch.py:88-99: the argument bridges the gz topic under its own name,
    # and the node's remapping renames it "scan".
    from sensorkit.describe.sensorinfo import describe, load
    from sensorkit.describe.topics import BridgeConfig, bridge_remaps, robot_topics
    from sensorkit.loading.launch_facts import NodeRemap

    path = tmp_path / "rover.urdf"
    path.write_text(gz_robot(lidar_tags="<topic>lidar/scan_raw</topic><gz_frame_id>laser_link</gz_frame_id>"))
    raw = BridgeTopic("lidar/scan_raw", None, "sensor_msgs/msg/LaserScan", "GZ_TO_ROS", LAUNCH, 12, "gz.msgs.LaserScan")
    remap = NodeRemap("ros_gz_bridge", "parameter_bridge", None, None, "lidar/scan_raw", "scan", SourceRef(LAUNCH, 14))
    other = NodeRemap("nav2_bringup", "x", None, None, "lidar/scan_raw", "nope", SourceRef(LAUNCH, 30))
    facts = _facts(raw, remaps=[remap, other])
    info = describe(load(path), "harmonic")
    config = BridgeConfig([LAUNCH], [raw], bridge_remaps(facts), [LAUNCH])
    names = {t.name for t in robot_topics(info, config).ros_topics if t.sensor == "laser"}
    assert names == {"/scan"}
    # Near miss: without the remapping, the ROS name is the gz one.
    plain = robot_topics(info, BridgeConfig([LAUNCH], [raw]))
    assert {t.name for t in plain.ros_topics if t.sensor == "laser"} == {"/lidar/scan_raw"}


# --- the CLI and the settings file -------------------------------------------------------


def test_header_names_the_launch_files_read() -> None:
    from sensorkit.lint.engine import launch_note
    from sensorkit.lint.rules.base import Bridge

    facts = LaunchFacts(files=[LAUNCH, "launch/rviz.launch.py"], bridges=[SCAN])
    bridge = Bridge(files=["config/bridge.yaml", LAUNCH], topics=[SCAN])
    assert launch_note(facts, bridge) == (
        "bridges from config/bridge.yaml, launch/sim.launch.py; launch files read: launch/rviz.launch.py"
    )
    assert launch_note(LaunchFacts(), None) is None  # none read: the header is as before


def test_validate_header_shows_the_launch_note(tmp_path: Path) -> None:
    from sensorkit.lint.engine import Report
    from sensorkit.lint.report import render

    report = _run(tmp_path, _facts(SCAN, IMAGE, INFO))
    assert report.launch_note == f"bridges from {LAUNCH}"
    head = render(Report([report]), "text").splitlines()[0]
    assert head.endswith(f"; bridges from {LAUNCH})")
    plain = _run(tmp_path / "b", None)
    assert plain.launch_note is None and render(Report([plain]), "text").splitlines()[0].endswith(")")


def test_launch_flag_and_settings_key(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from sensorkit.cli import app
    from sensorkit.lint.config import load_config

    robot = tmp_path / "rover.urdf"
    robot.write_text(gz_robot())
    result = CliRunner().invoke(app, ["validate", str(robot), "--launch", str(tmp_path / "nope.launch.py")])
    assert result.exit_code == 2 and "--launch" in result.output and "no such file" in result.output
    (tmp_path / "launch").mkdir()
    (tmp_path / "launch" / "sim.launch.xml").write_text("<launch/>")
    (tmp_path / "sensorkit.toml").write_text('launch = ["launch/sim.launch.xml"]\n')
    cfg = load_config(tmp_path)
    assert cfg.launch == [str((tmp_path / "launch" / "sim.launch.xml").resolve())]
    topics = CliRunner().invoke(
        app, ["topics", str(robot), "--target", "classic", "--launch", str(robot)]
    )
    assert topics.exit_code == 0 and "--launch ignored" in topics.output
    # Near miss: an unknown key is still refused.
    (tmp_path / "sensorkit.toml").write_text('launches = ["x"]\n')
    with pytest.raises(UsageError):
        load_config(tmp_path)
