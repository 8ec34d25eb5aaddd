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

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sensorkit.describe.intrinsics import LaserScanParams
from sensorkit.model.transforms_np import Mat
from sensorkit.render._stats import median, unique
from sensorkit.render.checks import Check

if TYPE_CHECKING:
    from sensorkit.model.sensors import LidarSpec
    from sensorkit.render.scene import Shape
    from sensorkit.render.sim import RayHits, World

__all__ = [
    "SAMPLE_BEAMS",
    "LidarBeams",
    "LidarScan",
    "cast",
    "check_sample",
    "lidar_beams",
    "range_check",
]

RANGE_LIMIT_M = 0.01
GRAZING_COS = 0.26  # incidence beyond 75 degrees from the surface normal
# The range check measures at most this many beams of a scan (more only when the scan has
# more rows than this, one beam a row): a 128 x 2048 scan is checked on 32 beams a row.
SAMPLE_BEAMS = 4096
# A beam's footprint: rays this far to either side of it (or one step of the scan, when
# finer). A beam whose footprint meets one shape is compared with its exact range; any
# other with the exact ranges across its footprint. pybullet's surfaces are exact to well
# under this (a sphere's silhouette reaches 0.4 mm further than the exact one).
EDGE_M = 0.01
# Where the footprint is sampled, as fractions of its radius: near the beam too, so that a
# beam clipping a corner by less than pybullet's tolerance finds the range behind it.
FOOTPRINT_FRACTIONS = (0.1, 1.0)
_GOLDEN = (5**0.5 - 1) / 2
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
    rotation: FloatArray  # (3, 3) render frame to world


def lidar_beams(spec: LidarSpec, notes: list[str] | None = None) -> LidarBeams:
    """The beams of ``spec`` (``sensorkit.describe.published.lidar_scans``, so the preview casts
    exactly the scan the exports describe); raises InvalidValue when it cannot exist."""
    from sensorkit.describe.published import lidar_scans

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
    return LidarScan(
        beams, ranges32, points.astype(np.float32), hits, origin.copy(), dirs, R.copy()
    )


