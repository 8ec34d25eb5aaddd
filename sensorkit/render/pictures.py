"""The labelled pictures of a preview: what a user looks at rather than reads.

Each picture is a :class:`Figure`: an inline SVG for index.html (PNG pixels where there
are many dots, SVG for every label, tick and axis, so text stays sharp and needs no font
library) and ``facts``, the numbers it draws (also written to summary.json, and what the
tests compare with geometry):

- ``depth_figure``: depth.png with a colour bar in metres; the colour range is the 2nd to
  98th percentile of the valid depths, widened to round values and kept within the
  sensor's near/far (``depth_colour_range``);
- ``scan_figure``: scan.png with its range rings labelled in metres, the sectors where
  beams meet the robot shaded (``occluded_sectors``), and a legend;
- ``side_figure``: a side (elevation) view of a 3D or tilted lidar (``draw_side``):
  horizontal distance against height above the ground, ground hits in green;
- ``imu_figure``: an IMU's axes (x red, y green, z blue) seen as RViz's default orbit view
  sees them (``VIEW_YAW``, ``VIEW_PITCH``), beside the world's and, when its data is
  stamped with another frame, that frame's; with the frame check's result;
- ``closeup_figure``: the robot alone (the box around its links and sensors), from above
  and from the side, with every sensor's mount and axes, each named;
- ``stereo_figure``: a stereo pair's two images side by side with its baseline.

Nothing here imports pybullet or knows about files: the preview hands in arrays and PNG
bytes.
"""

from __future__ import annotations

import base64
import html
import math
import zlib
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from sensorkit.render._stats import percentile, unique
from sensorkit.render.overview import SELF_HIT, ScanView, row_palette
from sensorkit.render.raster import DEPTH_STOPS, Canvas, convex_hull, finite_rows

__all__ = [
    "AXIS_COLOURS",
    "GROUND_HIT",
    "VIEW_PITCH",
    "VIEW_YAW",
    "Figure",
    "Mount",
    "SideView",
    "at_far_clip",
    "closeup_figure",
    "depth_colour_range",
    "depth_figure",
    "draw_side",
    "imu_figure",
    "nice_step",
    "occluded_sectors",
    "scan_figure",
    "side_figure",
    "stereo_figure",
    "view_axes",
]

FloatArray = npt.NDArray[np.float64]
AXIS_COLOURS = ("#d62728", "#2ca02c", "#1f5fd6")  # x red, y green, z blue (as RViz)
GROUND_HIT = (46, 160, 67)
# The IMU triad is seen as RViz's default orbit view sees the world: from yaw 45 deg
# (ahead of the robot and to its left) and pitch 30 deg above the ground.
VIEW_YAW = math.radians(45.0)
VIEW_PITCH = math.radians(30.0)
_FONT = "font-family:system-ui,sans-serif"
FAR_CLIP_REL = 1e-4  # depth this close to the far clip (relative) is the far plane itself


@dataclass
class Figure:
    """One picture of index.html: an inline ``<svg>``, a caption, and the numbers drawn."""

    key: str  # depth | scan | side | imu | closeup | stereo:<pair>
    caption: str
    svg: str
    facts: dict[str, Any] = field(default_factory=dict)

    def html(self) -> str:
        return (
            f'<figure class="picture" data-figure="{html.escape(self.key)}">{self.svg}'
            f"<figcaption>{html.escape(self.caption)}</figcaption></figure>"
        )


def _num(v: float) -> str:
    return f"{v:.2f}".rstrip("0").rstrip(".") if math.isfinite(v) else str(v)


def _metres(v: float) -> str:
    """``2.8 m``, ``0.25 m``, ``12 m``: as many decimals as the value needs (3 at most)."""
    if not math.isfinite(v):
        return f"{v} m"
    text = f"{v:.3f}".rstrip("0").rstrip(".")
    return f"{'0' if text == '-0' else text} m"


