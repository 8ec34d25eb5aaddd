"""The transforms a recording holds (``/tf_static`` and ``/tf``) and lookups between frames.

Each child frame keeps one parent and one transform ``T_parent_child``: a static one wins
over a dynamic one, and of dynamic ones the first recorded is kept (a fixed joint's
transform does not change; a moving one is not compared). Frame names lose a leading
``/``, as tf2 drops it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["Edge", "RecordedTF", "frame_name", "quaternion_matrix"]

Mat = npt.NDArray[np.float64]


def frame_name(name: str) -> str:
    """A frame as tf2 names it: without a leading ``/``."""
    return name.strip().lstrip("/")


def quaternion_matrix(x: float, y: float, z: float, w: float) -> Mat:
    """The rotation matrix of a quaternion (normalised first; the zero quaternion is the
    identity, as tf2 refuses it rather than rotate)."""
    n = math.sqrt(x * x + y * y + z * z + w * w)
    if not n or not math.isfinite(n):
        return np.eye(3)
    x, y, z, w = x / n, y / n, z / n, w / n
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


@dataclass(frozen=True)
class Edge:
    """One recorded transform: ``T_parent_child``, and whether it came from /tf_static."""

    parent: str
    T: Mat
    static: bool


@dataclass
class RecordedTF:
    """The TF tree of a recording: each child frame's parent and transform."""

    edges: dict[str, Edge] = field(default_factory=dict)
    frames: set[str] = field(default_factory=set)
    transforms: int = 0  # TransformStamped entries read

    def add(
        self, parent: str, child: str, translation: Any, rotation: Any, *, static: bool
    ) -> None:
        """Keep ``T_parent_child`` unless a static one (or, for a dynamic one, any) is kept."""
        self.transforms += 1
        p, c = frame_name(parent), frame_name(child)
        self.frames.update((p, c))
        have = self.edges.get(c)
        if have is not None and (have.static or not static):
            return
        T = np.eye(4)
        T[:3, :3] = quaternion_matrix(
            float(rotation.x), float(rotation.y), float(rotation.z), float(rotation.w)
        )
        T[:3, 3] = (float(translation.x), float(translation.y), float(translation.z))
        if np.all(np.isfinite(T)):
            self.edges[c] = Edge(p, T, static)

    def knows(self, frame: str) -> bool:
        return frame_name(frame) in self.frames

    def _up(self, frame: str) -> list[str]:
        """``frame`` and its ancestors, nearest first (a cycle ends the walk)."""
        chain = [frame]
        seen = {frame}
        while chain[-1] in self.edges:
            parent = self.edges[chain[-1]].parent
            if parent in seen:
                break
            chain.append(parent)
            seen.add(parent)
        return chain

    def _T_up(self, chain: list[str], top: str) -> Mat:
        """``T_top_frame`` for ``chain`` (frame first) up to ``top``."""
        T = np.eye(4)
        for name in chain:
            if name == top:
                break
            T = self.edges[name].T @ T
        return T

    def lookup(self, target: str, source: str) -> Mat | None:
        """``T_target_source`` (the pose of ``source`` in ``target``), through their
        nearest common ancestor; None when no recorded chain joins them."""
        a, b = frame_name(target), frame_name(source)
        up_a, up_b = self._up(a), self._up(b)
        common = next((f for f in up_a if f in set(up_b)), None)
        if common is None:
            return None
        T_common_a = self._T_up(up_a, common)
        T_common_b = self._T_up(up_b, common)
        return np.linalg.inv(T_common_a) @ T_common_b

    def static_path(self, target: str, source: str) -> bool:
        """Whether every recorded transform between the two frames is a static one."""
        a, b = frame_name(target), frame_name(source)
        up_a, up_b = self._up(a), self._up(b)
        common = next((f for f in up_a if f in set(up_b)), None)
        if common is None:
            return False
        names = up_a[: up_a.index(common)] + up_b[: up_b.index(common)]
        return all(self.edges[n].static for n in names)
