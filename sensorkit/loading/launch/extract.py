"""From the nodes a launch starts to the facts about sensors (bridges, frames, spawns).

Sources, read at the lines cited:

- parameter_bridge arguments: ``TOPIC@ROS_TYPE@GZ_TYPE`` (both ways), ``TOPIC@ROS_TYPE[GZ_TYPE``
  (gz to ROS), ``TOPIC@ROS_TYPE]GZ_TYPE`` (ROS to gz); the topic before the first ``@`` is
  both the ROS and the gz name, and ROS arguments are removed first
  (gazebosim/ros_gz@humble:ros_gz_bridge/src/parameter_bridge.cpp:78 init_and_remove_ros_arguments,
  :87-89 the delimiters, :101-102 the one name for both sides, :110/:123/:126 the directions,
  :132 a ``/srv/`` type is a service; the same lines on jazzy; Fortress's
  ros_ign_bridge@galactic:ros_ign_bridge/src/parameter_bridge.cpp:91 ``@``, :114/:116 ``[``/``]``,
  and on humble ros_ign_bridge is a shim that runs ros_gz_bridge's parameter_bridge,
  @humble:ros_ign_bridge/src/parameter_bridge_shim.cpp:15,28-29);
  an argument it cannot parse makes it print usage and exit (:95-97);
- its ``config_file`` parameter (@humble:ros_gz_bridge/src/ros_gz_bridge.cpp:34,48-54);
- ``ros_gz_image image_bridge TOPIC..``: each argument is a gz image topic published to ROS
  under the same name (@humble:ros_gz_image/src/image_bridge.cpp:40 advertise(_topic),
  :42 Subscribe(_topic), :90-94 one per argument after remove_ros_arguments;
  @jazzy:ros_gz_image/src/image_bridge.cpp:108-111);
- static_transform_publisher: ``--frame-id``/``--child-frame-id``, or 8 (x y z yaw pitch
  roll parent child) or 9 (x y z qx qy qz qw parent child) positional arguments
  (ros2/geometry2@humble:tf2_ros/src/static_transform_broadcaster_program.cpp:217-218,
  :257, :293-294, :312-313);
- ``ros_gz_sim create``: ``-name``, ``-topic``, ``-file`` (gflags,
  @humble:ros_gz_sim/src/create.cpp:34,37,38) and on jazzy the ROS parameters of the same
  names (@jazzy:ros_gz_sim/src/create.cpp:126,128,129); gazebo_ros ``spawn_entity.py``:
  ``-entity``, ``-file``, ``-topic``
  (ros-simulation/gazebo_ros_pkgs@ros2:gazebo_ros/scripts/spawn_entity.py:57,59,65).
"""

from __future__ import annotations

from sensorkit.base.findings import SourceRef
from sensorkit.loading.bridge import BridgeError, BridgeTopic, read_bridge
from sensorkit.loading.launch.params import param
from sensorkit.loading.launch.spec import NodeSpec, Reading, plain
from sensorkit.loading.launch_facts import DeadBridge, NodeRemap, Spawn, StaticTransform

BRIDGE_PACKAGES = {"ros_gz_bridge", "ros_ign_bridge"}
IMAGE_PACKAGES = {"ros_gz_image", "ros_ign_image"}
SPAWN_TOOLS = {("ros_gz_sim", "create"), ("ros_ign_gazebo", "create")}
STATIC_PACKAGES = {"tf2_ros", "tf"}


def strip_ros_args(spec: NodeSpec) -> list[tuple[str | None, int | None]] | None:
    """The node's own arguments (``--ros-args ... --`` removed), with their lines; the
    ``-r from:=to`` and ``-p name:=value`` found there are added to the spec."""
    if spec.arguments is None:
        return None
    out: list[tuple[str | None, int | None]] = []
    in_ros, i = False, 0
    args = spec.arguments
    while i < len(args):
        arg, line = args[i], spec.arg_lines[i] if i < len(spec.arg_lines) else spec.line
        if arg == "--ros-args":
            in_ros = True
        elif in_ros and arg == "--":
            in_ros = False
        elif in_ros and arg in ("-r", "--remap", "-p", "--param") and i + 1 < len(args):
            value = args[i + 1]
            i += 1
            if value is None or ":=" not in value:
                if arg in ("-r", "--remap"):
                    spec.remaps_unknown = True
                else:
                    spec.params.append({None: None})
            elif arg in ("-r", "--remap"):
                src, dst = value.split(":=", 1)
                spec.remaps.append((src, dst))
            else:
                key, val = value.split(":=", 1)
                spec.params.append({key: val})
        elif not in_ros:
            out.append((arg, line))
        i += 1
    return out


def _full(name: str, namespace: str | None) -> str | None:
    """The ROS name of a topic name as the node sees it (None: namespace unknown)."""
    if name.startswith("/") or name.startswith("~"):
        return name
    if namespace is None:
        return None
    ns = namespace.strip("/")
    return f"/{ns}/{name}" if ns else name


