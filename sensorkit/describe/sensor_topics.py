"""The ROS topics of one sensor under a target, by role.

:func:`sensor_topics` gives each topic a sensor's data reaches its role (``image``,
``camera_info``, ``depth_image``, ``scan``, ...): Gazebo Classic from the plugin and its
remappings, Gazebo Sim from the gz ``<topic>`` through the ros_gz_bridge names
``sensorkit new`` uses (:mod:`sensorkit.describe.bridge`).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from sensorkit.describe.intrinsics import InvalidValue

if TYPE_CHECKING:
    from sensorkit.describe.bridge import BridgeEntry
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import Sensor

NO_PLUGIN = "no ROS plugin: the sensor publishes nothing to ROS"


def _no_plugin(sensor: Sensor, target: str, robot: Robot | None) -> str:
    """Why a sensor without a plugin of its own has no topics: nothing publishes it, or a
    model-level plugin reads it (the same answer SK607 gives, from sensorkit.model.owners)."""
    if robot is None:
        return NO_PLUGIN
    from sensorkit.model.owners import sensor_owner

    owner = sensor_owner(robot, sensor, target)
    if owner is None:
        return NO_PLUGIN
    if owner.certain:
        return f"no plugin of its own: {owner.how}; sensorkit does not name the topics it publishes"
    return (
        f"no plugin of its own, and {owner.how}: sensorkit cannot tell whether it publishes "
        "this sensor"
    )

__all__ = ["gz_roles", "sensor_topics"]


def _abs(topic: str) -> str:
    return "/" + topic.strip().strip("/")


def _ros2_topics(sensor: Sensor, robot: Robot | None) -> tuple[dict[str, str], list[str]]:
    from sensorkit.lint.rules.topic_names import resolved_topics
    from sensorkit.model.frames import ros_plugin

    plugin = ros_plugin(sensor)
    if plugin is None:
        return {}, [_no_plugin(sensor, "classic", robot)]
    topics: dict[str, str] = {}
    pairs = resolved_topics(plugin, sensor)
    if not pairs:
        return {}, [f"plugin {plugin.filename!r} publishes no topic sensorkit knows on ROS 2"]
    if plugin.library == "gazebo_ros_camera":
        base = plugin.param("camera_name") or sensor.name
        suffixes = {
            "image_raw": "image",
            "camera_info": "camera_info",
            "depth/image_raw": "depth_image",
            "depth/camera_info": "depth_camera_info",
            "points": "points",
            "image_trigger": "trigger",
        }
        for name, full in pairs:
            rest = name[len(base) + 1 :] if name.startswith(base + "/") else name
            if sensor.kind == "multicamera":
                cam, _, leaf = rest.partition("/")
                role = suffixes.get(leaf)
                if role is not None:
                    topics[f"{cam}/{role}"] = full
            elif rest in suffixes:
                topics[suffixes[rest]] = full
        return topics, []
    (_, full), *_ = pairs
    if sensor.kind == "lidar":
        output = plugin.param("output_type") or "sensor_msgs/PointCloud2"
        role = {"sensor_msgs/LaserScan": "scan", "sensor_msgs/Range": "range"}.get(output, "points")
        topics[role] = full
    elif sensor.kind == "imu":
        topics["imu"] = full
    else:
        topics["out"] = full
    return topics, []


def _ros1_topics(sensor: Sensor, robot: Robot | None) -> tuple[dict[str, str], list[str]]:
    """gazebo_ros_pkgs (ROS 1) names: ``/<robotNamespace>/<cameraName>/<...TopicName>``."""
    from sensorkit.model.frames import ros_plugin

    plugin = ros_plugin(sensor, "ros1")
    if plugin is None:
        return {}, [_no_plugin(sensor, "ros1", robot)]
    ns = (plugin.param("robotNamespace") or "").strip("/")

    def full(*parts: str) -> str:
        # The camera utils advertise on a NodeHandle in robotNamespace/cameraName
        # (ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a46:gazebo_plugins/src/
        # gazebo_ros_camera_utils.cpp:288, :321-340), the others on one in robotNamespace;
        # ROS 1 resolves a name that starts with "/" as global, in no namespace
        # (http://wiki.ros.org/Names, "Resolving"): an absolute topic name is not nested.
        last = parts[-1].strip() if parts else ""
        if last.startswith("/"):
            return _abs(last)
        return _abs("/".join(p.strip("/") for p in (ns, *parts) if p.strip("/")))

    if sensor.is_camera:
        cam = plugin.param("cameraName") or ""
        topics = {
            "image": full(cam, plugin.param("imageTopicName") or "image_raw"),
            "camera_info": full(cam, plugin.param("cameraInfoTopicName") or "camera_info"),
        }
        if sensor.is_depth:
            topics["depth_image"] = full(
                cam, plugin.param("depthImageTopicName") or "depth/image_raw"
            )
            topics["depth_camera_info"] = full(
                cam, plugin.param("depthImageCameraInfoTopicName") or "depth/camera_info"
            )
            topics["points"] = full(cam, plugin.param("pointCloudTopicName") or "points")
        return topics, []
    name = plugin.param("topicName")
    if not name:
        return {}, ["ROS 1 plugin without <topicName>: topic not known"]
    role = "scan" if sensor.kind == "lidar" else "imu" if sensor.kind == "imu" else "out"
    return {role: full(name)}, []


def _gz_roles(sensor: Sensor, entries: Iterable[BridgeEntry]) -> dict[str, str]:
    from sensorkit.knowledge.gazebo_sim import gz_own_subtopics

    topics: dict[str, str] = {}
    own = {
        name.strip("/"): role
        for entry in entries
        for name, role, _ in gz_own_subtopics(sensor.type, entry.gz_topic_name.strip("/"))
    }
    for entry in entries:
        ros = _abs(entry.ros_topic_name)
        kind = entry.ros_type_name.rsplit("/", 1)[-1]
        if own:  # segmentation / bounding-box camera: colored_map, labels_map, boxes, image
            role = own.get(entry.gz_topic_name.strip("/"))
            if role is not None:
                topics[role] = ros
            continue
        if kind == "Image":
            depth = sensor.kind == "depth" or entry.gz_topic_name.endswith("depth_image")
            topics["depth_image" if depth else "image"] = ros
        elif kind == "CameraInfo":
            if sensor.kind != "depth":
                topics["camera_info"] = ros
            if sensor.is_depth:  # the depth image is registered to the colour one
                topics["depth_camera_info"] = ros
        elif kind == "PointCloud2":
            topics["points"] = ros
        elif kind == "LaserScan":
            topics["scan"] = ros
        elif kind == "Imu":
            topics["imu"] = ros
    return topics


def _gz_entries(sensor: Sensor, target: str) -> list[BridgeEntry]:
    from sensorkit.describe.bridge import sensor_entries

    return sensor_entries(sensor.element, target)


def sensor_topics(
    sensor: Sensor, target: str, robot: Robot | None = None
) -> tuple[dict[str, str], list[str]]:
    """``(role -> ROS topic, notes)``: the ROS topics of ``sensor`` under ``target``.

    Roles: ``image``, ``camera_info``, ``depth_image``, ``depth_camera_info``,
    ``points``, ``scan``, ``range``, ``imu``, ``out`` and ``trigger`` (the one the
    camera subscribes to); a multicamera's
    are ``<camera>/image`` and ``<camera>/camera_info``. Gazebo Classic: the plugin's
    names after namespace and remapping (``~/out:=scan`` -> ``/scan``). Gazebo Sim: the
    ROS names of the ros_gz_bridge entries ``sensorkit new`` writes for the sensor's
    ``<topic>`` (``X/image`` -> ``/X/image_raw``, ...); a sensor without ``<topic>``
    publishes under the world's scoped name, which no file can name. With ``robot``, a
    sensor without a plugin of its own that a model-level plugin reads says so in its notes
    rather than "publishes nothing" (:mod:`sensorkit.model.owners`, as SK607 does).
    """
    from sensorkit.model.targets import is_gz

    if is_gz(target):
        if not sensor.topic:
            return {}, [
                "no <topic>: Gazebo Sim publishes under a name scoped by the world, "
                "which cannot be bridged from here; give the sensor a <topic>"
            ]
        try:
            entries = _gz_entries(sensor, target)
        except InvalidValue as exc:
            return {}, [f"cannot name its topics: {exc}"]
        if not entries:
            return {}, [f"sensor type {sensor.type!r} has no ros_gz_bridge message type"]
        return _gz_roles(sensor, entries), []
    if target == "ros1":
        return _ros1_topics(sensor, robot)
    return _ros2_topics(sensor, robot)


def gz_roles(sensor: Sensor, entry: BridgeEntry) -> list[str]:
    """The roles :func:`sensor_topics` gives one gz topic of ``sensor`` (``image``,
    ``depth_image``, ``camera_info``, ...; an RGB-D camera_info serves both images)."""
    return list(_gz_roles(sensor, [entry]))
