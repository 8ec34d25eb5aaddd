"""SK409: the focal length the image is rendered with against the one camera_info carries;
SK412: a partial <lens><intrinsics>/<projection>, whose left-out values take sdformat's defaults.

Gazebo Classic renders with ``<lens><intrinsics>`` when given, else with ``horizontal_fov``,
while gazebo_ros_camera publishes camera_info from ``<focal_length>``, else from
``horizontal_fov`` (sources in :data:`sensorkit.knowledge.gazebo_ros.CLASSIC_FOCAL_LENGTH_PARAM`).
Gazebo Sim renders with ``<lens><projection>`` when given, else with ``<intrinsics>``, else
with ``horizontal_fov``; its camera_info K comes from ``<intrinsics>`` (else horizontal_fov)
and P from ``<projection>``: a projection K disagrees with leaves K off the image, and
otherwise it is ``horizontal_fov`` that no longer holds.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.gazebo_ros import CLASSIC_FOCAL_LENGTH_PARAM, CLASSIC_NO_INTRINSICS_TYPES
from sensorkit.knowledge.gazebo_sim import LENS_BLOCKS_READ, LENS_DEFAULTED_TAGS, lens_block_values
from sensorkit.knowledge.limits import EDGE_PX
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.frames import publishing_plugin, ros_generation
from sensorkit.model.parse import parse_float
from sensorkit.model.sensors import CameraSpec, Sensor
from sensorkit.model.targets import is_gz


@rule(
    "SK409",
    "error/warning",
    "image and camera_info focal lengths disagree: Classic renders with <lens><intrinsics> "
    "(else horizontal_fov) but camera_info comes from focal_length (else horizontal_fov); "
    "gz lens projection that disagrees with camera_info K (Gazebo Sim renders with <projection> "
    "when given, else <intrinsics>): an error when camera_info misplaces the image edge by more "
    "than 1 px (a principal point: by more than SK411's 10 % and 1 px), a warning below; a gz "
    "lens that renders other than horizontal_fov, with camera_info matching the image: warning",
    "gazebo_ros_camera, at run time",
    formats=("urdf", "sdf"),
)
def focal_length(ctx: Context) -> Iterator[Finding]:
    for s in ctx.robot.sensors:
        cam = s.camera if s.is_camera else None
        if cam is None or cam.width is None or cam.width <= 0:
            continue
        hfov = cam.hfov if cam.hfov is not None else 1.047
        if not 0 < hfov < math.pi:
            continue
        half = math.tan(hfov / 2.0)
        if half <= 0.0 or cam.width > 2**1000:  # a denormal fov halves to 0; a width past floats
            continue
        expected = cam.width / (2.0 * half)
        if is_gz(ctx.target):
            yield from _gz_intrinsics(ctx, s, cam, hfov, expected)
        elif cam.lens_intrinsics is not None and s.type not in CLASSIC_NO_INTRINSICS_TYPES:
            yield from _classic_intrinsics(ctx, s, cam, hfov, expected)
        else:
            yield from _classic_focal_length(ctx, s, cam, hfov, expected)


# When a camera_info that disagrees with the image is a wrong calibration (an error) rather
# than a rounding (a warning). sensorkit's materiality floor, not a simulator fact
# (sensorkit.knowledge.limits.EDGE_PX): a focal length is wrong when it moves the image edge
# (width / 2 from the centre) by more than one pixel, the unit the image measures in; a
# principal point when SK411 would call it far.


# Two lens values (fx, or a K entry against the projection) within this relative difference
# are the same value written twice, rounded: sensorkit's floor, one for every lens comparison
# (tests/test_limits.py holds a case either side).
SAME_LENS_REL = 1e-3


def _focal_severity(size: int | None, rendered: float, published: float) -> Severity:
    """ERROR when camera_info's focal length ``published`` puts the image edge more than
    EDGE_PX pixels from where the ``rendered`` one draws it."""
    if not size or rendered <= 0 or not math.isfinite(published):
        return Severity.WARNING
    edge_shift = size / 2.0 * abs(published - rendered) / rendered
    return Severity.ERROR if edge_shift > EDGE_PX else Severity.WARNING


def _classic_focal_length(
    ctx: Context, s: Sensor, cam: CameraSpec, hfov: float, expected: float
) -> Iterator[Finding]:
    """No intrinsics: the image spans horizontal_fov, camera_info says the plugin's focal
    length: ROS 2 <focal_length>, ROS 1 <focalLength> (noetic gazebo_ros_camera_utils.cpp
    :183-189; each generation reads only its own tag: CLASSIC_FOCAL_LENGTH_PARAM)."""
    tag = CLASSIC_FOCAL_LENGTH_PARAM[ros_generation(ctx.target)]
    for p in s.plugins:
        f, _ = parse_float(p.param(tag))
        if f is not None and f > 0 and abs(f - expected) > 1e-6 * max(1.0, expected):
            yield ctx.finding(
                "SK409",
                _focal_severity(cam.width, expected, f),
                f"camera {s.name!r}: {tag} {f:g} disagrees with width {cam.width} and horizontal_fov {hfov:g} "
                f"(which give {expected:.6f}); camera_info and the rendered image will not match",
                p.source,
                sensor=s.name,
                fix=f"remove <{tag}> or write {expected!r}",
            )


def _classic_intrinsics(
    ctx: Context, s: Sensor, cam: CameraSpec, hfov: float, expected: float
) -> Iterator[Finding]:
    """Gazebo Classic renders with <lens><intrinsics> but gazebo_ros_camera's camera_info
    takes its fx from <focal_length> or horizontal_fov: they must agree."""
    assert cam.lens_intrinsics is not None
    fx = cam.lens_intrinsics[0]
    plugin, spec = publishing_plugin(s, ctx.target)
    if fx <= 0 or plugin is None or spec is None:
        return
    if not any(d is not None and d.endswith("camera_info") for _, d in spec.topics):
        return  # no camera_info to disagree with the image
    tag = CLASSIC_FOCAL_LENGTH_PARAM[ros_generation(ctx.target)]
    f, _ = parse_float(plugin.param(tag))
    given = f is not None and f > 0 and math.isfinite(f)
    published = f if given and f is not None else expected
    if abs(fx - published) <= SAME_LENS_REL * published:
        return
    spans = 2.0 * math.atan(cam.width / (2.0 * fx)) if cam.width else hfov
    whence = f"<{tag}>" if given else f"width {cam.width} and horizontal_fov {hfov:g}"
    yield ctx.finding(
        "SK409",
        _focal_severity(cam.width, fx, published),
        f"camera {s.name!r}: Gazebo Classic renders the image with <lens><intrinsics> fx {fx:g}, "
        f"but {spec.family} publishes camera_info fx {published:.4f} (from {whence}, it never "
        "reads the intrinsics): camera_info does not match the image",
        cam.source,
        sensor=s.name,
        fix=f"set horizontal_fov to {spans:.6f} (what fx {fx:g} spans)"
        + (f" and remove <{tag}>" if given else "")
        + f", or fx to {published:.6f}",
    )


def _gz_intrinsics(
    ctx: Context, s: Sensor, cam: CameraSpec, hfov: float, expected: float
) -> Iterator[Finding]:
    # What gz-sensors renders with and what camera_info carries (gazebosim/gz-sensors@
    # gz-sensors8 c8159af:src/CameraSensor.cc, UpdateLensIntrinsicsAndProjection, called at
    # :318 before PopulateInfo at :334): without <intrinsics>, K is taken from the
    # horizontal_fov projection (:844-857); with them, the render projection is built from
    # them (:858-873); then, with <projection>, the render projection is built again from
    # p_fx, p_fy, p_cx, p_cy (:898-914), so the projection wins. camera_info K is
    # LensIntrinsics (:729-739), P is LensProjection (:744-757). The same order on
    # @gz-sensors10 ff8c92b (:766-795, :802-837; K :664, P :679) and @ign-sensors6 7cfaddf
    # (inline in Load: :242-271, :290-325; K :740, P :755).
    # (Gazebo Classic renders with the intrinsics but publishes camera_info without them:
    # see _classic_intrinsics.)
    proj = cam.lens_projection
    if proj and "fx" not in proj:
        return  # a <projection> without p_fx renders with sdformat's default: not judged
    intr = cam.lens_intrinsics
    keys = ("fx", "fy", "cx", "cy")
    k: dict[str, float] = (
        {"fx": expected} if intr is None else dict(zip(keys, intr[:4], strict=True))
    )
    if proj:
        off: list[tuple[str, float, float]] = [
            (key, proj[key], k[key])
            for key in keys
            if key in proj
            and key in k
            and math.isfinite(proj[key])
            and abs(proj[key] - k[key]) > SAME_LENS_REL * max(1.0, abs(k[key]))
        ]
        if off:
            yield _gz_k_off_projection(ctx, s, cam, hfov, off)
            return
        render_fx, whence = proj["fx"], f"<lens><projection> p_fx {proj['fx']:g}"
    elif intr is not None:
        render_fx, whence = intr[0], f"<lens><intrinsics> fx {intr[0]:g}"
    else:
        return
    if render_fx > 0 and abs(render_fx - expected) > SAME_LENS_REL * expected:
        spans = 2.0 * math.atan(cam.width / (2.0 * render_fx)) if cam.width else hfov
        tag = "p_fx" if proj else "fx"
        yield ctx.finding(
            "SK409",
            Severity.WARNING,
            f"camera {s.name!r}: lens {tag} {render_fx:g} disagrees with width {cam.width} and "
            f"horizontal_fov {hfov:g} (which give {expected:.4f}): Gazebo Sim renders with "
            f"{whence}, so the image spans {spans:.4f} rad, not the horizontal_fov written",
            cam.source,
            sensor=s.name,
            fix=f"set {tag} to {expected:.6f}, or horizontal_fov to {spans:.6f}",
        )


def _gz_k_off_projection(
    ctx: Context, s: Sensor, cam: CameraSpec, hfov: float, off: list[tuple[str, float, float]]
) -> Finding:
    """gz renders with <projection>, camera_info K says otherwise (sources in _gz_intrinsics)."""
    src = (
        "<lens><intrinsics>"
        if cam.lens_intrinsics is not None
        else (f"width {cam.width} and horizontal_fov {hfov:g}")
    )
    rendered = ", ".join(f"p_{key} {p:g}" for key, p, _ in off)
    says = ", ".join(f"{key} {kv:.4f}" for key, _, kv in off)
    return ctx.finding(
        "SK409",
        _k_off_severity(cam, off),
        f"camera {s.name!r}: Gazebo Sim renders the image with <lens><projection> ({rendered}; "
        f"the projection wins over <intrinsics> and horizontal_fov), but camera_info K carries "
        f"{says} (from {src}); only P follows the projection: K does not match the image",
        cam.source,
        sensor=s.name,
        fix="make <intrinsics> (or horizontal_fov) agree with <projection>, or remove <projection>",
    )


def _k_off_severity(cam: CameraSpec, off: list[tuple[str, float, float]]) -> Severity:
    """ERROR when any of K's fx, fy, cx, cy is materially off the projection the image has."""
    from sensorkit.lint.rules.principal import FAR

    for key, rendered, k in off:
        size = cam.width if key in ("fx", "cx") else cam.height
        if key in ("fx", "fy") and _focal_severity(size, rendered, k) is Severity.ERROR:
            return Severity.ERROR
        if key in ("cx", "cy") and size and abs(rendered - k) > max(FAR * size, EDGE_PX):
            return Severity.ERROR
    return Severity.WARNING