class _Svg:
    """An SVG document built as text; every string is escaped."""

    def __init__(self, width: float, height: float) -> None:
        self.width = width
        self.height = height
        self.parts: list[str] = []

    def add(self, tag: str, text: str | None = None, **attrs: Any) -> None:
        def value(v: Any) -> str:
            return _num(v) if isinstance(v, float) else str(v)

        a = "".join(
            f' {k.rstrip("_").replace("_", "-")}="{html.escape(value(v))}"'
            for k, v in attrs.items()
            if v is not None
        )
        self.parts.append(
            f"<{tag}{a}>{html.escape(text)}</{tag}>" if text is not None else f"<{tag}{a}/>"
        )

    def image(self, png: bytes, x: float, y: float, w: float, h: float) -> None:
        data = base64.b64encode(png).decode("ascii")
        self.add(
            "image",
            href=f"data:image/png;base64,{data}",
            x=x,
            y=y,
            width=w,
            height=h,
            preserveAspectRatio="none",
            style="image-rendering:pixelated",
        )

    def text(
        self, x: float, y: float, s: str, *, size: float = 11, anchor: str = "start", **attrs: Any
    ) -> None:
        self.add("text", s, x=x, y=y, font_size=size, text_anchor=anchor, style=_FONT, **attrs)

    def line(
        self,
        p: FloatArray | tuple[float, float],
        q: FloatArray | tuple[float, float],
        colour: str,
        width: float = 1.0,
        **attrs: Any,
    ) -> None:
        self.add(
            "line",
            x1=float(p[0]),
            y1=float(p[1]),
            x2=float(q[0]),
            y2=float(q[1]),
            stroke=colour,
            stroke_width=width,
            **attrs,
        )

    def __str__(self) -> str:
        return (
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{_num(self.width)}" '
            f'height="{_num(self.height)}" style="max-width:100%;height:auto" viewBox="0 0 {_num(self.width)} {_num(self.height)}">'
            + "".join(self.parts)
            + "</svg>"
        )


def _hex(colour: tuple[int, int, int] | npt.NDArray[np.uint8]) -> str:
    return "#{:02x}{:02x}{:02x}".format(*(int(c) for c in colour))


def nice_step(span: float, count: int = 5) -> float:
    """A 1, 2 or 5 x 10^k step that cuts ``span`` into about ``count`` parts."""
    if not span > 0 or not math.isfinite(span):
        return 1.0
    raw = span / count
    base = 10.0 ** math.floor(math.log10(raw))
    return next(m * base for m in (1.0, 2.0, 5.0, 10.0) if m * base >= raw * 0.999)


def _ticks(lo: float, hi: float, count: int = 5) -> list[float]:
    """Round values from ``lo`` to ``hi``, about ``count`` of them (the ends when the span
    is not a finite, positive number)."""
    if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
        return [v for v in (lo, hi) if math.isfinite(v)]
    step = nice_step(hi - lo, count)
    first = math.ceil(lo / step - 1e-9) * step
    out = [round(first + k * step, 10) for k in range(int((hi - first) / step + 1e-9) + 1)]
    return [v for v in out if lo - 1e-9 <= v <= hi + 1e-9]


# ---- depth -------------------------------------------------------------------------------
def at_far_clip(depth: npt.NDArray[np.floating], far: float) -> npt.NDArray[np.bool_]:
    """Pixels on the far clip plane (within ``FAR_CLIP_REL`` of ``far``): the renderer's
    "nothing here" (sky), not a surface at that distance."""
    d = np.asarray(depth, dtype=np.float64)
    if not math.isfinite(far):
        return np.zeros(d.shape, dtype=bool)
    out: npt.NDArray[np.bool_] = np.isfinite(d) & (d >= far * (1.0 - FAR_CLIP_REL))
    return out


