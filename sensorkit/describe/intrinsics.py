"""Pinhole intrinsics and LaserScan geometry exactly as the simulators publish them.

Pure math: no I/O, no printing, no global state. Every function validates its inputs
and raises :class:`InvalidValue` (a :class:`ValueError` and a
:class:`~sensorkit.base.errors.UsageError`) with a message naming the offending value.

Three conventions are modelled (see ``camera_intrinsics`` and the helpers it names for
the sources):

``classic``
    Gazebo Classic with ``gazebo_ros_camera`` (ROS 2): ``cx = (W+1)/2``.
``gz``
    Gazebo Sim (gz-sensors with ogre2): ``cx = W/2``, focal length from a float32
    projection matrix.
``ideal``
    The pixel-centre pinhole convention, ``cx = (W-1)/2``: pixel ``i`` spans
    ``[i-0.5, i+0.5]``, so the optical axis passes through the centre of the image.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Literal, get_args

import numpy as np
import numpy.typing as npt

from sensorkit.base.errors import UsageError

__all__ = [
    "LASER_SCAN_FIELDS",
    "Convention",
    "Distortion",
    "Intrinsics",
    "InvalidValue",
    "LaserScanParams",
    "camera_intrinsics",
    "laser_scan",
]

Convention = Literal["classic", "gz", "ideal"]
"""Which simulator's intrinsics to reproduce."""

Distortion = tuple[float, float, float, float, float]
"""Plumb-bob coefficients in ``sensor_msgs/CameraInfo`` order: ``(k1, k2, p1, p2, k3)``."""

FloatArray = npt.NDArray[np.float64]

_CONVENTIONS: tuple[str, ...] = get_args(Convention)
_NO_DISTORTION: Distortion = (0.0, 0.0, 0.0, 0.0, 0.0)

# Near clip plane used to emulate Ogre's float32 frustum (SDF <clip><near> default).
_GZ_NEAR_CLIP = 0.1


class InvalidValue(UsageError, ValueError):
    """A parameter is out of range, not finite, or of the wrong kind."""


# --------------------------------------------------------------------------- checks


def _positive_int(name: str, value: object) -> int:
    """Return ``value`` as an int if it is an integer (not a bool) greater than zero."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value <= 0:
        msg = f"{name} must be a positive integer, got {value!r}"
        raise InvalidValue(msg)
    return int(value)


def _finite(name: str, value: object) -> float:
    """Return ``value`` as a float if it is a real, finite number (not a bool)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        msg = f"{name} must be a finite number, got {value!r}"
        raise InvalidValue(msg)
    number = float(value)
    if not math.isfinite(number):
        msg = f"{name} must be a finite number, got {value!r}"
        raise InvalidValue(msg)
    return number


def _positive(name: str, value: object) -> float:
    number = _finite(name, value)
    if number <= 0.0:
        msg = f"{name} must be greater than zero, got {value!r}"
        raise InvalidValue(msg)
    return number


def _hfov(value: object) -> float:
    number = _finite("hfov", value)
    if not 0.0 < number < math.pi:
        msg = f"hfov must be in (0, pi) radians for a pinhole camera, got {value!r}"
        raise InvalidValue(msg)
    return number


def _distortion(value: object) -> Distortion:
    if value is None:
        return _NO_DISTORTION
    if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
        msg = f"distortion must be (k1, k2, p1, p2, k3), got {value!r}"
        raise InvalidValue(msg)
    items = tuple(value)
    if len(items) != 5:
        msg = f"distortion must have 5 coefficients (k1, k2, p1, p2, k3), got {value!r}"
        raise InvalidValue(msg)
    names = ("k1", "k2", "p1", "p2", "k3")
    k1, k2, p1, p2, k3 = (_finite(f"distortion {n}", v) for n, v in zip(names, items, strict=True))
    return (k1, k2, p1, p2, k3)


def _convention(value: object) -> Convention:
    if value == "classic":
        return "classic"
    if value == "gz":
        return "gz"
    if value == "ideal":
        return "ideal"
    msg = f"convention must be one of {', '.join(_CONVENTIONS)}, got {value!r}"
    raise InvalidValue(msg)


