"""``render_preview``: put the robot in a textured scene and look through every sensor.

The library side of ``sensorkit render preview``: it loads the description, builds the
scene, renders every camera and casts every lidar in pybullet, runs the checks, and
writes the files. It never prints; pass ``progress`` to hear what it is doing.

Output folder layout::

    DIR/summary.json  DIR/overview.png  DIR/index.html
    DIR/<sensor>/rgb.png camera_info.yaml [depth.npy depth.png]     cameras
    DIR/<sensor>/<camera>/...                                        multicamera
    DIR/<sensor>/ranges.npy scan.png [points.npy side.png]           lidars
"""

from __future__ import annotations

import math
import os
import re
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from sensorkit.base.errors import InputError, UsageError
from sensorkit.base.findings import Severity
from sensorkit.knowledge.limits import PLAUSIBLE_CAMERA_PIXELS, PLAUSIBLE_LIDAR_RAYS
from sensorkit.model.transforms_np import Mat, matrix_to_rpy
from sensorkit.render.checks import Check, frame_check, pose_check, self_occlusion_check, worst

if TYPE_CHECKING:
    from sensorkit.base.findings import Finding
    from sensorkit.loading.untrusted import Untrusted
    from sensorkit.model import Loaded
    from sensorkit.model.frames import SensorFrames
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import CameraSpec, Sensor
    from sensorkit.render.lidar import LidarScan
    from sensorkit.render.overview import ScanView, SensorDrawing
    from sensorkit.render.pictures import Figure
    from sensorkit.render.scene import Scene, Shape
    from sensorkit.render.sim import World

if TYPE_CHECKING:  # the gate and the RViz view
    from sensorkit.render.gate import Verdict
    from sensorkit.render.rviz import Misplaced

__all__ = ["PreviewResult", "SensorPreview", "render_preview"]

Progress = Callable[[str], None]


@dataclass
class SensorPreview:
    """What was rendered for one sensor (one camera of a multicamera), and how it checked."""

    name: str  # the sensor name; "sensor/camera" for a camera of a multicamera
    sensor: str
    type: str
    kind: str
    link: str | None
    directory: Path | None = None
    files: dict[str, Path] = field(default_factory=dict)
    findings: list[Finding] = field(default_factory=list)  # validate's, about this sensor
    checks: list[Check] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    skipped: str | None = None  # why nothing was rendered
    info: dict[str, Any] = field(default_factory=dict)  # frames, intrinsics, scan, topics
    figures: dict[str, Figure] = field(default_factory=dict)  # labelled pictures, by key

    @property
    def status(self) -> str:
        return "skipped" if self.skipped else worst(self.checks)


@dataclass
class PreviewResult:
    out_dir: Path
    robot: str
    source: Path
    target: str
    target_reason: str
    scene: str
    joints: dict[str, float]
    sensors: list[SensorPreview]
    files: dict[str, Path] = field(default_factory=dict)  # summary, overview, index
    findings: list[Finding] | None = None  # validate's; None when it could not run
    fail_on: Severity | None = Severity.ERROR  # the gate's threshold; None: never fail
    findings_error: str | None = None
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0
    figures: list[Figure] = field(default_factory=list)  # the robot close up, stereo pairs

    @property
    def status(self) -> str:
        """The worst check's status (the findings are not in it; see ``verdict``)."""
        return worst([c for s in self.sensors for c in s.checks])

    @property
    def verdict(self) -> Verdict:
        """Pass or fail at ``fail_on``, from validate's findings and the checks."""
        from sensorkit.render.gate import verdict

        checks = [(s.name, c) for s in self.sensors for c in s.checks]
        return verdict(self.findings, self.findings_error, checks, self.fail_on)

    @property
    def failed(self) -> bool:
        return self.verdict.failed


def _say(progress: Progress | None, message: str) -> None:
    if progress is not None:
        progress(message)


def _folder_name(name: str, taken: set[str]) -> str:
    base = re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._") or "sensor"
    out, k = base, 2
    while out.lower() in taken or out.lower() in ("summary.json", "overview.png", "index.html"):
        out, k = f"{base}_{k}", k + 1
    taken.add(out.lower())
    return out


def _pose_dict(T: Mat) -> dict[str, Any]:
    return {
        "xyz": [float(v) for v in T[:3, 3]],
        "rpy": [float(v) for v in matrix_to_rpy(T[:3, :3])],
        "matrix": [[float(v) for v in row] for row in T],
    }


def _load(
    path: Path,
    args: Mapping[str, str],
    package_paths: Sequence[str],
    what: str,
    untrusted: Untrusted | None = None,
) -> tuple[Robot, Loaded]:
    """The robot at ``path`` and what loading it gave (kept for validate)."""
    from sensorkit.model import load_robot

    loaded = load_robot(
        path, args=dict(args), package_paths=tuple(package_paths), untrusted=untrusted
    )
    if loaded.robot is None:
        first = loaded.findings[0] if loaded.findings else None
        detail = f"{first.source}: {first.message}" if first is not None else "cannot be read"
        msg = f"{what} {detail}" if what else detail
        raise InputError(msg)
    return loaded.robot, loaded


def _topics(sensor: Sensor, target: str) -> dict[str, str] | None:
    """Role -> ROS topic (``image``, ``camera_info``, ``scan``...), None when unknown."""
    from sensorkit.describe.sensor_topics import sensor_topics

    topics, _ = sensor_topics(sensor, target)
    return topics or None


@dataclass
class _Job:
    """One sensor (or one camera of a multicamera) to render, planned before any runs."""

    sensor: Sensor
    name: str
    folder: Path
    colour: tuple[int, int, int]
    cam: CameraSpec | None = None


