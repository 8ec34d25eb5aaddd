"""Calibration against the image (issue 35 item 2): where the camera_info a target publishes
and the image it renders disagree, with the size in pixels.

SK413: a stereo baseline (``hackBaseline``/``hack_baseline``, ROS 2 ``Tx``) on a Gazebo
Classic camera with no stereo partner: camera_info P[0][3] = -f * baseline, where a
monocular camera has 0. SK414: distortion that camera_info D carries and the image does
not have, or the other way round (ROS 1 camera utils publish their own distortion tags
while Gazebo Classic renders the SDF ``<distortion>``; Gazebo Sim depth and RGBD cameras,
and Gazebo Classic's depth image under ROS 2, publish the SDF distortion without rendering
it). SK417: a ROS principal point over 1.5 px
from the centre Gazebo Classic renders, nearer than SK411's "far" (10 %). Sources in
:mod:`sensorkit.knowledge.sensor_blocks` and :mod:`sensorkit.knowledge.gazebo_ros`. The
focal length is SK409's, a partial lens SK412's.

Materiality (sensorkit's, not a simulator fact): a disagreement is an error when it moves a
point by more than one pixel, the unit the image measures in (as SK409's ``EDGE_PX``):
for P[0][3], the shift it gives a point 1 m away (image_geometry's projection,
u = (fx' X + Tx) / Z + cx'); for distortion, the shift at the image's corner.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from lxml import etree

from sensorkit.base.consequence import Consequence, Role
from sensorkit.base.findings import Finding
from sensorkit.knowledge.limits import EDGE_PX
from sensorkit.knowledge.sensor_blocks import (
    CLASSIC_DEPTH_DISTORTION_SOURCE,
    CLASSIC_DEPTH_TYPES,
    GZ_DISTORTION_NOT_RENDERED,
    GZ_DISTORTION_SOURCE,
    HACK_BASELINE_SOURCE,
    HACK_BASELINE_TAG,
    ROS1_AUTO_DISTORTION_TAG,
    ROS1_DISTORTION_SOURCE,
    ROS1_DISTORTION_TAGS,
    ROS2_TX_TAG,
)
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.principal import far_from_centre, written_principal_points
from sensorkit.model.frames import publishing_plugin, ros_generation
from sensorkit.model.parse import child, parse_float
from sensorkit.model.sensors import CameraSpec, Plugin, Sensor
from sensorkit.model.targets import is_gz

PX = EDGE_PX  # pixels: below this a disagreement changes no pixel (sensorkit.knowledge.limits)

# sdformat's <camera> defaults (sdf/1.7/camera.sdf:12, :18, :21 @sdf9 9ee2d4f; see
# sensorkit.knowledge.sdf_schema.CAMERA_DEFAULTS).
_WIDTH, _HEIGHT, _HFOV = 320, 240, 1.047

# The ROS camera plugins whose camera_info carries a baseline and a focal length as above.
_CAMERA_FAMILIES = {
    "ros1": frozenset(
        {
            "gazebo_plugins camera (ROS 1)",
            "gazebo_plugins triggered camera (ROS 1)",
            "gazebo_plugins depth camera (ROS 1)",
            "gazebo_plugins openni kinect (ROS 1)",
            "gazebo_plugins prosilica (ROS 1)",
        }
    ),
    "ros2": frozenset({"gazebo_ros camera (ROS 2)"}),
}
# ROS 1 plugins whose D comes from the camera utils' tags (the RGB image is Classic's
# rendered one, distorted by the SDF <distortion>).
_ROS1_RGB_FAMILIES = frozenset(
    {"gazebo_plugins camera (ROS 1)", "gazebo_plugins triggered camera (ROS 1)"}
)


def _size(cam: CameraSpec) -> tuple[int, int, float]:
    width = cam.width if cam.width and cam.width > 0 else _WIDTH
    height = cam.height if cam.height and cam.height > 0 else _HEIGHT
    hfov = cam.hfov if cam.hfov is not None else _HFOV
    return width, height, hfov


def _image_focal(cam: CameraSpec) -> float | None:
    """The focal length the image is rendered with, from width and horizontal_fov."""
    width, _, hfov = _size(cam)
    if not 0.0 < hfov < math.pi or math.tan(hfov / 2.0) <= 0.0:
        return None
    f = width / (2.0 * math.tan(hfov / 2.0))
    return f if math.isfinite(f) else None


def _number(plugin: Plugin, tag: str) -> float | None:
    value, _ = parse_float(plugin.param(tag))
    return value if value is not None and math.isfinite(value) else None


def _camera_plugin(ctx: Context, s: Sensor) -> tuple[Plugin, str] | None:
    """The sensor's Gazebo Classic ROS camera plugin and its generation, if any."""
    if is_gz(ctx.target):
        return None
    ros = ros_generation(ctx.target)
    plugin, spec = publishing_plugin(s, ctx.target)
    if plugin is None or spec is None or spec.family not in _CAMERA_FAMILIES.get(ros, ()):
        return None
    return plugin, ros


