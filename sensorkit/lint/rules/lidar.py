"""SK406: a lidar's scan and range blocks."""

from __future__ import annotations

import math
import re
from collections.abc import Iterator

from sensorkit.base.consequence import Consequence, Role
from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.limits import PLAUSIBLE_LIDAR_RAYS, as_float
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.parse import parse_float
from sensorkit.model.sensors import LidarSpec, Sensor
from sensorkit.model.targets import is_gz


def _backwards_sweep(
    ctx: Context, s: Sensor, spec: LidarSpec, label: str, lo: float, hi: float
) -> Finding:
    """Gazebo Classic's CPU ray casts beam i at min + i * (max - min) / (samples - 1)
    (elysia-best/gazebo-classic@upstream/11.10.2+dfsg:gazebo/physics/MultiRayShape.cc:75-93):
    min above max sweeps the same arc backwards, published with a negative angle_increment.
    It works: a warning."""
    return ctx.finding(
        "SK406",
        Severity.WARNING,
        f"lidar {s.name!r}: {label} min_angle {lo:g} is above max_angle {hi:g}: Gazebo "
        "Classic sweeps the same arc backwards, so scans carry a negative angle_increment",
        spec.source,
        sensor=s.name,
        fix="swap them",
    )


@rule(
    "SK406",
    "error/warning/info",
    "lidar: samples >= 1, min_angle < max_angle (a warning for a Gazebo Classic CPU ray, which sweeps "
    "backwards), 0 <= range min < max (min 0, written or not, is an error only on a "
    "Fortress/Harmonic gpu_lidar, whose near-clip exception aborts gz sim; a warning on Jetty, "
    "which keeps a 0.01 m near clip); vertical block sane (gz rows at least 1); "
    "resolution yields a whole beam count (warning); over 1e6 rays per scan (warning)",
    formats=("urdf", "sdf"),
)
def lidar_block(ctx: Context) -> Iterator[Finding]:
    for s in ctx.robot.sensors:
        spec = s.lidar
        if s.kind != "lidar" or spec is None:
            continue

        def err(msg: str, fix: str, s: Sensor = s, spec: LidarSpec = spec) -> Finding:
            return ctx.finding(
                "SK406",
                Severity.ERROR,
                f"lidar {s.name!r}: {msg}",
                spec.source,
                sensor=s.name,
                fix=fix,
            )

        for p in spec.problems:
            truncated = _truncated_samples(ctx, s, spec, p)
            if truncated is not None:
                yield truncated
                continue
            yield err(p, "write numbers (angles in radians, ranges in metres)")
        for label, samples, lo, hi, res in (
            ("horizontal", spec.samples, spec.min_angle, spec.max_angle, spec.resolution),
            ("vertical", spec.v_samples, spec.v_min_angle, spec.v_max_angle, spec.v_resolution),
        ):
            if label == "vertical" and not spec.has_vertical:
                continue
            # A vertical count of 0 is not saved by gz-sensors' clamp of the rows to 1
            # (_fractional_beams): Lidar::Load logs "Lidar: Image has 0 size!" and goes on
            # (gazebosim/gz-sensors@gz-sensors8 c8159af:src/Lidar.cc:145-148), the GPU rays
            # render 0 rows (src/GpuLidarSensor.cc:213-214), and the scan holds
            # samples x 0 ranges while the publishing loop writes one row into it
            # (src/Lidar.cc:272-296): no usable scan. An error on every target.
            if samples is not None and samples < 1:
                yield err(f"{label} samples {samples} < 1", "use at least 1 sample")
            if lo is not None and hi is not None and (lo > hi or (lo == hi and (samples or 1) > 1)):
                if lo > hi and s.type == "ray" and not is_gz(ctx.target):
                    yield _backwards_sweep(ctx, s, spec, label, lo, hi)
                else:
                    yield err(
                        f"{label} min_angle {lo:g} must be below max_angle {hi:g}",
                        "swap them or widen the range",
                    )
            if samples is not None and samples >= 1 and res is not None:
                beams = samples * res
                if res <= 0:
                    yield err(f"{label} resolution {res:g} must be > 0", "use 1")
                elif math.isfinite(beams) and abs(beams - round(beams)) > 1e-6:
                    yield _fractional_beams(ctx, s, spec, label, samples, res)
        rays = (spec.samples or 0) * (spec.v_samples or 1 if spec.has_vertical else 1)
        if rays > PLAUSIBLE_LIDAR_RAYS:
            rays_f = as_float(rays)
            per_s = (
                f", {rays_f * s.update_rate:.3g} rays/s at {s.update_rate:g} Hz"
                if s.update_rate
                else ""
            )
            yield ctx.finding(
                "SK406",
                Severity.WARNING,
                f"lidar {s.name!r}: {rays:,} rays per scan{per_s} is beyond any real lidar "
                "(an Ouster OS2-128 casts 262,144)",
                spec.source,
                sensor=s.name,
                fix="check samples for a typo (render preview refuses it unless --max-rays allows)",
            )
        rmin, rmax = spec.range_min, spec.range_max
        if rmin is not None and rmax is not None and not 0 <= rmin < rmax:
            yield err(
                f"range min {rmin:g} / max {rmax:g} must satisfy 0 <= min < max",
                "e.g. <min>0.12</min><max>12</max>",
            )
        elif rmin == 0 or (rmin is None and spec.raw.get("range_min") is None):
            yield from _range_min_zero(ctx, s, spec)


