"""OpenCV ``FileStorage`` YAML (``cv::FileStorage`` can read it back with ``>>``)."""

from __future__ import annotations

from sensorkit.describe.intrinsics import Intrinsics, InvalidValue
from sensorkit.exporters import _text as t

__all__ = ["OPENCV_YAML_HEADER", "opencv_matrix_lines", "opencv_yaml"]

OPENCV_YAML_HEADER = "%YAML:1.0\n---\n"
"""What ``cv::FileStorage`` writes first in YAML mode (``persistence.cpp``:
``puts("%YAML:1.0\\n---\\n")``). Its reader also accepts files without the ``---``."""


def opencv_matrix_lines(
    name: str, rows: int, cols: int, data: list[float], *, dt: str = "d"
) -> list[str]:
    """A ``!!opencv-matrix`` node in OpenCV's own layout: doubles (``dt: d``) unless
    ``dt="f"`` (floats, for readers that take the matrix with ``at<float>``)."""
    if len(data) != rows * cols:
        msg = f"{name} needs {rows * cols} values, got {len(data)}"
        raise InvalidValue(msg)
    if dt not in ("d", "f"):
        msg = f"dt must be 'd' or 'f', got {dt!r}"
        raise InvalidValue(msg)
    return [
        f"{name}: !!opencv-matrix",
        f"   rows: {rows}",
        f"   cols: {cols}",
        f"   dt: {dt}",
        f"   data: {t.real_list(data, name)}",
    ]


def opencv_yaml(intr: Intrinsics) -> str:
    """Camera matrix and distortion in OpenCV's YAML, as its calibration sample writes.

    ``%YAML:1.0`` and ``---``, then ``image_width``, ``image_height`` (ints),
    ``camera_matrix`` (3x3) and ``distortion_coefficients`` (1x5, k1 k2 p1 p2 k3), both
    ``!!opencv-matrix`` with ``dt: d``.
    """
    lines = [
        f"image_width: {t.integer(intr.width, 'width')}",
        f"image_height: {t.integer(intr.height, 'height')}",
        *opencv_matrix_lines("camera_matrix", 3, 3, t.matrix_rows(intr.K)),
        *opencv_matrix_lines("distortion_coefficients", 1, 5, list(intr.distortion)),
    ]
    return OPENCV_YAML_HEADER + "\n".join(lines) + "\n"