class _Run:
    """State shared by the sensors of one preview."""

    def __init__(
        self,
        robot: Robot,
        world: World,
        scene: Scene,
        poses: dict[str, Mat],
        target: str,
        out_dir: Path,
    ) -> None:
        from sensorkit.model.sdf import convert

        self.robot = robot
        self.world = world
        self.scene = scene
        self.poses = poses
        self.target = target
        self.out_dir = out_dir
        self.conv = convert(robot)
        self.markers: list[tuple[Shape, int, int]] = []
        for (body, link), shapes in world.shape_of.items():
            visual = [s for s in shapes if s.visual]
            if len(visual) == 1 and visual[0].kind == "sphere":
                self.markers.append((visual[0], body, link))

    def frames(self, sensor: Sensor) -> SensorFrames:
        from sensorkit.model.frames import sensor_frames

        return sensor_frames(self.robot, sensor, self.target, self.conv)

    def T_world_render(self, sensor: Sensor) -> Mat | None:
        if sensor.reference is None or sensor.reference not in self.poses:
            return None
        out: Mat = self.poses[sensor.reference] @ sensor.pose.matrix()
        return out

    def pose_check(self, link: str) -> Check:
        at = self.world.robot_link_at.get(link)
        if at is None:
            return Check("render_pose", "skipped", f"link {link!r} is not in pybullet's model")
        return pose_check(self.poses[link], self.world.link_frame(*at), link)

    def frame_info(self, frames: SensorFrames, T_render: Mat) -> dict[str, Any]:
        return {
            "link": frames.link,
            "render_pose": _pose_dict(T_render),
            "published_frame": frames.published,
            "published_how": frames.how,
            "published_is_default": frames.is_default,
            "camera_frame": frames.camera_frame,
        }


