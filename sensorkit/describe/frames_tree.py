"""A robot's TF tree as its sensors and Gazebo see it: the facts behind ``sensorkit frames``.

Every link, from each root down in the order the joints are written (as urdfdom's
``check_urdf`` walks it), with what concerns sensors:

- the sensors whose ``<gazebo reference>`` is the link (the frame a sensor is on);
- the frames each sensor's data is stamped with: ``SensorInfo.frame`` and its cameras'
  ``CameraView.frame`` from :func:`sensorkit.describe.sensorinfo.describe`, the same
  frames ``sensorkit topics`` lists (a stamped frame that is no link of the tree, such as
  Gazebo Sim's scoped default ``MODEL::LINK::SENSOR``, is kept on the sensor);
- optical frames: the link placed as a camera's optical frame at its render pose
  (:func:`sensorkit.model.frames.optical_frame_at`, what SK502 and SK503 compare with);
- what Gazebo's URDF-to-SDF conversion does to the link (:func:`sensorkit.model.sdf.convert`,
  sdformat ``parser_urdf.cc``, which Gazebo Classic and Gazebo Sim both load URDF with):
  a fixed joint's child is lumped into its parent unless the joint's gazebo block sets
  ``preserveFixedJoint`` or ``disableFixedJointLumping``, and never into a parent named
  ``world`` (ReduceFixedJoints and FixedJointShouldBeReduced: gazebosim/sdformat@sdf9
  (9ee2d4f), Gazebo 11's, src/parser_urdf.cc:398-420 and :3381-3391; the same code in
  @sdf12 (b9417e5) :407-421, :3456 for Fortress and @sdf14 (8512585) :410-424, :3471
  for Harmonic); a surviving link with no mass is dropped with everything below it
  (@sdf9 :2658). ``robot_state_publisher`` still publishes every link: lumping changes
  which link Gazebo attaches sensors to (a plugin's default frame, a gz scoped name), not
  the TF tree.

:func:`frame_tree` builds a :class:`FrameTree`; the CLI formats it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from sensorkit.describe.sensorinfo import RobotInfo
    from sensorkit.describe.views import SensorInfo
    from sensorkit.model.robot import Robot
    from sensorkit.model.sdf import Conversion

__all__ = ["Frame", "FrameTree", "SensorFrame", "Stamp", "frame_tree", "simulator_name"]


@dataclass(frozen=True)
class Stamp:
    """One frame a sensor's data is stamped with (header.frame_id)."""

    frame: str
    data: str  # "all": every message of the sensor; "images": its image data only
    how: str  # where the name comes from: frame_name, gz_frame_id, optical_frame_id, default
    in_tree: bool  # the frame is a link of the robot


@dataclass
class SensorFrame:
    """A sensor: the link it is on, the plugin that publishes it, the frames it stamps."""

    name: str
    type: str
    reference: str | None  # its <gazebo reference> as written
    link: str | None  # that reference when it is a link
    plugin: str | None  # the publishing plugin's filename (None on Gazebo Sim, or none)
    stamps: list[Stamp] = field(default_factory=list)
    note: str | None = None  # why it has no frame sensorkit can name
    # True only when nothing publishes its data (no plugin, no model-level plugin reading
    # it); a plugin whose frame sensorkit cannot tell still stamps one
    stamps_nothing: bool = False
    camera: bool = False
    optical: str | None = None  # a camera: the link placed as its optical frame, if any


@dataclass
class Frame:
    """One link of the tree, or the missing parent a joint names."""

    name: str
    parent: str | None
    joint: str | None  # the joint from the parent
    joint_type: str | None
    children: list[str] = field(default_factory=list)  # in the order the joints are written
    sensors: list[str] = field(default_factory=list)  # sensors on this link
    stamped_by: list[str] = field(default_factory=list)  # sensors whose data is stamped here
    optical_for: list[str] = field(default_factory=list)  # cameras it is the optical frame of
    lumped_into: str | None = None  # Gazebo merges it into this link
    kept: bool = False  # a fixed joint from the parent whose gazebo block disables lumping
    dropped_by: str | None = None  # Gazebo does not model it: this link has no mass
    missing: bool = False  # named by a joint as parent, but no <link> has the name


@dataclass
class FrameTree:
    """The whole tree of one robot under one target."""

    robot: str
    target: str
    target_reason: str
    simulator: str  # "Gazebo Classic", "Gazebo Harmonic", ...
    roots: list[str]  # tree tops, each walked in ``order``
    frames: dict[str, Frame]
    order: list[tuple[str, int]]  # (frame, depth) in check_urdf's walk
    sensors: list[SensorFrame]
    unreached: list[str] = field(default_factory=list)  # links on a cycle of joints

    @property
    def lumped(self) -> list[str]:
        return [f.name for f in self.frames.values() if f.lumped_into is not None]

    @property
    def optical(self) -> list[str]:
        return [f.name for f in self.frames.values() if f.optical_for]


def simulator_name(target: str) -> str:
    """The simulator a target runs in: Gazebo Classic, or Gazebo Fortress/Harmonic/Jetty."""
    from sensorkit.knowledge.gazebo_sim import gz_version
    from sensorkit.model.targets import is_gz

    return f"Gazebo {gz_version(target)}" if is_gz(target) else "Gazebo Classic"


