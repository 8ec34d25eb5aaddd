"""PNG files written with the standard library (zlib + struct): no imaging dependency.

Only what the preview needs: 8-bit grey, RGB or RGBA, no interlacing, filter type 0.
``read_png`` reads back what ``encode_png`` writes (and any non-interlaced 8-bit
grey/RGB/RGBA PNG with the standard filters), for tests and for textures.
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sensorkit.base.atomic import write_bytes

__all__ = ["encode_png", "read_png", "write_png"]

_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_COLOUR_TYPE = {1: 0, 3: 2, 4: 6}  # channels -> PNG colour type
_CHANNELS = {0: 1, 2: 3, 6: 4}


def _chunk(kind: bytes, data: bytes) -> bytes:
    crc = zlib.crc32(kind + data) & 0xFFFFFFFF
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)


def encode_png(image: npt.NDArray[np.uint8], *, level: int = 3) -> bytes:
    """The PNG bytes of an ``(H, W)``, ``(H, W, 3)`` or ``(H, W, 4)`` uint8 array."""
    img = np.ascontiguousarray(image)
    if img.dtype != np.uint8:
        msg = f"PNG images must be uint8, got {img.dtype}"
        raise ValueError(msg)
    if img.ndim == 2:
        img = img[:, :, None]
    if img.ndim != 3 or img.shape[2] not in _COLOUR_TYPE or img.shape[0] < 1 or img.shape[1] < 1:
        msg = f"PNG images must be (H, W), (H, W, 3) or (H, W, 4), got {image.shape}"
        raise ValueError(msg)
    height, width, channels = img.shape
    rows = np.zeros((height, 1 + width * channels), dtype=np.uint8)  # filter byte 0 per row
    rows[:, 1:] = img.reshape(height, width * channels)
    header = struct.pack(">IIBBBBB", width, height, 8, _COLOUR_TYPE[channels], 0, 0, 0)
    return b"".join(
        (
            _SIGNATURE,
            _chunk(b"IHDR", header),
            _chunk(b"IDAT", zlib.compress(rows.tobytes(), level)),
            _chunk(b"IEND", b""),
        )
    )


def write_png(path: Path, image: npt.NDArray[np.uint8], *, level: int = 3) -> bytes:
    """Encode ``image`` and publish it atomically at ``path``; returns the bytes."""
    data = encode_png(image, level=level)
    write_bytes(path, data, fsync=False)
    return data


def _paeth(a: int, b: int, c: int) -> int:
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def intact_png(data: bytes, width: int, height: int) -> bool:
    """``data`` is a whole PNG of ``width`` x ``height`` pixels: IHDR first, IEND last,
    every chunk's CRC intact, nothing after (it says nothing of what the pixels hold)."""
    if not data.startswith(_SIGNATURE):
        return False
    pos = len(_SIGNATURE)
    kinds: list[bytes] = []
    while pos + 12 <= len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        end = pos + 12 + length
        if end > len(data):
            return False
        body = data[pos + 4 : end - 4]  # the chunk's type and data, which its CRC covers
        if zlib.crc32(body) & 0xFFFFFFFF != struct.unpack(">I", data[end - 4 : end])[0]:
            return False
        if not kinds and (body[:4] != b"IHDR" or body[4:12] != struct.pack(">II", width, height)):
            return False
        kinds.append(body[:4])
        pos = end
    return pos == len(data) and kinds[-1:] == [b"IEND"]


def read_png(data: bytes) -> npt.NDArray[np.uint8]:
    """Decode a non-interlaced 8-bit grey/RGB/RGBA PNG into ``(H, W, C)`` uint8."""
    if not data.startswith(_SIGNATURE):
        msg = "not a PNG file"
        raise ValueError(msg)
    pos = len(_SIGNATURE)
    idat: list[bytes] = []
    width = height = channels = 0
    while pos + 8 <= len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in _CHANNELS or interlace:
                msg = f"unsupported PNG (bit depth {depth}, colour type {colour}, interlace {interlace})"
                raise ValueError(msg)
            channels = _CHANNELS[colour]
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    raw = zlib.decompress(b"".join(idat))
    stride = width * channels
    out = np.zeros((height, stride), dtype=np.uint8)
    prev = np.zeros(stride, dtype=np.int32)
    for r in range(height):
        start = r * (stride + 1)
        ftype = raw[start]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=start + 1).astype(np.int32)
        if ftype == 0:
            cur = line
        elif ftype == 2:
            cur = (line + prev) & 0xFF
        else:  # Sub, Average, Paeth depend on the left neighbour: byte by byte
            cur = np.zeros(stride, dtype=np.int32)
            for i in range(stride):
                left = int(cur[i - channels]) if i >= channels else 0
                up = int(prev[i])
                upleft = int(prev[i - channels]) if i >= channels else 0
                if ftype == 1:
                    pred = left
                elif ftype == 3:
                    pred = (left + up) // 2
                elif ftype == 4:
                    pred = _paeth(left, up, upleft)
                else:
                    msg = f"bad PNG filter type {ftype}"
                    raise ValueError(msg)
                cur[i] = (int(line[i]) + pred) & 0xFF
        out[r] = cur
        prev = cur
    return out.reshape(height, width, channels)
