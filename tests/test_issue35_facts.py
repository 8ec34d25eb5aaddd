"""Issue 35 item 8: facts about the simulators found wrong, each pinned to its source.

- <optical_frame_id> is read from <camera> only (gazebosim/sdformat@sdf12 b9417e5:
  src/Camera.cc:383-388; @sdf14 8512585: :385-390), so one written directly under <sensor>
  is lost (SK410), where before it was taken as read anyway.
- A gz lidar's vertical rows are at least 1 (gazebosim/gz-sensors@ign-sensors6 7cfaddf:
  src/Lidar.cc:378-386; @gz-sensors8 c8159af: :389-397), while the GPU rays render <samples>
  rows (gz-sensors8 src/GpuLidarSensor.cc:212-214). A vertical <samples> of 0 is not saved by
  that clamp: "Lidar: Image has 0 size!" (src/Lidar.cc:145-148), 0 rows rendered, a scan of
  no ranges written one row into (:272-296).
"""

from __future__ import annotations

from collections.abc import Callable

from builders import bridge_entry as _entry
from builders import gz_robot

from sensorkit.base.findings import Severity


def _of(report, rule: str):  # type: ignore[no-untyped-def]
    return [f for f in report.findings if f.rule == rule]


OPTICAL = "<optical_frame_id>camera_optical_frame</optical_frame_id>"


def test_optical_frame_id_under_sensor_is_lost(check: Callable) -> None:
    text = gz_robot(camera_tags=f"<topic>front_camera/image_raw</topic>{OPTICAL}")
    for target in ("fortress", "harmonic"):
        found = _of(check(text, target=target), "SK410")
        assert [f.severity for f in found] == [Severity.ERROR], target
        assert "<optical_frame_id>" in found[0].message and "camera.sdf" in found[0].message
    # Near miss: inside <camera>, where sdformat reads it.
    near = gz_robot(camera_tags="<topic>front_camera/image_raw</topic>").replace(
        "</clip></camera>", f"</clip>{OPTICAL}</camera>"
    )
    assert OPTICAL in near
    assert not _of(check(near, target="harmonic"), "SK410")


def _vertical(samples: str, resolution: str, lo: str = "0", hi: str = "0") -> str:
    vertical = (
        f"<vertical><samples>{samples}</samples><resolution>{resolution}</resolution>"
        f"<min_angle>{lo}</min_angle><max_angle>{hi}</max_angle></vertical>"
    )
    return gz_robot().replace("</horizontal></scan>", f"</horizontal>{vertical}</scan>")


def _sk406(check: Callable, text: str, target: str = "harmonic") -> list[tuple[Severity, str]]:
    return [(f.severity, f.message) for f in _of(check(text, target=target), "SK406")]


def test_gz_vertical_rows_are_at_least_one(check: Callable) -> None:
    # One vertical sample at resolution 0.5: 0.5 rows, clamped to the one row cast: info.
    found = _sk406(check, _vertical("1", "0.5"))
    assert [s for s, _ in found] == [Severity.INFO]
    assert "publishes 1 row, the 1 sample written" in found[0][1] and "nothing changes" in found[0][1]
    # Near miss, Gazebo Classic has no such clamp (a warning, it publishes 0 rows).
    from builders import lidar_sensor, robot

    vertical = "<vertical><samples>1</samples><resolution>0.5</resolution><min_angle>0</min_angle><max_angle>0</max_angle></vertical>"
    found = _sk406(check, robot(lidar=lidar_sensor(vertical=vertical)), "classic")
    assert [s for s, _ in found] == [Severity.WARNING] and "publishes 0" in found[0][1]
    # Near miss: two samples at 0.5 make one row from two cast: still a warning on gz.
    found = _sk406(check, _vertical("2", "0.25", "-0.1", "0.1"))
    assert [s for s, _ in found] == [Severity.WARNING]
    # A whole count says nothing.
    assert _sk406(check, _vertical("1", "1")) == []


def test_gz_vertical_samples_zero_stays_an_error(check: Callable) -> None:
    found = _sk406(check, _vertical("0", "1"))
    assert [s for s, _ in found] == [Severity.ERROR]
    assert "vertical samples 0 < 1" in found[0][1]


# --- segmentation and bounding-box cameras publish on their own sub-topics -----------------
# gz-sensors8 c8159af: src/SegmentationCameraSensor.cc:78-81 (suffixes "/colored_map",
# "/labels_map"), :197-213 (advertised on TOPIC + suffix), :238 (camera_info on
# TOPIC/camera_info); src/BoundingBoxCameraSensor.cc:190-212 (boxes on TOPIC, Image on
# TOPIC + "_image"), :237 (sibling camera_info). ros_gz_bridge pairs the boxes with
# vision_msgs Detection2DArray / Detection3DArray (ros_gz@jazzy 739cb42:
# ros_gz_bridge/ros_gz_bridge/mappings.py:114,116).


