"""Where a robot's links are: world poses at zero joint positions, world positions of all
links at once, and the transforms between two links' frames.

:class:`Poses` is a base of :class:`~sensorkit.model.robot.Robot`. "World" is the root
link of the tree a link hangs in; poses are flat 12-tuples (see
:mod:`sensorkit.model.transforms`), composed from the joint origins down each chain and
memoised on the robot.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from sensorkit.model.parse import Origin, Vec3
    from sensorkit.model.parts import Joint, Link
    from sensorkit.model.transforms import Mat, Pose


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


class Poses:
    """The pose questions of a :class:`~sensorkit.model.robot.Robot` (whose fields these are)."""

    links: list[Link]
    link_map: dict[str, Link]
    parent_joint: dict[str, Joint]
    child_joints: dict[str, list[Joint]]
    _T_world: dict[str, Pose | None]
    cache: dict[Any, Any]

    if TYPE_CHECKING:

        def tree_of(self, link: str) -> str: ...  # the robot's Tree answers

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
