"""``render_preview``: put the robot in a textured scene and look through every sensor.

The library side of ``sensorkit render preview``: it loads the description, builds the
scene, renders every camera and casts every lidar in pybullet, runs the checks, and
writes the files. It never prints; pass ``progress`` to hear what it is doing.

This module holds the steps in their order; each step's work is done elsewhere:
``admission`` refuses what cannot be rendered, ``plan`` decides the jobs, ``workers``
runs them (``camera_job``, ``lidar_job``; ``imu_job`` after), and ``assemble`` runs
validate and writes the overview, summary.json and index.html.

Output folder layout::

    DIR/summary.json  DIR/overview.png  DIR/index.html
    DIR/<sensor>/rgb.png camera_info.yaml [depth.npy depth.png]     cameras
    DIR/<sensor>/<camera>/...                                        multicamera
    DIR/<sensor>/ranges.npy scan.png [points.npy side.png]           lidars
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from sensorkit.base.errors import InputError
from sensorkit.base.findings import Severity
from sensorkit.model.transforms_np import Mat
from sensorkit.render.admission import MAX_CAMERA_PIXELS, MAX_LIDAR_RAYS
from sensorkit.render.plan import LEFT_OUT, Totals
from sensorkit.render.result import PreviewResult, SensorPreview
from sensorkit.render.session import Progress, say

if TYPE_CHECKING:
    from sensorkit.loading import PackageResolver
    from sensorkit.loading.cache import ExpansionCache
    from sensorkit.loading.untrusted import Untrusted
    from sensorkit.model import Loaded
    from sensorkit.model.robot import Robot
    from sensorkit.render.overview import SensorDrawing
    from sensorkit.render.scene import Scene, Shape
    from sensorkit.render.session import Session
    from sensorkit.render.sim import World
    from sensorkit.render.urdf_out import UrdfPart

__all__ = ["render_preview"]


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
    totals: Totals = Totals(),  # noqa: B008 (frozen: one value shared is fine)
    force: bool = False,
    untrusted: Untrusted | None = None,
    target_origin: str = "--target",
    fail_on: Severity | None = Severity.ERROR,
    select: Sequence[str] = (),
    ignore: Sequence[str] = (),
    cache: ExpansionCache | None = None,
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
        totals: one budget for the whole preview (pixels, rays, seconds; issue 36): past
            it what fits is rendered, the rest left out and named in the notes.
        force: replace a non-empty ``out_dir`` that is not an earlier preview (never the
            working folder, home, a root, nor one holding the robot or the scene).
        fail_on: the gate (``result.verdict``, the page's header): fail on validate's
            findings of this severity or above and on checks that fail (``warning``: that
            warn too); None never fails.
        select, ignore: validate's rules to run or skip (ids or prefixes), as for
            ``sensorkit validate``.
        cache: the expansion cache (``sensorkit.loading.cache``) the robot and the scene
            are read through; None: none. Not used with ``untrusted``.

    Raises:
        InputError: the robot or the scene cannot be read or loaded.
        UsageError: an unknown sensor or joint, a bad joint value or target; a sensor or a
            link too far from the root (or too large) to render; an ``out_dir`` that may
            not be replaced.
    """
    request = _Request(**locals())  # every argument above, by name
    started = time.perf_counter()
    return _staged(request, _ready(request), started)


@dataclass
class _Request:
    """``render_preview``'s arguments, as given."""

    path: Path
    out_dir: Path
    scene: Path | None
    sensors: Sequence[str]
    joints: Mapping[str, float] | None
    args: Mapping[str, str] | None
    package_paths: Sequence[str]
    target: str
    progress: Progress | None
    workers: int
    max_pixels: int
    max_rays: int
    totals: Totals  # one budget for the whole preview (issue 36)
    force: bool
    untrusted: Untrusted | None
    target_origin: str
    fail_on: Severity | None
    select: Sequence[str]
    ignore: Sequence[str]
    cache: ExpansionCache | None  # the expansion cache (sensorkit.loading.cache), if any