def depth_colour_range(
    depth: npt.NDArray[np.floating], near: float, far: float
) -> tuple[float, float]:
    """The depths the colour map spans: the 2nd to 98th percentile of the finite depths
    off the far clip plane (so that sky and a few far pixels do not wash the scene out),
    widened to round values (a tenth of the span, 1-2-5) and kept within ``near``..``far``."""
    values = np.asarray(depth, dtype=np.float64)
    values = values[np.isfinite(values) & ~at_far_clip(values, far)]
    if values.size == 0:
        hi = far if math.isfinite(far) else near + 1.0
        return float(near), float(hi)
    lo, hi = percentile(values, 2.0), percentile(values, 98.0)
    step = nice_step(hi - lo, 10) if hi > lo else nice_step(max(abs(hi), 1e-3), 10)
    lo = math.floor(lo / step + 1e-9) * step
    hi = math.ceil(hi / step - 1e-9) * step
    if hi <= lo:
        hi = lo + step
    lo, hi = max(lo, near), min(hi, far)
    if hi <= lo:  # near/far closer than one step
        lo, hi = float(values.min()), float(values.max()) + 1e-6
    return round(lo, 9), round(hi, 9)


def depth_figure(
    png: bytes,
    width: int,
    height: int,
    lo: float,
    hi: float,
    near: float,
    far: float,
    *,
    display: int = 480,
) -> Figure:
    """depth.png with a vertical colour bar from ``lo`` (bottom, warm) to ``hi`` (top,
    dark blue), ticks in metres, and swatches for +inf and -inf."""
    scale = min(display / width, 360 / height, 4.0)
    w, h = width * scale, height * scale
    bar_x, bar_w = w + 16, 16
    svg = _Svg(w + 120, max(h, 150) + 4)
    svg.image(png, 0, 0, w, h)
    gid = f"depthbar{zlib.crc32(png):08x}"
    stops = "".join(
        f'<stop offset="{k / (len(DEPTH_STOPS) - 1):.4f}" stop-color="{_hex(c)}"/>'
        for k, c in enumerate(DEPTH_STOPS.astype(np.uint8))
    )
    svg.parts.append(
        f'<defs><linearGradient id="{gid}" x1="0" y1="1" x2="0" y2="0">{stops}</linearGradient></defs>'
    )
    top, bottom = 8.0, h - 8.0 if h > 150 else 142.0
    svg.add(
        "rect", x=bar_x, y=top, width=bar_w, height=bottom - top, fill=f"url(#{gid})", stroke="#555"
    )

    def y_of(v: float) -> float:
        return bottom - (v - lo) / (hi - lo) * (bottom - top)

    inner = [
        v
        for v in _ticks(lo, hi)
        if abs(v - lo) > 0.06 * (hi - lo) and abs(v - hi) > 0.06 * (hi - lo)
    ]
    for v, end in [(lo, "min"), *((v, None) for v in inner), (hi, "max")]:
        y = y_of(v)
        svg.line((bar_x + bar_w, y), (bar_x + bar_w + 4, y), "#333")
        svg.text(
            bar_x + bar_w + 7,
            y + 4,
            _metres(v),
            class_="tick",
            data_value=repr(float(v)),
            data_end=end,
        )
    legend_y = bottom + 18 if h > 150 else 150.0
    svg.height = max(svg.height, legend_y + 30)
    svg.add("rect", x=0, y=legend_y - 9, width=10, height=10, fill="#e1e1e1", stroke="#999")
    svg.text(14, legend_y, f"nothing within {_metres(far)} (+inf, or the far clip plane)", size=10)
    svg.add("rect", x=0, y=legend_y + 5, width=10, height=10, fill="#000")
    svg.text(14, legend_y + 14, f"nearer than {_metres(near)} (-inf)", size=10)
    facts = {"colour_min_m": lo, "colour_max_m": hi, "near_m": near, "far_m": far}
    caption = (
        f"depth.png: metres along the optical axis, {_metres(lo)} (yellow) to {_metres(hi)} "
        "(dark blue), the 2nd to 98th percentile of the valid depths; nearer and further "
        "pixels take the end colours"
    )
    return Figure("depth", caption, str(svg), facts)


