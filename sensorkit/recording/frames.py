"""The frames of a recording against the description: SK803, SK804 and SK805.

- SK803: each topic's ``header.frame_id`` (the sampled messages') is the frame the
  description predicts. A camera stamped in a frame that is not optical gets SK502's own
  explanation (:func:`sensorkit.lint.rules.frames.not_optical`), the frame's rotation
  taken from the description, else from the recorded TF.
- SK804: that frame is in the recorded ``/tf`` or ``/tf_static``.
- SK805: the recorded transform from each sensor's frames (the frames its topics are
  stamped with, and the link it hangs off) to the parent link of its fixed joint agrees
  with the joint within 1 mm and 0.5 degree (SK503's and SK502's tolerances); a camera
  frame whose recorded rotation is not optical is explained as SK502 explains it.
"""

from __future__ import annotations

import math
from collections import Counter
from typing import TYPE_CHECKING

import numpy as np

from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.knowledge.limits import ANGLE_TOL, POSITION_TOL
from sensorkit.lint.rules.optical_text import not_optical
from sensorkit.model.targets import is_gz
from sensorkit.model.transforms import R_BODY_OPTICAL, angle_between, matrix_to_rpy
from sensorkit.model.transforms import Mat as Mat3
from sensorkit.recording.data import finding
from sensorkit.recording.tf import frame_name

if TYPE_CHECKING:
    from sensorkit.recording.bag import Recording
    from sensorkit.recording.expect import Expected
    from sensorkit.recording.tf import Mat

__all__ = ["check_frame_ids", "check_joints", "recorded_frame"]

CAMERA_ROLES = frozenset({"image", "camera_info", "depth_image", "depth_camera_info", "points"})


def recorded_frame(rec: Recording, topic: str) -> str | None:
    """The frame most of a topic's sampled messages are stamped with."""
    sample = rec.samples.get(topic)
    if sample is None or not sample.frame_ids:
        return None
    return frame_name(Counter(sample.frame_ids).most_common(1)[0][0])


def _T_world(exp: Expected, link: str) -> Mat | None:
    robot = exp.info.robot
    if link not in robot.link_map:
        return None
    T = robot.T_world_link(link)
    return None if T is None else np.asarray(T, dtype=np.float64)


def _R_render(exp: Expected, frame: str, rec: Recording) -> Mat | None:
    """The rotation of ``frame`` seen from the sensor's render pose: from the description
    when it has the frame, else through the recorded TF from the predicted frame."""
    T_render = exp.sensor.T_world_render
    if T_render is None:
        return None
    R_world_render = np.asarray(T_render, dtype=np.float64)[:3, :3]
    T_world_frame = _T_world(exp, frame)
    if T_world_frame is not None:
        return np.asarray(R_world_render.T @ T_world_frame[:3, :3])
    predicted = exp.frame
    T_world_pred = _T_world(exp, predicted) if predicted else None
    if predicted is None or T_world_pred is None:
        return None
    T_pred_frame = rec.tf.lookup(predicted, frame)
    if T_pred_frame is None:
        return None
    return np.asarray(R_world_render.T @ T_world_pred[:3, :3] @ T_pred_frame[:3, :3])


def _not_optical(exp: Expected, R: Mat | None) -> str | None:
    """SK502's explanation when ``R`` (from the render pose) is not optical, else None."""
    if R is None or angle_between(R, R_BODY_OPTICAL) <= ANGLE_TOL:
        return None
    rows = tuple(tuple(float(v) for v in row) for row in R)
    return not_optical(Mat3(rows), is_gz(exp.info.target))


def _topics_text(names: list[str]) -> str:
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def check_frame_ids(rec: Recording, exps: dict[str, Expected]) -> list[Finding]:
    """SK803 (once per sensor and wrong frame, naming its topics) and SK804 for every
    predicted topic the recording sampled."""
    out: list[Finding] = []
    wrong: dict[tuple[str, str, str, bool], list[Expected]] = {}
    unknown: set[tuple[str, str]] = set()
    for name, exp in exps.items():
        have = recorded_frame(rec, name)
        if have is None:
            continue
        want = exp.frame
        if want is not None and have != want:
            camera = exp.sensor.sensor.is_camera and exp.topic.role in CAMERA_ROLES
            wrong.setdefault((exp.sensor.name, have, want, camera), []).append(exp)
        if rec.has_tf and not rec.tf.knows(have) and (exp.sensor.name, have) not in unknown:
            unknown.add((exp.sensor.name, have))
            out.append(
                finding(
                    "SK804",
                    Severity.ERROR,
                    f"{name}: header.frame_id {have!r} is in neither /tf nor /tf_static of "
                    "the recording: TF cannot place its data",
                    exp,
                    frame=have,
                    fix="record /tf and /tf_static with robot_state_publisher running on "
                    "this description",
                )
            )
    for (sensor, have, want, camera), group in wrong.items():
        exp = group[0]
        names = _topics_text([e.name for e in group])
        why = _not_optical(exp, _R_render(exp, have, rec)) if camera else None
        if why is not None:
            message = (
                f"camera {sensor!r} stamps {names} with {have!r}, {why}; the description "
                f"stamps them with {want!r}"
            )
        else:
            message = f"{names}: header.frame_id is {have!r}, the description predicts {want!r}"
        out.append(
            finding(
                "SK803",
                Severity.ERROR,
                message,
                exp,
                frame=have,
                fix=f"record what the description's plugin stamps ({want!r}), or set the "
                "plugin's frame in the description to the frame the data is in",
            )
        )
    if exps and not rec.has_tf and any(recorded_frame(rec, n) for n in exps):
        out.append(
            Finding(
                "SK804",
                Severity.INFO,
                "the recording has no /tf or /tf_static: its frames were not checked "
                "against TF (SK804, SK805)",
                SourceRef(str(rec.path)),
                fix="record /tf and /tf_static too (ros2 bag record /tf /tf_static ...)",
            )
        )
    return out


