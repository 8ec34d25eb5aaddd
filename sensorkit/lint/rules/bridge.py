"""SK607, SK612, SK615: what reaches ROS.

A sensor that publishes nothing to ROS (no plugin on Classic and no model-level plugin
that reads it, see sensorkit.model.owners; on Gazebo Sim, no ros_gz_bridge entry for any
of its topics, or for a camera's image while its camera_info is bridged), and a bridge
entry of a sensor message type that no sensor of the robot feeds. Both are judged by
consequence (sensorkit.base.consequence): what the author meant ROS to receive against
what it receives; an error only where both are known.
"""

from __future__ import annotations

from collections.abc import Iterator

from sensorkit.base.consequence import UNKNOWN, Consequence, Role
from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.gazebo_sim import gz_never_created
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.topic_names import gz_primary_topic, gz_topics, is_bridged, norm_topic
from sensorkit.model.owners import Owner, sensor_owner
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


# What SK607 compares (issue 35): what the author meant ROS to receive from the sensor
# against what it does receive. A sensor that publishes nothing to ROS is an error where the
# description shows it is meant for ROS; where sensorkit cannot tell what the author meant,
# or what reaches ROS, it is info.
IN_ROS = "its data in ROS"


def _unread_bridge(ctx: Context) -> str | None:
    """The launch files that start a bridge sensorkit could not read, or None."""
    launch = ctx.launch
    if launch is None or not launch.bridge_unknown:
        return None
    return ", ".join(launch.bridge_unknown_in or launch.files)


def known_bridge(ctx: Context) -> set[str] | None:
    """The gz topics the known bridge carries to ROS (normalized), or None when no bridge
    is known or a bridge a launch file starts could not be read: then what reaches ROS is
    not known. Rules that judge a gz stream by whether ROS receives it ask this."""
    bridge = ctx.bridge
    if bridge is None or not bridge.files or _unread_bridge(ctx) is not None:
        return None
    return {norm_topic(t.gz) for t in bridge.topics if t.to_ros}


def no_image_in_ros(ctx: Context, s: Sensor, *, turned: bool) -> str | None:
    """Why no image or camera_info of the gz camera ``s`` reaches ROS, or None: a known
    bridge carries none of them (it may carry a depth camera's points, unless the frame
    they are stamped with is ``turned`` from the render pose: SK502). Those points are
    computed x-forward, z up (gazebosim/gz-rendering@gz-rendering8 ff0c5b8:ogre2/src/media/
    materials/programs/GLSL/depth_camera_fs.glsl:112-113; @ign-rendering6 c39b130: :106-107)
    and stamped with the image's frame (gazebosim/gz-sensors@gz-sensors8 c8159af:src/
    DepthCameraSensor.cc:446-448; @ign-sensors6 7cfaddf: :553-555), so in an x-forward
    frame they land right: only the images, which ROS never receives, would be misread."""
    if not is_gz(ctx.target) or not s.topic or ctx.bridge is None:
        return None
    bridged = known_bridge(ctx)
    if bridged is None:
        return None
    topics = gz_topics(s)
    points = [t for t in topics if t.endswith("/points") and is_bridged(t, False, bridged)]
    if any(is_bridged(t, False, bridged) for t in topics if not t.endswith("/points")):
        return None
    if points and turned:
        return None  # the points land turned as the frame is
    said = f"but no entry of {', '.join(ctx.bridge.files)} carries its images or camera_info to ROS"
    if points:
        said += (
            f", only its points ({', '.join(points)}), which gz computes x-forward and stamps "
            "with that x-forward frame: they land right in TF"
        )
    return said + ": nothing ROS receives is misread"


def _carried(ctx: Context, bridged: set[str]) -> str:
    """What the known bridge carries to ROS, in a few words."""
    names = sorted(bridged)
    shown = ", ".join(names[:4]) + (f" and {len(names) - 4} more" if len(names) > 4 else "")
    return f"the bridge carries {shown}" if names else "the bridge carries nothing to ROS"