@dataclass
class _Ready:
    """What the preview knows before pybullet starts: the robot, loaded and checked, at
    its joints, the URDF pybullet will load, and the scene."""

    robot: Robot
    loaded: Loaded  # kept for validate
    target: str
    target_reason: str
    positions: dict[str, float]
    poses: dict[str, Mat]
    robot_shapes: list[Shape]
    reach: float  # how far the robot reaches from its root (m)
    parts: list[UrdfPart]  # the bodies pybullet loads
    notes: list[str]
    scene_robot: Robot | None  # the --scene, loaded
    world_scene: Scene


def _ready(request: _Request) -> _Ready:
    """Load the robot and check everything that can be checked before pybullet starts;
    load the scene."""
    from sensorkit.loading import PackageResolver
    from sensorkit.render import admission
    from sensorkit.render.poses import joint_positions, link_poses
    from sensorkit.render.urdf_out import prepare_urdf

    say(request.progress, f"loading {request.path}")
    robot, loaded = _load(
        request.path,
        dict(request.args or {}),
        request.package_paths,
        "",
        request.untrusted,
        request.cache,
    )
    resolver = PackageResolver.from_options(
        list(request.package_paths), near=request.path, untrusted=request.untrusted is not None
    )
    sdf_notes: list[str] = []
    if robot.sdf is not None:
        robot, sdf_notes = _sdf_robot(robot, loaded, resolver)
    admission.check_sensor_names(robot, request.sensors)
    target, target_reason = admission.chosen_target(robot, request.target, request.target_origin)
    admission.check_budget(
        robot, request.sensors, target, max_pixels=request.max_pixels, max_rays=request.max_rays
    )
    admission.check_structure(robot, target)
    admission.check_rules(target, request.select, request.ignore)  # unknown rules: exit 2
    positions = joint_positions(robot, dict(request.joints or {}))
    poses = link_poses(robot, positions)
    robot_shapes = _robot_shapes(robot, poses)
    reach = _reach(robot_shapes, poses)
    admission.check_reach(robot, reach)
    prepared = prepare_urdf(robot, resolver)
    notes = sdf_notes + list(prepared.notes) + _parts_note(robot, len(prepared.parts))
    admission.check_tree(robot)
    scene_robot, world_scene = _scene(request, robot, reach)
    return _Ready(
        robot=robot,
        loaded=loaded,
        target=target,
        target_reason=target_reason,
        positions=positions,
        poses=poses,
        robot_shapes=robot_shapes,
        reach=reach,
        parts=prepared.parts,
        notes=notes,
        scene_robot=scene_robot,
        world_scene=world_scene,
    )


# Seconds one xacro expansion may take in a preview: its own, not validate's 60 s, so a
# runaway expression (${9**9**9}) ends the whole preview within 20 s (issue 25). PR2, the
# largest robot of the corpus, expands in under 1 s.
EXPANSION_TIMEOUT = 10.0


def _load(
    path: Path,
    args: Mapping[str, str],
    package_paths: Sequence[str],
    what: str,
    untrusted: Untrusted | None = None,
    cache: ExpansionCache | None = None,
) -> tuple[Robot, Loaded]:
    """The robot at ``path`` and what loading it gave (kept for validate)."""
    from sensorkit.model import load_robot

    loaded = load_robot(
        path,
        args=dict(args),
        package_paths=tuple(package_paths),
        untrusted=untrusted,
        timeout=EXPANSION_TIMEOUT,
        cache=cache,
        sdf=True,
    )
    if loaded.robot is None:
        first = loaded.findings[0] if loaded.findings else None
        detail = f"{first.source}: {first.message}" if first is not None else "cannot be read"
        msg = f"{what} {detail}" if what else detail
        raise InputError(msg)
    return loaded.robot, loaded


