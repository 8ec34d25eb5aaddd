"""Stereo pairs: which two cameras of a robot see as one rig, and how they sit.

:func:`stereo_pairs` finds the pairs among the cameras :func:`sensorkit.describe.sensorinfo.describe`
already modelled (``RobotInfo.stereo_pairs``); the exporters write each pair's Kalibr
camchain, ORB-SLAM3 stereo settings and camera_info files from it. Three shapes are
recognised, each with the right eye at positive x in the left eye's optical frame:

- a Gazebo Classic ``multicamera`` sensor with exactly two cameras and a ROS camera plugin
  that publishes it: ROS 2 ``gazebo_ros_camera`` handles ``MultiCameraSensor``
  (ros-simulation/gazebo_ros_pkgs@ros2:gazebo_plugins/src/gazebo_ros_camera.cpp:160-163) and
  publishes ``<camera_name>/<camera>/image_raw`` (:211-226); ROS 1
  ``gazebo_ros_multicamera`` publishes the cameras whose name contains ``left`` and
  ``right`` (@noetic-devel:gazebo_plugins/src/gazebo_ros_multicamera.cpp:84-94). Gazebo Sim
  never creates a ``multicamera`` (``sensorkit.knowledge.gazebo_sim``), so no pair there;
- two camera sensors named ``<stem>_left`` and ``<stem>_right`` (``left_<stem>``/
  ``right_<stem>`` too), as sensorkit's ``sensorkit_stereo_camera`` macro emits them for
  Classic and Gazebo Sim;
- two camera sensors of one image size where the right one's camera_info carries
  ``P[0][3] = Tx < 0`` (Classic ``<hack_baseline>`` or ``<Tx>``, gz
  ``<lens><projection><tx>``) and the left one sits where that Tx says.

Geometry comes from the robot's kinematics: each eye's optical frame is its render pose
(reference link, sensor ``<pose>``, a multicamera camera's own ``<pose>``) turned to the
optical convention (REP 103), i.e. exactly where its images are rendered from. The
camera_info convention (CameraInfo.msg) is that the right camera of a horizontal pair has
``Tx = -fx' * B`` (ros2/common_interfaces@rolling:sensor_msgs/msg/CameraInfo.msg:93-98).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from sensorkit.model.transforms_np import R_BODY_OPTICAL, Mat, invert

if TYPE_CHECKING:
    from sensorkit.describe.views import CameraView, SensorInfo
    from sensorkit.model.robot import Robot

__all__ = ["StereoPair", "T_world_optical", "stereo_pairs"]

RECTIFIED_TOL_M = 1e-6
"""Largest y/z offset (m) of the right eye in the left eye's frame for a rectified pair."""

RECTIFIED_TOL_RAD = 1e-6
"""Largest angle (rad) between the two optical frames of a rectified pair."""

MAX_VERGENCE_RAD = 0.2
"""Two cameras turned further apart than this (about 11 degrees) are not taken as a pair."""

_SNAP = 1e-12  # entries this close to 0 or +-1 are the float noise of composing poses

# Plugins that publish a multicamera to ROS (sensorkit.knowledge.plugins rows).
_MULTICAMERA_LIBRARIES = frozenset(
    {"gazebo_ros_camera", "gazebo_ros_multicamera", "gazebo_ros_triggered_multicamera"}
)


@dataclass
class StereoPair:
    """Two cameras that form one stereo rig, left and right as seen from behind them.

    ``T_left_right`` is the pose of the right eye's optical frame in the left eye's: it
    maps right-eye coordinates into left-eye ones (ORB-SLAM3's ``Stereo.T_c1_c2``);
    its inverse ``T_right_left`` is Kalibr's ``T_cn_cnm1`` of cam1.
    """

    name: str  # what --sensor picks: the multicamera, the macro's stem, or "left+right"
    left: CameraView
    right: CameraView
    how: str  # multicamera | names | projection Tx
    T_left_right: Mat
    notes: list[str] = field(default_factory=list)

    @property
    def T_right_left(self) -> Mat:
        """The transform that maps left-eye coordinates into the right eye's."""
        return _snap(invert(self.T_left_right))

    @property
    def baseline(self) -> float:
        """Distance between the two optical centres (m), as ORB-SLAM3 takes it from
        ``Stereo.T_c1_c2`` (UZ-SLAMLab/ORB_SLAM3@src/Settings.cc:347)."""
        return math.hypot(*self.T_left_right[:3, 3])

    @property
    def rectified(self) -> bool:
        """Parallel optical axes and the right eye straight along the left eye's x."""
        t = self.T_left_right[:3, 3]
        R = self.T_left_right[:3, :3]
        return (
            float(t[0]) > 0.0
            and abs(float(t[1])) <= RECTIFIED_TOL_M
            and abs(float(t[2])) <= RECTIFIED_TOL_M
            and float(np.abs(R - np.eye(3)).max()) <= RECTIFIED_TOL_RAD
        )

    @property
    def aliases(self) -> tuple[str, ...]:
        """Every name ``--sensor`` accepts for the pair."""
        return (self.name, f"{self.left.id}+{self.right.id}")


