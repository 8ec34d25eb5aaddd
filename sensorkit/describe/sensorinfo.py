"""What each sensor of a robot publishes: camera_info, LaserScan geometry, topics, frames.

The facts behind ``sensorkit intrinsics`` and ``sensorkit export`` (and the camera_info
the render preview compares against), without pybullet or any file written:

- :func:`published_intrinsics`: the ``camera_info`` a simulator publishes for a camera
  (Gazebo Classic reads ``cx``/``cy``/``focal_length``/``hack_baseline`` from the ROS 2
  plugin, ROS 1 ``Cx``/``Cy``/``focalLength``/``hackBaseline`` with 0 meaning "computed";
  Gazebo Sim uses ``<lens><intrinsics>`` verbatim); SDF defaults stand in for a missing
  width, height or fov, with a note.
- :func:`lidar_scans`: the LaserScan fields of a ``<lidar>``/``<ray>`` block.
- :func:`sensor_topics`: the ROS topics a sensor's data reaches, by role (``image``,
  ``camera_info``, ``depth_image``, ``scan``, ...): Classic from the plugin and its
  remappings, Gazebo Sim from the gz ``<topic>`` through the ros_gz_bridge names
  ``sensorkit new`` uses.
- :func:`body_frame`: the x-forward link at a camera's pose (LaserScans built from a
  depth image are stamped with it, never with the optical frame).
- :func:`describe`: all of the above for every sensor, as :class:`RobotInfo`, with its
  stereo pairs (:mod:`sensorkit.describe.stereo`).

``sensorkit.exporters.robot`` turns a :class:`RobotInfo` into the ``intrinsics`` and
``export`` commands' documents.

Errors are :class:`~sensorkit.base.errors.UsageError` (a bad request) or
:class:`~sensorkit.base.errors.InputError` (a robot that cannot be read); a camera or lidar
whose numbers cannot exist is kept with its ``error`` so that the other sensors still
export.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, get_args

from sensorkit.base.errors import InputError, UsageError
from sensorkit.describe.intrinsics import (
    Convention,
    Intrinsics,
    InvalidValue,
    LaserScanParams,
    camera_intrinsics,
    laser_scan,
)

if TYPE_CHECKING:
    from sensorkit.describe.bridge import BridgeEntry
    from sensorkit.describe.stereo import StereoPair
    from sensorkit.loading.untrusted import Untrusted
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import CameraSpec, LidarSpec, Sensor
    from sensorkit.model.transforms_np import Mat

__all__ = [
    "LIDAR_DEFAULTS",
    "SDF_DEFAULTS",
    "CameraView",
    "RobotInfo",
    "SensorInfo",
    "body_frame",
    "camera_size",
    "convention_of",
    "depth_range",
    "describe",
    "lidar_scans",
    "load",
    "plugin_number",
    "published_intrinsics",
    "resolve_target",
    "sensor_topics",
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

_POSE_TOL_M = 1e-4
_POSE_TOL_RAD = 1e-3


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
        if cam.lens_intrinsics is not None:
            notes.append(
                "<lens><intrinsics> ignored: Gazebo Classic's camera_info does not read it"
            )
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
        return (
            camera_intrinsics(
                width,
                height,
                hfov,
                "gz",
                lens_intrinsics=cam.lens_intrinsics,
                distortion=distortion,
                # gz-sensors fills camera_info P from <lens><projection> (p_fx, p_fy, p_cx,
                # p_cy, tx, ty); without it, from the intrinsics, tx 0
                # (gazebosim/gz-sensors@gz-sensors8:src/CameraSensor.cc:741-752, :876-890).
                projection=dict(cam.lens_projection),
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


# --------------------------------------------------------------------------- topics


def _abs(topic: str) -> str:
    return "/" + topic.strip().strip("/")


def _ros2_topics(sensor: Sensor) -> tuple[dict[str, str], list[str]]:
    from sensorkit.lint.rules.plugins import resolved_topics
    from sensorkit.model.frames import ros_plugin

    plugin = ros_plugin(sensor)
    if plugin is None:
        return {}, ["no ROS plugin: the sensor publishes nothing to ROS"]
    topics: dict[str, str] = {}
    pairs = resolved_topics(plugin, sensor)
    if not pairs:
        return {}, [f"plugin {plugin.filename!r} publishes no topic sensorkit knows on ROS 2"]
    if plugin.library == "gazebo_ros_camera":
        base = plugin.param("camera_name") or sensor.name
        suffixes = {
            "image_raw": "image",
            "camera_info": "camera_info",
            "depth/image_raw": "depth_image",
            "depth/camera_info": "depth_camera_info",
            "points": "points",
            "image_trigger": "trigger",
        }
        for name, full in pairs:
            rest = name[len(base) + 1 :] if name.startswith(base + "/") else name
            if sensor.kind == "multicamera":
                cam, _, leaf = rest.partition("/")
                role = suffixes.get(leaf)
                if role is not None:
                    topics[f"{cam}/{role}"] = full
            elif rest in suffixes:
                topics[suffixes[rest]] = full
        return topics, []
    (_, full), *_ = pairs
    if sensor.kind == "lidar":
        output = plugin.param("output_type") or "sensor_msgs/PointCloud2"
        role = {"sensor_msgs/LaserScan": "scan", "sensor_msgs/Range": "range"}.get(output, "points")
        topics[role] = full
    elif sensor.kind == "imu":
        topics["imu"] = full
    else:
        topics["out"] = full
    return topics, []


def _ros1_topics(sensor: Sensor) -> tuple[dict[str, str], list[str]]:
    """gazebo_ros_pkgs (ROS 1) names: ``/<robotNamespace>/<cameraName>/<...TopicName>``."""
    from sensorkit.model.frames import ros_plugin

    plugin = ros_plugin(sensor, "ros1")
    if plugin is None:
        return {}, ["no ROS plugin: the sensor publishes nothing to ROS"]
    ns = (plugin.param("robotNamespace") or "").strip("/")

    def full(*parts: str) -> str:
        return _abs("/".join(p.strip("/") for p in (ns, *parts) if p.strip("/")))

    if sensor.is_camera:
        cam = plugin.param("cameraName") or ""
        topics = {
            "image": full(cam, plugin.param("imageTopicName") or "image_raw"),
            "camera_info": full(cam, plugin.param("cameraInfoTopicName") or "camera_info"),
        }
        if sensor.is_depth:
            topics["depth_image"] = full(
                cam, plugin.param("depthImageTopicName") or "depth/image_raw"
            )
            topics["depth_camera_info"] = full(
                cam, plugin.param("depthImageCameraInfoTopicName") or "depth/camera_info"
            )
            topics["points"] = full(cam, plugin.param("pointCloudTopicName") or "points")
        return topics, []
    name = plugin.param("topicName")
    if not name:
        return {}, ["ROS 1 plugin without <topicName>: topic not known"]
    role = "scan" if sensor.kind == "lidar" else "imu" if sensor.kind == "imu" else "out"
    return {role: full(name)}, []


def _gz_roles(sensor: Sensor, entries: Iterable[BridgeEntry]) -> dict[str, str]:
    topics: dict[str, str] = {}
    for entry in entries:
        ros = _abs(entry.ros_topic_name)
        kind = entry.ros_type_name.rsplit("/", 1)[-1]
        if kind == "Image":
            depth = sensor.kind == "depth" or entry.gz_topic_name.endswith("depth_image")
            topics["depth_image" if depth else "image"] = ros
        elif kind == "CameraInfo":
            if sensor.kind != "depth":
                topics["camera_info"] = ros
            if sensor.is_depth:  # the depth image is registered to the colour one
                topics["depth_camera_info"] = ros
        elif kind == "PointCloud2":
            topics["points"] = ros
        elif kind == "LaserScan":
            topics["scan"] = ros
        elif kind == "Imu":
            topics["imu"] = ros
    return topics


def _gz_entries(sensor: Sensor, target: str) -> list[BridgeEntry]:
    from sensorkit.describe.bridge import sensor_entries

    return sensor_entries(sensor.element, target)


def sensor_topics(sensor: Sensor, target: str) -> tuple[dict[str, str], list[str]]:
    """``(role -> ROS topic, notes)``: the ROS topics of ``sensor`` under ``target``.

    Roles: ``image``, ``camera_info``, ``depth_image``, ``depth_camera_info``,
    ``points``, ``scan``, ``range``, ``imu``, ``out`` and ``trigger`` (the one the
    camera subscribes to); a multicamera's
    are ``<camera>/image`` and ``<camera>/camera_info``. Gazebo Classic: the plugin's
    names after namespace and remapping (``~/out:=scan`` -> ``/scan``). Gazebo Sim: the
    ROS names of the ros_gz_bridge entries ``sensorkit new`` writes for the sensor's
    ``<topic>`` (``X/image`` -> ``/X/image_raw``, ...); a sensor without ``<topic>``
    publishes under the world's scoped name, which no file can name.
    """
    from sensorkit.model.targets import is_gz

    if is_gz(target):
        if not sensor.topic:
            return {}, [
                "no <topic>: Gazebo Sim publishes under a name scoped by the world, "
                "which cannot be bridged from here; give the sensor a <topic>"
            ]
        try:
            entries = _gz_entries(sensor, target)
        except InvalidValue as exc:
            return {}, [f"cannot name its topics: {exc}"]
        if not entries:
            return {}, [f"sensor type {sensor.type!r} has no ros_gz_bridge message type"]
        return _gz_roles(sensor, entries), []
    if target == "ros1":
        return _ros1_topics(sensor)
    return _ros2_topics(sensor)


def gz_roles(sensor: Sensor, entry: BridgeEntry) -> list[str]:
    """The roles :func:`sensor_topics` gives one gz topic of ``sensor`` (``image``,
    ``depth_image``, ``camera_info``, ...; an RGB-D camera_info serves both images)."""
    return list(_gz_roles(sensor, [entry]))


# --------------------------------------------------------------------------- frames


def body_frame(robot: Robot, sensor: Sensor, prefer: Sequence[str | None] = ()) -> str | None:
    """The link placed exactly at the sensor's render pose, x forward (not optical).

    Candidates in order: ``prefer``, the sensor's reference link, then every link of its
    tree in document order. ``None`` when no link is there.
    """
    import numpy as np

    from sensorkit.model.transforms_np import T_world_link_np, angle_between, render_pose_np

    T_render = render_pose_np(robot, sensor)
    if T_render is None or sensor.reference is None:
        return None
    root = robot.tree_of(sensor.reference)
    seen: set[str] = set()
    for name in [*prefer, sensor.reference, *robot.subtree(root)]:
        if name is None or name in seen or name not in robot.link_map:
            continue
        seen.add(name)
        T = T_world_link_np(robot, name)
        if T is None:
            continue
        if float(np.linalg.norm(T[:3, 3] - T_render[:3, 3])) > _POSE_TOL_M:
            continue
        if angle_between(T_render[:3, :3], T[:3, :3]) <= _POSE_TOL_RAD:
            return name
    return None


# --------------------------------------------------------------------------- the model


@dataclass
class CameraView:
    """One camera as its consumers see it: camera_info, topics, frame."""

    sensor: Sensor
    spec: CameraSpec
    id: str  # the sensor name; "<sensor>/<camera>" for each camera of a multicamera
    name: str  # the camera_name written into camera_info files
    intrinsics: Intrinsics | None
    error: str | None
    notes: list[str]
    image_topic: str | None
    camera_info_topic: str | None
    frame: str | None  # the frame its images are stamped with

    @property
    def fps(self) -> float | None:
        """The sensor's ``<update_rate>``, when positive."""
        rate = self.sensor.update_rate
        return rate if rate is not None and rate > 0 else None


