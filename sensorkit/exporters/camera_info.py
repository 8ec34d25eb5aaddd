"""ROS ``camera_info`` YAML, as ``camera_calibration_parsers`` writes and reads it."""

from __future__ import annotations

from dataclasses import replace

from sensorkit.describe.intrinsics import Intrinsics
from sensorkit.exporters import _text as t

__all__ = ["camera_info_yaml", "stereo_camera_infos"]


def _matrix(name: str, rows: int, cols: int, data: list[float]) -> list[str]:
    return [
        f"{name}:",
        f"  rows: {rows}",
        f"  cols: {cols}",
        f"  data: {t.real_list(data, name)}",
    ]


def camera_info_yaml(intr: Intrinsics, *, camera_name: str = "camera") -> str:
    """The ``camera_info`` calibration file a ``camera_info_manager`` URL can load.

    Keys and layout follow ``camera_calibration_parsers`` (``parse_yml.cpp``):
    ``image_width``, ``image_height``, ``camera_name``, ``camera_matrix`` (3x3),
    ``distortion_model: plumb_bob``, ``distortion_coefficients`` (1x5, k1 k2 p1 p2 k3),
    ``rectification_matrix`` (3x3) and ``projection_matrix`` (3x4). Ints are written
    as ints, every matrix entry as an exact real.

    Args:
        intr: the camera.
        camera_name: the ``camera_name`` field (gazebo_ros_camera's ``<camera_name>``).

    Raises:
        InvalidValue: ``camera_name`` is empty.
    """
    lines = [
        f"image_width: {t.integer(intr.width, 'width')}",
        f"image_height: {t.integer(intr.height, 'height')}",
        f"camera_name: {t.string(camera_name, 'camera_name')}",
        *_matrix("camera_matrix", 3, 3, t.matrix_rows(intr.K)),
        "distortion_model: plumb_bob",
        *_matrix("distortion_coefficients", 1, 5, list(intr.distortion)),
        *_matrix("rectification_matrix", 3, 3, t.matrix_rows(intr.R)),
        *_matrix("projection_matrix", 3, 4, t.matrix_rows(intr.P)),
    ]
    return "\n".join(lines) + "\n"


def stereo_camera_infos(
    left: Intrinsics, right: Intrinsics, baseline: float
) -> tuple[Intrinsics, Intrinsics]:
    """The camera_info of a rectified horizontal pair: P's Tx = Ty = 0 on the left and
    Tx = -fx' * ``baseline`` on the right (fx' is P's own fx), everything else as given.

    sensor_msgs/CameraInfo: "The first camera always has Tx = Ty = 0. For the right
    (second) camera of a horizontal stereo pair, Ty = 0 and Tx = -fx' * B, where B is the
    baseline between the cameras" (ros2/common_interfaces@rolling:sensor_msgs/msg/CameraInfo.msg:93-98).

    Raises:
        InvalidValue: the baseline is not a positive finite number.
    """
    b = t.positive(baseline, "baseline")
    fx_p = float(right.P[0][0])
    return (
        replace(left, baseline_tx=0.0, p_ty=0.0),
        replace(right, baseline_tx=-fx_p * b + 0.0, p_ty=0.0),
    )
