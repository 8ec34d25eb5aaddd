"""Procedural textures rich in corners and edges, so that feature detectors find plenty.

Each texture is a deterministic function of its seed: two-tone checks, random
rectangles and discs in saturated colours, and a little fine noise.

Making the nine textures of the default room and encoding them for pybullet is a tenth of
a camera preview, the same every time: :func:`texture_file` keeps each one, as a BMP
(sensorkit.render.bitmap: pybullet loads it three times faster than a PNG), in the user's
cache folder (``$SENSORKIT_CACHE_DIR``, else ``$XDG_CACHE_HOME/sensorkit``, else
``~/.cache/sensorkit``), named by what makes it (kind, seed, size, a digest of this
module and numpy's version, whose random streams may change between releases). A cached
file is used only when it is a whole, well-formed BMP of the right size whose rows match
their CRC; anything else is made again. Where no cache folder can be written, the file
goes to the caller's temporary folder, as before.
"""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

__all__ = ["Texture", "feature_texture", "floor_texture", "texture_file"]


def _disc(
    img: npt.NDArray[np.int16], cx: float, cy: float, r: float, colour: npt.NDArray[np.int16]
) -> None:
    size = img.shape[0]
    x0, x1 = max(0, int(cx - r)), min(size, int(cx + r) + 2)
    y0, y1 = max(0, int(cy - r)), min(size, int(cy + r) + 2)
    if x0 >= x1 or y0 >= y1:
        return
    yy = np.arange(y0, y1)[:, None]
    xx = np.arange(x0, x1)[None, :]
    img[y0:y1, x0:x1][(xx - cx) ** 2 + (yy - cy) ** 2 <= r * r] = colour


def _checks(size: int, cell: int) -> npt.NDArray[np.bool_]:
    """A checkerboard of ``cell``-pixel squares, True on the odd ones."""
    parity = (np.arange(size) // cell) % 2 == 1
    out: npt.NDArray[np.bool_] = parity[:, None] ^ parity[None, :]
    return out


def _two_tone(
    checks: npt.NDArray[np.bool_], on: npt.NDArray[np.int16], off: npt.NDArray[np.int16]
) -> npt.NDArray[np.int16]:
    """An RGB image of ``on`` where ``checks`` holds and ``off`` elsewhere: np.where's
    image, looked up in a two-colour table (several times faster)."""
    table = np.stack([off, on]).astype(np.int16)
    out: npt.NDArray[np.int16] = table.take(checks.ravel().view(np.uint8), axis=0)
    return out.reshape(*checks.shape, 3)


def _finish(
    img: npt.NDArray[np.int16], rng: np.random.Generator, noise: int
) -> npt.NDArray[np.uint8]:
    img += rng.integers(-noise, noise + 1, img.shape, dtype=np.int16)
    return np.clip(img, 0, 255).astype(np.uint8)


def feature_texture(seed: int, size: int = 256) -> npt.NDArray[np.uint8]:
    """A square RGB texture with many corners of different contrast and scale. Shapes
    are sized within a 256 px patch: a larger texture (a whole wall) holds more of them,
    no bigger."""
    rng = np.random.default_rng(seed)
    unit = min(size, 256)
    per = (size // unit) ** 2  # as many shapes per texel as in a 256 px texture
    checks = _checks(size, unit // 8)
    base = rng.integers(90, 200, 3).astype(np.int16)
    img = _two_tone(checks, base * 110 // 100, base * 75 // 100)
    for _ in range(40 * per):
        w, h = rng.integers(unit // 20, unit // 4, 2)
        x0, y0 = rng.integers(0, size - w), rng.integers(0, size - h)
        row = np.empty((w, 3), dtype=np.int16)  # one row of the colour, then every row:
        row[:] = rng.integers(0, 256, 3)  # numpy fills a block with one colour slowly
        img[y0 : y0 + h, x0 : x0 + w] = row
    for _ in range(14 * per):
        r = rng.uniform(unit / 40, unit / 10)
        cx, cy = rng.uniform(0, size, 2)
        _disc(img, cx, cy, r, rng.integers(0, 256, 3).astype(np.int16))
    return _finish(img, rng, 10)


def floor_texture(seed: int, size: int = 256) -> npt.NDArray[np.uint8]:
    """A tiled floor: light and dark squares with speckles (one texture repeat = 1 m)."""
    rng = np.random.default_rng(seed)
    checks = _checks(size, size // 4)
    tone = np.array([150, 140, 120], dtype=np.int16)
    img = _two_tone(checks, tone * 115 // 100, tone * 70 // 100)
    for _ in range(60):
        r = rng.uniform(1.5, size / 40)
        cx, cy = rng.uniform(0, size, 2)
        _disc(img, cx, cy, r, rng.integers(20, 236, 3).astype(np.int16))
    return _finish(img, rng, 8)


@dataclass(frozen=True)
class Texture:
    """A texture of the default room, by what makes it."""

    kind: str  # "floor" or "feature"
    seed: int
    size: int = 256

    def image(self) -> npt.NDArray[np.uint8]:
        make = floor_texture if self.kind == "floor" else feature_texture
        return make(self.seed, self.size)


def cache_dir() -> Path | None:
    """sensorkit's folder in the user's cache (see the module doc), or None."""
    explicit = os.environ.get("SENSORKIT_CACHE_DIR")
    if explicit:
        return Path(explicit)
    xdg = os.environ.get("XDG_CACHE_HOME")
    if xdg and os.path.isabs(xdg):
        return Path(xdg) / "sensorkit"
    home = os.environ.get("HOME")
    return Path(home) / ".cache" / "sensorkit" if home else None


@functools.cache
def _digest() -> str:
    """What the textures depend on besides their seeds: this module's code and numpy."""
    import hashlib

    h = hashlib.sha256(Path(__file__).read_bytes())
    h.update(np.__version__.encode())
    return h.hexdigest()[:16]


def texture_file(texture: Texture, fallback: Path) -> Path:
    """A BMP of ``texture`` for pybullet to load (see sensorkit.render.bitmap): the cached
    one (made on first use), or, where the cache cannot be written, one written in the
    folder ``fallback``."""
    from sensorkit.render.bitmap import encode_bmp, intact_bmp

    folder = cache_dir()
    name = f"{texture.kind}-{texture.seed}-{texture.size}-{_digest()}.bmp"
    if folder is not None:
        path = folder / "textures" / name
        try:
            if intact_bmp(path.read_bytes(), texture.size, texture.size):
                return path
        except OSError:
            pass
    data = encode_bmp(texture.image())
    if folder is not None:
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            # a unique name, then one rename: a preview running beside this one reads a
            # whole file or none
            tmp = path.with_name(f".{name}.{os.getpid()}.tmp")
            tmp.write_bytes(data)
            os.replace(tmp, path)
            return path
        except OSError:
            pass
    out = fallback / name
    out.write_bytes(data)
    return out
