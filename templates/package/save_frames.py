#!/usr/bin/env python3
"""save_frames: write a frame of each camera topic to disk every INTERVAL seconds.

Written by sensorkit new; launch/save_frames.launch.py starts it with the robot's camera
topics. Alone:

    ros2 run PACKAGE save_frames.py --ros-args -p topics:="['/cam/image_raw']" -p interval:=2.0

Parameters
  topics     sensor_msgs/Image topics to save (string array)
  encodings  the encoding each topic should carry, in the same order ("" for any): a frame
             in another encoding is saved all the same, with one warning per topic
  interval   seconds of message time (header.stamp) between two saved frames of one topic
             (default 5.0; 0 saves every frame); a stamp that goes back (the simulation
             was reset) starts over
  folder     where to write (default "frames"): FOLDER/<topic>/<sec>_<nanosec>.<ext>, the
             topic with its slashes as "__" (ROS 2 names never hold a double underscore,
             so no two topics share a folder)
  format     depth images (32FC1 metres, 16UC1 millimetres): "png" writes a 16-bit PNG in
             millimetres, 0 where there is no depth (NaN, +-inf, <= 0 or beyond 65.535 m), as
             REP 118 defines 16UC1 depth images (ros-infrastructure/rep@79f7f76:
             rep-0118.rst:43-48); "npy" writes the array as received

Colour and grey images are written as PNG (8 or 16 bit, RGB order); a Bayer image as its
raw one-channel mosaic. Every file is written whole or not at all (a temporary file renamed
into place).

Everything above main() works without ROS: it needs numpy only and reads any object shaped
like sensor_msgs/Image (height, width, encoding, is_bigendian, step, data, header.stamp).
"""

from __future__ import annotations

import io
import math
import os
import struct
import sys
import zlib
from collections.abc import Callable
from typing import Any

import numpy as np

# encoding -> (numpy dtype of one sample, channels), as sensor_msgs/image_encodings names them
ENCODINGS: dict[str, tuple[str, int]] = {
    "mono8": ("u1", 1),
    "mono16": ("u2", 1),
    "rgb8": ("u1", 3),
    "bgr8": ("u1", 3),
    "rgba8": ("u1", 4),
    "bgra8": ("u1", 4),
    "rgb16": ("u2", 3),
    "bgr16": ("u2", 3),
    "rgba16": ("u2", 4),
    "bgra16": ("u2", 4),
    "8UC1": ("u1", 1),
    "8UC3": ("u1", 3),
    "16UC1": ("u2", 1),
    "32FC1": ("f4", 1),
    "bayer_rggb8": ("u1", 1),
    "bayer_bggr8": ("u1", 1),
    "bayer_gbrg8": ("u1", 1),
    "bayer_grbg8": ("u1", 1),
}
DEPTH_ENCODINGS = frozenset({"32FC1", "16UC1"})  # metres (float) and millimetres (uint16)
DEPTH_FORMATS = ("png", "npy")
MAX_MILLIMETRES = 65535


def image_to_array(msg: Any) -> np.ndarray:
    """The pixels of a sensor_msgs/Image-shaped ``msg`` as a native-endian numpy array:
    ``(height, width)`` for one channel, ``(height, width, channels)`` otherwise.

    Row padding (``step`` beyond ``width * bytes per pixel``) is dropped and big-endian
    data is swapped. Raises ValueError for an unknown encoding or too little data.
    """
    encoding = str(msg.encoding)
    if encoding not in ENCODINGS:
        raise ValueError(f"encoding {encoding!r} is not one save_frames reads")
    kind, channels = ENCODINGS[encoding]
    height, width, step = int(msg.height), int(msg.width), int(msg.step)
    sample = np.dtype(kind).newbyteorder(">" if msg.is_bigendian else "<")
    row = width * channels * sample.itemsize
    if height < 1 or width < 1:
        raise ValueError(f"an empty image ({width} x {height})")
    if step < row:
        raise ValueError(
            f"step {step} is shorter than a row of {width} {encoding} pixels ({row} bytes)"
        )
    data = bytes(msg.data)
    if len(data) < step * (height - 1) + row:
        raise ValueError(f"{len(data)} bytes of data for {height} rows of step {step}")
    raw = np.frombuffer(data, dtype=np.uint8, count=min(len(data), step * height))
    if raw.size < step * height:  # the last row may come without its padding
        raw = np.concatenate([raw, np.zeros(step * height - raw.size, dtype=np.uint8)])
    rows = raw.reshape(height, step)[:, :row]
    pixels = np.ascontiguousarray(rows).view(sample).astype(sample.newbyteorder("="))
    if channels == 1:
        return pixels.reshape(height, width)
    return pixels.reshape(height, width, channels)