def _snap(T: Mat) -> Mat:
    out = np.array(T, dtype=np.float64)
    out[np.abs(out) < _SNAP] = 0.0
    for one in (1.0, -1.0):
        out[np.abs(out - one) < _SNAP] = one
    out[3] = (0.0, 0.0, 0.0, 1.0)
    return out


def T_world_optical(robot: Robot, view: CameraView, target: str) -> Mat | None:
    """Where ``view``'s images are rendered from on ``target``, as an optical frame (z
    forward, x right, y down) in the root link's frame; ``None`` when the sensor is not on
    a known link. The camera's own ``<pose>`` (a multicamera's cameras have one each)
    counts where the target reads it (:func:`sensorkit.model.frames.camera_pose`)."""
    from sensorkit.model.frames_np import render_pose_np

    T = render_pose_np(robot, view.sensor, target, view.spec)
    if T is None:
        return None
    T_render_optical = np.eye(4)
    T_render_optical[:3, :3] = R_BODY_OPTICAL
    out: Mat = T @ T_render_optical
    return out


def _relative(robot: Robot, a: CameraView, b: CameraView, target: str) -> Mat | None:
    """``T_a_b``: camera b's optical frame in camera a's."""
    Ta, Tb = T_world_optical(robot, a, target), T_world_optical(robot, b, target)
    if Ta is None or Tb is None:
        return None
    return _snap(invert(Ta) @ Tb)


def _angle(R: Mat) -> float:
    c = (float(np.trace(R)) - 1.0) / 2.0
    return math.acos(max(-1.0, min(1.0, c)))


def _side_by_side(T_a_b: Mat) -> bool:
    """b sits to the right of a (positive x in a's optical frame), axes near-parallel."""
    return float(T_a_b[0, 3]) > 0.0 and _angle(T_a_b[:3, :3]) <= MAX_VERGENCE_RAD


def _stem(left: str, right: str) -> str | None:
    """``front`` for ``front_left``/``front_right`` (and ``left_front``/``right_front``)."""
    for sep in ("_", "-", "/", ""):
        if left.endswith(sep + "left") and right.endswith(sep + "right"):
            a, b = left[: -len(sep + "left")], right[: -len(sep + "right")]
            if a == b and a:
                return a
        if left.startswith("left" + sep) and right.startswith("right" + sep):
            a, b = left[len("left" + sep) :], right[len("right" + sep) :]
            if a == b and a:
                return a
    return None


def _ros_multicamera(target: str, views: list[CameraView]) -> bool:
    from sensorkit.model.frames import ros_plugin
    from sensorkit.model.targets import is_gz

    if is_gz(target) or len(views) != 2:
        return False
    plugin = ros_plugin(views[0].sensor, target)
    return plugin is not None and plugin.library in _MULTICAMERA_LIBRARIES


def _order(
    robot: Robot, a: CameraView, b: CameraView, target: str
) -> tuple[CameraView, CameraView, Mat] | None:
    """``(left, right, T_left_right)`` from where the two sit, or None when they do not
    sit side by side."""
    T_a_b = _relative(robot, a, b, target)
    if T_a_b is None:
        return None
    if _side_by_side(T_a_b):
        return a, b, T_a_b
    T_b_a = _snap(invert(T_a_b))
    if _side_by_side(T_b_a):
        return b, a, T_b_a
    return None


def _eye_word(view: CameraView) -> str | None:
    name = (view.spec.name or "").lower()
    if "left" in name and "right" not in name:
        return "left"
    if "right" in name and "left" not in name:
        return "right"
    return None