# ----------------------------------------------------------------------------- SK413


@rule(
    "SK413",
    "error/info",
    "a stereo baseline (ROS 1 <hackBaseline>, ROS 2 <hack_baseline> or <Tx>) on a Gazebo "
    "Classic camera with no stereo partner (no other camera of its image size, not a "
    "multicamera): camera_info P[0][3] = -f * baseline where a monocular camera has 0, so "
    "every point projected with P moves by -P[0][3] / Z pixels: an error above 1 px at 1 m, info below",
    "none",
    formats=("urdf", "sdf"),
)
def monocular_baseline(ctx: Context) -> Iterator[Finding]:
    cameras = [s for s in ctx.robot.sensors if s.is_camera]
    for s in cameras:
        if s.kind == "multicamera" or len(s.cameras) != 1:
            continue  # a multicamera is a rig: describe.stereo judges its baseline
        found = _camera_plugin(ctx, s)
        if found is None:
            continue
        plugin, ros = found
        cam = s.cameras[0]
        tx_tag, p03 = _published_tx(plugin, ros, cam)
        if tx_tag is None or p03 is None or p03 == 0.0:
            continue
        size = _size(cam)[:2]
        if any(o is not s and _size(c)[:2] == size for o in cameras for c in o.cameras):
            continue  # another camera of its size may be its partner: not judged
        yield ctx.judged(
            "SK413",
            Consequence(Role.CALIBRATION, "P[0][3] 0", f"P[0][3] {p03:.4g}", equal=abs(p03) <= PX),
            f"camera {s.name!r}: <{tx_tag}> gives camera_info P[0][3] = {p03:.4g} "
            f"({HACK_BASELINE_SOURCE[ros]}), but no other camera of its {size[0]}x{size[1]} "
            "image could be its stereo partner: a monocular camera's P[0][3] is 0, and a "
            f"consumer that projects with P shifts every point by {abs(p03):.3g} px at 1 m "
            f"({abs(p03) / 10.0:.3g} px at 10 m)",
            child(plugin.element, tx_tag),
            sensor=s.name,
            fix=f"remove <{tx_tag}> (or set it to 0)",
        )


def _published_tx(plugin: Plugin, ros: str, cam: CameraSpec) -> tuple[str | None, float | None]:
    """The tag that sets P[0][3], and the P[0][3] the plugin publishes from it."""
    if ros == "ros2" and plugin.param(ROS2_TX_TAG) is not None:
        return ROS2_TX_TAG, _number(plugin, ROS2_TX_TAG)  # gazebo_ros_camera.cpp:458
    tag = HACK_BASELINE_TAG[ros]
    if plugin.param(tag) is None:
        return None, None
    baseline = _number(plugin, tag)
    focal_tag = "focalLength" if ros == "ros1" else "focal_length"
    f = _number(plugin, focal_tag)
    if f is None or f == 0.0:  # 0 (the default) means computed from width and hfov
        f = _image_focal(cam)
    if baseline is None or f is None:
        return tag, None
    return tag, -f * baseline + 0.0