# --------------------------------------------------------------------------- intrinsics


def _or(value: float | None, default: float) -> float:
    return default if value is None else value


@dataclass(frozen=True)
class Intrinsics:
    """A pinhole camera as published in ``sensor_msgs/CameraInfo``.

    ``K = [[fx, skew, cx], [0, fy, cy], [0, 0, 1]]``, ``R = I`` and
    ``P = [[fx, skew, cx, baseline_tx], [0, fy, cy, 0], [0, 0, 1, 0]]``.
    ``baseline_tx`` is ``P[0][3]``, i.e. ``-fx * baseline`` for the right camera of a
    stereo pair (Gazebo Classic's ``hack_baseline``).
    """

    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float
    skew: float = 0.0
    distortion: Distortion = _NO_DISTORTION
    baseline_tx: float = 0.0
    convention: Convention = "ideal"
    # P's own values where the simulator lets them differ from K (Gazebo Classic's
    # P_fx/P_fy/P_cx/P_cy/Ty, Gazebo Sim's <lens><projection>); None: as in K.
    p_fx: float | None = None
    p_fy: float | None = None
    p_cx: float | None = None
    p_cy: float | None = None
    p_ty: float = 0.0

    def __post_init__(self) -> None:
        """Validate and normalise every field (ints stay ints, reals become floats)."""
        set_ = object.__setattr__
        set_(self, "width", _positive_int("width", self.width))
        set_(self, "height", _positive_int("height", self.height))
        set_(self, "fx", _positive("fx", self.fx))
        set_(self, "fy", _positive("fy", self.fy))
        set_(self, "cx", _finite("cx", self.cx))
        set_(self, "cy", _finite("cy", self.cy))
        set_(self, "skew", _finite("skew", self.skew))
        set_(self, "distortion", _distortion(self.distortion))
        set_(self, "baseline_tx", _finite("baseline_tx", self.baseline_tx))
        set_(self, "convention", _convention(self.convention))
        for name in ("p_fx", "p_fy", "p_cx", "p_cy"):
            value = getattr(self, name)
            if value is not None:
                set_(self, name, _finite(name, value))
        set_(self, "p_ty", _finite("p_ty", self.p_ty))

    @property
    def K(self) -> FloatArray:
        """The 3x3 camera matrix (a fresh array on every call)."""
        return np.array(
            [[self.fx, self.skew, self.cx], [0.0, self.fy, self.cy], [0.0, 0.0, 1.0]],
            dtype=np.float64,
        )

    @property
    def R(self) -> FloatArray:
        """The 3x3 rectification matrix: the identity for a simulated camera."""
        return np.eye(3, dtype=np.float64)

    @property
    def P(self) -> FloatArray:
        """The 3x4 projection matrix; ``P[0][3]`` is ``baseline_tx``."""
        return np.array(
            [
                [_or(self.p_fx, self.fx), self.skew, _or(self.p_cx, self.cx), self.baseline_tx],
                [0.0, _or(self.p_fy, self.fy), _or(self.p_cy, self.cy), self.p_ty],
                [0.0, 0.0, 1.0, 0.0],
            ],
            dtype=np.float64,
        )

    @property
    def baseline(self) -> float:
        """The stereo baseline P implies, ``-P[0][3] / P[0][0]`` (0 for a mono camera)."""
        return -self.baseline_tx / _or(self.p_fx, self.fx) + 0.0

    @property
    def hfov(self) -> float:
        """Horizontal field of view in radians, ``2 atan(W / (2 fx))``."""
        return 2.0 * math.atan(self.width / (2.0 * self.fx))

    @property
    def vfov(self) -> float:
        """Vertical field of view in radians, ``2 atan(H / (2 fy))``."""
        return 2.0 * math.atan(self.height / (2.0 * self.fy))

    @property
    def has_distortion(self) -> bool:
        """True when any plumb-bob coefficient is non-zero."""
        return any(c != 0.0 for c in self.distortion)

    def project(
        self, points_optical: npt.ArrayLike, *, apply_distortion: bool = False
    ) -> FloatArray:
        """Project points given in the optical frame (z forward) to pixel coordinates.

        ``u = fx x/z + skew y/z + cx``, ``v = fy y/z + cy``. With ``apply_distortion``
        the normalised coordinates go through the plumb-bob model first (as OpenCV's
        ``projectPoints``). Points with ``z <= 0`` (behind the camera) give NaN.

        Args:
            points_optical: an ``(N, 3)`` array (a single ``(3,)`` point is accepted).
            apply_distortion: apply ``distortion`` (k1, k2, p1, p2, k3).

        Returns:
            An ``(N, 2)`` float64 array of ``(u, v)``.
        """
        pts = np.asarray(points_optical, dtype=np.float64)
        if pts.ndim == 1:
            pts = pts.reshape(1, -1)
        if pts.ndim != 2 or pts.shape[1] != 3:
            msg = f"points_optical must have shape (N, 3), got {pts.shape}"
            raise InvalidValue(msg)
        z = pts[:, 2]
        in_front = z > 0.0
        safe_z = np.where(in_front, z, 1.0)
        x = pts[:, 0] / safe_z
        y = pts[:, 1] / safe_z
        if apply_distortion:
            k1, k2, p1, p2, k3 = self.distortion
            r2 = x * x + y * y
            radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3))
            xd = x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x)
            yd = y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y
            x, y = xd, yd
        u = self.fx * x + self.skew * y + self.cx
        v = self.fy * y + self.cy
        out = np.stack([u, v], axis=1)
        out[~in_front] = np.nan
        return out


