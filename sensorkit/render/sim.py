"""The pybullet side: the only module in sensorkit that imports pybullet.

A :class:`World` is one pybullet client in DIRECT mode (no display, no GUI thread).
pybullet and its C++ core print to the process's stdout and stderr (the build banner on
import, warnings from the URDF importer, TinyRenderer notes); every call that can print
runs inside an :class:`OutputCapture`, which points file descriptors 1 and 2 at a
temporary file at the OS level and restores them afterwards, so nothing reaches the
terminal and the text is still there to explain a failure.

Images come from the CPU TinyRenderer (``ER_TINY_RENDERER``). Rays are cast with
``rayTestBatch`` on all cores, in as few calls as pybullet allows (see ``MAX_RAYS``).
"""

from __future__ import annotations

import contextlib
import ctypes
import gc
import os
import sys
import tempfile
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from operator import itemgetter
from pathlib import Path
from types import ModuleType
from typing import IO, Any

import numpy as np
import numpy.typing as npt

from sensorkit.base.errors import InputError
from sensorkit.model.transforms_np import Mat
from sensorkit.render.scene import GROUND, Scene, Shape, box_mesh
from sensorkit.render.urdf_out import UrdfPart

__all__ = ["MAX_RAYS", "CameraImage", "RayHits", "World", "captured_output"]

# pybullet refuses more than MAX_RAY_INTERSECTION_BATCH_SIZE (16384) rays per call, and a
# call with exactly 16384 returns one result short (pybullet 3.2.7; a numpy input returns
# none at all), so 16383 is the largest batch that comes back whole.
MAX_RAYS = 16383

_LOG_LIMIT = 64 * 1024


def _flush_c_stdio() -> None:
    with contextlib.suppress(Exception):
        ctypes.CDLL(None).fflush(None)


class OutputCapture:
    """Points fds 1 and 2 at one temporary file while active; re-entrant and reusable.

    Nested activations cost nothing; the text written (up to 64 KiB per activation) is
    appended to ``log``.
    """

    def __init__(self, log: list[str] | None = None) -> None:
        self.log = log
        self._depth = 0
        self._sink: IO[bytes] | None = None
        self._saved: tuple[int, int] | None = None

    def __enter__(self) -> OutputCapture:
        self._depth += 1
        if self._depth > 1:
            return self
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        _flush_c_stdio()
        if self._sink is None:
            self._sink = tempfile.TemporaryFile()
        self._sink.seek(0)
        self._sink.truncate()
        self._saved = (os.dup(1), os.dup(2))
        os.dup2(self._sink.fileno(), 1)
        os.dup2(self._sink.fileno(), 2)
        return self

    def __exit__(self, *exc: object) -> None:
        self._depth -= 1
        if self._depth > 0 or self._saved is None or self._sink is None:
            return
        _flush_c_stdio()
        os.dup2(self._saved[0], 1)
        os.dup2(self._saved[1], 2)
        os.close(self._saved[0])
        os.close(self._saved[1])
        self._saved = None
        if self.log is not None:
            self._sink.seek(0)
            text = self._sink.read(_LOG_LIMIT).decode("utf-8", "replace")
            self.log.extend(line for line in text.splitlines() if line.strip())

    def close(self) -> None:
        if self._sink is not None:
            self._sink.close()
            self._sink = None

    def forget_sink(self) -> None:
        """After a fork: leave the shared file to the parent; the next use opens a new one."""
        self._sink = None


@contextlib.contextmanager
def captured_output(log: list[str] | None = None) -> Iterator[None]:
    """Send everything written to fds 1 and 2 to a temporary file while inside.

    The text written (up to 64 KiB) is appended to ``log`` when one is given.
    """
    capture = OutputCapture(log)
    try:
        with capture:
            yield
    finally:
        capture.close()


def _pybullet() -> ModuleType:
    with captured_output():
        import pybullet

    module: ModuleType = pybullet
    return module