def remapped(spec: NodeSpec, topic: str) -> str | None:
    """The ROS name ``topic`` has after the node's remappings (None: unknown)."""
    full = _full(topic, spec.namespace)
    if full is None or spec.remaps_unknown:
        return None
    for src, dst in spec.remaps:
        if src is None or dst is None:
            return None
        src_full = _full(src, spec.namespace)
        if src_full is None:
            return None
        if src_full.lstrip("/") == full.lstrip("/") if not spec.namespace else src_full == full:
            return dst
    return topic


def parse_bridge_arg(arg: str) -> tuple[str, str, str] | str | None:
    """(topic, ROS type, direction) of one parameter_bridge argument; ``"service"`` for a
    service; None when parameter_bridge would print its usage and exit
    (ros_gz@humble:ros_gz_bridge/src/parameter_bridge.cpp:94-130)."""
    pos = arg.find("@")
    if pos <= 0:
        return None
    topic, rest = arg[:pos], arg[pos + 1 :]
    direction = "BIDIRECTIONAL"
    pos = rest.find("@")
    if pos <= 0:
        pos = rest.find("[")
        direction = "GZ_TO_ROS"
        if pos <= 0:
            pos = rest.find("]")
            direction = "ROS_TO_GZ"
            if pos == 0:
                return None
            if pos < 0:
                direction, pos = "NONE", len(rest)
    ros_type = rest[:pos]
    if "/srv/" in ros_type:
        return "service"
    if direction == "NONE" or not rest[pos + 1 :] or "@" in rest[pos + 1 :]:
        return None
    return topic, ros_type, direction


def _bridge_unknown(reading: Reading, spec: NodeSpec) -> None:
    """A bridge whose topics cannot be told: none may be said not bridged; the file that
    starts it is kept, for the finding to name (not every launch file read)."""
    reading.facts.bridge_unknown = True
    if spec.file and spec.file not in reading.facts.bridge_unknown_in:
        reading.facts.bridge_unknown_in.append(spec.file)


def _add_topic(reading: Reading, spec: NodeSpec, gz: str, ros_type: str | None,
               direction: str, line: int | None) -> None:
    ros = remapped(spec, gz)
    if ros is None:
        _bridge_unknown(reading, spec)
        ros = gz
    reading.facts.bridges.append(BridgeTopic(gz=gz, ros=ros, ros_type=ros_type,
                                             direction=direction, file=spec.file, line=line))


def bridge(reading: Reading, spec: NodeSpec) -> None:
    """A parameter_bridge: its arguments and its config_file."""
    args = strip_ros_args(spec)
    if args is None:
        _bridge_unknown(reading, spec)
        args = []
    start = len(reading.facts.bridges)
    bad: tuple[str, int | None] | None = None
    for arg, line in args:
        if arg is None:
            _bridge_unknown(reading, spec)
            continue
        parsed = parse_bridge_arg(arg)
        if parsed == "service":
            continue
        if not isinstance(parsed, tuple):
            bad = bad or (arg, line)
            continue
        _add_topic(reading, spec, parsed[0], parsed[1], parsed[2], line)
    config_file(reading, spec, *param(reading, spec, "config_file"))
    if bad is not None:
        # parameter_bridge prints its usage and exits on the first argument it cannot parse
        # (gazebosim/ros_gz@humble 5cc92f8, @jazzy 739cb42:ros_gz_bridge/src/
        # parameter_bridge.cpp:92-98): none of this node's bridges exist.
        dead = tuple(reading.facts.bridges[start:])
        del reading.facts.bridges[start:]
        reading.facts.dead_bridges.append(
            DeadBridge(bad[0], dead, SourceRef(spec.file, bad[1] if bad[1] is not None else spec.line))
        )


def config_file(reading: Reading, spec: NodeSpec, given: bool, value: str | None) -> None:
    """Read a bridge's config_file (a YAML list, sensorkit.loading.bridge.read_bridge)."""
    if not given or value == "":
        return
    path = plain(value)
    if path is None:
        _bridge_unknown(reading, spec)
        return
    from pathlib import Path

    file = Path(path)
    if not file.is_file() or not reading.inside(file):
        _bridge_unknown(reading, spec)
        reading.problem(spec.file, f"bridge config_file not found in the workspace: {path}", spec.line)
        return
    try:
        topics = read_bridge(file, reading.display(file))
    except BridgeError as exc:
        _bridge_unknown(reading, spec)
        reading.problem(spec.file, f"could not read: {exc}", spec.line)
        return
    for t in topics:
        ros = remapped(spec, t.ros or t.gz)
        if ros is None:
            _bridge_unknown(reading, spec)
            ros = t.ros
        reading.facts.bridges.append(BridgeTopic(t.gz, ros, t.ros_type, t.direction, t.file, t.line))


def image_bridge(reading: Reading, spec: NodeSpec) -> None:
    """ros_gz_image image_bridge: every argument is a gz image topic, same name in ROS."""
    args = strip_ros_args(spec)
    if args is None:
        _bridge_unknown(reading, spec)
        return
    for arg, line in args:
        if arg is None:
            _bridge_unknown(reading, spec)
            continue
        _add_topic(reading, spec, arg, "sensor_msgs/msg/Image", "GZ_TO_ROS", line)