def _focal_from_hfov(width: int, hfov: float) -> float:
    """``W / (2 tan(hfov/2))`` in double precision (inf when the tangent underflows to 0)."""
    tangent = math.tan(hfov / 2.0)
    return width / (2.0 * tangent) if tangent > 0.0 else math.inf


def _gz_focal(width: int, height: int, hfov: float) -> tuple[float, float]:
    """Emulate gz-rendering's ogre2 projection matrix read back by gz-sensors.

    gz-rendering (``Ogre2Camera::SetHFOV``) sets ``vfov = 2 atan(tan(hfov/2) / aspect)``
    in double, then Ogre keeps the frustum in ``float`` (``Ogre::Real``):
    ``tanY = tan(fovy/2)``, ``tanX = tanY * aspect``, ``A = 2 n / (2 tanX n)``,
    ``B = 2 n / (2 tanY n)``. gz-sensors reads it back with
    ``gz::rendering::projectionToCameraIntrinsic``: ``fx = A W/2``, ``fy = B H/2``.
    The result agrees with the double formula to float32 precision (~1e-7 relative)
    for ordinary images; as vfov nears pi (very tall images) ``tan`` is ill-conditioned
    and the float32 value drifts further (up to ~1e-3 relative at vfov 3.14).
    """
    f32 = np.float32
    aspect = width / height
    vfov = 2.0 * math.atan(math.tan(hfov / 2.0) / aspect)
    near = f32(_GZ_NEAR_CLIP)
    tan_y = f32(np.tan(f32(f32(vfov) * f32(0.5))))
    tan_x = f32(tan_y * f32(aspect))
    half_w = f32(tan_x * near)
    half_h = f32(tan_y * near)
    two_near = f32(f32(2.0) * near)
    with np.errstate(divide="ignore", over="ignore"):  # a vanishing hfov: inf, refused later
        a = f32(two_near / f32(half_w + half_w))
        b = f32(two_near / f32(half_h + half_h))
    return float(a) * width / 2.0, float(b) * height / 2.0


def _check_applies(
    conv: Convention,
    focal_length: float | None,
    cx: float | None,
    cy: float | None,
    lens_intrinsics: tuple[float, float, float, float, float] | None,
) -> None:
    """Refuse the parameters of another convention than ``conv``."""
    if conv != "classic":
        for name, given in (("focal_length", focal_length), ("cx", cx), ("cy", cy)):
            if given is not None:
                msg = f"{name} is a gazebo_ros_camera (classic) parameter, got {name}={given!r}"
                raise InvalidValue(msg)
    if conv != "gz" and lens_intrinsics is not None:
        msg = f"lens_intrinsics apply to the gz convention only, got {lens_intrinsics!r}"
        raise InvalidValue(msg)


