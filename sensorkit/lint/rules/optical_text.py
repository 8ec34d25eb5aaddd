"""What optical data looks like when it is stamped with a frame that is not optical:
SK502's explanation, said of a description (``validate``) and of a recording
(``sensorkit check-recording``, SK803 and SK805) in the same words."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from sensorkit.knowledge.limits import ANGLE_TOL
from sensorkit.model import transforms as tf

if TYPE_CHECKING:
    from sensorkit.model.transforms import Mat

__all__ = ["not_optical", "optical_consequence"]



def _describe_axis(v: tuple[float, float, float]) -> str:
    names = {
        (1, 0, 0): "forward",
        (-1, 0, 0): "backwards",
        (0, 1, 0): "to the left",
        (0, -1, 0): "to the right",
        (0, 0, 1): "up",
        (0, 0, -1): "down",
    }
    i = max(range(3), key=lambda k: abs(v[k]))  # the first largest, as numpy's argmax
    key = [0, 0, 0]
    key[i] = 1 if v[i] > 0 else -1
    return names[(key[0], key[1], key[2])]


def optical_consequence(R_render_frame: Mat, gz: bool = False) -> str:
    """What consumers will see when optical data is stamped with this frame."""
    R = R_render_frame
    forward = (R[0][2], R[1][2], R[2][2])  # R @ (0, 0, 1)
    right = (R[0][0], R[1][0], R[2][0])  # R @ (1, 0, 0)
    fwd = _describe_axis(forward)
    if tf.rotation_angle(R_render_frame) < ANGLE_TOL:
        if gz:
            # Gazebo Sim's own cloud is x-forward (gz-sensors#488), so with a body frame it
            # lands right; what breaks is everything that reads image + camera_info.
            return (
                "the frame is x-forward (a body frame): images and camera_info say the camera "
                "looks along its z, so depth_image_proc clouds and image_geometry rays point up "
                "at the sky and RViz's Camera display overlays the wrong way (Gazebo's own "
                "points topic, computed x-forward, happens to land right)"
            )
        return (
            "the frame is x-forward (a body frame), so the camera's viewing axis (optical z) "
            "lands on z: the point cloud points up at the sky and images are rotated in RViz"
        )
    if fwd == "forward":
        return f"the viewing axis is right but image x points {_describe_axis(right)}: the image is rotated or mirrored"
    if fwd == "up":
        return "the viewing axis lands pointing up: the point cloud points at the sky"
    if fwd == "down":
        return "the viewing axis lands pointing down: the point cloud points into the floor"
    return f"the viewing axis lands pointing {fwd}: the point cloud is turned away from where the camera looks"


def not_optical(R_render_frame: Mat, gz: bool = False) -> str:
    """SK502's explanation of a camera frame that is not optical: how far off it is and
    what consumers will see (``sensorkit check-recording`` says it of a recording too)."""
    err = tf.angle_between(R_render_frame, tf.R_BODY_OPTICAL)
    return (
        f"which is not an optical frame (off by {math.degrees(err):.1f} degrees): "
        f"{optical_consequence(R_render_frame, gz)}"
    )
