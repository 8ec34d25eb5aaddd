"""SK6xx: plugins, topics and targets."""

from __future__ import annotations

import re
from collections import defaultdict
from collections.abc import Iterator
from dataclasses import dataclass

from lxml import etree

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.gazebo_ros import (
    RAY_OUTPUT_TYPES,
    ROS1_ONLY,
    ROS1_TO_ROS2_PARAMS,
    ROS2_ONLY,
    ROS2_PLUGINS,
)
from sensorkit.knowledge.gazebo_sim import (
    GZ_NAVSAT_SUFFIX,
    GZ_NAVSAT_TYPES,
    GZ_UNSUPPORTED_SENSOR_TYPES,
)
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.frames import GZ_DEPRECATED_FRAME_TAGS, GZ_FRAME_TAGS, GZ_OPTICAL_FRAME_ID
from sensorkit.model.parse import child, children, local
from sensorkit.model.robot import all_plugins
from sensorkit.model.sensors import Plugin, Sensor
from sensorkit.model.targets import is_classic_plugin, is_gz, is_gz_plugin

GZ_FRAME_TAG_NAMES = ("gz_frame_id", "ignition_frame_id", "frame_id")


def _ros_name(p: Plugin) -> str | None:
    """``gazebo_ros_camera`` -> ``camera`` for gazebo_ros plugins, else None."""
    lib = p.library
    if lib.startswith("gazebo_ros_") and lib not in ("gazebo_ros_control", "gazebo_ros2_control"):
        return lib[len("gazebo_ros_") :]
    if lib == "gazebo_ros_control":
        return "control"
    return None


@rule(
    "SK601",
    "error/warning/info",
    "plugin library exists for the target; name the replacement (ROS 1 `libgazebo_ros_depth_camera.so` -> "
    "`libgazebo_ros_camera.so` with a depth sensor, `libgazebo_ros_laser.so`/`gpu_laser` -> "
    "`libgazebo_ros_ray_sensor.so`, `libgazebo_ros_*` under gz -> gz sensors + ros_gz_bridge); a placeholder "
    "filename (`dummyfile`) exists for no target (a warning on gz, where the sensor still publishes)",
)
def plugin_exists(ctx: Context) -> Iterator[Finding]:
    for p in all_plugins(ctx.robot):
        problem = plugin_problem(p, ctx.target)
        if problem is None:
            continue
        severity, message, fix = problem
        if p.sensor is not None and severity == Severity.ERROR and not is_gz(ctx.target):
            # Its frame findings are folded in here: the sensor's frame is checked once
            # a plugin that loads names one.
            fix += _frame_advice(ctx, p.sensor)
        yield ctx.finding(
            "SK601",
            severity,
            message,
            p.source,
            sensor=p.sensor.name if p.sensor else None,
            fix=fix,
        )


# Filenames that name no library at all: copied placeholders. Gazebo Sim resolves a
# plugin's filename through its plugin paths and logs "Failed to load system plugin"
# when nothing matches, loading nothing (gazebosim/gz-sim@gz-sim8:src/SystemLoader.cc).
PLACEHOLDERS = frozenset({"", "dummy", "dummyfile", "placeholder", "todo", "none", "null", "foo"})


