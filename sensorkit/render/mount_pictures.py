"""The labelled pictures of where the sensors sit and which way they point.

Each picture is a :class:`~sensorkit.render.svg.Figure` (an inline SVG and the numbers
it draws, which summary.json holds and the tests compare with geometry):

- ``imu_figure``: an IMU's axes (x red, y green, z blue) seen as RViz's default orbit view
  sees them (``VIEW_YAW``, ``VIEW_PITCH``), beside the world's and, when its data is
  stamped with another frame, that frame's; with the frame check's result;
- ``closeup_figure``: the robot alone (the box around its links and sensors), from above
  and from the side, with every sensor's mount and axes, each named;
- ``stereo_figure``: a stereo pair's two images side by side with its baseline.

What the sensors see (depth, scans) is drawn by ``sensorkit.render.pictures``. Nothing
here imports pybullet or knows about files: the preview hands in arrays and PNG bytes.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sensorkit.render.raster import convex_hull
from sensorkit.render.svg import Figure, Svg, metres, num

__all__ = [
    "AXIS_COLOURS",
    "VIEW_PITCH",
    "VIEW_YAW",
    "Mount",
    "closeup_figure",
    "imu_figure",
    "stereo_figure",
    "view_axes",
]

FloatArray = npt.NDArray[np.float64]
Projection = Callable[[FloatArray], tuple[float, float]]
AXIS_COLOURS = ("#d62728", "#2ca02c", "#1f5fd6")  # x red, y green, z blue (as RViz)
# The IMU triad is seen as RViz's default orbit view sees the world: from yaw 45 deg
# (ahead of the robot and to its left) and pitch 30 deg above the ground.
VIEW_YAW = math.radians(45.0)
VIEW_PITCH = math.radians(30.0)


# ---- IMU axes ------------------------------------------------------------------------------
def view_axes(yaw: float = VIEW_YAW, pitch: float = VIEW_PITCH) -> tuple[FloatArray, FloatArray]:
    """Screen right and up, as world vectors, of a camera at ``yaw``/``pitch`` on a sphere
    around the origin looking at it (RViz's orbit view)."""
    eye = np.array(
        [math.cos(yaw) * math.cos(pitch), math.sin(yaw) * math.cos(pitch), math.sin(pitch)]
    )
    right = np.cross(-eye, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, -eye)
    return right, up / np.linalg.norm(up)


@dataclass
class _Orbit:
    """Where the orbit view puts a world vector: ``centre`` is the origin's pixel,
    ``length`` the pixels of a unit vector, ``right`` and ``up`` the screen's axes."""

    centre: float
    length: float
    right: FloatArray
    up: FloatArray

    def tip(self, v: FloatArray, scale: float = 1.0) -> tuple[float, float]:
        c, length = self.centre, self.length
        return (c + float(v @ self.right) * length * scale, c - float(v @ self.up) * length * scale)


def imu_figure(
    R_world_imu: FloatArray,
    R_world_stamped: FloatArray | None,
    stamped_frame: str | None,
    check_status: str,
    check_message: str,
    *,
    size: int = 260,
) -> Figure:
    """The IMU's axes (solid, x red, y green, z blue), the world's (thin grey) and, when
    its data is stamped with a frame turned from it, that frame's (dashed), as seen from
    ``VIEW_YAW``/``VIEW_PITCH``."""
    right, up = view_axes()
    orbit = _Orbit(size / 2.0, size * 0.36, right, up)
    svg = Svg(size + 250, size + 20)
    _draw_world_axes(svg, orbit)
    axes = _draw_imu_axes(svg, orbit, R_world_imu)
    if R_world_stamped is not None:
        _draw_stamped_axes(svg, orbit, R_world_stamped)
    svg.add("circle", cx=orbit.centre, cy=orbit.centre, r=3, fill="#000")
    stamped_label = (stamped_frame or "?") if R_world_stamped is not None else None
    _imu_legend(svg, size + 6.0, stamped_label, check_status)
    facts = {
        "view_yaw_deg": math.degrees(VIEW_YAW),
        "view_pitch_deg": math.degrees(VIEW_PITCH),
        "axes_px": axes,
        "stamped_frame": stamped_frame,
        "frame_check": check_status,
    }
    caption = f"IMU axes; frame check {check_status}" + (
        f": {check_message}" if check_status == "warn" else ""
    )
    return Figure("imu", caption, str(svg), facts)


def _draw_world_axes(svg: Svg, orbit: _Orbit) -> None:
    """The world's axes, thin grey and named."""
    c = orbit.centre
    for i, name in enumerate("xyz"):
        e = np.eye(3)[i]
        svg.line((c, c), orbit.tip(e, 0.55), "#b0b0b0", 1.0, class_=f"world-{name}")
        t = orbit.tip(e, 0.62)
        svg.text(t[0], t[1] + 3, f"world {name}", size=9, anchor="middle", fill="#999")


def _draw_imu_axes(svg: Svg, orbit: _Orbit, R_world_imu: FloatArray) -> dict[str, list[float]]:
    """The IMU's axes, solid and named; where each ends, in pixels from the centre."""
    c = orbit.centre
    axes: dict[str, list[float]] = {}
    for i, name in enumerate("xyz"):
        v = np.asarray(R_world_imu[:3, i], dtype=np.float64)
        end = orbit.tip(v)
        svg.line(
            (c, c), end, AXIS_COLOURS[i], 3.0, class_=f"axis axis-{name}", stroke_linecap="round"
        )
        lab = orbit.tip(v, 1.12)
        svg.text(
            lab[0],
            lab[1] + 4,
            name,
            size=13,
            anchor="middle",
            fill=AXIS_COLOURS[i],
            font_weight="bold",
        )
        axes[name] = [end[0] - c, end[1] - c]
    return axes


def _draw_stamped_axes(svg: Svg, orbit: _Orbit, R_world_stamped: FloatArray) -> None:
    """The axes of the frame the data is stamped with, dashed and primed."""
    c = orbit.centre
    for i, name in enumerate("xyz"):
        v = np.asarray(R_world_stamped[:3, i], dtype=np.float64)
        end = orbit.tip(v, 0.85)
        svg.line(
            (c, c),
            end,
            AXIS_COLOURS[i],
            2.0,
            class_=f"stamped stamped-{name}",
            stroke_dasharray="5 4",
        )
        lab = orbit.tip(v, 0.95)
        svg.text(lab[0], lab[1] + 4, f"{name}'", size=10, anchor="middle", fill=AXIS_COLOURS[i])


def _imu_legend(svg: Svg, x: float, stamped_label: str | None, check_status: str) -> None:
    """What the lines are (``stamped_label``: the stamped frame's name, when its axes are
    drawn) and the frame check's result."""
    lines = ["x red, y green, z blue: the IMU's", "measurement axes (its render pose)"]
    if stamped_label is not None:
        lines += [f"dashed x' y' z': {stamped_label},", "the frame its data is stamped with"]
    lines += ["thin grey: the world", "seen from ahead-left, above", "(RViz's default view)"]
    for k, text in enumerate(lines):
        svg.text(x, 18 + 17 * k, text, size=12)
    status_colour = {"ok": "#17702a", "warn": "#a05a00", "fail": "#b3171b"}.get(
        check_status, "#777"
    )
    svg.text(
        x,
        18 + 17 * len(lines) + 8,
        f"frame check: {check_status}",
        size=11,
        fill=status_colour,
        class_="frame-check",
        font_weight="bold",
    )


# ---- the robot, close up ---------------------------------------------------------------------
@dataclass
class Mount:
    """A sensor where it is rendered from: name, colour, pose in the world."""

    name: str
    colour: str
    T_world: FloatArray
    link: str | None = None


@dataclass
class _Frame:
    """The close up's frame: the robot's box widened by ``margin`` (``lo``..``hi``), the
    scale both views share, and the length of each sensor's axes."""

    lo: FloatArray
    hi: FloatArray
    margin: float
    axis_len: float
    scale: float

    def projection(self, x0: float, axis: int) -> Projection:
        """World point -> pixel in the view whose left edge is ``x0`` and whose up is the
        world's ``axis`` (1 from above, 2 from the side)."""
        lo3, hi3, scale = self.lo, self.hi, self.scale

        def proj(p: FloatArray) -> tuple[float, float]:
            return (x0 + float(p[0] - lo3[0]) * scale, 20 + float(hi3[axis] - p[axis]) * scale)

        return proj


def closeup_figure(
    boxes: list[tuple[FloatArray, FloatArray]],
    outlines: list[FloatArray],
    link_origins: list[FloatArray],
    mounts: list[Mount],
    *,
    panel: int = 380,
) -> Figure:
    """The robot from above (x right, y up) and from its right side (x right, z up), one
    scale for both, framed on the robot's links and sensors, not the room: each shape's
    silhouette (``outlines``: world points of each visual, ``Shape.outline``), each
    collision box pybullet reports (``boxes``: lo, hi corners; meshes too), each sensor's
    origin and axes (x red, y green, z blue), named in a column beside each view with a
    leader line to it."""
    frame = _closeup_frame(boxes, outlines, link_origins, mounts, panel)
    lo3, hi3, scale, margin = frame.lo, frame.hi, frame.scale, frame.margin
    label_w = 150.0
    panel_w = float(hi3[0] - lo3[0]) * scale + label_w
    top_h = float(hi3[1] - lo3[1]) * scale
    side_h = float(hi3[2] - lo3[2]) * scale
    gap = 28.0
    names_h = 30 + 12.0 * len(mounts)  # the column of names, at 12 px a name at least
    svg = Svg(2 * panel_w + gap, max(top_h, side_h, names_h) + 60)
    views = {
        "top": (0.0, frame.projection(0.0, 1), top_h),
        "side": (panel_w + gap, frame.projection(panel_w + gap, 2), side_h),
    }
    placed: dict[str, dict[str, list[float]]] = {}
    for view_name, (x0, proj, h) in views.items():
        w = panel_w - label_w
        _closeup_view(svg, frame, view_name, x0, proj, w, h)
        _draw_boxes(svg, proj, boxes)
        _draw_outlines(svg, proj, outlines)
        _draw_mounts(svg, proj, mounts, frame.axis_len)
        _name_mounts(svg, proj, mounts, view_name, x0 + w + 10, h, placed)
    svg.text(
        0,
        svg.height - 6,
        "axes: x red, y green, z blue; dark grey: each link's visual shape, light grey: its collision box",
        size=10,
    )
    facts = {
        "bbox_m": [[float(v) for v in lo3 + margin], [float(v) for v in hi3 - margin]],
        "view_bbox_m": [[float(v) for v in lo3], [float(v) for v in hi3]],
        "pixels_per_m": scale,
        "axis_length_m": frame.axis_len,
        "mounts_px": placed,
    }
    caption = "The robot close up: every sensor's mount and axes, named"
    return Figure("closeup", caption, str(svg), facts)


def _closeup_frame(
    boxes: list[tuple[FloatArray, FloatArray]],
    outlines: list[FloatArray],
    link_origins: list[FloatArray],
    mounts: list[Mount],
    panel: int,
) -> _Frame:
    """The box around every link origin, collision box, sensor and visual outline, with
    room for the sensors' axes; the scale that fits it in ``panel`` pixels."""
    pts: list[FloatArray] = [np.asarray(p, dtype=np.float64)[:3] for p in link_origins]
    for lo, hi in boxes:
        pts += [np.asarray(lo, dtype=np.float64)[:3], np.asarray(hi, dtype=np.float64)[:3]]
    pts += [m.T_world[:3, 3] for m in mounts]
    pts += [row for o in outlines for row in np.asarray(o, dtype=np.float64).reshape(-1, 3)]
    cloud = np.array(pts) if pts else np.zeros((1, 3))
    lo3, hi3 = cloud.min(axis=0), cloud.max(axis=0)
    span = float(max(np.max(hi3 - lo3), 0.05))
    axis_len = 0.12 * span
    margin = axis_len * 1.3
    lo3, hi3 = lo3 - margin, hi3 + margin
    scale = min(
        panel / float(hi3[0] - lo3[0]), panel / float(max(hi3[1] - lo3[1], hi3[2] - lo3[2]))
    )
    return _Frame(lo3, hi3, margin, axis_len, scale)


def _closeup_view(
    svg: Svg, frame: _Frame, view_name: str, x0: float, proj: Projection, w: float, h: float
) -> None:
    """One view's background and title; from the side, the ground when it is in view."""
    lo3, hi3 = frame.lo, frame.hi
    svg.add("rect", x=x0, y=20, width=w, height=h, fill="#f7f7f4", stroke="#ddd")
    title = (
        "from above (x right, y up)"
        if view_name == "top"
        else "from the right side (x right, z up)"
    )
    svg.text(x0, 13, title, size=11)
    if view_name == "side" and lo3[2] < 0 < hi3[2]:
        g0, g1 = proj(np.array([lo3[0], 0, 0])), proj(np.array([hi3[0], 0, 0]))
        svg.line(g0, g1, "#a08c6e", 1.5)
        svg.text(g0[0] + 3, g0[1] - 3, "ground", size=9, fill="#a08c6e")


def _draw_boxes(svg: Svg, proj: Projection, boxes: list[tuple[FloatArray, FloatArray]]) -> None:
    """Each collision box pybullet reports, light grey."""
    for lo, hi in boxes:
        a = proj(np.asarray(lo, dtype=np.float64))
        b = proj(np.asarray(hi, dtype=np.float64))
        svg.add(
            "rect",
            x=min(a[0], b[0]),
            y=min(a[1], b[1]),
            width=abs(b[0] - a[0]),
            height=abs(b[1] - a[1]),
            fill="#c8ccd2",
            fill_opacity="0.6",
            stroke="#6c7280",
        )


def _draw_outlines(svg: Svg, proj: Projection, outlines: list[FloatArray]) -> None:
    """Each visual shape's silhouette (the hull of its outline), dark grey."""
    for outline in outlines:
        if len(outline) >= 3:
            hull = convex_hull(np.array([proj(q) for q in outline]))
            if len(hull) >= 3:
                svg.add(
                    "polygon",
                    points=" ".join(f"{num(x)},{num(y)}" for x, y in hull),
                    fill="#8a93a3",
                    fill_opacity="0.5",
                    stroke="#444",
                )


def _draw_mounts(svg: Svg, proj: Projection, mounts: list[Mount], axis_len: float) -> None:
    """Each sensor's origin in its colour and its axes (those not seen end on), named."""
    for m in mounts:
        o = proj(m.T_world[:3, 3])
        for i, name in enumerate("xyz"):
            e = proj(m.T_world[:3, 3] + m.T_world[:3, i] * axis_len)
            if math.hypot(e[0] - o[0], e[1] - o[1]) > 1.5:
                svg.line(o, e, AXIS_COLOURS[i], 2.0, stroke_linecap="round")
                ex, ey = o[0] + (e[0] - o[0]) * 1.18, o[1] + (e[1] - o[1]) * 1.18
                svg.text(ex, ey + 3, name, size=8, anchor="middle", fill=AXIS_COLOURS[i])
        svg.add("circle", cx=o[0], cy=o[1], r=3.5, fill=m.colour, stroke="#000")


def _name_mounts(
    svg: Svg,
    proj: Projection,
    mounts: list[Mount],
    view_name: str,
    lx: float,
    h: float,
    placed: dict[str, dict[str, list[float]]],
) -> None:
    """The names, in a column at ``lx`` right of the view, in the order of their heights,
    each with a leader line to its sensor; where each sensor is goes to ``placed``."""
    order = sorted(mounts, key=lambda m: proj(m.T_world[:3, 3])[1])
    step = max(12.0, min(24.0, h / max(1, len(order))))
    ys = [20 + 10 + k * step for k in range(len(order))]
    for m, y in zip(order, ys, strict=True):
        o = proj(m.T_world[:3, 3])
        svg.line(
            o,
            (lx - 2, y - 3),
            "#999",
            0.8,
            class_="leader",
            data_sensor=m.name,
            data_view=view_name,
        )
        svg.text(
            lx,
            y,
            m.name,
            size=10,
            class_="mount",
            data_sensor=m.name,
            data_view=view_name,
            fill=m.colour if m.colour != "#000000" else None,
        )
        placed.setdefault(m.name, {})[view_name] = [o[0], o[1]]


# ---- stereo pairs ----------------------------------------------------------------------------
def stereo_figure(
    name: str,
    left_name: str,
    right_name: str,
    left_png: bytes,
    right_png: bytes,
    size: tuple[int, int],
    baseline: float,
    t_left_right: FloatArray,
    rectified: bool,
    how: str,
    *,
    display: int = 320,
) -> Figure:
    """The left and right images side by side (left on the left), with lines across both
    at the same rows (a rectified pair sees a point on the same row in each), and the
    baseline."""
    width, height = size
    k = min(display / width, 3.0)
    w, h = width * k, height * k
    gap = 10.0
    svg = Svg(2 * w + gap, h + 58)
    svg.text(0, 12, f"left: {left_name}", size=11)
    svg.text(w + gap, 12, f"right: {right_name}", size=11)
    svg.image(left_png, 0, 18, w, h)
    svg.image(right_png, w + gap, 18, w, h)
    for f in (0.25, 0.5, 0.75):
        y = 18 + h * f
        svg.line(
            (0, y), (2 * w + gap, y), "#00e5ff", 0.8, stroke_opacity="0.7", stroke_dasharray="6 4"
        )
    t = np.asarray(t_left_right, dtype=np.float64)
    text = f"baseline {metres(baseline)} ({baseline * 1000:.1f} mm)"
    svg.text(
        0,
        h + 36,
        text,
        size=13,
        class_="baseline",
        data_baseline=repr(float(baseline)),
        font_weight="bold",
    )
    svg.text(
        0,
        h + 52,
        f"right eye in the left eye's optical frame: ({t[0]:+.4f}, {t[1]:+.4f}, {t[2]:+.4f}) m; "
        + ("rectified" if rectified else "not rectified")
        + f"; found by {how}",
        size=10,
    )
    facts = {
        "left": left_name,
        "right": right_name,
        "baseline_m": float(baseline),
        "t_left_right_m": [float(v) for v in t],
        "rectified": rectified,
        "how": how,
    }
    caption = f"stereo pair {name}: dashed lines cross both images at the same rows"
    return Figure(f"stereo:{name}", caption, str(svg), facts)
