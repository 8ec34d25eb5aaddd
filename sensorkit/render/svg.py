"""The labelled pictures' common ground: a :class:`Figure` and the SVG it is drawn in.

A figure is an inline SVG for index.html (PNG pixels where there are many dots, SVG for
every label, tick and axis, so text stays sharp and needs no font library) and ``facts``,
the numbers it draws (also written to summary.json). ``Svg`` builds the document as
escaped text; ``num``, ``metres`` and ``hex_colour`` write numbers and colours the way
every picture shows them, ``quantity`` and ``vector`` the way index.html's tables do
(lengths in mm, angles in degrees, fixed decimals, a non-breaking space before the unit); ``nice_step`` and ``ticks`` pick round values for scales.
"""

from __future__ import annotations

import base64
import html
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = [
    "Figure",
    "Svg",
    "glue_units",
    "hex_colour",
    "label_box",
    "metres",
    "nice_step",
    "num",
    "quantity",
    "ticks",
    "vector",
]

FloatArray = npt.NDArray[np.float64]
_FONT = "font-family:system-ui,sans-serif"
# The smallest text a picture draws, in its own units: index.html shows every picture at
# 92 % of its size or more at a 1400 px wide window, so no label is under 11 px there
# (the Chromium test measures it).
MIN_TEXT = 12.0


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
            f"<figcaption>{html.escape(glue_units(self.caption))}</figcaption></figure>"
        )


def num(v: float) -> str:
    return f"{v:.2f}".rstrip("0").rstrip(".") if math.isfinite(v) else str(v)


def metres(v: float) -> str:
    """``2.8 m``, ``0.25 m``, ``12 m``: as many decimals as the value needs (3 at most)."""
    if not math.isfinite(v):
        return f"{v} m"
    text = f"{v:.3f}".rstrip("0").rstrip(".")
    return f"{'0' if text == '-0' else text} m"


NBSP = "\u00a0"  # between a number and its unit: a line never breaks there
# unit given -> (factor, unit shown, decimals): lengths in mm, angles in degrees
_SHOWN: dict[str, tuple[float, str, int]] = {
    "m": (1000.0, NBSP + "mm", 1),
    "mm": (1.0, NBSP + "mm", 1),
    "rad": (180.0 / math.pi, "\u00b0", 2),
    "deg": (1.0, "\u00b0", 2),
    "px": (1.0, NBSP + "px", 2),
    "%": (1.0, NBSP + "%", 1),
}


_UNIT_AFTER_NUMBER = r"(\d) (mm|m|cm|px|deg|degrees|rad|s|ms|%)(?![\w])"


def glue_units(text: str) -> str:
    """``text`` with a non-breaking space between each number and the unit after it
    (``2.75 m``, ``0.35 px``), so that a line never ends between them."""
    import re

    return re.sub(_UNIT_AFTER_NUMBER, "\\1" + NBSP + "\\2", text)


def _fixed(v: float, decimals: int) -> str:
    if not math.isfinite(v):
        return str(v)
    text = f"{v:.{decimals}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text  # no "-0.0"


def quantity(value: float, unit: str, decimals: int | None = None) -> str:
    """``2.3\u00a0mm`` for (0.0023, "m"), ``11.46\u00b0`` for (0.2, "rad"), ``0.35\u00a0px``:
    lengths in mm and angles in degrees, with fixed decimals (``decimals`` overrides);
    another unit is kept, with 3 decimals."""
    factor, shown, places = _SHOWN.get(unit, (1.0, NBSP + unit if unit else "", 3))
    return _fixed(value * factor, places if decimals is None else decimals) + shown


def vector(values: list[float] | tuple[float, ...], unit: str) -> str:
    """``(250.0, 0.0, 100.0)\u00a0mm``: a vector in one unit, as ``quantity`` writes it."""
    factor, shown, places = _SHOWN.get(unit, (1.0, NBSP + unit if unit else "", 3))
    return "(" + ", ".join(_fixed(float(v) * factor, places) for v in values) + ")" + shown