def _gz_unbridged(ctx: Context, s: Sensor, topic: str, bridged: set[str]) -> Finding | None:
    """SK607 for a gz sensor when a bridge is known: none of its topics bridged, or a
    camera whose camera_info is bridged and none of its images."""
    scoped = not s.topic
    topics = gz_topics(s) if s.topic else [topic, f"/sensor/{s.name}/"]
    files = ", ".join(ctx.bridge.files) if ctx.bridge else ""
    shown = topic if s.topic else f"/world/WORLD/model/{_scoped_path(ctx, s)}{topic}"
    fix_topic = topic.lstrip("/") if s.topic else "..." + topic
    unread = _unread_bridge(ctx)
    if any(is_bridged(t, scoped, bridged) for t in topics):
        # A camera_info without its image: ROS gets the calibration of a camera it never sees.
        split = _camera_split(s, gz_topics(s) if s.topic else [topic])
        if split is None or not is_bridged(split[1], scoped, bridged):
            return None
        images, info = split
        if any(is_bridged(t, scoped, bridged) for t in images):
            return None
        # Cannot tell when the launch files are not known: projects often bridge the image
        # with ros_gz_image's image_bridge from a launch file (MOGI-ROS/
        # Week-9-10-Simple-arm@425c335:bme_ros2_simple_arm/launch/spawn_robot.launch.py:133-138
        # bridges /gripper_camera/image and /table_camera/image so, beside a gz_bridge.yaml
        # that carries only their camera_info). When the launch files read start a bridge,
        # fully read, and none of them carries the image either, ROS gets no image: an error.
        launch = ctx.launch
        known = launch is not None and bool(launch.bridges) and not launch.bridge_unknown
        text = (
            f"camera {s.name!r}: {files} bridges its camera_info ({info}) but not its image "
            f"({', '.join(images)})"
        )
        if known and launch is not None:
            text += (
                f", and no bridge the launch files start ({', '.join(launch.files)}) carries "
                "it: ROS gets the calibration of a camera it never sees"
            )
        else:
            text += (
                ": unless a launch file bridges the image some other way (ros_gz_image's "
                "image_bridge), ROS gets the calibration of a camera it never sees"
            )
        return ctx.judged(
            "SK607",
            Consequence(Role.OUTPUT, "its image in ROS", None if known else UNKNOWN),
            text,
            s.source,
            sensor=s.name,
            fix=f"add a GZ_TO_ROS entry with gz_topic_name: {fix_topic} (sensor_msgs/msg/Image)",
        )
    if unread is not None:
        # A bridge the launch starts could not be read: it may carry this sensor.
        return ctx.judged(
            "SK607",
            Consequence(Role.OUTPUT, IN_ROS, UNKNOWN),
            f"sensor {s.name!r} publishes on gz topic {shown}, which no bridge entry sensorkit "
            f"read names; a bridge started in {unread} could not be read, so sensorkit cannot "
            "tell whether it reaches ROS",
            s.source,
            sensor=s.name,
        )
    # The bridge known names none of the sensor's topics: ros_gz_bridge creates one bridge
    # per entry of its config_file, each for the entry's gz topic only (gazebosim/ros_gz@
    # jazzy 739cb42:ros_gz_bridge/src/ros_gz_bridge.cpp:54-62, :88-102), so ROS receives
    # nothing of the sensor.
    return ctx.judged(
        "SK607",
        Consequence(Role.OUTPUT, IN_ROS, None),
        f"sensor {s.name!r} publishes on gz topic {shown}, and no entry of {files} names any "
        f"of its topics: ROS receives nothing from it ({_carried(ctx, bridged)})",
        s.source,
        sensor=s.name,
        fix=f"add a GZ_TO_ROS entry with gz_topic_name: {fix_topic}",
    )


def _ros_intent(ctx: Context) -> str | None:
    """Why a Gazebo Classic description is meant for ROS, or None: it loads a gazebo_ros
    plugin (for another sensor, or the robot), or its package is a ROS package."""
    from sensorkit.loading.package_xml import package_generation
    from sensorkit.model.robot import all_plugins

    for p in all_plugins(ctx.robot):
        base = p.filename.rsplit("/", 1)[-1]
        if base.startswith(("libgazebo_ros", "gazebo_ros")):
            return f"it loads the ROS plugin {base}"
    package = package_generation(ctx.robot.document.path)
    return None if package is None else package.why


