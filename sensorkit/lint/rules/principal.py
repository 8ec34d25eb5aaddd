"""SK411: a gazebo_ros camera plugin's principal point far from the image's centre.

Gazebo Classic renders a camera without ``<lens><intrinsics>`` through a symmetric frustum,
so the principal point of the image is its centre, while gazebo_ros publishes camera_info
with the ``<Cx>``/``<Cy>`` (ROS 1) or ``<cx>``/``<cy>`` (ROS 2) written; sources in
:data:`sensorkit.knowledge.gazebo_ros.PRINCIPAL_POINT_PARAMS`.

"Far": more than 10 % of the image's width (height) from width / 2 (height / 2), and more
than one pixel. The plugins' default, (width + 1) / 2, and the other centre conventions,
(width - 1) / 2, are half a pixel from width / 2, never far.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge import plugins as known
from sensorkit.knowledge.gazebo_ros import PRINCIPAL_POINT_FAMILIES, PRINCIPAL_POINT_PARAMS
from sensorkit.knowledge.limits import EDGE_PX
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.frames import ros_generation
from sensorkit.model.parse import child, parse_float
from sensorkit.model.sensors import Plugin

FAR = 0.10  # of the width (height)


def far_from_centre(value: float, size: int) -> bool:
    """Whether a principal point coordinate is far from the centre of ``size`` pixels."""
    return abs(value - size / 2.0) > max(FAR * size, EDGE_PX)


@rule(
    "SK411",
    "error",
    "a gazebo_ros camera plugin's principal point (ROS 1 <Cx>/<Cy>, ROS 2 <cx>/<cy>) more than "
    "10 % of the image width/height (and 1 px) from its centre width/2, height/2: Gazebo Classic "
    "renders the principal point at the centre, so camera_info does not match the image (ROS 1 "
    "<Cx> 0 means computed, and a camera with <lens><intrinsics> is not judged)",
    "none",
    formats=("urdf", "sdf"),
)
def principal_point(ctx: Context) -> Iterator[Finding]:
    for w in written_principal_points(ctx):
        yield from _judge(ctx, w)


@dataclass(frozen=True)
class WrittenPoint:
    """A principal point coordinate a gazebo_ros camera plugin writes, with the image size
    (in pixels, along ``axis``) it is measured against."""

    sensor: str
    plugin: Plugin
    tag: str
    size: int
    axis: str
    value: float
    zero_is_default: bool  # ROS 1: 0 means (size + 1) / 2


def written_principal_points(ctx: Context) -> Iterator[WrittenPoint]:
    """Each finite principal point (``<Cx>``/``<Cy>``, ``<cx>``/``<cy>``) a known camera
    plugin writes for a camera without ``<lens><intrinsics>`` (whose image may be rendered
    off-centre: SK409's ground), on the targets whose plugins read it. SK411 and SK417
    judge them."""
    ros = ros_generation(ctx.target)
    if ros not in PRINCIPAL_POINT_PARAMS:
        return
    cx_tag, cy_tag, zero_is_default = PRINCIPAL_POINT_PARAMS[ros]
    for s in ctx.robot.sensors:
        if not s.is_camera:
            continue
        for p in s.plugins:
            spec = known.lookup(p.filename, ros)
            if spec is None or spec.family not in PRINCIPAL_POINT_FAMILIES:
                continue
            for cam in s.cameras:
                if cam.lens_intrinsics is not None:
                    continue
                for tag, size, axis in ((cx_tag, cam.width, "width"), (cy_tag, cam.height, "height")):
                    value, _ = parse_float(p.param(tag))
                    if value is None or not math.isfinite(value) or size is None or size <= 0:
                        continue
                    yield WrittenPoint(s.name, p, tag, size, axis, value, zero_is_default)


def _judge(ctx: Context, w: WrittenPoint) -> Iterator[Finding]:
    value, size, tag = w.value, w.size, w.tag
    if value == 0 and w.zero_is_default:
        return  # ROS 1: 0 means (size + 1) / 2
    if not far_from_centre(value, size):
        return
    centre = (size + 1) / 2.0
    yield ctx.finding(
        "SK411",
        Severity.ERROR,
        f"camera {w.sensor!r}: <{tag}> {value:g} is {abs(value - size / 2.0):.1f} px from the centre of "
        f"the {size} px {w.axis} ({size / 2.0:g}); Gazebo renders the principal point at the centre, so "
        "camera_info does not match the image (a principal point is in pixels, not metres)",
        child(w.plugin.element, tag),
        sensor=w.sensor,
        fix=f"remove <{tag}> (the plugin then computes {centre:g})"
        + (" or write 0" if w.zero_is_default else ""),
    )
