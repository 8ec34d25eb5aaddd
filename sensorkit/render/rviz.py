"""What RViz will show: a sensor's data placed by the frame it is stamped with.

A consumer (RViz, TF, a SLAM node) reads a message's coordinates in the frame its header
names: an image or a depth cloud as an optical frame (z forward, x right, y down), a scan
or a point cloud as x forward, z up. When that frame is not where the sensor looks (SK502,
SK503), the data lands somewhere else: a body-frame camera's cloud points at the sky. This
module takes a sample of the data in its true coordinates and places it both ways, for
the overview (top-down, beside the truth) and for ``rviz.png``: two panels, from above and
from the side along the sensor's heading, the truth in the sensor's colour and what RViz
will show in magenta.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from sensorkit.model.transforms_np import Mat
from sensorkit.render.raster import Canvas, finite_rows

__all__ = ["MISMATCH", "Misplaced", "camera_points", "draw_rviz", "lidar_points"]

FloatArray = npt.NDArray[np.float64]
MISMATCH = (230, 0, 200)  # the overview's colour for a frame that differs
MAX_POINTS = 1500  # a sample of the data is enough to see where it lands
PANEL = (320, 240)  # width, height of each of rviz.png's two panels
GAP = 6  # white columns between them
_GRID = (40, 30)  # image points sampled across a camera's image


@dataclass
class Misplaced:
    """A sensor's data where it really is and where a consumer will put it."""

    frame: str  # the frame the data is stamped with
    T_world_true: Mat  # the frame its coordinates are really in (optical, or the scan's)
    T_world_stamped: Mat  # the frame a consumer reads them in
    points: FloatArray  # (N, 3) a sample of the data, in its own coordinates
    axis: int  # the forward axis of both frames: 2 (optical z) or 0 (a scan's x)
    reach: float  # metres of forward axis to draw
    frustum: FloatArray | None = None  # (4, 3) a camera's image corners at ``reach``

    def true_world(self, pts: FloatArray) -> FloatArray:
        out: FloatArray = pts @ self.T_world_true[:3, :3].T + self.T_world_true[:3, 3]
        return out

    def stamped_world(self, pts: FloatArray) -> FloatArray:
        out: FloatArray = pts @ self.T_world_stamped[:3, :3].T + self.T_world_stamped[:3, 3]
        return out

    def forward(self) -> FloatArray:
        """``(2, 3)``: the far ends of the true and the stamped forward axis, in the world."""
        tip = np.zeros((1, 3))
        tip[0, self.axis] = self.reach
        return np.vstack([self.true_world(tip), self.stamped_world(tip)])

    def to_dict(self) -> dict[str, Any]:
        """For summary.json: where the sample's centre really is and where RViz puts it."""
        true_c = self.true_world(self.points).mean(axis=0) if len(self.points) else None
        stamped_c = self.stamped_world(self.points).mean(axis=0) if len(self.points) else None
        shift = (
            float(np.linalg.norm(stamped_c - true_c))
            if true_c is not None and stamped_c is not None
            else None
        )
        return {
            "frame": self.frame,
            "points": len(self.points),
            "centre_true": None if true_c is None else [float(v) for v in true_c],
            "centre_in_rviz": None if stamped_c is None else [float(v) for v in stamped_c],
            "centre_moved_m": shift,
        }


def _subsample(points: FloatArray, limit: int = MAX_POINTS) -> FloatArray:
    points = points[finite_rows(points)]
    if len(points) > limit:
        points = points[np.linspace(0, len(points) - 1, limit).round().astype(np.intp)]
    return points


def camera_points(
    depth: npt.NDArray[np.float32],
    fx: float,
    fy: float,
    cx: float,
    cy: float,
    skew: float = 0.0,
    reach: float = 1.0,
) -> tuple[FloatArray, FloatArray]:
    """(image points, frustum corners) in the optical frame: ``depth`` (metres along the
    optical axis, 0-based pixel centres at ``cx, cy``) sampled on a grid, and the four
    image corners at ``reach`` along the axis."""
    h, w = depth.shape
    cols = np.linspace(0, w - 1, min(w, _GRID[0]))
    rows = np.linspace(0, h - 1, min(h, _GRID[1]))
    u, v = np.meshgrid(cols, rows)
    z = depth[np.rint(v).astype(np.intp), np.rint(u).astype(np.intp)].astype(np.float64)
    y = (v - cy) / fy
    x = (u - cx - skew * y) / fx
    pts = np.stack([x * z, y * z, z], axis=-1).reshape(-1, 3)
    pts = pts[np.isfinite(z).reshape(-1) & (z.reshape(-1) > 0)]
    cu = np.array([0.0, w - 1.0, w - 1.0, 0.0])
    cv = np.array([0.0, 0.0, h - 1.0, h - 1.0])
    cyy = (cv - cy) / fy
    cxx = (cu - cx - skew * cyy) / fx
    corners = np.stack([cxx * reach, cyy * reach, np.full(4, reach)], axis=1)
    return _subsample(pts), corners


def lidar_points(points: npt.NDArray[np.float32]) -> FloatArray:
    """A sample of a scan's returns in its own frame (x forward, y left, z up)."""
    return _subsample(np.asarray(points, dtype=np.float64).reshape(-1, 3))


