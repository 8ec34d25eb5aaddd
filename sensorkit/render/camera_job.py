"""One camera of a preview: render it, write its files, check it, draw it in the overview.

``render_camera_job`` renders what the simulator renders (``sensorkit.render.camera``),
writes rgb.png, camera_info.yaml and, for a depth camera, depth.npy and a labelled
depth.png, notes the frames, intrinsics and topics summary.json shows, checks the image
against the scene's exact geometry (markers, flat surfaces) and the robot's frames, and
gives the camera's drawing for overview.png: its edge rays along the middle row.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from sensorkit.render.checks import self_occlusion_check
from sensorkit.render.result import SensorPreview
from sensorkit.render.session import open_folder, say, shown, skipped, topics_of

if TYPE_CHECKING:
    from pathlib import Path

    from sensorkit.describe.intrinsics import Intrinsics
    from sensorkit.model.sensors import CameraSpec, Sensor
    from sensorkit.render.camera import RenderCamera
    from sensorkit.render.overview import SensorDrawing
    from sensorkit.render.plan import Job
    from sensorkit.render.session import JobResult, Progress, Session
    from sensorkit.render.sim import CameraImage

__all__ = ["render_camera_job"]

Depth = npt.NDArray[np.float32]


def render_camera_job(run: Session, job: Job, progress: Progress | None) -> JobResult:
    """Render ``job``'s camera into its folder, check it, and draw it in the overview."""
    from sensorkit.describe.intrinsics import InvalidValue
    from sensorkit.describe.published import published_intrinsics
    from sensorkit.model.frames import camera_pose
    from sensorkit.render.camera import depth_from_buffer, render_camera
    from sensorkit.render.png import write_png

    sensor, name, cam = job.sensor, job.name, job.cam
    assert cam is not None
    out = SensorPreview.of(sensor, name)
    T_render = run.T_world_render(sensor)
    if T_render is None:
        return skipped(out, f"its reference link {sensor.reference!r} is not a link of the robot")
    extra = camera_pose(sensor, run.target, cam)  # <camera><pose>, where the target reads it
    if extra is not None:
        T_render = T_render @ extra.matrix()
    try:
        published, notes = published_intrinsics(sensor, cam, run.target)
    except InvalidValue as exc:
        return skipped(out, f"not a pinhole camera sensorkit can render: {exc}")
    out.notes += notes
    rc = render_camera(sensor, cam, run.target, T_render, published)
    say(progress, f"rendering {name} ({rc.width}x{rc.height})")
    image = run.world.render(rc.width, rc.height, rc.view_matrix(), rc.projection_matrix())
    depth = depth_from_buffer(image.depth_buffer, rc.near, rc.far)
    folder = open_folder(out, job.folder)
    out.files["rgb"] = folder / "rgb.png"
    write_png(out.files["rgb"], image.rgb)
    if sensor.is_depth:
        _write_depth(out, folder, sensor, cam, run.target, rc, depth)
    _write_camera_info(out, folder, sensor, published)

    frames = run.frames(sensor)
    out.info["frames"] = run.frame_info(frames, T_render)
    out.info["intrinsics"] = _intrinsics(published, rc)
    out.info["topics"] = _topics(sensor, cam, run.target)
    _image_checks(run, out, rc, image, depth, published)
    how = frames.image_how or frames.how
    _, stamped = run.placement_checks(
        out, sensor, rc.T_world_optical, frames.camera_frame, how, optical=True
    )

    drawing, axis_len = _drawing(run, job, rc, depth)
    seen = None
    if stamped is not None:
        from sensorkit.render.rviz import Misplaced, camera_points

        frame, T_frame = stamped
        pts, corners = camera_points(depth, rc.fx, rc.fy, rc.cx, rc.cy, rc.skew, axis_len)
        seen = Misplaced(frame, rc.T_world_optical, T_frame, pts, 2, axis_len, corners)
    return shown(out, drawing, seen)