def _stoul(text: str) -> int | None:
    """What ``std::stoul(text, nullptr, base)`` returns: the leading whole number (after
    white space and an optional sign; "0x" hexadecimal), ignoring what follows; None where
    it throws (no digits)."""
    m = re.match(r"\s*([+-]?)(0[xX][0-9a-fA-F]+|[0-9]+)", text)
    if m is None:
        return None
    digits = m.group(2)
    value = int(digits, 16) if digits[:2].lower() == "0x" else int(digits)
    return -value if m.group(1) == "-" else value


def _truncated_samples(ctx: Context, s: Sensor, spec: LidarSpec, problem: str) -> Finding | None:
    """SK406 for a sample count that is not a whole number, judged by what sdformat makes of it.

    sdformat parses an ``unsigned int`` with ``std::stoul(tmp, nullptr, numericBase)``, which
    reads the leading digits and ignores the rest without error (gazebosim/sdformat@sdf9
    9ee2d4f:src/Param.cc:354-357; @sdf12 b9417e5:src/Param.cc:702-705; @sdf14 8512585:
    src/Param.cc:911-914), and <samples> is an unsigned int (sdf/1.7/ray.sdf:10). So
    "666.518" is a lidar of 666 beams: the count written, to less than one beam (info);
    "1e3" is a lidar of 1 beam (an error)."""
    for label, raw in (("horizontal", spec.raw.get("samples")), ("vertical", spec.raw.get("v_samples"))):
        if raw is None or not problem.startswith(f"{label} samples") or "whole number" not in problem:
            continue
        written, _ = parse_float(raw)
        used = _stoul(raw)
        if written is None or used is None:
            return None
        c = Consequence(Role.GEOMETRY, f"{written:g}", used, equal=abs(written - used) < 1.0)
        return ctx.judged(
            "SK406",
            c,
            f"lidar {s.name!r}: {label} samples {raw.strip()!r} is not a whole number; sdformat "
            f"reads the leading digits only, a lidar of {used} beams",
            spec.source,
            sensor=s.name,
            fix=f"write <samples>{used if c.equal else round(written)}</samples>",
        )
    return None


def _fractional_beams(
    ctx: Context, s: Sensor, spec: LidarSpec, label: str, samples: int, res: float
) -> Finding:
    """Samples x resolution that is not whole: Gazebo publishes floor(product) beams.

    A gz lidar's vertical rows are at least 1: Lidar::VerticalRangeCount returns
    max(1, floor(samples x resolution)) (gazebosim/gz-sensors@ign-sensors6 7cfaddf:
    src/Lidar.cc:378-386; @gz-sensors8 c8159af and @gz-sensors10 ff8c92b: :389-397), and the
    GPU rays render <samples> rows, never told the resolution (gz-sensors8
    src/GpuLidarSensor.cc:212-214). Where those rows are the samples written (one sample,
    resolution under 1), what is cast is what is published: info.
    """
    beams = samples * res
    published = math.floor(beams)
    clamp = ""
    if label == "vertical" and is_gz(ctx.target) and published < 1:
        published, clamp = 1, ", at least one row"
    if clamp and published == samples:
        # One sample written, one row published (the resolution changes nothing): the
        # rows the author wrote are the rows gz-sensors publishes, so the finding is info
        # and says both.
        return ctx.judged(
            "SK406",
            Consequence(Role.GEOMETRY, f"{samples} row", f"{published} row"),
            f"lidar {s.name!r}: vertical resolution {res:g} on {samples} sample gives "
            f"{beams:g} rows, which gz-sensors raises to at least 1 (Lidar::VerticalRangeCount): "
            f"it publishes {published} row, the {samples} sample written",
            spec.source,
            sensor=s.name,
            fix="drop the vertical <resolution> (or write 1): it changes nothing on one sample",
        )
    sev = Severity.WARNING
    return ctx.finding(
        "SK406",
        sev,
        f"lidar {s.name!r}: {label} samples {samples} x resolution {res:g} = {beams:g} is not a "
        f"whole beam count (Gazebo publishes {published}{clamp})",
        spec.source,
        sensor=s.name,
        fix="pick samples and resolution whose product is whole",
    )