def _sdf_robot(robot: Robot, loaded: Loaded, resolver: PackageResolver) -> tuple[Robot, list[str]]:
    """The SDF model drawn as its URDF subset (:mod:`sensorkit.render.sdf_urdf`), and
    notes: what is not drawn, and which model of a world is previewed (the first with
    sensors: a world often starts with its ground plane)."""
    from sensorkit.render.sdf_urdf import sdf_render_robot

    if len(loaded.robots) > 1:
        robot = next((r for r in loaded.robots if r.sensors), robot)
    drawn, notes = sdf_render_robot(robot, resolver)
    if len(loaded.robots) > 1:
        others = ", ".join(repr(r.name) for r in loaded.robots if r is not robot)
        which = "the first with sensors" if robot.sensors else "the first (none has sensors)"
        notes.insert(
            0,
            f"the world holds {len(loaded.robots)} models: previewing {robot.name!r}, "
            f"{which} (not {others})",
        )
    return drawn, notes


def _robot_shapes(robot: Robot, poses: dict[str, Mat]) -> list[Shape]:
    from sensorkit.render.scene import scene_shapes_from_robot

    return [s for s in scene_shapes_from_robot(robot, poses) if s.visual and s.kind != "mesh"]


def _reach(robot_shapes: list[Shape], poses: dict[str, Mat]) -> float:
    pts = [T[:2, 3] for T in poses.values()]
    for s in robot_shapes:
        pts.extend(s.footprint())
    return max((float(np.hypot(*p)) for p in pts), default=0.5)


def _parts_note(robot: Robot, parts: int) -> list[str]:
    """Why a robot over pybullet's limits is loaded as ``parts`` bodies (none for one)."""
    if parts <= 1:
        return []
    from sensorkit.render.urdf_out import BODY_LINKS, BODY_Q

    return [
        f"robot: its {len(robot.links)} links do not fit one pybullet body (at most "
        f"{BODY_LINKS - 1} links beside the base and {BODY_Q} joint position variables), "
        f"so it is loaded as {parts} bodies, each placed where sensorkit's "
        "kinematics puts its base link"
    ]


def _scene(request: _Request, robot: Robot, reach: float) -> tuple[Robot | None, Scene]:
    """The --scene's robot and the scene it makes, or the default room (textured when a
    camera will look at it), sized to hold a robot that ``reach``es that far."""
    from sensorkit.render.plan import wanted
    from sensorkit.render.scene import Scene, default_scene, scene_shapes_from_robot

    if request.scene is None:
        cameras = any(
            s.is_camera and s.cameras for s in robot.sensors if wanted(s, request.sensors)
        )
        return None, default_scene(reach, textured=cameras)
    say(request.progress, f"loading scene {request.scene}")
    scene_robot, _ = _load(
        request.scene, {}, request.package_paths, "scene:", request.untrusted, request.cache
    )
    shapes = scene_shapes_from_robot(scene_robot)
    extent = max(
        (float(np.abs(s.footprint()).max()) for s in shapes if len(s.footprint())), default=3.0
    )
    return scene_robot, Scene(shapes, str(request.scene), max(extent, reach) + 0.5, request.scene)


def _staged(request: _Request, ready: _Ready, started: float) -> PreviewResult:
    """Render into a staging folder beside ``out_dir`` that replaces it whole at the end:
    an interrupted render (an exception, or the process killed) leaves the old folder as
    it was, and two renders into one folder take turns on the folder lock."""
    from sensorkit.base.atomic import staged_folder
    from sensorkit.render.assemble import run_validate, share_findings, write_preview

    path, scene, out_dir = request.path, request.scene, request.out_dir
    check_out = _out_checker(out_dir, request.force, [path] if scene is None else [path, scene])
    check_out()  # before pybullet starts; again under the folder lock
    with staged_folder(out_dir) as stage:
        check_out()
        run, previews, drawings, robot_boxes = _render(request, ready, stage)
        say(request.progress, "running validate")
        findings, findings_error = run_validate(
            path,
            ready.loaded,
            ready.target,
            dict(request.args or {}),
            request.package_paths,
            request.select,
            request.ignore,
        )
        share_findings(findings, previews)
        out = [p.name for p in previews if (p.skipped or "").startswith(LEFT_OUT)]
        if out:
            ready.notes.append(
                f"{len(out)} sensor(s) left out, past the preview's total budget "
                f"(--max-total-pixels, --max-total-rays, --max-seconds): {', '.join(out)}"
            )
        result = PreviewResult(
            out_dir=stage,
            robot=ready.robot.name,
            source=path,
            target=ready.target,
            target_reason=ready.target_reason,
            scene=ready.world_scene.source,
            joints=ready.positions,
            sensors=previews,
            findings=findings,
            findings_error=findings_error,
            notes=ready.notes,
            fail_on=request.fail_on,
            placement=run.placement,
        )
        write_preview(
            result,
            run,
            ready.robot_shapes,
            robot_boxes,
            drawings,
            ready.reach,
            started,
            request.progress,
        )
    _rebase(result, stage, out_dir)
    return result


