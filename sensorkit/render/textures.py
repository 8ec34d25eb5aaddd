"""Procedural textures rich in corners and edges, so that feature detectors find plenty.

Each texture is a deterministic function of its seed: two-tone checks, random
rectangles and discs in saturated colours, and a little fine noise. No files are read.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["feature_texture", "floor_texture"]


def feature_texture(seed: int, size: int = 256) -> npt.NDArray[np.uint8]:
    """A square RGB texture with many corners of different contrast and scale."""
    rng = np.random.default_rng(seed)
    img = np.empty((size, size, 3), dtype=np.float64)
    base = rng.uniform(90, 200, 3)
    cell = size // 8
    yy, xx = np.mgrid[0:size, 0:size]
    checks = ((yy // cell + xx // cell) % 2).astype(np.float64)[:, :, None]
    img[:] = base * (0.75 + 0.35 * checks)
    for _ in range(40):
        w, h = rng.integers(size // 20, size // 4, 2)
        x0, y0 = rng.integers(0, size - w), rng.integers(0, size - h)
        img[y0 : y0 + h, x0 : x0 + w] = rng.uniform(0, 255, 3)
    for _ in range(14):
        r = rng.uniform(size / 40, size / 10)
        cx, cy = rng.uniform(0, size, 2)
        img[(xx - cx) ** 2 + (yy - cy) ** 2 <= r * r] = rng.uniform(0, 255, 3)
    img += rng.normal(0.0, 6.0, img.shape)
    return np.clip(img, 0, 255).astype(np.uint8)


def floor_texture(seed: int, size: int = 256) -> npt.NDArray[np.uint8]:
    """A tiled floor: light and dark squares with speckles (one texture repeat = 1 m)."""
    rng = np.random.default_rng(seed)
    cell = size // 4
    yy, xx = np.mgrid[0:size, 0:size]
    checks = ((yy // cell + xx // cell) % 2).astype(np.float64)
    img = np.empty((size, size, 3), dtype=np.float64)
    img[:] = (150.0, 140.0, 120.0)
    img *= (0.7 + 0.45 * checks)[:, :, None]
    for _ in range(60):
        r = rng.uniform(1.5, size / 40)
        cx, cy = rng.uniform(0, size, 2)
        img[(xx - cx) ** 2 + (yy - cy) ** 2 <= r * r] = rng.uniform(20, 235, 3)
    img += rng.normal(0.0, 5.0, img.shape)
    return np.clip(img, 0, 255).astype(np.uint8)
