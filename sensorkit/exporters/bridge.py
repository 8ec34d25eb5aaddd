"""``ros_gz_bridge`` configuration YAML and the message-type pairs it needs.

The file is a list of maps with ``ros_topic_name``, ``gz_topic_name``,
``ros_type_name``, ``gz_type_name`` and ``direction`` (``GZ_TO_ROS``, ``ROS_TO_GZ`` or
``BIDIRECTIONAL``). Gazebo Fortress spells the gz types ``ignition.msgs.*``; Garden
and later ``gz.msgs.*``.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Literal, NamedTuple

from sensorkit.describe.intrinsics import InvalidValue
from sensorkit.exporters import _text as t

__all__ = [
    "DIRECTIONS",
    "BridgeEntry",
    "MessageKind",
    "bridge_types",
    "bridge_yaml",
    "sensor_bridge_entries",
]

MessageKind = Literal["image", "camera_info", "laser_scan", "points", "imu"]
Direction = Literal["GZ_TO_ROS", "ROS_TO_GZ", "BIDIRECTIONAL"]
DIRECTIONS: tuple[str, ...] = ("GZ_TO_ROS", "ROS_TO_GZ", "BIDIRECTIONAL")

_TYPES: dict[str, tuple[str, str]] = {
    "image": ("sensor_msgs/msg/Image", "Image"),
    "camera_info": ("sensor_msgs/msg/CameraInfo", "CameraInfo"),
    "laser_scan": ("sensor_msgs/msg/LaserScan", "LaserScan"),
    "points": ("sensor_msgs/msg/PointCloud2", "PointCloudPacked"),
    "imu": ("sensor_msgs/msg/Imu", "IMU"),
}
_IGNITION_RELEASES = frozenset({"fortress", "citadel", "edifice"})
_GZ_RELEASES = frozenset({"garden", "harmonic", "ionic", "jetty"})


class BridgeEntry(NamedTuple):
    """One bridged topic, in the order and spelling of the ros_gz_bridge YAML keys."""

    ros_topic_name: str
    gz_topic_name: str
    ros_type_name: str
    gz_type_name: str
    direction: str = "GZ_TO_ROS"


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


def sensor_bridge_entries(sensor_type: str, gz_topic: str, *, gz_version: str) -> list[BridgeEntry]:
    """The GZ_TO_ROS entries for everything a gz-sensors sensor publishes on ``gz_topic``.

    ROS topic names are the gz names. Topics (gz-sensors): ``camera`` -> ``<topic>``
    and a sibling ``camera_info``; ``depth_camera`` -> ``<topic>``, sibling
    ``camera_info``, ``<topic>/points``; ``rgbd_camera`` -> ``<topic>/image``,
    ``/depth_image``, ``/points``, ``/camera_info``; ``gpu_lidar``/``lidar`` ->
    ``<topic>`` and ``<topic>/points``; ``imu`` -> ``<topic>``.

    Raises:
        InvalidValue: unknown sensor type or release, or an empty topic.
    """
    t.string(gz_topic, "gz_topic")
    topic = gz_topic.rstrip("/") or gz_topic
    kinds: list[tuple[str, MessageKind]]
    if sensor_type == "camera":
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
    else:
        msg = (
            "sensor_type must be camera, depth_camera, rgbd_camera, gpu_lidar, lidar or imu, "
            f"got {sensor_type!r}"
        )
        raise InvalidValue(msg)
    entries = []
    for name, kind in kinds:
        ros_type, gz_type = bridge_types(kind, gz_version)
        entries.append(BridgeEntry(name, name, ros_type, gz_type, "GZ_TO_ROS"))
    return entries


def bridge_yaml(entries: Iterable[BridgeEntry | tuple[str, str, str, str, str]]) -> str:
    """The ``ros_gz_bridge`` ``config_file`` YAML for ``entries``.

    Each entry is ``(ros_topic_name, gz_topic_name, ros_type_name, gz_type_name,
    direction)``.

    Raises:
        InvalidValue: no entries (an empty list bridges nothing and hides the mistake),
            an empty name, an unknown direction, or the same ROS topic twice.
    """
    items = [BridgeEntry(*entry) for entry in entries]
    if not items:
        msg = "nothing to bridge: the entry list is empty"
        raise InvalidValue(msg)
    seen: set[str] = set()
    lines: list[str] = []
    for item in items:
        if item.direction not in DIRECTIONS:
            msg = f"direction must be one of {', '.join(DIRECTIONS)}, got {item.direction!r}"
            raise InvalidValue(msg)
        if item.ros_topic_name in seen:
            msg = f"ros_topic_name {item.ros_topic_name!r} is bridged twice"
            raise InvalidValue(msg)
        seen.add(item.ros_topic_name)
        lines += [
            f"- ros_topic_name: {t.string(item.ros_topic_name, 'ros_topic_name')}",
            f"  gz_topic_name: {t.string(item.gz_topic_name, 'gz_topic_name')}",
            f"  ros_type_name: {t.string(item.ros_type_name, 'ros_type_name')}",
            f"  gz_type_name: {t.string(item.gz_type_name, 'gz_type_name')}",
            f"  direction: {item.direction}",
        ]
    return "\n".join(lines) + "\n"
