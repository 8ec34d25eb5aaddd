"""``ros_gz_bridge`` configuration YAML: the text of a robot's ``bridge.yaml``.

The file is a list of maps with ``ros_topic_name``, ``gz_topic_name``,
``ros_type_name``, ``gz_type_name`` and ``direction`` (``GZ_TO_ROS``, ``ROS_TO_GZ`` or
``BIDIRECTIONAL``). Which entries a robot needs is :mod:`sensorkit.describe.bridge`.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Literal

from sensorkit.describe.bridge import BridgeEntry
from sensorkit.describe.intrinsics import InvalidValue
from sensorkit.exporters import _text as t

__all__ = [
    "CLOUD_HEADER",
    "DIRECTIONS",
    "bridge_file_text",
    "bridge_yaml",
]

Direction = Literal["GZ_TO_ROS", "ROS_TO_GZ", "BIDIRECTIONAL"]
DIRECTIONS: tuple[str, ...] = ("GZ_TO_ROS", "ROS_TO_GZ", "BIDIRECTIONAL")


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


CLOUD_HEADER = (
    "# Depth-camera clouds are not bridged: Gazebo Sim computes them x-forward but stamps\n"
    "# them with the optical frame (gz-sensors#488), so RViz would show them on their side.\n"
    "# Build them from the depth image and camera_info with depth_image_proc.\n"
)


def bridge_file_text(
    entries: Iterable[BridgeEntry], *, robot: str, gz_version: str, by: str = "sensorkit new"
) -> str:
    """The ``config/bridge.yaml`` text: a short header, then the entries."""
    header = (
        f"# ros_gz_bridge configuration for {robot} on Gazebo Sim ({gz_version}),\n"
        f"# written by {by} from the topics the robot description declares.\n"
        "#   ros2 run ros_gz_bridge parameter_bridge --ros-args -p config_file:=bridge.yaml\n"
        + CLOUD_HEADER
    )
    return header + bridge_yaml(entries)