class Svg:
    """An SVG document built as text; every string is escaped."""

    def __init__(self, width: float, height: float) -> None:
        self.width = width
        self.height = height
        self.parts: list[str] = []
        self.boxes: list[tuple[float, float, float, float]] = []  # text laid out so far

    def add(self, tag: str, text: str | None = None, **attrs: Any) -> None:
        def value(v: Any) -> str:
            return num(v) if isinstance(v, float) else str(v)

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
        """``s`` at (``x``, ``y``), or, when that would cover text already laid out, at
        the nearest free place a line above or below or beside it (``label_box``)."""
        size = max(size, MIN_TEXT)
        bold = str(attrs.get("font_weight", "")) == "bold"
        x, y = self._free_place(x, y, label_box(x, y, s, size, anchor, bold=bold))
        self.boxes.append(label_box(x, y, s, size, anchor, bold=bold))
        self.add("text", s, x=x, y=y, font_size=size, text_anchor=anchor, style=_FONT, **attrs)

    def _free_place(
        self, x: float, y: float, box: tuple[float, float, float, float]
    ) -> tuple[float, float]:
        w, h = box[2] - box[0], box[3] - box[1]
        steps = [(0.0, 0.0)]
        for k in (1, 2, 3):
            steps += [(0.0, -k * h), (0.0, k * h), (k * (w / 2 + 2), 0.0), (-k * (w / 2 + 2), 0.0)]
        for dx, dy in steps:
            moved = (box[0] + dx, box[1] + dy, box[2] + dx, box[3] + dy)
            if not any(_overlap(moved, other) for other in self.boxes):
                return x + dx, y + dy
        return x, y

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
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{num(self.width)}" '
            f'height="{num(self.height)}" style="max-width:100%;height:auto" viewBox="0 0 {num(self.width)} {num(self.height)}">'
            + "".join(self.parts)
            + "</svg>"
        )


def label_box(
    x: float, y: float, s: str, size: float, anchor: str = "start", *, bold: bool = False
) -> tuple[float, float, float, float]:
    """(left, top, right, bottom) that text ``s`` at baseline (``x``, ``y``) stays within,
    a little generously: 0.62 em a character (0.68 bold), 1.25 em tall."""
    w = len(s) * size * (0.68 if bold else 0.62)
    left = x - w / 2 if anchor == "middle" else x - w if anchor == "end" else x
    return (left, y - size, left + w, y + 0.25 * size)


def _overlap(a: tuple[float, float, float, float], b: tuple[float, float, float, float]) -> bool:
    return min(a[2], b[2]) > max(a[0], b[0]) and min(a[3], b[3]) > max(a[1], b[1])


def hex_colour(colour: tuple[int, int, int] | npt.NDArray[np.uint8]) -> str:
    return "#{:02x}{:02x}{:02x}".format(*(int(c) for c in colour))


def nice_step(span: float, count: int = 5) -> float:
    """A 1, 2 or 5 x 10^k step that cuts ``span`` into about ``count`` parts."""
    if not span > 0 or not math.isfinite(span):
        return 1.0
    raw = span / count
    base = 10.0 ** math.floor(math.log10(raw))
    return next(m * base for m in (1.0, 2.0, 5.0, 10.0) if m * base >= raw * 0.999)


def ticks(lo: float, hi: float, count: int = 5) -> list[float]:
    """Round values from ``lo`` to ``hi``, about ``count`` of them (the ends when the span
    is not a finite, positive number)."""
    if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
        return [v for v in (lo, hi) if math.isfinite(v)]
    step = nice_step(hi - lo, count)
    first = math.ceil(lo / step - 1e-9) * step
    out = [round(first + k * step, 10) for k in range(int((hi - first) / step + 1e-9) + 1)]
    return [v for v in out if lo - 1e-9 <= v <= hi + 1e-9]
