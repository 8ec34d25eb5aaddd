"""``check-recording``: every check of a recording against a described robot.

:func:`check_recording` reads the recording (bounded, :mod:`sensorkit.recording.bag`),
says which predicted topics are missing or of another type (SK801, SK802), checks the
content of what was sampled (SK806-SK810, :mod:`sensorkit.recording.data`) and the frames
(SK803-SK805, :mod:`sensorkit.recording.frames`). Findings are data: nothing here prints.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.model.frames import ros_generation
from sensorkit.recording.bag import Limits, Progress, Recording, read_recording
from sensorkit.recording.data import (
    check_camera_info,
    check_cloud,
    check_image,
    check_rate,
    check_scan,
    finding,
)
from sensorkit.recording.expect import SENSOR_TYPES, Expected, expectations
from sensorkit.recording.frames import check_frame_ids, check_joints

if TYPE_CHECKING:
    from pathlib import Path

    from sensorkit.describe.sensorinfo import RobotInfo
    from sensorkit.describe.topics import RobotTopics
    from sensorkit.recording.bag import TopicSample

__all__ = ["RecordingReport", "check_recording"]


@dataclass
class RecordingReport:
    """What a check of one recording found, and what it read."""

    recording: Recording
    findings: list[Finding]
    expected: int  # topics the description predicts
    notes: list[str] = field(default_factory=list)


def _presence(rec: Recording, exps: dict[str, Expected]) -> list[Finding]:
    """SK801 and SK802: predicted topics missing, empty or of another type; sensor topics
    recorded that nothing predicts (info)."""
    out: list[Finding] = []
    for name, exp in exps.items():
        want = exp.type or "?"
        fix = f"record {name} too, and check that the sensor publishes it (sensorkit topics)"
        if name not in rec.types:
            out.append(
                finding(
                    "SK801",
                    Severity.ERROR,
                    f"{name} ({want}) is not in the recording: sensor {exp.sensor.name!r} "
                    "publishes it",
                    exp,
                    fix=fix,
                )
            )
        elif rec.counts.get(name, 0) == 0:
            out.append(
                finding(
                    "SK801",
                    Severity.ERROR,
                    f"{name} is in the recording with no message",
                    exp,
                    fix=fix,
                )
            )
        elif exp.type is not None and rec.types[name] != exp.type:
            out.append(
                finding(
                    "SK802",
                    Severity.ERROR,
                    f"{name} is recorded as {rec.types[name]}, where sensor "
                    f"{exp.sensor.name!r} publishes {exp.type}",
                    exp,
                )
            )
    predicted = list(exps)
    for name, mtype in sorted(rec.types.items()):
        if mtype not in SENSOR_TYPES or name in exps:
            continue
        if any(name.startswith(p.rstrip("/") + "/") for p in predicted):
            continue  # image_transport's compressed, theora, ... beside a predicted topic
        out.append(
            Finding(
                "SK801",
                Severity.INFO,
                f"{name} ({mtype}, {rec.counts.get(name, 0)} messages) is recorded, but no "
                "sensor of the description publishes it",
                SourceRef(str(rec.path)),
            )
        )
    return out


def _content(sample: TopicSample, exp: Expected) -> list[Finding]:
    """SK806-SK810 for one sampled topic whose type is the predicted one."""
    mtype = exp.type
    out: list[Finding] = []
    intr = exp.camera.intrinsics if exp.camera is not None else None
    if mtype == "sensor_msgs/msg/CameraInfo" and intr is not None:
        out += check_camera_info(sample, exp, intr)
    elif mtype == "sensor_msgs/msg/Image":
        size = (intr.width, intr.height) if intr is not None else None
        out += check_image(sample, exp, size)
    elif mtype == "sensor_msgs/msg/LaserScan":
        out += check_scan(sample, exp)
    elif mtype == "sensor_msgs/msg/PointCloud2":
        out += check_cloud(sample, exp, ros_generation(exp.info.target))
    out += check_rate(sample, exp)
    return out


def check_recording(
    infos: list[RobotInfo],
    topics: list[RobotTopics],
    path: Path,
    *,
    limits: Limits | None = None,
    progress: Progress | None = None,
) -> RecordingReport:
    """Check the recording at ``path`` against the robots ``infos`` described (one, or each
    model of a world) and the topics ``topics`` lists for them (``robot_topics``).

    Raises:
        UsageError: rosbags is not installed.
        InputError: ``path`` is not a recording rosbags can read.
    """
    exps: dict[str, Expected] = {}
    for info, listed in zip(infos, topics, strict=True):
        for name, exp in expectations(info, listed).items():
            exps.setdefault(name, exp)
    rec = read_recording(path, exps, limits=limits, progress=progress)
    findings = _presence(rec, exps)
    notes = list(rec.notes)
    for name, exp in exps.items():
        sample = rec.samples.get(name)
        if sample is None:
            continue
        notes += [f"{name}: {e}" for e in dict.fromkeys(sample.errors)]
        if exp.type is None or rec.types.get(name) == exp.type:
            try:
                findings += _content(sample, exp)
            except (AttributeError, TypeError, ValueError, IndexError) as exc:
                notes.append(f"{name}: its messages could not be checked ({exc!r})")
    findings += check_frame_ids(rec, exps)
    findings += check_joints(rec, exps)
    findings.sort(key=lambda f: (f.sensor is None, f.sensor or "", f.rule, f.message))
    return RecordingReport(rec, findings, len(exps), notes)