def plugin_problem(p: Plugin, target: str) -> tuple[Severity, str, str] | None:
    """Why ``p`` cannot load under ``target`` as (severity, message, fix), or None."""
    if p.library.strip().lower() in PLACEHOLDERS:
        if is_gz(target):
            return (
                Severity.WARNING,
                f"plugin filename {p.filename!r} names no library: Gazebo Sim logs an error and loads "
                "nothing (the sensor itself still publishes on its <topic>)",
                "remove the placeholder <plugin>, or name the system you meant",
            )
        return (
            Severity.ERROR,
            f"plugin filename {p.filename!r} names no library: Gazebo cannot load it"
            + (" and the sensor publishes nothing to ROS" if p.sensor is not None else ""),
            "name the real plugin library (e.g. libgazebo_ros_camera.so, libgazebo_ros_ray_sensor.so)",
        )
    name = _ros_name(p)
    if is_gz(target):
        if is_classic_plugin(p.filename):
            return (
                Severity.ERROR,
                f"{p.filename} is a Gazebo Classic plugin: Gazebo Sim ({target}) never loads it",
                "remove it: Gazebo Sim sensors publish on <topic> by themselves; bridge them to ROS with ros_gz_bridge",
            )
        if target == "fortress" and p.filename.rsplit("/", 1)[-1].startswith(
            ("gz-sim", "libgz-sim")
        ):
            # Fortress maps gz-sim to ignition-gazebo from ignition-gazebo 6.16.0
            # (gazebosim/gz-sim@ign-gazebo6 aab5556:src/SystemLoader.cc:73-79); before it,
            # the library is not found.
            fixed = p.filename.replace("libgz-sim", "libignition-gazebo").replace(
                "gz-sim", "ignition-gazebo"
            )
            return (
                Severity.INFO,
                f"{p.filename} loads on Fortress from ignition-gazebo 6.16 on, which maps gz-sim "
                "to ignition-gazebo; an older Fortress does not find it",
                f"write {fixed} to support every Fortress release",
            )
        return None
    if is_gz_plugin(p.filename):
        return (
            Severity.ERROR,
            f"{p.filename} is a Gazebo Sim system: Gazebo Classic never loads it",
            "use the gazebo_ros plugin for Classic, or validate with --target harmonic/fortress/jetty",
        )
    if name is None:
        return None
    if target == "classic" and name in ROS1_ONLY:
        return (
            Severity.ERROR,
            f"{p.filename} exists only in ROS 1: ROS 2 Gazebo Classic cannot load it"
            + (" and the sensor publishes nothing" if p.sensor is not None else ""),
            f"use {ROS1_ONLY[name]}",
        )
    if target == "ros1" and name in ROS2_ONLY:
        return (
            Severity.ERROR,
            f"{p.filename} exists only in ROS 2 gazebo_plugins",
            "use the ROS 1 plugin (e.g. libgazebo_ros_laser.so), or --target classic",
        )
    return None


def _frame_advice(ctx: Context, s: Sensor) -> str:
    """The frame the replacement plugin should name (folded in, instead of frame findings)."""
    from sensorkit.model.frames import optical_frame_at

    fr = ctx.frames_of(s)
    if fr.link is None:
        return ""
    if s.is_camera:
        frame = optical_frame_at(ctx.robot, fr.T_world_render)
        if frame is None:
            return f"; then publish in an optical frame at the camera (add {fr.link}_optical_frame)"
    else:
        frame = fr.link
    return f", with <frame_name>{frame}</frame_name>"


@rule(
    "SK602",
    "error",
    "ROS 1 parameter tags inside a ROS 2 plugin (`frameName`, `cameraName`, `imageTopicName`, `topicName`, "
    "`robotNamespace`, `hackBaseline`, `updateRate`, ...) are silently ignored: name the ROS 2 form",
)
def ros1_params(ctx: Context) -> Iterator[Finding]:
    if ctx.target != "classic":
        return
    for p in all_plugins(ctx.robot):
        name = _ros_name(p)
        if name is None or name not in ROS2_PLUGINS:
            continue
        sensor = p.sensor.name if p.sensor else None
        for el in p.param_elements():
            tag = local(el)
            if tag in ROS1_TO_ROS2_PARAMS:
                yield ctx.finding(
                    "SK602",
                    Severity.ERROR,
                    f"<{tag}> is a ROS 1 parameter: the ROS 2 {p.filename} never reads it and says nothing",
                    el,
                    sensor=sensor,
                    fix=f"use {ROS1_TO_ROS2_PARAMS[tag]}",
                )
        ros = p.ros_block()
        if ros is not None:
            for el in children(ros, "remap"):
                src, dst = el.get("from", "FROM"), el.get("to", "TO")
                yield ctx.finding(
                    "SK602",
                    Severity.ERROR,
                    f'<remap from="{src}" to="{dst}"/> is ROS 1 launch syntax: gazebo_ros ignores it',
                    el,
                    sensor=sensor,
                    fix=f"<remapping>{src}:={dst}</remapping>",
                )