_FLAGS = {"--x", "--y", "--z", "--qx", "--qy", "--qz", "--qw", "--roll", "--pitch", "--yaw",
          "--frame-id", "--child-frame-id"}


def static_transform(reading: Reading, spec: NodeSpec) -> None:
    """static_transform_publisher: flag style or 8/9 positional arguments."""
    args = strip_ros_args(spec)
    frames: dict[str, str | None] = {}
    positional: list[str | None] = []
    unknown = args is None
    for i, (arg, _) in enumerate(args or []):
        prev = args[i - 1][0] if args and i else None
        if arg in _FLAGS:
            continue
        if prev in _FLAGS:
            frames[prev] = arg
        elif arg is None:
            unknown = True
        else:
            positional.append(arg)
    if spec.package == "tf" and len(positional) in (9, 10):
        positional = positional[:-1]  # ROS 1 tf: a period in ms comes last
    parent, child = frames.get("--frame-id"), frames.get("--child-frame-id")
    if "--frame-id" not in frames and len(positional) in (8, 9) and not unknown:
        parent, child = positional[-2], positional[-1]
    parent, child = plain(parent), plain(child)
    if parent is None or child is None:
        reading.facts.static_transform_unknown = True
        reading.problem(spec.file, "static_transform_publisher frames not resolved", spec.line)
        return
    reading.facts.static_transforms.append(StaticTransform(parent, child, SourceRef(spec.file, spec.line)))


def _option(args: list[tuple[str | None, int | None]], names: tuple[str, ...]) -> tuple[bool, str | None]:
    """(given, value) of a ``-name value`` / ``-name=value`` / ``--name value`` option."""
    for i, (arg, _) in enumerate(args):
        if arg is None:
            continue
        for name in names:
            for flag in (f"-{name}", f"--{name}"):
                if arg == flag:
                    return True, args[i + 1][0] if i + 1 < len(args) else None
                if arg.startswith(flag + "="):
                    return True, arg[len(flag) + 1 :]
    return False, None


def spawn(reading: Reading, spec: NodeSpec, tool: str) -> None:
    """A spawn: the name the model gets, and where its description comes from."""
    args = strip_ros_args(spec)
    unknown_args = args is None or any(a is None for a, _ in args)
    values: dict[str, str | None] = {}
    names = ("name",) if tool == "ros_gz_sim create" else ("entity",)
    for key, flags in (("name", names), ("topic", ("topic",)), ("file", ("file",))):
        given, value = _option(args or [], flags)
        if not given and tool == "ros_gz_sim create":
            given, value = param(reading, spec, key)
        values[key] = plain(value) if given else (None if unknown_args else "")
    name = values["name"] or None
    reading.facts.spawns.append(Spawn(tool, name, values["topic"] or None, values["file"] or None,
                                      SourceRef(spec.file, spec.line)))


def node_remaps(reading: Reading, spec: NodeSpec) -> None:
    for src, dst in spec.remaps:
        if src is None or dst is None:
            reading.facts.remap_unknown = True
            continue
        reading.facts.remaps.append(NodeRemap(spec.package, spec.executable, spec.name,
                                              spec.namespace, src, dst, SourceRef(spec.file, spec.line)))
    if spec.remaps_unknown:
        reading.facts.remap_unknown = True


def extract(reading: Reading, spec: NodeSpec) -> None:
    """Every fact one node gives."""
    pkg, exe = spec.package, (spec.executable or "").removesuffix(".py")
    if pkg in BRIDGE_PACKAGES and exe == "parameter_bridge":
        bridge(reading, spec)
    elif pkg in IMAGE_PACKAGES and exe == "image_bridge":
        image_bridge(reading, spec)
    elif pkg in STATIC_PACKAGES and exe == "static_transform_publisher":
        static_transform(reading, spec)
    elif (pkg, exe) in SPAWN_TOOLS:
        spawn(reading, spec, "ros_gz_sim create")
    elif pkg == "gazebo_ros" and exe == "spawn_entity":
        spawn(reading, spec, "spawn_entity.py")
    elif pkg == "robot_state_publisher" and exe == "robot_state_publisher":
        frame_prefix(reading, spec)
    elif pkg is None or (exe is None and pkg in BRIDGE_PACKAGES | IMAGE_PACKAGES):
        _bridge_unknown(reading, spec)  # a node not resolved may be a bridge
    node_remaps(reading, spec)


def frame_prefix(reading: Reading, spec: NodeSpec) -> None:
    """robot_state_publisher's frame_prefix ("" when absent; unknown when unresolved)."""
    strip_ros_args(spec)  # picks up -p frame_prefix:=...
    given, value = param(reading, spec, "frame_prefix")
    value = plain(value) if given else ""
    facts = reading.facts
    if value is None or (facts.frame_prefix is not None and facts.frame_prefix != value):
        facts.frame_prefix, facts.frame_prefix_unknown = None, True
        if value is not None:
            reading.problem(spec.file, "robot_state_publishers with different frame_prefix", spec.line)
    elif not facts.frame_prefix_unknown:
        facts.frame_prefix = value
