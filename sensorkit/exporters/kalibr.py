"""Kalibr camchain YAML (``camchain.yaml``), one pinhole/radtan camera."""

from __future__ import annotations

import re

import numpy as np
import numpy.typing as npt

from sensorkit.exporters import _text as t
from sensorkit.intrinsics import Intrinsics, InvalidValue

__all__ = ["kalibr_camchain_yaml"]

_CAM_ID = re.compile(r"^cam[0-9]+$")


def _check_transform(T_cam_imu: npt.ArrayLike) -> list[list[float]]:
    matrix = np.asarray(T_cam_imu, dtype=np.float64)
    if matrix.shape != (4, 4):
        msg = f"T_cam_imu must be a 4x4 matrix, got shape {matrix.shape}"
        raise InvalidValue(msg)
    if not np.isfinite(matrix).all():
        msg = "T_cam_imu must be finite"
        raise InvalidValue(msg)
    if not np.array_equal(matrix[3], [0.0, 0.0, 0.0, 1.0]):
        msg = f"T_cam_imu last row must be [0, 0, 0, 1], got {matrix[3].tolist()}"
        raise InvalidValue(msg)
    rotation = matrix[:3, :3]
    if not np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-6) or np.linalg.det(rotation) < 0:
        msg = "T_cam_imu rotation block must be a proper rotation"
        raise InvalidValue(msg)
    return [[float(v) for v in row] for row in matrix]


def kalibr_camchain_yaml(
    intr: Intrinsics,
    *,
    rostopic: str,
    T_cam_imu: npt.ArrayLike | None = None,
    camera_id: str = "cam0",
) -> str:
    """A Kalibr camchain entry for a pinhole camera with radtan distortion.

    ``camera_model: pinhole``, ``intrinsics: [fu, fv, pu, pv]`` (reals),
    ``distortion_model: radtan``, ``distortion_coeffs: [k1, k2, r1, r2]`` (exactly four),
    ``resolution: [w, h]`` (ints), ``rostopic`` and, when given, ``T_cam_imu`` (4x4, maps
    points from the IMU frame into the camera's optical frame).

    Raises:
        InvalidValue: the camera has skew or a non-zero k3 (Kalibr's pinhole/radtan
            cannot hold them), the transform is not a rigid 4x4, or a name is bad.
    """
    if not _CAM_ID.match(camera_id):
        msg = f"camera_id must look like cam0, cam1, ..., got {camera_id!r}"
        raise InvalidValue(msg)
    if intr.skew != 0.0:
        msg = f"Kalibr's pinhole model has no skew, got skew={intr.skew!r}"
        raise InvalidValue(msg)
    k1, k2, p1, p2, k3 = intr.distortion
    if k3 != 0.0:
        msg = f"Kalibr's radtan model has four coefficients, got k3={k3!r}"
        raise InvalidValue(msg)
    lines = [
        f"{camera_id}:",
        "  camera_model: pinhole",
        f"  intrinsics: {t.real_list([intr.fx, intr.fy, intr.cx, intr.cy], 'intrinsics')}",
        "  distortion_model: radtan",
        f"  distortion_coeffs: {t.real_list([k1, k2, p1, p2], 'distortion')}",
        f"  resolution: {t.int_list([intr.width, intr.height], 'resolution')}",
        f"  rostopic: {t.string(rostopic, 'rostopic')}",
    ]
    if T_cam_imu is not None:
        lines.append("  T_cam_imu:")
        lines.extend(f"  - {t.real_list(row, 'T_cam_imu')}" for row in _check_transform(T_cam_imu))
    return "\n".join(lines) + "\n"