def _camera(
    run: _Run, job: _Job, progress: Progress | None
) -> tuple[SensorPreview, SensorDrawing | None]:
    from sensorkit.base.atomic import write_text
    from sensorkit.describe.intrinsics import InvalidValue
    from sensorkit.describe.published import depth_range, published_intrinsics
    from sensorkit.exporters import camera_dict, camera_info_yaml
    from sensorkit.render._files import save_npy
    from sensorkit.render.camera import (
        PIXEL_ORIGIN,
        depth_check,
        depth_from_buffer,
        orb_check,
        render_camera,
        reprojection_check,
    )
    from sensorkit.render.overview import SensorDrawing
    from sensorkit.render.pictures import at_far_clip, depth_colour_range, depth_figure
    from sensorkit.render.png import write_png
    from sensorkit.render.raster import colourise_depth

    sensor, name, cam = job.sensor, job.name, job.cam
    assert cam is not None
    out = SensorPreview(name, sensor.name, sensor.type, sensor.kind, sensor.reference)
    T_render = run.T_world_render(sensor)
    if T_render is None:
        out.skipped = f"its reference link {sensor.reference!r} is not a link of the robot"
        return out, None
    if cam.pose is not None:
        T_render = T_render @ cam.pose.matrix()
    try:
        published, notes = published_intrinsics(sensor, cam, run.target)
    except InvalidValue as exc:
        out.skipped = f"not a pinhole camera sensorkit can render: {exc}"
        return out, None
    out.notes += notes
    rc = render_camera(sensor, cam, run.target, T_render, published)
    _say(progress, f"rendering {name} ({rc.width}x{rc.height})")
    image = run.world.render(rc.width, rc.height, rc.view_matrix(), rc.projection_matrix())
    depth = depth_from_buffer(image.depth_buffer, rc.near, rc.far)

    folder = job.folder
    folder.mkdir(parents=True, exist_ok=True)
    out.directory = folder
    out.files["rgb"] = folder / "rgb.png"
    write_png(out.files["rgb"], image.rgb)
    if sensor.is_depth:
        near, far, depth_notes = depth_range(sensor, cam, run.target)
        out.notes += depth_notes
        published_depth = depth.copy()
        published_depth[published_depth > far] = np.inf
        published_depth[published_depth < near] = -np.inf
        out.files["depth"] = folder / "depth.npy"
        save_npy(out.files["depth"], published_depth.astype(np.float32))
        out.files["depth_png"] = folder / "depth.png"
        shown = np.where(at_far_clip(published_depth, far), np.inf, published_depth)
        lo, hi = depth_colour_range(shown, near, far)
        png = write_png(out.files["depth_png"], colourise_depth(shown, lo=lo, hi=hi))
        _add_figure(out, depth_figure(png, rc.width, rc.height, lo, hi, near, far))
    camera_name = None
    from sensorkit.model.frames import ros_plugin

    plugin = ros_plugin(sensor)
    if plugin is not None:
        camera_name = plugin.param("camera_name") or plugin.param("cameraName")
    out.files["camera_info"] = folder / "camera_info.yaml"
    write_text(
        out.files["camera_info"],
        camera_info_yaml(published, camera_name=camera_name or sensor.name),
        fsync=False,
    )

    frames = run.frames(sensor)
    out.info["frames"] = run.frame_info(frames, T_render)
    out.info["intrinsics"] = camera_dict(
        published,
        pixel_origin=PIXEL_ORIGIN[published.convention],
        rendered={
            "fx": rc.fx,
            "fy": rc.fy,
            "cx": rc.cx,
            "cy": rc.cy,
            "skew": rc.skew,
            "near": rc.near,
            "far": rc.far,
            "coordinates": "0-based pixel centres",
        },
    )
    topics = _topics(sensor, run.target)
    if topics and sensor.kind == "multicamera":  # this camera's share: "left/image" -> "image"
        prefix = f"{cam.name}/"
        topics = {k[len(prefix) :]: v for k, v in topics.items() if k.startswith(prefix)} or None
    out.info["topics"] = topics

    out.checks.append(reprojection_check(rc, image, published, run.markers))
    out.checks.append(depth_check(rc, image, depth, run.world.shape_of))
    out.checks.append(self_occlusion_check(image.body, image.link, run.world.robot_links, "pixels"))
    out.checks.append(orb_check(image.rgb, sensor.kind))
    if sensor.reference is not None:
        out.checks.append(run.pose_check(sensor.reference))
    frame = frames.camera_frame
    T_frame = run.poses.get(frame) if frame is not None else None
    fcheck = frame_check(
        rc.T_world_optical, T_frame, frame, frames.image_how or frames.how, optical=True
    )
    out.checks.append(fcheck)

    # overview: edge rays along the middle row, as far as they reach
    mid = rc.height // 2
    edge_cols = np.array([0.0, rc.width - 1.0])
    origin, dirs, cos = rc.rays_at(edge_cols, np.array([float(mid), float(mid)]))
    reach = min(rc.far, run.scene.half_extent * 3)

    def end(k: int) -> np.ndarray:
        z = float(depth[mid, int(edge_cols[k])])
        dist = z / float(cos[k]) if math.isfinite(z) else reach
        out_end: np.ndarray = origin + dirs[k] * dist
        return out_end

    centre_z = float(depth[mid, rc.width // 2])
    axis_len = centre_z if math.isfinite(centre_z) else reach
    drawing = SensorDrawing(
        name,
        job.colour,
        origin,
        origin + rc.T_world_optical[:3, 2] * axis_len,
        [end(0), end(1)],
    )
    if fcheck.status == "warn" and T_frame is not None and frame is not None:
        from sensorkit.render.rviz import Misplaced, camera_points

        drawing.published_origin = T_frame[:3, 3].copy()
        drawing.published_axis_end = T_frame[:3, 3] + T_frame[:3, 2] * axis_len
        pts, corners = camera_points(depth, rc.fx, rc.fy, rc.cx, rc.cy, rc.skew, axis_len)
        seen = Misplaced(frame, rc.T_world_optical, T_frame, pts, 2, axis_len, corners)
        _show_misplaced(out, drawing, seen)
    out.info["colour"] = "#{:02x}{:02x}{:02x}".format(*drawing.colour)
    return out, drawing


def _lidar(
    run: _Run, job: _Job, progress: Progress | None
) -> tuple[SensorPreview, SensorDrawing | None]:
    from sensorkit.describe.intrinsics import InvalidValue
    from sensorkit.exporters import laser_scan_dict
    from sensorkit.render._files import save_npy
    from sensorkit.render._stats import median
    from sensorkit.render.lidar import cast, lidar_beams, range_check
    from sensorkit.render.overview import SensorDrawing, draw_scan, scan_view
    from sensorkit.render.png import write_png
    from sensorkit.render.raster import take_rows

    sensor = job.sensor
    out = SensorPreview(sensor.name, sensor.name, sensor.type, sensor.kind, sensor.reference)
    T_render = run.T_world_render(sensor)
    if T_render is None:
        out.skipped = f"its reference link {sensor.reference!r} is not a link of the robot"
        return out, None
    if sensor.lidar is None:
        out.skipped = "no <lidar> or <ray> block"
        return out, None
    try:
        beams = lidar_beams(sensor.lidar, out.notes)
    except InvalidValue as exc:
        out.skipped = f"its scan cannot be cast: {exc}"
        return out, None
    V, H = beams.shape
    _say(
        progress,
        f"casting {sensor.name} ({V} x {H} beams)"
        if V > 1
        else f"casting {sensor.name} ({H} beams)",
    )
    scan = cast(run.world, T_render, beams)
    folder = job.folder
    folder.mkdir(parents=True, exist_ok=True)
    out.directory = folder
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
    world_pts = pts @ T_render[:3, :3].T + T_render[:3, 3]
    view = scan_view(pts, beams.range_max)
    png = write_png(
        out.files["scan_png"],
        draw_scan(pts, rows, self_hit, beams.range_max, sectors=sectors, view=view),
    )
    _lidar_figures(run, out, scan, png, view, world_pts, rows, self_hit, sectors)

    frames = run.frames(sensor)
    out.info["frames"] = run.frame_info(frames, T_render)
    out.info["scan"] = laser_scan_dict(beams.horizontal)
    if beams.vertical is not None:
        out.info["vertical"] = laser_scan_dict(beams.vertical)
    out.info["shape"] = [V, H]
    out.info["topics"] = _topics(sensor, run.target)
    out.checks.append(range_check(scan, run.world.shape_of))
    out.checks.append(
        self_occlusion_check(scan.hits.body, scan.hits.link, run.world.robot_links, "beams")
    )
    if sensor.reference is not None:
        out.checks.append(run.pose_check(sensor.reference))
    frame = frames.published
    T_frame = run.poses.get(frame) if frame is not None else None
    fcheck = frame_check(T_render, T_frame, frame, frames.how, optical=False)
    out.checks.append(fcheck)

    finite = np.isfinite(scan.ranges.reshape(-1))
    fwd = median(scan.ranges[np.isfinite(scan.ranges)]) if finite.any() else beams.range_max
    origin = T_render[:3, 3].copy()
    drawing = SensorDrawing(
        sensor.name,
        job.colour,
        origin,
        origin + T_render[:3, 0] * min(fwd, 1.0),
        [],
        take_rows(world_pts, finite),
    )
    if fcheck.status == "warn" and T_frame is not None and frame is not None:
        from sensorkit.render.rviz import Misplaced, lidar_points

        drawing.published_origin = T_frame[:3, 3].copy()
        drawing.published_axis_end = T_frame[:3, 3] + T_frame[:3, 0] * min(fwd, 1.0)
        seen = Misplaced(frame, T_render, T_frame, lidar_points(scan.points), 0, min(fwd, 1.0))
        _show_misplaced(out, drawing, seen)
    out.info["colour"] = "#{:02x}{:02x}{:02x}".format(*drawing.colour)
    return out, drawing


def _show_misplaced(out: SensorPreview, drawing: SensorDrawing, seen: Misplaced) -> None:
    """Data stamped with a frame that is not where the sensor looks: put it where RViz
    will, in the overview (magenta) and in rviz.png (from above and from the side)."""
    from sensorkit.render.png import write_png
    from sensorkit.render.rviz import draw_rviz, moved_text

    drawing.published_hits = seen.stamped_world(seen.points)
    if seen.frustum is not None:
        drawing.published_edges = list(seen.stamped_world(seen.frustum))
    assert out.directory is not None
    out.files["rviz_png"] = out.directory / "rviz.png"
    write_png(out.files["rviz_png"], draw_rviz(seen, drawing.colour))
    out.info["rviz"] = seen.to_dict()
    out.notes.append(
        f"RViz will place this data in {seen.frame!r}, not where the sensor sees it: "
        f"{moved_text(seen)} (rviz.png)"
    )


def _wanted(sensor: Sensor, only: Sequence[str]) -> bool:
    """Is ``sensor`` previewed (``only``: the sensors asked for; all when empty)?"""
    return not only or sensor.name in only


def _plan(robot: Robot, only: Sequence[str], out_dir: Path) -> list[_Job | SensorPreview]:
    """What to render, in document order, with folders and colours fixed up front."""
    from sensorkit.render.overview import PALETTE

    plan: list[_Job | SensorPreview] = []
    taken: set[str] = set()
    drawn = 0
    for sensor in robot.sensors:
        if not _wanted(sensor, only):
            continue
        if sensor.is_camera and sensor.cameras:
            folder = out_dir / _folder_name(sensor.name, taken)
            multi = sensor.kind == "multicamera"
            cams = sensor.cameras if multi else sensor.cameras[:1]
            inner: set[str] = set()
            for i, cam in enumerate(cams):
                label = f"{sensor.name}/{cam.name or i}" if multi else sensor.name
                where = folder / _folder_name(cam.name or f"camera{i}", inner) if multi else folder
                plan.append(_Job(sensor, label, where, PALETTE[drawn % len(PALETTE)], cam))
                drawn += 1
        elif sensor.kind == "lidar":
            folder = out_dir / _folder_name(sensor.name, taken)
            plan.append(_Job(sensor, sensor.name, folder, PALETTE[drawn % len(PALETTE)]))
            drawn += 1
        else:
            why = (
                "it has no <camera> block"
                if sensor.is_camera
                else f"only cameras and lidars are, and its type is {sensor.type or 'missing'!r}"
            )
            plan.append(
                SensorPreview(
                    sensor.name,
                    sensor.name,
                    sensor.type,
                    sensor.kind,
                    sensor.reference,
                    skipped=why,
                )
            )
    return plan


_Result = tuple[SensorPreview, "SensorDrawing | None"]


def _run_job(run: _Run, job: _Job, progress: Progress | None) -> _Result:
    return _camera(run, job, progress) if job.cam is not None else _lidar(run, job, progress)


# Costs of a job in units of one camera pixel rendered: a lidar ray costs about 12 of
# them, and the checks and files of any sensor some 80,000.
_JOB_OVERHEAD = 80_000
_RAY_COST = 12


def _cost(job: _Job) -> int:
    """Rough CPU a job takes, in units of one TinyRenderer pixel."""
    from sensorkit.describe.published import SDF_DEFAULTS

    if job.cam is not None:
        w = job.cam.width if job.cam.width and job.cam.width > 0 else int(SDF_DEFAULTS["width"])
        h = job.cam.height if job.cam.height and job.cam.height > 0 else int(SDF_DEFAULTS["height"])
        return _JOB_OVERHEAD + w * h
    lidar = job.sensor.lidar
    rays = 1 if lidar is None else max(lidar.samples or 1, 1) * max(lidar.v_samples or 1, 1)
    return _JOB_OVERHEAD + _RAY_COST * rays


def _groups(jobs: list[_Job], workers: int) -> list[list[_Job]]:
    """Jobs split into at most ``workers`` groups of about equal cost, each in document
    order: largest first, each to the lightest group, and of equal ones to the last.
    Group 0 stays in this process, which has the overview and validate to do after."""
    loads = [0] * max(1, min(workers, len(jobs)))
    groups: list[list[_Job]] = [[] for _ in loads]
    for job in sorted(jobs, key=_cost, reverse=True):
        g = max(range(len(loads)), key=lambda k: (-loads[k], k))
        groups[g].append(job)
        loads[g] += _cost(job)
    order = {id(j): k for k, j in enumerate(jobs)}
    return [sorted(group, key=lambda j: order[id(j)]) for group in groups]


def _preload(jobs: list[_Job], target: str) -> None:
    """Import here, before forking, what rendering the jobs imports, so that the forked
    processes inherit it instead of each importing it again."""
    import importlib
    import pickle  # noqa: F401 (the children send their results with it)

    from sensorkit.model.targets import is_gz

    names = [
        "sensorkit.base.atomic",
        "sensorkit.exporters",
        "sensorkit.describe.intrinsics",
        "sensorkit.model.frames",
        "sensorkit.render._files",
        "sensorkit.render.overview",
        "sensorkit.render.png",
        "sensorkit.render.raster",
        "sensorkit.render.rviz",
        "sensorkit.describe.sensorinfo",
    ]
    if any(j.cam is not None for j in jobs):
        names.append("sensorkit.render.camera")
    if any(j.cam is None for j in jobs):
        names.append("sensorkit.render.lidar")
    if is_gz(target):
        names.append("sensorkit.describe.bridge")  # the topics of a gz sensor
    for name in names:
        importlib.import_module(name)


def _render_all(
    run: _Run, plan: list[_Job | SensorPreview], progress: Progress | None, workers: int
) -> list[_Result]:
    """Render every job; with ``workers`` > 1 on Linux, split the jobs, cameras and lidars
    alike, over forked processes of about equal work. Every fork happens before anything
    is rendered or cast here (rayTestBatch starts threads, which must not exist when
    forking). A child that fails has its jobs rendered here instead."""
    jobs = [j for j in plan if isinstance(j, _Job)]
    if workers <= 1 or not sys.platform.startswith("linux") or not hasattr(os, "fork"):
        workers = 1
    groups = _groups(jobs, workers)
    done: dict[int, _Result] = {}
    children: list[tuple[int, int, list[_Job]]] = []
    if len(groups) > 1:
        _preload(jobs, run.target)
    for group in groups[1:]:
        for job in group:
            what = "rendering" if job.cam is not None else "casting"
            _say(progress, f"{what} {job.name} (in another process)")
        child = _fork(run, group)
        if child is not None:
            children.append((*child, group))
        else:
            groups[0] += group
    for job in groups[0]:
        done[id(job)] = _run_job(run, job, progress)
    for pid, fd, group in children:
        results = _collect(pid, fd)
        if results is None or len(results) != len(group):
            results = [_run_job(run, job, progress) for job in group]
        for job, result in zip(group, results, strict=True):
            done[id(job)] = result
    return [done[id(j)] if isinstance(j, _Job) else (j, None) for j in plan]


def _fork(run: _Run, group: list[_Job]) -> tuple[int, int] | None:
    """Render ``group`` in a forked child; (pid, read end of its pipe), or None."""
    import pickle

    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    read, write = os.pipe()
    try:
        pid = os.fork()
    except OSError:
        os.close(read)
        os.close(write)
        return None
    if pid == 0:  # the child: render, send the results, leave without cleanup
        code = 0
        try:
            os.close(read)
            run.world.quiet.forget_sink()
            payload = pickle.dumps([_run_job(run, job, None) for job in group])
        except BaseException:
            payload, code = b"", 1
        try:
            with os.fdopen(write, "wb") as pipe:
                pipe.write(payload)
        finally:
            os._exit(code)
    os.close(write)
    return pid, read


def _collect(pid: int, fd: int) -> list[_Result] | None:
    import pickle

    with os.fdopen(fd, "rb") as pipe:
        payload = pipe.read()
    _, status = os.waitpid(pid, 0)
    if status != 0 or not payload:
        return None
    try:
        results: list[_Result] = pickle.loads(payload)
    except Exception:
        return None
    return results


def _robot_shapes(robot: Robot, poses: dict[str, Mat]) -> list[Shape]:
    from sensorkit.render.scene import scene_shapes_from_robot

    return [s for s in scene_shapes_from_robot(robot, poses) if s.visual and s.kind != "mesh"]


def _reach(robot_shapes: list[Shape], poses: dict[str, Mat]) -> float:
    pts = [T[:2, 3] for T in poses.values()]
    for s in robot_shapes:
        pts.extend(s.footprint())
    return max((float(np.hypot(*p)) for p in pts), default=0.5)


def _validate(
    path: Path,
    loaded: Loaded,
    target: str,
    args: Mapping[str, str],
    package_paths: Sequence[str],
    select: Sequence[str] = (),
    ignore: Sequence[str] = (),
) -> tuple[list[Finding] | None, str | None]:
    """validate's findings on the robot the preview loaded from ``path`` (``loaded``:
    read once, for both)."""
    try:
        from sensorkit.lint.engine import Options, validate_loaded
    except ImportError as exc:
        return None, f"validate is not available ({exc})"
    options = Options(
        target=target,
        args=dict(args),
        package_paths=tuple(package_paths),
        select=tuple(select),
        ignore=tuple(ignore),
    )
    report = validate_loaded(path, loaded, options)
    if report.error:
        return None, report.error
    return list(report.findings), None


# Budgets checked before anything is allocated: the plausibility limits validate warns of
# (SK403/SK406), with their reasons, in sensorkit/knowledge/limits.py.
MAX_CAMERA_PIXELS = PLAUSIBLE_CAMERA_PIXELS
MAX_LIDAR_RAYS = PLAUSIBLE_LIDAR_RAYS
# Sensors further than this from the robot's root are not on a robot (1e308 m overflows).
MAX_POSE_M = 1e4


def _beams(samples: int | None, resolution: float | None) -> float:
    """Rays one scan line casts: samples x resolution (SDF multiplies them), at least 1."""
    n = float(max(samples or 1, 1))
    if resolution is not None and resolution > 0:
        n *= resolution  # 90 samples at resolution 1e5 are 9 million rays (inf past 1e308)
    return max(n, 1.0)


def check_budget(robot: Robot, only: Sequence[str], *, max_pixels: int, max_rays: int) -> None:
    """Refuse (UsageError, exit 2) a sensor whose render would exhaust the machine, or whose
    pose is not a finite place near the robot, naming the sensor and the option to raise."""
    from sensorkit.describe.published import SDF_DEFAULTS
    from sensorkit.model.transforms_np import render_pose_np

    for s in robot.sensors:
        if only and s.name not in only:
            continue
        for cam in s.cameras:
            w = cam.width if cam.width and cam.width > 0 else int(SDF_DEFAULTS["width"])
            h = cam.height if cam.height and cam.height > 0 else int(SDF_DEFAULTS["height"])
            if w * h > max_pixels:
                msg = (
                    f"sensor {s.name!r}: a {w}x{h} camera is {w * h:,} pixels, over the render "
                    f"budget of {max_pixels:,}; pass --max-pixels {w * h} to render it anyway"
                )
                raise UsageError(msg)
        if s.lidar is not None:
            rays = _beams(s.lidar.samples, s.lidar.resolution) * _beams(
                s.lidar.v_samples, s.lidar.v_resolution
            )
            if rays > max_rays:
                raise_it = (
                    f"; pass --max-rays {rays:.0f} to cast it anyway" if rays < math.inf else ""
                )
                msg = (
                    f"sensor {s.name!r}: a lidar of {rays:,.0f} rays per scan (samples x "
                    f"resolution) is over the render budget of {max_rays:,}{raise_it}"
                )
                raise UsageError(msg)
        T = render_pose_np(robot, s)
        if T is not None:
            import numpy as np

            if not np.all(np.isfinite(T)) or float(np.abs(T[:3, 3]).max()) > MAX_POSE_M:
                msg = (
                    f"sensor {s.name!r} sits at {T[:3, 3].tolist()} m from the robot's root: not a "
                    f"finite place within {MAX_POSE_M:g} m, so it cannot be rendered (check its joint origins)"
                )
                raise UsageError(msg)


def check_structure(robot: Robot, target: str) -> None:
    """Never hand pybullet a structurally broken robot (a typeless joint segfaults it):
    validate's SK2xx errors stop the render with one line (exit 2)."""
    from sensorkit.base.findings import Severity
    from sensorkit.lint.engine import Options, check_robot

    report = check_robot(robot, Options(target=target, select=("SK2",)))
    errors = [f for f in report.findings if f.severity == Severity.ERROR]
    if errors:
        first = errors[0]
        more = f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
        msg = (
            f"{first.file}:{first.line}: {first.rule} {first.message}{more}: the kinematic tree is "
            "broken, so nothing is rendered; run sensorkit validate"
        )
        raise InputError(msg)


def _out_checker(out_dir: Path, force: bool, inputs: list[Path]) -> Callable[[], None]:
    """A check that ``out_dir`` may be replaced whole: missing, empty, an earlier preview
    and nothing else, or anything (not precious, not holding an input) with ``force``."""
    from sensorkit.base.atomic import check_replaceable
    from sensorkit.render.report import is_preview

    def check() -> None:
        check_replaceable(out_dir, force=force or is_preview(out_dir), inputs=inputs)

    return check


def _rebase(result: PreviewResult, stage: Path, out_dir: Path) -> None:
    """Point the result's paths from the staging folder at the published one."""

    def moved(path: Path) -> Path:
        try:
            return out_dir / path.relative_to(stage)
        except ValueError:
            return path

    result.out_dir = out_dir
    result.files = {k: moved(v) for k, v in result.files.items()}
    for s in result.sensors:
        s.files = {k: moved(v) for k, v in s.files.items()}
        if s.directory is not None:
            s.directory = moved(s.directory)


def render_preview(
    path: Path,
    out_dir: Path,
    *,
    scene: Path | None = None,
    sensors: Sequence[str] = (),
    joints: Mapping[str, float] | None = None,
    args: Mapping[str, str] | None = None,
    package_paths: Sequence[str] = (),
    target: str = "auto",
    progress: Progress | None = None,
    workers: int = 1,
    max_pixels: int = MAX_CAMERA_PIXELS,
    max_rays: int = MAX_LIDAR_RAYS,
    force: bool = False,
    untrusted: Untrusted | None = None,
    target_origin: str = "--target",
    fail_on: Severity | None = Severity.ERROR,
    select: Sequence[str] = (),
    ignore: Sequence[str] = (),
) -> PreviewResult:
    """Render every camera and cast every lidar of the robot at ``path`` into ``out_dir``.

    Args:
        path: the URDF or xacro file.
        out_dir: the folder to write. It is filled beside itself and replaced whole at
            the end, so an interrupted render leaves the old one as it was; it must be
            missing, empty or an earlier preview (recognised by its summary.json, with
            nothing added by hand), unless ``force``.
        scene: a URDF of static objects to use instead of the default room (the ground
            plane stays).
        sensors: only these sensors (by ``<sensor name>``); all when empty.
        joints: joint positions (radians or metres) by joint name; others stay at zero.
        args: xacro arguments.
        package_paths: where ROS packages live (``DIR`` or ``NAME=DIR``).
        target: ``auto`` or a simulator target (decides camera_info's convention and the
            published frames).
        progress: called with a short message before each step.
        workers: processes to render cameras and cast lidars in (Linux; the others are
            forked from this one after the world is built, so each renders from the same
            state, and get sensors of about equal work). 1 renders everything here;
            results are the same either way.
        max_pixels: the most pixels one camera may have (checked before anything is
            allocated: a 100000 x 100000 camera would need hundreds of GB).
        max_rays: the most rays one lidar may cast per scan.
        force: replace a non-empty ``out_dir`` that is not an earlier preview (never the
            working folder, home, a root, nor one holding the robot or the scene).
        fail_on: the gate (``result.verdict``, the page's header): fail on validate's
            findings of this severity or above and on checks that fail (``warning``: that
            warn too); None never fails.
        select, ignore: validate's rules to run or skip (ids or prefixes), as for
            ``sensorkit validate``.

    Raises:
        InputError: the robot or the scene cannot be read or loaded.
        UsageError: an unknown sensor or joint, a bad joint value or target; a sensor or a
            link too far from the root (or too large) to render; an ``out_dir`` that may
            not be replaced.
    """
    from sensorkit.loading import PackageResolver
    from sensorkit.model.targets import TARGETS, detect_target
    from sensorkit.render.poses import joint_positions, link_poses
    from sensorkit.render.scene import Scene, default_scene, scene_shapes_from_robot
    from sensorkit.render.urdf_out import prepare_urdf

    started = time.perf_counter()
    args = dict(args or {})
    _say(progress, f"loading {path}")
    robot, loaded = _load(path, args, package_paths, "", untrusted)
    known = [s.name for s in robot.sensors]
    for name in sensors:
        if name not in known:
            listing = ", ".join(known) if known else "the robot has no <sensor>"
            msg = f"--sensor {name}: no sensor called {name!r} (sensors: {listing})"
            raise UsageError(msg)
    if target == "auto":
        target, target_reason = detect_target(robot)
    elif target in TARGETS:
        target_reason = f"chosen with {target_origin}"
    else:
        msg = f"unknown target {target!r}: use auto, " + ", ".join(TARGETS)
        raise UsageError(msg)
    check_budget(robot, sensors, max_pixels=max_pixels, max_rays=max_rays)
    check_structure(robot, target)
    from sensorkit.lint.engine import Options

    Options(target=target, select=tuple(select), ignore=tuple(ignore))  # unknown rules: exit 2
    positions = joint_positions(robot, dict(joints or {}))
    poses = link_poses(robot, positions)
    robot_shapes = _robot_shapes(robot, poses)
    reach = _reach(robot_shapes, poses)
    if not reach <= MAX_POSE_M:  # also nan: 1e308 origins or sizes overflow the scene
        msg = (
            f"{robot.document.display}: the robot reaches {reach:g} m from its root: not a finite "
            f"size within {MAX_POSE_M:g} m, so it cannot be rendered (check its joint origins and "
            "geometry sizes)"
        )
        raise UsageError(msg)

    resolver = PackageResolver.from_options(list(package_paths), near=path)
    prepared = prepare_urdf(robot, resolver)
    notes = list(prepared.notes)
    if len(prepared.parts) > 1:
        from sensorkit.render.urdf_out import BODY_LINKS, BODY_Q

        notes.append(
            f"robot: its {len(robot.links)} links do not fit one pybullet body (at most "
            f"{BODY_LINKS - 1} links beside the base and {BODY_Q} joint position variables), "
            f"so it is loaded as {len(prepared.parts)} bodies, each placed where sensorkit's "
            "kinematics puts its base link"
        )
    roots = robot.roots()
    if len(roots) != 1:
        where = robot.document.display
        if not robot.links:
            msg = f"{where}: defines no links, so there is nothing to render (a file of macros to include?)"
        elif not roots:
            msg = f"{where}: its joints form a cycle, and pybullet needs a tree"
        else:
            msg = f"{where}: the robot has {len(roots)} root links ({', '.join(roots)}); pybullet needs one tree"
        raise InputError(msg)

    scene_robot: Robot | None = None
    if scene is not None:
        _say(progress, f"loading scene {scene}")
        scene_robot, _ = _load(scene, {}, package_paths, "scene:", untrusted)
        shapes = scene_shapes_from_robot(scene_robot)
        extent = max(
            (float(np.abs(s.footprint()).max()) for s in shapes if len(s.footprint())), default=3.0
        )
        world_scene = Scene(
            shapes, str(scene), max(extent, _reach(robot_shapes, poses)) + 0.5, scene
        )
    else:
        cameras = any(s.is_camera and s.cameras for s in robot.sensors if _wanted(s, sensors))
        world_scene = default_scene(_reach(robot_shapes, poses), textured=cameras)

    from sensorkit.base.atomic import staged_folder

    check_out = _out_checker(out_dir, force, [path] if scene is None else [path, scene])
    check_out()  # before pybullet starts; again under the folder lock

    # Everything is written into a staging folder beside out_dir that replaces it whole at
    # the end: an interrupted render (an exception, or the process killed) leaves the old
    # folder as it was, and two renders into one folder take turns on the folder lock.
    with staged_folder(out_dir) as stage:
        check_out()
        from sensorkit.render.sim import World

        _say(progress, "starting pybullet (DIRECT, TinyRenderer)")
        with World() as world:
            ground_half = max(world_scene.half_extent + 1.0, 10.0 if scene is not None else 0.0)
            if scene is not None and scene_robot is not None:
                from sensorkit.render.scene import GROUND, Shape

                ground = Shape("ground", GROUND, np.eye(4), (), GROUND)
                world.add_ground(ground_half, world_scene, ground)
                scene_urdf = prepare_urdf(
                    scene_robot,
                    PackageResolver.from_options(list(package_paths), near=scene),
                    what="scene",
                )
                notes += scene_urdf.notes
                world.add_scene_urdf(scene_urdf.text, world_scene.shapes)
                world_scene.shapes.insert(0, ground)
            else:
                world.add_default_shapes(world_scene, world_scene.half_extent)
            _say(progress, f"loading {robot.name or 'the robot'} into pybullet")
            world.add_robot_parts(prepared.parts, poses)
            world.set_joints(positions)
            world.refresh_bounds()

            run = _Run(robot, world, world_scene, poses, target, stage)
            plan = _plan(robot, sensors, stage)
            results = _render_all(run, plan, progress, workers)
            previews = [p for p, _ in results]
            _draw_imus(run, previews)
            drawings = [d for _, d in results if d is not None]
            robot_boxes = []
            for body in world.robot_bodies:
                for _, lo, hi in world.aabbs(body):
                    if float(np.max(hi - lo)) > 0.005:
                        robot_boxes.append((lo, hi))

        _say(progress, "running validate")
        findings, findings_error = _validate(
            path, loaded, target, args, package_paths, select, ignore
        )
        from sensorkit.render.gate import sensor_findings

        for p in previews:
            p.findings = sensor_findings(findings, p.sensor)

        result = PreviewResult(
            out_dir=stage,
            robot=robot.name,
            source=path,
            target=target,
            target_reason=target_reason,
            scene=world_scene.source,
            joints=positions,
            sensors=previews,
            findings=findings,
            findings_error=findings_error,
            notes=notes,
            fail_on=fail_on,
        )
        from sensorkit.render.overview import draw_overview
        from sensorkit.render.png import write_png
        from sensorkit.render.report import write_index, write_summary

        _say(progress, "writing overview, summary and index")
        half = max(world_scene.half_extent, _reach(robot_shapes, poses) + 0.5) + 0.3
        overview = draw_overview(world_scene.shapes, robot_shapes, robot_boxes, drawings, half)
        result.files["overview"] = stage / "overview.png"
        write_png(result.files["overview"], overview)
        result.figures += _robot_figures(run, previews, robot_boxes, robot_shapes, notes)
        result.seconds = time.perf_counter() - started
        result.files["summary"] = stage / "summary.json"
        result.files["index"] = stage / "index.html"
        write_summary(result)
        write_index(result)
    _rebase(result, stage, out_dir)
    return result


# ---- labelled pictures (sensorkit.render.pictures) -------------------------------------------
def _add_figure(out: SensorPreview, figure: Figure) -> None:
    """Show ``figure`` on the sensor's part of index.html; its numbers go to summary.json."""
    out.figures[figure.key] = figure
    out.info.setdefault("pictures", {})[figure.key] = figure.facts


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
    run: _Run,
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
    _add_figure(out, scan_figure(scan_png, view, sectors, V, int(self_hit.sum())))
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
    _add_figure(out, side_figure(png, side, facts))


def _draw_imus(run: _Run, previews: list[SensorPreview]) -> None:
    """Give each IMU (nothing to render) its frame checks and a picture of its axes."""
    from sensorkit.render.pictures import imu_figure

    for k, p in enumerate(previews):
        sensor = next(
            (x for x in run.robot.sensors if x.name == p.sensor and x.kind == "imu"), None
        )
        if p.kind != "imu" or sensor is None:
            continue
        T_render = run.T_world_render(sensor)
        if T_render is None:
            continue
        imu = SensorPreview(p.name, p.sensor, p.type, p.kind, p.link)
        frames = run.frames(sensor)
        imu.info["frames"] = run.frame_info(frames, T_render)
        imu.info["topics"] = _topics(sensor, run.target)
        if sensor.reference is not None:
            imu.checks.append(run.pose_check(sensor.reference))
        frame = frames.published
        T_frame = run.poses.get(frame) if frame is not None else None
        fcheck = frame_check(T_render, T_frame, frame, frames.how, optical=False)
        imu.checks.append(fcheck)
        stamped = T_frame[:3, :3] if fcheck.status == "warn" and T_frame is not None else None
        _add_figure(
            imu, imu_figure(T_render[:3, :3], stamped, frame, fcheck.status, fcheck.message)
        )
        previews[k] = imu


def _robot_figures(
    run: _Run,
    previews: list[SensorPreview],
    boxes: list[tuple[np.ndarray, np.ndarray]],
    robot_shapes: list[Shape],
    notes: list[str],
) -> list[Figure]:
    """The robot close up with every sensor's mount, and each stereo pair side by side."""
    from sensorkit.base.errors import SensorkitError
    from sensorkit.describe.sensorinfo import describe
    from sensorkit.render.pictures import Mount, closeup_figure, stereo_figure
    from sensorkit.render.png import read_png

    mounts = []
    for p in previews:
        pose = p.info.get("frames", {}).get("render_pose")
        if pose is not None:
            mounts.append(
                Mount(p.name, p.info.get("colour", "#000000"), np.array(pose["matrix"]), p.link)
            )
    figures = [
        closeup_figure(
            boxes,
            [s.outline() for s in robot_shapes],
            [T[:3, 3] for T in run.poses.values()],
            mounts,
        )
    ]
    try:
        pairs = describe(run.robot, run.target).stereo_pairs
    except (SensorkitError, ValueError, ArithmeticError) as exc:  # a picture never stops a render
        notes.append(f"stereo pairs: not drawn ({exc})")
        return figures
    by_name = {p.name: p for p in previews}
    for pair in pairs:
        left, right = by_name.get(pair.left.id), by_name.get(pair.right.id)
        if left is None or right is None or "rgb" not in left.files or "rgb" not in right.files:
            continue
        left_png = left.files["rgb"].read_bytes()
        h, w = read_png(left_png).shape[:2]
        figures.append(
            stereo_figure(
                pair.name,
                left.name,
                right.name,
                left_png,
                right.files["rgb"].read_bytes(),
                (w, h),
                pair.baseline,
                pair.T_left_right[:3, 3],
                pair.rectified,
                pair.how,
            )
        )
    return figures