def _classic_unpublished(ctx: Context, s: Sensor, owner: Owner | None) -> Finding:
    """SK607 for a Gazebo Classic sensor with no plugin of its own."""
    if owner is not None:
        return ctx.judged(
            "SK607",
            Consequence(Role.OUTPUT, IN_ROS, UNKNOWN),
            f"sensor {s.name!r} has no plugin, and {owner.how}: sensorkit cannot tell "
            "whether it reads this sensor; if it does not, nothing publishes it to ROS",
            s.source,
            sensor=s.name,
            fix="check in the running simulation that its data reaches ROS (ros2 topic list); "
            "if not, add the gazebo_ros plugin for its type",
        )
    # Gazebo Classic publishes a sensor's data on gz-transport only; a gazebo_ros plugin
    # in the sensor is what creates its ROS publisher (ros-simulation/gazebo_ros_pkgs@ros2
    # d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:189-202, gazebo_ros_ray_sensor.cpp:
    # 119-133, gazebo_ros_imu_sensor.cpp:95).
    intent = _ros_intent(ctx)
    return ctx.judged(
        "SK607",
        Consequence(Role.OUTPUT, IN_ROS if intent else UNKNOWN, None),
        f"sensor {s.name!r} has no plugin: Gazebo Classic simulates it but publishes nothing "
        "to ROS"
        + (
            f", though the description is meant for ROS ({intent})"
            if intent
            else "; nothing in the description says it is meant for ROS (no gazebo_ros "
            "plugin, no package.xml), so sensorkit cannot tell whether that matters"
        ),
        s.source,
        sensor=s.name,
        fix="add the gazebo_ros plugin for its type (libgazebo_ros_camera.so, libgazebo_ros_ray_sensor.so, libgazebo_ros_imu_sensor.so)",
    )


@rule(
    "SK607",
    "error/info",
    "a sensor publishes nothing to ROS, judged by consequence: an error where the description "
    "is meant for ROS (Classic: a gazebo_ros plugin or a package.xml; gz: a known bridge that "
    "names none of the sensor's topics, or the camera_info without the image when the launch "
    "files' bridges are known); info where sensorkit cannot tell (a model-level plugin it does "
    "not know names the sensor, a bridge it could not read, only a camera's camera_info "
    "bridged, no bridge known and the sensor on its scoped default topic)",
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
                    yield ctx.judged(
                        "SK607",
                        Consequence(Role.OUTPUT, IN_ROS, UNKNOWN),
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
                    Consequence(Role.OUTPUT, IN_ROS, UNKNOWN),
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
        else:
            yield _classic_unpublished(ctx, s, owner)


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
    "(a typo, or a sensor outside this description: sensorkit cannot tell which, info); silent "
    "when the model includes a model sensorkit could not read, whose sensors it does not know",
    formats=("urdf", "sdf"),
)
def stale_bridge_entry(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    if bridge is None or not bridge.files or not is_gz(ctx.target) or not ctx.robot.sensors:
        return
    from sensorkit.lint.rules.bridge_flow import misspelt_entries, unread_includes

    if _shares_world(ctx) or unread_includes(ctx):
        # An include that brought no model (SK107) may hold the sensor the entry names:
        # ArduPilot/ardupilot_gz@main iris_with_lidar includes model://iris_with_standoffs,
        # another repository's model whose imu_sensor its bridge's IMU entry carries.
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
        # What the entry carries to ROS: the data of a sensor of another model in the world,
        # or nothing (a typo): which, sensorkit cannot tell.
        yield ctx.judged(
            "SK612",
            Consequence(Role.OUTPUT, f"sensor data on {t.gz}", UNKNOWN),
            f"bridge entry for gz topic {t.gz!r} ({t.ros_type}) matches no sensor of this robot: "
            "a typo, or a sensor of another model in the world",
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
