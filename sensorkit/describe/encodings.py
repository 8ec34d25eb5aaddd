"""Image encodings a camera topic carries, by target: what gazebo_ros_camera publishes for
an SDF ``<format>`` on Gazebo Classic, and what gz-sensors and ros_gz give on Gazebo Sim
(the facts in :mod:`sensorkit.knowledge.messages`). ``sensorkit topics`` and the recording
checks read them through :mod:`sensorkit.describe.topics`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sensorkit.knowledge import messages as msgs

if TYPE_CHECKING:
    from sensorkit.model.sensors import Plugin

__all__ = ["classic_encoding", "gz_encoding"]



def classic_encoding(
    role: str, fmt: str | None, *, ros1: bool = False, plugin: Plugin | None = None
) -> tuple[str | None, str | None]:
    """``(encoding, note)`` of a Gazebo Classic camera topic (``image`` or ``depth_image``).

    ``fmt`` is the camera's ``<image><format>`` (None: sdformat's default R8G8B8). ROS 1
    depth images are 16UC1 when the plugin sets ``<useDepth16UC1Format>``.
    """
    if role == "depth_image":
        if ros1 and plugin is not None and plugin.library in msgs.ROS1_DEPTH_LIBRARIES:
            flag = (plugin.param(msgs.ROS1_DEPTH_16UC1_PARAM) or "").strip().lower()
            if flag in ("true", "1"):
                return "16UC1", None
        return msgs.CLASSIC_DEPTH_ENCODING, None
    if role != "image":
        return None, None
    written = (fmt or "").strip() or msgs.SDF_DEFAULT_IMAGE_FORMAT
    encoding = msgs.CLASSIC_IMAGE_ENCODINGS.get(written)
    if encoding is None:
        return msgs.CLASSIC_UNSUPPORTED_ENCODING, (
            f"<format>{written}</format> is not one gazebo_ros_camera knows: it publishes "
            f"{msgs.CLASSIC_UNSUPPORTED_ENCODING}"
        )
    return encoding, None


def _sdf_pixel_format(fmt: str) -> str:
    if fmt in msgs.SDF_PIXEL_FORMAT_NAMES:
        return fmt
    return msgs.SDF_OLD_PIXEL_FORMATS.get(fmt, "UNKNOWN_PIXEL_FORMAT")


def gz_encoding(
    role: str, sensor_type: str, fmt: str | None, target: str
) -> tuple[str | None, str | None]:
    """``(encoding, note)`` of a Gazebo Sim image as ros_gz_bridge publishes it.

    None with a note when the bridge has no encoding for the gz pixel format (Bayer).
    """
    if role == "depth_image":
        return msgs.ROS_GZ_ENCODINGS[msgs.GZ_DEPTH_PIXEL_FORMAT], None
    if role != "image":
        return None, None
    note = None
    written = (fmt or "").strip() or msgs.SDF_DEFAULT_IMAGE_FORMAT
    if sensor_type in ("rgbd_camera", "rgbd"):
        pixel = msgs.GZ_RGBD_IMAGE_PIXEL_FORMAT
        if _sdf_pixel_format(written) != pixel:
            note = (
                f"an rgbd_camera's colour image is {pixel} whatever <format>{written}</format> says"
            )
    else:
        pixel = _sdf_pixel_format(written)
        rendered = msgs.GZ_CAMERA_PIXEL_FORMATS.get(target, frozenset())
        if pixel not in rendered:
            note = (
                f"gz-sensors on {target} does not render <format>{written}</format>: "
                f"the camera publishes {msgs.GZ_CAMERA_FALLBACK_FORMAT}"
            )
            pixel = msgs.GZ_CAMERA_FALLBACK_FORMAT
    encoding = msgs.ROS_GZ_ENCODINGS.get(pixel)
    if encoding is None:
        return None, (
            f"ros_gz_bridge has no ROS encoding for {pixel}: the bridged Image has an empty "
            "encoding and no data"
        )
    return encoding, note
