"""SK502, SK503 and SK303: the frame a sensor stamps its data with.

The frame parameter (a plugin's ``frame_name``, a Gazebo sensor's ``gz_frame_id``, a
camera's ``optical_frame_id``) is pointed at a link that is where the sensor measures: the
optical frame at a camera, a lidar's own link. A camera with none gets a new
``LINK_optical_frame`` on a fixed joint (unsafe). A name is copied as written where it
means the same (see :meth:`~sensorkit.fix.registry.FixContext.text_for`).
"""

from __future__ import annotations

from lxml import etree

from sensorkit.base.findings import Finding
from sensorkit.fix.fixers.angles import (
    ANGLE_TOL,
    OPTICAL_RPY_URDF,
    OPTICAL_RPY_XACRO,
    urdf_number,
)
from sensorkit.fix.registry import Fix, FixContext, Written, fixer, is_expr
from sensorkit.fix.source import Deferred, Edit, NotFixable, escape
from sensorkit.knowledge.gazebo_ros import ROS1_RENAMES
from sensorkit.model.frames import GZ_FRAME_TAGS, SensorFrames, optical_frame_at
from sensorkit.model.parse import child
from sensorkit.model.sensors import Sensor
from sensorkit.model.targets import is_gz

__all__ = ["explicit_frame", "frame_at_origin", "optical_frame"]


def _sensor(fx: FixContext, f: Finding) -> tuple[Sensor, SensorFrames]:
    """The sensor a finding is about, and its frames."""
    matches = [s for s in fx.robot.sensors if s.name == f.sensor]
    exact = [s for s in matches if s.source == f.source]
    if not (exact or matches):
        raise NotFixable(f"sensor {f.sensor!r} not found")
    s = (exact or matches)[0]
    return s, fx.ctx.frames_of(s)


def _name_sources(fx: FixContext, link: str) -> list[tuple[Written, str]]:
    """Places whose text evaluates to link name ``link``: its ``<link name>`` and the
    ``<gazebo reference>`` of blocks about it, as written."""
    out: list[tuple[Written, str]] = []
    elements: list[tuple[etree._Element, str]] = []
    lk = fx.robot.link_map.get(link)
    if lk is not None:
        elements.append((lk.element, "name"))
    elements += [(g.element, "reference") for g in fx.robot.gazebo if g.reference == link]
    for el, attr in elements:
        try:
            w = fx.written(el)
        except NotFixable:
            continue
        a = w.tag.attr(attr)
        if a is not None:
            out.append((w, a.raw))
    return out


def _frame_target(
    fx: FixContext, s: Sensor, fr: SensorFrames
) -> tuple[Written, str, etree._Element | None]:
    """Where a sensor's frame is named: the element to write in (plugin or sensor), the
    tag, and the element already naming it (None: add one)."""
    if is_gz(fx.target):
        cam = s.camera
        if fr.image_frame is not None and fr.image_how == "optical_frame_id" and cam is not None:
            return (
                fx.written(cam.element),
                "optical_frame_id",
                child(cam.element, "optical_frame_id"),
            )
        tags = GZ_FRAME_TAGS[fx.target]
        tag = fr.how if fr.how in tags else tags[0]
        return fx.written(s.element), tag, child(s.element, tag)
    p, spec = fr.plugin, fr.spec
    if p is None or spec is None or not spec.frame_params:
        raise NotFixable(f"sensor {s.name!r} has no plugin sensorkit knows that names a frame")
    for ros1, ros2 in ROS1_RENAMES.get(p.library, {}).items():
        pending = child(p.element, ros1) is not None and child(p.element, ros2) is None
        if fx.target == "classic" and ros2 in spec.frame_params and pending:
            raise Deferred(f"its <{ros1}> becomes <{ros2}> first (SK602)")
    tag = fr.how if fr.how in spec.frame_params else spec.frame_params[0]
    return fx.written(p.element), tag, child(p.element, tag)


def _name_frame(
    fx: FixContext, s: Sensor, value: str, sources: list[tuple[Written, str]]
) -> tuple[list[Edit], frozenset[str]]:
    """Edits that make ``s`` stamp its data with frame ``value``."""
    fr = fx.ctx.frames_of(s)
    scope, tag, el = _frame_target(fx, s, fr)
    text = fx.text_for(value, sources, scope)
    claims = frozenset({f"frame:{scope.where}"})
    if el is None:
        return [scope.file.insert_child(scope.tag, [(0, f"<{tag}>{text}</{tag}>")])], claims
    w, raw = fx.written_text(el)
    if is_expr(raw):
        raise NotFixable(
            f"<{tag}>{raw.strip()}</{tag}> at {w.where} is a xacro expression: "
            "change it where its value comes from"
        )
    return [w.file.set_text(w.tag, text)], claims


