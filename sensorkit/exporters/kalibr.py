"""Kalibr camchain YAML (``camchain.yaml``): one pinhole/radtan camera, or a stereo pair.

Read by ethz-asl/kalibr ``aslam_offline_calibration/kalibr/python/kalibr_common/ConfigReader.py``
(1f60227): ``CameraChainParameters`` counts every top-level key as a camera
(``numCameras``: ``len(self.data)``, :753-754) and reads ``cam{N}`` (:671-677), so a
camchain holds nothing but ``cam0``, ``cam1``, ...; ``T_cn_cnm1`` of every camera after the
first (:688-700), ``T_cam_imu`` of each (:709-718), optional ``cam_overlaps`` (ids below the
camera count, :736-747). Per camera: ``rostopic`` a string (:246-253), ``resolution`` two ints
(:368-375), ``distortion_model`` radtan with exactly 4 coefficients (:339-352). The wiki
(github.com/ethz-asl/kalibr/wiki/yaml-formats) defines ``T_cn_cnm1`` as "camera extrinsic
transformation, always with respect to the last camera in the chain (e.g. cam1: T_cn_cnm1 =
T_c1_c0, takes cam0 to cam1 coordinates)" and ``T_cam_imu`` as the "transformation from IMU
to camera coordinates (T_c_i)".
"""

from __future__ import annotations

import re

import numpy as np
import numpy.typing as npt

from sensorkit.describe.intrinsics import Intrinsics, InvalidValue
from sensorkit.exporters import _text as t

__all__ = ["kalibr_camchain_yaml", "kalibr_stereo_camchain_yaml"]

_CAM_ID = re.compile(r"^cam[0-9]+$")


def _check_transform(T: npt.ArrayLike, name: str = "T_cam_imu") -> list[list[float]]:
    matrix = np.asarray(T, dtype=np.float64)
    if matrix.shape != (4, 4):
        msg = f"{name} must be a 4x4 matrix, got shape {matrix.shape}"
        raise InvalidValue(msg)
    if not np.isfinite(matrix).all():
        msg = f"{name} must be finite"
        raise InvalidValue(msg)
    if not np.array_equal(matrix[3], [0.0, 0.0, 0.0, 1.0]):
        msg = f"{name} last row must be [0, 0, 0, 1], got {matrix[3].tolist()}"
        raise InvalidValue(msg)
    rotation = matrix[:3, :3]
    if not np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-6) or np.linalg.det(rotation) < 0:
        msg = f"{name} rotation block must be a proper rotation"
        raise InvalidValue(msg)
    return [[float(v) for v in row] for row in matrix]


def _matrix_lines(name: str, T: npt.ArrayLike) -> list[str]:
    return [f"  {name}:", *(f"  - {t.real_list(row, name)}" for row in _check_transform(T, name))]


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
    lines = _camera_lines(intr, camera_id, rostopic)
    if T_cam_imu is not None:
        lines += _matrix_lines("T_cam_imu", T_cam_imu)
    return "\n".join(lines) + "\n"


def _camera_lines(intr: Intrinsics, camera_id: str, rostopic: str) -> list[str]:
    if intr.skew != 0.0:
        msg = f"Kalibr's pinhole model has no skew, got skew={intr.skew!r}"
        raise InvalidValue(msg)
    k1, k2, p1, p2, k3 = intr.distortion
    if k3 != 0.0:
        msg = f"Kalibr's radtan model has four coefficients, got k3={k3!r}"
        raise InvalidValue(msg)
    return [
        f"{camera_id}:",
        "  camera_model: pinhole",
        f"  intrinsics: {t.real_list([intr.fx, intr.fy, intr.cx, intr.cy], 'intrinsics')}",
        "  distortion_model: radtan",
        f"  distortion_coeffs: {t.real_list([k1, k2, p1, p2], 'distortion')}",
        f"  resolution: {t.int_list([intr.width, intr.height], 'resolution')}",
        f"  rostopic: {t.string(rostopic, 'rostopic')}",
    ]


def kalibr_stereo_camchain_yaml(
    left: Intrinsics,
    right: Intrinsics,
    *,
    rostopics: tuple[str, str],
    T_cn_cnm1: npt.ArrayLike,
    T_cam_imu: tuple[npt.ArrayLike, npt.ArrayLike] | None = None,
) -> str:
    """A two-camera Kalibr camchain: ``cam0`` the left eye, ``cam1`` the right.

    Each camera as :func:`kalibr_camchain_yaml` writes it, plus ``cam_overlaps``
    (each sees the other); ``cam1`` carries ``T_cn_cnm1`` = ``T_c1_c0``, the transform
    that maps cam0 (left optical frame) coordinates into cam1's, i.e. for a horizontal
    pair a translation of ``[-baseline, 0, 0]``; with ``T_cam_imu`` (left's, right's)
    each camera carries its own.

    Raises:
        InvalidValue: a camera Kalibr's pinhole/radtan cannot hold (skew, k3), a
            transform that is not a rigid 4x4, or an empty topic.
    """
    lines = _camera_lines(left, "cam0", rostopics[0])
    if T_cam_imu is not None:
        lines += _matrix_lines("T_cam_imu", T_cam_imu[0])
    lines.append(f"  cam_overlaps: {t.int_list([1])}")
    lines += _camera_lines(right, "cam1", rostopics[1])
    lines += _matrix_lines("T_cn_cnm1", T_cn_cnm1)
    if T_cam_imu is not None:
        lines += _matrix_lines("T_cam_imu", T_cam_imu[1])
    lines.append(f"  cam_overlaps: {t.int_list([0])}")
    return "\n".join(lines) + "\n"