def _range_min_zero(ctx: Context, s: Sensor, spec: LidarSpec) -> Iterator[Finding]:
    """Range min 0 is the SDF default and legal, except as a GPU lidar's near clip.

    A <min> not written is 0 too: it is a required element with default 0
    (gazebosim/sdformat@sdf12 b9417e5:sdf/1.9/lidar.sdf:50 and sdf/1.6/ray.sdf:50), which
    sdformat's parser adds when it is missing (@sdf12:src/parser.cc:1903-1925, @sdf14 8512585:
    :2073-2074), so sdf::Lidar reads 0 (@sdf12:src/Lidar.cc:162-163).

    Sources beside GZ_LIDAR_NEAR_CLIP_TYPES and GZ_NEAR_CLIP_KEPT (knowledge/gazebo_sim.py:
    ogre-next throws on a near clip <= 0 and nothing catches it on Fortress and Harmonic;
    Jetty's gz-rendering10 refuses the 0 and keeps 0.01 m) and CLASSIC_LIDAR_NEAR_CLIP_TYPES
    (knowledge/gazebo_ros.py: unverified).
    """
    from sensorkit.knowledge.gazebo_ros import CLASSIC_LIDAR_NEAR_CLIP_TYPES
    from sensorkit.knowledge.gazebo_sim import GZ_LIDAR_NEAR_CLIP_TYPES, GZ_NEAR_CLIP_KEPT

    fix = "use a small positive min, e.g. <min>0.05</min>"
    written = (
        "range min 0"
        if spec.raw.get("range_min") is not None
        else "range <min> is not written, so sdformat gives it its required default 0; it"
    )
    kept = GZ_NEAR_CLIP_KEPT.get(ctx.target)
    if is_gz(ctx.target) and s.type in GZ_LIDAR_NEAR_CLIP_TYPES and kept is not None:
        c = Consequence(Role.LIMIT, "near clip 0 m", f"near clip {kept:g} m")
        yield ctx.judged(
            "SK406",
            c,
            f"lidar {s.name!r}: {written} becomes the GPU ray camera's near clip; "
            f"gz-rendering on {ctx.target} refuses a near clip of 0 (it logs 'Near clip "
            f"distance must be a finite number greater than 0') and keeps {kept:g} m, so the "
            "lidar works and sees nothing nearer",
            spec.source,
            sensor=s.name,
            fix=fix,
        )
    elif is_gz(ctx.target) and s.type in GZ_LIDAR_NEAR_CLIP_TYPES:
        msg = (
            f"{written} becomes the GPU ray camera's near clip, and Ogre throws "
            "'Near clip distance must be greater than zero' in the render thread, which "
            "nothing catches: the whole `gz sim` server aborts, not just this lidar"
        )
        yield ctx.finding(
            "SK406", Severity.ERROR, f"lidar {s.name!r}: {msg}", spec.source, sensor=s.name, fix=fix
        )
    elif not is_gz(ctx.target) and s.type in CLASSIC_LIDAR_NEAR_CLIP_TYPES:
        msg = (
            f"{written} becomes the GPU laser's near clip; sensorkit has not verified "
            "that Gazebo Classic (gazebo11) accepts a near clip of 0"
        )
        yield ctx.finding(
            "SK406", Severity.INFO, f"lidar {s.name!r}: {msg}", spec.source, sensor=s.name, fix=fix
        )