# ---- lidar from above ----------------------------------------------------------------------
def occluded_sectors(
    azimuth: FloatArray, blocked: npt.NDArray[np.bool_], *, full_circle: bool
) -> list[tuple[float, float]]:
    """Azimuth intervals (radians, counter-clockwise from +x) whose beams meet the robot:
    each run of blocked columns, half a step wider on each side; on a full circle a run
    that wraps from the last column to the first is one sector."""
    n = len(azimuth)
    if n == 0 or not blocked.any():
        return []
    half = 0.5 * (float(azimuth[1] - azimuth[0]) if n > 1 else 0.0)
    runs: list[list[int]] = []
    for i in np.flatnonzero(blocked):
        if runs and runs[-1][1] == i - 1:
            runs[-1][1] = int(i)
        else:
            runs.append([int(i), int(i)])
    sectors = [(float(azimuth[a]) - half, float(azimuth[b]) + half) for a, b in runs]
    if full_circle and len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == n - 1:
        first, last = sectors.pop(0), sectors.pop()
        sectors.append((last[0], first[1] + 2 * math.pi))
    return sectors


def scan_figure(
    png: bytes,
    view: ScanView,
    sectors: list[tuple[float, float]],
    rows: int,
    self_hits: int,
    *,
    display: int = 480,
) -> Figure:
    """scan.png with each range ring labelled in metres where it crosses the forward-right
    diagonal, and a legend: beam colours, hits on the robot, self-occluded sectors."""
    k = display / view.size
    legend_h = 20 + 16 * (2 + bool(sectors))
    svg = _Svg(display, display + legend_h)
    svg.image(png, 0, 0, display, display)
    c = view.centre * k
    for radius in view.rings:
        r = radius * view.scale * k
        x, y = c + r * math.sqrt(0.5), c - r * math.sqrt(0.5)
        if 0 <= x <= display - 8 and y >= 10:
            svg.text(
                x + 2,
                y - 2,
                _metres(radius),
                size=10,
                class_="ring",
                data_radius=repr(radius),
                fill="#777",
            )
    y = display + 16
    if rows > 1:
        palette = row_palette(rows)
        shown = unique(np.linspace(0, rows - 1, min(rows, 60)).round().astype(int))
        for i, row in enumerate(shown):
            svg.add(
                "rect",
                x=4 + i * (120 / len(shown)),
                y=y - 9,
                width=120 / len(shown) + 0.5,
                height=10,
                fill=_hex(palette[row]),
            )
        svg.text(130, y, f"beam rows, lowest (blue) to highest (orange), {rows} rows", size=10)
    else:
        svg.add("circle", cx=8, cy=y - 4, r=4, fill=_hex(row_palette(1)[0]))
        svg.text(18, y, "returns", size=10)
    y += 16
    svg.add("circle", cx=8, cy=y - 4, r=4, fill=_hex(SELF_HIT))
    svg.text(18, y, f"returns from the robot itself ({self_hits})", size=10, class_="self-hits")
    y += 16
    degrees = [(math.degrees(a), math.degrees(b)) for a, b in sectors]
    if sectors:
        svg.add("rect", x=3, y=y - 9, width=10, height=10, fill="#ffdede", stroke="#e88")
        listed = ", ".join(f"{a:+.0f}..{b:+.0f} deg" for a, b in degrees)
        svg.text(
            18,
            y,
            f"self-occluded azimuths (0 ahead, + to the left): {listed}",
            size=10,
            class_="sectors",
        )
        y += 16
    svg.text(
        4, y, f"black triangle: the sensor, forward up; rings every {_metres(view.step)}", size=10
    )
    facts = {
        "rings_m": view.rings,
        "ring_step_m": view.step,
        "half_width_m": view.half,
        "pixels_per_m": view.scale,
        "self_occluded_deg": [[round(a, 3), round(b, 3)] for a, b in degrees],
    }
    caption = "scan.png: the returns from above in the sensor's frame, forward up, left to the left"
    return Figure("scan", caption, str(svg), facts)


