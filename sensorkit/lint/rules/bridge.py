"""SK607, SK612, SK615: what reaches ROS.

A sensor that publishes nothing to ROS (no plugin on Classic and no model-level plugin
that reads it, see sensorkit.model.owners; on Gazebo Sim, no ros_gz_bridge entry for any
of its topics, or for a camera's image while its camera_info is bridged), and a bridge entry of a sensor message type
that no sensor of the robot feeds.
"""

from __future__ import annotations

from collections.abc import Iterator

from sensorkit.base.consequence import UNKNOWN, Consequence, Role
from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.gazebo_sim import gz_never_created
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.topic_names import gz_primary_topic, gz_topics, is_bridged, norm_topic
from sensorkit.model.owners import sensor_owner
from sensorkit.model.sensors import Sensor
from sensorkit.model.targets import is_gz


def _scoped_link(ctx: Context, s: Sensor) -> str:
    """The link a sensor belongs to in Gazebo: its own, or the one lumping merges it into."""
    ref = s.reference or "LINK"
    return ctx.conversion.survivor(ref) if ref in ctx.robot.link_map else ref


def _scoped_path(ctx: Context, s: Sensor) -> str:
    """``MODEL/link/LINK`` of a sensor's scoped gz topic. An SDF link of a nested model is
    ``inner::link`` in the model, and gz-sim scopes it as ``MODEL/model/inner/link/link``:
    each entity adds its type and name (gazebosim/gz-sim@gz-sim8_8.9.0:src/Util.cc:138-183)."""
    link = _scoped_link(ctx, s)
    if ctx.robot.sdf is None:
        return f"MODEL/link/{link}"
    *models, name = link.split("::")
    return "MODEL" + "".join(f"/model/{m}" for m in models) + f"/link/{name}"


def _camera_split(s: Sensor, topics: list[str]) -> tuple[list[str], str] | None:
    """``(image topics, camera_info topic)`` of a gz camera, from :func:`gz_topics` order
    (or the scoped default); None for a sensor that is not a camera."""
    from sensorkit.knowledge.gazebo_sim import GZ_BOUNDINGBOX_TYPES, GZ_SEGMENTATION_TYPES

    if s.kind not in ("camera", "depth", "rgbd", "multicamera"):
        return None
    own = s.type in GZ_SEGMENTATION_TYPES or s.type in GZ_BOUNDINGBOX_TYPES
    if not s.topic:
        name = f"/sensor/{s.name}"
        images = [f"{name}/image", f"{name}/depth_image"] if s.kind == "rgbd" else [topics[0]]
        if s.type in GZ_BOUNDINGBOX_TYPES:
            images.append(f"{topics[0]}_image")
        info = f"{topics[0]}/camera_info" if s.type in GZ_SEGMENTATION_TYPES else f"{name}/camera_info"
        return images, info
    if s.kind == "rgbd":
        return topics[:2], topics[3]
    if own:  # colored and labels maps, or boxes and their image (gz_own_subtopics)
        return topics[:2], topics[2]
    return [topics[0]], topics[-1]


