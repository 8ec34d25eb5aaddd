"""SK6xx: plugins, topics and targets."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator
from dataclasses import dataclass

from lxml import etree

from sensorkit.findings import Finding, Severity
from sensorkit.model.frames import GZ_FRAME_TAGS, GZ_OPTICAL_FRAME_ID
from sensorkit.model.robot import child, children, local, text_of
from sensorkit.model.sensors import Plugin, Sensor, all_plugins
from sensorkit.model.targets import is_classic_plugin, is_gz, is_gz_plugin
from sensorkit.rules.base import Context, rule

# gazebo_plugins / gazebo_ros in ROS 2 (libgazebo_ros_<name>.so).
ROS2_PLUGINS = {
    "camera",
    "ray_sensor",
    "imu_sensor",
    "gps_sensor",
    "ft_sensor",
    "bumper",
    "p3d",
    "diff_drive",
    "ackermann_drive",
    "tricycle_drive",
    "planar_move",
    "joint_state_publisher",
    "joint_pose_trajectory",
    "force",
    "elevator",
    "hand_of_god",
    "harness",
    "projector",
    "template",
    "vacuum_gripper",
    "video",
    "wheel_slip",
    "multi_camera",
    "init",
    "factory",
    "state",
    "properties",
    "force_system",
}
# ROS 1 only, with what replaces each in ROS 2.
ROS1_ONLY: dict[str, str] = {
    "depth_camera": "libgazebo_ros_camera.so on a sensor of type depth",
    "openni_kinect": "libgazebo_ros_camera.so on a sensor of type depth",
    "multicamera": "libgazebo_ros_camera.so on a sensor of type multicamera",
    "triggered_camera": "libgazebo_ros_camera.so with <triggered>true</triggered>",
    "triggered_multicamera": "libgazebo_ros_camera.so on a multicamera sensor with <triggered>true</triggered>",
    "laser": "libgazebo_ros_ray_sensor.so with <output_type>sensor_msgs/LaserScan</output_type>",
    "gpu_laser": "libgazebo_ros_ray_sensor.so on a gpu_ray sensor with <output_type>sensor_msgs/LaserScan</output_type>",
    "block_laser": "libgazebo_ros_ray_sensor.so with <output_type>sensor_msgs/PointCloud2</output_type>",
    "range": "libgazebo_ros_ray_sensor.so with <output_type>sensor_msgs/Range</output_type>",
    "imu": "a sensor of type imu with libgazebo_ros_imu_sensor.so",
    "skid_steer_drive": "libgazebo_ros_diff_drive.so with <num_wheel_pairs>2</num_wheel_pairs>",
    "prosilica": "nothing in gazebo_plugins (use libgazebo_ros_camera.so)",
    "f3d": "nothing in gazebo_plugins (libgazebo_ros_ft_sensor.so measures joint wrenches)",
    "hokuyo_node": "nothing in gazebo_plugins (use libgazebo_ros_ray_sensor.so)",
    "camera_synchronizer": "nothing in gazebo_plugins",
    "vision_reconfigure": "nothing in gazebo_plugins",
    "control": "gazebo_ros2_control (libgazebo_ros2_control.so)",
}
# ROS 2 gazebo_ros names that ROS 1 gazebo_plugins never had.
ROS2_ONLY = {
    "ray_sensor",
    "gps_sensor",
    "ackermann_drive",
    "wheel_slip",
    "multi_camera",
    "init",
    "factory",
    "state",
    "properties",
    "force_system",
}
ROS1_TO_ROS2_PARAMS: dict[str, str] = {
    "frameName": "<frame_name>",
    "cameraName": "<camera_name>",
    "robotNamespace": "<ros><namespace>",
    "hackBaseline": "<hack_baseline>",
    "baseline": "<hack_baseline>",
    "focalLength": "<focal_length>",
    "Cx": "<cx>",
    "Cy": "<cy>",
    "CxPrime": "nothing (ROS 2 has no CxPrime)",
    "pointCloudCutoff": "<min_depth>",
    "pointCloudCutoffMax": "<max_depth>",
    "imageTopicName": "the fixed name <camera_name>/image_raw plus <ros><remapping>",
    "cameraInfoTopicName": "the fixed name <camera_name>/camera_info plus <ros><remapping>",
    "depthImageTopicName": "the fixed name <camera_name>/depth/image_raw plus <ros><remapping>",
    "depthImageInfoTopicName": "the fixed name <camera_name>/depth/camera_info plus <ros><remapping>",
    "depthImageCameraInfoTopicName": "the fixed name <camera_name>/depth/camera_info plus <ros><remapping>",
    "pointCloudTopicName": "the fixed name <camera_name>/points plus <ros><remapping>",
    "distortionK1": "the SDF <camera><distortion><k1>",
    "distortionK2": "the SDF <camera><distortion><k2>",
    "distortionK3": "the SDF <camera><distortion><k3>",
    "distortionT1": "the SDF <camera><distortion><p1>",
    "distortionT2": "the SDF <camera><distortion><p2>",
    "updateRate": "the sensor's <update_rate> (or <update_rate> for model plugins)",
    "updateRateHZ": "the sensor's <update_rate>",
    "alwaysOn": "the sensor's <always_on>",
    "topicName": "<ros><remapping>~/out:=TOPIC</remapping>",
    "bodyName": "<frame_name>",
    "gaussianNoise": "an SDF <noise> block on the sensor",
    "xyzOffset": "the sensor's <pose>",
    "xyzOffsets": "the sensor's <pose>",
    "rpyOffset": "the sensor's <pose>",
    "rpyOffsets": "the sensor's <pose>",
    "serviceName": "nothing (ROS 2 has no calibration service)",
    "initialOrientationAsReference": "<initial_orientation_as_reference>",
    "leftJoint": "<left_joint>",
    "rightJoint": "<right_joint>",
    "leftFrontJoint": "<left_joint> (with <num_wheel_pairs>)",
    "rightFrontJoint": "<right_joint> (with <num_wheel_pairs>)",
    "leftRearJoint": "<left_joint> (with <num_wheel_pairs>)",
    "rightRearJoint": "<right_joint> (with <num_wheel_pairs>)",
    "wheelSeparation": "<wheel_separation>",
    "wheelDiameter": "<wheel_diameter>",
    "wheelTorque": "<max_wheel_torque>",
    "wheelAcceleration": "<max_wheel_acceleration>",
    "commandTopic": "<ros><remapping>cmd_vel:=TOPIC</remapping>",
    "odometryTopic": "<ros><remapping>odom:=TOPIC</remapping>",
    "odometryFrame": "<odometry_frame>",
    "robotBaseFrame": "<robot_base_frame>",
    "publishWheelTF": "<publish_wheel_tf>",
    "publishOdomTF": "<publish_odom_tf>",
    "publishWheelJointState": "a joint_state_publisher plugin",
    "odometrySource": "<odometry_source>",
    "rosDebugLevel": "nothing (use --ros-args --log-level)",
}
RAY_OUTPUT_TYPES = {
    "sensor_msgs/LaserScan",
    "sensor_msgs/PointCloud",
    "sensor_msgs/PointCloud2",
    "sensor_msgs/Range",
}
PLUGIN_SENSOR_KINDS: dict[str, set[str]] = {
    "gazebo_ros_camera": {"camera", "depth", "multicamera"},
    "gazebo_ros_ray_sensor": {"ray", "gpu_ray"},
    "gazebo_ros_imu_sensor": {"imu"},
    "gazebo_ros_depth_camera": {"depth"},
    "gazebo_ros_openni_kinect": {"depth"},
    "gazebo_ros_laser": {"ray"},
    "gazebo_ros_gpu_laser": {"gpu_ray"},
    "gazebo_ros_block_laser": {"ray"},
    "gazebo_ros_velodyne_laser": {"ray", "gpu_ray"},
    "gazebo_ros_velodyne_gpu_laser": {"gpu_ray"},
    "gazebo_ros_multicamera": {"multicamera"},
    "gazebo_ros_gps_sensor": {"gps"},
}
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
    "error",
    "plugin library exists for the target; name the replacement (ROS 1 `libgazebo_ros_depth_camera.so` -> "
    "`libgazebo_ros_camera.so` with a depth sensor, `libgazebo_ros_laser.so`/`gpu_laser` -> "
    "`libgazebo_ros_ray_sensor.so`, `libgazebo_ros_*` under gz -> gz sensors + ros_gz_bridge)",
)
def plugin_exists(ctx: Context) -> Iterator[Finding]:
    target = ctx.target
    for p in all_plugins(ctx.robot):
        name = _ros_name(p)
        sensor = p.sensor.name if p.sensor else None
        if is_gz(target):
            if is_classic_plugin(p.filename):
                yield ctx.finding(
                    "SK601",
                    Severity.ERROR,
                    f"{p.filename} is a Gazebo Classic plugin: Gazebo Sim ({target}) never loads it",
                    p.source,
                    sensor=sensor,
                    fix="remove it: Gazebo Sim sensors publish on <topic> by themselves; bridge them to ROS with ros_gz_bridge",
                )
            elif target == "fortress" and p.filename.rsplit("/", 1)[-1].startswith(
                ("gz-sim", "libgz-sim")
            ):
                fixed = p.filename.replace("libgz-sim", "libignition-gazebo").replace(
                    "gz-sim", "ignition-gazebo"
                )
                yield ctx.finding(
                    "SK601",
                    Severity.ERROR,
                    f"{p.filename} does not exist in Fortress (gz-sim names start with Garden)",
                    p.source,
                    sensor=sensor,
                    fix=f"use {fixed}",
                )
            continue
        if is_gz_plugin(p.filename):
            yield ctx.finding(
                "SK601",
                Severity.ERROR,
                f"{p.filename} is a Gazebo Sim system: Gazebo Classic never loads it",
                p.source,
                sensor=sensor,
                fix="use the gazebo_ros plugin for Classic, or validate with --target harmonic/fortress/jetty",
            )
            continue
        if name is None:
            continue
        if target == "classic" and name in ROS1_ONLY:
            yield ctx.finding(
                "SK601",
                Severity.ERROR,
                f"{p.filename} exists only in ROS 1: ROS 2 Gazebo Classic cannot load it and the sensor publishes nothing",
                p.source,
                sensor=sensor,
                fix=f"use {ROS1_ONLY[name]}",
            )
        elif target == "ros1" and name in ROS2_ONLY:
            yield ctx.finding(
                "SK601",
                Severity.ERROR,
                f"{p.filename} exists only in ROS 2 gazebo_plugins",
                p.source,
                sensor=sensor,
                fix="use the ROS 1 plugin (e.g. libgazebo_ros_laser.so), or --target classic",
            )


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
    for s in ctx.robot.sensors:
        for p in s.plugins:
            kinds = PLUGIN_SENSOR_KINDS.get(p.library)
            if kinds is None or s.type in kinds:
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
        if child(s.element, "camera") is not None and text_of(s.element, "camera", "triggered") in (
            "true",
            "1",
        ):
            names.append(f"{cam}/image_trigger")
        return names
    if lib in (
        "gazebo_ros_ray_sensor",
        "gazebo_ros_imu_sensor",
        "gazebo_ros_velodyne_laser",
        "gazebo_ros_gps_sensor",
    ):
        return ["~/out"]
    return []


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
    cam = s.camera
    if cam is not None and cam.camera_info_topic:
        return "/" + cam.camera_info_topic.strip("/")
    parent = base.rsplit("/", 1)[0]
    return f"{parent}/camera_info"


@rule(
    "SK604",
    "error",
    "two plugins resolve to the same ROS node name (gazebo_ros refuses the second)",
    "gazebo_ros, at run time",
)
def node_names(ctx: Context) -> Iterator[Finding]:
    if is_gz(ctx.target):
        return
    seen: dict[str, Plugin] = {}
    for p in all_plugins(ctx.robot):
        if not _is_ros2_gazebo_plugin(p) or not p.name:
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


@rule(
    "SK605",
    "error",
    "two sensors publish on the same resolved ROS topic (namespace + camera_name/sensor name + suffix; `~/out` + remappings)",
)
def topic_collisions(ctx: Context) -> Iterator[Finding]:
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
        if first is second or key in reported:
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


@rule(
    "SK607",
    "warning",
    "a sensor publishes nothing to ROS (no plugin on classic; no topic/bridge entry on gz)",
)
def publishes_nothing(ctx: Context) -> Iterator[Finding]:
    for s in ctx.robot.sensors:
        if is_gz(ctx.target):
            if not s.topic:
                yield ctx.finding(
                    "SK607",
                    Severity.WARNING,
                    f"sensor {s.name!r} has no <topic>: Gazebo Sim publishes on a scoped default topic that no bridge entry names",
                    s.source,
                    sensor=s.name,
                    fix=f"add <topic>{s.name}</topic> and a ros_gz_bridge entry for it",
                )
        elif not s.plugins:
            yield ctx.finding(
                "SK607",
                Severity.WARNING,
                f"sensor {s.name!r} has no plugin: Gazebo Classic simulates it but publishes nothing to ROS",
                s.source,
                sensor=s.name,
                fix="add the gazebo_ros plugin for its type (libgazebo_ros_camera.so, libgazebo_ros_ray_sensor.so, libgazebo_ros_imu_sensor.so)",
            )


@rule(
    "SK608",
    "warning",
    "a gz frame tag that the chosen gz version ignores (`ignition_frame_id` on harmonic+, `gz_frame_id` on jetty, `optical_frame_id` on jetty)",
)
def ignored_frame_tags(ctx: Context) -> Iterator[Finding]:
    target = ctx.target
    if not is_gz(target):
        return
    read = GZ_FRAME_TAGS[target]
    for s in ctx.robot.sensors:
        for tag in GZ_FRAME_TAG_NAMES:
            if tag in s.frame_tags and tag not in read:
                yield ctx.finding(
                    "SK608",
                    Severity.WARNING,
                    f"sensor {s.name!r}: <{tag}> is ignored by {target}; it reads <{read[0]}>",
                    child(s.element, tag),
                    sensor=s.name,
                    frame=s.frame_tags[tag],
                    fix=f"write <{read[0]}>{s.frame_tags[tag]}</{read[0]}>",
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
