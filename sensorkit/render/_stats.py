"""Median, percentiles and unique values as the checks and pictures use them, without
``numpy.ma``.

``np.median``, ``np.percentile`` and a plain ``np.unique`` import ``numpy.ma`` on first
use (its import builds signatures of C functions, which compiles the tokenizer's
regular expressions): some 15 ms of a preview that needs a few numbers from them.
``median`` and ``percentile`` give numpy's numbers bit for bit on 1-D arrays
(``method="linear"``, numpy's default): the same order statistics from
``np.partition``, combined with the same floating-point operations in the same dtype. A
NaN anywhere gives NaN, as numpy's do; an empty array gives NaN. ``unique`` gives
``np.unique``'s sorted values of an integer array.
"""

from __future__ import annotations

import math
from typing import Any, TypeVar

import numpy as np
import numpy.typing as npt

_Int = TypeVar("_Int", bound=np.integer[Any])

__all__ = ["median", "percentile", "unique"]


def median(values: npt.NDArray[np.floating]) -> float:
    """``float(np.median(values))`` for a 1-D float array."""
    a = np.asarray(values).ravel()
    n = a.size
    if n == 0:
        return math.nan
    half = n // 2
    kth = [half - 1, half, n - 1] if n % 2 == 0 else [half, n - 1]
    part = np.partition(a, kth)
    if np.isnan(part[-1]):
        return math.nan
    if n % 2:
        return float(part[half])
    # np.mean of the two middle values: their sum divided by 2, in the array's dtype
    return float((part[half - 1] + part[half]) / 2)


def percentile(values: npt.NDArray[np.floating], q: float) -> float:
    """``float(np.percentile(values, q))`` for a 1-D float array and ``0 <= q <= 100``."""
    a = np.asarray(values).ravel()
    n = a.size
    if n == 0:
        return math.nan
    virtual = (n - 1) * (q / 100)
    if virtual >= n - 1:  # numpy takes the largest value
        part = np.partition(a, [n - 1])
        return float(part[-1])
    lo = math.floor(virtual)
    part = np.partition(a, [lo, lo + 1, n - 1])
    if np.isnan(part[-1]):
        return math.nan
    below, above = part[lo], part[lo + 1]
    gamma = virtual - lo
    diff = above - below
    # numpy's _lerp: from the nearer end, so that gamma = 1 gives the upper value exactly
    return float(above - diff * (1 - gamma) if gamma >= 0.5 else below + diff * gamma)


def unique(values: npt.NDArray[_Int]) -> npt.NDArray[_Int]:
    """``np.unique(values)`` for an integer array: its distinct values, sorted."""
    s = np.sort(values.ravel())
    keep = np.empty(s.shape, dtype=bool)
    keep[:1] = True
    np.not_equal(s[1:], s[:-1], out=keep[1:])
    out: npt.NDArray[_Int] = s[keep]
    return out
