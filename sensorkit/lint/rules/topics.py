"""SK605, SK606, SK609: the ROS topics sensors publish.

Two sensors on one resolved topic, a ray plugin's message type, and a ``<remapping>`` that
matches none of the plugin's topics.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator

from lxml import etree

from sensorkit.base.consequence import Consequence, Role
from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.gazebo_ros import RAY_OUTPUT_TYPES
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.topic_names import (
    gz_topics,
    plugin_services,
    plugin_topics,
    resolve_name,
    resolved_topics,
)
from sensorkit.model.sensors import Sensor
from sensorkit.model.targets import is_gz


def _is_range(s: Sensor) -> bool:
    """Range sensors (sonar, IR): many on one topic is the ROS habit, each message carries its
    own frame_id (sensor_msgs/Range), and consumers such as range_sensor_layer expect it."""
    return any(
        p.library == "gazebo_ros_ray_sensor" and (p.param("output_type") or "").endswith("/Range")
        for p in s.plugins
    ) or any(p.library == "gazebo_ros_range" for p in s.plugins)


@rule(
    "SK605",
    "error/warning/info",
    "two sensors publish on the same resolved ROS topic (namespace + camera_name/sensor name + suffix; "
    "`~/out` + remappings). Severity by consequence: an error when subscribers get two streams of "
    "different data interleaved; info when the only topics shared are camera_info and both cameras "
    "publish the same K and P (a duplicate, not wrong data); a warning on Gazebo Sim when a known "
    "bridge carries none of the shared gz topics to ROS (only gz subscribers get the mixed stream)",
    formats=("urdf", "sdf"),
)
def topic_collisions(ctx: Context) -> Iterator[Finding]:
    if ctx.target == "ros1":
        return  # ROS 1 topic names (robotNamespace, *TopicName, tf_prefix) are not modelled
    owners: dict[str, list[tuple[Sensor, etree._Element]]] = defaultdict(list)
    for s in ctx.robot.sensors:
        if is_gz(ctx.target):
            for t in dict.fromkeys(gz_topics(s)):
                owners[t].append((s, s.element))
        else:
            for p in s.plugins:
                for _, full in dict.fromkeys(resolved_topics(p, s)):
                    owners[full].append((s, p.element))
    reported: set[tuple[int, int]] = set()
    for items in owners.values():
        if len(items) < 2:
            continue
        (first, _), (second, el) = items[0], items[1]
        key = (id(first), id(second))
        if first is second or key in reported or (_is_range(first) and _is_range(second)):
            continue
        reported.add(key)
        shared = [
            t
            for t, its in owners.items()
            if any(x is first for x, _ in its) and any(x is second for x, _ in its)
        ]
        c = _collision(ctx, first, second, shared)
        unbridged = _gz_only(ctx, shared)
        if unbridged:
            c = Consequence(Role.SIM_TOPIC, c.intended, c.effective, c.equal)
        yield ctx.judged(
            "SK605",
            c,
            f"sensors {first.name!r} (on {first.reference!r}) and {second.name!r} (on {second.reference!r}) "
            f"both publish on {', '.join(shared)}: subscribers get both streams interleaved"
            + (": the same calibration twice" if c.changes_nothing else "")
            + (
                f"; no entry of {unbridged} carries {'it' if len(shared) == 1 else 'them'} "
                "to ROS, so only gz subscribers get the mixed stream"
                if unbridged
                else ""
            ),
            el,
            sensor=second.name,
            fix=(
                "give each sensor its own <topic>"
                if is_gz(ctx.target)
                else "give each camera its own sensor name or <camera_name>, a <ros><namespace>, or a remapping"
            ),
        )


def _gz_only(ctx: Context, shared: list[str]) -> str | None:
    """The known bridge's files when it carries none of the gz topics ``shared`` to ROS
    (ros_gz_bridge bridges the entries of its config_file only: gazebosim/ros_gz@jazzy
    739cb42:ros_gz_bridge/src/ros_gz_bridge.cpp:54-62, :88-102), else None: two sensors
    mixed on a gz topic nothing bridges give ROS nothing wrong (issue 35)."""
    from sensorkit.lint.rules.bridge import known_bridge
    from sensorkit.lint.rules.topic_names import is_bridged

    if not is_gz(ctx.target) or ctx.bridge is None:
        return None
    bridged = known_bridge(ctx)
    if bridged is None or any(is_bridged(t, False, bridged) for t in shared):
        return None
    return ", ".join(ctx.bridge.files)


def _collision(ctx: Context, first: Sensor, second: Sensor, shared: list[str]) -> Consequence:
    """What subscribers of the shared topics get instead of ``second``'s own stream.

    Only camera_info shared, between cameras whose camera_info is computed from the same
    inputs: the same K, D and P twice. camera_info is a function of the image size,
    horizontal_fov, <lens>, <distortion> and the plugin's calibration parameters
    (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:
    359-374 cx, cy, fx; :399 hack_baseline; :402-414 D; :427-458 K and P), except that gz-sim
    gives the second camera of a link a baseline of its own (gazebosim/gz-sim@gz-sim8:
    src/systems/sensors/Sensors.cc:1189-1224), so on Gazebo Sim two cameras of one link are
    never called the same."""
    if shared and all(t.endswith("camera_info") for t in shared):
        a, b = _calibration(ctx, first), _calibration(ctx, second)
        if a is not None and b is not None:
            return Consequence(Role.CALIBRATION, b, a)
    return Consequence(Role.TOPIC, f"{second.name}'s own stream", f"{second.name}'s and {first.name}'s interleaved")


def _calibration(ctx: Context, s: Sensor) -> str | None:
    """The inputs camera_info is computed from, in words; None when not a camera."""
    cam = s.camera if s.is_camera else None
    if cam is None or len(s.cameras) != 1:
        return None
    if is_gz(ctx.target):
        def link(x: Sensor) -> str | None:
            ref = x.reference
            return ctx.conversion.survivor(ref) if ref in ctx.robot.link_map else ref

        if any(o is not s and o.is_camera and link(o) == link(s) for o in ctx.robot.sensors):
            return None  # a gz stereo baseline may differ (see _collision)
    params = sorted(
        f"{k} {p.param(k)}"
        for p in s.plugins
        for k in ("focal_length", "cx", "cy", "hack_baseline", "focalLength", "Cx", "Cy", "CxPrime", "hackBaseline")
        if p.param(k) is not None
    )
    parts = [f"{cam.width}x{cam.height}", f"hfov {cam.hfov if cam.hfov is not None else 1.047:g}"]
    if cam.lens_intrinsics is not None:
        parts.append(f"lens {cam.lens_intrinsics}")
    parts += [f"{k} {v:g}" for k, v in sorted(cam.distortion.items())] + params
    return ", ".join(parts)


@rule(
    "SK606",
    "warning/error",
    "ray plugin output_type missing (defaults to PointCloud2: warning) or invalid (error)",
    "gazebo_ros, at run time",
    formats=("urdf", "sdf"),
)
def ray_output_type(ctx: Context) -> Iterator[Finding]:
    if ctx.target != "classic":
        return
    for s in ctx.robot.sensors:
        for p in s.plugins:
            if p.library != "gazebo_ros_ray_sensor":
                continue
            value = p.param("output_type")
            if value is None:
                yield ctx.finding(
                    "SK606",
                    Severity.WARNING,
                    f"ray plugin {p.name!r} on {s.name!r} has no <output_type>: it publishes sensor_msgs/PointCloud2 "
                    "(a 2D lidar usually wants LaserScan)",
                    p.source,
                    sensor=s.name,
                    fix="add <output_type>sensor_msgs/LaserScan</output_type> (or PointCloud2 for a 3D lidar)",
                )
            elif value not in RAY_OUTPUT_TYPES:
                # An error: gazebo_ros_ray_sensor logs "Invalid <output_type> [...]" and returns
                # from Load before it subscribes or publishes (ros-simulation/gazebo_ros_pkgs@ros2
                # (d52f7c4):gazebo_plugins/src/gazebo_ros_ray_sensor.cpp:122-138).
                yield ctx.finding(
                    "SK606",
                    Severity.ERROR,
                    f"ray plugin {p.name!r}: <output_type>{value}</output_type> is not one gazebo_ros_ray_sensor knows; "
                    "it publishes nothing",
                    p.source,
                    sensor=s.name,
                    fix="use sensor_msgs/LaserScan, sensor_msgs/PointCloud2, sensor_msgs/PointCloud or sensor_msgs/Range"
                    + (
                        f" (without '/msg/': {value.replace('/msg/', '/')})"
                        if "/msg/" in value
                        else ""
                    ),
                )


@rule(
    "SK609",
    "warning",
    "a `<remapping>` whose source matches none of the topics the plugin publishes (it changes nothing: e.g. `scan:=...` on gazebo_ros_ray_sensor, which publishes `~/out`)",
    formats=("urdf", "sdf"),
)
def useless_remapping(ctx: Context) -> Iterator[Finding]:
    if is_gz(ctx.target):
        return
    for s in ctx.robot.sensors:
        for p in s.plugins:
            names = plugin_topics(p, s)
            if not names:
                continue
            ns, node = p.namespace(), p.name
            published = {resolve_name(n, ns, node) for n in names}
            services = {resolve_name(n, ns, node) for n in plugin_services(p)}
            for src, dst, el in p.remappings():
                if resolve_name(src, ns, node) in published | services:
                    continue
                hint = "~/out" if "~/out" in names else names[0]
                yield ctx.finding(
                    "SK609",
                    Severity.WARNING,
                    f"remapping {src}:={dst} on {p.filename} matches none of its topics "
                    f"({', '.join(sorted(published))}): it changes nothing",
                    el,
                    sensor=s.name,
                    fix=f"remap the name it publishes: <remapping>{hint}:={dst}</remapping>",
                )