# ---- lidar from the side -------------------------------------------------------------------
@dataclass
class SideView:
    """Pixel mapping of ``draw_side``: column = x0 + d * sx, row = z0 - z * sz, where d is
    the horizontal distance from the sensor (ahead positive) and z the height above the
    ground (world z)."""

    width: int
    height: int
    x0: float
    sx: float
    z0: float
    sz: float
    d_max: float
    z_lo: float
    z_hi: float

    def px(self, d: FloatArray, z: FloatArray) -> FloatArray:
        return np.stack([self.x0 + d * self.sx, self.z0 - z * self.sz], axis=1)


def draw_side(
    points: FloatArray,
    origin: FloatArray,
    heading: FloatArray,
    rows: npt.NDArray[np.int64],
    n_rows: int,
    ground: npt.NDArray[np.bool_],
    self_hit: npt.NDArray[np.bool_],
    *,
    width: int = 640,
    height: int = 260,
) -> tuple[npt.NDArray[np.uint8], SideView, dict[str, Any]]:
    """A lidar seen from its side: every return at its horizontal distance from the sensor
    (positive where it lies ahead of the sensor's heading, negative behind) and its height
    above the ground (world z); ground hits green, hits on the robot red, others by row.

    ``points``: world coordinates ``(N, 3)`` (NaN for no return); ``heading``: the
    sensor's forward axis in the world.
    """
    finite = finite_rows(points)
    keep = slice(None) if finite.all() else finite  # every point: no copies
    rel = points - origin
    flat = np.array([heading[0], heading[1]], dtype=np.float64)
    norm = float(np.hypot(*flat))
    flat = flat / norm if norm > 1e-9 else np.array([1.0, 0.0])
    along = rel[:, 0] * flat[0] + rel[:, 1] * flat[1]
    dist = np.hypot(rel[:, 0], rel[:, 1]) * np.where(along < 0, -1.0, 1.0)
    z = points[:, 2]
    sensor_z = float(origin[2])
    d_max = float(np.max(np.abs(dist[keep]))) * 1.05 if finite.any() else 1.0
    d_max = max(d_max, 1.0)
    z_lo = min(0.0, float(np.min(z[keep])) if finite.any() else 0.0) - 0.1
    z_hi = max(sensor_z, float(np.max(z[keep])) if finite.any() else sensor_z) + 0.2
    left, right, top, bottom = 8.0, 8.0, 8.0, 8.0
    sx = (width - left - right) / (2 * d_max)
    sz = (height - top - bottom) / (z_hi - z_lo)
    view = SideView(width, height, left + d_max * sx, sx, top + z_hi * sz, sz, d_max, z_lo, z_hi)
    canvas = Canvas(width, height, (250, 250, 250))
    g = view.px(np.array([-d_max, d_max]), np.array([0.0, 0.0]))
    canvas.polygon(np.array([g[0], g[1], [g[1][0], height], [g[0][0], height]]), (236, 230, 218))
    canvas.line(g[0], g[1], (150, 130, 100), width=2)
    s = view.px(np.array([0.0, 0.0]), np.array([0.0, sensor_z]))
    canvas.line(s[0], s[1], (200, 200, 200))
    colours = row_palette(n_rows)[rows[keep]]
    colours[ground[keep]] = GROUND_HIT
    colours[self_hit[keep]] = SELF_HIT
    order = np.argsort(ground[keep], kind="stable")  # ground hits last: they stay visible
    pts = view.px(dist[keep], z[keep])
    canvas.points(pts[order], colours[order], radius=1.0)
    canvas.circle(s[1], 4, (0, 0, 0))
    on_ground = finite & ground
    ahead = on_ground & (dist > 0)
    behind = on_ground & (dist < 0)
    facts: dict[str, Any] = {
        "sensor_height_m": sensor_z,
        "ground_hits": int(on_ground.sum()),
        "nearest_ground_ahead_m": float(dist[ahead].min()) if ahead.any() else None,
        "nearest_ground_behind_m": float(-dist[behind].max()) if behind.any() else None,
        "lowest_return_m": float(z[keep].min()) if finite.any() else None,
        "view": {
            "x0": view.x0,
            "pixels_per_m_horizontal": view.sx,
            "z0": view.z0,
            "pixels_per_m_vertical": view.sz,
        },
    }
    return canvas.image, view, facts