@rule(
    "SK603",
    "error",
    "plugin matches the sensor type (camera plugin on camera/depth/multicamera; ray plugin on ray/gpu_ray; imu plugin on imu)",
)
def plugin_sensor_type(ctx: Context) -> Iterator[Finding]:
    if is_gz(ctx.target):
        return
    from sensorkit.knowledge import plugins as known
    from sensorkit.model.frames import ros_generation

    for s in ctx.robot.sensors:
        for p in s.plugins:
            spec = known.lookup(p.filename, ros_generation(ctx.target))
            kinds = spec.sensor_types if spec is not None and spec.level == "sensor" else None
            if not kinds or s.type in kinds:
                continue
            yield ctx.finding(
                "SK603",
                Severity.ERROR,
                f"{p.filename} on sensor {s.name!r} of type {s.type!r}: it only works on "
                + "/".join(sorted(kinds)),
                p.source,
                sensor=s.name,
                fix=f"change the sensor type to {sorted(kinds)[0]} or use the plugin for {s.type}",
            )


def _is_ros2_gazebo_plugin(p: Plugin) -> bool:
    name = _ros_name(p)
    return name is not None or p.library.startswith(("gazebo_ros", "gazebo_ros2"))


def _resolve(name: str, ns: str, node: str) -> str:
    """ROS 2 name resolution (rcl) of a topic name for a node in ``ns``."""
    ns = "/" + ns.strip("/") if ns.strip("/") else ""
    if name.startswith("/"):
        return "/" + name.strip("/")
    if name.startswith("~"):
        rest = name[1:].lstrip("/")
        return f"{ns}/{node}" + (f"/{rest}" if rest else "")
    return f"{ns}/{name.strip('/')}"


@dataclass
class Topic:
    """A resolved topic name and the sensor and plugin that publish it."""

    name: str  # resolved
    sensor: Sensor | None
    plugin: Plugin | None
    element: etree._Element


def plugin_topics(p: Plugin, s: Sensor | None) -> list[str]:
    """Unresolved names a known sensor plugin publishes (before remapping)."""
    lib = p.library
    if lib == "gazebo_ros_camera" and s is not None:
        cam = p.param("camera_name") or s.name
        names = [f"{cam}/image_raw", f"{cam}/camera_info"]
        if s.kind == "depth":
            names += [f"{cam}/depth/image_raw", f"{cam}/depth/camera_info", f"{cam}/points"]
        if s.kind == "multicamera":
            names = []
            for c in s.cameras:
                names += [f"{cam}/{c.name}/image_raw", f"{cam}/{c.name}/camera_info"]
        # <triggered> is read from the plugin element, not the sensor's <camera>
        # (gazebo_ros_pkgs@d52f7c4 gazebo_plugins/src/gazebo_ros_camera.cpp:271
        # `_sdf->Get<bool>("triggered", false)`, _sdf being the plugin's SDF).
        if (p.param("triggered") or "").strip().lower() in ("true", "1"):
            names.append(f"{cam}/image_trigger")
        return names
    # Other sensor plugins: the topics the plugin table lists (gazebo_ros_camera's depend on
    # the sensor's kind, above). Parameters that rename a topic are ROS 1 only.
    from sensorkit.knowledge import plugins as known

    spec = known.lookup(p.filename, "ros2")
    if spec is None or spec.level != "sensor":
        return []
    return [
        p.param(param) or default if param else default for param, default in spec.topics if default
    ]


