"""Top-down pictures: the whole scene with every sensor (overview.png), and each lidar's
scan around the sensor (scan.png).

In the overview, +x points right and +y up; grid lines are 1 m apart. Each sensor has its
own colour: a camera's frustum (edge rays at the middle image row, as far as they reach)
and optical axis, a lidar's beams to their hits. When the frame the data is stamped with
does not match where the sensor looks, that frame's forward axis is drawn dashed in
magenta from the frame's origin, beside the true axis (two magenta rings when that axis
points straight up or down), with the data (and a camera's frustum) in magenta where
RViz will place it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from sensorkit.render.raster import Canvas, convex_hull, finite_rows, take_rows
from sensorkit.render.scene import GROUND, MARKER, Shape

__all__ = [
    "PALETTE",
    "ScanView",
    "SensorDrawing",
    "draw_overview",
    "draw_scan",
    "overview_px",
    "row_palette",
    "scan_colours",
    "scan_view",
]

FloatArray = npt.NDArray[np.float64]
PALETTE: list[tuple[int, int, int]] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (23, 190, 207),
    (188, 189, 34),
]
MISMATCH = (230, 0, 200)  # kept for "where RViz will put it" (sensorkit.render.rviz)
MARKER_COLOUR = (230, 170, 0)  # the scene's marker spheres: amber, never magenta


@dataclass
class SensorDrawing:
    """What the overview needs of one sensor, in world coordinates."""

    name: str
    colour: tuple[int, int, int]
    origin: FloatArray
    axis_end: FloatArray  # the true forward axis, as far as drawn
    edges: list[FloatArray] = field(default_factory=list)  # frustum edge end points
    hits: FloatArray | None = None  # lidar hit points (N, 3)
    published_origin: FloatArray | None = None
    published_axis_end: FloatArray | None = None
    published_hits: FloatArray | None = (
        None  # the data where RViz will put it (sensorkit.render.rviz)
    )
    published_edges: list[FloatArray] = field(default_factory=list)  # the frustum, likewise


class _View:
    def __init__(self, half: float, size: int) -> None:
        self.half = half
        self.scale = size / (2.0 * half)
        self.size = size

    def px(self, xy: FloatArray) -> FloatArray:
        """World (x, y) rows to pixel (column, row) rows."""
        a = np.atleast_2d(np.asarray(xy, dtype=np.float64))
        return np.stack(
            [(a[:, 0] + self.half) * self.scale, (self.half - a[:, 1]) * self.scale], axis=1
        )


def overview_px(xy: FloatArray, half: float, size: float) -> FloatArray:
    """World (x, y) rows to (column, row) in an overview ``size`` px square, ``half`` m
    from its centre to each edge (as ``draw_overview`` draws)."""
    a = np.atleast_2d(np.asarray(xy, dtype=np.float64))
    k = size / (2.0 * half)
    return np.stack([(a[:, 0] + half) * k, (half - a[:, 1]) * k], axis=1)


def draw_overview(
    scene_shapes: list[Shape],
    robot_shapes: list[Shape],
    robot_boxes: list[tuple[FloatArray, FloatArray]],
    sensors: list[SensorDrawing],
    half: float,
    size: int = 720,
) -> npt.NDArray[np.uint8]:
    """The top-down overview as an RGB image."""
    canvas = Canvas(size, size, (246, 246, 242))
    view = _View(half, size)
    if half <= 20:
        for k in range(int(-np.floor(half)), int(np.floor(half)) + 1):
            a = view.px(np.array([[k, -half], [k, half]]))
            b = view.px(np.array([[-half, k], [half, k]]))
            shade = (205, 205, 200) if k else (170, 170, 165)
            canvas.line(a[0], a[1], shade)
            canvas.line(b[0], b[1], shade)
    markers = [s for s in scene_shapes if s.role == MARKER and s.kind == "sphere" and s.visual]
    marker_ids = {id(m) for m in markers}
    for shape in scene_shapes:
        if shape.kind == GROUND or not shape.visual or id(shape) in marker_ids:
            continue
        pts = shape.footprint()
        if len(pts) < 3:
            continue
        hull = view.px(convex_hull(pts))
        fill = (190, 180, 165) if shape.role == "wall" else (215, 200, 170)
        canvas.polygon(hull, fill, (120, 110, 100))
    for radius in sorted({m.size[0] for m in markers}):
        same = np.array([m.centre[:2] for m in markers if m.size[0] == radius])
        canvas.points(view.px(same), MARKER_COLOUR, radius=max(1.0, radius * view.scale))
    for s in sensors:  # beams first, faint, so that the robot and the axes stay visible
        if s.hits is not None and len(s.hits):
            hits = take_rows(s.hits, finite_rows(s.hits))
            step = max(1, len(hits) // 360)
            sub = view.px(hits[::step, :2])
            o = view.px(s.origin[:2])
            faint = tuple(int(c * 0.25 + 255 * 0.75) for c in s.colour)
            canvas.lines(np.repeat(o, len(sub), axis=0), sub, faint)  # type: ignore[arg-type]
    for lo, hi in robot_boxes:
        rect = view.px(np.array([[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]]))
        canvas.polygon(rect, (120, 130, 140), (60, 60, 70))
    for shape in robot_shapes:
        pts = shape.footprint()
        if len(pts) >= 3:
            canvas.polygon(view.px(convex_hull(pts)), (95, 105, 120), (40, 40, 50))
    for s in sensors:
        o = view.px(s.origin[:2])[0]
        if s.hits is not None and len(s.hits):
            canvas.points(view.px(s.hits[:, :2]), s.colour, radius=1.0)
        for edge in s.edges:
            canvas.line(o, view.px(edge[:2])[0], s.colour, width=2)
        if len(s.edges) == 2:
            canvas.line(view.px(s.edges[0][:2])[0], view.px(s.edges[1][:2])[0], s.colour)
        canvas.line(o, view.px(s.axis_end[:2])[0], s.colour, width=2)
        if s.published_origin is not None and s.published_axis_end is not None:
            po = view.px(s.published_origin[:2])[0]
            pe = view.px(s.published_axis_end[:2])[0]
            true_len = float(np.hypot(*(view.px(s.axis_end[:2])[0] - o)))
            canvas.line(po, pe, MISMATCH, width=2, dash=6)
            if s.published_hits is not None and len(s.published_hits):
                canvas.points(view.px(s.published_hits[:, :2]), MISMATCH, radius=1.0)
            for edge in s.published_edges:
                canvas.line(po, view.px(edge[:2])[0], MISMATCH)
            if float(np.hypot(*(pe - po))) < max(6.0, 0.2 * true_len):  # it points up or down
                canvas.circle(po, 9, None, MISMATCH)
                canvas.circle(po, 12, None, MISMATCH)
            canvas.circle(po, 3, MISMATCH)
        canvas.circle(o, 4, s.colour, (0, 0, 0))
    return canvas.image


@dataclass
class ScanView:
    """Where ``draw_scan`` puts things: the sensor at the centre, forward (+x) up, left
    (+y) left, ``half`` metres from the centre to each edge, a range ring every ``step`` m
    (1, 2, 5, 10... m: at most 8 rings)."""

    size: int
    half: float
    step: float

    @property
    def scale(self) -> float:
        """Pixels per metre."""
        return self.size / (2.0 * self.half)

    @property
    def centre(self) -> float:
        return self.size / 2.0

    @property
    def rings(self) -> list[float]:
        """The ring radii drawn, in metres."""
        return [k * self.step for k in range(1, int(self.half / self.step + 1e-9) + 1)]

    def px(self, xy: FloatArray) -> FloatArray:
        """Sensor-frame (x, y) rows to pixel (column, row) rows."""
        a = np.atleast_2d(np.asarray(xy, dtype=np.float64))
        c = self.centre
        return np.stack([c - a[:, 1] * self.scale, c - a[:, 0] * self.scale], axis=1)


def _furthest(points: FloatArray, rows: npt.NDArray[np.bool_]) -> float:
    """``max(np.hypot(x, y))`` over the ``rows`` of ``points`` (at least one), exactly,
    with np.hypot (slow: 6 ms for 262,144 points) only on the rows whose x * x + y * y
    comes within 1e-9 of the largest (rounding moves it by a few parts in 1e16)."""
    x, y = points[:, 0], points[:, 1]
    with np.errstate(invalid="ignore", over="ignore"):
        square = x * x + y * y
    top = float(np.max(square, where=rows, initial=-np.inf))
    if not math.isfinite(top) or top == 0.0:  # overflow or all at the centre: every row
        return float(np.max(np.hypot(x[rows], y[rows])))
    near = rows & (square >= top * (1.0 - 1e-9))
    return float(np.max(np.hypot(x[near], y[near])))


def scan_view(points: FloatArray, range_max: float, size: int = 480) -> ScanView:
    """The view ``draw_scan`` uses for ``points``: out to the furthest return plus 10 %."""
    finite = finite_rows(points)
    reach = _furthest(points, finite) if finite.any() else range_max
    half = max(1.0, min(range_max, reach * 1.1))
    step = next((s for s in (0.5, 1, 2, 5, 10, 20, 50, 100) if half / s <= 8), 200.0)
    return ScanView(size, half, float(step))


SECTOR = (255, 222, 222)  # azimuths where a beam meets the robot itself
SELF_HIT = (220, 30, 30)


def draw_scan(
    points: FloatArray,
    elevation_index: npt.NDArray[np.int64],
    self_hit: npt.NDArray[np.bool_],
    range_max: float,
    size: int = 480,
    *,
    sectors: list[tuple[float, float]] | None = None,
    view: ScanView | None = None,
) -> npt.NDArray[np.uint8]:
    """A lidar's returns seen from above in its own frame, forward (+x) up, left (+y) left.

    Range rings every 1, 2, 5, 10... m (``scan_view``; pass ``view`` when it is already
    computed for these points); returns from the robot itself in red, and ``sectors``
    (azimuth intervals in radians, counter-clockwise from +x) shaded light red; 3D scans
    are coloured by beam row.
    """
    canvas = Canvas(size, size, (250, 250, 250))
    finite = finite_rows(points)
    if view is None or view.size != size:
        view = scan_view(points, range_max, size)
    c = view.centre
    for a0, a1 in sectors or []:
        n = max(2, int(np.degrees(a1 - a0)) + 2)
        arc = np.linspace(a0, a1, n)
        reach = view.half * 1.5
        rim = np.stack([np.cos(arc) * reach, np.sin(arc) * reach], axis=1)
        canvas.polygon(np.vstack([[[c, c]], view.px(rim)]), SECTOR)
    for radius in view.rings:
        canvas.circle((c, c), radius * view.scale, None, (215, 215, 215))
    canvas.line((c, 0), (c, size), (225, 225, 225))
    canvas.line((0, c), (size, c), (225, 225, 225))
    rows = int(elevation_index.max()) + 1 if len(elevation_index) else 1
    colours = scan_colours(elevation_index[finite], self_hit[finite], rows)
    canvas.points(view.px(take_rows(points, finite)[:, :2]), colours, radius=1.0)
    canvas.polygon(np.array([[c, c - 9], [c - 6, c + 6], [c + 6, c + 6]]), (0, 0, 0))
    return canvas.image


def row_palette(rows: int) -> npt.NDArray[np.uint8]:
    """One colour a beam row, lowest (blue) to highest (orange); one row: blue."""
    if rows <= 1:
        return np.array([[31, 119, 180]], dtype=np.uint8)
    t = np.arange(rows) / max(1, rows - 1)
    return np.stack([40 + 200 * t, 90 + 60 * (1 - t), 220 - 180 * t], axis=1).astype(np.uint8)


def scan_colours(
    elevation_index: npt.NDArray[np.int64], self_hit: npt.NDArray[np.bool_], rows: int
) -> npt.NDArray[np.uint8]:
    """The colour of each return: its row's of ``rows`` (``row_palette``), red when it hit
    the robot."""
    colours = row_palette(rows)[elevation_index]
    colours[self_hit] = SELF_HIT
    return colours