def depth_to_millimetres(depth: np.ndarray, encoding: str) -> np.ndarray:
    """A depth image as uint16 millimetres, 0 where there is no depth.

    32FC1 is metres, with non-finite values for no depth (rep-0118.rst:28-32): NaN, +-inf,
    values <= 0 and values beyond 65.535 m (which 16 bits cannot hold) all become 0, the
    "invalid depth" of a 16UC1 image in millimetres (rep-0118.rst:43-48); the rest is
    rounded to the nearest millimetre. 16UC1 is millimetres already and is returned as is.
    """
    if encoding == "16UC1":
        return depth.astype(np.uint16)
    if encoding != "32FC1":
        raise ValueError(f"{encoding!r} is not a depth encoding (32FC1 or 16UC1)")
    metres = depth.astype(np.float64)
    with np.errstate(invalid="ignore"):
        mm = np.rint(metres * 1000.0)
        valid = np.isfinite(mm) & (mm > 0) & (mm <= MAX_MILLIMETRES)
    return np.where(valid, mm, 0).astype(np.uint16)


def rgb_order(pixels: np.ndarray, encoding: str) -> np.ndarray:
    """bgr/bgra pixels reordered to rgb/rgba (what PNG stores); others unchanged."""
    if encoding.startswith("bgra") or encoding.startswith("bgr") or encoding == "8UC3":
        swapped = pixels.copy()
        swapped[..., [0, 2]] = pixels[..., [2, 0]]
        return swapped
    return pixels


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def encode_png(pixels: np.ndarray) -> bytes:
    """PNG bytes of an 8- or 16-bit image: ``(H, W)`` grey, ``(H, W, 3)`` RGB or
    ``(H, W, 4)`` RGBA (16-bit samples are stored big-endian, as PNG wants)."""
    img = pixels[:, :, None] if pixels.ndim == 2 else pixels
    if img.ndim != 3 or img.shape[2] not in (1, 3, 4):
        raise ValueError(f"cannot write a {pixels.shape} array as PNG")
    if img.dtype == np.uint8:
        depth = 8
    elif img.dtype == np.uint16:
        depth = 16
        img = img.astype(">u2")
    else:
        raise ValueError(f"PNG holds 8 or 16 bit samples, not {pixels.dtype}")
    height, width, channels = img.shape
    colour = {1: 0, 3: 2, 4: 6}[channels]
    rows = img.reshape(height, width * channels).view(np.uint8).reshape(height, -1)
    scanlines = np.hstack([np.zeros((height, 1), dtype=np.uint8), rows])  # filter 0 per row
    header = struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + _chunk(b"IHDR", header)
        + _chunk(b"IDAT", zlib.compress(scanlines.tobytes(), 6))
        + _chunk(b"IEND", b"")
    )


def frame_file(msg: Any, depth_format: str = "png") -> tuple[str, bytes]:
    """``(extension, file bytes)`` for one Image-shaped message."""
    if depth_format not in DEPTH_FORMATS:
        raise ValueError(f"format {depth_format!r}: use png or npy")
    pixels = image_to_array(msg)
    encoding = str(msg.encoding)
    if encoding in DEPTH_ENCODINGS:
        if depth_format == "npy":
            out = io.BytesIO()
            np.save(out, pixels, allow_pickle=False)
            return "npy", out.getvalue()
        return "png", encode_png(depth_to_millimetres(pixels, encoding))
    return "png", encode_png(rgb_order(pixels, encoding))


def is_due(last: float | None, now: float, interval: float) -> bool:
    """Whether a frame stamped ``now`` is saved when the last one saved was at ``last``:
    the first frame, one ``interval`` or more later, or one stamped earlier than ``last``
    (the clock went back)."""
    if last is None or now < last:
        return True
    return now - last >= interval


def topic_folder(topic: str) -> str:
    """The folder name of a topic: ``/rgbd/depth/image_raw`` -> ``rgbd__depth__image_raw``."""
    name = "__".join(part for part in topic.strip().split("/") if part)
    if not name or name in (".", ".."):
        raise ValueError(f"topic {topic!r} has no name")
    return name


def frame_name(sec: int, nanosec: int, ext: str) -> str:
    """``0000000012_345000000.png``: sorts in time order."""
    return f"{int(sec):010d}_{int(nanosec):09d}.{ext}"


