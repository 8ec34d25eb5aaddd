"""Numpy twins of the robot's frame queries, for rendering and export.

:func:`T_world_link_np` is :meth:`Robot.T_world_link
<sensorkit.model.robot.Robot.T_world_link>` and :func:`render_pose_np` is
:func:`sensorkit.model.frames.render_pose`, as 4x4 numpy arrays (``T_a_b``, see
:mod:`sensorkit.model.transforms_np`). Kept apart from the pure numpy math so that it
needs no robot or sensor, and from :mod:`sensorkit.model.frames` so that ``sensorkit
validate`` never imports numpy.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from sensorkit.model.transforms_np import Mat

if TYPE_CHECKING:
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import CameraSpec, Sensor


def T_world_link_np(robot: Robot, link: str) -> Mat | None:
    """:meth:`Robot.T_world_link <sensorkit.model.robot.Robot.T_world_link>` as a numpy
    array (the walk and its memo are the robot's own)."""
    T = robot.T_world_link(link)
    return None if T is None else np.array(T, dtype=np.float64)


def render_pose_np(
    robot: Robot, sensor: Sensor, target: str, camera: CameraSpec | None = None
) -> Mat | None:
    """:func:`sensorkit.model.frames.render_pose` in numpy (with ``<camera><pose>`` where
    ``target`` reads it: :func:`sensorkit.model.frames.camera_pose`)."""
    from sensorkit.model.frames import camera_pose

    if sensor.reference is None or sensor.reference not in robot.link_map:
        return None
    T = T_world_link_np(robot, sensor.reference)
    if T is None:
        return None
    out: Mat = T @ sensor.pose.matrix()
    extra = camera_pose(sensor, target, camera)
    if extra is not None:
        out = out @ extra.matrix()
    return out
