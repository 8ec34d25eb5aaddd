"""An :class:`~sensorkit.model.sdf_read.SdfModel` as a
:class:`~sensorkit.model.robot.Robot`: the records every rule and command reads.

- A link is a :class:`~sensorkit.model.parts.Link` named with its scope
  (``inner::link``), its inertial (libsdformat's default when it has none) and meshes
  read from SDF's elements.
- A joint is a :class:`~sensorkit.model.parts.Joint` whose ``origin`` is the child link's
  frame in the parent link's frame, what a URDF joint origin means, so that the Robot's
  poses (each link's in its tree's root, sensors' in their links) hold unchanged. Its
  ``axis`` is in the child link's frame, as URDF's is in the joint frame that is the child
  link's. A joint to ``world`` is no Robot joint (the model's root hangs from nothing);
  a joint's own pose is the SdfModel's (``robot.sdf.pose_of(joint)``).
- A sensor is read by :func:`~sensorkit.model.sensors.read_sensor` (the same XML as a
  ``<gazebo reference>`` block's), its ``reference`` its link and its ``pose`` resolved
  into its link's frame from whatever frame it is written relative to.
- Plugins of the model, its nested models and its links are ``model_plugins``.
"""

from __future__ import annotations

from lxml import etree

from sensorkit.loading.document import Document
from sensorkit.model.parse import (
    Origin,
    child,
    children,
    parse_float,
    parse_vec,
    stod_prefix,
    text_of,
)
from sensorkit.model.parts import Inertial, Joint, Link
from sensorkit.model.robot import Robot
from sensorkit.model.sdf_frames import between, scoped
from sensorkit.model.sdf_read import Element, SdfModel, ref
from sensorkit.model.sensors import Plugin, read_sensor
from sensorkit.model.transforms import IDENTITY, Pose, matrix_to_rpy, pose_matrix

_INERTIA_KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def exact_origin(p: Pose, source_el: etree._Element | None, doc: Document) -> Origin:
    """An Origin whose pose is ``p`` exactly (its xyz and rpy are for display)."""
    origin = Origin(
        (p[9], p[10], p[11]),
        matrix_to_rpy(pose_matrix(p)),
        source=doc.locate(source_el) if source_el is not None else None,
    )
    origin._pose = p
    return origin


def _inertial(el: etree._Element, doc: Document) -> Inertial:
    """The ``<inertial>`` ``el``, or the default one when ``el`` is the ``<link>``."""
    from sensorkit.model.sdf_read import read_pose

    if el.tag == "link":
        unit: dict[str, float | None] = {
            k: 1.0 if k in ("ixx", "iyy", "izz") else 0.0 for k in _INERTIA_KEYS
        }
        return Inertial(1.0, unit, exact_origin(IDENTITY, el, doc), el, doc)

    problems: list[str] = []
    lenient: list[tuple[str, str, float]] = []

    def number(key: str, text: str | None) -> float | None:
        value, why = parse_float(text)
        if why and text is not None:
            # sdformat reads the number the text starts with (parse.stod_prefix): that value
            # is simulated, and SK302 says so; only a text it cannot read is a problem.
            read = stod_prefix(text)
            if read is not None and read[0] - read[0] == 0.0:
                lenient.append((key, text, read[0]))
                return read[0]
            problems.append(f"{key} {why}")
        return value

    mass_text = text_of(el, "mass")
    mass = number("mass", mass_text)
    if mass_text is None:
        mass = 1.0  # gazebosim/sdformat@sdformat12_12.8.0:sdf/1.9/inertial.sdf:8
    inertia: dict[str, float | None] = {}
    for key in _INERTIA_KEYS:
        text = text_of(el, "inertia", key)
        value = number(key, text)
        default = 1.0 if key in ("ixx", "iyy", "izz") else 0.0  # inertial.sdf:54-90
        inertia[key] = value if text is not None else default
    raw, _, pose_el, _ = read_pose(el, (1, 9))
    return Inertial(
        mass, inertia, exact_origin(raw, pose_el, doc), el, doc, tuple(problems), tuple(lenient)
    )


def _link(item: Element, doc: Document) -> Link:
    el = item.element
    inertial_el = child(el, "inertial")
    meshes = []
    for part in (*children(el, "visual"), *children(el, "collision")):
        uri_el = child(child(child(part, "geometry"), "mesh"), "uri")
        if uri_el is not None and (uri_el.text or "").strip():
            meshes.append(((uri_el.text or "").strip(), doc.locate(uri_el)))
    # A link without <inertial> has libsdformat's default one: mass 1, inertia the unit
    # matrix, at the link's origin (gazebosim/sdformat@sdformat12_12.8.0:src/Link.cc:66-69,
    # 150-190), what gz-sim simulates: the element the Inertial points at is the link's.
    inertial = _inertial(inertial_el if inertial_el is not None else el, doc)
    return Link(item.name, el, doc, inertial, tuple(meshes))


