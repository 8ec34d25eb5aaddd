"""Forward kinematics at given joint positions (the model's own FK is at zero).

The root link sits at the world origin; revolute and continuous joints turn about their
axis, prismatic joints slide along it, every other joint stays at zero. Mimic joints
follow their leader (``multiplier * q + offset``).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from sensorkit.base.errors import UsageError
from sensorkit.model.parse import child, parse_float
from sensorkit.model.parts import Joint
from sensorkit.model.robot import Robot
from sensorkit.model.transforms_np import Mat

__all__ = ["MOVABLE", "joint_positions", "link_poses"]

MOVABLE = ("revolute", "continuous", "prismatic")


def _axis(joint: Joint) -> np.ndarray:
    axis = np.array(joint.axis if joint.axis is not None else (1.0, 0.0, 0.0), dtype=np.float64)
    n = float(np.linalg.norm(axis))
    return axis / n if n > 0 else np.array([1.0, 0.0, 0.0])


def _motion(joint: Joint, q: float) -> Mat:
    T = np.eye(4)
    if q == 0.0 or joint.type not in MOVABLE:
        return T
    a = _axis(joint)
    if joint.type == "prismatic":
        T[:3, 3] = a * q
        return T
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    T[:3, :3] = np.eye(3) + np.sin(q) * K + (1 - np.cos(q)) * (K @ K)
    return T


def joint_positions(robot: Robot, given: Mapping[str, float]) -> dict[str, float]:
    """Every movable joint's position: the given ones, mimics, zero for the rest.

    Raises:
        UsageError: a name is not a joint of the robot, or names a joint that cannot move.
    """
    out: dict[str, float] = {}
    for name, value in given.items():
        joint = robot.joint_map.get(name)
        if joint is None:
            movable = sorted(j.name for j in robot.joints if j.type in MOVABLE)
            hint = (
                f"; movable joints: {', '.join(movable)}"
                if movable
                else "; the robot has no movable joints"
            )
            msg = f"--joint {name}: no joint called {name!r}{hint}"
            raise UsageError(msg)
        if joint.type not in MOVABLE:
            msg = f"--joint {name}: joint {name!r} is {joint.type or 'untyped'}, only revolute, continuous and prismatic joints move"
            raise UsageError(msg)
        if not np.isfinite(value):
            msg = f"--joint {name}: {value!r} is not a finite number"
            raise UsageError(msg)
        out[name] = float(value)
    for joint in robot.joints:
        if (
            joint.type in MOVABLE
            and joint.has_mimic
            and joint.name not in given
            and joint.mimic in out
        ):
            el = child(joint.element, "mimic")
            multiplier, _ = parse_float(el.get("multiplier") if el is not None else None)
            offset, _ = parse_float(el.get("offset") if el is not None else None)
            out[joint.name] = (1.0 if multiplier is None else multiplier) * out[joint.mimic] + (
                offset or 0.0
            )
    return out


def link_poses(robot: Robot, positions: Mapping[str, float]) -> dict[str, Mat]:
    """T_world_link for every link reachable from a root (cycle-safe)."""
    poses: dict[str, Mat] = {}
    stack: list[tuple[str, Mat]] = [(root, np.eye(4)) for root in robot.roots()]
    while stack:
        link, T = stack.pop()
        if link in poses:
            continue
        poses[link] = T
        for joint in robot.child_joints.get(link, []):
            if (
                joint.child is None
                or joint.child in poses
                or robot.parent_joint.get(joint.child) is not joint
            ):
                continue
            q = positions.get(joint.name, 0.0)
            stack.append((joint.child, T @ joint.origin.matrix() @ _motion(joint, q)))
    return poses