# ----------------------------------------------------------------------------- SK414

_ORDER = ("k1", "k2", "k3", "p1", "p2")


def _corner_shift(f: float, width: int, height: int, a: dict[str, float], b: dict[str, float]) -> float:
    """Pixels between where plumb-bob distortions ``a`` and ``b`` put the image's corner."""
    x, y = (width / 2.0) / f, (height / 2.0) / f

    def distort(d: dict[str, float]) -> tuple[float, float]:
        k1, k2, k3, p1, p2 = (d.get(k, 0.0) for k in _ORDER)
        r2 = x * x + y * y
        radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3))
        return (
            x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
            y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y,
        )

    (ax, ay), (bx, by) = distort(a), distort(b)
    shift = f * math.hypot(ax - bx, ay - by)
    return shift if math.isfinite(shift) else math.inf


def _show(d: dict[str, float]) -> tuple[float, ...]:
    """k1 k2 p1 p2 k3, camera_info D's order."""
    return tuple(d.get(k, 0.0) for k in ("k1", "k2", "p1", "p2", "k3"))


@rule(
    "SK414",
    "error/info",
    "camera_info D and the image's distortion disagree: a ROS 1 camera plugin publishes its "
    "<distortionK1..T2> (without <autoDistortion>) while Gazebo Classic renders the SDF "
    "<distortion>; a Gazebo Sim depth or RGBD camera, or a Gazebo Classic depth camera's depth "
    "image (ROS 2), carries the SDF <distortion> in D but is rendered undistorted. An error when the image's corner moves by more than 1 px, info below",
    "none",
    formats=("urdf", "sdf"),
)
def distortion_not_rendered(ctx: Context) -> Iterator[Finding]:
    for s in ctx.robot.sensors:
        if not s.is_camera or len(s.cameras) != 1:
            continue
        cam = s.cameras[0]
        if is_gz(ctx.target):
            if s.type in GZ_DISTORTION_NOT_RENDERED and any(cam.distortion.get(k) for k in _ORDER):
                yield from _judge_distortion(
                    ctx, s, cam, rendered={}, published=dict(cam.distortion),
                    why=f"Gazebo Sim's {s.type} camera publishes the SDF <distortion> in camera_info "
                    f"D but renders its image undistorted ({GZ_DISTORTION_SOURCE})",
                    where=child(cam.element, "distortion"),
                    fix="remove <distortion> (a gz depth/RGBD image has none)",
                    image="depth image",
                )
        elif ctx.target == "ros1":
            yield from _ros1_distortion(ctx, s, cam)
        elif s.type in CLASSIC_DEPTH_TYPES and any(cam.distortion.get(k) for k in _ORDER):
            found = _camera_plugin(ctx, s)
            if found is not None:
                yield from _judge_distortion(
                    ctx, s, cam, rendered={}, published=dict(cam.distortion),
                    why="gazebo_ros_camera publishes depth/camera_info with the SDF <distortion> "
                    "but Gazebo Classic renders the depth image undistorted "
                    f"({CLASSIC_DEPTH_DISTORTION_SOURCE}); the color image is distorted and "
                    "matches its camera_info",
                    where=child(cam.element, "distortion"),
                    fix="remove <distortion> from the depth camera (its depth image has none)",
                    image="depth image",
                )


