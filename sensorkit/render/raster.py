"""A tiny numpy canvas for the top-down pictures, and the depth colour map.

Dots and lines are stamped with numpy (hundreds of thousands of returns at once);
polygons are filled by Pillow's ImageDraw within their bounding box.

Coordinates are pixels, x to the right and y down, as floats; shapes outside the canvas
are clipped. Nothing here knows about robots.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, TypeVar

import numpy as np
import numpy.typing as npt

_T = TypeVar("_T", bound="np.generic[Any]")

__all__ = ["DEPTH_STOPS", "Canvas", "colourise_depth", "convex_hull", "finite_rows", "take_rows"]

Colour = tuple[int, int, int]
_RGB = np.dtype("V3")  # one pixel, its three bytes as one value
# Dots past this count are drawn by pixel rather than one by one (same picture).
_MANY = 4096
Points = npt.NDArray[np.float64]

# Near (warm, bright) to far (cool, dark), evenly spaced over the scale; +inf and -inf
# get their own greys. Public for the colour bar beside depth.png.
DEPTH_STOPS = np.array(
    [
        [255, 236, 64],
        [246, 150, 40],
        [214, 72, 72],
        [140, 40, 130],
        [60, 40, 140],
        [16, 24, 72],
    ],
    dtype=np.float64,
)


def finite_rows(points: npt.NDArray[np.floating]) -> npt.NDArray[np.bool_]:
    """Which rows of ``points`` (``(N, k)``) are finite throughout, as
    ``np.isfinite(points).all(axis=1)`` says, column by column: numpy reduces along a
    short last axis some ten times slower (5 ms for a 128 x 2048 scan's points)."""
    finite = np.isfinite(points)
    out = np.ones(finite.shape[0], dtype=bool)
    for k in range(finite.shape[1]):
        out &= finite[:, k]
    return out


def take_rows(a: npt.NDArray[_T], rows: npt.NDArray[np.bool_]) -> npt.NDArray[_T]:
    """``a[rows]`` for a boolean ``rows``: ``a`` itself (not a copy) when that is every
    row, else ``a.take`` of their indices (numpy masks the rows of a 2-D array some four
    times slower)."""
    if rows.all():
        return a
    out: npt.NDArray[_T] = a.take(np.flatnonzero(rows), axis=0)
    return out


def _rgb(colour: Colour) -> np.void:
    """``colour`` as one ``_RGB`` value."""
    out: np.void = np.array(colour, dtype=np.uint8).view(_RGB)[0]
    return out


def _rgbs(colours: npt.NDArray[Any]) -> npt.NDArray[np.void]:
    """``(N, 3)`` colours as ``N`` ``_RGB`` values."""
    return np.ascontiguousarray(colours, dtype=np.uint8).view(_RGB).reshape(-1)


class Canvas:
    """An RGB image with line, polygon, circle and point drawing."""

    def __init__(self, width: int, height: int, background: Colour = (255, 255, 255)) -> None:
        self.width = width
        self.height = height
        self.image = np.empty((height, width, 3), dtype=np.uint8)
        row = np.empty((width, 3), dtype=np.uint8)
        row[:] = background
        self.image[:] = row  # (a row at a time: filling with one colour is much slower)

    def _pixels(self) -> npt.NDArray[np.void]:
        """``image`` as one ``_RGB`` value a pixel (row-major), a view: writes to it show
        in ``image``. Indexing it with flat pixel numbers is several times faster than
        indexing ``image`` with rows and columns, or with a mask, and writing a pixel as
        one value twice as fast as writing a row of three bytes."""
        if not self.image.flags.c_contiguous:
            self.image = np.ascontiguousarray(self.image)
        return self.image.reshape(-1, 3).view(_RGB).reshape(-1)

    def _stamp(
        self,
        xs: npt.NDArray[np.float64],
        ys: npt.NDArray[np.float64],
        colour: Colour,
        radius: float,
    ) -> None:
        r = max(0, int(np.ceil(radius - 0.5)))
        ix = np.rint(xs).astype(np.int64)
        iy = np.rint(ys).astype(np.int64)
        offsets = [
            (dx, dy)
            for dx in range(-r, r + 1)
            for dy in range(-r, r + 1)
            if dx * dx + dy * dy <= radius * radius + 0.25
        ] or [(0, 0)]
        if len(ix) > _MANY:  # one colour: mark the centres once, then paint each offset
            near = (ix >= -r) & (ix < self.width + r) & (iy >= -r) & (iy < self.height + r)
            if not near.all():
                ix, iy = ix[near], iy[near]
            wide = self.width + 2 * r
            marked = np.zeros((self.height + 2 * r) * wide, dtype=bool)
            marked[(iy + r) * wide + (ix + r)] = True
            centres = marked.reshape(self.height + 2 * r, wide)
            paint = np.zeros((self.height, self.width), dtype=bool)
            for dx, dy in offsets:
                paint |= centres[r - dy : r - dy + self.height, r - dx : r - dx + self.width]
            self._pixels()[np.flatnonzero(paint)] = _rgb(colour)
            return
        pixels = self._pixels()
        for dx, dy in offsets:
            x, y = ix + dx, iy + dy
            ok = (x >= 0) & (x < self.width) & (y >= 0) & (y < self.height)
            pixels[y[ok] * self.width + x[ok]] = _rgb(colour)

    def line(
        self,
        p0: Sequence[float],
        p1: Sequence[float],
        colour: Colour,
        *,
        width: float = 1.0,
        dash: float | None = None,
    ) -> None:
        """A segment; ``dash`` (pixels) draws it dashed."""
        x0, y0 = float(p0[0]), float(p0[1])
        x1, y1 = float(p1[0]), float(p1[1])
        if not all(np.isfinite(v) for v in (x0, y0, x1, y1)):
            return
        length = float(np.hypot(x1 - x0, y1 - y0))
        if length > 20 * (self.width + self.height):  # clip absurd segments cheaply
            return
        n = max(2, int(np.ceil(length * 2)) + 1)
        s = np.linspace(0.0, 1.0, n)
        xs = x0 + (x1 - x0) * s
        ys = y0 + (y1 - y0) * s
        if dash:
            keep = (np.floor(s * length / dash) % 2) == 0
            xs, ys = xs[keep], ys[keep]
        self._stamp(xs, ys, colour, width / 2.0)

    def lines(self, starts: Points, ends: Points, colour: Colour, *, width: float = 1.0) -> None:
        """Many segments at once (``(N, 2)`` arrays)."""
        if len(starts) == 0:
            return
        lengths = np.hypot(*(ends - starts).T)
        n = int(max(2, np.ceil(np.nanmax(lengths) * 2) + 1)) if np.isfinite(lengths).any() else 2
        n = min(n, 4 * (self.width + self.height))
        s = np.linspace(0.0, 1.0, n)[None, :]
        xs = starts[:, :1] + (ends[:, :1] - starts[:, :1]) * s
        ys = starts[:, 1:2] + (ends[:, 1:2] - starts[:, 1:2]) * s
        ok = np.isfinite(xs) & np.isfinite(ys)
        if ok.all():  # every sample: no copies
            self._stamp(xs.ravel(), ys.ravel(), colour, width / 2.0)
        else:
            self._stamp(xs[ok], ys[ok], colour, width / 2.0)

    def polygon(self, points: Points, fill: Colour | None, outline: Colour | None = None) -> None:
        """A filled polygon (Pillow's scan conversion, within its bounding box) with an
        optional outline."""
        pts = np.asarray(points, dtype=np.float64)
        if len(pts) < 3 or not np.isfinite(pts).all():
            return
        if fill is not None:
            from PIL import Image, ImageDraw

            x_lo = max(0, int(np.floor(pts[:, 0].min())))
            x_hi = min(self.width - 1, int(np.ceil(pts[:, 0].max())))
            y_lo = max(0, int(np.floor(pts[:, 1].min())))
            y_hi = min(self.height - 1, int(np.ceil(pts[:, 1].max())))
            if x_lo <= x_hi and y_lo <= y_hi:
                mask = Image.new("L", (x_hi - x_lo + 1, y_hi - y_lo + 1), 0)
                corners = [(float(x) - x_lo, float(y) - y_lo) for x, y in pts]
                ImageDraw.Draw(mask).polygon(corners, fill=1)
                rows, cols = np.nonzero(np.asarray(mask))
                self._pixels()[(rows + y_lo) * self.width + cols + x_lo] = _rgb(fill)
        if outline is not None:
            self.lines(pts, np.roll(pts, -1, axis=0), outline)

    def circle(
        self,
        centre: Sequence[float],
        radius: float,
        fill: Colour | None,
        outline: Colour | None = None,
    ) -> None:
        angles = np.linspace(0.0, 2 * np.pi, max(12, int(radius * 4)), endpoint=False)
        pts = np.stack(
            [centre[0] + radius * np.cos(angles), centre[1] + radius * np.sin(angles)], axis=1
        )
        if radius < 1.5 and fill is not None:
            self._stamp(np.array([centre[0]]), np.array([centre[1]]), fill, radius)
            return
        self.polygon(pts, fill, outline)

    def points(
        self, pts: Points, colour: Colour | npt.NDArray[np.uint8], *, radius: float = 0.5
    ) -> None:
        """Dots; ``colour`` may be one colour or one per point (``(N, 3)`` uint8)."""
        pts = np.asarray(pts, dtype=np.float64)
        if len(pts) == 0:
            return
        ok = finite_rows(pts)
        pts = take_rows(pts, ok)
        if isinstance(colour, np.ndarray) and colour.ndim == 2:
            cols = _rgbs(take_rows(colour, ok))
            ix = np.rint(pts[:, 0]).astype(np.int64)
            iy = np.rint(pts[:, 1]).astype(np.int64)
            r = max(0, int(np.ceil(radius - 0.5)))
            if len(ix) > _MANY:  # keep the last dot of each pixel: it is the one that shows
                near = (ix >= -r) & (ix < self.width + r) & (iy >= -r) & (iy < self.height + r)
                at = np.flatnonzero(near)
                key = (iy[at] + r) * (self.width + 2 * r) + (ix[at] + r)
                last = np.full((self.width + 2 * r) * (self.height + 2 * r), -1, dtype=np.int64)
                np.maximum.at(last, key, at)
                keep = last[last >= 0]
                ix, iy, cols = ix[keep], iy[keep], cols[keep]
            pixels = self._pixels()
            for dx in range(-r, r + 1):
                for dy in range(-r, r + 1):
                    x, y = ix + dx, iy + dy
                    inside = (x >= 0) & (x < self.width) & (y >= 0) & (y < self.height)
                    pixels[y[inside] * self.width + x[inside]] = cols[inside]
            return
        c = (int(colour[0]), int(colour[1]), int(colour[2]))
        self._stamp(pts[:, 0], pts[:, 1], c, radius)


def convex_hull(points: Points) -> Points:
    """The 2D convex hull (Andrew's monotone chain), counter-clockwise."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2).round(9)
    # np.unique(pts, axis=0) without numpy.ma (see sensorkit.render._stats): the rows
    # sorted by x, then y, each once
    pts = pts[np.lexsort((pts[:, 1], pts[:, 0]))]
    if len(pts) > 1:
        pts = pts[np.concatenate([[True], (pts[1:] != pts[:-1]).any(axis=1)])]
    if len(pts) < 3:
        return pts

    def cross(
        o: npt.NDArray[np.float64], a: npt.NDArray[np.float64], b: npt.NDArray[np.float64]
    ) -> float:
        return float((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]))

    lower: list[npt.NDArray[np.float64]] = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    upper: list[npt.NDArray[np.float64]] = []
    for p in pts[::-1]:
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def colourise_depth(
    depth: npt.NDArray[np.floating], *, lo: float | None = None, hi: float | None = None
) -> npt.NDArray[np.uint8]:
    """An RGB picture of a depth image: near warm and bright, far dark blue.

    The scale runs from ``lo`` to ``hi`` (default: the 1st and 99th percentiles of the
    finite values); +inf (nothing within range) is light grey, -inf (closer than the
    minimum) and NaN are black.
    """
    d = np.asarray(depth, dtype=np.float64)
    out = np.zeros((*d.shape, 3), dtype=np.uint8)
    finite = np.isfinite(d)
    out[np.isposinf(d)] = (225, 225, 225)
    if finite.any():
        values = d[finite]
        lo = float(np.percentile(values, 1)) if lo is None else lo
        hi = float(np.percentile(values, 99)) if hi is None else hi
        if hi <= lo:
            hi = lo + 1e-6
        t = np.clip((values - lo) / (hi - lo), 0.0, 1.0) * (len(DEPTH_STOPS) - 1)
        i = np.minimum(t.astype(np.int64), len(DEPTH_STOPS) - 2)
        f = (t - i)[:, None]
        rgb = DEPTH_STOPS[i] * (1.0 - f) + DEPTH_STOPS[i + 1] * f
        out[finite] = np.rint(rgb).astype(np.uint8)
    return out