def check_sample(rows: int, cols: int, limit: int = SAMPLE_BEAMS) -> npt.NDArray[np.intp]:
    """Flat (row-major) indices of the beams the range check examines, sorted.

    Every beam of a scan of at most ``limit`` beams. A larger scan: every row (evenly
    spaced rows when there are more than ``limit``), each with ``limit // rows`` columns
    spread evenly over the row and shifted from row to row by the golden ratio, so that
    the sample covers every azimuth and every elevation. Deterministic: the same scan
    shape always gives the same beams.
    """
    if rows * cols <= limit:
        return np.arange(rows * cols, dtype=np.intp)
    if rows <= limit:
        picked = np.arange(rows, dtype=np.intp)
    else:
        picked = unique(np.linspace(0, rows - 1, limit).round().astype(np.intp))
    k = min(cols, max(1, limit // len(picked)))
    shift = (picked * _GOLDEN) % 1.0
    at = np.floor((np.arange(k)[None, :] + shift[:, None]) * (cols / k)).astype(np.intp)
    out: npt.NDArray[np.intp] = (picked[:, None] * cols + np.minimum(at, cols - 1)).ravel()
    return out


def _first_hits(
    known: list[Shape], origin: FloatArray, dirs: FloatArray, start: float
) -> tuple[FloatArray, npt.NDArray[np.int64], FloatArray]:
    """(distance from ``origin + start * dir``, shape index or -1, normal) of each unit
    ray's first entry into ``known``.

    A bounded shape is intersected only with the rays that can pass through its bounding
    sphere: those whose azimuth about ``origin`` points at the sphere (found by bisection
    in the rays sorted by azimuth), then those whose line passes within its radius. Most
    shapes are small and off to one side; the ground, unbounded, meets every ray.
    """
    n = len(dirs)
    starts = origin + dirs * start
    best_t = np.full(n, np.inf)
    best_i = np.full(n, -1, dtype=np.int64)
    best_n = np.zeros((n, 3))
    azimuth = np.arctan2(dirs[:, 1], dirs[:, 0])
    order = np.argsort(azimuth, kind="stable")
    sorted_az = azimuth[order]
    vertical = np.flatnonzero((dirs[:, 0] == 0) & (dirs[:, 1] == 0))  # no azimuth
    everything = np.arange(n)
    for i, shape in enumerate(known):
        idx = everything
        radius = shape.bounding_radius
        if np.isfinite(radius):
            pad = radius * (1.0 + 1e-9) + 1e-9
            p = shape.T_world[:3, 3] - origin
            rho = math.hypot(float(p[0]), float(p[1]))
            if rho > pad:  # the sphere's shadow on the ground plane is a wedge of azimuths
                mid, half = math.atan2(float(p[1]), float(p[0])), math.asin(pad / rho) + 1e-9
                inside = np.zeros(n, dtype=bool)  # the rays in the wedge, in index order
                for lo, hi in _wrapped(mid - half, mid + half):
                    j0 = int(np.searchsorted(sorted_az, lo, side="left"))
                    j1 = int(np.searchsorted(sorted_az, hi, side="right"))
                    inside[order[j0:j1]] = True
                inside[vertical] = True
                idx = np.flatnonzero(inside)
            # then the line test: w = centre - start, along the ray w.d, off it |w|^2 - (w.d)^2
            # (take: the same rows as starts[idx], a few times faster)
            w = shape.T_world[:3, 3] - starts.take(idx, axis=0)
            along = np.einsum("ij,ij->i", w, dirs.take(idx, axis=0))
            ww = np.einsum("ij,ij->i", w, w)
            idx = idx[(ww - along * along <= pad * pad) & ((along >= 0) | (ww <= pad * pad))]
            if len(idx) == 0:
                continue
        t_i, normal = shape.hit(starts.take(idx, axis=0), dirs.take(idx, axis=0))
        closer = np.isfinite(t_i) & (t_i < best_t[idx])
        at = idx[closer]
        best_t[at] = t_i[closer]
        best_i[at] = i
        best_n[at] = normal[closer]
    return best_t, best_i, best_n


def _wrapped(lo: float, hi: float) -> list[tuple[float, float]]:
    """The interval [lo, hi] of angles as intervals within [-pi, pi]."""
    if hi - lo >= 2 * math.pi:
        return [(-math.pi, math.pi)]
    if lo < -math.pi:
        return [(lo + 2 * math.pi, math.pi), (-math.pi, hi)]
    if hi > math.pi:
        return [(lo, math.pi), (-math.pi, hi - 2 * math.pi)]
    return [(lo, hi)]


def _probe_dirs(
    scan: LidarScan, sample: npt.NDArray[np.intp], reach: FloatArray
) -> list[FloatArray]:
    """World directions across each sampled beam's footprint: left and right, up and down,
    by one step of the scan or by ``EDGE_M`` at ``reach`` (where the beam lands),
    whichever angle is smaller, and by ``FOOTPRINT_FRACTIONS`` of that. A 2D scan (one
    row) and a scan of one column are probed ``EDGE_M`` across too: a level beam meeting
    the floor at the foot of a wall lies on an edge that no other row of the scan shows."""
    beams = scan.beams
    V, H = beams.shape
    a = beams.azimuth[sample % H]
    e = beams.elevation[sample // H]
    with np.errstate(divide="ignore"):
        near = np.where(np.isfinite(reach) & (reach > 0), EDGE_M / reach, 0.0)
    da = abs(beams.horizontal.angle_increment) if H > 1 else 0.0
    de = abs(beams.vertical.angle_increment) if V > 1 and beams.vertical is not None else 0.0
    out = []
    for step, along_e in ((da, False), (de, True)):
        edge = np.minimum(step, near) if step else near
        for delta in (f * sign * edge for sign in (-1.0, 1.0) for f in FOOTPRINT_FRACTIONS):
            ee, aa = (e + delta, a) if along_e else (e, a + delta)
            ce = np.cos(ee)
            local = np.stack([ce * np.cos(aa), ce * np.sin(aa), np.sin(ee)], axis=1)
            out.append(local @ scan.rotation.T)
    return out


def range_check(
    scan: LidarScan, shapes_of: dict[tuple[int, int], list[Shape]], *, limit: int = SAMPLE_BEAMS
) -> Check:
    """Cast ranges against the exact first hit among all known shapes.

    Measured on the beams of ``check_sample`` (all of them for a scan of at most
    ``limit`` beams; for a larger one a few thousand, from every row and spread over
    every azimuth), where pybullet hit a known primitive or nothing. Ranges are compared,
    not which shape was hit. A beam inside one surface (the rays at the edge of its
    footprint, one step of the scan or ``EDGE_M`` away, whichever is nearer, meet the
    same shape; see ``_probe_dirs``) that meets it less than 75 degrees from its normal
    must be within ``RANGE_LIMIT_M`` of the exact range. Any other beam (at a shape's
    edge, where two shapes meet, or grazing a surface, where a hair's breadth of angle
    or of surface tolerance moves the range a lot) passes when its range lies within
    ``RANGE_LIMIT_M`` of the exact ranges across its footprint. A beam that pybullet says
    hit nothing while the whole footprint meets known shapes within range counts as
    missed.
    """
    known, owner = _known_shapes(shapes_of)
    if not known:
        return Check("ranges", "skipped", "the scene has no known shapes")
    V, H = scan.beams.shape
    sample = check_sample(V, H, limit)
    beams = _sample_exact(scan, known, sample)
    err, looked, same = _errors(beams, owner)
    missed_at = looked & ~np.isfinite(beams.ranges) & (err > RANGE_LIMIT_M)
    compared = looked & np.isfinite(beams.ranges)
    missed = int(missed_at.sum())
    if int(compared.sum()) == 0 and missed == 0:
        return Check("ranges", "skipped", "no beam reaches a known shape")
    return _ranges_check(scan, len(sample), beams, err, compared, same, missed)


def _known_shapes(
    shapes_of: dict[tuple[int, int], list[Shape]],
) -> tuple[list[Shape], list[tuple[int, int]]]:
    """The shapes whose exact geometry is known (collision shapes but meshes), and the
    (body, link) each belongs to."""
    known: list[Shape] = []
    owner: list[tuple[int, int]] = []  # the (body, link) of each known shape
    for key, shapes in shapes_of.items():
        for shape in shapes:
            if shape.collision and shape.kind != "mesh":
                owner.append(key)
                known.append(shape)
    return known, owner


@dataclass
class _Sampled:
    """The sampled beams against the exact geometry, an entry a beam."""

    ranges: FloatArray  # pybullet's range (+inf: no return)
    body: npt.NDArray[np.int32]  # what pybullet hit (body < 0: nothing)
    link: npt.NDArray[np.int32]
    exact: FloatArray  # the exact first hit's range (+inf: none within range)
    in_range: npt.NDArray[np.bool_]  # the exact first hit is within range
    shape: npt.NDArray[np.int64]  # the exact first hit's shape (index of known), or -1
    lo: FloatArray  # the exact ranges across the beam's footprint, lowest
    hi: FloatArray  # and highest
    grazing: npt.NDArray[np.bool_]  # meets its surface beyond 75 degrees from the normal
    interior: npt.NDArray[np.bool_]  # its whole footprint meets one shape, not grazing


def _sample_exact(scan: LidarScan, known: list[Shape], sample: npt.NDArray[np.intp]) -> _Sampled:
    """pybullet's ranges of the ``sample`` beams beside the exact first hits among
    ``known``, along each beam and across its footprint (``_probe_dirs``)."""
    hits = scan.hits
    rmin, rmax = scan.beams.range_min, scan.beams.range_max
    dirs = scan.dirs_world[sample]
    best_t, best_i, best_n = _first_hits(known, scan.origin, dirs, rmin)
    span = rmax - rmin
    in_range = best_t < span
    label = np.where(in_range, best_i, -1)
    exact = np.where(in_range, rmin + best_t, np.inf)
    body, link = hits.body[sample], hits.link[sample]
    ranges = np.where(body >= 0, scan.ranges.reshape(-1)[sample].astype(np.float64), np.inf)
    # the footprint's size where the beam lands: at the exact hit, else at pybullet's
    probes = _probe_dirs(scan, sample, np.where(in_range, exact, ranges))
    around = np.concatenate(probes)
    t_p, i_p, _ = _first_hits(known, scan.origin, around, rmin)
    beside = np.where(t_p < span, i_p, -1).reshape(len(probes), len(sample))
    footprint = np.where(t_p < span, rmin + t_p, np.inf).reshape(len(probes), len(sample))
    lo = np.minimum(exact, footprint.min(axis=0))
    hi = np.maximum(exact, footprint.max(axis=0))
    # a surface tolerance e moves a ray's range by e / cos(incidence): grazing is an edge
    grazing = in_range & (np.abs(np.einsum("ij,ij->i", best_n, dirs)) < GRAZING_COS)
    interior = (beside == label).all(axis=0) & ~grazing
    return _Sampled(ranges, body, link, exact, in_range, best_i, lo, hi, grazing, interior)


def _errors(
    b: _Sampled, owner: list[tuple[int, int]]
) -> tuple[FloatArray, npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
    """Each beam's error (0 when both saw nothing), whether it is looked at (pybullet hit
    a known shape or nothing, and something is within range), and whether pybullet hit
    the exact first hit's shape."""
    on_known = np.zeros(len(b.ranges), dtype=bool)
    for key in dict.fromkeys(owner):
        on_known |= (b.body == key[0]) & (b.link == key[1])
    # pybullet hit the exact first hit's shape: the (body, link) that shape belongs to
    owner_body = np.array([key[0] for key in owner], dtype=np.int64)
    owner_link = np.array([key[1] for key in owner], dtype=np.int64)
    first = np.maximum(b.shape, 0)
    same = (b.shape >= 0) & (owner_body[first] == b.body) & (owner_link[first] == b.link)
    looked = (on_known | (b.body < 0)) & (np.isfinite(b.ranges) | b.in_range)
    ranges = b.ranges
    with np.errstate(invalid="ignore"):
        # interior: against the exact range; elsewhere: how far outside the footprint
        err = np.where(
            b.interior,
            np.abs(ranges - b.exact),
            np.maximum(np.maximum(b.lo - ranges, ranges - b.hi), 0.0),
        )
    err = np.where(np.isnan(err), 0.0, err)  # inf - inf: both saw nothing
    return err, looked, same


def _ranges_check(
    scan: LidarScan,
    sampled: int,
    b: _Sampled,
    err: FloatArray,
    compared: npt.NDArray[np.bool_],
    same: npt.NDArray[np.bool_],
    missed: int,
) -> Check:
    """The check's verdict, message and details from the errors of the ``compared``
    beams (``sampled`` beams were looked at; ``missed`` returned nothing wrongly)."""
    V, H = scan.beams.shape
    n = int(compared.sum())
    errs = err[compared] if n else np.zeros(1)
    worst_m = float(errs.max())
    status = "ok" if worst_m <= RANGE_LIMIT_M and missed == 0 else "fail"
    edges = int((compared & ~b.interior).sum())
    message = f"{n} beams on known shapes are within {worst_m * 1000:.2f} mm of the exact range" + (
        f" ({edges} at edges or grazing, across their footprint)" if edges else ""
    )
    if sampled < V * H:
        message += f" ({sampled:,} of the {V * H:,} beams checked, from every row)"
    if missed:
        message += f"; {missed} beams returned nothing although a known shape is within range"
    other = compared & ~same
    details = {
        "beams": n,
        "max_m": worst_m,
        "median_m": median(errs),
        "missed": missed,
        # pybullet hit another shape than the exact first hit: at a range outside the
        # footprint (counted in max_m) or, at an edge, within it (fine)
        "wrong_shape": int((other & (err > RANGE_LIMIT_M)).sum()),
        "other_shape_in_footprint": int((other & (err <= RANGE_LIMIT_M)).sum()),
        "edge_beams": edges,
        "grazing": int((compared & b.grazing).sum()),
        "rays": V * H,
        "sampled": sampled,
        "batch_calls": scan.hits.calls,
    }
    return Check("ranges", status, message, worst_m, "m", RANGE_LIMIT_M, details)