@dataclass
class SensorInfo:
    """A sensor under one target: where it is, what it publishes, and its geometry."""

    sensor: Sensor
    link: str | None  # its <gazebo reference>, when that is a link
    frame: str | None  # the frame its data is stamped with
    frame_how: str  # frame_name, gz_frame_id, default, ...
    frame_is_default: bool
    body_frame: str | None  # x-forward link at its render pose
    T_world_render: Mat | None
    topics: dict[str, str]
    has_colour: bool = False  # a camera with a colour (or grey) image, not depth only
    topic_notes: list[str] = field(default_factory=list)  # why topics are missing
    cameras: list[CameraView] = field(default_factory=list)
    scan: LaserScanParams | None = None
    vertical: LaserScanParams | None = None
    scan_error: str | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def name(self) -> str:
        return self.sensor.name


@dataclass
class RobotInfo:
    """Every sensor of a robot under one target."""

    robot: Robot
    target: str
    target_reason: str
    convention: Convention
    sensors: list[SensorInfo]
    stereo_pairs: list[StereoPair] = field(default_factory=list)  # see sensorkit.describe.stereo

    @property
    def cameras(self) -> list[CameraView]:
        return [c for s in self.sensors for c in s.cameras]

    @property
    def imus(self) -> list[SensorInfo]:
        return [s for s in self.sensors if s.sensor.kind == "imu"]