def _write_depth(
    out: SensorPreview,
    folder: Path,
    sensor: Sensor,
    cam: CameraSpec,
    target: str,
    rc: RenderCamera,
    depth: Depth,
) -> None:
    """depth.npy as published (+inf past the far clip, -inf nearer than the near one) and
    depth.png, labelled."""
    from sensorkit.describe.published import depth_range
    from sensorkit.render._files import save_npy
    from sensorkit.render.pictures import (
        at_far_clip,
        depth_colour_range,
        depth_figure,
        depth_percentiles,
    )
    from sensorkit.render.png import write_png
    from sensorkit.render.raster import colourise_depth

    near, far, depth_notes = depth_range(sensor, cam, target)
    out.notes += depth_notes
    published_depth = depth.copy()
    published_depth[published_depth > far] = np.inf
    published_depth[published_depth < near] = -np.inf
    out.files["depth"] = folder / "depth.npy"
    save_npy(out.files["depth"], published_depth.astype(np.float32))
    out.files["depth_png"] = folder / "depth.png"
    shown_depth = np.where(at_far_clip(published_depth, far), np.inf, published_depth)
    used = depth_percentiles(shown_depth, far)
    lo, hi = depth_colour_range(shown_depth, near, far, used)
    png = write_png(out.files["depth_png"], colourise_depth(shown_depth, lo=lo, hi=hi))
    out.add_figure(depth_figure(png, rc.width, rc.height, lo, hi, near, far, percentiles=used))


def _write_camera_info(
    out: SensorPreview, folder: Path, sensor: Sensor, published: Intrinsics
) -> None:
    """camera_info.yaml, named as the sensor's ROS plugin names the camera."""
    from sensorkit.base.atomic import write_text
    from sensorkit.exporters import camera_info_yaml
    from sensorkit.model.frames import ros_plugin

    camera_name = None
    plugin = ros_plugin(sensor)
    if plugin is not None:
        camera_name = plugin.param("camera_name") or plugin.param("cameraName")
    out.files["camera_info"] = folder / "camera_info.yaml"
    write_text(
        out.files["camera_info"],
        camera_info_yaml(published, camera_name=camera_name or sensor.name),
        fsync=False,
    )


def _intrinsics(published: Intrinsics, rc: RenderCamera) -> dict[str, Any]:
    """camera_info's intrinsics, with those the simulator renders (0-based)."""
    from sensorkit.exporters import camera_dict
    from sensorkit.render.camera import PIXEL_ORIGIN

    return camera_dict(
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


def _topics(sensor: Sensor, cam: CameraSpec, target: str) -> dict[str, str] | None:
    """The camera's topics; of a multicamera, this camera's share ("left/image" -> "image")."""
    topics = topics_of(sensor, target)
    if topics and sensor.kind == "multicamera":
        prefix = f"{cam.name}/"
        topics = {k[len(prefix) :]: v for k, v in topics.items() if k.startswith(prefix)} or None
    return topics


def _image_checks(
    run: Session,
    out: SensorPreview,
    rc: RenderCamera,
    image: CameraImage,
    depth: Depth,
    published: Intrinsics,
) -> None:
    """The image against the scene's exact geometry: markers through camera_info's K,
    depth on flat surfaces; the robot in view; ORB features enough for ORB-SLAM3."""
    from sensorkit.render.camera import depth_check, orb_check, reprojection_check

    out.checks.append(reprojection_check(rc, image, published, run.markers))
    out.checks.append(depth_check(rc, image, depth, run.world.shape_of))
    out.checks.append(self_occlusion_check(image.body, image.link, run.world.robot_links, "pixels"))
    out.checks.append(orb_check(image.rgb, out.kind))


def _drawing(run: Session, job: Job, rc: RenderCamera, depth: Depth) -> tuple[SensorDrawing, float]:
    """The camera in the overview: its optical axis and its edge rays along the middle
    row, as far as they reach; and the axis's length."""
    from sensorkit.render.overview import SensorDrawing

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
        job.name,
        job.colour,
        origin,
        origin + rc.T_world_optical[:3, 2] * axis_len,
        [end(0), end(1)],
    )
    return drawing, axis_len
