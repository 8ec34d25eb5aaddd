"""Hover on a ``<sensor>``: what ``sensorkit topics`` and ``sensorkit intrinsics`` say of it.

The sensor is found by the line of its ``<sensor>`` tag or of the ``<gazebo reference>``
block holding it, in the validated robot (a sensor written once in a macro and used twice
shows both). The facts come from :mod:`sensorkit.describe` through the functions the two
commands use: :func:`~sensorkit.describe.sensorinfo.describe`,
:func:`~sensorkit.describe.topics.load_bridge` and
:func:`~sensorkit.describe.topics.robot_topics`.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from sensorkit.lsp.analysis import Analysis

if TYPE_CHECKING:
    from sensorkit.describe.sensorinfo import RobotInfo
    from sensorkit.describe.topics import RobotTopics, Topic
    from sensorkit.describe.views import SensorInfo
    from sensorkit.model.sensors import Sensor

__all__ = ["hover_text", "sensors_at"]


def sensors_at(analysis: Analysis, path: str, line: int) -> list[Sensor]:
    """The sensors whose ``<sensor>`` tag, or ``<gazebo>`` block, is written at ``line``
    (1-based) of ``path`` (absolute)."""
    robot = analysis.robot
    if robot is None:
        return []
    out: list[Sensor] = []
    for s in robot.sensors:
        for ref in (s.source, robot.document.locate(s.block)):
            if ref.file and ref.line == line and os.path.abspath(ref.file) == path:
                out.append(s)
                break
    return out


def _described(analysis: Analysis) -> tuple[RobotInfo, RobotTopics]:
    """The robot described under its target and its topics, worked out once."""
    memo = analysis.memo.get("topics")
    if memo is None:
        from sensorkit.describe.sensorinfo import describe
        from sensorkit.describe.topics import load_bridge, robot_topics
        from sensorkit.model.targets import is_gz

        assert analysis.robot is not None and analysis.target is not None
        info = describe(analysis.robot, analysis.target)
        if analysis.report is not None:  # where the target came from, as validate says it
            info.target_reason = analysis.report.target_reason
        opts = analysis.options
        bridge = None
        if is_gz(info.target):
            bridge = load_bridge(info.robot, info.target, (), opts.launch, opts.package_paths)
        memo = (info, robot_topics(info, bridge))
        analysis.memo["topics"] = memo
    return memo  # type: ignore[return-value]


def hover_text(analysis: Analysis, sensors: list[Sensor]) -> str:
    """Markdown for ``sensors`` of the robot of ``analysis``."""
    info, topics = _described(analysis)
    parts: list[str] = []
    for sensor in sensors:
        si = next((s for s in info.sensors if s.sensor is sensor), None)
        if si is None:
            continue
        mine = [t for t in topics.topics if t.sensor == sensor.name]
        parts.append(_sensor_text(si, mine))
    if parts:
        parts.append(f"_target {info.target} ({info.target_reason})_")
    return "\n\n".join(parts)


def _code(text: str | None) -> str:
    return f"`{text}`" if text else "-"


def _sensor_text(si: SensorInfo, topics: list[Topic]) -> str:
    s = si.sensor
    lines = [f"**sensor `{s.name}`** ({s.type}, {s.kind}) on link {_code(si.link)}"]
    lines.append(f"- frame_id: {_code(si.frame)} ({si.frame_how})")
    if s.update_rate:
        lines.append(f"- rate: {s.update_rate:g} Hz")
    if topics:
        gz = any(t.gz_name for t in topics)
        head = "| topic | type | frame_id | encoding |" + (" gz topic |" if gz else "")
        lines += ["", head, "|---|---|---|---|" + ("---|" if gz else "")]
        for t in topics:
            name = t.name or "(not bridged)"
            if t.direction != "publishes":
                name += f" ({t.direction})"
            row = f"| {_code(name)} | {_code(t.type)} | {_code(t.frame)} | {_code(t.encoding)} |"
            lines.append(row + (f" {_code(t.gz_name)} |" if gz else ""))
    else:
        lines.append(
            "- topics: none" + (f" ({'; '.join(si.topic_notes)})" if si.topic_notes else "")
        )
    for view in si.cameras:
        lines.append("")
        lines.append(_camera_text(view.id, view.intrinsics, view.error))
    if si.scan is not None:
        sc = si.scan
        lines += [
            "",
            f"LaserScan: {sc.samples} ranges, angle {sc.angle_min:.4f} .. {sc.angle_max:.4f} rad "
            f"(step {sc.angle_increment:.6f}), range {sc.range_min:g} .. {sc.range_max:g} m",
        ]
    elif si.scan_error:
        lines += ["", f"LaserScan: {si.scan_error}"]
    return "\n".join(lines)


def _camera_text(name: str, intr: object, error: str | None) -> str:
    from sensorkit.describe.intrinsics import Intrinsics

    if not isinstance(intr, Intrinsics):
        return f"camera `{name}`: {error or 'no intrinsics'}"
    d = ", ".join(f"{v:g}" for v in intr.distortion)
    return (
        f"camera `{name}`: {intr.width}x{intr.height}, fx {intr.fx:.3f}, fy {intr.fy:.3f}, "
        f"cx {intr.cx:.3f}, cy {intr.cy:.3f} ({intr.convention}); distortion [{d}]"
    )