def load(
    path: Path,
    *,
    args: Mapping[str, str] | None = None,
    package_paths: Sequence[str] = (),
    untrusted: Untrusted | None = None,
    overlay: Mapping[str, bytes] | None = None,
) -> Robot:
    """Load and model a URDF/xacro file (``overlay``: absolute path -> bytes read instead).

    Raises:
        InputError: the file cannot be read, expanded or parsed as a robot.
    """
    from sensorkit.model import load_robot

    loaded = load_robot(
        path,
        args=dict(args or {}),
        package_paths=tuple(package_paths),
        untrusted=untrusted,
        overlay=overlay,
    )
    if loaded.robot is None:
        first = loaded.findings[0] if loaded.findings else None
        msg = f"{first.source}: {first.message}" if first is not None else f"{path}: cannot be read"
        raise InputError(msg)
    return loaded.robot


def resolve_target(robot: Robot, target: str) -> tuple[str, str]:
    """``(target, why)``: ``auto`` detected as ``sensorkit validate`` does, else checked.

    Raises:
        UsageError: an unknown target.
    """
    from sensorkit.model.targets import TARGETS, detect_target

    if target == "auto":
        return detect_target(robot)
    if target in TARGETS:
        return target, "chosen with --target"
    msg = f"unknown target {target!r}: use auto, " + ", ".join(TARGETS)
    raise UsageError(msg)