def _ros1_distortion(ctx: Context, s: Sensor, cam: CameraSpec) -> Iterator[Finding]:
    plugin, spec = publishing_plugin(s, ctx.target)
    if plugin is None or spec is None or spec.family not in _ROS1_RGB_FAMILIES or s.type != "camera":
        return
    auto = (plugin.param(ROS1_AUTO_DISTORTION_TAG) or "").strip().lower()
    if auto in ("true", "1"):
        return  # D comes from the SDF distortion the image has
    published: dict[str, float] = {}
    for key, tag in ROS1_DISTORTION_TAGS.items():
        if plugin.param(tag) is None:
            continue
        value = _number(plugin, tag)
        if value is None:
            return  # not a number: sensorkit does not know what the plugin makes of it
        published[key] = value
    rendered = dict(cam.distortion)
    if _show(published) == _show(rendered):
        return
    tags = [t for t in ROS1_DISTORTION_TAGS.values() if plugin.param(t) is not None]
    where = child(plugin.element, tags[0]) if tags else child(cam.element, "distortion")
    yield from _judge_distortion(
        ctx, s, cam, rendered=rendered, published=published,
        why="the ROS 1 camera plugin publishes D from its own <distortionK1..T2> tags while "
        f"Gazebo Classic renders the image with the SDF <distortion> ({ROS1_DISTORTION_SOURCE})",
        where=where,
        fix="write the same coefficients in <distortion> (k1 k2 k3 p1 p2) and the plugin's "
        "<distortionK1..T2>, or <autoDistortion>true</autoDistortion>",
    )


def _judge_distortion(
    ctx: Context,
    s: Sensor,
    cam: CameraSpec,
    *,
    rendered: dict[str, float],
    published: dict[str, float],
    why: str,
    where: etree._Element | None,
    fix: str,
    image: str = "image",
) -> Iterator[Finding]:
    f = _image_focal(cam)
    if f is None:
        return
    width, height, _ = _size(cam)
    shift = _corner_shift(f, width, height, rendered, published)
    yield ctx.judged(
        "SK414",
        Consequence(
            Role.CALIBRATION,
            f"D {list(_show(rendered))} (the {image}'s)",
            f"D {list(_show(published))}",
            equal=shift <= PX,
        ),
        f"camera {s.name!r}: camera_info D = {list(_show(published))} but the {image} is rendered with "
        f"distortion {list(_show(rendered))} (k1 k2 p1 p2 k3): {why}; undistorting with D moves the "
        f"{image}'s corner by {shift:.3g} px",
        where,
        sensor=s.name,
        fix=fix,
    )


# ----------------------------------------------------------------------------- SK417

# A principal point the image does not have, nearer than SK411's "far": sensorkit's 1 px
# materiality plus the half pixel by which the centre conventions differ ((W - 1) / 2 for
# pixel centres, W / 2 for the frustum's axis, (W + 1) / 2 gazebo_ros's default), so that
# the point is over a pixel off whichever convention the reader takes.
PRINCIPAL_PX = EDGE_PX + 0.5


@rule(
    "SK417",
    "error",
    "a gazebo_ros camera plugin's principal point (ROS 1 <Cx>/<Cy>, ROS 2 <cx>/<cy>) more than "
    "1.5 px from the image centre (1 px, plus the half pixel between centre conventions) but "
    "not as far as SK411 reports: Gazebo Classic renders the principal point at the centre, "
    "so camera_info misplaces every bearing by that many pixels",
    "none",
    formats=("urdf", "sdf"),
)
def principal_point_offset(ctx: Context) -> Iterator[Finding]:
    for w in written_principal_points(ctx):
        value, size, tag = w.value, w.size, w.tag
        if (value == 0 and w.zero_is_default) or far_from_centre(value, size):
            continue  # computed, or SK411's
        off = abs(value - size / 2.0)
        if off <= PRINCIPAL_PX:
            continue
        yield ctx.judged(
            "SK417",
            Consequence(Role.CALIBRATION, size / 2.0, value, equal=False),
            f"camera {w.sensor!r}: <{tag}> {value:g} is {off:.3g} px from the centre of the "
            f"{size} px image ({size / 2.0:g}), where Gazebo Classic renders the principal "
            "point (gazebo/rendering/Camera.cc:2033-2035, 11.10.2: a symmetric frustum): "
            f"camera_info misplaces every bearing by {off:.3g} px",
            child(w.plugin.element, tag),
            sensor=w.sensor,
            fix=f"remove <{tag}> (the plugin then computes {(size + 1) / 2.0:g})",
        )