def _classic_pinhole(
    w: int, h: int, fov: float, focal_length: float | None, cx: float | None, cy: float | None
) -> tuple[float, float, float, float, float]:
    """``(fx, fy, cx, cy, skew)`` as Gazebo Classic publishes them.

    gazebo_ros_pkgs ``ros2``, ``gazebo_plugins/src/gazebo_ros_camera.cpp``,
    ``GazeboRosCamera::Load``: ``cx = _sdf->Get<double>("cx", (W+1)/2)`` (any value
    present in the plugin SDF is used verbatim; ROS 1 treated 0 as "auto", ROS 2 does
    not), likewise ``cy`` with ``(H+1)/2``; ``focal_length`` defaults to 0 and 0 means
    ``W / (2 tan(hfov/2))`` (a non-zero value is used verbatim, with a warning when it
    disagrees); ``K = [f 0 cx; 0 f cy; 0 0 1]`` with ``fx = fy = f``; ``R = I``;
    ``P[3] = -f * hack_baseline``; ``D = {k1, k2, t1, t2, k3}`` read from the SDF
    ``<distortion>`` (SDF spells them k1 k2 k3 p1 p2). ``GazeboRosCamera::OnNewDepthFrame``
    builds the point cloud with ``atan2(i - 0.5 (W-1), f)``, i.e. centred on
    ``((W-1)/2, (H-1)/2)``, half a pixel away from the published ``cx, cy``.
    """
    f = _focal_from_hfov(w, fov)
    if focal_length is not None:
        given_f = _finite("focal_length", focal_length)
        if given_f < 0.0:
            msg = f"focal_length must be >= 0 (0 means computed), got {focal_length!r}"
            raise InvalidValue(msg)
        if given_f != 0.0:
            f = given_f
    px = (w + 1.0) / 2.0 if cx is None else _finite("cx", cx)
    py = (h + 1.0) / 2.0 if cy is None else _finite("cy", cy)
    return f, f, px, py, 0.0


def _gz_pinhole(
    w: int, h: int, fov: float, lens_intrinsics: tuple[float, float, float, float, float] | None
) -> tuple[float, float, float, float, float]:
    """``(fx, fy, cx, cy, skew)`` as Gazebo Sim publishes them.

    gz-sensors ``src/CameraSensor.cc``,
    ``CameraSensor::UpdateLensIntrinsicsAndProjection``: without ``<lens><intrinsics>``
    it reads the ogre projection matrix back with
    ``gz::rendering::projectionToCameraIntrinsic`` (``fx = P00 W/2``,
    ``cx = -W (P02 - 1)/2 = W/2``, ``cy = H/2``); Ogre stores that matrix in float32,
    so ``fx`` agrees with ``W / (2 tan(hfov/2))`` to float32 precision (emulated here).
    With ``<lens><intrinsics>`` (fx fy cx cy s) the values are used verbatim.
    ``CameraSensor::PopulateInfo`` writes ``D = {k1, k2, p1, p2, k3}`` and K with
    ``K[0][1] = 0`` even when ``s`` is non-zero (``Intrinsics.K`` keeps the skew the
    image is rendered with). Fortress before 6.8.0 published 277/160/120 defaults
    unless intrinsics were given; that old behaviour is not modelled.
    """
    if lens_intrinsics is None:
        fx, fy = _gz_focal(w, h, fov)
        return fx, fy, w / 2.0, h / 2.0, 0.0
    items = tuple(lens_intrinsics)
    if len(items) != 5:
        msg = f"lens_intrinsics must be (fx, fy, cx, cy, s), got {lens_intrinsics!r}"
        raise InvalidValue(msg)
    return (
        _positive("lens_intrinsics fx", items[0]),
        _positive("lens_intrinsics fy", items[1]),
        _finite("lens_intrinsics cx", items[2]),
        _finite("lens_intrinsics cy", items[3]),
        _finite("lens_intrinsics s", items[4]),
    )


