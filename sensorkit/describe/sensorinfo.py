"""What each sensor of a robot publishes: camera_info, LaserScan geometry, topics, frames.

The facts behind ``sensorkit intrinsics`` and ``sensorkit export`` (and the camera_info
the render preview compares against), without pybullet or any file written:

- :func:`describe`: every sensor of a robot under one target, as :class:`RobotInfo`: its
  :class:`~sensorkit.describe.views.SensorInfo` and
  :class:`~sensorkit.describe.views.CameraView` records, filled from the camera_info and
  LaserScan a simulator publishes (:mod:`sensorkit.describe.published`), the sensor's
  topics by role (:mod:`sensorkit.describe.sensor_topics`) and frames, with the stereo
  pairs (:mod:`sensorkit.describe.stereo`).
- :func:`body_frame`: the x-forward link at a camera's pose (LaserScans built from a
  depth image are stamped with it, never with the optical frame).
- :func:`load` and :func:`resolve_target`: the robot and the target to describe it for.

``sensorkit.exporters.documents`` and ``sensorkit.exporters.robot`` turn a
:class:`RobotInfo` into the ``intrinsics`` and ``export`` commands' documents.

Errors are :class:`~sensorkit.base.errors.UsageError` (a bad request) or
:class:`~sensorkit.base.errors.InputError` (a robot that cannot be read); a camera or lidar
whose numbers cannot exist is kept with its ``error`` so that the other sensors still
export.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, get_args

from sensorkit.base.errors import InputError, UsageError
from sensorkit.describe.intrinsics import Convention, InvalidValue
from sensorkit.describe.published import convention_of, lidar_scans, published_intrinsics
from sensorkit.describe.sensor_topics import sensor_topics
from sensorkit.describe.views import CameraView, SensorInfo

if TYPE_CHECKING:
    from sensorkit.base.findings import Finding
    from sensorkit.describe.stereo import StereoPair
    from sensorkit.loading.cache import ExpansionCache
    from sensorkit.loading.untrusted import Untrusted
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import Sensor

__all__ = [
    "RobotInfo",
    "body_frame",
    "describe",
    "load",
    "load_models",
    "resolve_target",
]

_POSE_TOL_M = 1e-4
_POSE_TOL_RAD = 1e-3


# --------------------------------------------------------------------------- frames


def body_frame(
    robot: Robot, sensor: Sensor, target: str, prefer: Sequence[str | None] = ()
) -> str | None:
    """The link placed exactly at the sensor's render pose, x forward (not optical).

    Candidates in order: ``prefer``, the sensor's reference link, then every link of its
    tree in document order. ``None`` when no link is there.
    """
    from sensorkit.model.frames_np import T_world_link_np, render_pose_np
    from sensorkit.model.transforms_np import angle_between

    T_render = render_pose_np(robot, sensor, target)
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
        if math.hypot(*(T[:3, 3] - T_render[:3, 3])) > _POSE_TOL_M:  # no overflow when far
            continue
        if angle_between(T_render[:3, :3], T[:3, :3]) <= _POSE_TOL_RAD:
            return name
    return None


# --------------------------------------------------------------------------- the model


@dataclass
class RobotInfo:
    """Every sensor of a robot under one target."""

    robot: Robot
    target: str
    target_reason: str
    convention: Convention
    sensors: list[SensorInfo]
    stereo_pairs: list[StereoPair] = field(default_factory=list)  # see sensorkit.describe.stereo
    # The name a launch file spawns the robot under (the MODEL of Gazebo Sim's scoped frames
    # and topics), as validate uses it; None: not known, the robot's own name stands for it.
    model: str | None = None

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
    cache: ExpansionCache | None = None,
) -> Robot:
    """Load and model a URDF/xacro or SDF file: its robot, the first model of an SDF world
    (``overlay``: absolute path -> bytes read instead; ``cache``: the expansion cache, see
    ``sensorkit.loading.cache``).

    Raises:
        InputError: the file cannot be read, expanded or parsed as a robot.
    """
    return load_models(
        path,
        args=args,
        package_paths=package_paths,
        untrusted=untrusted,
        overlay=overlay,
        cache=cache,
    )[0]


# What loading finds about a robot it still loads, which every command describing the robot
# says (validate reports them as findings): a misspelt xacro arg (SK102), a package or an
# SDF include that does not resolve (SK103, SK107: what it holds is missing from the list).
SAID_ON_LOAD = ("SK102", "SK103", "SK107")


def load_models(
    path: Path,
    *,
    args: Mapping[str, str] | None = None,
    package_paths: Sequence[str] = (),
    untrusted: Untrusted | None = None,
    overlay: Mapping[str, bytes] | None = None,
    cache: ExpansionCache | None = None,
    said: list[Finding] | None = None,
) -> list[Robot]:
    """Every robot of ``path``: each model of an SDF world, else the one robot (the
    errors of :func:`load`). ``said`` receives what loading found about a robot it did
    load (:data:`SAID_ON_LOAD`), for the command to say."""
    from sensorkit.model import load_robot

    loaded = load_robot(
        path,
        args=dict(args or {}),
        package_paths=tuple(package_paths),
        untrusted=untrusted,
        overlay=overlay,
        cache=cache,
        sdf=True,
    )
    if loaded.robot is None:
        first = loaded.findings[0] if loaded.findings else None
        msg = f"{first.source}: {first.message}" if first is not None else f"{path}: cannot be read"
        raise InputError(msg)
    robots = list(loaded.robots) or [loaded.robot]
    if said is not None:
        said.extend(f for f in loaded.findings if f.rule in SAID_ON_LOAD)
        said.extend(_world_include_errors(robots))
    return robots


def _world_include_errors(robots: list[Robot]) -> list[Finding]:
    """The SK107 findings of includes that brought no model: a world's own, and those a
    model holds, nested ones included (an error, or the info of a model:// URI on no path
    searched, which may resolve when the simulation runs): what they hold is not listed.
    Validate's SK107 rule says them; loading alone does not report them."""
    from sensorkit.model.sdf_includes import include_finding

    out: list[Finding] = []
    for robot in robots:
        sm = robot.sdf
        for inc in [*sm.includes, *sm.world_includes] if sm is not None else ():
            found = include_finding(inc, robot.document)
            if found is not None and found not in out:
                out.append(found)
    return out


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


