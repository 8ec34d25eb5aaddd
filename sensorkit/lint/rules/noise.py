"""SK408: sensor noise blocks (moved out of sensors.py; the rule id and order are unchanged)."""

from __future__ import annotations

from collections.abc import Iterator

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.sdf_values import noise_type_effect
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.sensors import Noise, Sensor


def _noises(s: Sensor) -> list[Noise]:
    out = [n for n in (c.noise for c in s.cameras) if n is not None]
    if s.lidar is not None and s.lidar.noise is not None:
        out.append(s.lidar.noise)
    out.extend(s.imu_noise)
    return out


@rule(
    "SK408",
    "error/warning",
    "noise type known (an error where the sensor does not run: Gazebo Classic crashes on any type "
    "but gaussian, gaussian_quantized, none, custom; Gazebo Sim refuses a camera's, and from "
    "Harmonic an IMU's; a warning for a Gazebo Sim lidar, and a Fortress IMU, which run without "
    "noise); stddev >= 0",
    formats=("urdf", "sdf"),
)
def noise(ctx: Context) -> Iterator[Finding]:
    for s in ctx.robot.sensors:
        for n in _noises(s):
            for p in n.problems:
                yield ctx.finding(
                    "SK408",
                    Severity.ERROR,
                    f"sensor {s.name!r}: {p}",
                    n.source,
                    sensor=s.name,
                    fix="write numbers",
                )
            effect = None if n.type is None else noise_type_effect(ctx.target, s.kind, n.type)
            if effect is not None:
                fatal, what = effect
                yield ctx.finding(
                    "SK408",
                    Severity.ERROR if fatal else Severity.WARNING,
                    f"sensor {s.name!r}: noise type {n.type!r} is unknown: {what}",
                    n.source,
                    sensor=s.name,
                    fix="use gaussian, gaussian_quantized or none",
                )
            if n.stddev is not None and n.stddev < 0:
                yield ctx.finding(
                    "SK408",
                    Severity.ERROR,
                    f"sensor {s.name!r}: noise stddev {n.stddev:g} is negative",
                    n.source,
                    sensor=s.name,
                    fix="stddev is a standard deviation: >= 0",
                )
