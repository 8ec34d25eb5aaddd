"""Cameras: what the simulator renders, what camera_info publishes, and how they compare.

Pixel coordinates
-----------------
Everything measured in an image here uses 0-based pixel-centre coordinates: pixel
``(i, r)`` (column, row) covers ``[i - 0.5, i + 0.5] x [r - 0.5, r + 0.5]``, as OpenCV and
ROS image_geometry read them. In those coordinates:

* Gazebo (Classic and Sim, OpenGL rasterisers that sample at pixel centres) renders a
  symmetric frustum whose optical axis passes through ``((W-1)/2, (H-1)/2)``; with
  ``<lens><intrinsics>`` gz-sensors builds the frustum from ``cx, cy`` read with pixel
  edges at integers, i.e. its axis passes through ``(cx - 0.5, cy - 0.5)``.
* pybullet's TinyRenderer samples pixel ``(i, r)`` at viewport point ``(i, H - 1 - r)``,
  not at the pixel centre: with pybullet's own symmetric projection
  (``computeProjectionMatrixFOV``) its optical axis lands on ``(W/2, H/2 - 1)``, half a
  pixel right of and half a pixel above Gazebo's. ``RenderCamera.projection_matrix``
  builds the frustum so that pixel ``(i, r)`` sees exactly the direction
  ``((i - cx)/fx, (r - cy)/fy, 1)`` of the camera being emulated; the preview's images
  are therefore Gazebo's images, pixel for pixel (up to rasterisation).
* camera_info's K is written in the simulator's convention: classic ``cx = (W+1)/2``
  (the image centre if the first pixel's centre is 1), gz ``cx = W/2`` (first centre at
  0.5), ideal ``cx = (W-1)/2`` (first centre at 0). ``PIXEL_ORIGIN`` holds those offsets.

The reprojection check projects every visible marker through the published K, moves the
result by the convention's ``PIXEL_ORIGIN`` into 0-based pixel-centre coordinates, and
compares it with the marker's centroid in the image: that residual is what the check
judges (it catches a wrong pose, fov, focal length or principal point). The constant
``PIXEL_ORIGIN`` bias that a 0-based consumer (OpenCV, image_geometry, ORB-SLAM3) sees
when it uses camera_info's K as is, 1 px for classic and 0.5 px for gz, is reported
beside it, measured as well as predicted.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sensorkit.describe.intrinsics import Intrinsics
from sensorkit.model.transforms_np import R_BODY_OPTICAL, Mat, invert
from sensorkit.render._stats import median, percentile, unique
from sensorkit.render.checks import Check

if TYPE_CHECKING:
    from sensorkit.model.sensors import CameraSpec, Sensor
    from sensorkit.render.scene import Shape
    from sensorkit.render.sim import CameraImage

__all__ = [
    "PIXEL_ORIGIN",
    "RenderCamera",
    "depth_check",
    "depth_from_buffer",
    "orb_check",
    "render_camera",
    "reprojection_check",
]

PIXEL_ORIGIN = {"classic": 1.0, "gz": 0.5, "ideal": 0.0}
REPROJECTION_LIMIT_PX = 0.5
DEPTH_LIMIT_M = 0.01
DEPTH_SAMPLES = 20_000
# ORB-SLAM3 Tracking: monocular initialisation needs more than 100 keypoints in each of
# two frames, stereo/RGB-D initialisation more than 500 (StereoInitialization).
ORB_NEEDED = {"mono": 100, "rgbd": 500}

FloatArray = npt.NDArray[np.float64]


@dataclass
class RenderCamera:
    """The pinhole camera the simulator renders, in 0-based pixel-centre coordinates."""

    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float
    skew: float
    near: float
    far: float
    T_world_render: Mat  # x forward, y left, z up (Gazebo's camera frame)
    notes: list[str] = field(default_factory=list)

    @property
    def T_world_optical(self) -> Mat:
        T = np.eye(4)
        T[:3, :3] = R_BODY_OPTICAL
        out: Mat = self.T_world_render @ T
        return out

    def view_matrix(self) -> list[float]:
        """OpenGL view matrix (column-major): eye frame x right, y up, z backwards."""
        T_world_eye = self.T_world_optical.copy()
        T_world_eye[:3, 1:3] *= -1.0
        V = invert(T_world_eye)
        return [float(v) for v in V.T.ravel()]

    def projection_matrix(self) -> list[float]:
        """Projection for TinyRenderer so that pixel (i, r) sees ((i-cx)/fx, (r-cy)/fy, 1).

        TinyRenderer samples NDC ``x = 2i/W - 1`` and ``y = 1 - 2(r+1)/H`` (see the module
        docstring); solving ``u = fx X/Z + s Y/Z + cx``, ``v = fy Y/Z + cy`` for the
        clip coordinates gives the first two rows; the last two are OpenGL's.
        """
        W, H, n, f = self.width, self.height, self.near, self.far
        M = np.array(
            [
                [2 * self.fx / W, -2 * self.skew / W, 1 - 2 * self.cx / W, 0.0],
                [0.0, 2 * self.fy / H, 2 * (self.cy + 1) / H - 1, 0.0],
                [0.0, 0.0, -(f + n) / (f - n), -2 * f * n / (f - n)],
                [0.0, 0.0, -1.0, 0.0],
            ]
        )
        return [float(v) for v in M.T.ravel()]

    def pixel_rays(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(origin (3,), unit directions in the world (H, W, 3), cos to the axis (H, W))."""
        cols = np.arange(self.width, dtype=np.float64)[None, :]
        rows = np.arange(self.height, dtype=np.float64)[:, None]
        return self.rays_at(*np.broadcast_arrays(cols, rows))

    def rays_at(
        self, cols: FloatArray, rows: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Like ``pixel_rays`` for the pixels at ``cols``, ``rows`` (any matching shape)."""
        y = (np.asarray(rows, dtype=np.float64) - self.cy) / self.fy
        x = (np.asarray(cols, dtype=np.float64) - self.cx - self.skew * y) / self.fx
        d = np.stack([x, y, np.ones_like(x)], axis=-1)
        norm = np.linalg.norm(d, axis=-1)
        d /= norm[..., None]
        T = self.T_world_optical
        return T[:3, 3].copy(), d @ T[:3, :3].T, 1.0 / norm

    def world_to_optical(self, points: FloatArray) -> FloatArray:
        T = invert(self.T_world_optical)
        out: FloatArray = np.asarray(points) @ T[:3, :3].T + T[:3, 3]
        return out


def depth_from_buffer(
    buffer: npt.NDArray[np.float32], near: float, far: float
) -> npt.NDArray[np.float32]:
    """OpenGL depth buffer to metres along the optical axis; nothing rendered -> +inf."""
    d = buffer.astype(np.float64)
    with np.errstate(divide="ignore"):
        z = far * near / (far - (far - near) * d)
    z[d >= 1.0] = np.inf
    return z.astype(np.float32)


def render_camera(
    sensor: Sensor, cam: CameraSpec, target: str, T_world_render: Mat, published: Intrinsics
) -> RenderCamera:
    """The camera the simulator actually renders (which camera_info may not describe).

    ``published`` is the camera_info (``sensorkit.describe.published.published_intrinsics``).
    """
    from sensorkit.describe.published import SDF_DEFAULTS, camera_size, convention_of

    notes: list[str] = []
    width, height, hfov = camera_size(cam, [])
    if convention_of(target) == "gz" and cam.lens_intrinsics is not None:
        fx, fy, cx, cy, skew = cam.lens_intrinsics
        cx0, cy0 = cx - PIXEL_ORIGIN["gz"], cy - PIXEL_ORIGIN["gz"]
    else:
        if convention_of(target) == "gz":
            fx, fy = published.fx, published.fy
        else:
            fx = fy = width / (2.0 * math.tan(hfov / 2.0))
        cx0, cy0, skew = (width - 1) / 2.0, (height - 1) / 2.0, 0.0
    near = cam.near if cam.near is not None and cam.near > 0 else SDF_DEFAULTS["near"]
    far = cam.far if cam.far is not None and cam.far > near else max(SDF_DEFAULTS["far"], near * 10)
    return RenderCamera(width, height, fx, fy, cx0, cy0, skew, near, far, T_world_render, notes)


# ---- checks ------------------------------------------------------------------------------
def _interior_at(
    seg: npt.NDArray[np.int32], rows: npt.NDArray[np.intp], cols: npt.NDArray[np.intp]
) -> npt.NDArray[np.bool_]:
    """For the given pixels: do their 4 neighbours show the same body and link?"""
    H, W = seg.shape
    ok: npt.NDArray[np.bool_] = (rows > 0) & (rows < H - 1) & (cols > 0) & (cols < W - 1)
    r, c = np.clip(rows, 1, H - 2), np.clip(cols, 1, W - 2)
    k = seg[r, c]
    ok &= (seg[r - 1, c] == k) & (seg[r + 1, c] == k) & (seg[r, c - 1] == k) & (seg[r, c + 1] == k)
    return ok


def reprojection_check(
    camera: RenderCamera,
    image: CameraImage,
    published: Intrinsics,
    markers: list[tuple[Shape, int, int]],
) -> Check:
    """Markers' image centroids against their projection through camera_info's K."""
    origin = PIXEL_ORIGIN[published.convention]
    if not markers:
        return Check("reprojection", "skipped", "the scene has no markers")
    centres = np.array([m.centre for m, _, _ in markers])
    p_opt = camera.world_to_optical(centres)
    predicted = published.project(p_opt)  # in the convention's coordinates
    rows: list[dict[str, float | str]] = []
    for (shape, body, link), p, uv in zip(markers, p_opt, predicted, strict=True):
        row = _marker_offset(camera, image, shape, body, link, p, uv, origin)
        if row is not None:
            rows.append(row)
    if not rows:
        return Check(
            "reprojection", "skipped", "no marker is fully in view (markers need 12 or more pixels)"
        )
    du_all = np.array([r["du"] for r in rows], dtype=np.float64)
    dv_all = np.array([r["dv"] for r in rows], dtype=np.float64)
    err = np.hypot(du_all, dv_all)
    rms = float(np.sqrt(np.mean(err**2)))
    worst_px = float(err.max())
    # where K, read 0-based as is, puts the markers, minus where they are
    bias = (origin - float(np.mean(du_all)), origin - float(np.mean(dv_all)))
    details = {
        "markers": len(rows),
        "rms_px": rms,
        "max_px": worst_px,
        "convention": published.convention,
        "pixel_origin": origin,
        "rendered_principal_point": [camera.cx, camera.cy],
        "published_principal_point": [published.cx, published.cy],
        "zero_based_bias_px": [bias[0], bias[1]],
        "zero_based_bias_predicted_px": [published.cx - camera.cx, published.cy - camera.cy],
        "per_marker": rows[:50],
    }
    status = "ok" if rms <= REPROJECTION_LIMIT_PX else "fail"
    message = (
        f"{len(rows)} markers land {rms:.2f} px (rms, worst {worst_px:.2f} px) from camera_info's K "
        f"({published.convention} convention, first pixel centre at {origin:g})"
    )
    if abs(published.cx - camera.cx) > 1e-9 or abs(published.cy - camera.cy) > 1e-9:
        message += (
            f"; read 0-based (OpenCV, image_geometry) that K is off by ({bias[0]:+.2f}, {bias[1]:+.2f}) px "
            f"(predicted ({published.cx - camera.cx:+.2f}, {published.cy - camera.cy:+.2f}))"
        )
    return Check("reprojection", status, message, rms, "px", REPROJECTION_LIMIT_PX, details)


def _marker_offset(
    camera: RenderCamera,
    image: CameraImage,
    shape: Shape,
    body: int,
    link: int,
    p: FloatArray,
    uv: FloatArray,
    origin: float,
) -> dict[str, float | str] | None:
    """Where marker ``shape`` (centre ``p`` in the optical frame) is in the image, and how
    far from ``uv``, where camera_info's K puts it (in the convention's coordinates, whose
    first pixel centre is at ``origin``); None when it cannot be measured to a fraction of
    a pixel: behind the camera, at the image's border, too small, or partly hidden."""
    from sensorkit.render.sim import seg_key

    W, H = camera.width, camera.height
    if not np.isfinite(uv).all() or p[2] <= camera.near:
        return None
    radius = shape.size[0]
    expected = math.pi * (camera.fx * radius / p[2]) * (camera.fy * radius / p[2])
    u0, v0 = uv[0] - origin, uv[1] - origin
    # where the renderer puts it (0-based), to look for it; K may disagree
    ur = camera.fx * p[0] / p[2] + camera.skew * p[1] / p[2] + camera.cx
    vr = camera.fy * p[1] / p[2] + camera.cy
    r_px = max(camera.fx, camera.fy) * radius / p[2]
    if not (r_px + 1 <= ur <= W - 2 - r_px and r_px + 1 <= vr <= H - 2 - r_px):
        return None
    reach = math.ceil(1.5 * r_px + 3)
    c0, c1 = max(0, int(ur) - reach), min(W, int(ur) + reach + 2)
    r0, r1 = max(0, int(vr) - reach), min(H, int(vr) + reach + 2)
    mask = image.seg[r0:r1, c0:c1] == seg_key(body, link)
    count = int(mask.sum())
    if count < 12 or count < 0.7 * expected:
        return None  # too small to measure to a fraction of a pixel, or partly hidden
    ys, xs = np.nonzero(mask)
    xs, ys = xs + c0, ys + r0
    if xs.min() == 0 or ys.min() == 0 or xs.max() == W - 1 or ys.max() == H - 1:
        return None
    du, dv = float(xs.mean() - u0), float(ys.mean() - v0)
    return {
        "marker": shape.name,
        "u": float(xs.mean()),
        "v": float(ys.mean()),
        "du": du,
        "dv": dv,
        "pixels": count,
    }


