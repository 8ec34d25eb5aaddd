"""SK617, SK618, SK619: ros_gz_bridge entries that carry a sensor's data nowhere (issue 35).

- SK617: an entry for a sensor's gz topic whose direction is ROS_TO_GZ: the bridge reads
  the ROS topic and publishes into Gazebo; nothing of the sensor's reaches ROS that way.
- SK618: an entry whose gz topic no sensor publishes while a sensor of the same message
  type has none: a misspelt topic ("did you mean ...?").
- SK619: a parameter_bridge started by a launch file with an argument it cannot parse: it
  prints its usage and exits, and none of its bridges exist.

Each is judged by the consequence model (sensorkit.base.consequence): a sensor whose data
reaches ROS by no other entry publishes nothing to ROS (error); a bridge sensorkit could not
read may carry it (info); another entry carrying it changes nothing (info).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from sensorkit.base.consequence import UNKNOWN, Consequence, Role
from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.topic_names import gz_topics, is_bridged, norm_topic
from sensorkit.loading.bridge import BridgeTopic
from sensorkit.model.sensors import Sensor
from sensorkit.model.targets import is_gz

# ros_gz_bridge's directions: an entry defaults to BIDIRECTIONAL (gazebosim/ros_gz@humble
# 5cc92f8:ros_gz_bridge/src/bridge_config.cpp:108; @jazzy 739cb42: :97); ROS_TO_GZ creates
# only the ROS->GZ handle, a ROS subscriber publishing into gz (humble ros_gz_bridge/src/
# ros_gz_bridge.cpp:74-85 sets the flags, :88-101 the GZ->ROS handle it then skips,
# :103-110 the ROS->GZ one; jazzy the same at :79-80, :89, :104).
ROS_TO_GZ = "ROS_TO_GZ"


@dataclass(frozen=True)
class _Topic:
    """A gz topic a sensor publishes, with its gz message type when known."""

    sensor: Sensor
    topic: str
    scoped: bool  # the tail of a scoped default topic (``/sensor/NAME/...``)
    msg: str | None  # gz message name (``Image``), None when unknown


def _sensor_topics(ctx: Context) -> list[_Topic]:
    from sensorkit.knowledge.gazebo_sim import GZ_SENSOR_TOPIC_MSGS, gz_never_created

    out: list[_Topic] = []
    for s in ctx.robot.sensors:
        if gz_never_created(ctx.target, s.type):
            continue
        msgs = GZ_SENSOR_TOPIC_MSGS.get(s.type)
        if s.topic:
            topics = gz_topics(s)
            paired = msgs is not None and len(msgs) == len(topics)
            for i, t in enumerate(topics):
                out.append(_Topic(s, t, False, msgs[i] if paired and msgs else None))
        else:
            out.append(_Topic(s, f"/sensor/{s.name}/", True, None))
    return out


def _matches(t: _Topic, gz: str) -> bool:
    return is_bridged(t.topic, t.scoped, {norm_topic(gz)})


def _to_ros(ctx: Context) -> set[str]:
    bridge = ctx.bridge
    return {norm_topic(t.gz) for t in bridge.topics if t.to_ros} if bridge is not None else set()


def _unknown_bridge(ctx: Context) -> bool:
    """Whether a sensor may reach ROS by a bridge sensorkit did not read: a launch bridge
    it could not read, or no launch file read that starts a bridge at all. Projects bridge
    camera images with ros_gz_image's image_bridge from a launch file beside a YAML
    (MOGI-ROS/Week-9-10-Simple-arm@425c335:bme_ros2_simple_arm/launch/spawn_robot.launch.py:
    133-138, as SK607 says): what the launch files start must be known before "nothing
    reaches ROS" is said (the same test as SK607's)."""
    launch = ctx.launch
    return launch is None or not launch.bridges or launch.bridge_unknown


