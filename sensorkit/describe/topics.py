"""What a robot's sensors will publish for one target: the facts behind ``sensorkit topics``.

Every topic with its resolved name (namespace and remappings applied), ROS message type,
frame_id, image encoding and rate. The names, frames and cameras come from
:func:`sensorkit.describe.sensorinfo.describe`, the same source ``validate``, ``export`` and the
bridge generator use; message types and encodings from
:mod:`sensorkit.knowledge.messages`.

On Gazebo Sim a sensor publishes gz topics, which reach ROS only through ros_gz_bridge:
each gz topic is listed with the ROS name the bridge configuration gives it (the
``--bridge`` files, else the parameter_bridge YAMLs in the robot package's ``config/``), or
as not bridged.

:func:`robot_topics` builds the list; :func:`topics_text` and :func:`topics_json` format it.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from sensorkit.describe.encodings import classic_encoding, gz_encoding
from sensorkit.knowledge import messages as msgs

if TYPE_CHECKING:
    from sensorkit.describe.bridge import BridgeEntry
    from sensorkit.describe.sensorinfo import RobotInfo
    from sensorkit.describe.views import CameraView, SensorInfo
    from sensorkit.loading.bridge import BridgeTopic
    from sensorkit.loading.launch_facts import LaunchFacts
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import Plugin

__all__ = [
    "BridgeConfig",
    "RobotTopics",
    "Topic",
    "classic_encoding",
    "gz_encoding",
    "load_bridge",
    "read_launch",
    "robot_topics",
    "topics_json",
    "topics_list",
    "topics_text",
]

CAMERA_ROLES = frozenset(
    {"image", "camera_info", "depth_image", "depth_camera_info", "points", "trigger"}
    | {"colored_map", "labels_map", "boxes"}  # segmentation and bounding-box cameras (gz)
)
IMAGE_ROLES = frozenset({"image", "depth_image"})


@dataclass(frozen=True)
class Topic:
    """One topic a sensor publishes (or, for a camera's trigger, subscribes to)."""

    name: str | None  # the resolved ROS name; None: a gz topic no bridge entry carries to ROS
    type: str | None  # the ROS message type (None: sensorkit does not know it)
    role: str  # image, camera_info, depth_image, ... (see sensor_topics.sensor_topics)
    sensor: str
    sensor_type: str
    camera: str | None  # the camera's id (``<sensor>/<camera>`` in a multicamera)
    frame: str | None  # header.frame_id
    encoding: str | None  # images only
    rate: float | None  # the sensor's <update_rate>, Hz
    direction: str = "publishes"  # "subscribes": the trigger of a triggered camera
    gz_name: str | None = None  # Gazebo Sim: the gz topic
    gz_type: str | None = None
    bridge: str | None = None  # Gazebo Sim: "FILE:LINE" of the bridge entry that carries it
    notes: tuple[str, ...] = ()

    @property
    def bridged(self) -> bool | None:
        """Gazebo Sim: whether a bridge entry carries it to ROS; None elsewhere."""
        return None if self.gz_name is None else self.name is not None


@dataclass
class BridgeConfig:
    """The ros_gz_bridge configuration that applies: its files and their entries."""

    files: list[str]
    topics: list[BridgeTopic]
    # ROS name -> the name a launch file remaps it to on a ros_gz_bridge node
    remaps: dict[str, str] = field(default_factory=dict)
    launch_files: list[str] = field(default_factory=list)  # the launch files read


@dataclass
class RobotTopics:
    """Every topic of a robot's sensors under one target."""

    robot: str
    target: str
    target_reason: str
    topics: list[Topic]
    sensors: int
    bridge_files: list[str] | None = None  # Gazebo Sim: the bridge files read
    launch_files: list[str] = field(default_factory=list)  # the launch files read
    notes: list[str] = field(default_factory=list)

    @property
    def ros_topics(self) -> list[Topic]:
        """The topics ROS sees (on Gazebo Sim, the bridged ones)."""
        return [t for t in self.topics if t.name is not None]


# --------------------------------------------------------------------------- bridge


def read_launch(
    robot: Robot, target: str, launch: Sequence[str] = (), package_paths: Sequence[str] = ()
) -> LaunchFacts | None:
    """The launch files ``validate`` reads (``launch``, else those found); None: none read."""
    from sensorkit.lint.engine import Options, load_launch

    options = Options(target=target, launch=tuple(launch), package_paths=tuple(package_paths))
    return load_launch(robot, options)


def load_bridge(
    robot: Robot,
    target: str,
    files: Sequence[str] = (),
    launch: Sequence[str] = (),
    package_paths: Sequence[str] = (),
    facts: LaunchFacts | None = None,
) -> BridgeConfig:
    """The bridge configuration for ``robot``: ``files``, else the package's ``config/``
    parameter_bridge YAMLs, and the bridges of its launch files (``launch``, else those
    the launch reader finds), as ``sensorkit validate`` reads them.

    Raises:
        UsageError: a file that is not a ros_gz_bridge configuration.
    """
    from sensorkit.lint.engine import Options, load_bridges, load_launch

    options = Options(
        target=target,
        bridges=tuple(files),
        launch=tuple(launch),
        package_paths=tuple(package_paths),
    )
    if facts is None:
        facts = load_launch(robot, options)
    found = load_bridges(robot, options, facts)
    config = BridgeConfig(list(found.files), list(found.topics))
    if facts is not None:
        config.remaps = bridge_remaps(facts)
        config.launch_files = list(facts.files)
    return config


# ros_gz_bridge's node: "ros_gz_bridge" on Humble and later, "ros_ign_bridge" on Fortress's
# distributions (turtlebot/turtlebot4_simulator@humble a238c94:turtlebot4_ignition_bringup/
# launch/ros_ign_bridge.launch.py:82-99 remaps the bridged scoped scan topic to "scan").
BRIDGE_PACKAGES = frozenset({"ros_gz_bridge", "ros_ign_bridge"})


def bridge_remaps(facts: LaunchFacts) -> dict[str, str]:
    """The remappings the launch files give ros_gz_bridge nodes, by absolute ROS name."""
    return {
        _abs(r.src): _abs(r.dst)
        for r in facts.remaps
        if r.package in BRIDGE_PACKAGES and "$" not in r.src
    }


def _abs(topic: str) -> str:
    return "/" + topic.strip().strip("/")


def _matches(written: str, gz_name: str, scoped: bool) -> bool:
    """A bridge entry's gz name ``written`` names the gz topic ``gz_name``.

    A scoped name (a sensor without ``<topic>``) matches by its tail from ``/sensor/``:
    the world and model names are the launch's. Placeholders a launch file fills in
    (``<namespace>``, ``$(var x)``) match one name part.
    """
    want = _abs(gz_name)
    have = _abs(written)
    if scoped:
        tail = want[want.index("/sensor/") :]
        return have.endswith(tail)
    if "<" in have or "$(" in have:
        parts = re.split(r"<[^>]*>|\$\([^)]*\)", have)
        return re.fullmatch("[^/]*".join(re.escape(p) for p in parts), want) is not None
    return have == want


# --------------------------------------------------------------------------- topics


def _view(info: SensorInfo, key: str) -> CameraView | None:
    """The camera a role belongs to: ``key`` is the camera name of a multicamera role."""
    if not info.cameras:
        return None
    if key:
        for view in info.cameras:
            if view.id == f"{info.name}/{key}":
                return view
    return info.cameras[0]


def _rate(info: SensorInfo) -> float | None:
    """The sensor's ``<update_rate>`` in Hz; None when missing, 0 or not a finite number."""
    rate = info.sensor.update_rate
    return rate if rate is not None and 0 < rate < math.inf else None


def _ros_type(role: str, plugin: Plugin | None, ros1: bool) -> tuple[str | None, str | None]:
    """``(message type, reason it publishes nothing)`` of a Classic topic."""
    library = plugin.library if plugin is not None else ""
    if ros1:
        if role in CAMERA_ROLES:
            return msgs.ros1_type(msgs.ROS2_ROLE_TYPES[role]), None
        return msgs.ROS1_LIBRARY_TYPES.get(library), None
    if library == "gazebo_ros_ray_sensor" and plugin is not None:
        output = (plugin.param("output_type") or msgs.RAY_DEFAULT_OUTPUT).strip()
        if output not in msgs.RAY_OUTPUT_MESSAGES:
            return None, f"<output_type>{output}</output_type> is invalid: it publishes nothing"
        return msgs.RAY_OUTPUT_MESSAGES[output], None
    if role == "out":
        return msgs.ROS2_OUT_TYPES.get(library), None
    return msgs.ROS2_ROLE_TYPES.get(role), None


def _classic_topics(info: SensorInfo, target: str, notes: list[str]) -> list[Topic]:
    from sensorkit.model.frames import ros_plugin

    ros1 = target == "ros1"
    plugin = ros_plugin(info.sensor, target)
    out: list[Topic] = []
    for key, name in info.topics.items():
        cam, _, role = key.rpartition("/")
        mtype, nothing = _ros_type(role, plugin, ros1)
        if nothing is not None:
            notes.append(f"sensor {info.name!r}: {nothing}")
            continue
        view = _view(info, cam) if role in CAMERA_ROLES else None
        fmt = view.spec.format if view is not None else None
        encoding, why = (
            classic_encoding(role, fmt, ros1=ros1, plugin=plugin)
            if role in IMAGE_ROLES
            else (None, None)
        )
        out.append(
            Topic(
                name=name,
                type=mtype,
                role=role,
                sensor=info.name,
                sensor_type=info.sensor.type,
                camera=view.id if view is not None else None,
                frame=view.frame if view is not None else info.frame,
                encoding=encoding,
                rate=_rate(info),
                direction="subscribes" if role == "trigger" else "publishes",
                notes=(why,) if why else (),
            )
        )
    return out


def _scoped_topic(
    robot: Robot, info: SensorInfo, survivor: str | None, spawned: str | None = None
) -> str | None:
    """What a gz sensor without ``<topic>`` publishes on: its scoped name plus the suffix
    gz-sim gives its kind (see ``sensorkit.lint.rules.topic_names.GZ_DEFAULT_SUFFIX``)."""
    from sensorkit.knowledge.gazebo_sim import GZ_TYPE_DEFAULT_SUFFIX
    from sensorkit.lint.rules.topic_names import GZ_DEFAULT_SUFFIX

    kind = info.sensor.kind
    if kind not in GZ_DEFAULT_SUFFIX:
        return None
    # rgbd_camera's suffix is "": it publishes BASE/image, BASE/depth_image, ...
    suffix = "" if kind == "rgbd" else GZ_DEFAULT_SUFFIX[kind]
    suffix = GZ_TYPE_DEFAULT_SUFFIX.get(info.sensor.type, suffix)
    link = survivor or info.sensor.reference or "LINK"
    world, model = "WORLD", spawned or "MODEL"
    if robot.sdf is not None:
        # gz-sim's scoped name: every entity from the world down as TYPE/NAME, nested
        # models too (gazebosim/gz-sim@gz-sim8_8.14.0:src/Util.cc:138-183, used with
        # "/" as in gazebosim/gz-sim@gz-sim8_8.14.0:src/systems/imu/Imu.cc:201). A
        # world file names the world and the model; a model file is spawned under a
        # name sensorkit cannot know.
        *nested, link = link.split("::")
        if robot.sdf.world is not None:
            world, model = robot.sdf.world.get("name", "") or world, robot.name or model
        model += "".join(f"/model/{part}" for part in nested)
    return f"/world/{world}/model/{model}/link/{link}/sensor/{info.name}{suffix}"


def _gz_topics(
    robot: Robot,
    info: SensorInfo,
    target: str,
    bridge: BridgeConfig,
    survivor: str | None,
    notes: list[str],
    spawned: str | None = None,
) -> list[Topic]:
    from sensorkit.describe.bridge import published_entries
    from sensorkit.describe.sensor_topics import gz_roles
    from sensorkit.knowledge.gazebo_sim import gz_never_created, gz_version

    sensor = info.sensor
    never = gz_never_created(target, sensor.type)
    if never is not None:
        notes.append(
            f"sensor {info.name!r}: Gazebo Sim {gz_version(target)} never creates a {sensor.type!r} "
            f"sensor, so it publishes nothing (use {never.use})"
        )
        return []
    scoped = None if sensor.topic else _scoped_topic(robot, info, survivor, spawned)
    entries: list[BridgeEntry] = published_entries(sensor.element, target, topic=scoped)
    if not entries:
        why = (
            "sensorkit does not know the gz topics of this sensor type"
            if sensor.topic or scoped is None
            else "no ros_gz_bridge message type for this sensor type"
        )
        notes.append(f"sensor {info.name!r} ({sensor.type}): {why}")
        return []
    out: list[Topic] = []
    for entry in entries:
        roles = gz_roles(sensor, entry) or ["out"]
        role = roles[0]
        view = _view(info, "") if role in CAMERA_ROLES else None
        fmt = view.spec.format if view is not None else None
        encoding, encoding_note = gz_encoding(role, sensor.type, fmt, target)
        base = Topic(
            name=None,
            type=entry.ros_type_name,
            role=role,
            sensor=info.name,
            sensor_type=sensor.type,
            camera=view.id if view is not None else None,
            frame=view.frame if view is not None else info.frame,
            encoding=encoding,
            rate=_rate(info),
            gz_name=_abs(entry.gz_topic_name),
            gz_type=entry.gz_type_name,
            notes=(encoding_note,) if encoding_note else (),
        )
        carried = [
            t
            for t in bridge.topics
            if t.to_ros and _matches(t.gz, entry.gz_topic_name, scoped is not None)
        ]
        if not carried:
            out.append(base)
        for t in carried:
            extra: tuple[str, ...] = ()
            said = (t.ros_type or "").replace("/msg/", "/")
            if said and said != entry.ros_type_name.replace("/msg/", "/"):
                extra = (f"the bridge entry says ros_type_name {t.ros_type}",)
            out.append(
                replace(
                    base,
                    name=_ros_name(t, bridge),
                    bridge=f"{t.file}:{t.line}" if t.line else t.file,
                    notes=base.notes + extra,
                )
            )
    return out


def _ros_name(t: BridgeTopic, bridge: BridgeConfig) -> str:
    """The ROS name a bridge entry publishes under: its ros name (parameter_bridge
    arguments: the gz name), after the launch's remappings of the bridge node."""
    name = _abs(t.ros or t.gz)
    return bridge.remaps.get(name, name)


def _sort_key(t: Topic) -> tuple[bool, str, str, str]:
    return (t.name is None, t.name or t.gz_name or "", t.sensor, t.role)


def robot_topics(info: RobotInfo, bridge: BridgeConfig | None = None) -> RobotTopics:
    """Every topic of ``info``'s sensors, sorted by name (gz topics no bridge carries last).

    ``bridge`` matters on Gazebo Sim only; None there means no configuration is known, so
    nothing is bridged.
    """
    from sensorkit.model.targets import is_gz

    target = info.target
    notes: list[str] = []
    topics: list[Topic] = []
    gz = is_gz(target)
    config = bridge if bridge is not None else BridgeConfig([], [])
    survivors: dict[str, str] = {}
    if gz and any(not s.sensor.topic for s in info.sensors):
        from sensorkit.model.sdf import convert

        conversion = convert(info.robot)
        survivors = {
            s.name: conversion.survivor(s.link) for s in info.sensors if s.link is not None
        }
    for s in info.sensors:
        if gz:
            topics += _gz_topics(
                info.robot, s, target, config, survivors.get(s.name), notes, info.model
            )
        else:
            if not s.topics:
                notes += [f"sensor {s.name!r}: {n}" for n in s.topic_notes]
            topics += _classic_topics(s, target, notes)
    topics.sort(key=_sort_key)
    result = RobotTopics(
        robot=info.robot.name,
        target=target,
        target_reason=info.target_reason,
        topics=topics,
        sensors=len(info.sensors),
        bridge_files=list(config.files) if gz else None,
        launch_files=list(config.launch_files),
        notes=notes,
    )
    if gz and topics:
        if not config.files:
            notes.append(
                "no ros_gz_bridge configuration found (none given with --bridge, no "
                "parameter_bridge YAML in the robot package's config/): no gz topic reaches "
                "ROS; `sensorkit export` writes a bridge.yaml"
            )
        elif any(t.name is not None for t in topics):
            notes.append(
                "bridged names are shown in the root namespace: a bridge node started in a "
                "namespace puts its relative names under it"
            )
    return result


# --------------------------------------------------------------------------- formats


def _type_list(topics: Iterable[Topic]) -> dict[str, list[str]]:
    by_name: dict[str, list[str]] = {}
    for t in topics:
        if t.name is None:
            continue
        types = by_name.setdefault(t.name, [])
        shown = t.type or "?"
        if shown not in types:
            types.append(shown)
    return by_name


def _rate_text(rate: float | None) -> str:
    return f"{rate:g} Hz" if rate is not None else "-"


def _table(rows: list[list[str]]) -> list[str]:
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    return ["  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)).rstrip() for r in rows]


def topics_list(result: RobotTopics) -> str:
    """The ``ros2 topic list -t`` lines (``/name [type]``, sorted by name: the shape
    ros2/ros2cli@humble 28d73d25:ros2topic/ros2topic/verb/list.py:74-79 prints)."""
    lines = [
        f"{name} [{', '.join(types)}]" for name, types in sorted(_type_list(result.topics).items())
    ]
    return "".join(line + "\n" for line in lines)


def topics_text(result: RobotTopics) -> str:
    """One row per topic, each printed once: the ROS name, its message type, (on Gazebo
    Sim the gz topic; a gz topic no bridge entry carries shows ``(not bridged)``),
    frame_id, encoding, rate and sensor. The ``ros2 topic list -t`` lines are
    :func:`topics_list` (``--format list``)."""
    if not result.topics:
        return ""
    gz = result.bridge_files is not None
    head = ["topic", "type", *(["gz topic"] if gz else []), "frame_id", "encoding", "rate", "sensor"]
    rows = [head]
    for t in result.topics:
        who = f"{t.sensor} ({t.sensor_type})"
        if t.direction != "publishes":
            who += f", {t.direction}"
        rows.append(
            [
                t.name or "(not bridged)",
                t.type or "-",
                *([t.gz_name or "-"] if gz else []),
                t.frame or "-",
                t.encoding or "-",
                _rate_text(t.rate),
                who,
            ]
        )
    return "\n".join(_table(rows)) + "\n"


def _topic_json(t: Topic) -> dict[str, Any]:
    return {
        "topic": t.name,
        "type": t.type,
        "direction": t.direction,
        "frame_id": t.frame,
        "encoding": t.encoding,
        "rate": t.rate,
        "sensor": t.sensor,
        "sensor_type": t.sensor_type,
        "role": t.role,
        "camera": t.camera,
        "gz_topic": t.gz_name,
        "gz_type": t.gz_type,
        "bridged": t.bridged,
        "bridge_entry": t.bridge,
        "notes": list(t.notes),
    }


def topics_json(result: RobotTopics) -> str:
    """The list as one JSON document (``topics`` in the order of :func:`topics_text`)."""
    doc = {
        "robot": result.robot,
        "target": result.target,
        "target_reason": result.target_reason,
        "bridge_files": result.bridge_files,
        "launch_files": result.launch_files,
        "topics": [_topic_json(t) for t in result.topics],
        "notes": result.notes,
    }
    return json.dumps(doc, indent=2, allow_nan=False) + "\n"
