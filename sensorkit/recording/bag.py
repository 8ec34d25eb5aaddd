"""Read what a recording holds, bounded: its index, its TF and a sample of each topic.

:func:`read_recording` opens a ROS 1 ``.bag``, a rosbag2 folder (sqlite3 or MCAP) or a
bare ``.mcap``/``.db3`` with rosbags (imported here only: the extra
````sensorkit-ros[recording]````). From the index it takes every topic, its message type and
count, without reading a message; then, per topic asked for, the first
:attr:`Limits.stamps` messages, of which only the header (stamp and frame_id) is parsed
from the raw bytes, and the first :attr:`Limits.decoded` decoded whole for their content.
A topic stops early at :attr:`Limits.topic_bytes`. ``/tf_static`` is read up to
:attr:`Limits.tf_messages` messages and ``/tf`` as far. So what is read does not grow with
the bag: a 2 GB bag of images costs what its first hundred images cost.

A file rosbags cannot open is an :class:`~sensorkit.base.errors.InputError` (one line, exit
2); a message that cannot be decoded is a note, and the topic is checked without it.
"""

from __future__ import annotations

import struct
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sensorkit.base.errors import InputError, UsageError
from sensorkit.recording.tf import RecordedTF

__all__ = [
    "INSTALL_HINT",
    "Limits",
    "Progress",
    "Recording",
    "TopicSample",
    "normal_type",
    "read_recording",
]

INSTALL_HINT = "pip install 'sensorkit-ros[recording]' (from a clone: pip install './sensorkit[recording]')"

TF_TOPICS = ("/tf_static", "/tf")
TF_TYPES = frozenset({"tf2_msgs/msg/TFMessage", "tf/msg/tfMessage"})

# Message types whose first field is std_msgs/Header: their stamp and frame_id are read
# from the raw bytes without decoding the message (an image is never decoded for them).
HEADER_FIRST = frozenset(
    {
        "sensor_msgs/msg/Image",
        "sensor_msgs/msg/CompressedImage",
        "sensor_msgs/msg/CameraInfo",
        "sensor_msgs/msg/LaserScan",
        "sensor_msgs/msg/PointCloud2",
        "sensor_msgs/msg/PointCloud",
        "sensor_msgs/msg/Imu",
        "sensor_msgs/msg/Range",
        "sensor_msgs/msg/NavSatFix",
        "sensor_msgs/msg/MagneticField",
        "sensor_msgs/msg/FluidPressure",
    }
)

# One call per step: (steps done, steps in all, what is being read).
Progress = Callable[[int, int, str], None]


@dataclass(frozen=True)
class Limits:
    """How much of a recording is read: per topic and for TF."""

    stamps: int = 100  # header stamps per topic (the rate is measured from them)
    decoded: int = 2  # messages per topic decoded whole (their content is checked)
    topic_bytes: int = 200 * 1024 * 1024  # a topic's sample stops past this many bytes
    tf_messages: int = 2000  # /tf_static and /tf messages read, each


@dataclass
class TopicSample:
    """What was read of one topic."""

    topic: str
    msgtype: str  # normal form, pkg/msg/Name
    count: int  # messages in the recording (the index's count)
    stamps: list[int] = field(default_factory=list)  # header stamps (ns), in recording order
    frame_ids: list[str] = field(default_factory=list)  # header frame_ids, as stamps
    messages: list[Any] = field(default_factory=list)  # the first few, decoded
    read: int = 0  # messages read
    bytes_read: int = 0
    errors: list[str] = field(default_factory=list)


@dataclass
class Recording:
    """The index of a recording, its TF and the samples of the topics asked for."""

    path: Path
    storage: str  # "ROS 1 bag", "rosbag2 (sqlite3)", "rosbag2 (mcap)", ...
    ros1: bool
    start_ns: int
    duration_ns: int
    types: dict[str, str]  # topic -> message type (normal form)
    counts: dict[str, int]  # topic -> messages
    samples: dict[str, TopicSample] = field(default_factory=dict)
    tf: RecordedTF = field(default_factory=RecordedTF)
    notes: list[str] = field(default_factory=list)
    bytes_read: int = 0
    seconds: float = 0.0

    @property
    def has_tf(self) -> bool:
        return any(t in self.types for t in TF_TOPICS)