def describe(
    robot: Robot, target: str, *, convention: Convention | None = None, model: str | None = None
) -> RobotInfo:
    """Every sensor of ``robot`` under ``target`` (``auto`` is detected).

    ``convention`` overrides the target's camera_info convention for the intrinsics
    (topics and frames stay the target's). ``model``: the name a launch file spawns the
    robot under (validate's ``LaunchFacts.spawn_name``), the MODEL of Gazebo Sim's default
    frames and scoped topics.

    Raises:
        UsageError: an unknown target or convention.
    """
    from sensorkit.model.frames import sensor_frames
    from sensorkit.model.frames_np import render_pose_np
    from sensorkit.model.sdf import convert
    from sensorkit.model.targets import is_gz

    chosen, why = resolve_target(robot, target)
    if convention is not None and convention not in get_args(Convention):
        msg = f"unknown convention {convention!r}: use " + ", ".join(get_args(Convention))
        raise UsageError(msg)
    conv = convention or convention_of(chosen)
    conversion = convert(robot)
    infos: list[SensorInfo] = []
    for sensor in robot.sensors:
        frames = sensor_frames(robot, sensor, chosen, conversion, model=model)
        topics, notes = sensor_topics(sensor, chosen, robot)
        info = SensorInfo(
            sensor=sensor,
            link=frames.link,
            frame=frames.published,
            frame_how=frames.how,
            frame_is_default=frames.is_default,
            body_frame=body_frame(robot, sensor, chosen, prefer=(frames.published,)),
            T_world_render=None if frames.T_world_render is None else render_pose_np(robot, sensor, chosen),
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

    return RobotInfo(robot, chosen, why, conv, infos, stereo_pairs(robot, chosen, infos), model)


def spawned_as(info: RobotInfo, model: str | None) -> RobotInfo:
    """``info`` for the robot spawned under ``model`` (a launch file's name for it), as
    validate sees it; ``info`` itself when no name is known or the file is a world, whose
    models are named in it."""
    robot = info.robot
    if model is None or model == info.model or (robot.sdf is not None and robot.sdf.world is not None):
        return info
    out = describe(robot, info.target, convention=info.convention, model=model)
    out.target_reason = info.target_reason
    return out