def _unless(ctx: Context, elsewhere: bool) -> str:
    if elsewhere:
        return "; another entry carries it to ROS, so nothing is lost"
    if _unknown_bridge(ctx):
        return (
            "; unless a bridge the launch files start (not read here) carries it another way "
            "(ros_gz_image's image_bridge), the sensor's data never reaches ROS"
        )
    return "; no bridge the launch files start carries it either: the sensor publishes nothing to ROS"


def unread_includes(ctx: Context) -> list[str]:
    """The URIs of the SDF includes whose model sensorkit did not read (SK107 says why):
    their sensors are unknown to it."""
    sm = ctx.robot.sdf
    if sm is None:
        return []
    return [inc.uri or "(no <uri>)" for inc in [*sm.includes, *sm.world_includes] if inc.path is None]


def _shares_world(ctx: Context) -> bool:
    sm = ctx.robot.sdf
    return sm is not None and sm.world is not None and sum(
        1 for el in sm.world if el.tag in ("model", "include")
    ) > 1


@rule(
    "SK617",
    "error/info",
    "a ros_gz_bridge entry for a sensor's gz topic runs ROS_TO_GZ: it carries ROS data into "
    "Gazebo, and the sensor's data never reaches ROS through it (error when no other entry "
    "carries it to ROS)",
    formats=("urdf", "sdf"),
)
def wrong_direction(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    if bridge is None or not bridge.topics or not is_gz(ctx.target):
        return
    sensors = _sensor_topics(ctx)
    to_ros = _to_ros(ctx)
    for entry in bridge.topics:
        if entry.direction.strip().upper() != ROS_TO_GZ:
            continue
        hit = next((t for t in sensors if _matches(t, entry.gz)), None)
        if hit is None:
            continue
        elsewhere = is_bridged(hit.topic, hit.scoped, to_ros)
        intended = "data in ROS"
        effective = "data in ROS" if elsewhere else UNKNOWN if _unknown_bridge(ctx) else None
        yield ctx.judged(
            "SK617",
            Consequence(Role.OUTPUT, intended, effective),
            f"bridge entry for gz topic {entry.gz!r} runs ROS_TO_GZ, but sensor {hit.sensor.name!r} "
            "publishes there: ros_gz_bridge subscribes to the ROS topic and publishes into Gazebo, "
            "so nothing of the sensor reaches ROS through this entry, and anything published on "
            "the ROS topic lands on the sensor's gz topic (gazebosim/ros_gz@humble 5cc92f8:"
            "ros_gz_bridge/src/ros_gz_bridge.cpp:74-110; @jazzy 739cb42: :79-104)"
            + _unless(ctx, elsewhere),
            SourceRef(entry.file, entry.line),
            sensor=hit.sensor.name,
            fix="write direction: GZ_TO_ROS (in a launch argument: TOPIC@ROS_TYPE[GZ_TYPE)",
        )


def _kind_of(entry: BridgeTopic) -> set[str]:
    """The gz message names an entry's types allow (empty: not a sensor type sensorkit knows)."""
    from sensorkit.knowledge.gazebo_sim import GZ_TO_ROS_TYPES, gz_msg_name, ros_msg_name

    if entry.gz_type:
        return {gz_msg_name(entry.gz_type)}
    if entry.ros_type:
        ros = ros_msg_name(entry.ros_type)
        return {gz for gz, ros_types in GZ_TO_ROS_TYPES.items() if ros in ros_types}
    return set()


@rule(
    "SK618",
    "error/info",
    "a ros_gz_bridge entry names a gz topic no sensor publishes while a sensor publishing that "
    "message type is bridged by no entry: a misspelt topic, and the sensor publishes nothing "
    "to ROS (did you mean ...?)",
    formats=("urdf", "sdf"),
)
def misspelt_topic(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    if bridge is None or not bridge.topics or not is_gz(ctx.target) or _shares_world(ctx):
        return
    if unread_includes(ctx):
        return  # the entry may name a sensor of a model sensorkit could not read (as SK612)
    from sensorkit.base.suggest import closest

    sensors = _sensor_topics(ctx)
    to_ros = _to_ros(ctx)
    for entry in bridge.topics:
        if not entry.to_ros or "$" in entry.gz or "<" in entry.gz:
            continue
        if any(_matches(t, entry.gz) for t in sensors):
            continue
        kinds = _kind_of(entry)
        if not kinds:
            continue
        unbridged = {
            t.topic: t
            for t in sensors
            if not t.scoped and t.msg in kinds and not is_bridged(t.topic, False, to_ros)
        }
        hint = closest(norm_topic(entry.gz), unbridged)
        if not hint:
            continue
        meant = unbridged[hint[0]]
        yield ctx.judged(
            "SK618",
            Consequence(
                Role.OUTPUT,
                f"{meant.topic} in ROS",
                UNKNOWN if _unknown_bridge(ctx) else None,
            ),
            f"bridge entry for gz topic {entry.gz!r} matches no sensor of this robot, and sensor "
            f"{meant.sensor.name!r} publishes gz.msgs.{meant.msg} on {meant.topic!r}, which no "
            f"entry bridges: did you mean {meant.topic.lstrip('/')!r}?" + _unless(ctx, False),
            SourceRef(entry.file, entry.line),
            sensor=meant.sensor.name,
            fix=f"gz_topic_name: {meant.topic.lstrip('/')}",
        )


def misspelt_entries(ctx: Context) -> set[tuple[str | None, int | None]]:
    """(file, line) of the entries SK618 reports, so that SK612 does not say them twice."""
    return {(f.source.file, f.source.line) for f in misspelt_topic(ctx)}


@rule(
    "SK619",
    "error/warning/info",
    "a parameter_bridge a launch file starts has an argument it cannot parse: it prints its "
    "usage and exits, and none of its bridges (arguments and config_file) exist",
    formats=("urdf", "sdf"),
)
def dead_bridge(ctx: Context) -> Iterator[Finding]:
    launch = ctx.launch
    if launch is None or not launch.dead_bridges or not is_gz(ctx.target):
        return
    sensors = _sensor_topics(ctx)
    to_ros = _to_ros(ctx)
    for dead in launch.dead_bridges:
        carried = [t for t in sensors if any(e.to_ros and _matches(t, e.gz) for e in dead.topics)]
        lost = sorted({t.sensor.name for t in carried if not is_bridged(t.topic, t.scoped, to_ros)})
        what = f"none of its {len(dead.topics)} bridge(s) exist"
        text = (
            f"parameter_bridge argument {dead.argument!r} is not TOPIC@ROS_TYPE@GZ_TYPE (or [ / ]): "
            f"ros_gz_bridge prints its usage and exits before it spins, so {what} "
            "(gazebosim/ros_gz@humble 5cc92f8 and @jazzy 739cb42:ros_gz_bridge/src/"
            "parameter_bridge.cpp:92-98, :163-167)"
        )
        fix = "write the argument as TOPIC@ROS_TYPE@GZ_TYPE, TOPIC@ROS_TYPE[GZ_TYPE or TOPIC@ROS_TYPE]GZ_TYPE"
        if carried:
            names = lost or sorted({t.sensor.name for t in carried})
            yield ctx.judged(
                "SK619",
                Consequence(
                    Role.OUTPUT,
                    "data in ROS",
                    (UNKNOWN if launch.bridge_unknown else None) if lost else "data in ROS",
                ),
                f"{text}: sensor{'s' if len(names) > 1 else ''} "
                f"{', '.join(repr(n) for n in names)} "
                + (
                    ("publish" if len(names) > 1 else "publishes") + " nothing to ROS"
                    if lost
                    else "reach" + ("" if len(names) > 1 else "es") + " ROS through another bridge"
                ),
                dead.source,
                sensor=names[0],
                fix=fix,
            )
            continue
        shown = ", ".join(sorted({e.gz for e in dead.topics})[:4]) or "nothing else"
        yield ctx.finding(
            "SK619",
            Severity.WARNING,
            f"{text}: it would bridge {shown}, none of this robot's sensor topics",
            dead.source,
            fix=fix,
        )
