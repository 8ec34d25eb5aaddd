"""The robot model: links, joints, inertials and the kinematic tree, read from URDF XML.

Reading is tolerant: a broken value becomes ``None`` plus a note, duplicate names and
cycles are kept as they are, so that the rules can report them (findings are data). The
model never raises on bad input.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from sys import intern
from typing import TYPE_CHECKING, Any

from lxml import etree

from sensorkit.base.findings import SourceRef
from sensorkit.loading.document import Document
from sensorkit.loading.marks import LOC_ATTR

if TYPE_CHECKING:
    from sensorkit.model.sensors import Plugin, Sensor
    from sensorkit.model.transforms import Mat, Pose
    from sensorkit.model.transforms_np import Mat as NpMat

Vec3 = tuple[float, float, float]
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


def parse_vec3(text: str) -> tuple[Vec3 | None, str | None]:
    """Three finite numbers from an attribute, or (None, why): ``parse_vec``'s fast path."""
    try:
        a, b, c = text.split()
        v = (float(a), float(b), float(c))
    except ValueError:
        return None, f"{text!r} is not 3 numbers"
    if v[0] - v[0] or v[1] - v[1] or v[2] - v[2]:  # NaN for NaN and inf, 0.0 otherwise
        return None, f"{text!r} is not finite"
    return v, None


def parse_vec(text: str | None, n: int = 3) -> tuple[tuple[float, ...] | None, str | None]:
    """``n`` numbers from an attribute, or (None, why)."""
    if text is None:
        return None, None
    if n == 3:
        return parse_vec3(text)
    parts = text.split()
    if len(parts) != n:
        return None, f"{text!r} is not {n} numbers"
    try:
        values = tuple(map(float, parts))
    except ValueError:
        return None, f"{text!r} is not {n} numbers"
    if sum(values) - sum(values) != 0.0:  # any NaN or inf makes this NaN
        return None, f"{text!r} is not finite"
    return values, None


def parse_float(text: str | None) -> tuple[float | None, str | None]:
    """One finite number, or (None, why)."""
    if text is None:
        return None, None
    try:
        value = float(text)
    except ValueError:
        return None, f"{text!r} is not a number"
    if value - value != 0.0:
        return None, f"{text!r} is not finite"
    return value, None


def local(el: etree._Element) -> str:
    """Tag name without namespace ('' for comments and processing instructions)."""
    tag = el.tag
    if not isinstance(tag, str):
        return ""
    if tag[0] == "{":
        return tag.rsplit("}", 1)[-1]
    return tag


def children(el: etree._Element, name: str) -> list[etree._Element]:
    """Child elements called ``name`` (documents are namespace-free after loading)."""
    if name.isidentifier():  # a plain tag name: a loop costs less than lxml's findall()
        return [c for c in el if c.tag == name]
    return list(el.findall(name))


def child(el: etree._Element | None, name: str) -> etree._Element | None:
    """The first child element called ``name`` (or matching an ElementPath), or None."""
    if el is None:
        return None
    if name.isidentifier():  # a plain tag name: a loop costs less than lxml's find()
        for c in el:
            if c.tag == name:
                return c
        return None
    return el.find(name)


def text_of(el: etree._Element | None, *path: str) -> str | None:
    """Stripped text of a descendant by child names, or None."""
    cur = el
    for name in path:
        cur = child(cur, name)
        if cur is None:
            return None
    if cur is None or cur.text is None:
        return None
    return str(cur.text).strip()


_ZERO: Vec3 = (0.0, 0.0, 0.0)