def _pair_notes(target: str, pair: StereoPair) -> None:
    """What the simulator's own camera_info says that the pair's files do not."""
    left, right = pair.left.intrinsics, pair.right.intrinsics
    b = pair.baseline
    if not pair.rectified:
        t = pair.T_left_right[:3, 3]
        pair.notes.append(
            f"not a rectified pair (right eye at x {t[0]:+.6g}, y {t[1]:+.6g}, z {t[2]:+.6g} m, "
            f"turned {_angle(pair.T_left_right[:3, :3]):.3g} rad in the left eye's frame): "
            "only the Kalibr and ORB-SLAM3 v1.0 files, which carry the whole transform"
        )
    if right is not None:
        published = right.baseline
        if published <= 0.0:
            pair.notes.append(
                f"{pair.right.id}'s camera_info has no Tx (P[0][3] = 0): consumers of the "
                f"simulator's camera_info see no baseline; the eyes are {b:.6g} m apart"
            )
        elif abs(published - b) > RECTIFIED_TOL_M:
            pair.notes.append(
                f"{pair.right.id}'s camera_info says the baseline is {published:.6g} m "
                f"(P[0][3] = {right.baseline_tx:.6g}) but the eyes are {b:.6g} m apart: the "
                "pair's files use the kinematics; fix <hack_baseline>/<Tx> (Classic) or "
                "<lens><projection><tx> (gz) to agree"
            )
    # ROS 1's multicamera forces the left eye's baseline to 0 (gazebo_ros_multicamera.cpp:84-88);
    # ROS 2's gazebo_ros_camera reads <hack_baseline> once per camera, left included
    # (gazebo_ros_camera.cpp:358, :399, :458).
    if left is not None and left.baseline_tx != 0.0 and target != "ros1":
        pair.notes.append(
            f"{pair.left.id}'s camera_info carries P[0][3] = {left.baseline_tx:.6g} too "
            "(gazebo_ros_camera applies <hack_baseline> to every camera of a multicamera): "
            "the pair's files give the left eye Tx 0"
        )
    if pair.left.frame is not None and pair.left.frame == pair.right.frame:
        pair.notes.append(
            f"both eyes are stamped {pair.left.frame!r}: TF cannot place them apart; the "
            "pair's files take each eye's pose from where it renders"
        )


def stereo_pairs(robot: Robot, target: str, sensors: Sequence[SensorInfo]) -> list[StereoPair]:
    """The stereo pairs among the cameras of ``sensors`` (see the module docstring), in
    sensor order. A camera belongs to one pair at most."""
    pairs: list[StereoPair] = []
    used: set[str] = set()
    cameras = [c for s in sensors for c in s.cameras]

    def add(name: str, left: CameraView, right: CameraView, how: str, T: Mat) -> None:
        pair = StereoPair(name, left, right, how, T)
        _pair_notes(target, pair)
        pairs.append(pair)
        used.update((left.id, right.id))

    # 1. multicamera sensors with two cameras and a ROS plugin
    for s in sensors:
        if s.sensor.kind != "multicamera" or not _ros_multicamera(target, s.cameras):
            continue
        a, b = s.cameras
        ordered = _order(robot, a, b, target)
        if ordered is None:
            s.notes.append("its two cameras do not sit side by side: not exported as a pair")
            continue
        left, right, T = ordered
        add(s.name, left, right, "multicamera", T)
        if _eye_word(left) == "right" or _eye_word(right) == "left":
            pairs[-1].notes.append(
                f"camera {left.spec.name!r} sits to the left of {right.spec.name!r}, "
                "whatever their names say: the pair follows where they are"
            )

    mono = [c for c in cameras if c.sensor.kind == "camera"]
    names = {s.name for s in sensors} | {c.id for c in cameras}
    notes_of = {s.name: s.notes for s in sensors}

    # 2. <stem>_left / <stem>_right camera sensors (sensorkit's stereo macro)
    for lcam in mono:
        for rcam in mono:
            if lcam.id in used or rcam.id in used or lcam is rcam:
                continue
            stem = _stem(lcam.sensor.name, rcam.sensor.name)
            if stem is None:
                continue
            T_named = _relative(robot, lcam, rcam, target)
            if T_named is None or not _side_by_side(T_named):
                notes_of[rcam.sensor.name].append(
                    f"named as the right eye of {lcam.sensor.name!r} but does not sit side by "
                    "side to its right: not exported as a stereo pair"
                )
                continue
            name = stem if stem not in names else f"{lcam.id}+{rcam.id}"
            add(name, lcam, rcam, "names", T_named)

    # 3. a right eye whose camera_info carries Tx < 0, and the camera where Tx puts its left
    for rcam in mono:
        intr = rcam.intrinsics
        if rcam.id in used or intr is None or not intr.baseline_tx < 0.0:
            continue
        where = np.array([intr.baseline, 0.0, 0.0])
        best: tuple[float, CameraView, Mat] | None = None
        for lcam in mono:
            li = lcam.intrinsics
            if lcam is rcam or lcam.id in used or li is None:
                continue
            if (li.width, li.height) != (intr.width, intr.height) or li.baseline_tx != 0.0:
                continue
            T_tx = _relative(robot, lcam, rcam, target)
            if T_tx is None or not _side_by_side(T_tx):
                continue
            miss = float(np.linalg.norm(T_tx[:3, 3] - where))
            if best is None or miss < best[0]:
                best = (miss, lcam, T_tx)
        if best is not None:
            add(f"{best[1].id}+{rcam.id}", best[1], rcam, "projection Tx", best[2])
    order = {c.id: i for i, c in enumerate(cameras)}
    pairs.sort(key=lambda p: order[p.left.id])
    return pairs
