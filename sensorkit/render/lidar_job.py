"""One lidar of a preview: cast it, write its files, check it, draw it in the overview.

``render_lidar_job`` casts every beam as Gazebo does (``sensorkit.render.lidar``),
writes ranges.npy (and points.npy for a 3D lidar), scan.png from above and, for a 3D
or tilted lidar, side.png, both labelled; notes the scan and topics summary.json shows,
checks the ranges against the scene's exact geometry and the robot's frames, and gives
the lidar's drawing for overview.png: its returns, in the world.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sensorkit.render.checks import self_occlusion_check
from sensorkit.render.result import SensorPreview
from sensorkit.render.session import open_folder, say, shown, skipped, topics_of

if TYPE_CHECKING:
    from pathlib import Path

    from sensorkit.model.transforms_np import Mat
    from sensorkit.render.lidar import LidarScan
    from sensorkit.render.overview import ScanView
    from sensorkit.render.plan import Job
    from sensorkit.render.session import JobResult, Progress, Session

__all__ = ["render_lidar_job"]


def render_lidar_job(run: Session, job: Job, progress: Progress | None) -> JobResult:
    """Cast ``job``'s lidar, write its files, check it, and draw it in the overview."""
    from sensorkit.describe.intrinsics import InvalidValue
    from sensorkit.exporters import laser_scan_dict
    from sensorkit.render.lidar import cast, lidar_beams, range_check

    sensor = job.sensor
    out = SensorPreview.of(sensor)
    T_render = run.T_world_render(sensor)
    if T_render is None:
        return skipped(out, f"its reference link {sensor.reference!r} is not a link of the robot")
    if sensor.lidar is None:
        return skipped(out, "no <lidar> or <ray> block")
    try:
        beams = lidar_beams(sensor.lidar, out.notes)
    except InvalidValue as exc:
        return skipped(out, f"its scan cannot be cast: {exc}")
    V, H = beams.shape
    say(
        progress,
        f"casting {sensor.name} ({V} x {H} beams)"
        if V > 1
        else f"casting {sensor.name} ({H} beams)",
    )
    scan = cast(run.world, T_render, beams)
    world_pts = _write_scan(run, out, open_folder(out, job.folder), scan, T_render)

    frames = run.frames(sensor)
    out.info["frames"] = run.frame_info(frames, T_render)
    out.info["scan"] = laser_scan_dict(beams.horizontal)
    if beams.vertical is not None:
        out.info["vertical"] = laser_scan_dict(beams.vertical)
    out.info["shape"] = [V, H]
    out.info["topics"] = topics_of(sensor, run.target)
    out.checks.append(range_check(scan, run.world.shape_of))
    out.checks.append(
        self_occlusion_check(scan.hits.body, scan.hits.link, run.world.robot_links, "beams")
    )
    _, stamped = run.placement_checks(
        out, sensor, T_render, frames.published, frames.how, optical=False
    )
    return _drawn(job, out, scan, T_render, world_pts, stamped)


def _write_scan(
    run: Session, out: SensorPreview, folder: Path, scan: LidarScan, T_render: Mat
) -> np.ndarray:
    """ranges.npy, points.npy (3D lidars) and scan.png with its labels (and side.png);
    gives every beam's point in the world (NaN for no return)."""
    from sensorkit.render._files import save_npy
    from sensorkit.render.overview import draw_scan, scan_view
    from sensorkit.render.png import write_png

    beams = scan.beams
    V, H = beams.shape
    out.files["ranges"] = folder / "ranges.npy"
    save_npy(out.files["ranges"], scan.ranges if beams.vertical is not None else scan.ranges[0])
    if beams.vertical is not None:
        out.files["points"] = folder / "points.npy"
        save_npy(out.files["points"], scan.points)
    rows = np.repeat(np.arange(V), H)
    self_hit = np.isin(scan.hits.body, run.world.robot_bodies)
    out.files["scan_png"] = folder / "scan.png"
    sectors = _self_occluded(scan, self_hit)
    # the points in the sensor's frame and in the world, and the view of scan.png: once,
    # for every picture
    pts = scan.points.reshape(-1, 3).astype(np.float64)
    world_pts: np.ndarray = pts @ T_render[:3, :3].T + T_render[:3, 3]
    view = scan_view(pts, beams.range_max)
    png = write_png(
        out.files["scan_png"],
        draw_scan(pts, rows, self_hit, beams.range_max, sectors=sectors, view=view),
    )
    _lidar_figures(run, out, scan, png, view, world_pts, rows, self_hit, sectors)
    return world_pts