@rule(
    "SK412",
    "warning",
    "partial lens projection/intrinsics: the left-out values take sdformat's defaults "
    "fx=fy=277, cx=160, cy=120",
    "none",
    formats=("urdf", "sdf"),
)
def partial_lens(ctx: Context) -> Iterator[Finding]:
    # sdformat fills what a written <lens><intrinsics>/<projection> leaves out with 277, 277,
    # 160, 120; Gazebo Sim renders with those and publishes them in camera_info, Gazebo
    # Classic renders with the intrinsics ones and never reads <projection> (sources at
    # sensorkit.knowledge.gazebo_sim.SDF_LENS_INTRINSICS_DEFAULTS).
    sim = "gz" if is_gz(ctx.target) else "classic"
    for s in ctx.robot.sensors:
        cam = s.camera if s.is_camera else None
        if cam is None or not cam.lens_left_out or s.type in CLASSIC_NO_INTRINSICS_TYPES:
            continue  # a wide-angle camera is no pinhole: its lens is not judged
        natural = _natural_lens(cam)
        for block in LENS_BLOCKS_READ[sim]:
            left_out = cam.lens_left_out.get(block, ())
            missing = [t for t in LENS_DEFAULTED_TAGS[block] if t in left_out]
            values = lens_block_values(block, _written(cam, block))
            if not missing or all(
                natural.get(t.removeprefix("p_")) is not None
                and abs(values[t] - natural[t.removeprefix("p_")])
                <= _TOLERANCE[t.removeprefix("p_")]
                for t in missing
            ):
                continue  # nothing left out, or the defaults are what the image gives anyway
            yield _partial_lens_finding(ctx, s, cam, block, sim, missing, values, natural)


