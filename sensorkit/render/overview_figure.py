"""The overview as index.html shows it: overview.png with metre ticks, every sensor's
frame named, the scene's markers, and a colour key.

The key reserves magenta (``MISMATCH``) for one thing, "where RViz will put it": the
frame a sensor's data is stamped with, when that is not where the sensor looks. Markers
are drawn in ``MARKER_COLOUR``, never magenta. Frame names stand in a column right of
the picture, each joined to its sensor by a leader line, one row apart, so no two
overlap and none covers the scene.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from sensorkit.render.overview import MARKER_COLOUR, MISMATCH, overview_px
from sensorkit.render.svg import Figure, Svg, hex_colour, metres, nice_step

if TYPE_CHECKING:
    from sensorkit.render.overview import SensorDrawing
    from sensorkit.render.scene import Shape

__all__ = ["FrameLabel", "overview_figure", "spread"]

ROW = 16.0  # px between two frame names
LEFT, BOTTOM = 44.0, 22.0  # the tick labels' margins
CHAR = 7.2  # px a character of 12 px text takes, at most (for the column's width)
KEY_ROW = 18.0  # px between two rows of the colour key


@dataclass
class FrameLabel:
    """A sensor's name and frame, in its colour, for the overview."""

    sensor: str
    frame: str
    colour: str  # "#rrggbb"
    origin: np.ndarray  # world (x, y, z)


def spread(wanted: list[float], low: float, high: float, gap: float = ROW) -> list[float]:
    """Positions as near ``wanted`` (sorted) as can be, at least ``gap`` apart, within
    ``low``..``high`` when they fit (pushed down, then back up from ``high``)."""
    out: list[float] = []
    for y in wanted:
        out.append(max(y, low, out[-1] + gap) if out else max(y, low))
    over = (out[-1] - high) if out else 0.0
    if over > 0:
        out = [y - over for y in out]
        for i in range(len(out) - 2, -1, -1):
            out[i] = min(out[i], out[i + 1] - gap)
    return out


def _ticks(svg: Svg, half: float, k: float, size: float) -> list[float]:
    """Metre ticks under the picture (x) and left of it (y)."""
    step = max(1.0, nice_step(2 * half, 8))
    values = [v * step for v in range(int(-half // step), int(half // step) + 1)]
    values = [v for v in values if -half <= v <= half]
    for v in values:
        x = LEFT + (v + half) * k
        y = (half - v) * k
        svg.line((x, size), (x, size + 4), "#555")
        svg.text(x, size + 15, metres(v), size=10, anchor="middle", class_="tick tick-x")
        svg.line((LEFT - 4, y), (LEFT, y), "#555")
        svg.text(LEFT - 6, y + 3.5, metres(v), size=10, anchor="end", class_="tick tick-y")
    svg.text(LEFT + size, size + 15, "x", size=10, anchor="end", class_="axis-name")
    return values


def _key_columns(width: float) -> int:
    """Entries a row of the colour key: 300 px each at least (12 px text)."""
    return max(1, min(3, int(width // 300.0)))


def _legend(svg: Svg, y0: float, width: float, mismatch: bool) -> None:
    """The colour key, up to three entries a row (300 px each at least)."""
    entries: list[tuple[str, str, str]] = [
        ("line", "#1f77b4", "where a sensor looks (its own colour)"),
        ("faint", "#c7ddec", "lidar beams, to their returns"),
        ("box", "#5f6978", "the robot, from above"),
        ("box", "#bea58f", "walls and crates"),
        ("dot", hex_colour(MARKER_COLOUR), "scene markers (reprojection)"),
        ("dash", hex_colour(MISMATCH), "magenta: where RViz puts the data"),
    ]
    per_row = _key_columns(width)
    col = width / per_row
    for i, (kind, colour, text) in enumerate(entries):
        x, y = (i % per_row) * col, y0 + (i // per_row) * KEY_ROW
        if kind == "dot":
            svg.add("circle", cx=x + 7, cy=y - 3.5, r=4.0, fill=colour, class_="key-swatch")
        elif kind == "box":
            svg.add("rect", x=x + 1, y=y - 9, width=12, height=10, fill=colour)
        else:
            dash = "4 3" if kind == "dash" else None
            svg.line((x, y - 4), (x + 14, y - 4), colour, 3.0, stroke_dasharray=dash)
        used = "" if kind != "dash" or mismatch else " (none here)"
        svg.text(x + 18, y, text + used, size=10, class_="key", data_colour=colour)


def overview_figure(
    png: bytes,
    size: int,
    half: float,
    labels: list[FrameLabel],
    markers: list[Shape],
    drawings: list[SensorDrawing],
    *,
    display: int = 400,
) -> Figure:
    """overview.png (``size`` px square, ``half`` m from the centre to each edge) framed
    with metre ticks, the frame names and the colour key."""
    k = display / (2.0 * half)
    longest = max((len(f"{lb.sensor}: {lb.frame}") for lb in labels), default=0)
    width = LEFT + display + max(250.0, 40 + CHAR * longest)
    per_row = _key_columns(width)
    svg = Svg(width, display + BOTTOM + 24 + KEY_ROW * -(-6 // per_row))
    svg.image(png, LEFT, 0, display, display)
    values = _ticks(svg, half, k, display)
    for m in markers:  # drawn again over the picture: the browser can tell their colour
        p = overview_px(m.centre[:2], half, display)[0]
        svg.add(
            "circle",
            cx=float(p[0]) + LEFT,
            cy=float(p[1]),
            r=max(1.5, float(m.size[0]) * k),
            fill=hex_colour(MARKER_COLOUR),
            class_="marker",
        )
    placed = sorted(
        ((lb, overview_px(lb.origin[:2], half, display)[0]) for lb in labels),
        key=lambda lp: float(lp[1][1]),
    )
    rows = spread([float(p[1]) for _, p in placed], 10.0, display - 4)
    x_text = LEFT + display + 28
    for (lb, p), y in zip(placed, rows, strict=True):
        colour = lb.colour
        svg.line(
            (LEFT + float(p[0]), float(p[1])), (x_text - 4, y - 4), colour, 0.8, class_="leader"
        )
        svg.text(x_text, y, f"{lb.sensor}: {lb.frame}", size=10, fill=colour, class_="frame-name")
    mismatch = any(d.published_origin is not None for d in drawings)
    _legend(svg, display + BOTTOM + 14, width, mismatch)
    step = metres(values[1] - values[0]) if len(values) > 1 else metres(2 * half)
    caption = (
        f"Top-down, +x right, +y up, a tick every {step}; each sensor named with the frame "
        "its data is stamped with."
    )
    facts = {
        "half_width_m": half,
        "ticks_m": values,
        "frames": {lb.sensor: lb.frame for lb in labels},
        "rviz_colour": hex_colour(MISMATCH),
        "marker_colour": hex_colour(MARKER_COLOUR),
    }
    return Figure("overview", caption, str(svg), facts)