def _camera_views(
    robot: Robot,
    sensor: Sensor,
    target: str,
    conv: Convention,
    topics: dict[str, str],
    frame: str | None,
) -> list[CameraView]:
    from sensorkit.model.frames import ros_plugin
    from sensorkit.model.targets import is_gz

    views: list[CameraView] = []
    multi = sensor.kind == "multicamera" and len(sensor.cameras) > 1
    plugin = None if is_gz(target) else ros_plugin(sensor, target)
    base_name = (plugin.param("camera_name") if plugin is not None else None) or sensor.name
    for index, spec in enumerate(sensor.cameras):
        cam_name = spec.name or f"camera{index}"
        key = f"{cam_name}/" if multi else ""
        try:
            intr, notes = published_intrinsics(sensor, spec, target, convention=conv)
            error = None
        except InvalidValue as exc:
            intr, notes, error = None, [], str(exc)
        views.append(
            CameraView(
                sensor=sensor,
                spec=spec,
                id=f"{sensor.name}/{cam_name}" if multi else sensor.name,
                name=f"{base_name}_{cam_name}" if multi else base_name,
                intrinsics=intr,
                error=error,
                notes=notes,
                image_topic=topics.get(f"{key}image"),
                camera_info_topic=topics.get(f"{key}camera_info"),
                frame=frame,
            )
        )
    return views


def describe(robot: Robot, target: str, *, convention: Convention | None = None) -> RobotInfo:
    """Every sensor of ``robot`` under ``target`` (``auto`` is detected).

    ``convention`` overrides the target's camera_info convention for the intrinsics
    (topics and frames stay the target's).

    Raises:
        UsageError: an unknown target or convention.
    """
    from sensorkit.model.frames import sensor_frames
    from sensorkit.model.sdf import convert
    from sensorkit.model.targets import is_gz
    from sensorkit.model.transforms_np import render_pose_np

    chosen, why = resolve_target(robot, target)
    if convention is not None and convention not in get_args(Convention):
        msg = f"unknown convention {convention!r}: use " + ", ".join(get_args(Convention))
        raise UsageError(msg)
    conv = convention or convention_of(chosen)
    conversion = convert(robot)
    infos: list[SensorInfo] = []
    for sensor in robot.sensors:
        frames = sensor_frames(robot, sensor, chosen, conversion)
        topics, notes = sensor_topics(sensor, chosen)
        info = SensorInfo(
            sensor=sensor,
            link=frames.link,
            frame=frames.published,
            frame_how=frames.how,
            frame_is_default=frames.is_default,
            body_frame=body_frame(robot, sensor, prefer=(frames.published,)),
            T_world_render=None if frames.T_world_render is None else render_pose_np(robot, sensor),
            topics=topics,
            # Gazebo Sim's depth_camera renders depth only; every other camera has colour
            has_colour=sensor.is_camera and not (is_gz(chosen) and sensor.kind == "depth"),
            topic_notes=notes,
            notes=list(notes),
        )
        if sensor.is_camera:
            info.cameras = _camera_views(robot, sensor, chosen, conv, topics, frames.camera_frame)
            if not sensor.cameras:
                info.notes.append("no <camera> block")
        if sensor.kind == "lidar":
            if sensor.lidar is None:
                info.scan_error = "no <lidar> or <ray> block"
            else:
                try:
                    info.scan, info.vertical = lidar_scans(sensor.lidar, info.notes)
                except InvalidValue as exc:
                    info.scan_error = str(exc)
        infos.append(info)
    from sensorkit.describe.stereo import stereo_pairs

    described = RobotInfo(robot, chosen, why, conv, infos)
    described.stereo_pairs = stereo_pairs(described)
    return described