def _pose_text(T: Mat) -> str:
    values = [*(float(v) for v in T[:3, 3]), *matrix_to_rpy(T[:3, :3])]
    x, y, z, r, p, w = (round(v, 4) + 0.0 for v in values)  # no "-0.0000"
    return f"xyz {x:.4f} {y:.4f} {z:.4f} rpy {r:.4f} {p:.4f} {w:.4f}"


def _sensor_frames(
    exps: dict[str, Expected], rec: Recording
) -> dict[str, tuple[Expected, list[str], set[str]]]:
    """Per sensor: an Expected of it, the frames to compare (stamped ones, then its link),
    and the frames its camera data is stamped with."""
    out: dict[str, tuple[Expected, list[str], set[str]]] = {}
    for name, exp in exps.items():
        entry = out.setdefault(exp.sensor.name, (exp, [], set()))
        frame = recorded_frame(rec, name) or exp.frame
        if frame is not None and frame not in entry[1]:
            entry[1].append(frame)
        if frame is not None and exp.sensor.sensor.is_camera and exp.topic.role in CAMERA_ROLES:
            entry[2].add(frame)
    for exp, frames, _optical in out.values():
        link = exp.sensor.link
        if link is not None and link not in frames:
            frames.append(link)
    return out


def check_joints(rec: Recording, exps: dict[str, Expected]) -> list[Finding]:
    """SK805: the recorded transform of each sensor frame from the parent link of its
    fixed joint, against the joint."""
    if not rec.has_tf:
        return []
    out: list[Finding] = []
    for exp, frames, camera_frames in _sensor_frames(exps, rec).values():
        robot = exp.info.robot
        for frame in frames:
            joint = robot.parent_joint.get(frame)
            if joint is None or joint.type != "fixed" or joint.parent is None:
                continue
            parent = joint.parent
            if not (rec.tf.knows(frame) and rec.tf.knows(parent)):
                continue  # a frame TF lacks is SK804's (when data is stamped with it)
            T_world_parent, T_world_frame = _T_world(exp, parent), _T_world(exp, frame)
            if T_world_parent is None or T_world_frame is None:
                continue
            want = np.linalg.inv(T_world_parent) @ T_world_frame
            have = rec.tf.lookup(parent, frame)
            if have is None:
                out.append(
                    finding(
                        "SK805",
                        Severity.ERROR,
                        f"the recorded TF has both {parent!r} and {frame!r}, but no chain of "
                        f"transforms between them (the description joins them by {joint.name!r})",
                        exp,
                        frame=frame,
                    )
                )
                continue
            moved = float(np.linalg.norm(have[:3, 3] - want[:3, 3]))
            turned = angle_between(have[:3, :3], want[:3, :3])
            if moved <= POSITION_TOL and turned <= ANGLE_TOL:
                continue
            message = (
                f"the recorded TF places {frame!r} in {parent!r} at {_pose_text(have)}, the "
                f"description's joint {joint.name!r} at {_pose_text(want)} (off by "
                f"{moved * 1000:.1f} mm and {math.degrees(turned):.1f} degrees)"
            )
            if frame in camera_frames and exp.sensor.T_world_render is not None:
                R_world_render = np.asarray(exp.sensor.T_world_render, dtype=np.float64)[:3, :3]
                R = R_world_render.T @ T_world_parent[:3, :3] @ have[:3, :3]
                why = _not_optical(exp, R)
                if why is not None:
                    message += (
                        f"; the data of camera {exp.sensor.name!r} is stamped with {frame!r}, {why}"
                    )
            out.append(
                finding(
                    "SK805",
                    Severity.ERROR,
                    message,
                    exp,
                    frame=frame,
                    fix="publish TF from this description (robot_state_publisher), not from "
                    "a hand-written static transform",
                )
            )
    return out