def _gz_unbridged(ctx: Context, s: Sensor, topic: str, bridged: set[str]) -> Finding | None:
    """SK607 for a gz sensor when a bridge is known: none of its topics bridged, or a
    camera whose camera_info is bridged and none of its images."""
    scoped = not s.topic
    topics = gz_topics(s) if s.topic else [topic, f"/sensor/{s.name}/"]
    files = ", ".join(ctx.bridge.files) if ctx.bridge else ""
    shown = topic if s.topic else f"/world/WORLD/model/{_scoped_path(ctx, s)}{topic}"
    fix_topic = topic.lstrip("/") if s.topic else "..." + topic
    if any(is_bridged(t, scoped, bridged) for t in topics):
        # A camera_info without its image: ROS gets the calibration of a camera it never sees.
        split = _camera_split(s, gz_topics(s) if s.topic else [topic])
        if split is None or not is_bridged(split[1], scoped, bridged):
            return None
        images, info = split
        if any(is_bridged(t, scoped, bridged) for t in images):
            return None
        # Info, not a warning, when the launch files are not known: projects often bridge the
        # image with ros_gz_image's image_bridge from a launch file (MOGI-ROS/
        # Week-9-10-Simple-arm@425c335:bme_ros2_simple_arm/launch/spawn_robot.launch.py:133-138
        # bridges /gripper_camera/image and /table_camera/image so, beside a gz_bridge.yaml
        # that carries only their camera_info). When the launch files read start a bridge,
        # fully read, and none of them carries the image either, it is a warning (issue 23).
        launch = ctx.launch
        known = launch is not None and bool(launch.bridges) and not launch.bridge_unknown
        if known and launch is not None:
            return ctx.finding(
                "SK607",
                Severity.WARNING,
                f"camera {s.name!r}: {files} bridges its camera_info ({info}) but not its image "
                f"({', '.join(images)}), and no bridge the launch files start "
                f"({', '.join(launch.files)}) carries it: ROS gets the calibration of a camera "
                "it never sees",
                s.source,
                sensor=s.name,
                fix=f"add a GZ_TO_ROS entry with gz_topic_name: {fix_topic} (sensor_msgs/msg/Image)",
            )
        return ctx.finding(
            "SK607",
            Severity.INFO,
            f"camera {s.name!r}: {files} bridges its camera_info ({info}) but not its image "
            f"({', '.join(images)}): unless a launch file bridges the image some other way "
            "(ros_gz_image's image_bridge), ROS gets the calibration of a camera it never sees",
            s.source,
            sensor=s.name,
            fix=f"add a GZ_TO_ROS entry with gz_topic_name: {fix_topic} (sensor_msgs/msg/Image)",
        )
    if ctx.launch is not None and ctx.launch.bridge_unknown:
        # A bridge the launch starts could not be read: it may carry this sensor.
        return ctx.finding(
            "SK607",
            Severity.INFO,
            f"sensor {s.name!r} publishes on gz topic {shown}, which no bridge entry sensorkit "
            f"read names; a bridge started in {', '.join(ctx.launch.bridge_unknown_in or ctx.launch.files)} "
            "could not be read, so "
            "sensorkit cannot tell whether it reaches ROS",
            s.source,
            sensor=s.name,
        )
    return ctx.finding(
        "SK607",
        Severity.WARNING,
        f"sensor {s.name!r} publishes on gz topic {shown}, and no entry of "
        f"{files} names any of its topics: unless a launch "
        "file bridges them some other way, ROS never sees this sensor",
        s.source,
        sensor=s.name,
        fix=f"add a GZ_TO_ROS entry with gz_topic_name: {fix_topic}",
    )


