"""Reading a URDF document into a :class:`~sensorkit.model.robot.Robot`: what urdfdom
reads in each element, the readers of links, inertials and joints, and :func:`build_robot`.

Reading is tolerant: a broken value becomes ``None`` plus a note, duplicate names and
cycles are kept as they are, so that the rules can report them (findings are data). The
model never raises on bad input.
"""

from __future__ import annotations

from collections.abc import Callable
from sys import intern
from typing import Any, TypeVar

from lxml import etree

from sensorkit.base.findings import SourceRef
from sensorkit.loading.document import Document
from sensorkit.loading.marks import LOC_ATTR
from sensorkit.model.parse import Origin, Vec3, local, parse_float, parse_vec3
from sensorkit.model.parts import GazeboBlock, Inertial, Joint, Link, Stray
from sensorkit.model.robot import Robot
from sensorkit.model.sensors import Plugin, read_sensor

JOINT_TYPES = {"revolute", "continuous", "prismatic", "fixed", "floating", "planar"}
# What urdfdom reads inside each element; anything else it silently ignores (SK105).
URDF_CHILDREN: dict[str, frozenset[str]] = {
    "link": frozenset({"inertial", "visual", "collision"}),
    "inertial": frozenset({"origin", "mass", "inertia"}),
    "visual": frozenset({"origin", "geometry", "material"}),
    "collision": frozenset({"origin", "geometry"}),
    "joint": frozenset(
        {
            "origin",
            "parent",
            "child",
            "axis",
            "calibration",
            "dynamics",
            "limit",
            "safety_controller",
            "mimic",
        }
    ),
}
# What may stand directly under <robot>: urdfdom's link/joint/material, the ROS extensions
# that other tools read (gazebo, transmission, ros2_control, urdfdom's experimental sensor)
# and simulators' own sections (webots, mujoco). Anything else is read by nobody: typically
# an ``xacro:element`` or macro that expanded to a literal tag, taking a sensor with it.
ROBOT_CHILDREN = frozenset(
    {
        "link",
        "joint",
        "material",
        "gazebo",
        "transmission",
        "ros2_control",
        "sensor",
        "webots",
        "mujoco",
    }
)
URDF_CHILDREN["robot"] = ROBOT_CHILDREN
URDF_ATTRS: dict[str, frozenset[str]] = {
    "mass": frozenset({"value"}),
    "inertia": frozenset({"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}),
    "origin": frozenset({"xyz", "rpy"}),
    "limit": frozenset({"lower", "upper", "effort", "velocity"}),
    "axis": frozenset({"xyz"}),
    "parent": frozenset({"link"}),
    "child": frozenset({"link"}),
    "link": frozenset({"name", "type"}),
    "joint": frozenset({"name", "type"}),
    "dynamics": frozenset({"damping", "friction"}),
    "mimic": frozenset({"joint", "multiplier", "offset"}),
    "safety_controller": frozenset(
        {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"}
    ),
    "calibration": frozenset({"rising", "falling", "reference_position"}),
}


def _check_attrs(el: etree._Element, tag: str, link: str | None, strays: list[Stray]) -> None:
    allowed = URDF_ATTRS.get(tag)
    if allowed is None:
        return
    keys = el.keys()
    if allowed.issuperset(keys):
        return
    _stray_attrs(el, tag, keys, allowed, link, strays)


def _stray_attrs(
    el: etree._Element,
    tag: str,
    keys: list[str],
    allowed: frozenset[str],
    link: str | None,
    strays: list[Stray],
) -> None:
    for key in keys:
        if key not in allowed and key != LOC_ATTR and not key.startswith("{"):
            strays.append(Stray(el, tag, key, link))


def _stray_child(c: etree._Element, parent_tag: str, link: str | None, strays: list[Stray]) -> None:
    if isinstance(c.tag, str):
        strays.append(Stray(c, parent_tag, None, link))


_INERTIA_KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_MASS_ATTRS = URDF_ATTRS["mass"] | {LOC_ATTR}
_INERTIA_ATTRS = URDF_ATTRS["inertia"] | {LOC_ATTR}
_ORIGIN_ATTRS = URDF_ATTRS["origin"] | {LOC_ATTR}
_LINK_ATTRS = URDF_ATTRS["link"] | {LOC_ATTR}
_JOINT_ATTRS = URDF_ATTRS["joint"] | {LOC_ATTR}
_LIMIT_KEYS = ("lower", "upper", "effort", "velocity")
_JOINT_CHILD_ATTRS = {tag: URDF_ATTRS[tag] | {LOC_ATTR} for tag in URDF_CHILDREN["joint"]}

# What the attributes of an <origin>, <mass>, <inertia> or <limit> read as, by their
# (name, text) pairs: robots repeat a few values ("0 0 0", one inertia per link type)
# thousands of times. Pure functions of the key, emptied by each build_robot. What they
# hold (Origins, inertia and limit dicts) is shared by every element that reads the same:
# the model is read-only, and one object instead of thousands keeps a 100,000-link model
# smaller (fewer allocations, fewer cache misses in every later pass over it).
_Items = tuple[tuple[str, str], ...]
_Hit = TypeVar("_Hit", bound=tuple[Any, ...])  # what a memo holds: its last item says clean
_ORIGIN_MEMO: dict[_Items, tuple[Origin, bool]] = {}
_MASS_MEMO: dict[_Items, tuple[float | None, tuple[str, ...], bool]] = {}
_INERTIA_MEMO: dict[_Items, tuple[dict[str, float | None], tuple[str, ...], bool]] = {}
_LIMIT_MEMO: dict[_Items, tuple[dict[str, float | None], tuple[str, ...], bool]] = {}
_AXIS_MEMO: dict[str, tuple[Vec3 | None, str | None]] = {}


def _read_memo(
    el: etree._Element,
    tag: str,
    memo: dict[_Items, _Hit],
    parts: Callable[[_Items], _Hit],
    link: str | None,
    strays: list[Stray],
) -> _Hit:
    """What ``parts`` reads from ``el``'s attributes, through ``memo``; the attributes are
    checked for strays on the way when they are not all clean."""
    items = el.items()
    if items and items[-1][0] == LOC_ATTR:  # the source mark xacro stamps last: not a key
        del items[-1]
    key = tuple(items)
    hit = memo.get(key)
    if hit is None:
        hit = memo[key] = parts(key)
    if not hit[-1]:
        _check_attrs(el, tag, link, strays)
    return hit


def _origin_parts(items: _Items) -> tuple[Origin, bool]:
    attrs = dict(items)
    return Origin.from_text(attrs.get("xyz"), attrs.get("rpy")), _ORIGIN_ATTRS.issuperset(attrs)


def _mass_parts(items: _Items) -> tuple[float | None, tuple[str, ...], bool]:
    attrs = dict(items)
    text = attrs.get("value")
    mass: float | None = None
    if text is None:
        problems: tuple[str, ...] = ("<mass> has no value attribute",)
    else:
        mass, why = parse_float(text)
        problems = (f"mass {why}",) if why else ()
    return mass, problems, _MASS_ATTRS.issuperset(attrs)


def _inertia_parts(items: _Items) -> tuple[dict[str, float | None], tuple[str, ...], bool]:
    attrs = dict(items)
    problems: list[str] = []
    inertia: dict[str, float | None] = {}
    for key in _INERTIA_KEYS:
        text = attrs.get(key)
        if text is None:
            inertia[key] = None
            continue
        try:
            value: float | None = float(text)
        except ValueError:
            value = None
        if value is None or value - value != 0.0:
            problems.append(f"{key} {text!r} is not a finite number")
            value = None
        inertia[key] = value
    return inertia, tuple(problems), _INERTIA_ATTRS.issuperset(attrs)


_NO_INERTIA = _inertia_parts(())
_NO_ORIGIN = Origin()  # shared, as the memo's are


def _read_inertial(el: etree._Element, doc: Document, link: str, strays: list[Stray]) -> Inertial:
    mass_hit = inertia_hit = None
    origin: Origin | None = None
    for c in el:  # one pass: lxml's find() costs more per call than this loop
        tag = c.tag
        if tag == "mass":
            if mass_hit is None:
                mass_hit = _read_memo(c, "mass", _MASS_MEMO, _mass_parts, link, strays)
            elif not _MASS_ATTRS.issuperset(c.keys()):
                _check_attrs(c, "mass", link, strays)
        elif tag == "inertia":
            if inertia_hit is None:
                inertia_hit = _read_memo(c, "inertia", _INERTIA_MEMO, _inertia_parts, link, strays)
            elif not _INERTIA_ATTRS.issuperset(c.keys()):
                _check_attrs(c, "inertia", link, strays)
        elif tag == "origin":
            if origin is None:
                origin = _read_memo(c, "origin", _ORIGIN_MEMO, _origin_parts, link, strays)[0]
            elif not _ORIGIN_ATTRS.issuperset(c.keys()):
                _check_attrs(c, "origin", link, strays)
        else:
            _stray_child(c, "inertial", link, strays)
    if mass_hit is None:
        mass: float | None = None
        problems: tuple[str, ...] = ("no <mass>",)
    else:
        mass, problems = mass_hit[0], mass_hit[1]
    if inertia_hit is None:
        inertia_hit = _NO_INERTIA
    if inertia_hit[1]:
        problems += inertia_hit[1]
    return Inertial(
        mass,
        inertia_hit[0],
        origin if origin is not None else _NO_ORIGIN,
        el,
        doc,
        problems,
    )


_VISUAL = frozenset({"visual", "collision"})


def _read_link(el: etree._Element, doc: Document, strays: list[Stray]) -> Link:
    name = intern(el.get("name", ""))  # see _read_joint
    if not _LINK_ATTRS.issuperset(el.keys()):
        _check_attrs(el, "link", name, strays)
    inertial: Inertial | None = None
    meshes: list[tuple[str, SourceRef]] | None = None
    for part in el:
        tag = part.tag
        if tag == "inertial":
            if inertial is None:
                inertial = _read_inertial(part, doc, name, strays)
        elif tag in _VISUAL:
            allowed = URDF_CHILDREN[tag]
            for c in part:
                ctag = c.tag
                if ctag == "geometry":
                    for shape in c:
                        if shape.tag == "mesh" and shape.get("filename"):
                            mesh = (shape.get("filename", ""), doc.locate(shape))
                            if meshes is None:
                                meshes = [mesh]
                            else:
                                meshes.append(mesh)
                elif ctag == "origin":
                    if not _ORIGIN_ATTRS.issuperset(c.keys()):
                        _check_attrs(c, "origin", name, strays)
                elif ctag not in allowed:
                    _stray_child(c, tag, name, strays)
        else:
            _stray_child(part, "link", name, strays)
    return Link(name, el, doc, inertial, tuple(meshes) if meshes else ())


def _limit_parts(items: _Items) -> tuple[dict[str, float | None], tuple[str, ...], bool]:
    attrs = dict(items)
    limit: dict[str, float | None] = {}
    problems: list[str] = []
    for key in _LIMIT_KEYS:
        value, why = parse_float(attrs.get(key))
        if why:
            problems.append(f"{key} {why}")
        limit[key] = value
    return limit, tuple(problems), _JOINT_CHILD_ATTRS["limit"].issuperset(attrs)


def _axis_parts(text: str) -> tuple[Vec3 | None, str | None]:
    axis, why = parse_vec3(text)
    if axis is not None and axis[0] == 0.0 and axis[1] == 0.0 and axis[2] == 0.0:
        why = "axis is zero"
    return axis, why


def _name_and_type(
    el: etree._Element, items: list[tuple[str, str]], strays: list[Stray]
) -> tuple[str, str]:
    """A joint's name and type from its attributes ``items`` (in another shape than name,
    then type), checking them for strays."""
    attrs = dict(items)
    if not _JOINT_ATTRS.issuperset(attrs):
        _stray_attrs(el, "joint", el.keys(), URDF_ATTRS["joint"], None, strays)
    return attrs.get("name", ""), attrs.get("type", "")


_ONE_ATTR = frozenset({"parent", "child", "axis"})  # joint children read for one attribute


def _read_joint(el: etree._Element, doc: Document, strays: list[Stray]) -> Joint:
    # lxml's items() is one call where keys() and get() are two or three: each element's
    # attributes are read once, and the usual shapes (name then type; a lone link or xyz)
    # are recognised without a dict.
    parent = child = mimic = None
    has_parent = has_child = has_mimic = has_axis = False
    origin: Origin | None = None
    axis_text: str | None = None
    limit_hit = None
    it = el.items()
    if it and it[-1][0] == LOC_ATTR:
        del it[-1]
    if len(it) == 2 and it[0][0] == "name" and it[1][0] == "type":
        name, jtype = it[0][1], it[1][1]
    else:
        name, jtype = _name_and_type(el, it, strays)
    for c in el:
        tag = c.tag
        if tag in _ONE_ATTR:
            it = c.items()
            if it and it[-1][0] == LOC_ATTR:
                del it[-1]
            wanted = "xyz" if tag == "axis" else "link"
            if len(it) == 1 and it[0][0] == wanted:
                value: str | None = it[0][1]
                clean = True
            else:
                attrs = dict(it)
                value = attrs.get(wanted)
                clean = _JOINT_CHILD_ATTRS[tag].issuperset(attrs)
            if tag == "parent":
                if not has_parent:
                    has_parent, parent = True, value
            elif tag == "child":
                if not has_child:
                    has_child, child = True, value
            elif not has_axis:
                has_axis, axis_text = True, value
            if not clean:
                _check_attrs(c, tag, None, strays)
            continue
        if tag == "origin":
            if origin is None:
                origin = _read_memo(c, "origin", _ORIGIN_MEMO, _origin_parts, None, strays)[0]
                continue  # its attributes are checked
        elif tag == "limit":
            if limit_hit is None:
                limit_hit = _read_memo(c, "limit", _LIMIT_MEMO, _limit_parts, None, strays)
                continue  # its attributes are checked
        elif tag == "mimic" and not has_mimic:
            has_mimic, mimic = True, c.get("joint")
        attrs_ok = _JOINT_CHILD_ATTRS.get(tag)
        if attrs_ok is None:
            _stray_child(c, "joint", None, strays)
        elif not attrs_ok.issuperset(c.keys()):
            _check_attrs(c, tag, None, strays)
    # Link names are interned (here and in _read_link): a link's name, and the parent and
    # child of its joints, are one string object, so the many dict lookups by link name
    # that follow (tree, conversion, poses, rules) match by identity instead of comparing
    # text in another part of memory. On a 100,000-link robot that is most of their cost.
    joint = Joint(
        name,
        intern(jtype),  # a handful of values: one string each, not one per joint
        parent if parent is None else intern(parent),
        child if child is None else intern(child),
        origin if origin is not None else _NO_ORIGIN,
        el,
        doc,
    )
    if axis_text is not None:
        hit = _AXIS_MEMO.get(axis_text)
        if hit is None:
            hit = _AXIS_MEMO[axis_text] = _axis_parts(axis_text)
        joint.axis, joint.axis_problem = hit
    if limit_hit is not None:
        joint.limit, joint.limit_problems = limit_hit[0], limit_hit[1]
    if has_mimic:
        joint.has_mimic, joint.mimic = True, mimic
    return joint


def _clear_memos() -> None:
    for memo in (_ORIGIN_MEMO, _MASS_MEMO, _INERTIA_MEMO, _LIMIT_MEMO, _AXIS_MEMO):
        memo.clear()


def build_robot(doc: Document) -> Robot:
    """Read the model from a loaded document. Never raises on bad content."""
    import gc

    enabled = gc.isenabled()
    gc.disable()  # tens of thousands of small acyclic objects: collection only costs time
    try:
        return _build_robot(doc)
    finally:
        _clear_memos()
        if enabled:
            gc.enable()


def _own_namespace(el: etree._Element, root: etree._Element) -> bool:
    """``el`` is in the robot's own namespace (none, or the file's default one)."""
    tag, rtag = el.tag, root.tag
    ns = tag[1:].split("}", 1)[0] if isinstance(tag, str) and tag.startswith("{") else ""
    rns = rtag[1:].split("}", 1)[0] if isinstance(rtag, str) and rtag.startswith("{") else ""
    return ns == rns


def _build_robot(doc: Document) -> Robot:
    root = doc.root
    robot = Robot(name=root.get("name", ""), document=doc)
    links, joints, strays = robot.links, robot.joints, robot.strays
    add_link, add_joint = links.append, joints.append
    for el in root:
        tag = el.tag
        if tag == "link":
            add_link(_read_link(el, doc, strays))
            continue
        if tag == "joint":
            add_joint(_read_joint(el, doc, strays))
            continue
        name = local(el)
        if name == "link":
            add_link(_read_link(el, doc, strays))
        elif name == "joint":
            add_joint(_read_joint(el, doc, strays))
        elif name == "gazebo":
            robot.gazebo.append(GazeboBlock(el.get("reference"), el, doc.locate(el)))
        elif name and name not in ROBOT_CHILDREN and _own_namespace(el, root):
            strays.append(Stray(el, "robot", None, None))
    robot.index_tree()
    read_gazebo(robot)
    return robot


def read_gazebo(robot: Robot) -> None:
    """Fill ``robot.sensors`` and ``robot.model_plugins`` from its ``<gazebo>`` blocks."""
    locate = robot.document.locate
    for block in robot.gazebo:
        for el in block.element:
            tag = local(el)
            if tag == "sensor":
                robot.sensors.append(read_sensor(el, block.element, block.reference, locate))
            elif tag == "plugin":
                robot.model_plugins.append(
                    Plugin(el.get("filename", ""), el.get("name", ""), el, locate(el))
                )
