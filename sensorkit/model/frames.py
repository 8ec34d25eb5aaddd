"""Where each sensor renders from, and which frame its data is stamped with.

The render pose is the pose of the sensor's reference link composed with the sensor's
``<pose>``. The published frame is the plugin's frame element (classic ``frame_name``,
ROS 1 ``frameName``) or the gz frame tag the target reads; when absent, the target's
default: classic, the reference link after fixed-joint lumping; gz, the scoped sensor
name (which matches no URDF link).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from sensorkit.model.targets import is_gz

if TYPE_CHECKING:
    from sensorkit.model.robot import Robot
    from sensorkit.model.sdf import Conversion
    from sensorkit.model.sensors import Plugin, Sensor
    from sensorkit.model.transforms import Mat

# Which sensor-level tag each gz version reads for the frame id, in order.
GZ_FRAME_TAGS: dict[str, tuple[str, ...]] = {
    "fortress": ("ignition_frame_id", "gz_frame_id"),
    "harmonic": ("gz_frame_id",),
    "jetty": ("frame_id",),
}
# Versions that read <camera><optical_frame_id> for image, camera_info and cloud frames.
GZ_OPTICAL_FRAME_ID = ("fortress", "harmonic")

ROS_SENSOR_PLUGINS = {
    "gazebo_ros_camera",
    "gazebo_ros_ray_sensor",
    "gazebo_ros_imu_sensor",
    "gazebo_ros_depth_camera",
    "gazebo_ros_openni_kinect",
    "gazebo_ros_multicamera",
    "gazebo_ros_laser",
    "gazebo_ros_gpu_laser",
    "gazebo_ros_block_laser",
    "gazebo_ros_range",
    "gazebo_ros_imu",
    "gazebo_ros_velodyne_laser",
    "gazebo_ros_velodyne_gpu_laser",
    "gazebo_ros_triggered_camera",
    "gazebo_ros_gps_sensor",
}


@dataclass
class SensorFrames:
    """A sensor's render pose and published frame under one target."""

    sensor: Sensor
    link: str | None  # the link the sensor is attached to (its <gazebo reference>)
    T_world_render: Mat | None
    published: str | None  # frame name stamped on the data (None: publishes nothing)
    how: str  # where the name came from: "frame_name", "gz_frame_id", "default", ...
    is_default: bool
    plugin: Plugin | None
    image_frame: str | None = None  # gz <optical_frame_id> overrides for image data
    image_how: str | None = None

    @property
    def camera_frame(self) -> str | None:
        """The frame image data is stamped with."""
        return self.image_frame or self.published

    def T_render_frame(self, robot: Robot, frame: str | None) -> Mat | None:
        """Pose of link ``frame`` seen from the render pose (None if either is unknown)."""
        if frame is None or frame not in robot.link_map or self.T_world_render is None:
            return None
        T_world_frame = robot.T_world_link(frame)
        if T_world_frame is None:
            return None
        from sensorkit.model.transforms import invert

        out: Mat = invert(self.T_world_render) @ T_world_frame
        return out


def optical_frame_at(
    robot: Robot, T_world_render: Mat | None, tol_m: float = 1e-3, tol_rad: float = 0.0087
) -> str | None:
    """A link already placed as the optical frame of a camera rendering from T_world_render."""
    if T_world_render is None:
        return None
    import numpy as np

    from sensorkit.model.transforms import R_BODY_OPTICAL, angle_between

    for lk in robot.links:
        if lk.name not in robot.parent_joint:
            continue
        T = robot.T_world_link(lk.name)
        if T is None or float(np.linalg.norm(T[:3, 3] - T_world_render[:3, 3])) > tol_m:
            continue
        if angle_between(T_world_render[:3, :3].T @ T[:3, :3], R_BODY_OPTICAL) <= tol_rad:
            return lk.name
    return None


def ros_plugin(sensor: Sensor) -> Plugin | None:
    """The plugin that publishes a classic sensor's data to ROS, if any."""
    for p in sensor.plugins:
        if p.library in ROS_SENSOR_PLUGINS or p.library.startswith("gazebo_ros"):
            return p
    return sensor.plugins[0] if sensor.plugins else None


def render_pose(robot: Robot, sensor: Sensor) -> Mat | None:
    """T_world_render: the reference link's pose composed with the sensor's ``<pose>``."""
    if sensor.reference is None or sensor.reference not in robot.link_map:
        return None
    T = robot.T_world_link(sensor.reference)
    if T is None:
        return None
    out: Mat = T @ sensor.pose.matrix()
    return out


def sensor_frames(robot: Robot, sensor: Sensor, target: str, conv: Conversion) -> SensorFrames:
    """Compute render pose and published frame of ``sensor`` for ``target``."""
    link = sensor.reference if sensor.reference in robot.link_map else None
    T = render_pose(robot, sensor)
    default = conv.survivor(link) if link else None
    if is_gz(target):
        published: str | None = None
        how = "default"
        for tag in GZ_FRAME_TAGS[target]:
            if sensor.frame_tags.get(tag):
                published, how = sensor.frame_tags[tag], tag
                break
        is_default = published is None
        if is_default:
            published = f"{robot.name}/{link or sensor.reference}/{sensor.name}"
        out = SensorFrames(sensor, link, T, published, how, is_default, None)
        cam = sensor.camera
        if cam is not None and cam.optical_frame_id and target in GZ_OPTICAL_FRAME_ID:
            out.image_frame, out.image_how = cam.optical_frame_id, "optical_frame_id"
        return out
    plugin = ros_plugin(sensor)
    if plugin is None:
        return SensorFrames(sensor, link, T, None, "no plugin", True, None)
    names: tuple[str, ...] = ("frameName",) if target == "ros1" else ("frame_name",)
    if target == "ros1":
        names = ("frameName", "frame_name") if plugin.library == "gazebo_ros_imu_sensor" else names
        if plugin.library in ("gazebo_ros_imu",):
            names = ("frameName", "bodyName")
    for name in names:
        value = plugin.param(name)
        if value:
            return SensorFrames(sensor, link, T, value, name, False, plugin)
    return SensorFrames(sensor, link, T, default, "default", True, plugin)
