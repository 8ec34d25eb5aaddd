"""Which frames are in TF when the launch files are known (issue 24), for SK501.

robot_state_publisher puts its frame_prefix before every link's name, a static transform
publisher adds frames the description lacks, and the name the robot is spawned under is
the MODEL of a Gazebo Sim default frame (sensorkit.loading.launch_facts).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.lint.rules.base import Context

if TYPE_CHECKING:
    from sensorkit.model.frames import SensorFrames
    from sensorkit.model.sensors import Sensor


def in_tf(ctx: Context, frame: str) -> bool:
    """``frame`` is in TF, as far as sensorkit can tell (True when it cannot tell).

    Without launch facts: a link of the robot. With them (issue 24): a frame a static
    transform publishes, or a link under robot_state_publisher's frame_prefix, which it puts
    before every link's name (frame_prefix "robot/": TF has "robot/base_link", not
    "base_link"); when the prefix could not be read, any name ending in a link's may be one.
    """
    robot = ctx.robot
    launch = ctx.launch
    if launch is None:
        return frame in robot.link_map
    if frame in launch.static_frames():
        return True
    if launch.frame_prefix_unknown:
        return any(frame.endswith(link) for link in robot.link_map)
    prefix = launch.frame_prefix or ""
    return frame.startswith(prefix) and frame[len(prefix) :] in robot.link_map


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
