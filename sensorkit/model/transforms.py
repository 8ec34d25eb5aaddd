"""Rigid transforms in pure Python, named ``T_a_b`` (pose of frame b in frame a).

URDF's ``rpy`` is fixed-axis roll, pitch, yaw: R = Rz(yaw) @ Ry(pitch) @ Rx(roll).

``sensorkit validate`` needs a few hundred small products, where numpy's import (a tenth
of a second) and per-call overhead cost more than the arithmetic: a :class:`Mat` is a
tuple of row tuples with ``@``, ``.T`` and ``__array__``, so numpy code still takes it
(``np.asarray(T)``, ``ndarray @ T``, and ``T[:3, 3]`` answers with a numpy array).
Rendering and export compute in numpy with the twins in
:mod:`sensorkit.model.transforms_np`.

Internally the model keeps poses as flat 12-tuples (:data:`Pose`): the rotation row by
row, then the translation; :func:`compose` and :func:`pose_matrix` work on them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy.typing as npt

Vec3 = tuple[float, float, float]
Pose = tuple[float, float, float, float, float, float, float, float, float, float, float, float]
IDENTITY: Pose = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)


class Mat(tuple):  # type: ignore[type-arg]
    """A small matrix: a tuple of row tuples of floats."""

    __slots__ = ()

    def __matmul__(self, other: Any) -> Any:
        if isinstance(other, Mat):
            cols = tuple(zip(*other, strict=True))
            return Mat(tuple(sum(a * b for a, b in zip(row, col, strict=True)) for col in cols) for row in self)
        if isinstance(other, (tuple, list)) and other and not isinstance(other[0], (tuple, list)):
            return tuple(sum(a * b for a, b in zip(row, other, strict=True)) for row in self)
        return NotImplemented

    def __rmatmul__(self, other: Any) -> Any:
        if isinstance(other, (tuple, list)) and other and not isinstance(other[0], (tuple, list)):
            return tuple(sum(a * b for a, b in zip(other, col, strict=True)) for col in zip(*self, strict=True))
        return NotImplemented

    def __getitem__(self, key: Any) -> Any:
        if type(key) is tuple:  # numpy-style T[:3, 3]: answered by numpy, for numpy callers
            return self.__array__()[key]
        return tuple.__getitem__(self, key)

    @property
    def T(self) -> Mat:
        return Mat(zip(*self, strict=True))

    def tolist(self) -> list[list[float]]:
        return [list(row) for row in self]

    def __array__(self, dtype: Any = None, copy: Any = None) -> npt.NDArray[Any]:
        import numpy as np

        return np.array(tuple(self), dtype=dtype if dtype is not None else np.float64)


# REP 103: optical frame (z forward, x right, y down) in the body frame (x forward, z up).
R_BODY_OPTICAL: Mat = Mat(((0.0, 0.0, 1.0), (-1.0, 0.0, 0.0), (0.0, -1.0, 0.0)))


def rot_x(a: float) -> Mat:
    c, s = math.cos(a), math.sin(a)
    return Mat(((1.0, 0.0, 0.0), (0.0, c, -s), (0.0, s, c)))


def rot_y(a: float) -> Mat:
    c, s = math.cos(a), math.sin(a)
    return Mat(((c, 0.0, s), (0.0, 1.0, 0.0), (-s, 0.0, c)))


def rot_z(a: float) -> Mat:
    c, s = math.cos(a), math.sin(a)
    return Mat(((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0)))


def _rpy9(r: float, p: float, y: float) -> tuple[float, ...]:
    """Rz(y) @ Ry(p) @ Rx(r), row by row."""
    if r == 0.0 and p == 0.0 and y == 0.0:
        return IDENTITY[:9]
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    a, b = cy * sp, sy * sp
    return (
        cy * cp, a * sr - sy * cr, a * cr + sy * sr,
        sy * cp, b * sr + cy * cr, b * cr - cy * sr,
        -sp, cp * sr, cp * cr,
    )  # fmt: skip


def rpy_to_matrix(rpy: Sequence[float]) -> Mat:
    """Rotation matrix of URDF ``rpy``."""
    r, p, y = rpy
    m = _rpy9(float(r), float(p), float(y))
    return Mat((m[0:3], m[3:6], m[6:9]))


def matrix_to_rpy(R: Any) -> Vec3:
    """URDF ``rpy`` of a rotation matrix (pitch in [-pi/2, pi/2])."""
    sy = -float(R[2][0])
    sy = max(-1.0, min(1.0, sy))
    pitch = math.asin(sy)
    if abs(sy) < 1.0 - 1e-12:
        roll = math.atan2(float(R[2][1]), float(R[2][2]))
        yaw = math.atan2(float(R[1][0]), float(R[0][0]))
    else:  # gimbal lock: put everything into yaw
        roll = 0.0
        yaw = math.atan2(-float(R[0][1]), float(R[1][1]))
    return (roll, pitch, yaw)


# ---- poses as flat 12-tuples ------------------------------------------------------------
def pose(xyz: Sequence[float], rpy: Sequence[float]) -> Pose:
    """The pose of a URDF origin."""
    x, y, z = xyz
    return (*_rpy9(float(rpy[0]), float(rpy[1]), float(rpy[2])), float(x), float(y), float(z))  # type: ignore[return-value]


def compose(a: Pose, b: Pose) -> Pose:
    """``a @ b`` of two poses."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8, ax, ay, az = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8, bx, by, bz = b
    return (
        a0 * b0 + a1 * b3 + a2 * b6, a0 * b1 + a1 * b4 + a2 * b7, a0 * b2 + a1 * b5 + a2 * b8,
        a3 * b0 + a4 * b3 + a5 * b6, a3 * b1 + a4 * b4 + a5 * b7, a3 * b2 + a4 * b5 + a5 * b8,
        a6 * b0 + a7 * b3 + a8 * b6, a6 * b1 + a7 * b4 + a8 * b7, a6 * b2 + a7 * b5 + a8 * b8,
        a0 * bx + a1 * by + a2 * bz + ax,
        a3 * bx + a4 * by + a5 * bz + ay,
        a6 * bx + a7 * by + a8 * bz + az,
    )  # fmt: skip


