"""Lidars as Gazebo casts them: beam directions, ranges, points, and their check.

Beam ``(v, h)`` leaves the render pose (x forward, y left, z up) in the direction
``(cos e cos a, cos e sin a, sin e)`` with azimuth ``a`` (counter-clockwise from x) and
elevation ``e`` (up positive). Horizontal beams follow LaserScan: ``N = floor(samples *
resolution)``, from ``min_angle`` to ``max_angle`` in ``(max - min) / (N - 1)`` steps; the
vertical fan follows the same rule. Each ray starts ``range_min`` from the sensor (as
Gazebo's do, so nothing nearer is seen) and ends at ``range_max``; a beam with no hit
has range ``+inf``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sensorkit.intrinsics import LaserScanParams
from sensorkit.model.transforms_np import Mat
from sensorkit.render.checks import Check

if TYPE_CHECKING:
    from sensorkit.model.sensors import LidarSpec
    from sensorkit.render.scene import Shape
    from sensorkit.render.sim import RayHits, World

__all__ = ["LidarBeams", "LidarScan", "cast", "lidar_beams", "range_check"]

RANGE_LIMIT_M = 0.01
GRAZING_COS = 0.26  # incidence beyond 75 degrees from the surface normal
FloatArray = npt.NDArray[np.float64]


@dataclass
class LidarBeams:
    horizontal: LaserScanParams
    vertical: LaserScanParams | None
    azimuth: FloatArray  # (H,)
    elevation: FloatArray  # (V,)
    range_min: float
    range_max: float

    @property
    def shape(self) -> tuple[int, int]:
        return (len(self.elevation), len(self.azimuth))

    def directions(self) -> FloatArray:
        """Unit beam directions in the render frame, ``(V, H, 3)``."""
        a = self.azimuth[None, :]
        e = self.elevation[:, None]
        return np.stack(
            np.broadcast_arrays(np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)), axis=-1
        )


@dataclass
class LidarScan:
    beams: LidarBeams
    ranges: npt.NDArray[np.float32]  # (V, H); +inf for no return
    points: npt.NDArray[np.float32]  # (V, H, 3) in the render frame; NaN for no return
    hits: RayHits
    origin: FloatArray  # sensor origin in the world
    dirs_world: FloatArray  # (V*H, 3)


def lidar_beams(spec: LidarSpec, notes: list[str] | None = None) -> LidarBeams:
    """The beams of ``spec`` (``sensorkit.sensorinfo.lidar_scans``, so the preview casts
    exactly the scan the exports describe); raises InvalidValue when it cannot exist."""
    from sensorkit.sensorinfo import lidar_scans

    h, v = lidar_scans(spec, notes)
    elevation = v.beam_angles() if v is not None else np.zeros(1)
    return LidarBeams(h, v, h.beam_angles(), elevation, h.range_min, h.range_max)


def cast(world: World, T_world_render: Mat, beams: LidarBeams) -> LidarScan:
    """Cast every beam in as few ``rayTestBatch`` calls as pybullet allows."""
    dirs_local = beams.directions().reshape(-1, 3)
    R, origin = T_world_render[:3, :3], T_world_render[:3, 3]
    dirs = dirs_local @ R.T
    starts = origin + dirs * beams.range_min
    ends = origin + dirs * beams.range_max
    hits = world.cast(starts, ends)
    span = beams.range_max - beams.range_min
    ranges = np.where(hits.body >= 0, beams.range_min + hits.fraction * span, np.inf)
    V, H = beams.shape
    ranges32 = ranges.reshape(V, H).astype(np.float32)
    points = (dirs_local * np.where(np.isfinite(ranges), ranges, np.nan)[:, None]).reshape(V, H, 3)
    return LidarScan(beams, ranges32, points.astype(np.float32), hits, origin.copy(), dirs)


def _interior(labels: npt.NDArray[np.int64]) -> npt.NDArray[np.bool_]:
    """Beams whose neighbours in the scan grid (left, right, above, below) share the label."""
    same = np.ones(labels.shape, dtype=bool)
    same[:, 1:] &= labels[:, 1:] == labels[:, :-1]
    same[:, :-1] &= labels[:, :-1] == labels[:, 1:]
    if labels.shape[0] > 1:
        same[1:, :] &= labels[1:, :] == labels[:-1, :]
        same[:-1, :] &= labels[:-1, :] == labels[1:, :]
    return same


def range_check(scan: LidarScan, shapes_of: dict[tuple[int, int], list[Shape]]) -> Check:
    """Cast ranges against the exact first hit among all known shapes.

    Every beam is intersected with every known primitive; where the first analytic hit
    and pybullet's hit are the same shape, the ranges are compared. Beams at the edge
    of a shape (a neighbour in the scan grid sees something else), and beams meeting the
    surface more than 75 degrees from its normal, are left out: there a ray's range
    depends on a hair's breadth of angle or of surface tolerance. A beam that pybullet
    says hit nothing while a known shape lies within range counts as missed.
    """
    hits = scan.hits
    V, H = scan.beams.shape
    rmin, rmax = scan.beams.range_min, scan.beams.range_max
    starts = scan.origin + scan.dirs_world * rmin
    ranges = scan.ranges.reshape(-1).astype(np.float64)
    known: list[Shape] = []
    owner: dict[tuple[int, int], set[int]] = {}
    for key, shapes in shapes_of.items():
        for shape in shapes:
            if shape.collision and shape.kind != "mesh":
                owner.setdefault(key, set()).add(len(known))
                known.append(shape)
    if not known:
        return Check("ranges", "skipped", "the scene has no known shapes")
    best_t = np.full(len(ranges), np.inf)
    best_i = np.full(len(ranges), -1, dtype=np.int64)
    best_n = np.zeros((len(ranges), 3))
    for i, shape in enumerate(known):
        t, normal = shape.hit(starts, scan.dirs_world)
        closer = np.isfinite(t) & (t < best_t)
        best_t[closer] = t[closer]
        best_i[closer] = i
        best_n[closer] = normal[closer]
    # a surface tolerance e moves a ray's range by e / cos(incidence): skip grazing beams
    grazing = np.abs(np.einsum("ij,ij->i", best_n, scan.dirs_world)) < GRAZING_COS
    in_range = best_t < rmax - rmin
    label = np.where(in_range, best_i, -1)
    interior = _interior(label.reshape(V, H)).reshape(-1)
    pb_known = np.zeros(len(ranges), dtype=bool)
    same = np.zeros(len(ranges), dtype=bool)
    for key, indices in owner.items():
        sel = (hits.body == key[0]) & (hits.link == key[1])
        pb_known |= sel
        same |= sel & np.isin(best_i, list(indices))
    compared = same & interior & in_range & np.isfinite(ranges) & ~grazing
    missed = int(((hits.body < 0) & interior & in_range).sum())
    other = int((pb_known & ~same & interior & in_range).sum())
    n = int(compared.sum())
    if n == 0 and missed == 0 and other == 0:
        return Check("ranges", "skipped", "no beam reaches a known shape")
    err = np.abs(ranges[compared] - (rmin + best_t[compared])) if n else np.zeros(1)
    worst_m = float(err.max())
    status = "ok" if worst_m <= RANGE_LIMIT_M and missed == 0 and other == 0 else "fail"
    message = f"{n} beams on known shapes are within {worst_m * 1000:.2f} mm of the exact range"
    if missed:
        message += f"; {missed} beams returned nothing although a known shape is within range"
    if other:
        message += f"; {other} beams hit a different known shape than the exact first hit"
    details = {
        "beams": n,
        "max_m": worst_m,
        "median_m": float(np.median(err)),
        "missed": missed,
        "wrong_shape": other,
        "grazing_skipped": int((same & interior & in_range & grazing).sum()),
        "rays": len(ranges),
        "batch_calls": hits.calls,
    }
    return Check("ranges", status, message, worst_m, "m", RANGE_LIMIT_M, details)