def plugin_services(p: Plugin) -> list[str]:
    """Unresolved names of services a known sensor plugin offers (remappable too)."""
    if p.library == "gazebo_ros_camera":
        # camera_info_manager creates "set_camera_info" relative to the node's namespace.
        return ["set_camera_info"]
    return []


def resolved_topics(p: Plugin, s: Sensor | None) -> list[tuple[str, str]]:
    """(unresolved, resolved-after-remapping) for a plugin's topics."""
    ns, node = p.namespace(), p.name
    rules = [(_resolve(a, ns, node), _resolve(b, ns, node)) for a, b, _ in p.remappings()]
    out = []
    for name in plugin_topics(p, s):
        full = _resolve(name, ns, node)
        for src, dst in rules:
            if src == full:
                full = dst
                break
        out.append((name, full))
    return out


def gz_topics(s: Sensor) -> list[str]:
    """Topics a gz sensor publishes, from its <topic> (empty: gz's scoped default)."""
    if not s.topic:
        return []
    base = "/" + s.topic.strip("/")
    if s.kind == "rgbd":
        return [f"{base}/image", f"{base}/depth_image", f"{base}/points", f"{base}/camera_info"]
    if s.kind == "depth":
        return [base, f"{base}/points", _info_topic(s, base)]
    if s.kind in ("camera", "multicamera"):
        return [base, _info_topic(s, base)]
    if s.kind == "lidar":
        return [base, f"{base}/points"]
    return [base]


def _info_topic(s: Sensor, base: str) -> str:
    from sensorkit.knowledge.gazebo_sim import GZ_READS_CAMERA_INFO_TOPIC

    cam = s.camera
    if cam is not None and cam.camera_info_topic and s.type in GZ_READS_CAMERA_INFO_TOPIC:
        return "/" + cam.camera_info_topic.strip("/")
    parent = base.rsplit("/", 1)[0]
    return f"{parent}/camera_info"


@rule(
    "SK604",
    "error",
    "two plugins resolve to the same ROS 2 node name (gazebo_ros refuses the second)",
    "gazebo_ros, at run time",
)
def node_names(ctx: Context) -> Iterator[Finding]:
    if is_gz(ctx.target) or ctx.target == "ros1":
        # ROS 1: gzserver is one ROS node, "gazebo" (ros-simulation/gazebo_ros_pkgs@noetic-devel
        # f9e1a46:gazebo_ros/src/gazebo_ros_api_plugin.cpp:126 ros::init(..., "gazebo")), and
        # plugins only open ros::NodeHandles in it (gazebo_plugins/src/gazebo_ros_camera_utils.cpp:288;
        # velodyne: tier4/velodyne_simulator@master fe021b6:velodyne_gazebo_plugins/src/
        # GazeboRosVelodyneLaser.cpp:169): a plugin's name="..." names no node, so none clash.
        return
    from sensorkit.knowledge import plugins as known
    from sensorkit.knowledge.gazebo_ros import ROS2_LIBRARIES

    seen: dict[str, Plugin] = {}
    for p in all_plugins(ctx.robot):
        if not _is_ros2_gazebo_plugin(p) or not p.name:
            continue
        # Only plugins that load and that sensorkit knows make a ROS 2 node of their name.
        if plugin_problem(p, ctx.target) is not None or (
            p.library not in ROS2_LIBRARIES and known.lookup(p.filename, "ros2") is None
        ):
            continue
        full = _resolve(p.name, p.namespace(), "")
        if full in seen:
            first = seen[full]
            yield ctx.finding(
                "SK604",
                Severity.ERROR,
                f"plugins {first.name!r} ({first.filename}, line {first.source.line}) and {p.name!r} ({p.filename}) "
                f"are both ROS node {full!r}: gazebo_ros refuses the second",
                p.source,
                sensor=p.sensor.name if p.sensor else None,
                fix='give each plugin a unique name="..." (e.g. the sensor name + _controller)',
            )
        else:
            seen[full] = p


