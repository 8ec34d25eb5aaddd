"""SK607, SK612: what reaches ROS.

A sensor that publishes nothing to ROS (no plugin on Classic; on Gazebo Sim, no
ros_gz_bridge entry for any of its topics), and a bridge entry of a sensor message type
that no sensor of the robot feeds.
"""

from __future__ import annotations

from collections.abc import Iterator

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.gazebo_sim import gz_never_created
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.topic_names import gz_primary_topic, gz_topics, is_bridged, norm_topic
from sensorkit.model.parse import local
from sensorkit.model.sensors import Sensor
from sensorkit.model.targets import is_gz


def _scoped_link(ctx: Context, s: Sensor) -> str:
    """The link a sensor belongs to in Gazebo: its own, or the one lumping merges it into."""
    ref = s.reference or "LINK"
    return ctx.conversion.survivor(ref) if ref in ctx.robot.link_map else ref


def _ros2_control_sensors(ctx: Context) -> set[str]:
    """Sensors a ros2_control simulation plugin reads by name: a <ros2_control><sensor name=...>
    matching the simulator sensor's name. Gazebo Classic's gazebo_ros2_control
    (ros-controls/gazebo_ros2_control@humble:gazebo_ros2_control/src/gazebo_system.cpp:554-589,
    IMU and force-torque) and Gazebo Sim's gz_ros2_control
    (ros-controls/gz_ros2_control@jazzy:gz_ros2_control/src/gz_system.cpp:426-448;
    @humble:ign_ros2_control/src/ign_system.cpp:430-452, IMU). Only with the plugin loaded."""
    plugins = (
        ("gz_ros2_control", "ign_ros2_control") if is_gz(ctx.target) else ("gazebo_ros2_control",)
    )
    if not any(p.library.startswith(plugins) for p in ctx.robot.model_plugins):
        return set()
    root = ctx.robot.document.root
    return {
        el.get("name", "")
        for block in root
        if local(block) == "ros2_control"
        for el in block
        if local(el) == "sensor"
    }


def _is_published_by_model_plugin(ctx: Context, s: Sensor) -> bool:
    """A model-level plugin names this sensor among its parameters (it publishes it by name)."""
    for p in ctx.robot.model_plugins:
        for el in p.element.iter():
            if (
                el is not p.element
                and isinstance(el.tag, str)
                and (el.text or "").strip() == s.name
            ):
                return True
    return False


@rule(
    "SK607",
    "warning",
    "a sensor publishes nothing to ROS (no plugin on classic, and no model-level plugin that "
    "publishes it by name; on gz: no ros_gz_bridge entry for its topic when a bridge is known, "
    "info on the scoped default topic when none is)",
)
def publishes_nothing(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    bridged = (
        {norm_topic(t.gz) for t in bridge.topics if t.to_ros}
        if bridge is not None and bridge.files
        else None
    )
    via_control = _ros2_control_sensors(ctx)
    for s in ctx.robot.sensors:
        if is_gz(ctx.target):
            topic = gz_primary_topic(s)
            if topic is None or (s.kind == "imu" and s.name in via_control):
                continue
            if gz_never_created(ctx.target, s.type):  # never created (SK613): nothing to bridge
                continue
            if bridged is None:
                if not s.topic:
                    yield ctx.finding(
                        "SK607",
                        Severity.INFO,
                        f"sensor {s.name!r} has no <topic>: Gazebo Sim publishes it on its scoped default "
                        f"/world/WORLD/model/MODEL/link/{_scoped_link(ctx, s)}{topic}; a ros_gz_bridge entry must "
                        "name that topic for ROS to see it (no bridge configuration is known: pass --bridge FILE)",
                        s.source,
                        sensor=s.name,
                        fix=f"add <topic>{s.name}</topic> (a short, stable name) and bridge it",
                    )
                continue
            # Any of its topics will do: images often travel through ros_gz_image's
            # image_bridge, started by a launch file, while camera_info goes through the YAML.
            topics = gz_topics(s) if s.topic else [topic, f"/sensor/{s.name}/"]
            if any(is_bridged(t, not s.topic, bridged) for t in topics):
                continue
            shown = (
                topic if s.topic else f"/world/WORLD/model/MODEL/link/{_scoped_link(ctx, s)}{topic}"
            )
            yield ctx.finding(
                "SK607",
                Severity.WARNING,
                f"sensor {s.name!r} publishes on gz topic {shown}, and no entry of "
                f"{', '.join(bridge.files) if bridge else ''} names any of its topics: unless a launch "
                "file bridges them some other way, ROS never sees this sensor",
                s.source,
                sensor=s.name,
                fix=f"add a GZ_TO_ROS entry with gz_topic_name: {topic.lstrip('/') if s.topic else '...' + topic}",
            )
        elif (
            not s.plugins
            and s.name not in via_control
            and not _is_published_by_model_plugin(ctx, s)
        ):
            yield ctx.finding(
                "SK607",
                Severity.WARNING,
                f"sensor {s.name!r} has no plugin: Gazebo Classic simulates it but publishes nothing to ROS",
                s.source,
                sensor=s.name,
                fix="add the gazebo_ros plugin for its type (libgazebo_ros_camera.so, libgazebo_ros_ray_sensor.so, libgazebo_ros_imu_sensor.so)",
            )


# ROS message types that carry sensor data: a bridge entry of one of these whose gz topic
# no sensor publishes is probably a typo (or a sensor outside this robot).
SENSOR_MSG_TYPES = frozenset(
    {
        "sensor_msgs/msg/Image",
        "sensor_msgs/msg/CameraInfo",
        "sensor_msgs/msg/LaserScan",
        "sensor_msgs/msg/PointCloud2",
        "sensor_msgs/msg/Imu",
        "sensor_msgs/msg/NavSatFix",
    }
)


@rule(
    "SK612",
    "info",
    "a ros_gz_bridge entry of a sensor message type whose gz topic no sensor of the robot publishes "
    "(a typo, or a sensor outside this description)",
)
def stale_bridge_entry(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    if bridge is None or not bridge.files or not is_gz(ctx.target) or not ctx.robot.sensors:
        return
    from sensorkit.base.findings import SourceRef
    from sensorkit.base.suggest import closest

    explicit: set[str] = set()
    scoped: list[str] = []
    for s in ctx.robot.sensors:
        if s.topic:
            explicit.update(gz_topics(s))
        else:
            scoped.append(f"/sensor/{s.name}/")
    for t in bridge.topics:
        if (t.ros_type or "").replace("/msg/", "/") not in {
            x.replace("/msg/", "/") for x in SENSOR_MSG_TYPES
        }:
            continue
        gz = norm_topic(t.gz)
        if gz in explicit or any(tail in gz + "/" for tail in scoped) or "$" in gz or "<" in gz:
            continue
        hint = closest(gz, explicit)
        yield ctx.finding(
            "SK612",
            Severity.INFO,
            f"bridge entry for gz topic {t.gz!r} ({t.ros_type}) matches no sensor of this robot",
            SourceRef(t.file, t.line),
            fix=f"did you mean {hint[0].lstrip('/')!r}?"
            if hint
            else "remove it, or check the sensor's <topic>",
        )