@dataclass(slots=True)
class Origin:
    """A URDF ``<origin>``: xyz and rpy, zeros when absent; notes when unreadable.

    Read-only once made: the model builder hands one Origin to every element whose
    attributes read the same (robots repeat "0 0 0" and a few poses thousands of times).
    """

    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    problems: tuple[str, ...] = ()
    rpy_text: str | None = None
    source: SourceRef | None = None
    _pose: Pose | None = field(default=None, init=False, repr=False, compare=False)

    @classmethod
    def read(cls, el: etree._Element | None, source: SourceRef | None = None) -> Origin:
        if el is None:
            return cls(source=source)
        xyz_text, rpy_text = el.get("xyz"), el.get("rpy")
        xyz: Vec3 | None = _ZERO
        rpy: Vec3 | None = _ZERO
        problems: list[str] = []
        if xyz_text is not None:
            xyz, why = parse_vec3(xyz_text)
            if why:
                problems.append(f"xyz {why}")
        if rpy_text is not None:
            rpy, why = parse_vec3(rpy_text)
            if why:
                problems.append(f"rpy {why}")
        return cls(xyz or _ZERO, rpy or _ZERO, tuple(problems), rpy_text, source)

    def pose(self) -> Pose:
        """The origin as a flat pose (see :mod:`sensorkit.model.transforms`), memoised."""
        p = self._pose
        if p is None:
            from sensorkit.model.transforms import pose

            p = self._pose = pose(self.xyz, self.rpy)
        return p

    def transform(self) -> Mat:
        """The origin as a pure-Python 4x4 matrix."""
        from sensorkit.model.transforms import pose_matrix

        return pose_matrix(self.pose())

    def matrix(self) -> NpMat:
        """The origin as a 4x4 numpy array (for rendering and export)."""
        from sensorkit.model.transforms_np import transform

        return transform(self.xyz, self.rpy)


def _shared_pose(origin: Origin, shared: dict[tuple[int, int], Pose]) -> Pose:
    """``origin.pose()``, computed once per xyz and rpy pair in ``shared`` (one walk's).

    Origins read from the same text share their xyz and rpy tuples (the reader's memo).
    Keyed by identity, so equal values that differ in sign (0.0, -0.0) stay apart; the
    tuples outlive the walk, so no identity is reused during it.
    """
    p = origin._pose
    if p is None:
        key = (id(origin.xyz), id(origin.rpy))
        p = shared.get(key)
        if p is None:
            p = shared[key] = origin.pose()
        else:
            origin._pose = p
    return p


class _Located:
    """Mixin: ``source`` is computed on first use (most elements never need it)."""

    __slots__ = ()
    element: etree._Element
    doc: Document

    @property
    def source(self) -> SourceRef:
        return self.doc.locate(self.element)


@dataclass(slots=True)
class Inertial(_Located):
    """A link's ``<inertial>``: mass, inertia and origin (None where unreadable; see problems).

    ``inertia`` and ``origin`` are shared by every inertial whose text reads the same: read
    them, never change them.
    """

    mass: float | None
    inertia: dict[str, float | None]
    origin: Origin
    element: etree._Element
    doc: Document
    problems: tuple[str, ...] = ()


@dataclass(slots=True)
class Link(_Located):
    """A ``<link>``: its first inertial and the mesh files its visuals and collisions name."""

    name: str
    element: etree._Element
    doc: Document
    inertial: Inertial | None = None
    meshes: tuple[tuple[str, SourceRef], ...] = ()

    @property
    def mass(self) -> float:
        """Mass Gazebo sees (0 when missing or unreadable)."""
        if self.inertial is None or self.inertial.mass is None:
            return 0.0
        return self.inertial.mass


@dataclass(slots=True)
class Joint(_Located):
    """A ``<joint>`` as urdfdom reads it (the first of each child element counts)."""

    name: str
    type: str
    parent: str | None
    child: str | None
    origin: Origin
    element: etree._Element
    doc: Document
    axis: Vec3 | None = None
    axis_problem: str | None = None
    limit: dict[str, float | None] | None = None
    limit_problems: tuple[str, ...] = ()
    mimic: str | None = None
    has_mimic: bool = False


@dataclass(slots=True)
class Stray:
    """Something urdfdom silently ignores: an unknown child element, or attribute if ``attr``."""

    element: etree._Element
    parent_tag: str
    attr: str | None
    link: str | None


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


@dataclass
class GazeboBlock:
    """A ``<gazebo>`` extension; ``reference`` is None for model-level blocks."""

    reference: str | None
    element: etree._Element
    source: SourceRef