def depth_check(
    camera: RenderCamera,
    image: CameraImage,
    depth: npt.NDArray[np.float32],
    shapes_of: dict[tuple[int, int], list[Shape]],
) -> Check:
    """Rendered depth against the exact depth of known flat surfaces (boxes, the ground).

    Measured on a regular sample of about 20,000 pixels (every pixel of a small image).
    """
    stride = max(1, round(math.sqrt(camera.width * camera.height / DEPTH_SAMPLES)))
    grid_rows, grid_cols = np.mgrid[0 : camera.height : stride, 0 : camera.width : stride]
    rows, cols = grid_rows.ravel(), grid_cols.ravel()
    keep = _interior_at(image.seg, rows, cols) & np.isfinite(depth[rows, cols])
    rows, cols = rows[keep], cols[keep]
    sample_keys = image.seg[rows, cols]
    origin, dirs, cos = camera.rays_at(cols, rows)
    analytic = np.full(len(rows), np.nan)
    for key in unique(sample_keys):
        if key < 0:
            continue
        body, link = int(key) & 0xFFFFFF, (int(key) >> 24) - 1
        visual = [s for s in shapes_of.get((body, link), []) if s.visual]
        if not visual or not all(s.is_flat for s in visual):
            continue
        sel = sample_keys == key
        d = dirs[sel]
        o = np.broadcast_to(origin, d.shape)
        t = np.fmin.reduce([s.intersect(o, d) for s in visual])
        analytic[sel] = t * cos[sel]
    depth = depth[rows, cols]
    compared = np.isfinite(analytic)
    n = int(compared.sum())
    if n == 0:
        return Check("depth", "skipped", "no known flat surface in view")
    err = np.abs(depth[compared].astype(np.float64) - analytic[compared])
    p99 = percentile(err, 99)
    worst_m = float(err.max())
    status = "ok" if p99 <= DEPTH_LIMIT_M else "fail"
    message = (
        f"rendered depth of {n} pixels on known surfaces is within {p99 * 1000:.2f} mm "
        f"(99th percentile; worst {worst_m * 1000:.2f} mm) of the exact depth"
    )
    details = {"pixels": n, "p99_m": p99, "max_m": worst_m, "median_m": median(err)}
    return Check("depth", status, message, p99, "m", DEPTH_LIMIT_M, details)


def orb_check(rgb: npt.NDArray[np.uint8], kind: str) -> Check:
    """ORB keypoints per frame (OpenCV, optional) against what ORB-SLAM3 needs to start."""
    try:
        import cv2
    except ImportError:
        return Check(
            "orb_features", "skipped", "OpenCV is not installed (pip install 'sensorkit-ros[orb]')"
        )
    need = ORB_NEEDED["rgbd" if kind in ("depth", "rgbd") else "mono"]
    gray = cv2.cvtColor(np.ascontiguousarray(rgb), cv2.COLOR_RGB2GRAY)
    orb = cv2.ORB_create(nfeatures=1000, scaleFactor=1.2, nlevels=8, fastThreshold=20)
    count = len(orb.detect(gray, None))
    status = "ok" if count > need else "warn"
    mode = "RGB-D" if need == ORB_NEEDED["rgbd"] else "monocular"
    message = f"{count} ORB keypoints (1000 asked); ORB-SLAM3 {mode} initialisation needs more than {need}"
    return Check("orb_features", status, message, float(count), "keypoints", float(need))
