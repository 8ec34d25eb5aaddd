"""SK601, SK603, SK604, SK610: a plugin loads under the target, fits its sensor, is its own node.

The library a ``<plugin>`` names exists for the target (and what to write instead), a
sensor plugin sits on a sensor of a type it serves, two gazebo_ros plugins never make the
same ROS 2 node, and a plugin sensorkit does not know is said once.
"""

from __future__ import annotations

from collections.abc import Iterator

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.gazebo_ros import ROS1_ONLY, ROS2_ONLY
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.topic_names import resolve_name
from sensorkit.model.robot import all_plugins
from sensorkit.model.sensors import Plugin, Sensor
from sensorkit.model.targets import is_classic_plugin, is_gz, is_gz_plugin


def ros_name(p: Plugin) -> str | None:
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
    formats=("urdf", "sdf"),
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
    name = ros_name(p)
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
    "SK603",
    "error",
    "plugin matches the sensor type (camera plugin on camera/depth/multicamera; ray plugin on ray/gpu_ray; imu plugin on imu)",
    formats=("urdf", "sdf"),
)
def plugin_sensor_type(ctx: Context) -> Iterator[Finding]:
    # An error: the plugin gets no data from a sensor of another type. Gazebo Classic's
    # CameraPlugin logs "CameraPlugin requires a CameraSensor." and dereferences the null sensor
    # (elysia-best/gazebo-classic@upstream/11.10.2+dfsg:plugins/CameraPlugin.cc:43-53); RayPlugin
    # throws "RayPlugin requires a Ray Sensor as its parent" (plugins/RayPlugin.cc:45-49); ROS 2
    # gazebo_ros_imu_sensor logs "Parent is not an imu sensor. Exiting." and returns
    # (ros-simulation/gazebo_ros_pkgs@ros2 (d52f7c4):gazebo_plugins/src/gazebo_ros_imu_sensor.cpp:69-73).
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
    name = ros_name(p)
    return name is not None or p.library.startswith(("gazebo_ros", "gazebo_ros2"))


@rule(
    "SK604",
    "error",
    "two plugins resolve to the same ROS 2 node name (gazebo_ros refuses the second)",
    "gazebo_ros, at run time",
    formats=("urdf", "sdf"),
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
        # An error: gazebo_ros::Node::Get logs "Found multiple nodes with same name" and returns
        # nullptr for a second node of one full name (ros-simulation/gazebo_ros_pkgs@ros2
        # (d52f7c4):gazebo_ros/src/node.cpp:118-129, since 3.7.0, the Humble line), which the
        # plugin then dereferences (e.g. gazebo_plugins/src/gazebo_ros_camera.cpp:155-158).
        # Foxy and Galactic (branches foxy b6f7bf1, galactic 95cd859) had no such check.
        # Only plugins that load and that sensorkit knows make a ROS 2 node of their name.
        if plugin_problem(p, ctx.target) is not None or (
            p.library not in ROS2_LIBRARIES and known.lookup(p.filename, "ros2") is None
        ):
            continue
        full = resolve_name(p.name, p.namespace(), "")
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
    "SK610",
    "info",
    "a sensor's plugin is one sensorkit does not know: it cannot tell the frame or topics it "
    "publishes, so frame and topic rules stay silent for that sensor",
    formats=("urdf", "sdf"),
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