@dataclass
class Robot:
    """The whole description, with lazy forward kinematics at zero joint positions."""

    name: str
    document: Document
    links: list[Link] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)
    gazebo: list[GazeboBlock] = field(default_factory=list)
    sensors: list[Sensor] = field(default_factory=list)
    model_plugins: list[Plugin] = field(default_factory=list)
    strays: list[Stray] = field(default_factory=list)
    link_map: dict[str, Link] = field(default_factory=dict)
    joint_map: dict[str, Joint] = field(default_factory=dict)
    parent_joint: dict[str, Joint] = field(default_factory=dict)
    child_joints: dict[str, list[Joint]] = field(default_factory=dict)
    _T_world: dict[str, Pose | None] = field(default_factory=dict, repr=False)
    # (tree top, number of ancestors) of links whose way up has no cycle
    _up: dict[str, tuple[str, int]] = field(default_factory=dict, repr=False)
    _roots: list[str] | None = field(default=None, repr=False)
    cache: dict[Any, Any] = field(default_factory=dict, repr=False)  # derived data, by user

    @property
    def macros_only(self) -> bool:
        """A xacro that expands to no link, joint or sensor: it only defines macros or
        properties for robots to include (a partial given explicitly)."""
        return self.document.expanded and not self.links and not self.joints and not self.sensors

    # ---- tree -------------------------------------------------------------------------
    def roots(self) -> list[str]:
        """Links that no joint names as child, in document order."""
        if self._roots is None:
            self._roots = [lk.name for lk in self.links if lk.name not in self.parent_joint]
        return list(self._roots)

    def root(self) -> str | None:
        r = self.roots()
        return r[0] if len(r) == 1 else None

    def ancestors(self, link: str) -> list[str]:
        """Links from ``link``'s parent up to its root (stops on a cycle)."""
        out: list[str] = []
        seen = {link}
        cur = link
        while cur in self.parent_joint:
            parent = self.parent_joint[cur].parent
            if parent is None or parent in seen:
                break
            out.append(parent)
            seen.add(parent)
            cur = parent
        return out

    def _top(self, link: str) -> tuple[str, int] | None:
        """``(tree_of(link), len(ancestors(link)))``, memoised; None on a way up with a cycle.

        One walk up to the first link already known, so all calls together cost O(links).
        """
        up = self._up
        hit = up.get(link)
        if hit is not None:
            return hit
        pj = self.parent_joint
        path = [link]
        seen = {link}
        cur = link
        while True:
            joint = pj.get(cur)
            parent = joint.parent if joint is not None else None
            if parent is None:
                top, depth = cur, 0
                break
            if parent in seen:  # a cycle: ancestors() answers differently per start
                return None
            hit = up.get(parent)
            if hit is not None:
                top, depth = hit[0], hit[1] + 1
                break
            path.append(parent)
            seen.add(parent)
            cur = parent
        # path ends with cur, at ``depth``; each link below it is one deeper
        n = len(path)
        for i, name in enumerate(path):
            up[name] = (top, depth + n - 1 - i)
        return up[link]

    def tree_of(self, link: str) -> str:
        """The top of the tree ``link`` hangs in (a root link, or the missing parent of a cut)."""
        known = self._top(link)
        if known is not None:
            return known[0]
        up = self.ancestors(link)
        return up[-1] if up else link

    def depth(self, link: str) -> int:
        """``len(ancestors(link))``: how many links are above ``link``."""
        known = self._top(link)
        return known[1] if known is not None else len(self.ancestors(link))

    def path_up(self, link: str, top: str) -> list[str] | None:
        """``link`` and its ancestors below ``top`` (None unless ``top`` is an ancestor).

        Walks only the ``depth(link) - depth(top)`` steps between them.
        """
        a, b = self._top(link), self._top(top)
        if a is None or b is None:  # a cycle on the way: the plain walk
            chain = [link, *self.ancestors(link)]
            return chain[: chain.index(top)] if top in chain[1:] else None
        steps = a[1] - b[1]
        if steps <= 0 or a[0] != b[0]:
            return None
        out = []
        cur: str | None = link
        for _ in range(steps):
            assert cur is not None
            out.append(cur)
            cur = self.parent_joint[cur].parent
        return out if cur == top else None

    def cut_off(self) -> list[str]:
        """Links whose parent joint names a parent link that does not exist (SK202)."""
        return [
            lk.name
            for lk in self.links
            if (j := self.parent_joint.get(lk.name)) is not None
            and j.parent is not None
            and j.parent not in self.link_map
        ]

    def subtree(self, link: str) -> list[str]:
        """``link`` and every link below it (cycle-safe)."""
        out: list[str] = []
        seen: set[str] = set()
        stack = [link]
        while stack:
            cur = stack.pop()
            if cur in seen:
                continue
            seen.add(cur)
            out.append(cur)
            for j in self.child_joints.get(cur, []):
                if j.child is not None:
                    stack.append(j.child)
        return out

    # ---- kinematics -------------------------------------------------------------------
    def world_pose(self, link: str) -> Pose | None:
        """Pose of ``link`` in its root's frame at zero joint positions (None if unknown).

        "World" is the root link of the tree ``link`` belongs to. Memoised; iterative, so
        a 10,000-link chain costs no recursion.
        """
        cache = self._T_world
        if link in cache:
            return cache[link]
        if link not in self.link_map:
            return None
        from sensorkit.model.transforms import IDENTITY, compose

        chain: list[str] = []
        cur: str | None = link
        seen: set[str] = set()
        base: Pose | None = None
        while cur is not None:
            if cur in cache:
                base = cache[cur]
                break
            if cur in seen:  # cycle: no defined pose
                for c in chain:
                    cache[c] = None
                return None
            seen.add(cur)
            chain.append(cur)
            joint = self.parent_joint.get(cur)
            if joint is None:
                base = IDENTITY
                cache[cur] = base
                chain.pop()
                break
            cur = joint.parent
            if cur is None:
                for c in chain:
                    cache[c] = None
                return None
            if cur not in self.link_map:
                # A joint to a missing parent (SK202) cuts this subtree off: it is a tree of
                # its own, rooted where the cut is, so its sensors can still be checked.
                base = IDENTITY
                cache[chain[-1]] = base
                chain.pop()
                break
        T = base
        pj = self.parent_joint
        shared: dict[tuple[int, int], Pose] = {}
        for name in reversed(chain):
            T = None if T is None else compose(T, _shared_pose(pj[name].origin, shared))
            cache[name] = T
        return cache[link]

    def world_positions(self) -> dict[str, Vec3 | None]:
        """The position of :meth:`world_pose` of every link (by name), memoised.

        A link that is no joint's parent needs no rotation of its own: its position is its
        parent's rotation times its joint's xyz, plus the parent's position, computed as
        :func:`~sensorkit.model.transforms.compose` computes it (the same floats). Only
        the poses of parents are composed and kept: on a wide tree most links cost nine
        multiplications instead of a composition, and a third of a pose's memory.
        """
        known: dict[str, Vec3 | None] | None = self.cache.get("world_positions")
        if known is not None:
            return known
        from sensorkit.model.transforms import compose

        out: dict[str, Vec3 | None] = {}
        cache = self._T_world
        pj, links, kids = self.parent_joint, self.link_map, self.child_joints
        shared: dict[tuple[int, int], Pose] = {}
        for lk in self.links:
            name = lk.name
            if name in cache:
                P = cache[name]
            else:
                joint = pj.get(name)
                parent = joint.parent if joint is not None else None
                if joint is None or parent not in cache or parent not in links:
                    P = self.world_pose(name)
                else:  # the usual case: parents come first
                    a = cache[parent]
                    if a is None:
                        P = cache[name] = None
                    elif name in kids:  # a parent itself: its children need its rotation
                        P = cache[name] = compose(a, _shared_pose(joint.origin, shared))
                    else:
                        b = _shared_pose(joint.origin, shared)
                        bx, by, bz = b[9], b[10], b[11]
                        out[name] = (
                            a[0] * bx + a[1] * by + a[2] * bz + a[9],
                            a[3] * bx + a[4] * by + a[5] * bz + a[10],
                            a[6] * bx + a[7] * by + a[8] * bz + a[11],
                        )
                        continue
            out[name] = None if P is None else (P[9], P[10], P[11])
        self.cache["world_positions"] = out
        return out

    def T_world_link(self, link: str) -> Mat | None:
        """:meth:`world_pose` as a 4x4 matrix."""
        from sensorkit.model.transforms import pose_matrix

        p = self.world_pose(link)
        return None if p is None else pose_matrix(p)

    def T_link_link(self, a: str, b: str) -> Mat | None:
        """Pose of link ``b`` in link ``a`` (None unless both are in one tree)."""
        from sensorkit.model.transforms import relative

        Ta, Tb = self.T_world_link(a), self.T_world_link(b)
        if Ta is None or Tb is None:
            return None
        if self.tree_of(a) != self.tree_of(b):
            return None
        return relative(Ta, Tb)


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
_ORIGIN_MEMO: dict[_Items, tuple[Origin, bool]] = {}
_MASS_MEMO: dict[_Items, tuple[float | None, tuple[str, ...], bool]] = {}
_INERTIA_MEMO: dict[_Items, tuple[dict[str, float | None], tuple[str, ...], bool]] = {}
_LIMIT_MEMO: dict[_Items, tuple[dict[str, float | None], tuple[str, ...], bool]] = {}
_AXIS_MEMO: dict[str, tuple[Vec3 | None, str | None]] = {}


