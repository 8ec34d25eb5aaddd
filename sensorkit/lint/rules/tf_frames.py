"""Which frames are in TF when the launch files are known (issue 24), for SK501.

robot_state_publisher puts its frame_prefix before every link's name, a static transform
publisher adds frames the description lacks, and the name the robot is spawned under is
the MODEL of a Gazebo Sim default frame (sensorkit.loading.launch_facts). An SDF model's
frames may reach TF in more ways than a URDF's (:func:`sdf_maybe_in_tf`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.knowledge.gazebo_sim import GZ_SENSOR_POSE_PARAM
from sensorkit.lint.rules.base import Context

if TYPE_CHECKING:
    from sensorkit.model.frames import SensorFrames
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import Sensor


def in_tf(ctx: Context, frame: str) -> bool:
    """``frame`` is in TF, as far as sensorkit can tell (True when it cannot tell).

    Without launch facts: a link of the robot. With them (issue 24): a frame a static
    transform publishes, or a link under robot_state_publisher's frame_prefix, which it puts
    before every link's name (frame_prefix "robot/": TF has "robot/base_link", not
    "base_link"); when the prefix could not be read, any name ending in a link's may be one.
    """
    robot = ctx.robot
    if robot.sdf is not None and sdf_maybe_in_tf(ctx, frame):
        return True
    launch = ctx.launch
    if launch is None:
        return frame in robot.link_map
    if frame in launch.static_frames():
        return True
    if launch.frame_prefix_unknown:
        return any(frame.endswith(link) for link in robot.link_map)
    prefix = launch.frame_prefix or ""
    return frame.startswith(prefix) and frame[len(prefix) :] in robot.link_map


def sdf_maybe_in_tf(ctx: Context, frame: str) -> bool:
    """``frame`` may be in TF for an SDF model: True unless it is sure not to be.

    TF gets an SDF model's frames from robot_state_publisher fed the SDF through
    sdformat_urdf, which publishes the model's links by name and refuses a model with
    nested models or in a world (ros/sdformat_urdf@9cec63e:sdformat_urdf/README.md:20-22;
    src/sdformat_urdf.cpp:71-75 a world, :103-126 one URDF link per link, :320 named as
    the link), or from gz-sim's PosePublisher bridged to /tf, which names each link with
    its model's scope (gazebosim/gz-sim@gz-sim8_8.9.0:src/systems/pose_publisher/
    PosePublisher.cc:421-422) and ros_gz_bridge turns "::" into "/" (see
    frames._gz_default_frame), or from a URDF kept beside the SDF (turtlebot3), which
    sensorkit does not see. So a frame may be in TF when it is a link, a link under any
    prefix ("MODEL/link", robot_state_publisher's frame_prefix), or a <frame> of the model
    (a URDF beside it may have it); and whenever the model has nested models (their links'
    names in TF are not known) or an include sensorkit could not read.
    """
    robot = ctx.robot
    sm = robot.sdf
    if sm is None:
        return True
    if any("::" in name for name in robot.link_map) or any(i.path is None for i in sm.includes):
        return True
    name = frame.replace("::", "/").strip("/")
    if name in robot.link_map or name.rpartition("/")[2] in robot.link_map:
        return True
    vertex = sm.graph.vertices.get(frame)
    return vertex is not None and vertex.kind == "frame"


def gz_default_in_tf(ctx: Context, s: Sensor, fr: SensorFrames) -> bool:
    """A launch's static transform puts the default frame in TF, as ros_gz_bridge hands it
    to ROS ("::" turned into "/", see frames._gz_default_frame): turtlebot4's simulation publishes
    "turtlebot4/rplidar_link/rplidar" so. When the spawned MODEL name is not known, any
    static frame ".../LINK/SENSOR" may be it."""
    launch = ctx.launch
    if launch is None or not launch.static_transforms:
        return False
    frames = {f.strip("/") for f in launch.static_frames()}
    if launch.spawn_name() is not None:
        return (fr.published or "").replace("::", "/").strip("/") in frames
    tail = "/" + "/".join((fr.published or "").split("::")[1:])
    return any(f.endswith(tail) for f in frames)


def gz_sensor_poses_published(robot: Robot) -> bool:
    """The model loads gz-sim's PosePublisher with <publish_sensor_pose> true.

    It publishes each sensor's pose from MODEL::LINK to MODEL::LINK::SENSOR, the very name
    a sensor with no frame tag stamps, and ros_gz_bridge turns "::" into "/" in both (see
    GZ_SENSOR_POSE_PARAM in sensorkit/knowledge/gazebo_sim.py). Whether that reaches TF and
    joins the robot's tree is the launch's business (a bridge of the pose topic to /tf,
    robot_state_publisher's frame_prefix "MODEL/"), which sensorkit does not see: osrf/vrx
    does both. So SK501 says nothing then, for every kind: a miss at worst, never a false
    warning.
    """
    from sensorkit.knowledge import plugins as known

    pose_publisher = known.lookup("gz-sim-pose-publisher-system", "gz")
    return pose_publisher is not None and any(
        known.lookup(p.filename, "gz") is pose_publisher
        and (p.param(GZ_SENSOR_POSE_PARAM) or "").strip().lower() in ("true", "1")
        for p in robot.model_plugins
    )


def prefix_finding(
    ctx: Context, frame: str, what: str, how: str | None, where: SourceRef, sensor: str | None
) -> Finding | None:
    """SK501 for a frame that names a link, when robot_state_publisher prefixes the links."""
    launch = ctx.launch
    prefix = launch.frame_prefix if launch is not None else None
    if launch is not None and prefix and frame in ctx.robot.link_map:
        # robot_state_publisher publishes every link as frame_prefix + name
        # (ros/robot_state_publisher@humble 8b5af4f:src/robot_state_publisher.cpp:268-269
        # moving joints, :291-292 fixed ones: header.frame_id = frame_prefix + root,
        # child_frame_id = frame_prefix + tip; :124 declares it, default "").
        return ctx.finding(
            "SK501",
            Severity.ERROR,
            f"{what} {frame!r} (<{how}>), but robot_state_publisher in "
            f"{', '.join(launch.files)} has frame_prefix {prefix!r}: TF has the link as "
            f"{prefix + frame!r}, not {frame!r}, so it cannot place the data",
            where,
            sensor=sensor,
            frame=frame,
            fix=f"stamp it {prefix + frame!r}",
        )
    return None
