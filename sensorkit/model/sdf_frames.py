"""SDF's pose frame semantics: the graph of frames of one model (or world) and the poses
it resolves, as libsdformat's PoseRelativeTo graph does.

Every vertex is named as seen from the top model, nested models' names scoped with
``::`` (``outer::inner::link``), as sdformat names them; the top model's own frame
(``__model__``) is the vertex ``""``, and a nested model's frame is the vertex of its
name. Each vertex has the vertex its raw pose is written relative to and that raw pose;
a pose in the top frame is the composition up that chain (sdformat's
``resolvePoseRelativeToRoot``). References are cited as
``gazebosim/sdformat@TAG:PATH:LINE`` (``TAG`` sdformat12_12.8.0, Gazebo Fortress).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from lxml import etree

from sensorkit.model.transforms import IDENTITY, Pose, compose, invert, matrix_pose, pose_matrix

TOP = ""  # the top model's frame (__model__), or the world frame of a world's graph


def inverse(p: Pose) -> Pose:
    """The inverse of a rigid pose."""
    return matrix_pose(invert(pose_matrix(p)))


def between(a: Pose, b: Pose) -> Pose:
    """Pose of frame b in frame a, both given in one frame: ``inverse(a) @ b``."""
    return compose(inverse(a), b)


def scoped(scope: str, name: str) -> str:
    """The vertex a name written inside the model ``scope`` (``""`` for the top model)
    refers to: ``__model__`` is the scope's own frame; other names are looked up in the
    scope and below it, never above (sdformat's ScopedGraph, ``VertexIdByName``)."""
    if name == "__model__":
        return scope
    return f"{scope}::{name}" if scope else name


@dataclass
class Vertex:
    """A frame: a link, joint, ``<frame>`` or nested model, with its raw pose.

    ``relative_to`` is the vertex the raw pose is in (already defaulted as sdformat does
    for each kind), ``written`` what the file said (None: nothing), ``attached_to`` the
    vertex a frame is attached to, a joint's child, a model's canonical link.
    """

    name: str
    kind: str  # link | joint | frame | model
    relative_to: str
    raw: Pose
    element: etree._Element
    written: str | None = None
    attached_to: str | None = None
    pose_element: etree._Element | None = None  # the <pose> its raw pose was read from


@dataclass
class FrameGraph:
    """The frames of one model (or of a world: its models and frames) by scoped name."""

    vertices: dict[str, Vertex] = field(default_factory=dict)
    duplicates: list[Vertex] = field(default_factory=list)  # a name already taken
    _poses: dict[str, Pose | None] = field(default_factory=dict, repr=False)

    def add(self, vertex: Vertex) -> None:
        # The first of a name counts; sdformat reports the others as DUPLICATE_NAME
        # (gazebosim/sdformat@sdformat12_12.8.0:src/FrameSemantics.cc:636-645).
        if vertex.name in self.vertices or vertex.name == TOP:
            self.duplicates.append(vertex)
        else:
            self.vertices[vertex.name] = vertex

    def knows(self, name: str) -> bool:
        return name == TOP or name in self.vertices

    def pose(self, name: str) -> Pose | None:
        """Pose of the vertex ``name`` in the top frame; None when it is unknown, or its
        chain names a frame that does not exist or comes back to itself (a cycle)."""
        if name == TOP:
            return IDENTITY
        memo = self._poses
        if name in memo:
            return memo[name]
        chain: list[str] = []
        seen: set[str] = set()
        cur = name
        base: Pose | None
        while True:
            if cur == TOP:
                base = IDENTITY
                break
            if cur in memo:
                base = memo[cur]
                break
            vertex = self.vertices.get(cur)
            if vertex is None or cur in seen:  # unknown name, or a cycle
                base = None
                break
            seen.add(cur)
            chain.append(cur)
            cur = vertex.relative_to
        # X_top_v = X_top_r * X_r_v down the chain: resolvePoseRelativeToRoot
        # (gazebosim/sdformat@sdformat12_12.8.0:src/FrameSemantics.cc:1721-1761).
        pose = base
        for v in reversed(chain):
            pose = None if pose is None else compose(pose, self.vertices[v].raw)
            memo[v] = pose
        return memo.get(name)

    def pose_in_scope(self, name: str, scope: str) -> Pose | None:
        """Pose of ``name`` in the frame of the model ``scope`` it belongs to, walking its
        chain up to that frame only (no memo: used while the graph is still built)."""
        out, cur, seen = IDENTITY, name, set()
        while cur != scope:
            vertex = self.vertices.get(cur)
            if vertex is None or cur in seen:
                return None
            seen.add(cur)
            out = compose(vertex.raw, out)
            cur = vertex.relative_to
        return out

    def place(self, model: str, frame: str | None) -> bool:
        """Make the model vertex ``model``'s raw pose that of its placement ``frame``
        (a name in the model's scope): X_RM = X_RPf * X_MPf^-1
        (gazebosim/sdformat@sdformat12_12.8.0:src/FrameSemantics.cc:248-274).
        False when the frame does not resolve (the pose is left as written)."""
        vertex = self.vertices.get(model)
        if not frame or vertex is None:
            return True
        X_MPf = self.pose_in_scope(scoped(model, frame), model)
        if X_MPf is None:
            return False
        vertex.raw = compose(vertex.raw, inverse(X_MPf))
        return True

    def in_frame(self, name: str, frame: str) -> Pose | None:
        """Pose of vertex ``name`` in vertex ``frame`` (None if either is unresolved)."""
        a, b = self.pose(frame), self.pose(name)
        if a is None or b is None:
            return None
        return between(a, b)

    def link_of(self, name: str) -> str | None:
        """The link a vertex is attached to: a link itself; a frame's attached_to, a
        joint's child, a model's canonical link, followed to a link (the
        FrameAttachedTo graph: gazebosim/sdformat@sdformat12_12.8.0:src/FrameSemantics.cc:
        760-837, 913-950). None when the chain ends elsewhere or loops."""
        seen: set[str] = set()
        cur: str | None = name
        while cur is not None and cur not in seen:
            seen.add(cur)
            vertex = self.vertices.get(cur)
            if vertex is None:
                return None
            if vertex.kind == "link":
                return cur
            cur = vertex.attached_to
        return None
