"""PNG files, read and written with Pillow.

Pillow is imported inside each function: only a preview that writes or reads a picture
loads it (``sensorkit validate`` never does). Images are numpy arrays: ``(H, W)`` grey,
``(H, W, 3)`` RGB or ``(H, W, 4)`` RGBA, 8 bits a channel; ``read_png`` gives back
exactly the pixels ``encode_png`` was given (as ``(H, W, C)``).
"""

from __future__ import annotations

import io
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sensorkit.base.atomic import write_bytes

if TYPE_CHECKING:
    from pathlib import Path

__all__ = ["encode_png", "intact_png", "read_png", "write_png"]

_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_IEND = b"\x00\x00\x00\x00IEND\xaeB`\x82"  # the last chunk: empty, with its CRC
_MODES = {1: "L", 3: "RGB", 4: "RGBA"}  # channels -> Pillow mode


def encode_png(image: npt.NDArray[np.uint8], *, level: int = 3) -> bytes:
    """The PNG bytes of an ``(H, W)``, ``(H, W, 3)`` or ``(H, W, 4)`` uint8 array
    (``level``: zlib's compression level, 0 to 9)."""
    from PIL import Image

    img = np.ascontiguousarray(image)
    if img.dtype != np.uint8:
        msg = f"PNG images must be uint8, got {img.dtype}"
        raise ValueError(msg)
    if img.ndim == 3 and img.shape[2] == 1:
        img = img[:, :, 0]
    channels = 1 if img.ndim == 2 else img.shape[2] if img.ndim == 3 else 0
    if channels not in _MODES or img.shape[0] < 1 or img.shape[1] < 1:
        msg = f"PNG images must be (H, W), (H, W, 3) or (H, W, 4), got {image.shape}"
        raise ValueError(msg)
    out = io.BytesIO()
    Image.fromarray(img, _MODES[channels]).save(out, "PNG", compress_level=level)
    return out.getvalue()


def write_png(path: Path, image: npt.NDArray[np.uint8], *, level: int = 3) -> bytes:
    """Encode ``image`` and publish it atomically at ``path``; returns the bytes."""
    data = encode_png(image, level=level)
    write_bytes(path, data, fsync=False)
    return data


def intact_png(data: bytes, width: int, height: int) -> bool:
    """``data`` is a whole PNG of ``width`` x ``height`` pixels: every chunk's CRC intact,
    IEND last, nothing after (it says nothing of what the pixels hold)."""
    from PIL import Image

    if not (data.startswith(_SIGNATURE) and data.endswith(_IEND)):
        return False
    try:
        with Image.open(io.BytesIO(data), formats=["PNG"]) as img:
            if img.size != (width, height):
                return False
            img.verify()  # every chunk's CRC, up to IEND
    except (OSError, ValueError, SyntaxError, EOFError):
        return False
    return True


def read_png(data: bytes) -> npt.NDArray[np.uint8]:
    """Decode a PNG into ``(H, W, C)`` uint8: C is 1 for grey, 3 for RGB, 4 for RGBA
    (a palette or 16-bit image becomes RGB or RGBA). A file that is not a whole PNG
    raises ValueError."""
    from PIL import Image

    try:
        with Image.open(io.BytesIO(data), formats=["PNG"]) as opened:
            opened.load()
            img: Image.Image = opened
            if img.mode not in _MODES.values():
                transparent = "A" in img.getbands() or "transparency" in img.info
                img = img.convert("RGBA" if transparent else "RGB")
            pixels = np.asarray(img, dtype=np.uint8)
    except (OSError, SyntaxError, EOFError) as exc:
        msg = f"not a readable PNG file: {exc}"
        raise ValueError(msg) from exc
    return pixels[:, :, None] if pixels.ndim == 2 else pixels
