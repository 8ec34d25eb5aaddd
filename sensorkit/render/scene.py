"""The world the robot is previewed in: shapes at known poses, and their exact geometry.

Every shape the checks rely on is a primitive (box, sphere, cylinder, or the ground
plane ``z = 0``) with a known pose, so a ray's first hit can be computed exactly
(``Shape.intersect``) and compared with what pybullet rendered or cast.

The default scene is a room whose inner wall faces are ``half`` metres from the origin
along +-x and +-y (3 m unless the robot is too big for it), four rotated crates near the
corners, and small marker spheres in front of every wall at known positions. Walls,
crates and floor carry procedural textures. A user scene (``--scene``) is a URDF of static
objects; its boxes, spheres and cylinders are read the same way, and its spheres serve as
markers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sensorkit.model.transforms_np import Mat, transform

if TYPE_CHECKING:
    from lxml import etree

    from sensorkit.model.robot import Robot
    from sensorkit.render.textures import Texture

__all__ = ["MARKER_RGBA", "Scene", "Shape", "box_mesh", "default_scene", "scene_shapes_from_robot"]

Array = npt.NDArray[np.float64]

GROUND = "ground"
MARKER = "marker"
MARKER_RGBA = (0.9, 0.667, 0.0, 1.0)  # amber: magenta is kept for where RViz puts data


@dataclass
class Shape:
    """One primitive at a known pose (``T_world`` is the pose of its centre).

    ``size``: box half extents (3); sphere ``(radius,)``; cylinder ``(radius, half_length)``
    along its local z; ground and mesh ``()``.
    """

    name: str
    kind: str  # box | sphere | cylinder | ground | mesh
    T_world: Mat
    size: tuple[float, ...] = ()
    role: str = "object"  # ground | wall | crate | marker | object
    rgba: tuple[float, float, float, float] = (0.7, 0.7, 0.7, 1.0)
    texture: str | None = None
    uv_per_m: float = 1.0
    visual: bool = True
    collision: bool = True
    link: str | None = None  # the scene URDF link it belongs to (user scenes)

    @property
    def centre(self) -> Array:
        return self.T_world[:3, 3].copy()

    @property
    def is_flat(self) -> bool:
        """Rendered exactly (no tessellation): boxes and the ground."""
        return self.kind in ("box", GROUND)

    def intersect(self, origins: Array, dirs: Array) -> Array:
        """Distance along each unit ray to the first entry into the shape (NaN: none).

        Rays starting inside a solid shape report NaN, as Bullet's ray test does.
        """
        return self.hit(origins, dirs)[0]

    def hit(self, origins: Array, dirs: Array) -> tuple[Array, Array]:
        """(distance, unit outward normal in the world) of each ray's first entry."""
        o = np.asarray(origins, dtype=np.float64).reshape(-1, 3)
        d = np.asarray(dirs, dtype=np.float64).reshape(-1, 3)
        if self.kind == GROUND:
            with np.errstate(divide="ignore", invalid="ignore"):
                t = -o[:, 2] / d[:, 2]
            t = np.where((d[:, 2] < 0) & (o[:, 2] > 0) & (t > 0), t, np.nan)
            return t, np.tile([0.0, 0.0, 1.0], (len(o), 1))
        R, c = self.T_world[:3, :3], self.T_world[:3, 3]
        lo = (o - c) @ R  # R^T (o - c), row-wise
        ld = d @ R
        if self.kind == "box":
            t, n = _box(lo, ld, np.asarray(self.size))
        elif self.kind == "sphere":
            t, n = _sphere(lo, ld, self.size[0])
        elif self.kind == "cylinder":
            t, n = _cylinder(lo, ld, self.size[0], self.size[1])
        else:
            return np.full(len(o), np.nan), np.zeros((len(o), 3))
        return t, n @ R.T

    @property
    def bounding_radius(self) -> float:
        """Radius of a sphere about ``centre`` holding the whole shape (inf: unbounded)."""
        if self.kind == "box":
            return math.sqrt(sum(float(v) * float(v) for v in self.size))
        if self.kind == "sphere":
            return float(self.size[0])
        if self.kind == "cylinder":
            return math.hypot(float(self.size[0]), float(self.size[1]))
        return math.inf

    def footprint(self) -> Array:
        """Points whose xy convex hull is the shape seen from above."""
        return self.outline()[:, :2]

    def outline(self) -> Array:
        """World points whose convex hull, seen along any world axis, is the shape's
        silhouette from that side (a sphere's three great circles); none for ground and
        meshes."""
        a = np.linspace(0, 2 * np.pi, 24, endpoint=False)
        if self.kind == "box":
            hx, hy, hz = self.size
            local = np.array(
                [[sx * hx, sy * hy, sz * hz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
            )
        elif self.kind == "sphere":
            r = self.size[0]
            c, s = r * np.cos(a), r * np.sin(a)
            zero = np.zeros_like(a)
            circles = np.concatenate(
                [np.stack(v, axis=1) for v in ((c, s, zero), (c, zero, s), (zero, c, s))]
            )
            return np.asarray(circles + self.centre, dtype=np.float64)
        elif self.kind == "cylinder":
            r, h = self.size
            ring = np.stack([r * np.cos(a), r * np.sin(a), np.zeros_like(a)], axis=1)
            cap = np.array([0.0, 0.0, h])
            local = np.concatenate([ring + cap, ring - cap])
        else:
            return np.zeros((0, 3))
        world: Array = local @ self.T_world[:3, :3].T + self.T_world[:3, 3]
        return world


def _box(o: Array, d: Array, h: Array) -> tuple[Array, Array]:
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / d
        t1 = (-h - o) * inv
        t2 = (h - o) * inv
    # a ray parallel to a slab: inside it for all t (enters at -inf, leaves at +inf), or
    # never (enters at +inf)
    parallel = d == 0
    inside_slab = np.abs(o) <= h
    t1 = np.where(parallel, np.where(inside_slab, -np.inf, np.inf), t1)
    t2 = np.where(parallel, np.inf, t2)
    entry = np.minimum(t1, t2)
    leave = np.maximum(t1, t2)
    axis = entry.argmax(axis=1)
    # max and min over the three slabs, column by column (numpy reduces along a short
    # last axis several times slower; the result is the same, NaN included)
    t_near = np.maximum(np.maximum(entry[:, 0], entry[:, 1]), entry[:, 2])
    t_far = np.minimum(np.minimum(leave[:, 0], leave[:, 1]), leave[:, 2])
    hit = (t_near <= t_far) & (t_near > 0)
    n = np.zeros_like(o)
    rows = np.arange(len(o))
    n[rows, axis] = -np.sign(d[rows, axis])
    return np.where(hit, t_near, np.nan), n


def _sphere(o: Array, d: Array, r: float) -> tuple[Array, Array]:
    b = np.einsum("ij,ij->i", o, d)
    c = np.einsum("ij,ij->i", o, o) - r * r
    disc = b * b - c
    with np.errstate(invalid="ignore"):
        t = -b - np.sqrt(disc)
    t = np.where((disc >= 0) & (c > 0) & (t > 0), t, np.nan)
    n = (o + d * np.nan_to_num(t)[:, None]) / r
    return t, n


def _cylinder(o: Array, d: Array, r: float, h: float) -> tuple[Array, Array]:
    best = np.full(len(o), np.inf)
    n = np.zeros_like(o)
    inside = (o[:, 0] ** 2 + o[:, 1] ** 2 < r * r) & (np.abs(o[:, 2]) < h)
    a = d[:, 0] ** 2 + d[:, 1] ** 2
    b = o[:, 0] * d[:, 0] + o[:, 1] * d[:, 1]
    c = o[:, 0] ** 2 + o[:, 1] ** 2 - r * r
    disc = b * b - a * c
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (-b - np.sqrt(disc)) / a
    z = o[:, 2] + t * d[:, 2]
    ok = (a > 0) & (disc >= 0) & (t > 0) & (np.abs(z) <= h) & (t < best)
    best = np.where(ok, t, best)
    p = o + d * np.where(ok, t, 0.0)[:, None]
    n[ok] = np.stack([p[ok, 0] / r, p[ok, 1] / r, np.zeros(int(ok.sum()))], axis=1)
    for cap in (-h, h):
        with np.errstate(divide="ignore", invalid="ignore"):
            tc = (cap - o[:, 2]) / d[:, 2]
            x = o[:, 0] + tc * d[:, 0]
            y = o[:, 1] + tc * d[:, 1]
        ok = (d[:, 2] != 0) & (tc > 0) & (x * x + y * y <= r * r) & (tc < best)
        best = np.where(ok, tc, best)
        n[ok] = (0.0, 0.0, 1.0 if cap > 0 else -1.0)
    return np.where(np.isfinite(best) & ~inside, best, np.nan), n


def box_mesh(
    half: tuple[float, float, float], uv_per_m: float
) -> tuple[list[list[float]], list[int], list[list[float]], list[list[float]]]:
    """Vertices, triangle indices, uvs and normals of a box whose texture repeats every
    ``1 / uv_per_m`` metres on every face (pybullet's own box maps one texel per face).
    The middle of each face takes the middle of the texture (uv 0.5): a face no wider
    than ``1 / uv_per_m`` shows one copy, with no seam."""
    vertices: list[list[float]] = []
    uvs: list[list[float]] = []
    normals: list[list[float]] = []
    indices: list[int] = []
    for axis in range(3):
        b, c = (axis + 1) % 3, (axis + 2) % 3
        for sign in (1.0, -1.0):
            corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
            if sign < 0:
                corners = corners[::-1]
            start = len(vertices)
            for u, v in corners:
                p = [0.0, 0.0, 0.0]
                p[axis] = sign * half[axis]
                p[b] = u * half[b]
                p[c] = v * half[c]
                vertices.append(p)
                uvs.append([0.5 + u * half[b] * uv_per_m, 0.5 + v * half[c] * uv_per_m])
                n = [0.0, 0.0, 0.0]
                n[axis] = sign
                normals.append(n)
            indices += [start, start + 1, start + 2, start, start + 2, start + 3]
    return vertices, indices, uvs, normals


@dataclass
class Scene:
    """Shapes to load, where they came from, and the textures they use."""

    shapes: list[Shape]
    source: str  # "default" or the scene file as the user named it
    half_extent: float  # a square of this half size around the origin holds the scene
    urdf: Path | None = None
    textures: dict[str, Texture] = field(default_factory=dict)  # made when loaded

    @property
    def markers(self) -> list[Shape]:
        return [s for s in self.shapes if s.role == MARKER and s.visual]


def default_scene(reach: float, *, textured: bool = True) -> Scene:
    """The room, crates and markers, sized so the robot (``reach`` metres from the origin
    at most) stands inside with at least 1.5 m to spare.

    ``textured=False`` leaves ``textures`` empty (the shapes still name theirs): for a
    preview without cameras, whose rays meet collision shapes and never see a texture.
    """
    half = max(3.0, math.ceil((reach + 1.5) * 2.0) / 2.0)
    s = half / 3.0  # everything else scales with the room
    height = 2.5 * s
    thick = 0.2
    shapes: list[Shape] = [
        Shape("ground", GROUND, np.eye(4), (), GROUND, (1, 1, 1, 1), "floor", 1.0),
    ]
    seeds: dict[str, tuple[int, int]] = {"floor": (7, 256)}  # texture -> (seed, size)
    walls = [
        ("wall_+x", (half + thick / 2, 0.0), (thick / 2, half + thick, height / 2)),
        ("wall_-x", (-half - thick / 2, 0.0), (thick / 2, half + thick, height / 2)),
        ("wall_+y", (0.0, half + thick / 2), (half + thick, thick / 2, height / 2)),
        ("wall_-y", (0.0, -half - thick / 2), (half + thick, thick / 2, height / 2)),
    ]
    # one copy of a wall's texture spans the whole wall: a camera never sees it repeat
    # (a 512 px texture: 80 texels a metre in the 6.4 m wall of the smallest room)
    once = 1.0 / (2.0 * (half + thick))
    for i, (name, (x, y), size) in enumerate(walls):
        key = f"wall{i}"
        seeds[key] = (100 + i, 512)
        shapes.append(
            Shape(name, "box", transform((x, y, height / 2)), size, "wall", (1, 1, 1, 1), key, once)
        )
    crate = (0.3 * s, 0.3 * s, 0.4 * s)
    for i, (sx, sy) in enumerate(((1, 1), (-1, 1), (-1, -1), (1, -1))):
        key = f"crate{i}"
        seeds[key] = (200 + i, 128)
        T = transform((sx * 0.62 * half, sy * 0.62 * half, crate[2]), (0.0, 0.0, 0.45 + 0.3 * i))
        shapes.append(Shape(f"crate_{i}", "box", T, crate, "crate", (1, 1, 1, 1), key, 1.2 / s))
    radius = 0.05 * s
    standoff = 0.25 * s
    for axis, sign, wall in ((0, 1, "+x"), (0, -1, "-x"), (1, 1, "+y"), (1, -1, "-y")):
        for lateral in (-0.75, -0.45, -0.15, 0.15, 0.45, 0.75):
            for z in (0.3, 0.9, 1.6):
                p = [0.0, 0.0, z * s]
                p[axis] = sign * (half - standoff)
                p[1 - axis] = lateral * half
                shapes.append(
                    Shape(
                        f"marker{wall}_{lateral:+.2f}_{z:.1f}",
                        "sphere",
                        transform(p),
                        (radius,),
                        MARKER,
                        MARKER_RGBA,
                    )
                )
    textures: dict[str, Texture] = {}
    if textured:
        from sensorkit.render.textures import Texture

        for key, (seed, pixels) in seeds.items():
            textures[key] = Texture("floor" if key == "floor" else "feature", seed, pixels)
    return Scene(shapes, "default", half + thick, None, textures)


def _geometry_shape(
    el: etree._Element, T_world: Mat, name: str, link: str, visual: bool
) -> Shape | None:
    from sensorkit.model.parse import child, parse_float, parse_vec

    geometry = child(el, "geometry")
    if geometry is None:
        return None
    origin = child(el, "origin")
    xyz, _ = parse_vec(origin.get("xyz")) if origin is not None else (None, None)
    rpy, _ = parse_vec(origin.get("rpy")) if origin is not None else (None, None)
    T = T_world @ transform(xyz or (0, 0, 0), rpy or (0, 0, 0))
    common = {"T_world": T, "visual": visual, "collision": not visual, "link": link}
    for g in geometry:
        tag = g.tag if isinstance(g.tag, str) else ""
        if tag == "box":
            size, _ = parse_vec(g.get("size"))
            if size is not None:
                return Shape(name, "box", size=tuple(abs(v) / 2 for v in size), **common)  # type: ignore[arg-type]
        elif tag == "sphere":
            r, _ = parse_float(g.get("radius"))
            if r is not None:
                return Shape(name, "sphere", size=(abs(r),), role=MARKER, **common)  # type: ignore[arg-type]
        elif tag == "cylinder":
            r, _ = parse_float(g.get("radius"))
            length, _ = parse_float(g.get("length"))
            if r is not None and length is not None:
                return Shape(name, "cylinder", size=(abs(r), abs(length) / 2), **common)  # type: ignore[arg-type]
        elif tag == "mesh":
            return Shape(name, "mesh", **common)  # type: ignore[arg-type]
    return None


def scene_shapes_from_robot(scene: Robot, poses: dict[str, Mat] | None = None) -> list[Shape]:
    """Every visual and collision primitive of a URDF at ``poses`` (default: zero joints)."""
    from sensorkit.model.frames_np import T_world_link_np
    from sensorkit.model.parse import children

    shapes: list[Shape] = []
    for link in scene.links:
        T = poses.get(link.name) if poses is not None else T_world_link_np(scene, link.name)
        if T is None:
            continue
        for kind in ("visual", "collision"):
            for i, el in enumerate(children(link.element, kind)):
                shape = _geometry_shape(
                    el, T, f"{link.name}/{kind}{i}", link.name, kind == "visual"
                )
                if shape is not None:
                    shapes.append(shape)
    return shapes