def _axis(
    sm: SdfModel, item: Element, joint: str, child_link: str
) -> tuple[tuple[float, float, float] | None, str | None]:
    """The joint's ``<axis><xyz>`` in the child link's frame. It is written in the joint's
    frame unless ``expressed_in`` names another (gazebosim/sdformat@sdformat12_12.8.0:
    src/JointAxis.cc:347-362); before 1.7, ``use_parent_model_frame`` is the model's
    (sdf/1.7/1_6.convert:11-27)."""
    axis_el = child(item.element, "axis")
    xyz_el = child(axis_el, "xyz")
    if xyz_el is None:
        return None, None
    values, why = parse_vec((xyz_el.text or "").strip() or "0 0 1", 3)
    if values is None:
        return None, f"axis {why}"
    if item.version < (1, 7):
        flag = (text_of(axis_el, "use_parent_model_frame") or "").lower()
        frame = item.model_frame if flag in ("true", "1") else joint
    else:
        expressed = xyz_el.get("expressed_in")
        frame = ref(item.scope, item.frame, expressed) if expressed else joint
    R = sm.graph.in_frame(frame, child_link)
    if R is None:
        return None, "axis expressed in a frame that does not resolve"
    x, y, z = values
    axis = (
        R[0] * x + R[1] * y + R[2] * z,
        R[3] * x + R[4] * y + R[5] * z,
        R[6] * x + R[7] * y + R[8] * z,
    )
    if axis == (0.0, 0.0, 0.0):
        return axis, "axis is zero"
    return axis, None


def _joint(sm: SdfModel, item: Element, doc: Document) -> Joint | None:
    """The Robot joint of an SDF joint, or None for one to ``world``."""
    el = item.element
    parent_text, child_text = text_of(el, "parent"), text_of(el, "child")
    if parent_text == "world":
        return None
    parent = kid = None  # None: not written, as the URDF reader has it
    if parent_text:
        parent = ref(item.scope, item.frame, parent_text)
        parent = sm.graph.link_of(parent) or parent
    if child_text:
        kid = ref(item.scope, item.frame, child_text)
        kid = sm.graph.link_of(kid) or kid
    a = sm.pose_of(parent) if parent is not None else None
    b = sm.pose_of(kid) if kid is not None else None
    rel = between(a, b) if a is not None and b is not None else IDENTITY
    origin = exact_origin(rel, child(el, "pose") if child(el, "pose") is not None else el, doc)
    joint = Joint(item.name, el.get("type", ""), parent, kid, origin, el, doc)
    if kid is not None:
        joint.axis, joint.axis_problem = _axis(sm, item, item.name, kid)
    limit_el = child(child(el, "axis"), "limit")
    if limit_el is not None:
        limit: dict[str, float | None] = {}
        problems: list[str] = []
        for key in ("lower", "upper", "effort", "velocity"):
            value, why = parse_float(text_of(limit_el, key))
            if why:
                problems.append(f"{key} {why}")
            limit[key] = value
        joint.limit, joint.limit_problems = limit, tuple(problems)
    return joint


def _sensor_pose(sm: SdfModel, item: Element, doc: Document) -> Origin | None:
    """The sensor's pose in its link's frame: its ``<pose>`` is in its link unless it
    names another frame (gazebosim/sdformat@sdformat12_12.8.0:src/Sensor.cc:486-493, the
    link its default; src/SemanticPose.cc:107-128)."""
    from sensorkit.model.sdf_read import read_pose
    from sensorkit.model.transforms import compose

    raw, rel, pose_el, _ = read_pose(item.element, item.version)
    frame = scoped(item.scope, rel) if rel is not None else item.name
    P_frame, P_link = sm.pose_of(frame), sm.pose_of(item.name)
    if P_frame is None or P_link is None:
        return None
    return exact_origin(
        between(P_link, compose(P_frame, raw)),
        pose_el if pose_el is not None else item.element,
        doc,
    )


def build_sdf_robot(doc: Document, sm: SdfModel) -> Robot:
    """The Robot of one SDF model. Never raises on bad content."""
    robot = Robot(name=sm.name, document=doc, sdf=sm)
    robot.links.extend(_link(item, doc) for item in sm.links)
    for item in sm.joints:
        joint = _joint(sm, item, doc)
        if joint is not None:
            robot.joints.append(joint)
    robot.index_tree()
    for item in sm.sensors:
        link_el = item.element.getparent()
        assert link_el is not None
        sensor = read_sensor(item.element, link_el, item.name, doc.locate)
        origin = _sensor_pose(sm, item, doc)
        if origin is not None:
            sensor.pose = origin
        else:
            sensor.problems.append("pose relative to a frame that does not resolve")
        robot.sensors.append(sensor)
    for _owner, el in sm.plugins:
        robot.model_plugins.append(
            Plugin(el.get("filename", ""), el.get("name", ""), el, doc.locate(el))
        )
    return robot