class _Fit:
    """Equal-aspect mapping of 2D coordinates into a panel, with a margin."""

    def __init__(self, pts: FloatArray, width: int, height: int, margin: int = 14) -> None:
        ok = pts[finite_rows(pts)]
        lo = ok.min(axis=0) if len(ok) else np.zeros(2)
        hi = ok.max(axis=0) if len(ok) else np.ones(2)
        span = np.maximum(hi - lo, 0.5)
        self.scale = min((width - 2 * margin) / span[0], (height - 2 * margin) / span[1])
        self.centre = (lo + hi) / 2.0
        self.mid = np.array([width / 2.0, height / 2.0])

    def px(self, pts: FloatArray) -> FloatArray:
        a = np.atleast_2d(np.asarray(pts, dtype=np.float64))
        d = (a - self.centre) * self.scale
        return np.stack([self.mid[0] + d[:, 0], self.mid[1] - d[:, 1]], axis=1)


def _heading(m: Misplaced) -> FloatArray:
    """The sensor's true forward axis on the ground (world x when it looks straight up or
    down): the side view looks across it."""
    f = m.T_world_true[:3, m.axis]
    flat = np.array([f[0], f[1]])
    n = float(np.hypot(*flat))
    return flat / n if n > 1e-6 else np.array([1.0, 0.0])


def _panel(
    m: Misplaced,
    colour: tuple[int, int, int],
    project: Any,
    ground: float | None,
) -> tuple[npt.NDArray[np.uint8], _Fit]:
    w, h = PANEL
    canvas = Canvas(w, h, (250, 250, 248))
    true_pts = m.true_world(m.points)
    rviz_pts = m.stamped_world(m.points)
    tips = m.forward()
    origins = np.vstack([m.T_world_true[:3, 3], m.T_world_stamped[:3, 3]])
    corners_t = m.true_world(m.frustum) if m.frustum is not None else np.zeros((0, 3))
    corners_s = m.stamped_world(m.frustum) if m.frustum is not None else np.zeros((0, 3))
    every = np.vstack([true_pts, rviz_pts, tips, origins, corners_t, corners_s])
    fit = _Fit(project(every), w, h)
    if ground is not None:  # the floor, seen edge-on
        y = float(fit.px(np.array([[0.0, ground]]))[0, 1])
        if 0 <= y < h:
            canvas.polygon(np.array([[0, y], [w, y], [w, h], [0, h]]), (232, 228, 218))
            canvas.line((0, y), (w, y), (170, 165, 150))
    faint = tuple(int(c * 0.35 + 255 * 0.65) for c in colour)
    o_t, o_s = fit.px(project(origins))
    for corners, o, c in ((corners_t, o_t, faint), (corners_s, o_s, (245, 170, 235))):
        for end in fit.px(project(corners)) if len(corners) else ():
            canvas.line(o, end, c)  # type: ignore[arg-type]
    canvas.points(fit.px(project(true_pts)), colour, radius=1.0)
    canvas.points(fit.px(project(rviz_pts)), MISMATCH, radius=1.0)
    t_t, t_s = fit.px(project(tips))
    canvas.line(o_t, t_t, colour, width=2)
    canvas.line(o_s, t_s, MISMATCH, width=2, dash=6)
    canvas.circle(o_t, 4, colour, (0, 0, 0))
    canvas.circle(o_s, 3, MISMATCH)
    canvas.polygon(
        np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]]), None, (200, 200, 200)
    )
    return canvas.image, fit


def draw_rviz(
    m: Misplaced, colour: tuple[int, int, int], ground: float | None = 0.0
) -> tuple[npt.NDArray[np.uint8], list[dict[str, Any]]]:
    """rviz.png: from above (+x right, +y up), then from the side (the sensor's heading
    right, up up; the floor at ``ground``), the truth in ``colour`` and what RViz will
    show in magenta, each with its forward axis (dashed: the stamped frame's); and each
    panel's scale (pixels per metre, where it starts in the image), for the labels
    index.html draws over it: axes, a scale bar and the stamped frame's name."""
    heading = _heading(m)

    def top(p: FloatArray) -> FloatArray:
        return np.asarray(p)[:, :2]

    def side(p: FloatArray) -> FloatArray:
        a = np.asarray(p)
        return np.stack([a[:, :2] @ heading, a[:, 2]], axis=1)

    gap = np.full((PANEL[1], GAP, 3), 255, dtype=np.uint8)
    above, fit_above = _panel(m, colour, top, None)
    beside, fit_beside = _panel(m, colour, side, ground)
    image: npt.NDArray[np.uint8] = np.concatenate([above, gap, beside], axis=1)
    panels = [
        {"view": "top", "x0": 0, "px_per_m": float(fit_above.scale),
         "axes": ["x", "y"], "heading": None},
        {"view": "side", "x0": PANEL[0] + GAP, "px_per_m": float(fit_beside.scale),
         "axes": ["forward", "z"], "heading": [float(v) for v in heading]},
    ]  # fmt: skip
    return image, panels


def moved_text(m: Misplaced) -> str:
    """``the data lands 1.20 m from where the sensor sees it, turned 120 deg``."""
    d = m.to_dict()
    R = m.T_world_true[:3, :3].T @ m.T_world_stamped[:3, :3]
    angle = math.degrees(math.acos(max(-1.0, min(1.0, (float(np.trace(R)) - 1.0) / 2.0))))
    moved = d["centre_moved_m"]
    where = f"its centre lands {moved:.2f} m from where it is" if moved is not None else "it moves"
    return f"{where}, turned {angle:.0f} deg"
