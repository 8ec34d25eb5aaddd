"""What a preview renders, decided before anything runs: one job per camera and lidar.

``plan_jobs`` walks the robot's sensors in document order and gives each camera (each
camera of a multicamera) and each lidar a :class:`Job` with its folder and its colour in
the overview fixed up front, so that jobs run in any order, or in other processes, write
the same files. A sensor that is not rendered gets its record at once, saying why.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from sensorkit.render.result import SensorPreview

if TYPE_CHECKING:
    from pathlib import Path

    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import CameraSpec, Sensor

__all__ = ["Job", "plan_jobs", "wanted"]


@dataclass
class Job:
    """One sensor (or one camera of a multicamera) to render, planned before any runs."""

    sensor: Sensor
    name: str
    folder: Path
    colour: tuple[int, int, int]
    cam: CameraSpec | None = None


def _folder_name(name: str, taken: set[str]) -> str:
    base = re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._") or "sensor"
    out, k = base, 2
    while out.lower() in taken or out.lower() in ("summary.json", "overview.png", "index.html"):
        out, k = f"{base}_{k}", k + 1
    taken.add(out.lower())
    return out


def wanted(sensor: Sensor, only: Sequence[str]) -> bool:
    """Is ``sensor`` previewed (``only``: the sensors asked for; all when empty)?"""
    return not only or sensor.name in only


@dataclass(frozen=True)
class Totals:
    """One budget for the whole preview (issue 36): pixels of every camera, rays of every
    lidar scan, and wall-clock seconds of rendering. Past it, what fits is rendered and
    the rest is left out, named (``left_out``)."""

    pixels: int = 64 * 1024 * 1024
    rays: int = 4_000_000
    seconds: float = 120.0


LEFT_OUT = "left out: the preview's total budget"


def left_out(sensor: Sensor, what: str) -> SensorPreview:
    """The record of a sensor the total budget left out, saying which part of it and how
    to raise it."""
    out = SensorPreview.of(sensor)
    out.skipped = f"{LEFT_OUT} of {what} is spent"
    return out


def _beams(samples: int | None, resolution: float | None) -> float:
    """Rays one scan line casts: samples x resolution (SDF multiplies them), at least 1."""
    n = float(max(samples or 1, 1))
    if resolution is not None and resolution > 0:
        n *= resolution  # 90 samples at resolution 1e5 are 9 million rays (inf past 1e308)
    return max(n, 1.0)


def lidar_rays(sensor: Sensor) -> float:
    """Rays one scan of ``sensor``'s lidar casts (samples x resolution, both ways)."""
    lidar = sensor.lidar
    if lidar is None:
        return 0.0
    return _beams(lidar.samples, lidar.resolution) * _beams(lidar.v_samples, lidar.v_resolution)


def _over_totals(sensor: Sensor, totals: Totals, spent: list[float]) -> str | None:
    """What ``sensor`` would take past ``totals`` (given ``spent`` pixels and rays so
    far), or None, counting it in when it fits."""
    from sensorkit.describe.published import camera_size

    if sensor.is_camera and sensor.cameras:
        cams = sensor.cameras if sensor.kind == "multicamera" else sensor.cameras[:1]
        pixels = sum(w * h for w, h, _ in (camera_size(c, []) for c in cams))
        if spent[0] + pixels > totals.pixels:
            return f"{totals.pixels:,} pixels (--max-total-pixels)"
        spent[0] += pixels
    elif sensor.kind == "lidar" and sensor.lidar is not None:
        rays = lidar_rays(sensor)
        if spent[1] + rays > totals.rays:
            return f"{totals.rays:,} rays (--max-total-rays)"
        spent[1] += rays
    return None


def plan_jobs(
    robot: Robot, only: Sequence[str], out_dir: Path, totals: Totals | None = None
) -> list[Job | SensorPreview]:
    """What to render, in document order, with folders and colours fixed up front; a
    sensor past ``totals`` (pixels, rays) is left out (:func:`left_out`)."""
    from sensorkit.render.overview import PALETTE

    plan: list[Job | SensorPreview] = []
    taken: set[str] = set()
    drawn = 0
    spent = [0.0, 0.0]
    for sensor in robot.sensors:
        if not wanted(sensor, only):
            continue
        over = _over_totals(sensor, totals, spent) if totals is not None else None
        if over is not None:
            plan.append(left_out(sensor, over))
            continue
        if sensor.is_camera and sensor.cameras:
            folder = out_dir / _folder_name(sensor.name, taken)
            multi = sensor.kind == "multicamera"
            cams = sensor.cameras if multi else sensor.cameras[:1]
            inner: set[str] = set()
            for i, cam in enumerate(cams):
                label = f"{sensor.name}/{cam.name or i}" if multi else sensor.name
                where = folder / _folder_name(cam.name or f"camera{i}", inner) if multi else folder
                plan.append(Job(sensor, label, where, PALETTE[drawn % len(PALETTE)], cam))
                drawn += 1
        elif sensor.kind == "lidar":
            folder = out_dir / _folder_name(sensor.name, taken)
            plan.append(Job(sensor, sensor.name, folder, PALETTE[drawn % len(PALETTE)]))
            drawn += 1
        else:
            plan.append(_not_rendered(sensor))
    return plan


def _not_rendered(sensor: Sensor) -> SensorPreview:
    """The record of a sensor that is neither a camera nor a lidar, saying so."""
    out = SensorPreview.of(sensor)
    out.skipped = (
        "it has no <camera> block"
        if sensor.is_camera
        else f"only cameras and lidars are, and its type is {sensor.type or 'missing'!r}"
    )
    return out