def _pinhole(
    conv: Convention,
    w: int,
    h: int,
    fov: float,
    focal_length: float | None,
    cx: float | None,
    cy: float | None,
    lens_intrinsics: tuple[float, float, float, float, float] | None,
) -> tuple[float, float, float, float, float]:
    """``(fx, fy, cx, cy, skew)`` in the convention ``conv``, from the parameters that
    apply to it (another convention's are refused)."""
    _check_applies(conv, focal_length, cx, cy, lens_intrinsics)
    if conv == "classic":
        return _classic_pinhole(w, h, fov, focal_length, cx, cy)
    if conv == "gz":
        return _gz_pinhole(w, h, fov, lens_intrinsics)
    f = _focal_from_hfov(w, fov)
    return f, f, (w - 1.0) / 2.0, (h - 1.0) / 2.0, 0.0


def _projection(conv: Convention, projection: dict[str, float] | None) -> dict[str, float]:
    """The P overrides (``fx``, ``fy``, ``cx``, ``cy``, ``tx``, ``ty``), checked."""
    proj = dict(projection or {})
    unknown = set(proj) - {"fx", "fy", "cx", "cy", "tx", "ty"}
    if unknown:
        msg = f"projection keys are fx, fy, cx, cy, tx, ty, got {sorted(unknown)}"
        raise InvalidValue(msg)
    if conv == "ideal" and proj:
        msg = "projection overrides apply to the classic and gz conventions only"
        raise InvalidValue(msg)
    return proj


def camera_intrinsics(
    width: int,
    height: int,
    hfov: float,
    convention: Convention,
    *,
    focal_length: float | None = None,
    cx: float | None = None,
    cy: float | None = None,
    lens_intrinsics: tuple[float, float, float, float, float] | None = None,
    distortion: tuple[float, float, float, float, float] | None = None,
    hack_baseline: float = 0.0,
    projection: dict[str, float] | None = None,
) -> Intrinsics:
    """The intrinsics a simulated camera publishes on ``camera_info``.

    Confirmed in the simulators' sources (cited where each is computed, in
    :func:`_classic_pinhole` and :func:`_gz_pinhole`):

    * **classic** - gazebo_ros_camera (ROS 2): ``cx = (W+1)/2``, ``cy = (H+1)/2`` and
      ``fx = fy = W / (2 tan(hfov/2))`` unless the plugin sets them;
      ``P[3] = -f * hack_baseline``.
    * **gz** - gz-sensors: ``fx = W / (2 tan(hfov/2))`` to float32 precision, ``cx = W/2``,
      ``cy = H/2``; ``<lens><intrinsics>`` verbatim when given.
    * **ideal** - ``fx = fy = W / (2 tan(hfov/2))``, ``cx = (W-1)/2``, ``cy = (H-1)/2``:
      the pixel-centre convention, which is also where Gazebo Classic's depth point cloud
      is centred.

    ``vfov`` is ``2 atan(H / (2 fy))`` in every convention.

    Args:
        width: image width in pixels (> 0).
        height: image height in pixels (> 0).
        hfov: horizontal field of view in radians, in (0, pi).
        convention: ``"classic"``, ``"gz"`` or ``"ideal"``.
        focal_length: classic only: the plugin's ``<focal_length>``; ``None`` or 0 means
            computed from ``hfov``.
        cx: classic only: the plugin's ``<cx>`` (``None`` means ``(W+1)/2``).
        cy: classic only: the plugin's ``<cy>`` (``None`` means ``(H+1)/2``).
        lens_intrinsics: gz only: ``<lens><intrinsics>`` as ``(fx, fy, cx, cy, s)``.
        distortion: plumb-bob ``(k1, k2, p1, p2, k3)`` (``None`` means none).
        hack_baseline: stereo baseline in metres: ``P[0][3] = -fx * hack_baseline``.

    Raises:
        InvalidValue: a value is out of range, not finite, or does not apply to the
            chosen convention.
    """
    w = _positive_int("width", width)
    h = _positive_int("height", height)
    fov = _hfov(hfov)
    conv = _convention(convention)
    dist = _distortion(distortion)
    baseline = _finite("hack_baseline", hack_baseline)
    fx, fy, px, py, skew = _pinhole(conv, w, h, fov, focal_length, cx, cy, lens_intrinsics)
    if not (math.isfinite(fx) and math.isfinite(fy)):
        msg = f"hfov {hfov!r} is too small for a {w} px image: the focal length is not finite"
        raise InvalidValue(msg)
    proj = _projection(conv, projection)
    # Classic: P[0][3] = Tx if given, else -f * hack_baseline; gz: <projection><tx>, else 0.
    tx = proj.get("tx", -fx * baseline)
    return Intrinsics(
        width=w,
        height=h,
        fx=fx,
        fy=fy,
        cx=px,
        cy=py,
        skew=skew,
        distortion=dist,
        baseline_tx=_finite("tx", tx) + 0.0,
        convention=conv,
        p_fx=proj.get("fx"),
        p_fy=proj.get("fy"),
        p_cx=proj.get("cx"),
        p_cy=proj.get("cy"),
        p_ty=proj.get("ty", 0.0),
    )