def _frames(robot: Robot, conv: Conversion) -> dict[str, Frame]:
    """A :class:`Frame` per link (document order), then per missing parent, with what the
    conversion does to it."""
    frames: dict[str, Frame] = {}
    for lk in robot.links:
        if lk.name in frames:
            continue
        joint = robot.parent_joint.get(lk.name)
        frames[lk.name] = Frame(
            lk.name,
            joint.parent if joint is not None else None,
            joint.name if joint is not None else None,
            joint.type if joint is not None else None,
        )
    for joint in robot.joints:
        child, parent = joint.child, joint.parent
        if child is None or parent is None or robot.parent_joint.get(child) is not joint:
            continue
        if child not in frames:
            continue  # a joint to a missing link adds no frame
        if parent not in frames:
            frames[parent] = Frame(parent, None, None, None, missing=True)
        frames[parent].children.append(child)
    for f in frames.values():
        if f.missing:
            continue
        if conv.is_lumped(f.name):
            f.lumped_into = conv.survivor(f.name)
        f.kept = f.joint_type == "fixed" and f.joint in conv.preserved_joints
        f.dropped_by = conv.dropped.get(f.name)
    return frames


def _walk(frames: dict[str, Frame]) -> tuple[list[str], list[tuple[str, int]], list[str]]:
    """``(roots, order, unreached)``: depth first from each frame without a parent, children
    in written order; links no walk reaches (a cycle of joints) last."""
    roots = [f.name for f in frames.values() if f.parent is None or f.parent not in frames]
    order: list[tuple[str, int]] = []
    seen: set[str] = set()
    for root in roots:
        stack = [(root, 0)]
        while stack:
            name, depth = stack.pop()
            if name in seen:
                continue
            seen.add(name)
            order.append((name, depth))
            stack.extend((c, depth + 1) for c in reversed(frames[name].children))
    unreached = [name for name in frames if name not in seen]
    return roots, order, unreached


def _stamps(info: SensorInfo, robot: Robot) -> list[Stamp]:
    """The frames ``info``'s data is stamped with, as ``sensorkit topics`` shows them."""
    out: list[Stamp] = []
    if info.frame is not None:
        out.append(Stamp(info.frame, "all", info.frame_how, info.frame in robot.link_map))
    for view in info.cameras:
        frame = view.frame
        if frame is None or any(s.frame == frame for s in out):
            continue
        how = "optical_frame_id" if info.frame is not None else info.frame_how
        out.append(Stamp(frame, "images", how, frame in robot.link_map))
    return out


def _sensor(info: SensorInfo, robot: Robot, target: str) -> SensorFrame:
    from sensorkit.model.frames import publishing_plugin
    from sensorkit.model.targets import is_gz

    sensor = info.sensor
    plugin = None if is_gz(target) else publishing_plugin(sensor, target)[0]
    out = SensorFrame(
        sensor.name,
        sensor.type,
        sensor.reference,
        info.link,
        plugin.filename if plugin is not None else None,
        _stamps(info, robot),
        camera=sensor.is_camera,
    )
    if not out.stamps:
        out.note, out.stamps_nothing = _no_stamp(info, robot, target, out.plugin)
    return out


def _no_stamp(info: SensorInfo, robot: Robot, target: str, plugin: str | None) -> tuple[str, bool]:
    """Why a sensor has no frame sensorkit can name, and whether its data is stamped at all:
    only a sensor no plugin publishes (and no model-level plugin reads) stamps nothing; a
    plugin sensorkit does not know, or whose frame it cannot tell, still stamps a frame."""
    from sensorkit.model.owners import sensor_owner

    if info.frame_how == "no plugin":
        owner = sensor_owner(robot, info.sensor, target)
        if owner is not None:
            return f"{owner.how}; sensorkit does not know the frame it stamps", False
        return "no plugin publishes it to ROS", True
    if info.frame_how == "unknown plugin":
        return f"sensorkit does not know where {plugin} stamps its data", False
    return "its frame cannot be told", False


def frame_tree(info: RobotInfo) -> FrameTree:
    """The TF tree of ``info``'s robot, with its sensors' frames, under ``info``'s target."""
    from sensorkit.model.frames import optical_frame_at, render_pose
    from sensorkit.model.sdf import convert

    robot = info.robot
    frames = _frames(robot, convert(robot))
    roots, order, unreached = _walk(frames)
    sensors: list[SensorFrame] = []
    for s in info.sensors:
        entry = _sensor(s, robot, info.target)
        sensors.append(entry)
        if entry.link is not None:
            frames[entry.link].sensors.append(entry.name)
        for stamp in entry.stamps:
            hit = frames.get(stamp.frame) if stamp.in_tree else None
            if hit is not None and entry.name not in hit.stamped_by:
                hit.stamped_by.append(entry.name)
        if s.sensor.is_camera:
            optical = optical_frame_at(robot, render_pose(robot, s.sensor, info.target))
            if optical is not None and optical in frames:
                frames[optical].optical_for.append(entry.name)
                entry.optical = optical
    return FrameTree(
        robot=robot.name,
        target=info.target,
        target_reason=info.target_reason,
        simulator=simulator_name(info.target),
        roots=roots,
        frames=frames,
        order=order,
        sensors=sensors,
        unreached=unreached,
    )