def pose_matrix(p: Pose) -> Mat:
    """The 4x4 homogeneous matrix of a pose."""
    return Mat(
        (
            (p[0], p[1], p[2], p[9]),
            (p[3], p[4], p[5], p[10]),
            (p[6], p[7], p[8], p[11]),
            (0.0, 0.0, 0.0, 1.0),
        )
    )


def matrix_pose(T: Any) -> Pose:
    """The pose of a 4x4 homogeneous matrix (its last row is not read)."""
    r0, r1, r2 = T[0], T[1], T[2]
    return (
        float(r0[0]), float(r0[1]), float(r0[2]),
        float(r1[0]), float(r1[1]), float(r1[2]),
        float(r2[0]), float(r2[1]), float(r2[2]),
        float(r0[3]), float(r1[3]), float(r2[3]),
    )  # fmt: skip


# ---- matrices ---------------------------------------------------------------------------
def transform(
    xyz: Sequence[float] = (0.0, 0.0, 0.0), rpy: Sequence[float] = (0.0, 0.0, 0.0)
) -> Mat:
    """4x4 homogeneous transform from a URDF origin."""
    return pose_matrix(pose(xyz, rpy))


def rotation(T: Any) -> Mat:
    """The 3x3 rotation of a 4x4 transform."""
    return Mat((tuple(T[0][:3]), tuple(T[1][:3]), tuple(T[2][:3])))


def translation(T: Any) -> Vec3:
    """The translation of a 4x4 transform."""
    return (T[0][3], T[1][3], T[2][3])


def invert(T: Any) -> Mat:
    """Inverse of a rigid transform."""
    (r0, r1, r2, x), (r3, r4, r5, y), (r6, r7, r8, z) = T[0], T[1], T[2]
    return Mat(
        (
            (r0, r3, r6, -(r0 * x + r3 * y + r6 * z)),
            (r1, r4, r7, -(r1 * x + r4 * y + r7 * z)),
            (r2, r5, r8, -(r2 * x + r5 * y + r8 * z)),
            (0.0, 0.0, 0.0, 1.0),
        )
    )


def relative(Ta: Any, Tb: Any) -> Mat:
    """``invert(Ta) @ Tb``: pose of b in a, both given in one frame."""
    return pose_matrix(compose(matrix_pose(invert(Ta)), matrix_pose(Tb)))


def norm(v: Sequence[float]) -> float:
    """Euclidean length."""
    return math.sqrt(sum(c * c for c in v))


def rotation_angle(R: Any) -> float:
    """Angle (rad) of a rotation matrix, robust near 0 and pi."""
    c = (float(R[0][0]) + float(R[1][1]) + float(R[2][2]) - 1.0) / 2.0
    return math.acos(max(-1.0, min(1.0, c)))


def angle_between(Ra: Any, Rb: Any) -> float:
    """Angle (rad) of the rotation taking Ra to Rb: the angle of Ra.T @ Rb."""
    # trace(Ra.T @ Rb) is the sum of the element-wise products
    t = 0.0
    for i in range(3):
        a, b = Ra[i], Rb[i]
        t += float(a[0]) * float(b[0]) + float(a[1]) * float(b[1]) + float(a[2]) * float(b[2])
    return math.acos(max(-1.0, min(1.0, (t - 1.0) / 2.0)))
