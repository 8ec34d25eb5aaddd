"""What a simulator publishes for one sensor's data: camera_info, depth range, LaserScan.

- :func:`published_intrinsics`: the ``camera_info`` a simulator publishes for a camera
  (Gazebo Classic reads ``cx``/``cy``/``focal_length``/``hack_baseline`` from the ROS 2
  plugin, ROS 1 ``Cx``/``Cy``/``focalLength``/``hackBaseline`` with 0 meaning "computed";
  Gazebo Sim uses ``<lens><intrinsics>`` verbatim); SDF defaults stand in for a missing
  width, height or fov, with a note.
- :func:`depth_range`: the depths a depth image holds as numbers.
- :func:`lidar_scans`: the LaserScan fields of a ``<lidar>``/``<ray>`` block.

Numbers that cannot exist raise :class:`~sensorkit.describe.intrinsics.InvalidValue`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from sensorkit.describe.intrinsics import (
    Convention,
    Intrinsics,
    InvalidValue,
    LaserScanParams,
    camera_intrinsics,
    laser_scan,
)

if TYPE_CHECKING:
    from sensorkit.model.sensors import CameraSpec, LidarSpec, Sensor

__all__ = [
    "CLASSIC_MIN_DEPTH",
    "LIDAR_DEFAULTS",
    "SDF_DEFAULTS",
    "camera_size",
    "convention_of",
    "depth_range",
    "gz_lens",
    "lidar_scans",
    "plugin_number",
    "published_intrinsics",
]

SDF_DEFAULTS: dict[str, float] = {
    "width": 320,
    "height": 240,
    "hfov": 1.047,
    "near": 0.1,
    "far": 100.0,
}
"""sdformat's defaults for ``<camera>``: image 320 x 240, horizontal_fov 1.047 rad, clip
0.1-100 m."""

LIDAR_DEFAULTS: dict[str, float] = {
    "samples": 640,
    "resolution": 1.0,
    "min_angle": 0.0,
    "max_angle": 0.0,
    "range_min": 0.0,
}
"""sdformat's defaults for ``<lidar>``/``<ray>`` (``<range><max>`` has none worth using)."""

CLASSIC_MIN_DEPTH = 0.4
"""gazebo_ros_camera's ``<min_depth>`` default; ``<max_depth>`` defaults to +inf."""


CLASSIC_LENS_NOTE = (
    "<lens><intrinsics> not in camera_info: Gazebo Classic renders the image with them,"
    " but gazebo_ros_camera's camera_info never reads them (see SK409)"
)
"""Gazebo Classic renders with ``<lens><intrinsics>``; camera_info comes from the plugin
and ``horizontal_fov`` (sources: :data:`sensorkit.knowledge.gazebo_ros.CLASSIC_FOCAL_LENGTH_PARAM`)."""


def convention_of(target: str) -> Convention:
    """The camera_info convention of a target: Gazebo Classic (ROS 1 and 2) or gz."""
    return "classic" if target in ("classic", "ros1") else "gz"


# --------------------------------------------------------------------------- cameras


def plugin_number(sensor: Sensor, names: Sequence[str], notes: list[str]) -> float | None:
    """The first of ``names`` the sensor's ROS plugin sets, as a finite number.

    ``None`` when no plugin sets it; a value that is not a finite number is ignored with
    a note (gazebo_ros reads it as its default).
    """
    from sensorkit.model.frames import ros_plugin

    plugin = ros_plugin(sensor)
    if plugin is None:
        return None
    for name in names:
        text = plugin.param(name)
        if text is None:
            continue
        try:
            value = float(text)
        except ValueError:
            notes.append(f"plugin <{name}> {text!r} is not a number; ignored")
            return None
        return value if math.isfinite(value) else None
    return None


def camera_size(cam: CameraSpec, notes: list[str]) -> tuple[int, int, float]:
    """``(width, height, hfov)`` of ``cam``; sdformat's defaults (with a note) where the
    value is missing or unusable."""
    width = cam.width if cam.width and cam.width > 0 else None
    height = cam.height if cam.height and cam.height > 0 else None
    hfov = cam.hfov
    if width is None:
        width = int(SDF_DEFAULTS["width"])
        notes.append(f"no usable image width: SDF's default {width}")
    if height is None:
        height = int(SDF_DEFAULTS["height"])
        notes.append(f"no usable image height: SDF's default {height}")
    if hfov is None:
        hfov = SDF_DEFAULTS["hfov"]
        notes.append(f"no horizontal_fov: SDF's default {hfov} rad")
    return width, height, hfov


