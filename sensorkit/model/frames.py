"""Where each sensor renders from, and which frame its data is stamped with.

The render pose is the pose of the sensor's reference link composed with the sensor's
``<pose>``. The published frame is the plugin's frame element (classic ``frame_name``,
ROS 1 ``frameName``, less the leading "/" that ROS 1's tf::resolve drops, see
``sensorkit.knowledge.plugins.stamped_frame``) or the gz frame tag the target reads; when
absent, the target's default: classic, the reference link after fixed-joint lumping; gz,
the scoped sensor name (which matches no URDF link).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from sensorkit.knowledge import plugins as known
from sensorkit.knowledge.limits import ANGLE_TOL, POSITION_TOL
from sensorkit.model.targets import is_gz

if TYPE_CHECKING:
    from sensorkit.knowledge.plugins import PluginSpec
    from sensorkit.model.parse import Origin
    from sensorkit.model.robot import Robot
    from sensorkit.model.sdf import Conversion
    from sensorkit.model.sensors import CameraSpec, Plugin, Sensor
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

    def T_render_frame(
        self, robot: Robot, frame: str | None, *, position: bool = True
    ) -> Mat | None:
        """Pose of link ``frame`` seen from the render pose (None if either is unknown).

        For an SDF model, also None when TF's publishers disagree on where the link is
        (:func:`sdf_tf_agrees`); ``position=False``: only its rotation is asked for."""
        if frame is None or frame not in robot.link_map or self.T_world_render is None:
            return None
        if robot.sdf is not None and not sdf_tf_agrees(robot, frame, position=position):
            return None
        if self.link is not None and robot.tree_of(frame) != robot.tree_of(self.link):
            return None  # in another tree (cut off by a joint to a missing link): no relation
        T_world_frame = robot.T_world_link(frame)
        if T_world_frame is None:
            return None
        from sensorkit.model.transforms import relative

        return relative(self.T_world_render, T_world_frame)


SDF_AGREE_TOL = 1e-6  # m and rad: below this two poses of a frame are the same for SK5xx


def sdf_tf_agrees(robot: Robot, link: str, *, position: bool = True) -> bool:
    """Whether TF places the SDF link ``link`` where the SDF does, whoever publishes it.

    robot_state_publisher fed the SDF through sdformat_urdf puts a link at the frame of the
    joint it is the child of ("urdf link pose is the location of the joint having it as
    a child": ros/sdformat_urdf@9cec63e:sdformat_urdf/src/sdformat_urdf.cpp:322-327, the
    joint origins chained between joint frames :221-231); gz-sim's PosePublisher, bridged
    to /tf, publishes the link's own pose (gazebosim/gz-sim@gz-sim8_8.9.0:
    src/systems/pose_publisher/PosePublisher.cc:421-422 names it, :513 its Pose). The two
    agree when the joint's pose in its child link is the identity, as it is when the
    joint writes no <pose>: a joint's pose is relative to its child by default
    (gazebosim/sdformat@sdformat12_12.8.0:src/FrameSemantics.cc:383-387). A link no joint
    hangs is its own frame either way. ``position=False``: only the rotations are compared.
    """
    sm = robot.sdf
    joint = robot.parent_joint.get(link)
    if sm is None or joint is None:
        return True
    from sensorkit.model.transforms import pose_matrix, rotation, rotation_angle, translation

    j = sm.graph.in_frame(joint.name, link)  # the Robot's joint names are scoped vertices
    if j is None:
        return False
    T = pose_matrix(j)
    if rotation_angle(rotation(T)) > SDF_AGREE_TOL:
        return False
    return not position or max(abs(v) for v in translation(T)) <= SDF_AGREE_TOL


# Links farther than this from the origin (or not finite) are outside the grid of
# _links_near and always offered as candidates.
_GRID_LIMIT = 1e9


def _links_near(robot: Robot, tol_m: float) -> tuple[dict[tuple[int, int, int], list[int]], list[int]]:
    """A grid of cells 2 * tol_m wide holding the index (in ``robot.links``) of each link
    that a joint places, by its position; and the links outside any cell. Memoised.
    """
    key = ("links_near", tol_m)
    known: tuple[dict[tuple[int, int, int], list[int]], list[int]] | None = robot.cache.get(key)
    if known is not None:
        return known
    cells: dict[tuple[int, int, int], list[int]] = {}
    outside: list[int] = []
    size = 2.0 * tol_m
    floor = math.floor
    pj = robot.parent_joint
    positions = robot.world_positions()
    lim = _GRID_LIMIT
    for i, lk in enumerate(robot.links):
        if lk.name not in pj:
            continue
        P = positions[lk.name]
        if P is None:
            continue
        x, y, z = P
        if -lim < x < lim and -lim < y < lim and -lim < z < lim:
            cell = (floor(x / size), floor(y / size), floor(z / size))
            bucket = cells.get(cell)
            if bucket is None:
                cells[cell] = [i]
            else:
                bucket.append(i)
        else:
            outside.append(i)
    robot.cache[key] = cells, outside
    return cells, outside


def optical_frame_at(
    robot: Robot,
    T_world_render: Mat | None,
    tol_m: float = POSITION_TOL,
    tol_rad: float = ANGLE_TOL,
) -> str | None:
    """A link already placed as the optical frame of a camera rendering from T_world_render.

    The first such link in document order. Only links near the camera are looked at: the
    grid of :func:`_links_near` offers every link within ``tol_m`` (and more), and each
    candidate is tested as a scan of all links would test it, so the answer is the scan's.
    """
    if T_world_render is None:
        return None
    from sensorkit.model.transforms import R_BODY_OPTICAL, angle_between, rotation

    px, py, pz = T_world_render[0][3], T_world_render[1][3], T_world_render[2][3]
    links = robot.links
    lim = _GRID_LIMIT
    if -lim < px < lim and -lim < py < lim and -lim < pz < lim and 1e-9 < tol_m < lim:
        cells, outside = _links_near(robot, tol_m)
        size = 2.0 * tol_m
        cx, cy, cz = math.floor(px / size), math.floor(py / size), math.floor(pz / size)
        found = list(outside)
        for i in (cx - 1, cx, cx + 1):
            for j in (cy - 1, cy, cy + 1):
                for k in (cz - 1, cz, cz + 1):
                    bucket = cells.get((i, j, k))
                    if bucket is not None:
                        found.extend(bucket)
        found.sort()
        candidates = [links[i].name for i in found]
    else:  # a camera off the grid: every link
        candidates = [lk.name for lk in links if lk.name in robot.parent_joint]
    if not candidates:
        return None
    # angle_between(R_render.T @ R_link, R_BODY_OPTICAL) is the angle of
    # R_link.T @ (R_render @ R_BODY_OPTICAL)
    R_want = rotation(T_world_render) @ R_BODY_OPTICAL
    positions = robot.world_positions()  # the whole pose only of links close enough
    for name in candidates:
        at = positions.get(name)
        if at is None:
            continue
        dx, dy, dz = at[0] - px, at[1] - py, at[2] - pz
        if math.sqrt(dx * dx + dy * dy + dz * dz) > tol_m:
            continue
        P = robot.world_pose(name)
        if P is None:
            continue
        R = ((P[0], P[1], P[2]), (P[3], P[4], P[5]), (P[6], P[7], P[8]))
        if angle_between(R, R_want) <= tol_rad:
            return name
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


def camera_pose(sensor: Sensor, target: str, camera: CameraSpec | None = None) -> Origin | None:
    """The ``<camera><pose>`` the render pose composes on ``target``: ``camera``'s (by
    default the sensor's first camera), or None where there is none or the target never
    reads it.

    Gazebo Classic composes it onto the sensor's pose (``cameraPose = <camera><pose> +
    sensor pose``, ignition::math's ``A + B`` being B then A: gazebo-classic 11.10.2
    gazebo/sensors/CameraSensor.cc:168-172, DepthCameraSensor.cc:110-114,
    MultiCameraSensor.cc:156-159, WideAngleCameraSensor.cc:115-119); Gazebo Sim never reads
    it (gz-sensors8 src/CameraSensor.cc:221 places the camera at the sensor's pose; the
    sources are at ``sensorkit.knowledge.sensor_blocks.CAMERA_POSE_READ``).
    """
    from sensorkit.knowledge.sensor_blocks import CAMERA_POSE_READ

    if not CAMERA_POSE_READ.get(target, False):
        return None
    cam = camera if camera is not None else sensor.camera
    return None if cam is None else cam.pose


def render_pose(
    robot: Robot, sensor: Sensor, target: str, camera: CameraSpec | None = None
) -> Mat | None:
    """T_world_render: the reference link's pose composed with the sensor's ``<pose>`` and,
    on a target that reads it, the camera's ``<camera><pose>`` (:func:`camera_pose`;
    ``camera``: which of a multicamera's cameras, by default the first)."""
    if sensor.reference is None or sensor.reference not in robot.link_map:
        return None
    P = robot.world_pose(sensor.reference)
    if P is None:
        return None
    from sensorkit.model.transforms import compose, pose_matrix

    P = compose(P, sensor.pose.pose())
    extra = camera_pose(sensor, target, camera)
    if extra is not None:
        P = compose(P, extra.pose())
    return pose_matrix(P)


