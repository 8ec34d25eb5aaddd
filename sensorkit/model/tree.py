"""The kinematic tree of a robot: who hangs from whom, tree tops, depths and chains.

:class:`Tree` is a base of :class:`~sensorkit.model.robot.Robot`: it fills the robot's maps
from parent to child joints and back, and answers from them. Duplicate names and cycles are
kept as written (the first of a name counts; walks stop on a cycle), so that the rules can
report them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from sensorkit.model.parts import Joint, Link


class Tree:
    """The tree questions of a :class:`~sensorkit.model.robot.Robot` (whose fields these are)."""

    links: list[Link]
    joints: list[Joint]
    link_map: dict[str, Link]
    joint_map: dict[str, Joint]
    parent_joint: dict[str, Joint]
    child_joints: dict[str, list[Joint]]
    # (tree top, number of ancestors) of links whose way up has no cycle
    _up: dict[str, tuple[str, int]]
    _roots: list[str] | None

    def index_tree(self) -> None:
        """Fill the maps by name, of links, joints, parent joint and child joints, from
        ``links`` and ``joints`` (the first of a name, or of a child, counts)."""
        links, joints = self.links, self.joints
        link_map, joint_map = self.link_map, self.joint_map
        parent_joint, child_joints = self.parent_joint, self.child_joints
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