# --------------------------------------------------------------------------- LaserScan


@dataclass(frozen=True)
class LaserScanParams:
    """The fixed fields of a simulated ``sensor_msgs/LaserScan``.

    ``samples`` is the number of ranges in each message (N).
    """

    samples: int
    angle_min: float
    angle_max: float
    angle_increment: float
    range_min: float
    range_max: float
    time_increment: float = 0.0
    scan_time: float = 0.0

    def __post_init__(self) -> None:
        """Validate every field."""
        set_ = object.__setattr__
        set_(self, "samples", _positive_int("samples", self.samples))
        for name in (
            "angle_min",
            "angle_max",
            "angle_increment",
            "range_min",
            "range_max",
            "time_increment",
            "scan_time",
        ):
            set_(self, name, _finite(name, getattr(self, name)))
        if self.range_min < 0.0 or self.range_max <= self.range_min:
            msg = (
                "need 0 <= range_min < range_max, got "
                f"range_min={self.range_min!r}, range_max={self.range_max!r}"
            )
            raise InvalidValue(msg)

    def beam_angles(self) -> FloatArray:
        """The N beam angles, ``angle_min + i * angle_increment``."""
        return self.angle_min + np.arange(self.samples, dtype=np.float64) * self.angle_increment


LASER_SCAN_FIELDS: tuple[str, ...] = (
    "angle_min",
    "angle_max",
    "angle_increment",
    "time_increment",
    "scan_time",
    "range_min",
    "range_max",
)
"""The :class:`LaserScanParams` fields a ``sensor_msgs/LaserScan`` carries, in its order."""


def laser_scan(
    samples: int,
    resolution: float,
    min_angle: float,
    max_angle: float,
    range_min: float,
    range_max: float,
) -> LaserScanParams:
    """The LaserScan a simulated lidar publishes for an SDF ``<scan><horizontal>`` block.

    ``N = floor(samples * resolution)`` beams, ``angle_increment =
    (max_angle - min_angle) / (N - 1)`` (0 when N == 1), ``angle_min/max`` are the SDF
    angles, ``range_min/max`` the SDF ``<range>``, ``time_increment = scan_time = 0``.

    Raises:
        InvalidValue: a value is out of range or not finite, or N < 1.
    """
    n_samples = _positive_int("samples", samples)
    res = _positive("resolution", resolution)
    lo = _finite("min_angle", min_angle)
    hi = _finite("max_angle", max_angle)
    if hi < lo:
        msg = f"max_angle must be >= min_angle, got min_angle={lo!r}, max_angle={hi!r}"
        raise InvalidValue(msg)
    beams = n_samples * res
    if not math.isfinite(beams):
        msg = f"samples * resolution is not a finite beam count, got samples={samples!r}, resolution={resolution!r}"
        raise InvalidValue(msg)
    n = math.floor(beams)
    if n < 1:
        msg = (
            f"samples * resolution must give at least one beam, got samples={samples!r}, "
            f"resolution={resolution!r}"
        )
        raise InvalidValue(msg)
    increment = 0.0 if n == 1 else (hi - lo) / (n - 1)
    return LaserScanParams(
        samples=n,
        angle_min=lo,
        angle_max=hi,
        angle_increment=increment,
        range_min=_finite("range_min", range_min),
        range_max=_finite("range_max", range_max),
    )
