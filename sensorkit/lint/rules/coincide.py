"""Whether data stamped in one frame means the same as in another (issue 35 item 1).

A rule that finds a sensor's data stamped in a frame other than the one written (a ROS 1
frame tag the ROS 2 plugin ignores, SK602; lumping that moves the default frame, SK303)
states both as a :class:`~sensorkit.base.consequence.Consequence` of role FRAME, and
compares them here with SK5xx's own tolerances (0.5 degree, 1 mm): two links at the same
place and rotation are the same frame to every consumer of TF.

An IMU's message does not depend on where its frame sits, only on how it is turned:
gazebo_ros_imu_sensor fills orientation, angular_velocity and linear_acceleration from the
sensor itself and only stamps the frame (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:
gazebo_plugins/src/gazebo_ros_imu_sensor.cpp:102 frame_id, :135-140 the three vectors;
ROS 1 @noetic-devel f9e1a46:gazebo_plugins/src/gazebo_ros_imu_sensor.cpp:107-138 alike), so
a frame that differs from the written one by a translation only carries the same data.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sensorkit.base.consequence import Consequence, Role
from sensorkit.knowledge.limits import ANGLE_TOL, POSITION_TOL
from sensorkit.model import transforms as tf

if TYPE_CHECKING:
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import Sensor

# Sensor kinds whose data depends on the frame's rotation only (see the module's sources).
ROTATION_ONLY_KINDS = frozenset({"imu"})


def frames_coincide(robot: Robot, a: str, b: str, *, rotation_only: bool = False) -> bool | None:
    """Whether links ``a`` and ``b`` sit at one place and rotation (within SK5xx's
    tolerances; ``rotation_only``: only the rotation is compared); None when either is not
    a link of the robot, or they hang in different trees."""
    a, b = a.removeprefix("/"), b.removeprefix("/")
    if a == b:
        return True
    if a not in robot.link_map or b not in robot.link_map or robot.tree_of(a) != robot.tree_of(b):
        return None
    Ta, Tb = robot.T_world_link(a), robot.T_world_link(b)
    if Ta is None or Tb is None:
        return None
    T = tf.relative(Ta, Tb)
    if tf.rotation_angle(tf.rotation(T)) > ANGLE_TOL:
        return False
    return rotation_only or tf.norm(tf.translation(T)) <= POSITION_TOL


def frame_consequence(robot: Robot, sensor: Sensor | None, written: str, used: str) -> Consequence:
    """The FRAME consequence of data stamped ``used`` where ``written`` was meant: equal when
    the two frames coincide for this sensor's data (an IMU: same rotation)."""
    rotation_only = sensor is not None and sensor.kind in ROTATION_ONLY_KINDS
    same = frames_coincide(robot, written, used, rotation_only=rotation_only)
    return Consequence(Role.FRAME, written.removeprefix("/"), used.removeprefix("/"), equal=bool(same))


def coincide_note(robot: Robot, sensor: Sensor | None, written: str, used: str) -> str:
    """Words for a FRAME consequence that changes nothing although the names differ."""
    if written.removeprefix("/") == used.removeprefix("/"):
        return ""
    if sensor is not None and sensor.kind in ROTATION_ONLY_KINDS:
        return (
            f"; {used!r} is turned as {written!r} is, and an IMU's data depends on its frame's "
            "rotation only, so the data means the same"
        )
    return f"; {used!r} and {written!r} are at one place and rotation, so the data means the same"