def seg_key(body: int, link: int) -> int:
    """pybullet's segmentation value for a (body, link): ``body + ((link + 1) << 24)``."""
    return body + ((link + 1) << 24)


@dataclass
class CameraImage:
    rgb: npt.NDArray[np.uint8]  # (H, W, 3)
    depth_buffer: npt.NDArray[np.float32]  # (H, W), OpenGL depth in [0, 1]
    seg: npt.NDArray[np.int32]  # (H, W) seg_key of what each pixel shows, -1 for nothing

    @property
    def body(self) -> npt.NDArray[np.int32]:
        """(H, W) body id hit, -1 for none."""
        out: npt.NDArray[np.int32] = np.where(self.seg < 0, -1, self.seg & 0xFFFFFF).astype(
            np.int32
        )
        return out

    @property
    def link(self) -> npt.NDArray[np.int32]:
        """(H, W) link index hit (-1: the base, or nothing)."""
        out: npt.NDArray[np.int32] = np.where(self.seg < 0, -1, (self.seg >> 24) - 1).astype(
            np.int32
        )
        return out


@dataclass
class RayHits:
    body: npt.NDArray[np.int32]  # -1: no hit
    link: npt.NDArray[np.int32]
    fraction: npt.NDArray[np.float64]  # along from -> to; 1.0 for no hit
    calls: int  # rayTestBatch calls made