def _distortion(cam: CameraSpec) -> tuple[float, float, float, float, float] | None:
    """SDF ``<distortion>`` (k1 k2 k3 p1 p2) in camera_info order (k1 k2 p1 p2 k3)."""
    dist = cam.distortion
    if not any(dist.get(k, 0.0) for k in ("k1", "k2", "k3", "p1", "p2")):
        return None
    k1, k2, p1, p2, k3 = (float(dist.get(k, 0.0)) for k in ("k1", "k2", "p1", "p2", "k3"))
    return (k1, k2, p1, p2, k3)


def gz_lens(
    cam: CameraSpec, notes: list[str]
) -> tuple[tuple[float, float, float, float, float] | None, dict[str, float]]:
    """``(lens_intrinsics, projection)`` as Gazebo Sim loads ``cam``'s ``<lens>`` blocks: a
    value a written block leaves out takes sdformat's default, with a note (sources:
    :data:`sensorkit.knowledge.gazebo_sim.SDF_LENS_INTRINSICS_DEFAULTS`). A block with a value
    that is not a number is taken as written (the parser already said so)."""
    from sensorkit.knowledge.gazebo_sim import LENS_DEFAULTED_TAGS, lens_block_values

    lens, projection = cam.lens_intrinsics, dict(cam.lens_projection)
    keys = {"p_fx": "fx", "p_fy": "fy", "p_cx": "cx", "p_cy": "cy", "tx": "tx", "ty": "ty"}
    given = {
        "intrinsics": cam.lens_intrinsics_given,
        "projection": {tag: projection[key] for tag, key in keys.items() if key in projection},
    }
    for block, left_out in cam.lens_left_out.items():
        values = lens_block_values(block, given[block])
        if len(given[block]) + len(left_out) < len(values):
            continue  # a value written but unreadable: not modelled
        if block == "intrinsics":
            lens = (values["fx"], values["fy"], values["cx"], values["cy"], values["s"])
        else:
            projection = {keys[tag]: v for tag, v in values.items()}
        defaulted = [t for t in LENS_DEFAULTED_TAGS[block] if t in left_out]
        if defaulted:
            said = ", ".join(f"{t}={values[t]:g}" for t in defaulted)
            notes.append(f"<lens><{block}> leaves out {said}: sdformat's defaults (see SK412)")
    return lens, projection


def published_intrinsics(
    sensor: Sensor, cam: CameraSpec, target: str, *, convention: Convention | None = None
) -> tuple[Intrinsics, list[str]]:
    """The camera_info a simulator publishes for ``cam`` under ``target``, and notes.

    ``convention`` (default: the target's, see :func:`convention_of`) chooses whose
    numbers to reproduce: ``classic`` reads the ROS plugin's principal point, focal
    length and baseline (``target="ros1"``: ROS 1 names, where 0 means "computed"),
    ``gz`` reads ``<lens><intrinsics>``, ``ideal`` reads neither.

    Raises:
        InvalidValue: the camera cannot be a pinhole (e.g. hfov >= pi) or a plugin
            value is out of range.
    """
    notes: list[str] = []
    width, height, hfov = camera_size(cam, notes)
    distortion = _distortion(cam)
    conv = convention if convention is not None else convention_of(target)
    if conv == "classic":
        ros1 = target == "ros1"
        cx = plugin_number(sensor, ("Cx",) if ros1 else ("cx",), notes)
        cy = plugin_number(sensor, ("Cy",) if ros1 else ("cy",), notes)
        focal = plugin_number(sensor, ("focalLength",) if ros1 else ("focal_length",), notes)
        baseline = plugin_number(sensor, ("hackBaseline",) if ros1 else ("hack_baseline",), notes)
        # ROS 2 gazebo_ros_camera builds P from P_fx, P_fy, P_cx, P_cy, Tx, Ty when given
        # (ros-simulation/gazebo_ros_pkgs@ros2:gazebo_plugins/src/gazebo_ros_camera.cpp:455-462).
        projection: dict[str, float] = {}
        if not ros1:
            for tag, key in (
                ("P_fx", "fx"),
                ("P_fy", "fy"),
                ("P_cx", "cx"),
                ("P_cy", "cy"),
                ("Tx", "tx"),
                ("Ty", "ty"),
            ):
                value = plugin_number(sensor, (tag,), notes)
                if value is not None:
                    projection[key] = value
        if ros1:  # gazebo_ros_camera_utils (ROS 1) treats 0 as "compute it"
            cx = cx or None
            cy = cy or None
        if cam.lens_intrinsics is not None or "intrinsics" in cam.lens_left_out:
            notes.append(CLASSIC_LENS_NOTE)
        return (
            camera_intrinsics(
                width,
                height,
                hfov,
                "classic",
                focal_length=focal,
                cx=cx,
                cy=cy,
                distortion=distortion,
                hack_baseline=baseline or 0.0,
                projection=projection,
            ),
            notes,
        )
    if conv == "gz":
        lens, projection = gz_lens(cam, notes)
        return (
            camera_intrinsics(
                width,
                height,
                hfov,
                "gz",
                lens_intrinsics=lens,
                distortion=distortion,
                # gz-sensors fills camera_info P from <lens><projection> (p_fx, p_fy, p_cx,
                # p_cy, tx, ty); without it, from the intrinsics, tx 0
                # (gazebosim/gz-sensors@gz-sensors8:src/CameraSensor.cc:741-752, :876-890).
                projection=projection,
            ),
            notes,
        )
    return camera_intrinsics(width, height, hfov, "ideal", distortion=distortion), notes