def _publish_in(fx: FixContext, f: Finding, s: Sensor, frame: str, title: str) -> Fix:
    """Name link ``frame`` in ``s``'s frame parameter, copied as the link's name is written."""
    edits, claims = _name_frame(fx, s, frame, _name_sources(fx, frame))
    return Fix(f, tuple(edits), title, claims=claims)


def _body_frame_at(fx: FixContext, fr: SensorFrames) -> str | None:
    """A link at a lidar's render pose with the same orientation (x forward, z up)."""
    if fr.T_world_render is None:
        return None
    # pure Python (sensorkit.model.transforms), as validate computes: validate's [*] marks
    # ask this fixer too, and must not import numpy
    from sensorkit.model.transforms import angle_between, norm, rotation, translation

    robot = fx.robot
    at = translation(fr.T_world_render)
    R_render = rotation(fr.T_world_render)
    names = ([fr.link] if fr.link else []) + [lk.name for lk in robot.links]
    for name in names:
        T = robot.T_world_link(name)
        if T is None or (fr.link and robot.tree_of(name) != robot.tree_of(fr.link)):
            continue
        if norm([a - b for a, b in zip(translation(T), at, strict=True)]) > 1e-3:
            continue
        if angle_between(R_render, rotation(T)) <= ANGLE_TOL:
            return name
    return None


def _optical_frame(fx: FixContext, f: Finding, s: Sensor, fr: SensorFrames) -> Fix:
    existing = optical_frame_at(fx.robot, fr.T_world_render)
    if existing is not None:
        title = f"publish in {existing!r}, the optical frame at the camera"
        return _publish_in(fx, f, s, existing, title)
    if f.rule == "SK502" and f.frame in fx.robot.link_map:
        from sensorkit.lint.rules.frame_joints import OPTICAL_NAME, blamed_optical_joint

        if OPTICAL_NAME.search(f.frame or ""):
            # Meant as the optical frame: a second one would leave this wrong one in TF.
            _joint, _rpy, why = blamed_optical_joint(fx.ctx, s, fr, f.frame)
            raise NotFixable(
                f"{f.frame!r} is meant as the optical frame: sensorkit neither adds a second "
                f"one beside it nor turns it here ({why}); correct it by hand"
            )
    return _add_optical_frame(fx, f, s, fr)


def _add_optical_frame(fx: FixContext, f: Finding, s: Sensor, fr: SensorFrames) -> Fix:
    """Unsafe: a new ``LINK_optical_frame`` at the camera, and the sensor published in it."""
    robot = fx.robot
    link = fr.link
    if link is None or link not in robot.link_map:
        raise NotFixable("the sensor's link is not found")
    new_link, new_joint = f"{link}_optical_frame", f"{link}_optical_joint"
    for name, kind in ((new_link, "link"), (new_joint, "joint")):
        if name in robot.link_map or name in robot.joint_map:
            raise NotFixable(
                f"a {kind} {name!r} exists already but is not the camera's optical frame"
            )
    wl = fx.written(robot.link_map[link].element)
    a = wl.tag.attr("name")
    if a is None:
        raise NotFixable(f"<link> at {wl.where} has no name as written")
    from sensorkit.model.transforms import (
        R_BODY_OPTICAL,
        matrix_to_rpy,
        rotation,
        transform,
        translation,
    )

    pose = s.pose
    if pose.rpy == (0.0, 0.0, 0.0):
        xyz = " ".join(urdf_number(v) for v in pose.xyz)
        rpy = OPTICAL_RPY_XACRO if fx.xacro else OPTICAL_RPY_URDF
    else:
        T = transform(pose.xyz, pose.rpy)
        R = rotation(T) @ R_BODY_OPTICAL
        xyz = " ".join(urdf_number(float(v)) for v in translation(T))
        rpy = " ".join(urdf_number(v) for v in matrix_to_rpy(R))
    moved = pose.xyz != (0.0, 0.0, 0.0) or pose.rpy != (0.0, 0.0, 0.0)
    if moved and fx.copies_of(wl) > 1:
        raise NotFixable(
            f"{wl.where} is in a xacro macro used {fx.copies_of(wl)} times with a sensor <pose>: add the optical frame there by hand"
        )
    name_raw = a.raw if is_expr(a.raw) else escape(link, {'"': "&quot;"})
    if not is_expr(a.raw) and fx.copies_of(wl) > 1:
        raise NotFixable(
            f"{wl.where} is in a xacro macro used {fx.copies_of(wl)} times: add the optical frame there by hand"
        )
    lines = [
        (0, f'<joint name="{name_raw}_optical_joint" type="fixed">'),
        (1, f'<parent link="{name_raw}"/>'),
        (1, f'<child link="{name_raw}_optical_frame"/>'),
        (1, f'<origin xyz="{xyz}" rpy="{rpy}"/>'),
        (0, "</joint>"),
        (0, f'<link name="{name_raw}_optical_frame"/>'),
    ]
    add = wl.file.insert_after(wl.tag, lines)
    edits, claims = _name_frame(fx, s, new_link, [(wl, f"{a.raw}_optical_frame")])
    return Fix(
        f,
        (add, *edits),
        f"add link {new_link!r} (fixed joint {new_joint!r}, the exact optical rotation) and publish in it",
        safe=False,
        claims=claims | {f"optical:{wl.where}"},
    )