def normal_type(msgtype: str) -> str:
    """``pkg/msg/Name`` for ``pkg/Name`` (ROS 1) or ``pkg/msg/Name`` (ROS 2)."""
    pkg, _, name = msgtype.strip().rpartition("/")
    if not pkg:
        return name
    if "/" not in pkg:
        pkg += "/msg"
    return f"{pkg}/{name}"


def storage_of(path: Path) -> str:
    """What kind of recording ``path`` is, from its name and its files."""
    if path.suffix == ".bag":
        return "ROS 1 bag"
    if path.is_dir():
        if any(path.glob("*.mcap")):
            return "rosbag2 (mcap)"
        return "rosbag2 (sqlite3)" if any(path.glob("*.db3")) else "rosbag2"
    return {".mcap": "MCAP file", ".db3": "rosbag2 sqlite3 file"}.get(path.suffix, "recording")


def _rosbags() -> Any:
    try:
        from rosbags import highlevel, typesys
    except ImportError:  # the optional extra is not installed
        msg = f"check-recording needs rosbags, which is not installed: {INSTALL_HINT}"
        raise UsageError(msg) from None
    return highlevel, typesys


def _header(raw: bytes | memoryview, ros1: bool) -> tuple[int, str]:
    """``(stamp ns, frame_id)`` of a message whose first field is std_msgs/Header, read
    from its serialized bytes: ROS 1 ``seq, secs, nsecs, len, chars``; CDR (rosbag2) a
    4-byte encapsulation header (byte 1: 1 little-endian, 0 big-endian), then
    ``sec, nanosec, len (with the NUL), chars``."""
    data = bytes(raw[:4096])
    if ros1:
        _seq, sec, nsec, length = struct.unpack_from("<IIII", data, 0)
        text = data[16 : 16 + length]
    else:
        order = "<" if data[1] == 1 else ">"
        sec, nsec, length = struct.unpack_from(order + "iII", data, 4)
        text = data[16 : 16 + max(length - 1, 0)]
    return sec * 1_000_000_000 + nsec, text.decode("utf-8", "replace")


class _Reader:
    """An open rosbags AnyReader and its connections by topic."""

    def __init__(self, path: Path) -> None:
        highlevel, typesys = _rosbags()
        try:
            try:
                self.reader = highlevel.AnyReader([path])
                self.reader.open()
            except highlevel.AnyReaderError as exc:
                if "no type definitions" not in str(exc):
                    raise
                # An older rosbag2 holds no message definitions: read it with the newest
                # distribution's types (made only then: building them costs 0.2 s).
                store = typesys.get_typestore(typesys.Stores.LATEST)
                self.reader = highlevel.AnyReader([path], default_typestore=store)
                self.reader.open()
        except (OSError, UsageError):
            raise
        except Exception as exc:  # rosbags' errors, and what a broken file raises in it
            msg = f"{path}: rosbags cannot read it as a recording: {exc}"
            raise InputError(msg) from None
        self.by_topic: dict[str, list[Any]] = {}
        for conn in self.reader.connections:
            self.by_topic.setdefault(conn.topic, []).append(conn)

    def close(self) -> None:
        try:
            self.reader.close()
        except Exception:  # closing a broken file says nothing more
            return

    def raw(self, topic: str) -> Iterable[tuple[Any, int, bytes]]:
        conns = self.by_topic.get(topic, [])
        return self.reader.messages(connections=conns) if conns else ()

    def decode(self, raw: bytes, msgtype: str) -> Any:
        return self.reader.deserialize(raw, msgtype)


