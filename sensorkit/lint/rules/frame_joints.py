"""SK508, SK509: frames as the joints write them; and the optical joint SK502 blames.

SK502 judges the frame a camera stamps; when that frame is a link whose only role is to
be the camera's optical frame, the wrong rotation is its joint's ``rpy``, and that is what
SK502 points at (:func:`dedicated_optical_joint`, :func:`optical_rpy_for`). SK508 judges a
link named optical that no sensor stamps; SK509 a sensor mounted implausibly far away.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from typing import TYPE_CHECKING

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.limits import ANGLE_TOL, POSITION_TOL
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model import transforms as tf
from sensorkit.model.parse import child

if TYPE_CHECKING:
    from sensorkit.model.frames import SensorFrames
    from sensorkit.model.parts import Joint
    from sensorkit.model.sensors import Sensor
    from sensorkit.model.transforms import Mat

HALF_PI = math.pi / 2
FAR_M = 10.0  # SK509


def rpy_text(rpy: tuple[float, float, float], xacro: bool) -> str:
    """An rpy as it should be written: multiples of pi/2 exactly (``${-pi/2}`` in xacro,
    full precision in URDF), other angles in full precision."""
    exact = {-1: "${-pi/2}", 1: "${pi/2}", -2: "${-pi}", 2: "${pi}"}
    out = []
    for v in rpy:
        k = round(v / HALF_PI)
        snapped = abs(v - k * HALF_PI) < 1e-9
        if snapped and k == 0:
            out.append("0")
        elif snapped and xacro and k in exact:
            out.append(exact[k])
        else:
            text = repr(float(k * HALF_PI if snapped else v))
            out.append(text[:-2] if text.endswith(".0") else text)
    return " ".join(out)


def dedicated_optical_joint(ctx: Context, s: Sensor, frame: str | None) -> tuple[Joint | None, str]:
    """The fixed joint into ``frame`` when ``frame`` is a link whose only role is to be
    ``s``'s optical frame, so that its rotation can change and nothing else moves; else
    (None, why not).

    Nothing else may depend on the link's orientation: it has no child link, no visual,
    collision or inertial, no sensor sits on it, no <gazebo> block names it, no other
    sensor stamps its data with it and no model plugin names it.
    """
    robot = ctx.robot
    if frame is None or frame not in robot.link_map:
        return None, f"{frame!r} is not a link"
    joint = robot.parent_joint.get(frame)
    if joint is None or joint.type != "fixed":
        return None, f"{frame!r} does not hang on a fixed joint"
    why = _other_roles(ctx, s, frame)
    return (None, why) if why else (joint, "")


def _other_roles(ctx: Context, s: Sensor, frame: str) -> str:
    """Why link ``frame``'s orientation matters beyond ``s``'s images ("" when it does not)."""
    robot = ctx.robot
    if robot.child_joints.get(frame):
        return f"links hang off {frame!r}"
    el = robot.link_map[frame].element
    for tag in ("visual", "collision", "inertial"):
        if child(el, tag) is not None:
            return f"{frame!r} has a <{tag}>, which would turn with it"
    if any(x.reference == frame for x in robot.sensors):
        return f"a sensor sits on {frame!r}"
    if any(g.reference == frame for g in robot.gazebo):
        return f"a <gazebo reference> names {frame!r}"
    for x in robot.sensors:
        if x is s:
            continue
        fr = ctx.frames_of(x)
        if frame in (fr.published, fr.image_frame):
            return f"sensor {x.name!r} stamps its data with {frame!r} too"
    for p in robot.model_plugins:
        if any((e.text or "").strip().strip("/") == frame for e in p.param_elements()):
            return f"plugin {p.name!r} names {frame!r}"
    return ""


def blamed_optical_joint(
    ctx: Context, s: Sensor, fr: SensorFrames, frame: str | None
) -> tuple[Joint | None, tuple[float, float, float] | None, str]:
    """(joint, rpy, "") when the wrong rotation of the optical frame ``s`` stamps is its
    joint's rpy, which ``rpy`` corrects; else (None, None, why not).

    Its joint is blamed only when nothing else can be: the link's only role is this
    optical frame (:func:`dedicated_optical_joint`), it sits at the camera (else it is not
    this camera's frame at all, SK503) and its joint does not already write the optical
    rotation from its parent (if it does, the sensor's <pose> or a joint above turns the
    camera, and the optical joint is right).
    """
    joint, why = dedicated_optical_joint(ctx, s, frame)
    if joint is None:
        return None, None, why
    T = fr.T_render_frame(ctx.robot, frame)
    if T is None or tf.norm(tf.translation(T)) > POSITION_TOL:
        return None, None, f"{frame!r} is not at the camera"
    if tf.angle_between(tf.rpy_to_matrix(joint.origin.rpy), tf.R_BODY_OPTICAL) <= ANGLE_TOL:
        return (
            None,
            None,
            f"joint {joint.name!r} already writes the optical rotation: the sensor's <pose> or a "
            "joint above it turns the camera",
        )
    rpy = optical_rpy_for(ctx, fr, joint)
    return (joint, rpy, "") if rpy is not None else (None, None, "its pose is unknown")


def optical_rpy_for(
    ctx: Context, fr: SensorFrames, joint: Joint
) -> tuple[float, float, float] | None:
    """The rpy of ``joint`` that makes its child the optical frame of the camera rendering
    from ``fr``: R_parent_child = R_parent_world * R_world_render * Rz(-pi/2)Rx(-pi/2)."""
    if joint.parent is None or fr.T_world_render is None:
        return None
    T_parent = ctx.robot.T_world_link(joint.parent)
    if T_parent is None:
        return None
    R = tf.rotation(tf.relative(T_parent, fr.T_world_render))
    return tf.matrix_to_rpy(_mul3(R, tf.R_BODY_OPTICAL))


def _mul3(A: Mat, B: Mat) -> Mat:
    return tf.Mat(
        tuple(tuple(sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)) for i in range(3))
    )


def sdf_optical_fix(ctx: Context, s: Sensor, fr: SensorFrames) -> str:
    """SK502's fix in SDF: Fortress and Harmonic stamp images with <optical_frame_id>
    (see GZ_OPTICAL_FRAME_ID in sensorkit.model.frames); else an optical link."""
    from sensorkit.model.frames import GZ_OPTICAL_FRAME_ID

    name = f"{(fr.link or s.name).rpartition('::')[2]}_optical_frame"
    link = (
        f'a link {name} whose <pose relative_to="{fr.link}"> is the sensor\'s <pose> turned by '
        f"roll -pi/2, yaw -pi/2 (-1.5707963267948966 0 -1.5707963267948966 when the sensor's "
        f"is 0), with a fixed joint from {fr.link!r}"
    )
    if ctx.target in GZ_OPTICAL_FRAME_ID:
        return f"add {link}, and name it in <camera><optical_frame_id>"
    return f"add {link}, and publish in it"


# A link named for an optical frame: "optical" as a word of its name, last or followed by
# "frame" or "link" (camera_optical_frame, camera_link_optical, rgb_optical_link), not
# optical_flow_link (a PX4 optical-flow sensor's body) or optical_table.
OPTICAL_NAME = re.compile(r"(?:^|[_/\-])optical(?:$|[_\-](?:frame|link)(?:$|[_\-]))", re.IGNORECASE)


@rule(
    "SK508",
    "warning",
    "a link named as an optical frame (`optical` as a word of its name, last or before `frame`/`link`) "
    "that no sensor stamps is optical: its rotation from its parent link, or from some link above "
    "it, is Rz(-pi/2)*Rx(-pi/2) within 0.5 degree (a frame a sensor stamps is SK502's or SK504's)",
    formats=("urdf", "sdf"),
)
def optical_named(ctx: Context) -> Iterator[Finding]:
    from sensorkit.model.frames import sdf_tf_agrees

    robot = ctx.robot
    sdf = robot.sdf is not None
    # A frame a sensor stamps is judged by SK502 (cameras) or SK504 (lidars, IMUs).
    stamped: set[str | None] = set()
    for s in robot.sensors:
        fr = ctx.frames_of(s)
        stamped |= {fr.camera_frame if s.is_camera else None, fr.published, fr.image_frame}
    for lk in robot.links:
        name = lk.name
        if name in stamped or not OPTICAL_NAME.search(name):
            continue
        joint = robot.parent_joint.get(name)
        if joint is None or joint.parent is None:
            continue
        if sdf and not all(
            sdf_tf_agrees(robot, x, position=False) for x in (name, *robot.ancestors(name))
        ):
            continue  # TF's publishers turn these links differently (sdf_tf_agrees)
        errs = []
        up: str | None = joint.parent
        while up is not None:
            T = robot.T_link_link(up, name)
            if T is None:
                break
            errs.append(tf.angle_between(tf.rotation(T), tf.R_BODY_OPTICAL))
            pj = robot.parent_joint.get(up)
            up = pj.parent if pj is not None else None
        if not errs or min(errs) <= ANGLE_TOL:
            continue
        optical = rpy_text((-HALF_PI, 0.0, -HALF_PI), robot.document.expanded)
        pose = child(robot.link_map[name].element, "pose") if sdf else None
        yield ctx.finding(
            "SK508",
            Severity.WARNING,
            f"link {name!r} is named as an optical frame but is not one: its rotation from its parent "
            f"{joint.parent!r} is {math.degrees(errs[0]):.1f} degrees from the optical rotation "
            "(z forward, x right, y down), and no link above it sees it optical either: "
            "data stamped with it would land turned",
            (pose if pose is not None else robot.link_map[name].element) if sdf else joint.source,
            link=name,
            joint=joint.name,
            frame=name,
            fix=(
                f"turn the <pose> of link {name!r} by roll -pi/2, yaw -pi/2 from its parent"
                if sdf
                else f'give joint {joint.name!r} rpy="{optical}"'
            )
            + " if its parent is the camera's body frame (x forward, z up); if the link is no "
            "optical frame, rename it",
        )


@rule(
    "SK509",
    "warning",
    f"a sensor sits more than {FAR_M:g} m from the link it hangs off (millimetres written as "
    "metres): its origin, its `<pose>` through the fixed joints that lumping merges, measured from "
    "the link Gazebo attaches it to, or, when its own link is not lumped, from the parent link of "
    "the joint into its link (a link named `world` is the world: not measured)",
    formats=("urdf", "sdf"),
)
def far_sensor(ctx: Context) -> Iterator[Finding]:
    robot, conv = ctx.robot, ctx.conversion
    for s in robot.sensors:
        ref = s.reference
        if ref is None or ref not in robot.link_map:
            continue
        anchor = conv.survivor(ref)
        if anchor == ref:
            pj = robot.parent_joint.get(ref)
            if pj is None or pj.parent is None:
                continue
            anchor = pj.parent
        if anchor == "world":
            continue
        T = robot.T_link_link(anchor, ref)
        if T is None:
            continue
        T_sensor = tf.pose_matrix(tf.compose(tf.matrix_pose(T), s.pose.pose()))
        dist = tf.norm(tf.translation(T_sensor))
        if dist <= FAR_M:
            continue
        yield ctx.finding(
            "SK509",
            Severity.WARNING,
            f"sensor {s.name!r} sits {dist:.2f} m from {anchor!r}, the link it hangs off: "
            "a sensor that far out is most likely millimetres written as metres (URDF and SDF "
            "lengths are metres)",
            s.source,
            sensor=s.name,
            link=anchor,
            fix="write the "
            + ("link poses" if robot.sdf is not None else "joint origins")
            + " and the sensor <pose> between them in metres",
        )