@rule(
    "SK607",
    "warning/info",
    "a sensor publishes nothing to ROS (no plugin on classic, and no model-level plugin that "
    "reads it by name: info when one may and sensorkit cannot tell; on gz: no ros_gz_bridge "
    "entry for its topic when a bridge is known, info for a camera's image when only its "
    "camera_info is bridged, and on the scoped default topic when no bridge is known)",
    formats=("urdf", "sdf"),
)
def publishes_nothing(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    bridged = (
        {norm_topic(t.gz) for t in bridge.topics if t.to_ros}
        if bridge is not None and bridge.files
        else None
    )
    for s in ctx.robot.sensors:
        owner = sensor_owner(ctx.robot, s, ctx.target)
        if is_gz(ctx.target):
            topic = gz_primary_topic(s)
            if topic is None or (owner is not None and owner.certain):
                continue
            if gz_never_created(ctx.target, s.type):  # never created (SK613): nothing to bridge
                continue
            if bridged is None:
                if not s.topic:
                    yield ctx.finding(
                        "SK607",
                        Severity.INFO,
                        f"sensor {s.name!r} has no <topic>: Gazebo Sim publishes it on its scoped default "
                        f"/world/WORLD/model/{_scoped_path(ctx, s)}{topic}; a ros_gz_bridge entry must "
                        "name that topic for ROS to see it (no bridge configuration is known: pass --bridge FILE)",
                        s.source,
                        sensor=s.name,
                        fix=f"add <topic>{s.name}</topic> (a short, stable name) and bridge it",
                    )
                continue
            found = _gz_unbridged(ctx, s, topic, bridged)
            if found is not None and owner is not None and found.severity > Severity.INFO:
                # A model plugin may read it (ArduPilot's <imuName>, a <ros2_control> block):
                # whether its data needs a bridge sensorkit cannot tell (issue 35).
                found = ctx.judged(
                    "SK607",
                    Consequence(Role.OUTPUT, "published to ROS", UNKNOWN),
                    f"sensor {s.name!r}: no bridge entry names its gz topics, and {owner.how}: "
                    "sensorkit cannot tell whether its data reaches ROS that way",
                    s.source,
                    sensor=s.name,
                    fix="if ROS needs its data, add a GZ_TO_ROS entry for its gz topic",
                )
            if found is not None:
                yield found
        elif s.plugins or (owner is not None and owner.certain):
            continue
        elif owner is not None:
            yield ctx.finding(
                "SK607",
                Severity.INFO,
                f"sensor {s.name!r} has no plugin, and {owner.how}: sensorkit cannot tell "
                "whether it reads this sensor; if it does not, nothing publishes it to ROS",
                s.source,
                sensor=s.name,
                fix="check in the running simulation that its data reaches ROS (ros2 topic list); "
                "if not, add the gazebo_ros plugin for its type",
            )
        else:
            yield ctx.finding(
                "SK607",
                Severity.WARNING,
                f"sensor {s.name!r} has no plugin: Gazebo Classic simulates it but publishes nothing to ROS",
                s.source,
                sensor=s.name,
                fix="add the gazebo_ros plugin for its type (libgazebo_ros_camera.so, libgazebo_ros_ray_sensor.so, libgazebo_ros_imu_sensor.so)",
            )


def _shares_world(ctx: Context) -> bool:
    """An SDF model of a world that holds other models: one bridge serves them all, and
    each model is checked on its own, so an entry for another model's sensor is no stale
    entry of this one (an included model's sensors are in a file of its own)."""
    sm = ctx.robot.sdf
    if sm is None or sm.world is None:
        return False
    return sum(1 for el in sm.world if el.tag in ("model", "include")) > 1


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
    formats=("urdf", "sdf"),
)
def stale_bridge_entry(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    if bridge is None or not bridge.files or not is_gz(ctx.target) or not ctx.robot.sensors:
        return
    if _shares_world(ctx):
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
    from sensorkit.lint.rules.bridge_flow import misspelt_entries

    misspelt = misspelt_entries(ctx)  # SK618 says these, with the sensor left unbridged
    for t in bridge.topics:
        if (t.file, t.line) in misspelt:
            continue
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




def _published_types(ctx: Context) -> dict[str, tuple[set[str], list[str]]]:
    """gz topic -> (gz message types sensors publish on it, those sensors' names), for the
    sensors with a <topic> whose types sensorkit knows."""
    from sensorkit.knowledge.gazebo_sim import GZ_SENSOR_TOPIC_MSGS

    out: dict[str, tuple[set[str], list[str]]] = {}
    from sensorkit.knowledge.gazebo_sim import gz_own_subtopics
    from sensorkit.model.parse import text_of

    for s in ctx.robot.sensors:
        msgs = GZ_SENSOR_TOPIC_MSGS.get(s.type)
        if s.topic and s.camera is not None and gz_own_subtopics(s.type, "x"):
            box_type = text_of(s.camera.element, "box_type")
            msgs = tuple(m for _, _, m in gz_own_subtopics(s.type, "x", box_type))
        if msgs is None or not s.topic or gz_never_created(ctx.target, s.type):
            continue
        topics = gz_topics(s)
        if len(topics) != len(msgs):
            continue
        for topic, msg in zip(topics, msgs, strict=True):
            types, names = out.setdefault(topic, (set(), []))
            types.add(msg)
            names.append(s.name)
    return out


@rule(
    "SK615",
    "error",
    "a ros_gz_bridge entry (YAML or launch) whose message types do not match what the sensor "
    "publishes on that gz topic (gz.msgs.Image for a gpu_lidar's scan): gz-transport hands the "
    "bridge nothing, and ROS never sees the data",
    formats=("urdf", "sdf"),
)
def bridge_type_mismatch(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    if bridge is None or not bridge.topics or not is_gz(ctx.target):
        return
    from sensorkit.base.findings import SourceRef
    from sensorkit.knowledge.gazebo_sim import GZ_TO_ROS_TYPES, gz_msg_name, ros_msg_name

    published = _published_types(ctx)
    for t in bridge.topics:
        if not t.to_ros:
            continue
        found = published.get(norm_topic(t.gz))
        if found is None:
            continue
        types, names = found
        wrong: list[str] = []
        if t.gz_type and gz_msg_name(t.gz_type) not in types:
            wrong.append(f"gz type {t.gz_type}")
        ros_ok = set().union(*(GZ_TO_ROS_TYPES.get(m, frozenset()) for m in types))
        if t.ros_type and ros_ok and ros_msg_name(t.ros_type) not in ros_ok:
            wrong.append(f"ROS type {t.ros_type}")
        if not wrong:
            continue
        want = sorted(types)
        ros_want = sorted(ros_ok)
        yield ctx.finding(
            "SK615",
            Severity.ERROR,
            f"bridge entry for gz topic {t.gz!r} gives {' and '.join(wrong)}, but "
            f"{', '.join(repr(n) for n in names)} publish{'es' if len(names) == 1 else ''} "
            f"gz.msgs.{'/'.join(want)} there: ros_gz_bridge subscribes with the wrong type "
            "and gz-transport hands it nothing, so ROS never sees the data",
            SourceRef(t.file, t.line),
            sensor=names[0],
            fix=f"bridge it as {ros_want[0].replace('/', '/msg/', 1) if ros_want else '?'} "
            f"(gz.msgs.{want[0]})",
        )
