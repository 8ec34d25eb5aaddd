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

from sensorkit.knowledge import plugins as known
from sensorkit.model.targets import is_gz

if TYPE_CHECKING:
    from sensorkit.knowledge.plugins import PluginSpec
    from sensorkit.model.robot import Robot
    from sensorkit.model.sdf import Conversion
    from sensorkit.model.sensors import Plugin, Sensor
    from sensorkit.model.transforms import Mat

# Which sensor-level tag each gz version reads for the frame id, first found wins:
# Fortress ignition_frame_id, then gz_frame_id (gazebosim/gz-sensors@ign-sensors6:
# src/Sensor.cc:146-166); Harmonic gz_frame_id only (@gz-sensors8 c8159af:src/Sensor.cc:
# 184-195); Jetty <frame_id>, then the deprecated gz_frame_id with a warning
# (@gz-sensors10 ff8c92b:src/Sensor.cc:181-196). With none, the frame is the sensor's name,
# which gz-sim sets to its scoped name MODEL::LINK::SENSOR
# (gazebosim/gz-sim@gz-sim8:src/rendering/RenderUtil.cc:1719-1721).
GZ_FRAME_TAGS: dict[str, tuple[str, ...]] = {
    "fortress": ("ignition_frame_id", "gz_frame_id"),
    "harmonic": ("gz_frame_id",),
    "jetty": ("frame_id", "gz_frame_id"),
}
# Tags a version still reads but has deprecated.
GZ_DEPRECATED_FRAME_TAGS: dict[str, tuple[str, ...]] = {"jetty": ("gz_frame_id",)}
# Versions that read <camera><optical_frame_id> for image, camera_info and cloud frames.
GZ_OPTICAL_FRAME_ID = ("fortress", "harmonic")


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
    spec: PluginSpec | None = None  # what sensorkit knows of ``plugin`` (None: unknown)

    @property
    def unknown(self) -> bool:
        """A plugin publishes, but sensorkit does not know where it stamps its data."""
        return self.plugin is not None and self.spec is None

    @property
    def camera_frame(self) -> str | None:
        """The frame image data is stamped with."""
        return self.image_frame or self.published

    def T_render_frame(self, robot: Robot, frame: str | None) -> Mat | None:
        """Pose of link ``frame`` seen from the render pose (None if either is unknown)."""
        if frame is None or frame not in robot.link_map or self.T_world_render is None:
            return None
        if self.link is not None and robot.tree_of(frame) != robot.tree_of(self.link):
            return None  # in another tree (cut off by a joint to a missing link): no relation
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


def ros_generation(target: str) -> str:
    """Which plugin table a target reads: "ros1", "ros2" (Gazebo Classic) or "gz"."""
    return "gz" if is_gz(target) else "ros1" if target == "ros1" else "ros2"


def publishing_plugin(sensor: Sensor, target: str) -> tuple[Plugin | None, PluginSpec | None]:
    """The plugin that publishes a sensor's data to ROS under ``target``, and its spec.

    The first sensor-level plugin sensorkit knows for the target's ROS generation; when
    none is known, the first plugin with no spec (its frame cannot be told).
    """
    ros = ros_generation(target)
    for p in sensor.plugins:
        spec = known.lookup(p.filename, ros)
        if spec is not None and spec.level == "sensor":
            return p, spec
    return (sensor.plugins[0], None) if sensor.plugins else (None, None)


def ros_plugin(sensor: Sensor, target: str = "classic") -> Plugin | None:
    """The plugin that publishes a sensor's data to ROS, if any."""
    return publishing_plugin(sensor, target)[0]


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
    if is_gz(target):
        published: str | None = None
        how = "default"
        for tag in GZ_FRAME_TAGS[target]:
            if sensor.frame_tags.get(tag):
                published, how = sensor.frame_tags[tag], tag
                break
        is_default = published is None
        if is_default:
            where = conv.survivor(link) if link else sensor.reference
            published = f"{robot.name}::{where}::{sensor.name}"
        out = SensorFrames(sensor, link, T, published, how, is_default, None)
        cam = sensor.camera
        if cam is not None and cam.optical_frame_id and target in GZ_OPTICAL_FRAME_ID:
            out.image_frame, out.image_how = cam.optical_frame_id, "optical_frame_id"
        return out
    plugin, spec = publishing_plugin(sensor, target)
    if plugin is None:
        return SensorFrames(sensor, link, T, None, "no plugin", True, None)
    if spec is None:
        return SensorFrames(sensor, link, T, None, "unknown plugin", True, plugin)
    for name in spec.frame_params:
        value = plugin.param(name)
        if value:
            return SensorFrames(sensor, link, T, value, name, False, plugin, spec=spec)
    return SensorFrames(
        sensor, link, T, default_frame(spec, plugin, link, conv), "default", True, plugin, spec=spec
    )


def default_frame(
    spec: PluginSpec, plugin: Plugin, link: str | None, conv: Conversion
) -> str | None:
    """The frame a known plugin stamps when none of its frame parameters is given."""
    if spec.frame_default == known.LINK:
        if link is None:
            return None
        return conv.survivor(link) if spec.lumped else link
    if spec.frame_default == known.WORLD:
        return "world"
    if spec.frame_default == known.LITERAL:
        return spec.frame_default_value
    if spec.frame_default == known.PARAM and spec.frame_default_param:
        return plugin.param(spec.frame_default_param)
    return None