SCAN = _entry("scan", "sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan")
IMAGE = ("sensor_msgs/msg/Image", "gz.msgs.Image")
INFO = ("sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo")


def _cam(stype: str, box: str = "") -> str:
    text = gz_robot(camera_type=stype, camera_tags="<topic>cam</topic><gz_frame_id>camera_optical_frame</gz_frame_id>")
    return text.replace("</clip></camera>", f"</clip>{box}</camera>") if box else text


def _bridge(tmp_path, *entries: str) -> str:  # type: ignore[no-untyped-def]
    path = tmp_path / "bridge.yaml"
    path.write_text(SCAN + "".join(entries))
    return str(path)


def test_segmentation_camera_sub_topics(check: Callable, tmp_path) -> None:  # type: ignore[no-untyped-def]
    from sensorkit.lint.rules.topic_names import gz_topics

    bridge = _bridge(tmp_path, _entry("cam/labels_map", *IMAGE), _entry("cam/camera_info", *INFO))
    report = check(_cam("segmentation_camera"), target="harmonic", bridges=(bridge,))
    assert not {"SK607", "SK612", "SK615"} & {f.rule for f in report.findings}
    sensor = next(s for s in report.robot.sensors if s.name == "front_camera")  # type: ignore[attr-defined]
    assert gz_topics(sensor) == ["/cam/colored_map", "/cam/labels_map", "/cam/camera_info"]
    # Near miss: bridging TOPIC itself, as for a plain camera, carries nothing: ROS receives
    # nothing of the camera (an error, issue 35).
    bad = _bridge(tmp_path, _entry("cam", *IMAGE), _entry("camera_info", *INFO))
    found = check(_cam("segmentation_camera"), target="harmonic", bridges=(bad,)).findings
    sk607 = [f for f in found if f.rule == "SK607"]
    assert [f.severity for f in sk607] == [Severity.ERROR]
    assert {f.rule for f in found if f.severity is Severity.INFO} >= {"SK612"}


def test_bounding_box_camera_sub_topics(check: Callable, tmp_path) -> None:  # type: ignore[no-untyped-def]
    boxes2d = _entry("cam", "vision_msgs/msg/Detection2DArray", "gz.msgs.AnnotatedAxisAligned2DBox_V")
    ok = _bridge(tmp_path, boxes2d, _entry("cam_image", *IMAGE), _entry("camera_info", *INFO))
    report = check(_cam("boundingbox_camera"), target="harmonic", bridges=(ok,))
    assert not {"SK607", "SK612", "SK615"} & {f.rule for f in report.findings}
    # Near miss: a 3d <box_type> publishes AnnotatedOriented3DBox_V on TOPIC (box types
    # BoundingBoxCameraSensor.cc:150-165, :205-213), so the 2D entry carries nothing (SK615).
    found = check(_cam("boundingbox_camera", "<box_type>3d</box_type>"), target="harmonic", bridges=(ok,)).findings
    assert [f.severity for f in found if f.rule == "SK615"] == [Severity.ERROR]


def test_topics_and_bridge_export_know_the_sub_topics(tmp_path) -> None:  # type: ignore[no-untyped-def]
    from lxml import etree

    from sensorkit.describe.bridge import published_entries

    seg = etree.fromstring('<sensor name="s" type="segmentation"><topic>cam</topic><camera/></sensor>')
    got = [(e.gz_topic_name, e.ros_type_name) for e in published_entries(seg, "harmonic")]
    assert got == [
        ("cam/colored_map", "sensor_msgs/msg/Image"),
        ("cam/labels_map", "sensor_msgs/msg/Image"),
        ("cam/camera_info", "sensor_msgs/msg/CameraInfo"),
    ]
    box = etree.fromstring('<sensor name="b" type="boundingbox_camera"><topic>a/cam</topic><camera><box_type>3d</box_type></camera></sensor>')
    got = [(e.gz_topic_name, e.ros_type_name, e.gz_type_name) for e in published_entries(box, "fortress")]
    assert got == [
        ("a/cam", "vision_msgs/msg/Detection3DArray", "ignition.msgs.AnnotatedOriented3DBox_V"),
        ("a/cam_image", "sensor_msgs/msg/Image", "ignition.msgs.Image"),
        ("a/camera_info", "sensor_msgs/msg/CameraInfo", "ignition.msgs.CameraInfo"),
    ]
    # Near miss: a plain camera keeps TOPIC and a sibling camera_info.
    cam = etree.fromstring('<sensor name="c" type="camera"><topic>a/cam</topic><camera/></sensor>')
    assert [e.gz_topic_name for e in published_entries(cam, "harmonic")] == ["a/cam", "a/camera_info"]