def _items(el: etree._Element) -> _Items:
    """``el``'s attributes as a memo key: the source mark xacro stamps last is left out."""
    items = el.items()
    if items and items[-1][0] == LOC_ATTR:
        del items[-1]
    return tuple(items)


def _origin_parts(items: _Items) -> tuple[Origin, bool]:
    attrs = dict(items)
    xyz_text, rpy_text = attrs.get("xyz"), attrs.get("rpy")
    xyz: Vec3 | None = _ZERO
    rpy: Vec3 | None = _ZERO
    problems: list[str] = []
    if xyz_text is not None:
        xyz, why = parse_vec3(xyz_text)
        if why:
            problems.append(f"xyz {why}")
    if rpy_text is not None:
        rpy, why = parse_vec3(rpy_text)
        if why:
            problems.append(f"rpy {why}")
    clean = _ORIGIN_ATTRS.issuperset(attrs)
    return Origin(xyz or _ZERO, rpy or _ZERO, tuple(problems), rpy_text), clean


def _read_origin(el: etree._Element, link: str | None, strays: list[Stray]) -> Origin:
    """``Origin.read(el)``, checking its attributes for strays on the way."""
    key = _items(el)
    hit = _ORIGIN_MEMO.get(key)
    if hit is None:
        hit = _ORIGIN_MEMO[key] = _origin_parts(key)
    if not hit[1]:
        _check_attrs(el, "origin", link, strays)
    return hit[0]


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
                key = _items(c)
                mass_hit = _MASS_MEMO.get(key)
                if mass_hit is None:
                    mass_hit = _MASS_MEMO[key] = _mass_parts(key)
                if not mass_hit[2]:
                    _check_attrs(c, "mass", link, strays)
            elif not _MASS_ATTRS.issuperset(c.keys()):
                _check_attrs(c, "mass", link, strays)
        elif tag == "inertia":
            if inertia_hit is None:
                key = _items(c)
                inertia_hit = _INERTIA_MEMO.get(key)
                if inertia_hit is None:
                    inertia_hit = _INERTIA_MEMO[key] = _inertia_parts(key)
                if not inertia_hit[2]:
                    _check_attrs(c, "inertia", link, strays)
            elif not _INERTIA_ATTRS.issuperset(c.keys()):
                _check_attrs(c, "inertia", link, strays)
        elif tag == "origin":
            if origin is None:
                origin = _read_origin(c, link, strays)
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
        attrs = dict(it)
        name, jtype = attrs.get("name", ""), attrs.get("type", "")
        if not _JOINT_ATTRS.issuperset(attrs):
            _stray_attrs(el, "joint", el.keys(), URDF_ATTRS["joint"], None, strays)
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
                origin = _read_origin(c, None, strays)
                continue  # its attributes are checked
        elif tag == "limit":
            if limit_hit is None:
                key = _items(c)
                limit_hit = _LIMIT_MEMO.get(key)
                if limit_hit is None:
                    limit_hit = _LIMIT_MEMO[key] = _limit_parts(key)
                if not limit_hit[2]:
                    _check_attrs(c, "limit", None, strays)
                continue
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
            axis, why = parse_vec3(axis_text)
            if axis is not None and axis[0] == 0.0 and axis[1] == 0.0 and axis[2] == 0.0:
                why = "axis is zero"
            hit = _AXIS_MEMO[axis_text] = (axis, why)
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
    from sensorkit.model.sensors import read_gazebo

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
    link_map, joint_map = robot.link_map, robot.joint_map
    parent_joint, child_joints = robot.parent_joint, robot.child_joints
    for lk in links:
        if lk.name not in link_map:
            link_map[lk.name] = lk
    for j in joints:
        if j.name not in joint_map:
            joint_map[j.name] = j
        c = j.child
        if c is not None and c not in parent_joint:
            parent_joint[c] = j
        p = j.parent
        if p is not None:
            kids = child_joints.get(p)
            if kids is None:
                child_joints[p] = [j]
            else:
                kids.append(j)
    read_gazebo(robot)
    return robot
