"""The labelled pictures of what a sensor sees: depth images and lidar scans.

Each picture is a :class:`~sensorkit.render.svg.Figure` (an inline SVG and the numbers
it draws, which summary.json holds and the tests compare with geometry):

- ``depth_figure``: depth.png with a colour bar in metres; the colour range is the 2nd to
  98th percentile of the valid depths, widened to round values and kept within the
  sensor's near/far (``depth_colour_range``);
- ``scan_figure``: scan.png with its range rings labelled in metres, the sectors where
  beams meet the robot shaded (``occluded_sectors``), and a legend;
- ``side_figure``: a side (elevation) view of a 3D or tilted lidar (``draw_side``):
  horizontal distance against height above the ground, ground hits in green.

Where the sensors sit (IMU axes, the robot close up, stereo pairs) is drawn by
``sensorkit.render.mount_pictures``. Nothing here imports pybullet or knows about files:
the preview hands in arrays and PNG bytes.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from sensorkit.render._stats import percentile, unique
from sensorkit.render.overview import SELF_HIT, ScanView, row_palette
from sensorkit.render.raster import DEPTH_STOPS, Canvas, finite_rows, take_rows
from sensorkit.render.svg import Figure, Svg, hex_colour, metres, nice_step, ticks

__all__ = [
    "GROUND_HIT",
    "SideView",
    "at_far_clip",
    "depth_colour_range",
    "depth_figure",
    "depth_percentiles",
    "draw_side",
    "occluded_sectors",
    "scan_figure",
    "side_figure",
]

FloatArray = npt.NDArray[np.float64]
GROUND_HIT = (46, 160, 67)
FAR_CLIP_REL = 1e-4  # depth this close to the far clip (relative) is the far plane itself


# ---- depth -------------------------------------------------------------------------------
def at_far_clip(depth: npt.NDArray[np.floating], far: float) -> npt.NDArray[np.bool_]:
    """Pixels on the far clip plane (within ``FAR_CLIP_REL`` of ``far``): the renderer's
    "nothing here" (sky), not a surface at that distance."""
    d = np.asarray(depth, dtype=np.float64)
    if not math.isfinite(far):
        return np.zeros(d.shape, dtype=bool)
    out: npt.NDArray[np.bool_] = np.isfinite(d) & (d >= far * (1.0 - FAR_CLIP_REL))
    return out


def depth_percentiles(depth: npt.NDArray[np.floating], far: float) -> tuple[float, float] | None:
    """The 2nd and 98th percentiles of the finite depths off the far clip plane, which
    ``depth_colour_range`` widens (None: no such depth)."""
    values = np.asarray(depth, dtype=np.float64)
    values = values[np.isfinite(values) & ~at_far_clip(values, far)]
    if values.size == 0:
        return None
    return percentile(values, 2.0), percentile(values, 98.0)


def depth_colour_range(
    depth: npt.NDArray[np.floating],
    near: float,
    far: float,
    used: tuple[float, float] | None = None,
) -> tuple[float, float]:
    """The depths the colour map spans: the 2nd to 98th percentile of the finite depths
    off the far clip plane (so that sky and a few far pixels do not wash the scene out),
    widened to round values (a tenth of the span, 1-2-5) and kept within ``near``..``far``
    (``used``: those percentiles, when ``depth_percentiles`` already gave them)."""
    used = used if used is not None else depth_percentiles(depth, far)
    if used is None:
        hi = far if math.isfinite(far) else near + 1.0
        return float(near), float(hi)
    lo, hi = used
    step = nice_step(hi - lo, 10) if hi > lo else nice_step(max(abs(hi), 1e-3), 10)
    lo = math.floor(lo / step + 1e-9) * step
    hi = math.ceil(hi / step - 1e-9) * step
    if hi <= lo:
        hi = lo + step
    lo, hi = max(lo, near), min(hi, far)
    if hi <= lo:  # near/far closer than one step
        values = np.asarray(depth, dtype=np.float64)
        values = values[np.isfinite(values) & ~at_far_clip(values, far)]
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
    percentiles: tuple[float, float] | None = None,
) -> Figure:
    """depth.png with a vertical colour bar from ``lo`` (bottom, warm) to ``hi`` (top,
    dark blue), ticks in metres, and swatches for +inf and -inf; the caption gives the
    ``percentiles`` (2nd, 98th) that ``lo`` and ``hi`` were widened from."""
    scale = min(display / width, 360 / height, 4.0)
    w, h = width * scale, height * scale
    bar_x, bar_w = w + 16, 16
    svg = Svg(w + 120, max(h, 150) + 4)
    svg.image(png, 0, 0, w, h)
    gid = f"depthbar{zlib.crc32(png):08x}"
    stops = "".join(
        f'<stop offset="{k / (len(DEPTH_STOPS) - 1):.4f}" stop-color="{hex_colour(c)}"/>'
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
        for v in ticks(lo, hi)
        if abs(v - lo) > 0.06 * (hi - lo) and abs(v - hi) > 0.06 * (hi - lo)
    ]
    for v, end in [(lo, "min"), *((v, None) for v in inner), (hi, "max")]:
        y = y_of(v)
        svg.line((bar_x + bar_w, y), (bar_x + bar_w + 4, y), "#333")
        svg.text(
            bar_x + bar_w + 7,
            y + 4,
            metres(v),
            class_="tick",
            data_value=repr(float(v)),
            data_end=end,
        )
    legend_y = bottom + 18 if h > 150 else 150.0
    svg.height = max(svg.height, legend_y + 34)
    svg.add("rect", x=0, y=legend_y - 9, width=10, height=10, fill="#e1e1e1", stroke="#999")
    svg.text(14, legend_y, f"nothing within {metres(far)} (+inf, or the far clip plane)", size=12)
    svg.add("rect", x=0, y=legend_y + 9, width=10, height=10, fill="#000")
    svg.text(14, legend_y + 18, f"nearer than {metres(near)} (-inf)", size=12)
    facts: dict[str, Any] = {"colour_min_m": lo, "colour_max_m": hi, "near_m": near, "far_m": far}
    if percentiles is not None:
        p2, p98 = percentiles
        facts.update(p2_m=p2, p98_m=p98)
        used = (
            f"the valid depths' 2nd and 98th percentiles, {p2:.3f} m and {p98:.3f} m, "
            "widened to round values within the clip range"
        )
    else:
        used = "no valid depth: the clip range"
    caption = (
        f"depth.png: metres along the optical axis, {metres(lo)} (yellow) to {metres(hi)} "
        f"(dark blue): {used}; nearer and further pixels take the end colours"
    )
    return Figure("depth", caption, str(svg), facts)


# ---- lidar from above ----------------------------------------------------------------------
_NEAR = 2  # pixels about a return that a ring's label must not cover


def _return_pixels(
    view: ScanView, returns: FloatArray | None, k: float, display: int
) -> npt.NDArray[np.bool_]:
    """The figure's pixels (``display`` + 1 square) a return is drawn on, and their
    neighbours two pixels either way: what a ring's label must not cover.

    Each return's pixel is marked once on a grid ``_NEAR`` pixels wider on every side,
    then the marks are widened by ``_NEAR`` pixels along the rows and along the columns
    (a few passes over the picture rather than 25 over the returns: a 3D scan has
    hundreds of thousands)."""
    size = display + 1
    if returns is None or not len(returns):
        return np.zeros((size, size), dtype=bool)
    xy = np.asarray(returns, dtype=np.float64)[:, :2]
    xy = take_rows(xy, finite_rows(xy))
    cols, rows = (np.rint(view.px(xy) * k).astype(np.int64) + _NEAR).T
    wide = size + 2 * _NEAR
    inside = (cols >= 0) & (cols < wide) & (rows >= 0) & (rows < wide)
    marked = np.zeros((wide, wide), dtype=bool)
    marked[rows[inside], cols[inside]] = True
    across = np.zeros((wide, size), dtype=bool)  # within _NEAR columns of a mark
    for d in range(2 * _NEAR + 1):
        across |= marked[:, d : d + size]
    taken = np.zeros((size, size), dtype=bool)  # and within _NEAR rows
    for d in range(2 * _NEAR + 1):
        taken |= across[d : d + size]
    return taken


def _ring_label_spot(
    view: ScanView, radius: float, k: float, display: int, taken: npt.NDArray[np.bool_]
) -> tuple[float, float] | None:
    """Where on the ring of ``radius`` its label goes: the first angle, from the
    forward-right diagonal round the ring, whose label box is inside the picture and
    covers no return (None: no such place)."""
    c = view.centre * k
    r = radius * view.scale * k
    width = len(metres(radius)) * 6.5
    for step in range(24):
        a = math.radians(45.0 + 15.0 * (step // 2 + step % 2) * (1 if step % 2 else -1))
        x, y = c + r * math.cos(a), c - r * math.sin(a)
        left, top, right, bottom = x + 1, y - 14, x + 3 + width, y + 1
        if left < 0 or top < 0 or right > display or bottom > display:
            continue
        if not taken[int(top) : int(bottom) + 1, int(left) : int(right) + 1].any():
            return x, y
    return None


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
    returns: FloatArray | None = None,
) -> Figure:
    """scan.png with each range ring labelled in metres on the ring, where no return is
    under the label (``returns``: the points' x, y in the sensor's frame; the
    forward-right diagonal first, then round the ring), and a legend: beam colours, hits
    on the robot, self-occluded sectors."""
    k = display / view.size
    legend_h = 20 + 16 * (2 + bool(sectors))
    svg = Svg(display, display + legend_h)
    svg.image(png, 0, 0, display, display)
    taken = _return_pixels(view, returns, k, display)
    for radius in view.rings:
        spot = _ring_label_spot(view, radius, k, display, taken)
        if spot is not None:
            svg.text(
                spot[0] + 2,
                spot[1] - 2,
                metres(radius),
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
                fill=hex_colour(palette[row]),
            )
        svg.text(130, y, f"beam rows, lowest (blue) to highest (orange), {rows} rows", size=10)
    else:
        svg.add("circle", cx=8, cy=y - 4, r=4, fill=hex_colour(row_palette(1)[0]))
        svg.text(18, y, "returns", size=10)
    y += 16
    svg.add("circle", cx=8, cy=y - 4, r=4, fill=hex_colour(SELF_HIT))
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
        4, y, f"black triangle: the sensor, forward up; rings every {metres(view.step)}", size=10
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
    # every return once, ground hits last: drawn over the others, they stay visible
    order = np.concatenate([np.flatnonzero(finite & ~ground), np.flatnonzero(finite & ground)])
    x = points[:, 0].take(order) - origin[0]
    y = points[:, 1].take(order) - origin[1]
    z = points[:, 2].take(order)
    on_ground = ground.take(order)
    flat = np.array([heading[0], heading[1]], dtype=np.float64)
    norm = float(np.hypot(*flat))
    flat = flat / norm if norm > 1e-9 else np.array([1.0, 0.0])
    along = x * flat[0] + y * flat[1]
    dist = np.hypot(x, y) * np.where(along < 0, -1.0, 1.0)
    sensor_z = float(origin[2])
    seen = len(order) > 0
    d_max = max(float(np.max(np.abs(dist))) * 1.05 if seen else 1.0, 1.0)
    z_lo = min(0.0, float(np.min(z)) if seen else 0.0) - 0.1
    z_hi = max(sensor_z, float(np.max(z)) if seen else sensor_z) + 0.2
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
    colours = row_palette(n_rows)[rows.take(order)]
    colours[on_ground] = GROUND_HIT
    colours[self_hit.take(order)] = SELF_HIT
    canvas.points(view.px(dist, z), colours, radius=1.0)
    canvas.circle(s[1], 4, (0, 0, 0))
    ahead = on_ground & (dist > 0)
    behind = on_ground & (dist < 0)
    facts: dict[str, Any] = {
        "sensor_height_m": sensor_z,
        "ground_hits": int(on_ground.sum()),
        "nearest_ground_ahead_m": float(dist[ahead].min()) if ahead.any() else None,
        "nearest_ground_behind_m": float(-dist[behind].max()) if behind.any() else None,
        "lowest_return_m": float(z.min()) if seen else None,
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
    svg = Svg(view.width + 56, view.height + 54)
    ox = 48.0
    svg.image(png, ox, 0, view.width, view.height)
    for d in ticks(-view.d_max, view.d_max, 8):
        x = ox + view.x0 + d * view.sx
        svg.line((x, view.height), (x, view.height + 4), "#555")
        svg.text(x, view.height + 15, metres(d), size=9, anchor="middle", class_="dist")
    for zt in ticks(view.z_lo, view.z_hi, 4):
        y = view.z0 - zt * view.sz
        svg.line((ox - 4, y), (ox, y), "#555")
        svg.text(ox - 6, y + 3, metres(zt), size=9, anchor="end", class_="height")
    sensor_z = float(facts["sensor_height_m"])
    sy = view.z0 - sensor_z * view.sz
    svg.text(
        ox + view.x0 + 8,
        sy - 6,
        f"sensor {metres(sensor_z)} above the ground",
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
        svg.line((x, view.z0 - 2), (x, view.z0 + 8), hex_colour(GROUND_HIT), 2.0)
        svg.text(
            x + 4 * sign,
            view.z0 + 18,
            f"ground from {metres(float(reach))}",
            size=10,
            anchor=anchor,
            class_="ground",
            fill=hex_colour(GROUND_HIT),
        )
    svg.text(ox, view.height + 32, "horizontal distance from the sensor (ahead +, behind -)",
             size=12)  # fmt: skip
    svg.text(ox, view.height + 48, "against height; green: ground hits, red: the robot itself",
             size=12)  # fmt: skip
    ratio = view.sz / view.sx
    caption = "side.png: every return from the side" + (
        f" (heights stretched {ratio:.1f}x)" if ratio > 1.5 else ""
    )
    return Figure("side", caption, str(svg), facts)