def side_figure(png: bytes, view: SideView, facts: dict[str, Any]) -> Figure:
    """The side view with distance and height ticks in metres, the sensor's height and the
    nearest ground hit ahead and behind labelled."""
    svg = _Svg(view.width + 56, view.height + 34)
    ox = 48.0
    svg.image(png, ox, 0, view.width, view.height)
    for d in _ticks(-view.d_max, view.d_max, 8):
        x = ox + view.x0 + d * view.sx
        svg.line((x, view.height), (x, view.height + 4), "#555")
        svg.text(x, view.height + 15, _metres(d), size=9, anchor="middle", class_="dist")
    for zt in _ticks(view.z_lo, view.z_hi, 4):
        y = view.z0 - zt * view.sz
        svg.line((ox - 4, y), (ox, y), "#555")
        svg.text(ox - 6, y + 3, _metres(zt), size=9, anchor="end", class_="height")
    sensor_z = float(facts["sensor_height_m"])
    sy = view.z0 - sensor_z * view.sz
    svg.text(
        ox + view.x0 + 8,
        sy - 6,
        f"sensor {_metres(sensor_z)} above the ground",
        size=10,
        class_="sensor",
    )
    for key, sign, anchor in (
        ("nearest_ground_ahead_m", 1.0, "start"),
        ("nearest_ground_behind_m", -1.0, "end"),
    ):
        reach = facts.get(key)
        if reach is None:
            continue
        x = ox + view.x0 + sign * float(reach) * view.sx
        svg.line((x, view.z0 - 2), (x, view.z0 + 8), _hex(GROUND_HIT), 2.0)
        svg.text(
            x + 4 * sign,
            view.z0 + 18,
            f"ground from {_metres(float(reach))}",
            size=10,
            anchor=anchor,
            class_="ground",
            fill=_hex(GROUND_HIT),
        )
    svg.text(
        ox,
        view.height + 30,
        "horizontal distance from the sensor (ahead +, behind -) against height; green: ground hits, red: the robot itself",
        size=10,
    )
    ratio = view.sz / view.sx
    caption = "side.png: every return from the side" + (
        f" (heights stretched {ratio:.1f}x)" if ratio > 1.5 else ""
    )
    return Figure("side", caption, str(svg), facts)


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
    c = size / 2.0
    length = size * 0.36
    svg = _Svg(size + 200, size)

    def tip(v: FloatArray, scale: float = 1.0) -> tuple[float, float]:
        return (c + float(v @ right) * length * scale, c - float(v @ up) * length * scale)

    for i, name in enumerate("xyz"):
        e = np.eye(3)[i]
        svg.line((c, c), tip(e, 0.55), "#b0b0b0", 1.0, class_=f"world-{name}")
        t = tip(e, 0.62)
        svg.text(t[0], t[1] + 3, f"world {name}", size=9, anchor="middle", fill="#999")
    axes: dict[str, list[float]] = {}
    for i, name in enumerate("xyz"):
        v = np.asarray(R_world_imu[:3, i], dtype=np.float64)
        end = tip(v)
        svg.line(
            (c, c), end, AXIS_COLOURS[i], 3.0, class_=f"axis axis-{name}", stroke_linecap="round"
        )
        lab = tip(v, 1.12)
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
    if R_world_stamped is not None:
        for i, name in enumerate("xyz"):
            v = np.asarray(R_world_stamped[:3, i], dtype=np.float64)
            end = tip(v, 0.85)
            svg.line(
                (c, c),
                end,
                AXIS_COLOURS[i],
                2.0,
                class_=f"stamped stamped-{name}",
                stroke_dasharray="5 4",
            )
            lab = tip(v, 0.95)
            svg.text(lab[0], lab[1] + 4, f"{name}'", size=10, anchor="middle", fill=AXIS_COLOURS[i])
    svg.add("circle", cx=c, cy=c, r=3, fill="#000")
    x = size + 6.0
    lines = ["x red, y green, z blue: the IMU's", "measurement axes (its render pose)"]
    if R_world_stamped is not None:
        lines += [f"dashed x' y' z': {stamped_frame or '?'},", "the frame its data is stamped with"]
    lines += ["thin grey: the world", "seen from ahead-left, above", "(RViz's default view)"]
    for k, text in enumerate(lines):
        svg.text(x, 18 + 14 * k, text, size=10)
    status_colour = {"ok": "#17702a", "warn": "#a05a00", "fail": "#b3171b"}.get(
        check_status, "#777"
    )
    svg.text(
        x,
        18 + 14 * len(lines) + 8,
        f"frame check: {check_status}",
        size=11,
        fill=status_colour,
        class_="frame-check",
        font_weight="bold",
    )
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