def _is_range(s: Sensor) -> bool:
    """Range sensors (sonar, IR): many on one topic is the ROS habit, each message carries its
    own frame_id (sensor_msgs/Range), and consumers such as range_sensor_layer expect it."""
    return any(
        p.library == "gazebo_ros_ray_sensor" and (p.param("output_type") or "").endswith("/Range")
        for p in s.plugins
    ) or any(p.library == "gazebo_ros_range" for p in s.plugins)


@rule(
    "SK605",
    "error",
    "two sensors publish on the same resolved ROS topic (namespace + camera_name/sensor name + suffix; `~/out` + remappings)",
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
        yield ctx.finding(
            "SK605",
            Severity.ERROR,
            f"sensors {first.name!r} (on {first.reference!r}) and {second.name!r} (on {second.reference!r}) "
            f"both publish on {', '.join(shared)}: subscribers get both streams interleaved",
            el,
            sensor=second.name,
            fix=(
                "give each sensor its own <topic>"
                if is_gz(ctx.target)
                else "give each camera its own sensor name or <camera_name>, a <ros><namespace>, or a remapping"
            ),
        )


@rule(
    "SK606",
    "warning/error",
    "ray plugin output_type missing (defaults to PointCloud2: warning) or invalid (error)",
    "gazebo_ros, at run time",
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


# What a Gazebo Sim sensor with no <topic> publishes on: its scoped name plus a suffix
# (gazebosim/gz-sim@gz-sim8:src/rendering/RenderUtil.cc:1723-1725 sets
# scopedName(entity) + suffix, suffixes at :1737-1744; IMU: src/systems/imu/Imu.cc:201).
# The scoped name is /world/WORLD/model/MODEL/link/LINK/sensor/NAME.
GZ_DEFAULT_SUFFIX = {
    "camera": "/image",
    "depth": "/depth_image",
    "rgbd": "/image",  # rgbd_camera's suffix is "" and it publishes BASE/image, BASE/depth_image
    "lidar": "/scan",
    "imu": "/imu",
}


def _norm(topic: str) -> str:
    return "/" + topic.strip().strip("/")


def gz_primary_topic(s: Sensor) -> str | None:
    """The gz topic that carries a sensor's main data (None for kinds sensorkit does not know)."""
    suffix = GZ_DEFAULT_SUFFIX.get(s.kind)
    if suffix is None and s.type in GZ_NAVSAT_TYPES:
        # NavSat (kind "other"): gz-sim's NavSat system publishes scopedName + "/navsat"
        # (gazebosim/gz-sim@gz-sim8:src/systems/navsat/NavSat.cc:182-186), with a <topic>
        # on that topic alone (gz-sensors@gz-sensors8:src/NavSatSensor.cc:107-111).
        suffix = GZ_NAVSAT_SUFFIX
    if suffix is None:
        return None
    if s.topic:
        topics = gz_topics(s)
        return topics[0] if topics else None
    return f"/sensor/{s.name}{suffix}"  # the tail of the scoped name


def _bridged(topic: str, scoped: bool, bridged: set[str]) -> bool:
    """``topic`` is carried by one of the bridged gz topics.

    A scoped topic is matched by its tail (``/sensor/NAME/image``): the world and model
    names are the launch's. Placeholders that a launch file fills in before starting the
    bridge (``<namespace>``, ``$(var x)``) match any one name.
    """
    if scoped:
        tail = topic.rstrip("/") + "/"
        return any(tail in b + "/" for b in bridged)
    want = _norm(topic)
    for b in bridged:
        if "<" in b or "$(" in b:
            parts = re.split(r"<[^>]*>|\$\([^)]*\)", b)
            if re.fullmatch("[^/]*".join(re.escape(x) for x in parts), want):
                return True
        elif b == want:
            return True
    return False


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
        {_norm(t.gz) for t in bridge.topics if t.to_ros}
        if bridge is not None and bridge.files
        else None
    )
    via_control = _ros2_control_sensors(ctx)
    for s in ctx.robot.sensors:
        if is_gz(ctx.target):
            topic = gz_primary_topic(s)
            if topic is None or (s.kind == "imu" and s.name in via_control):
                continue
            if s.type in GZ_UNSUPPORTED_SENSOR_TYPES:  # never created (SK613): nothing to bridge
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
            if any(_bridged(t, not s.topic, bridged) for t in topics):
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
        gz = _norm(t.gz)
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


@rule(
    "SK608",
    "warning",
    "a gz frame tag that the chosen gz version ignores (`ignition_frame_id` on harmonic+, `frame_id` before jetty, "
    "`optical_frame_id` on jetty, a tag another one overrides) or has deprecated (`gz_frame_id` on jetty)",
)
def ignored_frame_tags(ctx: Context) -> Iterator[Finding]:
    target = ctx.target
    if not is_gz(target):
        return
    read = GZ_FRAME_TAGS[target]
    deprecated = GZ_DEPRECATED_FRAME_TAGS.get(target, ())
    for s in ctx.robot.sensors:
        for tag in GZ_FRAME_TAG_NAMES:
            if tag not in s.frame_tags:
                continue
            first = next(t for t in read if t in s.frame_tags) if tag in read else None
            if tag not in read:
                why, fix = f"is ignored by {target}; it reads <{read[0]}>", None
            elif first != tag:
                why, fix = (
                    f"is ignored by {target}: <{first}> takes precedence",
                    f"keep one frame tag: <{first}>",
                )
            elif tag in deprecated:
                why, fix = (
                    f"is deprecated on {target}: still read, with a warning at every start",
                    None,
                )
            else:
                continue
            yield ctx.finding(
                "SK608",
                Severity.WARNING,
                f"sensor {s.name!r}: <{tag}> {why}",
                child(s.element, tag),
                sensor=s.name,
                frame=s.frame_tags[tag],
                fix=fix or f"write <{read[0]}>{s.frame_tags[tag]}</{read[0]}>",
            )
        for tag, value, el in s.misplaced_frame_tags:
            yield ctx.finding(
                "SK608",
                Severity.WARNING,
                f"sensor {s.name!r}: <{tag}> inside <camera> is never read (gz-sensors reads it from <sensor>)",
                el,
                sensor=s.name,
                frame=value,
                fix=f"move <{read[0]}>{value}</{read[0]}> directly under <sensor>",
            )
        cam = s.camera
        if cam is not None and cam.optical_frame_id and target not in GZ_OPTICAL_FRAME_ID:
            yield ctx.finding(
                "SK608",
                Severity.WARNING,
                f"sensor {s.name!r}: <optical_frame_id> is ignored by {target}",
                child(cam.element, "optical_frame_id"),
                sensor=s.name,
                frame=cam.optical_frame_id,
                fix=f"set <{read[0]}>{cam.optical_frame_id}</{read[0]}> on the sensor instead",
            )


@rule(
    "SK609",
    "warning",
    "a `<remapping>` whose source matches none of the topics the plugin publishes (it changes nothing: e.g. `scan:=...` on gazebo_ros_ray_sensor, which publishes `~/out`)",
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
            published = {_resolve(n, ns, node) for n in names}
            services = {_resolve(n, ns, node) for n in plugin_services(p)}
            for src, dst, el in p.remappings():
                if _resolve(src, ns, node) in published | services:
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


@rule(
    "SK610",
    "info",
    "a sensor's plugin is one sensorkit does not know: it cannot tell the frame or topics it "
    "publishes, so frame and topic rules stay silent for that sensor",
)
def unknown_plugin(ctx: Context) -> Iterator[Finding]:
    if is_gz(ctx.target):
        return  # Gazebo Sim sensors stamp and publish by themselves, whatever plugin rides along
    from sensorkit.base.suggest import closest
    from sensorkit.knowledge.gazebo_ros import ROS1_LIBRARIES, ROS2_LIBRARIES

    for s in ctx.robot.sensors:
        fr = ctx.frames_of(s)
        p = fr.plugin
        if not fr.unknown or p is None or plugin_problem(p, ctx.target) is not None:
            continue
        known_names = ROS1_LIBRARIES if ctx.target == "ros1" else ROS2_LIBRARIES
        hint = closest(p.library, known_names) if p.library.startswith("gazebo_ros") else []
        yield ctx.finding(
            "SK610",
            Severity.INFO,
            f"unknown plugin {p.filename}: sensorkit cannot tell the frame or topics of sensor {s.name!r}",
            p.source,
            sensor=s.name,
            fix=(
                f"if you meant lib{hint[0]}.so, name it; otherwise check its frame by hand"
                if hint
                else "check the frame it publishes in by hand (ros2 topic echo --once ... header.frame_id)"
            ),
        )


@rule(
    "SK611",
    "warning",
    "under `--target auto`, a description written for ROS 1 (ROS 1-only plugins and tags, "
    "nothing only ROS 2 has) is said once and validated as ROS 1, instead of one SK602 per tag",
)
def written_for_ros1(ctx: Context) -> Iterator[Finding]:
    if not (ctx.auto and ctx.target == "ros1"):
        return
    from sensorkit.model.targets import ros1_evidence

    ev = ros1_evidence(ctx.robot)
    yield ctx.finding(
        "SK611",
        Severity.WARNING,
        f"this description is written for ROS 1 ({ev.describe()}); validated as ROS 1 Gazebo "
        "Classic. Under ROS 2 none of these plugins publish as written",
        ctx.robot.document.root,
        fix="on ROS 1, pass --target ros1 to say so; to port it to ROS 2, validate with "
        "--target classic: every tag and plugin is listed with its ROS 2 form",
    )


@rule(
    "SK614",
    "warning",
    "on Gazebo Sim, a bridge carries a depth or RGB-D camera's point cloud, which gz-sensors computes "
    "x-forward but stamps with the optical frame (gz-sensors#488): RViz shows it turned on its side",
)
def xforward_cloud(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    if not is_gz(ctx.target) or bridge is None or not bridge.files:
        return
    from sensorkit.knowledge.gazebo_sim import (
        CLOUD_FIX,
        GZ_XFORWARD_CLOUD_NOTE,
        GZ_XFORWARD_CLOUD_TYPES,
    )

    bridged = {_norm(t.gz) for t in bridge.topics if t.to_ros}
    for s in ctx.robot.sensors:
        if s.type not in GZ_XFORWARD_CLOUD_TYPES or not s.topic:
            continue
        cloud = next((t for t in gz_topics(s) if t.endswith("/points")), None)
        if cloud is None or not _bridged(cloud, False, bridged):
            continue
        fr = ctx.frames_of(s)
        frame = fr.camera_frame
        T = fr.T_render_frame(ctx.robot, frame)
        if T is not None:
            from sensorkit.model.transforms import R_BODY_OPTICAL, angle_between, rotation

            if angle_between(rotation(T), R_BODY_OPTICAL) > 0.0087:
                continue  # stamped with an x-forward frame: the cloud lands right (SK502 covers images)
        yield ctx.finding(
            "SK614",
            Severity.WARNING,
            f"sensor {s.name!r}: the bridge carries its cloud {cloud}, but {GZ_XFORWARD_CLOUD_NOTE}: "
            f"stamped {frame!r}, RViz shows the cloud turned on its side (depth along the camera's "
            "right, the scene's up pointing ahead)",
            s.source,
            sensor=s.name,
            frame=frame,
            fix=CLOUD_FIX,
        )