def _sample(rd: _Reader, sample: TopicSample, raw_type: str, ros1: bool, limits: Limits) -> None:
    """Read the first messages of one topic into ``sample``, within ``limits``."""
    header_first = sample.msgtype in HEADER_FIRST
    try:
        for _conn, _t, raw in rd.raw(sample.topic):
            sample.read += 1
            sample.bytes_read += len(raw)
            if header_first:
                try:
                    stamp, frame = _header(raw, ros1)
                except (struct.error, IndexError) as exc:
                    sample.errors.append(f"a header that cannot be read ({exc})")
                else:
                    sample.stamps.append(stamp)
                    sample.frame_ids.append(frame)
            if len(sample.messages) < limits.decoded:
                try:
                    sample.messages.append(rd.decode(raw, raw_type))
                except Exception as exc:  # a message rosbags cannot decode
                    sample.errors.append(f"a message that cannot be decoded ({exc})")
            if sample.read >= limits.stamps or sample.bytes_read >= limits.topic_bytes:
                break
    except Exception as exc:  # a chunk or page that cannot be read
        sample.errors.append(f"reading stopped: {exc}")


def _read_tf(rd: _Reader, rec: Recording, limits: Limits) -> None:
    for topic in TF_TOPICS:
        conns = rd.by_topic.get(topic, [])
        if not conns or normal_type(conns[0].msgtype) not in TF_TYPES:
            continue
        static = topic == "/tf_static"
        read = 0
        try:
            for conn, _t, raw in rd.raw(topic):
                read += 1
                rec.bytes_read += len(raw)
                try:
                    msg = rd.decode(raw, conn.msgtype)
                except Exception as exc:
                    rec.notes.append(f"{topic}: a message that cannot be decoded ({exc})")
                    continue
                for ts in msg.transforms:
                    rec.tf.add(
                        ts.header.frame_id,
                        ts.child_frame_id,
                        ts.transform.translation,
                        ts.transform.rotation,
                        static=static,
                    )
                if read >= limits.tf_messages:
                    if not static:
                        break
                    rec.notes.append(f"{topic}: read its first {read} messages only")
                    break
        except Exception as exc:
            rec.notes.append(f"{topic}: reading stopped: {exc}")


def read_recording(
    path: Path,
    topics: Iterable[str],
    *,
    limits: Limits | None = None,
    progress: Progress | None = None,
) -> Recording:
    """The index of the recording at ``path``, its TF, and a sample of each of ``topics``
    that it holds (see the module's docstring for what is read).

    Raises:
        UsageError: rosbags is not installed.
        InputError: ``path`` is not a recording rosbags can read.
    """
    lim = limits or Limits()
    if not path.exists():
        msg = f"{path}: no such file or folder"
        raise InputError(msg)
    started = time.monotonic()
    rd = _Reader(path)
    try:
        types: dict[str, str] = {}
        raw_types: dict[str, str] = {}
        counts: dict[str, int] = {}
        for topic, conns in rd.by_topic.items():
            raw_types[topic] = conns[0].msgtype
            types[topic] = normal_type(conns[0].msgtype)
            counts[topic] = sum(c.msgcount for c in conns)
        ros1 = not rd.reader.is2
        rec = Recording(
            path,
            storage_of(path),
            ros1,
            int(rd.reader.start_time) if counts and sum(counts.values()) else 0,
            int(rd.reader.duration) if counts and sum(counts.values()) else 0,
            types,
            counts,
        )
        wanted = [t for t in dict.fromkeys(topics) if t in types]
        steps = len(wanted) + 1
        if progress is not None:
            progress(0, steps, "TF")
        _read_tf(rd, rec, lim)
        for i, topic in enumerate(wanted, 1):
            if progress is not None:
                progress(i, steps, topic)
            sample = TopicSample(topic, types[topic], counts[topic])
            _sample(rd, sample, raw_types[topic], ros1, lim)
            rec.bytes_read += sample.bytes_read
            rec.samples[topic] = sample
        if progress is not None:
            progress(steps, steps, "done")
    finally:
        rd.close()
    rec.seconds = time.monotonic() - started
    return rec