_TOLERANCE = {"fx": 0.5, "fy": 0.5, "cx": 0.5, "cy": 0.5}  # pixels


def _written(cam: CameraSpec, block: str) -> dict[str, float]:
    """The values a <lens> block writes, keyed by its SDF tags."""
    if block == "intrinsics":
        return dict(cam.lens_intrinsics_given)
    return {
        (f"p_{k}" if k in ("fx", "fy", "cx", "cy") else k): v
        for k, v in cam.lens_projection.items()
    }


def _natural_lens(cam: CameraSpec) -> dict[str, float]:
    """fx, fy, cx, cy the image and horizontal_fov give (gz's K without a lens block, to the
    pixel): what left-out lens values would be harmless at."""
    out: dict[str, float] = {}
    hfov = cam.hfov if cam.hfov is not None else 1.047
    if cam.width is not None and cam.width > 0 and 0 < hfov < math.pi and math.tan(hfov / 2) > 0:
        out["fx"] = out["fy"] = cam.width / (2.0 * math.tan(hfov / 2.0))
        out["cx"] = cam.width / 2.0
    if cam.height is not None and cam.height > 0:
        out["cy"] = cam.height / 2.0
    return out


def _partial_lens_finding(
    ctx: Context,
    s: Sensor,
    cam: CameraSpec,
    block: str,
    sim: str,
    missing: list[str],
    values: dict[str, float],
    natural: dict[str, float],
) -> Finding:
    p = "p_" if block == "projection" else ""
    said = ", ".join(f"{t}={values[t]:g}" for t in missing)
    fx, fy, cx, cy = (values[p + k] for k in ("fx", "fy", "cx", "cy"))
    if block == "projection":
        what = (
            f"Gazebo Sim publishes camera_info P = [{fx:g}, 0, {cx:g}, {values['tx']:g}; 0, {fy:g}, "
            f"{cy:g}, {values['ty']:g}; 0, 0, 1, 0] and renders the image with it"
        )
    elif sim == "gz":
        what = (
            f"Gazebo Sim publishes camera_info K = [{fx:g}, 0, {cx:g}; 0, {fy:g}, {cy:g}; 0, 0, 1]"
            + ("" if "projection" in cam.lens_left_out else " (and P from it)")
            + " and renders the image with it"
        )
    else:
        what = (
            f"Gazebo Classic renders the image with fx {fx:g}, fy {fy:g}, cx {cx:g}, cy {cy:g} "
            "(gazebo_ros_camera's camera_info never reads <intrinsics>)"
        )
    gives = ", ".join(f"{k} {v:.4g}" for k, v in natural.items())
    fix = ", ".join(
        f"<{t}>{natural[t.removeprefix('p_')]:.6g}</{t}>"
        for t in missing
        if t.removeprefix("p_") in natural
    )
    return ctx.finding(
        "SK412",
        Severity.WARNING,
        f"camera {s.name!r}: <lens><{block}> leaves out {', '.join(missing)}, which take "
        f"sdformat's defaults ({said}): {what}"
        + (f"; the image and horizontal_fov give {gives}" if gives else ""),
        cam.source,
        sensor=s.name,
        fix=f"write {fix}" if fix else f"write {', '.join(missing)}",
    )