def write_whole(path: str, data: bytes) -> None:
    """Write ``data`` at ``path`` through a temporary file renamed into place."""
    folder = os.path.dirname(path) or "."
    os.makedirs(folder, exist_ok=True)
    temp = os.path.join(folder, f".{os.path.basename(path)}.{os.getpid()}.tmp")
    try:
        with open(temp, "wb") as f:
            f.write(data)
        os.replace(temp, path)
    except BaseException:
        if os.path.exists(temp):
            os.unlink(temp)
        raise


class FrameSaver:
    """What the node does with each message, without ROS: pick, convert, write."""

    def __init__(
        self,
        topics: list[str],
        *,
        encodings: list[str] | None = None,
        interval: float = 5.0,
        folder: str = "frames",
        depth_format: str = "png",
        warn: Callable[[str], None] | None = None,
    ) -> None:
        if not topics:
            raise ValueError("no topics to save")
        if not (interval >= 0 and math.isfinite(interval)):
            raise ValueError(f"interval {interval!r}: give 0 or more seconds")
        if depth_format not in DEPTH_FORMATS:
            raise ValueError(f"format {depth_format!r}: use png or npy")
        wanted = list(encodings or [])
        if wanted and len(wanted) != len(topics):
            raise ValueError(f"{len(wanted)} encodings for {len(topics)} topics")
        self.topics = list(topics)
        self.expected = dict(zip(self.topics, wanted or [""] * len(self.topics), strict=True))
        self.interval = float(interval)
        self.folder = folder
        self.depth_format = depth_format
        self.warn = warn or (lambda text: print(text, file=sys.stderr))
        self.last: dict[str, float] = {}
        self.warned: set[str] = set()  # topics told about an unexpected encoding
        self.refused: set[str] = set()  # topics told about a frame that cannot be saved

    def offer(self, topic: str, msg: Any) -> str | None:
        """Save ``msg`` if its topic is due; the path written, or None."""
        stamp = msg.header.stamp
        sec, nanosec = int(stamp.sec), int(stamp.nanosec)
        now = sec + nanosec * 1e-9
        if not is_due(self.last.get(topic), now, self.interval):
            return None
        expected = self.expected.get(topic, "")
        if expected and msg.encoding != expected and topic not in self.warned:
            self.warned.add(topic)
            self.warn(f"{topic}: encoding {msg.encoding!r}, expected {expected!r}; saved anyway")
        try:
            ext, data = frame_file(msg, self.depth_format)
        except ValueError as exc:
            if topic not in self.refused:
                self.refused.add(topic)
                self.warn(f"{topic}: not saved: {exc}")
            return None
        path = os.path.join(self.folder, topic_folder(topic), frame_name(sec, nanosec, ext))
        write_whole(path, data)
        self.last[topic] = now
        return path


def main(args: list[str] | None = None) -> None:
    """The ROS 2 node: one best-effort subscription per topic."""
    import rclpy
    from rclpy.node import Node
    from rclpy.parameter import Parameter
    from rclpy.qos import qos_profile_sensor_data
    from sensor_msgs.msg import Image

    rclpy.init(args=args)
    node = Node("save_frames")
    # Declared by type, no default: the value is None unless given (ros2/rclpy@humble
    # b488272b:rclpy/rclpy/node.py:451-459, :497-498).
    topics = node.declare_parameter("topics", Parameter.Type.STRING_ARRAY).value or []
    encodings = node.declare_parameter("encodings", Parameter.Type.STRING_ARRAY).value or []
    interval = node.declare_parameter("interval", 5.0).value
    folder = node.declare_parameter("folder", "frames").value
    depth_format = node.declare_parameter("format", "png").value
    topics = [t for t in topics if t]
    try:
        saver = FrameSaver(
            topics,
            encodings=list(encodings) if encodings else None,
            interval=float(interval),
            folder=str(folder),
            depth_format=str(depth_format),
            warn=lambda text: node.get_logger().warning(text),
        )
    except ValueError as exc:
        node.get_logger().fatal(str(exc))
        node.destroy_node()
        rclpy.shutdown()
        sys.exit(2)
    for topic in saver.topics:
        node.create_subscription(
            Image,
            topic,
            lambda msg, t=topic: saver.offer(t, msg),
            qos_profile_sensor_data,
        )
    node.get_logger().info(
        f"saving {len(saver.topics)} topics every {saver.interval:g} s into "
        f"{os.path.abspath(saver.folder)}"
    )
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        node.destroy_node()
        if rclpy.ok():
            rclpy.shutdown()


if __name__ == "__main__":
    main()