_Boxes = list[tuple[np.ndarray, np.ndarray]]


def _render(
    request: _Request, ready: _Ready, stage: Path
) -> tuple[Session, list[SensorPreview], list[SensorDrawing], _Boxes]:
    """Build the world in pybullet and render every sensor into ``stage``: the session,
    the sensors' records, their drawings for the overview and the robot's boxes."""
    from sensorkit.render.imu_job import draw_imus
    from sensorkit.render.plan import plan_jobs
    from sensorkit.render.session import Session
    from sensorkit.render.sim import World
    from sensorkit.render.workers import render_all

    say(request.progress, "starting pybullet (DIRECT, TinyRenderer)")
    with World() as world:
        _furnish(world, request, ready)
        run = Session(ready.robot, world, ready.world_scene, ready.poses, ready.target, stage)
        plan = plan_jobs(ready.robot, request.sensors, stage, request.totals)
        deadline = time.monotonic() + request.totals.seconds
        results = render_all(run, plan, request.progress, request.workers, deadline)
        previews = [p for p, _ in results]
        draw_imus(run, previews)
        drawings = [d for _, d in results if d is not None]
        robot_boxes = []
        lowest: tuple[float, str] = (0.0, "")
        for body in world.robot_bodies:
            for index, lo, hi in world.aabbs(body):
                if float(np.max(hi - lo)) > 0.005:
                    robot_boxes.append((lo, hi))
                    if float(lo[2]) < lowest[0]:
                        lowest = (float(lo[2]), world.robot_links.get((body, index), "?"))
    run.placement = placement_note(*lowest)
    return run, previews, drawings, robot_boxes


BELOW_GROUND_M = 0.01  # pybullet's boxes carry a small margin


def placement_note(lowest_z: float, link: str) -> str | None:
    """The line the page shows when the robot, placed with its root link at z = 0, has
    parts below the ground (``lowest_z``: the lowest point, on ``link``)."""
    if lowest_z > -BELOW_GROUND_M:
        return None
    return (
        f"The robot is placed with its root link at z = 0, and parts reach "
        f"{-lowest_z * 1000:.0f}\u00a0mm below the ground (lowest: {link!r}). In Gazebo it "
        "would stand on them: heights above the floor here are that much lower."
    )


def _furnish(world: World, request: _Request, ready: _Ready) -> None:
    """The ground and the scene (the --scene's URDF, whose notes join ``ready.notes``, or
    the default room's shapes), then the robot at its joints."""
    from sensorkit.loading import PackageResolver
    from sensorkit.render.scene import GROUND, Shape
    from sensorkit.render.urdf_out import prepare_urdf

    world_scene, scene = ready.world_scene, request.scene
    ground_half = max(world_scene.half_extent + 1.0, 10.0 if scene is not None else 0.0)
    if scene is not None and ready.scene_robot is not None:
        ground = Shape("ground", GROUND, np.eye(4), (), GROUND)
        world.add_ground(ground_half, world_scene, ground)
        scene_urdf = prepare_urdf(
            ready.scene_robot,
            PackageResolver.from_options(
                list(request.package_paths), near=scene, untrusted=request.untrusted is not None
            ),
            what="scene",
        )
        ready.notes += scene_urdf.notes
        world.add_scene_urdf(scene_urdf.text, world_scene.shapes)
        world_scene.shapes.insert(0, ground)
    else:
        world.add_default_shapes(world_scene, world_scene.half_extent)
    say(request.progress, f"loading {ready.robot.name or 'the robot'} into pybullet")
    world.add_robot_parts(ready.parts, ready.poses)
    world.set_joints(ready.positions)
    world.refresh_bounds()


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
