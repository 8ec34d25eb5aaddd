"""Numpy twins of :mod:`sensorkit.model.transforms`: 4x4 numpy arrays, ``T_a_b``.

For rendering and export, which compute in numpy anyway and whose printed numbers keep
every digit (the robot's frames in numpy are in :mod:`sensorkit.model.frames_np`).
``sensorkit validate`` never imports this module.

URDF's ``rpy`` is fixed-axis roll, pitch, yaw: R = Rz(yaw) @ Ry(pitch) @ Rx(roll).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

Mat = npt.NDArray[np.float64]
Vec3 = tuple[float, float, float]

# REP 103: optical frame (z forward, x right, y down) in the body frame (x forward, z up).
R_BODY_OPTICAL: Mat = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])


def rot_x(a: float) -> Mat:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(a: float) -> Mat:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(a: float) -> Mat:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rpy_to_matrix(rpy: Sequence[float]) -> Mat:
    """Rotation matrix of URDF ``rpy``."""
    r, p, y = rpy
    return rot_z(y) @ rot_y(p) @ rot_x(r)


def matrix_to_rpy(R: Mat) -> Vec3:
    """URDF ``rpy`` of a rotation matrix (pitch in [-pi/2, pi/2])."""
    sy = -float(R[2, 0])
    sy = max(-1.0, min(1.0, sy))
    pitch = math.asin(sy)
    if abs(sy) < 1.0 - 1e-12:
        roll = math.atan2(float(R[2, 1]), float(R[2, 2]))
        yaw = math.atan2(float(R[1, 0]), float(R[0, 0]))
    else:  # gimbal lock: put everything into yaw
        roll = 0.0
        yaw = math.atan2(-float(R[0, 1]), float(R[1, 1]))
    return (roll, pitch, yaw)


def transform(
    xyz: Sequence[float] = (0.0, 0.0, 0.0), rpy: Sequence[float] = (0.0, 0.0, 0.0)
) -> Mat:
    """4x4 homogeneous transform from a URDF origin."""
    T = np.eye(4)
    T[:3, :3] = rpy_to_matrix(rpy)
    T[:3, 3] = xyz
    return T


def invert(T: Mat) -> Mat:
    """Inverse of a rigid transform."""
    R = T[:3, :3]
    out = np.eye(4)
    out[:3, :3] = R.T
    out[:3, 3] = -R.T @ T[:3, 3]
    return out


def rotation_angle(R: Mat) -> float:
    """Angle (rad) of a rotation matrix, robust near 0 and pi."""
    c = (float(np.trace(R)) - 1.0) / 2.0
    return math.acos(max(-1.0, min(1.0, c)))


def angle_between(Ra: Mat, Rb: Mat) -> float:
    """Angle (rad) of the rotation taking Ra to Rb."""
    return rotation_angle(Ra.T @ Rb)

