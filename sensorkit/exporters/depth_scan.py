"""``depthimage_to_laserscan`` (ROS 2) parameters for a simulated depth camera."""

from __future__ import annotations

from sensorkit.describe.intrinsics import Intrinsics, InvalidValue
from sensorkit.exporters import _text as t

__all__ = ["depthimage_to_laserscan_remappings", "depthimage_to_laserscan_yaml"]

_OPTICAL_SUFFIXES = ("_optical_frame", "_optical")


def depthimage_to_laserscan_remappings(
    *, depth_topic: str, depth_camera_info_topic: str, scan_topic: str = "scan"
) -> dict[str, str]:
    """The node's remappings: its inputs are ``depth`` and ``depth_camera_info``, its
    output ``scan``.

    Raises:
        InvalidValue: a topic is empty.
    """
    for name, value in (
        ("depth_topic", depth_topic),
        ("depth_camera_info_topic", depth_camera_info_topic),
        ("scan_topic", scan_topic),
    ):
        t.string(value, name)
    return {"depth": depth_topic, "depth_camera_info": depth_camera_info_topic, "scan": scan_topic}


def depthimage_to_laserscan_yaml(
    intr: Intrinsics,
    *,
    depth_topic: str,
    depth_camera_info_topic: str,
    output_frame: str,
    range_min: float,
    range_max: float,
    scan_height: int = 1,
    fps: float | None = None,
    node_name: str = "depthimage_to_laserscan",
) -> str:
    """Parameters for ``depthimage_to_laserscan_node``, with its remappings as comments.

    ``scan_time`` (``1/fps`` when ``fps`` is given), ``range_min``, ``range_max``,
    ``scan_height`` (rows around the centre row, 1..height) and ``output_frame``. The
    LaserScan is x-forward, so ``output_frame`` must be the camera's body frame (x
    forward, z up) at the same place as the optical frame, never the optical frame.
    The topics are remappings (``depth``, ``depth_camera_info``), not parameters: pass
    :func:`depthimage_to_laserscan_remappings` to the launch file.

    Raises:
        InvalidValue: a range or the scan height is out of bounds, or ``output_frame``
            names an optical frame.
    """
    frame = t.string(output_frame, "output_frame")
    if output_frame.endswith(_OPTICAL_SUFFIXES):
        msg = (
            "output_frame must be the x-forward body frame of the camera, not the optical "
            f"frame, got {output_frame!r}"
        )
        raise InvalidValue(msg)
    lo = t.finite(range_min, "range_min")
    hi = t.finite(range_max, "range_max")
    if not 0.0 <= lo < hi:
        msg = f"need 0 <= range_min < range_max, got range_min={lo!r}, range_max={hi!r}"
        raise InvalidValue(msg)
    if isinstance(scan_height, bool) or not isinstance(scan_height, int):
        msg = f"scan_height must be an integer, got {scan_height!r}"
        raise InvalidValue(msg)
    if not 1 <= scan_height <= intr.height:
        msg = f"scan_height must be in 1..{intr.height} (the image height), got {scan_height!r}"
        raise InvalidValue(msg)
    scan_time = 0.033  # the node's own default
    if fps is not None:
        scan_time = 1.0 / t.positive(fps, "fps")
    remap = depthimage_to_laserscan_remappings(
        depth_topic=depth_topic, depth_camera_info_topic=depth_camera_info_topic
    )
    lines = [
        "# remappings: " + " ".join(f"{k}:={v}" for k, v in remap.items()),
        f"{t.string(node_name, 'node_name')}:",
        "  ros__parameters:",
        f"    scan_time: {t.real(scan_time, 'scan_time')}",
        f"    range_min: {t.real(lo, 'range_min')}",
        f"    range_max: {t.real(hi, 'range_max')}",
        f"    scan_height: {t.integer(scan_height, 'scan_height')}",
        f"    output_frame: {frame}",
    ]
    return "\n".join(lines) + "\n"