def _quat_to_matrix(q: Sequence[float]) -> Mat:
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def _matrix_to_quat(R: Mat) -> list[float]:
    """(x, y, z, w) of a rotation matrix (Shepperd's method)."""
    m = R
    trace = float(m[0, 0] + m[1, 1] + m[2, 2])
    if trace > 0:
        s = 2.0 * np.sqrt(trace + 1.0)
        return [(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, 0.25 * s]
    i = int(np.argmax([m[0, 0], m[1, 1], m[2, 2]]))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * np.sqrt(1.0 + m[i, i] - m[j, j] - m[k, k])
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = 0.25 * s
    q[j] = (m[j, i] + m[i, j]) / s
    q[k] = (m[k, i] + m[i, k]) / s
    q[3] = (m[k, j] - m[j, k]) / s
    return [float(v) for v in q]


class World:
    """One pybullet DIRECT client holding the ground, the scene and the robot."""

    def __init__(self) -> None:
        self.log: list[str] = []
        self.quiet = OutputCapture(self.log)
        self.p = _pybullet()
        with self.quiet:
            self.client: int = self.p.connect(self.p.DIRECT)
        if self.client < 0:
            msg = "pybullet could not start a DIRECT client"
            raise InputError(msg)
        self.robot_bodies: list[int] = []  # a robot over pybullet's link limit has several
        self.robot_links: dict[tuple[int, int], str] = {}  # (body, link index) -> URDF link
        self.robot_link_at: dict[str, tuple[int, int]] = {}  # URDF link -> (body, link index)
        self.shape_of: dict[tuple[int, int], list[Shape]] = {}  # (body, link) -> shapes
        self._tmp = tempfile.TemporaryDirectory(prefix="sensorkit-render-")

    # ---- lifetime ------------------------------------------------------------------
    def close(self) -> None:
        with contextlib.suppress(Exception), self.quiet:
            self.p.disconnect(physicsClientId=self.client)
        self.quiet.close()
        self._tmp.cleanup()

    def __enter__(self) -> World:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _call(self, name: str, *args: Any, **kwargs: Any) -> Any:
        with self.quiet:
            return getattr(self.p, name)(*args, physicsClientId=self.client, **kwargs)

    def _failure(self, what: str, exc: Exception) -> InputError:
        detail = [line for line in self.log if "error" in line.lower() or "cannot" in line.lower()]
        tail = f": {detail[-1].strip()}" if detail else ""
        return InputError(f"pybullet could not load {what} ({exc}){tail}")

    # ---- building the world --------------------------------------------------------
    def _texture(self, key: str, scene: Scene, cache: dict[str, int]) -> int:
        if key not in cache:
            from sensorkit.render.textures import texture_file

            path = texture_file(scene.textures[key], Path(self._tmp.name))
            cache[key] = int(self._call("loadTexture", str(path)))
        return cache[key]

    def add_default_shapes(self, scene: Scene, ground_half: float) -> None:
        """Create the shapes of a generated scene (and the ground) as static bodies."""
        with self.quiet:
            self._add_default_shapes(scene, ground_half)

    def _add_default_shapes(self, scene: Scene, ground_half: float) -> None:
        cache: dict[str, int] = {}
        markers = [s for s in scene.shapes if s.role == "marker"]
        for shape in scene.shapes:
            if shape.role == "marker":
                continue
            if shape.kind == GROUND:
                self.add_ground(ground_half, scene, shape, cache)
                continue
            half = tuple(float(v) for v in shape.size)
            col = self._call("createCollisionShape", self.p.GEOM_BOX, halfExtents=list(half))
            texture = shape.texture if shape.texture in scene.textures else None
            if texture is not None:
                v, i, uv, n = box_mesh((half[0], half[1], half[2]), shape.uv_per_m)
                vis = self._call(
                    "createVisualShape", self.p.GEOM_MESH, vertices=v, indices=i, uvs=uv, normals=n
                )
            else:
                vis = self._call(
                    "createVisualShape",
                    self.p.GEOM_BOX,
                    halfExtents=list(half),
                    rgbaColor=list(shape.rgba),
                )
            body = self._create(col, vis, shape.T_world)
            if texture is not None:
                tex = self._texture(texture, scene, cache)
                self._call(
                    "changeVisualShape", body, -1, textureUniqueId=tex, rgbaColor=[1, 1, 1, 1]
                )
            self.shape_of[(body, -1)] = [shape]
        if markers:
            r = markers[0].size[0]
            col = self._call("createCollisionShape", self.p.GEOM_SPHERE, radius=r)
            vis = self._call(
                "createVisualShape", self.p.GEOM_SPHERE, radius=r, rgbaColor=list(markers[0].rgba)
            )
            bodies = self._call(
                "createMultiBody",
                0,
                col,
                vis,
                batchPositions=[m.centre.tolist() for m in markers],
            )
            for body, marker in zip(bodies, markers, strict=True):
                self.shape_of[(int(body), -1)] = [marker]

    def add_ground(
        self, half: float, scene: Scene, shape: Shape, cache: dict[str, int] | None = None
    ) -> None:
        """The plane z = 0 for rays and a textured slab whose top face is z = 0 for images."""
        with self.quiet:
            self._add_ground(half, scene, shape, {} if cache is None else cache)

    def _add_ground(self, half: float, scene: Scene, shape: Shape, cache: dict[str, int]) -> None:
        col = self._call("createCollisionShape", self.p.GEOM_PLANE)
        slab = (half, half, 0.01)
        if shape.texture is not None and shape.texture in scene.textures:
            v, i, uv, n = box_mesh(slab, shape.uv_per_m)
            vis = self._call(
                "createVisualShape",
                self.p.GEOM_MESH,
                vertices=v,
                indices=i,
                uvs=uv,
                normals=n,
                visualFramePosition=[0, 0, -0.01],
            )
        else:
            vis = self._call(
                "createVisualShape",
                self.p.GEOM_BOX,
                halfExtents=list(slab),
                rgbaColor=[0.6, 0.58, 0.55, 1],
                visualFramePosition=[0, 0, -0.01],
            )
        body = self._create(col, vis, np.eye(4))
        if shape.texture is not None and shape.texture in scene.textures:
            tex = self._texture(shape.texture, scene, cache)
            self._call("changeVisualShape", body, -1, textureUniqueId=tex, rgbaColor=[1, 1, 1, 1])
        self.shape_of[(body, -1)] = [shape]

    def _create(self, col: int, vis: int, T: Mat) -> int:
        return int(
            self._call(
                "createMultiBody",
                baseMass=0,
                baseCollisionShapeIndex=col,
                baseVisualShapeIndex=vis,
                basePosition=T[:3, 3].tolist(),
                baseOrientation=_matrix_to_quat(T[:3, :3]),
            )
        )

    def load_urdf(
        self, text: bytes, what: str, T_world_base: Mat | None = None
    ) -> tuple[int, dict[int, str]]:
        """Load URDF text as a fixed-base body whose root link frame is at
        ``T_world_base`` (default: the origin); (body, link index -> name)."""
        path = Path(self._tmp.name) / f"{what}.urdf"
        path.write_bytes(text)
        T = np.eye(4) if T_world_base is None else T_world_base
        with self.quiet:
            return self._load_urdf(path, what, T)

    def _load_urdf(self, path: Path, what: str, T: Mat) -> tuple[int, dict[int, str]]:
        flags = self.p.URDF_USE_MATERIAL_COLORS_FROM_MTL
        position = [float(v) for v in T[:3, 3]]
        orientation = _matrix_to_quat(T[:3, :3])
        try:
            body = int(
                self._call(
                    "loadURDF", str(path), position, orientation, useFixedBase=True, flags=flags
                )
            )
        except self.p.error as exc:
            raise self._failure(what, exc) from None
        names: dict[int, str] = {-1: self._call("getBodyInfo", body)[0].decode("utf-8")}
        for j in range(self._call("getNumJoints", body)):
            names[j] = self._call("getJointInfo", body, j)[12].decode("utf-8")
        return body, names

    def add_scene_urdf(self, text: bytes, shapes: list[Shape]) -> int:
        body, names = self.load_urdf(text, "scene")
        by_link: dict[str, list[Shape]] = {}
        for shape in shapes:
            by_link.setdefault(shape.link or "", []).append(shape)
        for index, name in names.items():
            self.shape_of[(body, index)] = by_link.get(name, [])
        return body

    def add_robot(self, text: bytes) -> int:
        """Load a robot that fits in one pybullet body, its root at the origin."""
        return self.add_robot_parts([UrdfPart("", [], text)], {})[0]

    def add_robot_parts(self, parts: Sequence[UrdfPart], poses: Mapping[str, Mat]) -> list[int]:
        """Load a robot as one body per part, each base where ``poses`` puts that link
        (the first part's base is the root, at the origin). Returns the bodies."""
        for k, part in enumerate(parts):
            T = poses.get(part.base) if k else np.eye(4)
            if T is None:
                msg = f"the robot's link {part.base!r} has no pose, so it cannot be placed"
                raise InputError(msg)
            body, names = self.load_urdf(part.text, f"robot{k}" if k else "robot", T)
            self.robot_bodies.append(body)
            for index, name in names.items():
                if index == -1 and part.stand_in:
                    continue  # an empty stand-in: the link itself lives in another body
                self.robot_links[(body, index)] = name
                self.robot_link_at.setdefault(name, (body, index))
        return list(self.robot_bodies)

    def set_joints(self, positions: Mapping[str, float]) -> None:
        for body in self.robot_bodies:
            index = {
                self._call("getJointInfo", body, j)[1].decode("utf-8"): j
                for j in range(self._call("getNumJoints", body))
            }
            for name, value in positions.items():
                if name in index:
                    self._call("resetJointState", body, index[name], value)

    def refresh_bounds(self) -> None:
        """Bring the broadphase's bounding boxes up to date once everything is placed.

        pybullet 3.2.7 leaves a stale box for a link whose URDF ``<inertial>`` frame is
        rotated: ``rayTestBatch`` then misses the link (``getCameraImage`` does not, and
        ``getAABB`` computes afresh, so neither shows it) until the next collision pass.
        """
        with self.quiet:
            self._call("performCollisionDetection")

    # ---- queries ---------------------------------------------------------------------
    def link_frame(self, body: int, link: int) -> Mat:
        """World pose of a link's URDF frame (not its inertial frame)."""
        T = np.eye(4)
        if link == -1:
            pos, orn = self._call("getBasePositionAndOrientation", body)
            local_pos, local_orn = self._call("getDynamicsInfo", body, -1)[3:5]
            T_world_inertial = np.eye(4)
            T_world_inertial[:3, :3] = _quat_to_matrix(orn)
            T_world_inertial[:3, 3] = pos
            T_link_inertial = np.eye(4)
            T_link_inertial[:3, :3] = _quat_to_matrix(local_orn)
            T_link_inertial[:3, 3] = local_pos
            from sensorkit.model.transforms_np import invert

            return T_world_inertial @ invert(T_link_inertial)
        try:
            state = self._call("getLinkState", body, link, computeForwardKinematics=True)
        except self.p.error as exc:
            msg = f"pybullet cannot report where link {link} of body {body} is ({exc})"
            raise InputError(msg) from None
        T[:3, :3] = _quat_to_matrix(state[5])
        T[:3, 3] = state[4]
        return T

    def aabbs(self, body: int) -> list[tuple[int, np.ndarray, np.ndarray]]:
        out = []
        for link in [-1, *range(self._call("getNumJoints", body))]:
            lo, hi = self._call("getAABB", body, link)
            out.append((link, np.array(lo), np.array(hi)))
        return out

    def render(
        self, width: int, height: int, view: list[float], projection: list[float]
    ) -> CameraImage:
        """One TinyRenderer frame with a segmentation mask of (body, link)."""
        flags = self.p.ER_SEGMENTATION_MASK_OBJECT_AND_LINKINDEX
        _, _, rgba, depth, seg = self._call(
            "getCameraImage",
            width,
            height,
            viewMatrix=view,
            projectionMatrix=projection,
            renderer=self.p.ER_TINY_RENDERER,
            flags=flags,
            shadow=0,
        )
        rgba = np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)
        depth = np.asarray(depth, dtype=np.float32).reshape(height, width)
        seg = np.asarray(seg, dtype=np.int32).reshape(height, width)
        return CameraImage(np.ascontiguousarray(rgba[:, :, :3]), depth, seg)

    def cast(self, starts: np.ndarray, ends: np.ndarray) -> RayHits:
        """First hit of each ray from ``starts`` to ``ends`` (``(N, 3)``)."""
        # rayTestBatch answers with a tuple of five per ray (two of them tuples): the
        # cyclic collector would walk them again and again (a tenth of a second of a
        # 262,144-ray scan) though they hold no cycles and are gone within the batch.
        collecting = gc.isenabled()
        gc.disable()
        try:
            with self.quiet:
                return self._cast(starts, ends)
        finally:
            if collecting:
                gc.enable()

    def _cast(self, starts: np.ndarray, ends: np.ndarray) -> RayHits:
        n = len(starts)
        body = np.full(n, -1, dtype=np.int32)
        link = np.full(n, -1, dtype=np.int32)
        fraction = np.ones(n, dtype=np.float64)
        calls = 0
        for lo in range(0, n, MAX_RAYS):
            hi = min(n, lo + MAX_RAYS)
            results = self._call(
                "rayTestBatch",
                np.ascontiguousarray(starts[lo:hi], dtype=np.float64),
                np.ascontiguousarray(ends[lo:hi], dtype=np.float64),
                numThreads=0,
            )
            calls += 1
            if len(results) != hi - lo:
                msg = f"pybullet returned {len(results)} ray results for {hi - lo} rays"
                raise RuntimeError(msg)
            # each result is (body, link, fraction, position, normal)
            body[lo:hi] = np.fromiter(map(itemgetter(0), results), np.int32, hi - lo)
            link[lo:hi] = np.fromiter(map(itemgetter(1), results), np.int32, hi - lo)
            fraction[lo:hi] = np.fromiter(map(itemgetter(2), results), np.float64, hi - lo)
        return RayHits(body, link, fraction, calls)
