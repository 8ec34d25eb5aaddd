"""What the sensors of one preview share while they are rendered, and what each job asks of it.

A :class:`Session` holds the robot, the pybullet world, the scene and the link poses
once the world is built; every sensor's job (``camera_job``, ``lidar_job``, ``imu_job``)
reads its render pose, its published frames and its topics from it, and checks where
pybullet put the sensor's link and which frame its data is stamped with.
``shown`` hands back a job's record with its drawing in the overview, and puts data
stamped with a frame that is not where the sensor looks where RViz will show it.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sensorkit.model.transforms_np import Mat, matrix_to_rpy
from sensorkit.render.checks import Check, frame_check, pose_check
from sensorkit.render.result import SensorPreview
from sensorkit.render.svg import hex_colour

if TYPE_CHECKING:
    from sensorkit.model.frames import SensorFrames
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import Sensor
    from sensorkit.render.overview import SensorDrawing
    from sensorkit.render.rviz import Misplaced
    from sensorkit.render.scene import Scene, Shape
    from sensorkit.render.sim import World

__all__ = [
    "JobResult",
    "Progress",
    "Session",
    "open_folder",
    "say",
    "shown",
    "skipped",
    "topics_of",
]

Progress = Callable[[str], None]
# What a sensor's job gives back: its record, and its drawing in the overview (None when
# nothing was rendered).
JobResult = tuple[SensorPreview, "SensorDrawing | None"]


def say(progress: Progress | None, message: str) -> None:
    if progress is not None:
        progress(message)


def _pose_dict(T: Mat) -> dict[str, Any]:
    return {
        "xyz": [float(v) for v in T[:3, 3]],
        "rpy": [float(v) for v in matrix_to_rpy(T[:3, :3])],
        "matrix": [[float(v) for v in row] for row in T],
    }


def topics_of(sensor: Sensor, target: str) -> dict[str, str] | None:
    """Role -> ROS topic (``image``, ``camera_info``, ``scan``...), None when unknown."""
    from sensorkit.describe.sensor_topics import sensor_topics

    topics, _ = sensor_topics(sensor, target)
    return topics or None


class Session:
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
        self.placement: str | None = None  # a line when parts are below the ground
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

    def placement_checks(
        self,
        out: SensorPreview,
        sensor: Sensor,
        T_true: Mat,
        frame: str | None,
        how: str,
        *,
        optical: bool,
    ) -> tuple[Check, tuple[str, Mat] | None]:
        """Add to ``out.checks`` where pybullet puts the sensor's link (when it has one),
        then whether ``frame``, the one its data is stamped with, is ``T_true``, where the
        sensor looks. Gives the frame check, and the stamped frame and its pose when the
        check warns that it is a link elsewhere (the data lands there in RViz)."""
        if sensor.reference is not None:
            out.checks.append(self.pose_check(sensor.reference))
        T_frame = self.poses.get(frame) if frame is not None else None
        sdf = self.robot.sdf is not None
        fcheck = frame_check(T_true, T_frame, frame, how, optical=optical, sdf=sdf)
        out.checks.append(fcheck)
        if fcheck.status == "warn" and T_frame is not None and frame is not None:
            return fcheck, (frame, T_frame)
        return fcheck, None

    def frame_info(self, frames: SensorFrames, T_render: Mat) -> dict[str, Any]:
        return {
            "link": frames.link,
            "render_pose": _pose_dict(T_render),
            "published_frame": frames.published,
            "published_how": frames.how,
            "published_is_default": frames.is_default,
            "camera_frame": frames.camera_frame,
        }


def skipped(out: SensorPreview, why: str) -> JobResult:
    """``out``, not rendered because of ``why``."""
    out.skipped = why
    return out, None


def open_folder(out: SensorPreview, folder: Path) -> Path:
    """Make ``folder``, the sensor's own, and note it in ``out``."""
    folder.mkdir(parents=True, exist_ok=True)
    out.directory = folder
    return folder


def shown(out: SensorPreview, drawing: SensorDrawing, seen: Misplaced | None) -> JobResult:
    """``out`` with its drawing in the overview and its colour noted; with ``seen``, its
    data placed where RViz will put it too."""
    if seen is not None:
        _show_misplaced(out, drawing, seen)
    out.info["colour"] = hex_colour(drawing.colour)
    return out, drawing


def _show_misplaced(out: SensorPreview, drawing: SensorDrawing, seen: Misplaced) -> None:
    """Data stamped with a frame that is not where the sensor looks: put it where RViz
    will, in the overview (magenta) and in rviz.png (from above and from the side)."""
    from sensorkit.render.png import write_png
    from sensorkit.render.rviz import draw_rviz, moved_text

    T_frame = seen.T_world_stamped
    drawing.published_origin = T_frame[:3, 3].copy()
    drawing.published_axis_end = T_frame[:3, 3] + T_frame[:3, seen.axis] * seen.reach
    drawing.published_hits = seen.stamped_world(seen.points)
    if seen.frustum is not None:
        drawing.published_edges = list(seen.stamped_world(seen.frustum))
    assert out.directory is not None
    out.files["rviz_png"] = out.directory / "rviz.png"
    image, panels = draw_rviz(seen, drawing.colour)
    write_png(out.files["rviz_png"], image)
    out.info["rviz"] = seen.to_dict()
    out.info["rviz"]["panels"] = panels
    out.notes.append(
        f"RViz will place this data in {seen.frame!r}, not where the sensor sees it: "
        f"{moved_text(seen)} (rviz.png)"
    )