def sensor_frames(
    robot: Robot, sensor: Sensor, target: str, conv: Conversion, *, model: str | None = None
) -> SensorFrames:
    """Compute render pose and published frame of ``sensor`` for ``target``.

    ``model``: the name the robot is spawned under, when a launch file says (the MODEL of
    a gz default frame); else the URDF's robot name stands for it."""
    link = sensor.reference if sensor.reference in robot.link_map else None
    T = render_pose(robot, sensor, target)
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
            published = f"{model or robot.name}::{where}::{sensor.name}"
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
            stamped = known.stamped_frame(spec, value)
            return SensorFrames(sensor, link, T, stamped, name, False, plugin, spec=spec)
    frame = default_frame(spec, plugin, link, conv)
    if robot.sdf is not None and frame is not None and frame == link:
        # gazebo_ros's SensorFrameID: with no frame_name, the parent link's name without its
        # scopes (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_ros/src/utils.cpp:40-61): the
        # scoped name of a nested model's link loses its models.
        frame = frame.rpartition("::")[2]
    return SensorFrames(sensor, link, T, frame, "default", True, plugin, spec=spec)


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
        value = spec.frame_default_value
        return None if value is None else known.stamped_frame(spec, value)
    if spec.frame_default == known.PARAM and spec.frame_default_param:
        value = plugin.param(spec.frame_default_param)
        return None if value is None else known.stamped_frame(spec, value)
    return None