@fixer(
    "SK502",
    "safe/unsafe",
    "a stamped link whose only role is the optical frame gets its joint's rpy corrected in place "
    "(safe); else point the frame parameter at the optical frame already at the camera (safe); "
    "with none, add `LINK_optical_frame` on a fixed joint with the exact rotation and point at it (unsafe)",
)
def optical_frame(fx: FixContext, f: Finding) -> Fix:
    s, fr = _sensor(fx, f)
    if f.joint is not None:
        return _optical_joint_rpy(fx, f, s, fr)
    return _optical_frame(fx, f, s, fr)


def _optical_joint_rpy(fx: FixContext, f: Finding, s: Sensor, fr: SensorFrames) -> Fix:
    """The stamped frame is a link whose only role is to be this camera's optical frame
    (SK502 named its joint): write the joint's rpy that makes it optical, in place, rather
    than add a second optical frame and leave the wrong one in TF."""
    from sensorkit.lint.rules.frame_joints import blamed_optical_joint, rpy_text

    joint, rpy, why = blamed_optical_joint(fx.ctx, s, fr, f.frame)
    if joint is None or rpy is None or joint.name != f.joint:
        raise NotFixable(why or f"joint {f.joint!r} is not the one into {f.frame!r}")
    origin = child(joint.element, "origin")
    if origin is None:
        raise NotFixable(f"joint {joint.name!r} has no <origin> to edit")
    w = fx.written(origin)
    a = w.tag.attr("rpy")
    if a is None:
        raise NotFixable(
            f"<origin> at {w.where} has no rpy as written: add the optical one by hand"
        )
    if is_expr(a.raw):
        raise NotFixable(
            f'rpy="{a.raw}" at {w.where} is computed by xacro: change it where its value comes from'
        )
    if fx.copies_of(w) > 1:
        raise NotFixable(
            f"{w.where} is in a xacro macro used {fx.copies_of(w)} times: correct its rpy there by hand"
        )
    new = rpy_text(rpy, fx.xacro)
    return Fix(
        f,
        (w.file.set_attr(a, new),),
        f'joint {joint.name!r}: rpy "{a.raw}" -> "{new}" (the optical rotation at the camera)',
        claims=frozenset({f"rpy:{w.where}"}),
    )


@fixer(
    "SK503",
    "safe/unsafe",
    "point the frame parameter at a frame at the render origin: the camera's optical frame or the "
    "lidar's own link (safe); a camera with none gets `LINK_optical_frame` (unsafe)",
)
def frame_at_origin(fx: FixContext, f: Finding) -> Fix:
    s, fr = _sensor(fx, f)
    if s.is_camera:
        return _optical_frame(fx, f, s, fr)
    body = _body_frame_at(fx, fr)
    if body is None:
        raise NotFixable(f"no link sits where {s.name!r} measures: add one at its <pose> by hand")
    return _publish_in(fx, f, s, body, f"publish in {body!r}, the link at the sensor")


@fixer(
    "SK303",
    "safe",
    "add the frame parameter (`<frame_name>` on ROS 2) naming the sensor's own link (a camera's "
    "optical frame)",
)
def explicit_frame(fx: FixContext, f: Finding) -> Fix:
    s, fr = _sensor(fx, f)
    if fr.link is None:
        raise NotFixable("the sensor's link is not found")
    frame = fr.link
    if s.is_camera:
        found = optical_frame_at(fx.robot, fr.T_world_render)
        if found is None:
            raise NotFixable("no optical frame at the camera yet (SK502's unsafe fix adds one)")
        frame = found
    return _publish_in(fx, f, s, frame, f"name the frame {frame!r} in the plugin")