def depth_range(sensor: Sensor, cam: CameraSpec, target: str) -> tuple[float, float, list[str]]:
    """``(range_min, range_max, notes)``: the depths a depth image holds as numbers.

    Gazebo Classic: gazebo_ros_camera turns depths outside ``(min_depth, max_depth)``
    (defaults 0.4 m and +inf) into -inf/+inf, and nothing is rendered outside the clip
    planes. Gazebo Sim: ``<depth_camera><clip>``, else the camera's ``<clip>``.
    """
    notes: list[str] = []
    near = cam.near if cam.near is not None and cam.near > 0 else SDF_DEFAULTS["near"]
    far = cam.far if cam.far is not None and cam.far > near else SDF_DEFAULTS["far"]
    if convention_of(target) == "classic":
        ros1 = target == "ros1"
        lo = plugin_number(sensor, ("pointCloudCutoff",) if ros1 else ("min_depth",), notes)
        hi = plugin_number(sensor, ("pointCloudCutoffMax",) if ros1 else ("max_depth",), notes)
        lo = CLASSIC_MIN_DEPTH if lo is None else lo
        return max(lo, near), min(hi, far) if hi is not None else far, notes
    from sensorkit.knowledge.gazebo_sim import GZ_READS_DEPTH_CLIP

    if sensor.type not in GZ_READS_DEPTH_CLIP:  # depth_camera renders within <clip> only
        if cam.depth_near is not None or cam.depth_far is not None:
            notes.append(f"<depth_camera><clip> ignored: a gz {sensor.type} renders within <clip>")
        return near, far, notes
    lo = cam.depth_near if cam.depth_near is not None and cam.depth_near > 0 else near
    hi = cam.depth_far if cam.depth_far is not None and cam.depth_far > lo else far
    return lo, hi, notes


# --------------------------------------------------------------------------- lidars


def lidar_scans(
    spec: LidarSpec, notes: list[str] | None = None
) -> tuple[LaserScanParams, LaserScanParams | None]:
    """The horizontal LaserScan of a ``<lidar>``/``<ray>`` block and, for a 3D lidar, the
    vertical fan described the same way (N = floor(samples * resolution), ...).

    Missing values take sdformat's defaults (with a note); ``<range><max>`` is required.

    Raises:
        InvalidValue: no ``<range><max>``, or the scan cannot exist.
    """
    said = notes if notes is not None else []
    if spec.range_max is None:
        msg = "the lidar has no <range><max>"
        raise InvalidValue(msg)

    def pick(value: float | None, key: str, what: str) -> float:
        if value is not None:
            return value
        default = LIDAR_DEFAULTS[key]
        said.append(f"no {what}: SDF's default {default:g}")
        return default

    samples = spec.samples
    if samples is None:
        samples = int(pick(None, "samples", "horizontal samples"))
    resolution = pick(spec.resolution, "resolution", "horizontal resolution")
    lo = pick(spec.min_angle, "min_angle", "horizontal min_angle")
    hi = pick(spec.max_angle, "max_angle", "horizontal max_angle")
    rmin = pick(spec.range_min, "range_min", "range min")
    horizontal = laser_scan(samples, resolution, lo, hi, rmin, spec.range_max)
    vertical = None
    if spec.has_vertical and (spec.v_samples or 1) * (spec.v_resolution or 1.0) >= 2:
        vertical = laser_scan(
            spec.v_samples if spec.v_samples is not None else 1,
            spec.v_resolution if spec.v_resolution is not None else 1.0,
            spec.v_min_angle if spec.v_min_angle is not None else 0.0,
            spec.v_max_angle if spec.v_max_angle is not None else 0.0,
            rmin,
            spec.range_max,
        )
    return horizontal, vertical