# ---- the robot, close up ---------------------------------------------------------------------
@dataclass
class Mount:
    """A sensor where it is rendered from: name, colour, pose in the world."""

    name: str
    colour: str
    T_world: FloatArray
    link: str | None = None


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
    label_w = 150.0
    panel_w = float(hi3[0] - lo3[0]) * scale + label_w
    top_h = float(hi3[1] - lo3[1]) * scale
    side_h = float(hi3[2] - lo3[2]) * scale
    gap = 28.0
    names_h = 30 + 12.0 * len(mounts)  # the column of names, at 12 px a name at least
    svg = _Svg(2 * panel_w + gap, max(top_h, side_h, names_h) + 60)

    def projection(x0: float, axis: int) -> Callable[[FloatArray], tuple[float, float]]:
        def proj(p: FloatArray) -> tuple[float, float]:
            return (x0 + float(p[0] - lo3[0]) * scale, 20 + float(hi3[axis] - p[axis]) * scale)

        return proj

    views = {
        "top": (0.0, projection(0.0, 1), top_h),
        "side": (panel_w + gap, projection(panel_w + gap, 2), side_h),
    }
    placed: dict[str, dict[str, list[float]]] = {}
    for view_name, (x0, proj, h) in views.items():
        w = panel_w - label_w
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
        for outline in outlines:
            if len(outline) >= 3:
                hull = convex_hull(np.array([proj(q) for q in outline]))
                if len(hull) >= 3:
                    svg.add(
                        "polygon",
                        points=" ".join(f"{_num(x)},{_num(y)}" for x, y in hull),
                        fill="#8a93a3",
                        fill_opacity="0.5",
                        stroke="#444",
                    )
        for m in mounts:
            o = proj(m.T_world[:3, 3])
            for i, name in enumerate("xyz"):
                e = proj(m.T_world[:3, 3] + m.T_world[:3, i] * axis_len)
                if math.hypot(e[0] - o[0], e[1] - o[1]) > 1.5:
                    svg.line(o, e, AXIS_COLOURS[i], 2.0, stroke_linecap="round")
                    ex, ey = o[0] + (e[0] - o[0]) * 1.18, o[1] + (e[1] - o[1]) * 1.18
                    svg.text(ex, ey + 3, name, size=8, anchor="middle", fill=AXIS_COLOURS[i])
            svg.add("circle", cx=o[0], cy=o[1], r=3.5, fill=m.colour, stroke="#000")
        # the names, in a column right of the view, in the order of their heights
        order = sorted(mounts, key=lambda m: proj(m.T_world[:3, 3])[1])
        step = max(12.0, min(24.0, h / max(1, len(order))))
        ys = [20 + 10 + k * step for k in range(len(order))]
        lx = x0 + w + 10
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
        "axis_length_m": axis_len,
        "mounts_px": placed,
    }
    caption = "The robot close up: every sensor's mount and axes, named"
    return Figure("closeup", caption, str(svg), facts)


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
    svg = _Svg(2 * w + gap, h + 58)
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
    text = f"baseline {_metres(baseline)} ({baseline * 1000:.1f} mm)"
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
