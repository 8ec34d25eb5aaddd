"""The ros_gz_bridge entries of a robot: which gz topics reach ROS, under which names.

An entry is what one item of a ``ros_gz_bridge`` YAML says (:class:`BridgeEntry`; the
writers are :mod:`sensorkit.exporters.bridge`). Gazebo Fortress spells the gz types
``ignition.msgs.*``; Garden and later ``gz.msgs.*``.

No topic is written down twice: the macros say which gz topics they publish (their
``<topic>`` and ``<camera_info_topic>``), the drive plugins say theirs, and this module
reads them back from the expanded description. ROS names follow the Gazebo Classic
conventions of the same macros, so a robot publishes the same ROS topics on both
simulators:

- camera: ``<topic>`` (Image) and its camera_info topic (CameraInfo), same names;
- rgbd_camera ``X``: ``X/image`` -> ``X/image_raw``, ``X/depth_image`` ->
  ``X/depth/image_raw``, ``X/camera_info`` and ``X/points`` kept (one camera_info serves
  both images: the depth image is registered to the colour image);
- depth_camera: ``<topic>`` (depth Image), camera_info, ``<topic>/points``;
- 2D lidar (one vertical sample): ``<topic>`` (LaserScan) and ``<topic>/points``;
- 3D lidar ``X/scan``: ``X/scan/points`` -> ``X/points`` (PointCloud2). Its gz LaserScan
  holds every layer in one ranges array, which no ROS LaserScan consumer reads right, so
  it is not bridged;
- imu: ``<topic>`` (Imu);
- DiffDrive: cmd_vel (ROS_TO_GZ), odom, tf (to ``/tf``); JointStatePublisher:
  joint_states; and ``/clock`` always.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal, NamedTuple

from lxml import etree

from sensorkit.describe.intrinsics import InvalidValue
from sensorkit.knowledge.gazebo_sim import (
    GZ_BOUNDINGBOX_TYPES,
    GZ_NO_WIDE_ANGLE_RELEASES,
    GZ_READS_CAMERA_INFO_TOPIC,
    GZ_SEGMENTATION_TYPES,
    GZ_WIDE_ANGLE_TYPES,
    GZ_XFORWARD_CLOUD_TYPES,
    gz_own_subtopics,
)

if TYPE_CHECKING:
    from sensorkit.model.robot import Robot

__all__ = [
    "BridgeEntry",
    "MessageKind",
    "bridge_entries",
    "bridge_types",
    "model_bridge_entries",
    "published_entries",
    "sensor_bridge_entries",
    "sensor_entries",
]

MessageKind = Literal["image", "camera_info", "laser_scan", "points", "imu", "boxes_2d", "boxes_3d"]

_TYPES: dict[str, tuple[str, str]] = {
    "image": ("sensor_msgs/msg/Image", "Image"),
    "camera_info": ("sensor_msgs/msg/CameraInfo", "CameraInfo"),
    "laser_scan": ("sensor_msgs/msg/LaserScan", "LaserScan"),
    "points": ("sensor_msgs/msg/PointCloud2", "PointCloudPacked"),
    "imu": ("sensor_msgs/msg/Imu", "IMU"),
    # ros_gz_bridge's pairs for a bounding-box camera's boxes (knowledge/gazebo_sim.py)
    "boxes_2d": ("vision_msgs/msg/Detection2DArray", "AnnotatedAxisAligned2DBox_V"),
    "boxes_3d": ("vision_msgs/msg/Detection3DArray", "AnnotatedOriented3DBox_V"),
}
_IGNITION_RELEASES = frozenset({"fortress", "citadel", "edifice"})
_GZ_RELEASES = frozenset({"garden", "harmonic", "ionic", "jetty"})

_SENSOR_TYPES = {
    "camera",
    *GZ_WIDE_ANGLE_TYPES,  # publish as a camera does, from Garden on (knowledge/gazebo_sim.py)
    "depth_camera",
    "depth",
    "rgbd_camera",
    "rgbd",
    "gpu_lidar",
    "gpu_ray",
    "imu",
    *GZ_SEGMENTATION_TYPES,  # their own sub-topics (knowledge.gazebo_sim.gz_own_subtopics)
    *GZ_BOUNDINGBOX_TYPES,
}  # not ray/lidar/multicamera: gz-sim never creates them (sensorkit/knowledge/gazebo_sim.py)


class BridgeEntry(NamedTuple):
    """One bridged topic, in the order and spelling of the ros_gz_bridge YAML keys."""

    ros_topic_name: str
    gz_topic_name: str
    ros_type_name: str
    gz_type_name: str
    direction: str = "GZ_TO_ROS"


# --------------------------------------------------------------------------- by sensor type


def bridge_types(kind: MessageKind, gz_version: str) -> tuple[str, str]:
    """``(ros_type_name, gz_type_name)`` for a message kind on a Gazebo release.

    ``image`` (also depth images) -> Image, ``camera_info`` -> CameraInfo,
    ``laser_scan`` -> LaserScan, ``points`` -> PointCloud2 / PointCloudPacked,
    ``imu`` -> Imu / IMU. ``gz_version`` is a release name (``fortress``, ``garden``,
    ``harmonic``, ``ionic``, ``jetty``).

    Raises:
        InvalidValue: unknown kind or release.
    """
    if kind not in _TYPES:
        msg = f"kind must be one of {', '.join(_TYPES)}, got {kind!r}"
        raise InvalidValue(msg)
    release = gz_version.strip().lower() if isinstance(gz_version, str) else gz_version
    if release in _IGNITION_RELEASES:
        prefix = "ignition.msgs."
    elif release in _GZ_RELEASES:
        prefix = "gz.msgs."
    else:
        known = ", ".join(sorted(_IGNITION_RELEASES | _GZ_RELEASES))
        msg = f"gz_version must be one of {known}, got {gz_version!r}"
        raise InvalidValue(msg)
    ros_type, gz_name = _TYPES[kind]
    return ros_type, prefix + gz_name


def _sibling_camera_info(topic: str) -> str:
    """gz-sensors ``CameraSensor::AdvertiseInfo``: drop the last topic part, add
    ``/camera_info`` (``/cam/image`` -> ``/cam/camera_info``, ``camera`` -> ``/camera_info``)."""
    parts = [p for p in topic.split("/")[:-1] if p]
    return "".join(f"/{p}" for p in parts) + "/camera_info"


def sensor_bridge_entries(
    sensor_type: str, gz_topic: str, *, gz_version: str, box_type: str | None = None
) -> list[BridgeEntry]:
    """The GZ_TO_ROS entries for everything a gz-sensors sensor publishes on ``gz_topic``.

    ROS topic names are the gz names. Topics (gz-sensors): ``camera`` (and
    ``wideanglecamera``) -> ``<topic>`` and a sibling ``camera_info``; ``depth_camera`` -> ``<topic>``, sibling
    ``camera_info``, ``<topic>/points``; ``rgbd_camera`` -> ``<topic>/image``,
    ``/depth_image``, ``/points``, ``/camera_info``; ``gpu_lidar``/``lidar`` ->
    ``<topic>`` and ``<topic>/points``; ``imu`` -> ``<topic>``.

    Raises:
        InvalidValue: unknown sensor type or release, or an empty topic.
    """
    if not isinstance(gz_topic, str) or not gz_topic:
        msg = f"gz_topic must be a non-empty string, got {gz_topic!r}"
        raise InvalidValue(msg)
    topic = gz_topic.rstrip("/") or gz_topic
    kinds: list[tuple[str, MessageKind]]
    if sensor_type == "camera" or sensor_type in GZ_WIDE_ANGLE_TYPES:
        kinds = [(topic, "image"), (_sibling_camera_info(topic), "camera_info")]
    elif sensor_type in ("depth_camera", "depth"):
        kinds = [
            (topic, "image"),
            (_sibling_camera_info(topic), "camera_info"),
            (f"{topic}/points", "points"),
        ]
    elif sensor_type in ("rgbd_camera", "rgbd"):
        kinds = [
            (f"{topic}/image", "image"),
            (f"{topic}/depth_image", "image"),
            (f"{topic}/points", "points"),
            (f"{topic}/camera_info", "camera_info"),
        ]
    elif sensor_type in ("gpu_lidar", "gpu_ray", "lidar", "ray"):
        kinds = [(topic, "laser_scan"), (f"{topic}/points", "points")]
    elif sensor_type == "imu":
        kinds = [(topic, "imu")]
    elif sensor_type in GZ_SEGMENTATION_TYPES or sensor_type in GZ_BOUNDINGBOX_TYPES:
        by_msg: dict[str, MessageKind] = {
            "Image": "image",
            "CameraInfo": "camera_info",
            "AnnotatedAxisAligned2DBox_V": "boxes_2d",
            "AnnotatedOriented3DBox_V": "boxes_3d",
        }
        kinds = [(name, by_msg[m]) for name, _, m in gz_own_subtopics(sensor_type, topic, box_type)]
    else:
        msg = (
            "sensor_type must be camera, wideanglecamera, depth_camera, rgbd_camera, gpu_lidar, "
            "lidar or imu, "
            f"got {sensor_type!r}"
        )
        raise InvalidValue(msg)
    entries = []
    for name, kind in kinds:
        ros_type, gz_type = bridge_types(kind, gz_version)
        entries.append(BridgeEntry(name, name, ros_type, gz_type, "GZ_TO_ROS"))
    return entries


# --------------------------------------------------------------------------- from the description


def _msg_prefix(gz_version: str) -> str:
    return "ignition.msgs." if gz_version == "fortress" else "gz.msgs."


def _rel(topic: str) -> str:
    """gz-transport and a root-namespace ROS node read ``a/b`` and ``/a/b`` alike."""
    return topic.strip().strip("/")


def _text(el: etree._Element, path: str) -> str | None:
    found = el.find(path)
    text = None if found is None else found.text
    if text is None or not text.strip():
        return None
    return str(text).strip()


def _vertical_samples(sensor: etree._Element) -> int:
    for path in ("lidar/scan/vertical/samples", "ray/scan/vertical/samples"):
        text = _text(sensor, path)
        if text is not None:
            try:
                return int(float(text))
            except (ValueError, OverflowError):  # not a number, or inf
                return 1
    return 1


def published_entries(
    sensor: etree._Element, gz_version: str, topic: str | None = None
) -> list[BridgeEntry]:
    """Every gz topic an expanded ``<sensor>`` publishes, as GZ_TO_ROS entries whose ROS
    name is the gz name: what a bridge could carry, before :func:`sensor_entries` chooses.

    ``topic`` stands in for the sensor's ``<topic>`` (a sensor without one publishes under
    its scoped name); none and no ``<topic>``, or a type gz-sim does not create: empty.
    """
    stype = sensor.get("type") or ""
    topic = topic or _text(sensor, "topic")
    if stype not in _SENSOR_TYPES or topic is None:
        return []
    if stype in GZ_WIDE_ANGLE_TYPES and gz_version in GZ_NO_WIDE_ANGLE_RELEASES:
        return []  # Fortress never creates a wide-angle camera (knowledge/gazebo_sim.py)
    info_topic = (
        _text(sensor, "camera/camera_info_topic") if stype in GZ_READS_CAMERA_INFO_TOPIC else None
    )
    out: list[BridgeEntry] = []
    box_type = _text(sensor, "camera/box_type")
    for entry in sensor_bridge_entries(stype, _rel(topic), gz_version=gz_version, box_type=box_type):
        gz_name = _rel(entry.gz_topic_name)
        if entry.ros_type_name.endswith("/CameraInfo") and info_topic is not None:
            gz_name = _rel(info_topic)
        out.append(entry._replace(gz_topic_name=gz_name, ros_topic_name=gz_name))
    return out


def sensor_entries(sensor: etree._Element, gz_version: str) -> list[BridgeEntry]:
    """GZ_TO_ROS entries for one expanded ``<sensor>`` (empty if it has no ``<topic>``)."""
    stype = sensor.get("type") or ""
    topic = _text(sensor, "topic")
    if topic is None:
        return []
    topic = _rel(topic)
    out: list[BridgeEntry] = []
    vertical = _vertical_samples(sensor)
    for entry in published_entries(sensor, gz_version):
        if stype in GZ_XFORWARD_CLOUD_TYPES and entry.ros_type_name.endswith("/PointCloud2"):
            continue  # x-forward cloud stamped optical: not bridged (see the bridge file's header)
        gz_name = entry.gz_topic_name
        ros_name = gz_name
        kind = entry.ros_type_name
        if stype in ("rgbd_camera", "rgbd"):
            if gz_name == f"{topic}/image":
                ros_name = f"{topic}/image_raw"
            elif gz_name == f"{topic}/depth_image":
                ros_name = f"{topic}/depth/image_raw"
        if stype in ("gpu_lidar", "gpu_ray", "lidar", "ray") and vertical > 1:
            if kind.endswith("/LaserScan"):
                continue
            if topic.endswith("/scan"):
                ros_name = f"{topic[: -len('/scan')]}/points"
        out.append(entry._replace(ros_topic_name=ros_name))
    return out


def _same_name(
    plugin: etree._Element, tag: str, ros_type: str, gz_type: str, direction: str
) -> list[BridgeEntry]:
    """The entry for the topic the plugin's ``<tag>`` names, ROS name the gz name (none
    when the plugin does not set it)."""
    topic = _text(plugin, tag)
    if not topic:
        return []
    return [BridgeEntry(_rel(topic), _rel(topic), ros_type, gz_type, direction)]


def _plugin_entries(plugin: etree._Element, gz_version: str) -> list[BridgeEntry]:
    name = plugin.get("name") or ""
    prefix = _msg_prefix(gz_version)
    out: list[BridgeEntry] = []
    if name.endswith("::DiffDrive"):
        out += _same_name(plugin, "topic", "geometry_msgs/msg/Twist", prefix + "Twist", "ROS_TO_GZ")
        out += _same_name(
            plugin, "odom_topic", "nav_msgs/msg/Odometry", prefix + "Odometry", "GZ_TO_ROS"
        )
        tf = _text(plugin, "tf_topic")
        if tf:
            out.append(
                BridgeEntry(
                    "/tf", _rel(tf), "tf2_msgs/msg/TFMessage", prefix + "Pose_V", "GZ_TO_ROS"
                )
            )
    elif name.endswith("::JointStatePublisher"):
        out += _same_name(
            plugin, "topic", "sensor_msgs/msg/JointState", prefix + "Model", "GZ_TO_ROS"
        )
    return out


def bridge_entries(robot: etree._Element, gz_version: str) -> list[BridgeEntry]:
    """Every entry the expanded ``robot`` needs: ``/clock``, the drive, then each sensor."""
    prefix = _msg_prefix(gz_version)
    entries = [
        BridgeEntry("/clock", "/clock", "rosgraph_msgs/msg/Clock", prefix + "Clock", "GZ_TO_ROS")
    ]
    for gazebo in robot.iter("gazebo"):
        for plugin in gazebo.findall("plugin"):
            entries += _plugin_entries(plugin, gz_version)
    for gazebo in robot.iter("gazebo"):
        for sensor in gazebo.iter("sensor"):
            entries += sensor_entries(sensor, gz_version)
    return entries


def model_bridge_entries(robot: Robot, gz_version: str) -> list[BridgeEntry]:
    """:func:`bridge_entries` for a robot read from SDF, whose sensors and plugins sit in
    its links and model (no ``<gazebo>`` blocks), and only this model's in a world."""
    prefix = _msg_prefix(gz_version)
    entries = [
        BridgeEntry("/clock", "/clock", "rosgraph_msgs/msg/Clock", prefix + "Clock", "GZ_TO_ROS")
    ]
    for plugin in robot.model_plugins:
        entries += _plugin_entries(plugin.element, gz_version)
    for sensor in robot.sensors:
        entries += sensor_entries(sensor.element, gz_version)
    return entries