def _self_occluded(scan: LidarScan, self_hit: np.ndarray) -> list[tuple[float, float]]:
    """Azimuth sectors of the scan in which some beam meets the robot itself."""
    from sensorkit.render.pictures import occluded_sectors

    beams = scan.beams
    V, H = beams.shape
    azimuth = beams.azimuth
    full = H > 1 and float(azimuth[-1] - azimuth[0]) >= 2 * math.pi - 1.5 * float(
        azimuth[1] - azimuth[0]
    )
    blocked: npt.NDArray[np.bool_] = np.asarray(self_hit.reshape(V, H).any(axis=0), dtype=bool)
    return occluded_sectors(azimuth, blocked, full_circle=full)


def _lidar_figures(
    run: Session,
    out: SensorPreview,
    scan: LidarScan,
    scan_png: bytes,
    view: ScanView,
    world_pts: np.ndarray,
    rows: np.ndarray,
    self_hit: np.ndarray,
    sectors: list[tuple[float, float]],
) -> None:
    """scan.png labelled (``view``: where draw_scan put things); for a 3D lidar or a
    tilted 2D one, side.png (of ``world_pts``, every beam's point in the world) and its
    labels."""
    from sensorkit.render.pictures import draw_side, scan_figure, side_figure
    from sensorkit.render.png import write_png
    from sensorkit.render.scene import GROUND

    beams = scan.beams
    V = beams.shape[0]
    returns = scan.points.reshape(-1, 3)[:, :2].astype(np.float64)
    out.add_figure(scan_figure(scan_png, view, sectors, V, int(self_hit.sum()), returns=returns))
    tilt = math.degrees(math.acos(max(-1.0, min(1.0, float(scan.rotation[2, 2])))))
    if (V <= 1 and tilt <= 1.0) or out.directory is None:
        return
    ground = np.zeros(len(world_pts), dtype=bool)
    for (body, link), shapes in run.world.shape_of.items():
        if any(x.kind == GROUND for x in shapes):
            ground |= (scan.hits.body == body) & (scan.hits.link == link)
    image, side, facts = draw_side(
        world_pts, scan.origin, scan.rotation[:, 0], rows, V, ground, self_hit
    )
    facts["tilt_deg"] = tilt
    out.files["side_png"] = out.directory / "side.png"
    png = write_png(out.files["side_png"], image)
    out.add_figure(side_figure(png, side, facts))


def _drawn(
    job: Job,
    out: SensorPreview,
    scan: LidarScan,
    T_render: Mat,
    world_pts: np.ndarray,
    stamped: tuple[str, Mat] | None,
) -> JobResult:
    """``out`` with the lidar in the overview: its returns and its forward axis (as far
    as the median return, 1 m at most); with ``stamped``, where RViz will put them."""
    from sensorkit.render._stats import median
    from sensorkit.render.overview import SensorDrawing
    from sensorkit.render.raster import take_rows

    finite = np.isfinite(scan.ranges.reshape(-1))
    fwd = median(scan.ranges[np.isfinite(scan.ranges)]) if finite.any() else scan.beams.range_max
    origin = T_render[:3, 3].copy()
    drawing = SensorDrawing(
        job.sensor.name,
        job.colour,
        origin,
        origin + T_render[:3, 0] * min(fwd, 1.0),
        [],
        take_rows(world_pts, finite),
    )
    seen = None
    if stamped is not None:
        from sensorkit.render.rviz import Misplaced, lidar_points

        frame, T_frame = stamped
        seen = Misplaced(frame, T_render, T_frame, lidar_points(scan.points), 0, min(fwd, 1.0))
    return shown(out, drawing, seen)
