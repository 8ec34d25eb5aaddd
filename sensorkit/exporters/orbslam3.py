"""ORB-SLAM3 settings files, in the old format and in the ``File.version: "1.0"`` format.

Both are read with ``cv::FileStorage``, which tells ints from reals by the literal,
and ORB-SLAM3 checks the kind of every value it reads:

* **v1.0** (``src/Settings.cc``, ``Settings::readParameter<T>``): ``float`` keys accept
  a real or an int; ``int`` keys abort on a real ("parameter must be an integer
  number, aborting..."); string keys must be strings. ``System::System`` only takes the
  v1.0 path when ``File.version`` is the *string* ``"1.0"``.

  - ``readCamera1``: ``Camera.type`` (string). ``"PinHole"``: ``Camera1.fx/fy/cx/cy``
    (float), optional ``Camera1.k1`` ... ``Camera1.k3`` (float). ``"Rectified"``:
    ``Camera1.fx/fy/cx/cy`` only.
  - ``readCamera2`` (stereo): ``PinHole`` needs ``Camera2.*`` and the matrix
    ``Stereo.T_c1_c2``; ``Rectified`` reads ``Stereo.b`` (float). Both read
    ``Stereo.ThDepth`` (float). A simulated pair is already rectified, so stereo is
    written as ``Rectified``.
  - ``readImageInfo``: ``Camera.width``, ``Camera.height``, ``Camera.fps``,
    ``Camera.RGB`` (all int).
  - ``readRGBD``: ``RGBD.DepthMapFactor``, ``Stereo.ThDepth``, ``Stereo.b`` (float, all
    required).
  - ``readORB``: ``ORBextractor.nFeatures``, ``nLevels``, ``iniThFAST``, ``minThFAST``
    (int), ``scaleFactor`` (float).
  - ``readViewer``: ``Viewer.KeyFrameSize``, ``KeyFrameLineWidth``, ``GraphLineWidth``,
    ``PointSize``, ``CameraSize``, ``CameraLineWidth``, ``ViewpointX/Y/Z/F`` (float),
    optional ``Viewer.imageViewScale`` (float).

* **old format** (``src/Tracking.cc``, ``Tracking::ParseCamParamFile`` and
  ``ParseORBParamFile``): ``Camera.fx/fy/cx/cy/k1/k2/p1/p2`` must be reals
  (``node.isReal()``; an int literal such as ``500`` is refused), ``Camera.k3``
  optional real; ``Camera.bf``, ``ThDepth`` (stereo, RGB-D) and ``DepthMapFactor``
  (RGB-D) reals; ``Camera.fps`` read as a number, ``Camera.RGB`` as an int;
  ``ORBextractor.*`` as in v1.0.

* **stereo pairs** (:func:`orbslam3_stereo_yaml`), v1.0: ``Camera.type: "PinHole"`` with
  ``Camera1.*`` and ``Camera2.*`` and the 4x4 ``Stereo.T_c1_c2`` (``Settings::readCamera2``,
  ``src/Settings.cc:276-352``: PinHole sets ``bNeedToRectify_``, reads ``Camera2.fx/fy/cx/cy``,
  optional ``Camera2.k1..k3``, ``Stereo.T_c1_c2`` whose translation's norm is the baseline,
  and ``Stereo.ThDepth``), as ``Examples/Stereo/EuRoC.yaml:18-60`` writes them; the
  stereo-inertial file adds ``IMU.T_b_c1`` (4x4, left camera to IMU body) and
  ``IMU.NoiseGyro``, ``NoiseAcc``, ``GyroWalk``, ``AccWalk``, ``Frequency`` (float; readIMU,
  ``src/Settings.cc:414-432``; ``Examples/Stereo-Inertial/EuRoC.yaml:63-78``). Old format
  (``Tracking::ParseCamParamFile``): one ``Camera.*`` set and ``Camera.bf`` (a rectified pair
  only; ``src/Tracking.cc:1133-1148``), ``ThDepth`` (:1171-1184); stereo-inertial adds
  ``Tbc`` (4x4) and ``IMU.*`` with ``IMU.Frequency`` an int (``ParseIMUParamFile``,
  :1301-1419; ``Examples_old/Stereo-Inertial/EuRoC.yaml:34-49``). Every matrix is written
  ``dt: f``: ORB-SLAM3 reads them element by element as ``float`` (``Converter::toSophus``
  via ``toMatrix3d``/``toVector3d``, ``src/Converter.cc:171-201``, ``:300``; ``Tbc`` through
  ``cvTbc.ptr<float>``, ``src/Tracking.cc:1323``), so a ``dt: d`` matrix would be read as
  garbage.

``ThDepth`` is in baselines: points closer than ``ThDepth * b`` metres are "close".
``DepthMapFactor`` divides the raw depth: 1.0 for Gazebo's 32FC1 metres, 1000.0 for
16UC1 millimetres, 5000.0 for TUM PNGs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from sensorkit.describe.intrinsics import Intrinsics, InvalidValue
from sensorkit.exporters import _text as t
from sensorkit.exporters.opencv import OPENCV_YAML_HEADER, opencv_matrix_lines

__all__ = [
    "DEFAULT_RGBD_BASELINE",
    "OrbExtractorSettings",
    "OrbImuSettings",
    "OrbSlam3Mode",
    "OrbSlam3Version",
    "ViewerSettings",
    "orbslam3_stereo_yaml",
    "orbslam3_yaml",
]

OrbSlam3Mode = Literal["monocular", "rgbd", "stereo"]
OrbSlam3Version = Literal["1.0", "old"]

DEFAULT_RGBD_BASELINE = 0.08
"""Virtual baseline (metres) for RGB-D when none is given: ORB-SLAM3 uses it only for
the close/far split (``ThDepth * b``) and the virtual right coordinate."""


@dataclass(frozen=True)
class OrbExtractorSettings:
    """``ORBextractor.*`` (the values of ORB-SLAM3's own example files)."""

    n_features: int = 1000
    scale_factor: float = 1.2
    n_levels: int = 8
    ini_th_fast: int = 20
    min_th_fast: int = 7


@dataclass(frozen=True)
class ViewerSettings:
    """``Viewer.*`` (the values of ORB-SLAM3's own example files)."""

    key_frame_size: float = 0.05
    key_frame_line_width: float = 1.0
    graph_line_width: float = 0.9
    point_size: float = 2.0
    camera_size: float = 0.08
    camera_line_width: float = 3.0
    viewpoint_x: float = 0.0
    viewpoint_y: float = -0.7
    viewpoint_z: float = -1.8
    viewpoint_f: float = 500.0
    image_view_scale: float = 1.0


def _orb_lines(orb: OrbExtractorSettings) -> list[str]:
    for name in ("n_features", "n_levels", "ini_th_fast", "min_th_fast"):
        value = getattr(orb, name)
        if isinstance(value, bool) or not isinstance(value, int) or value <= 0:
            msg = f"ORBextractor {name} must be a positive integer, got {value!r}"
            raise InvalidValue(msg)
    if t.finite(orb.scale_factor, "ORBextractor scale_factor") <= 1.0:
        msg = f"ORBextractor scale_factor must be > 1, got {orb.scale_factor!r}"
        raise InvalidValue(msg)
    return [
        f"ORBextractor.nFeatures: {t.integer(orb.n_features)}",
        f"ORBextractor.scaleFactor: {t.real(orb.scale_factor, 'scale_factor')}",
        f"ORBextractor.nLevels: {t.integer(orb.n_levels)}",
        f"ORBextractor.iniThFAST: {t.integer(orb.ini_th_fast)}",
        f"ORBextractor.minThFAST: {t.integer(orb.min_th_fast)}",
    ]


def _viewer_lines(viewer: ViewerSettings) -> list[str]:
    pairs = [
        ("KeyFrameSize", viewer.key_frame_size),
        ("KeyFrameLineWidth", viewer.key_frame_line_width),
        ("GraphLineWidth", viewer.graph_line_width),
        ("PointSize", viewer.point_size),
        ("CameraSize", viewer.camera_size),
        ("CameraLineWidth", viewer.camera_line_width),
        ("ViewpointX", viewer.viewpoint_x),
        ("ViewpointY", viewer.viewpoint_y),
        ("ViewpointZ", viewer.viewpoint_z),
        ("ViewpointF", viewer.viewpoint_f),
        ("imageViewScale", viewer.image_view_scale),
    ]
    return [f"Viewer.{key}: {t.real(value, f'Viewer.{key}')}" for key, value in pairs]


def _baseline(intr: Intrinsics, mode: OrbSlam3Mode, baseline: float | None) -> float:
    if mode == "monocular":
        if baseline is not None:
            msg = f"baseline does not apply to a monocular camera, got baseline={baseline!r}"
            raise InvalidValue(msg)
        return 0.0
    if baseline is None:
        if mode == "rgbd":
            return DEFAULT_RGBD_BASELINE
        if intr.baseline_tx < 0.0:
            return intr.baseline
        msg = (
            "stereo needs the baseline in metres: pass baseline= or use the right "
            f"camera's intrinsics (P[0][3] < 0), got baseline_tx={intr.baseline_tx!r}"
        )
        raise InvalidValue(msg)
    return t.positive(baseline, "baseline")


def _check_version(version: str) -> None:
    if version not in ("1.0", "old"):
        msg = f"version must be '1.0' or 'old', got {version!r}"
        raise InvalidValue(msg)


def _check_mono(intr: Intrinsics, mode: str, version: str) -> None:
    """Refuse what no single-camera file can hold: an unknown mode or version, skew, or
    a distorted camera exported as one eye of a rectified stereo pair."""
    if mode not in ("monocular", "rgbd", "stereo"):
        msg = f"mode must be monocular, rgbd or stereo, got {mode!r}"
        raise InvalidValue(msg)
    _check_version(version)
    if intr.skew != 0.0:
        msg = f"ORB-SLAM3's pinhole model has no skew, got skew={intr.skew!r}"
        raise InvalidValue(msg)
    if mode == "stereo" and intr.has_distortion:
        msg = (
            "stereo is exported as a rectified pair, which must have no distortion, "
            f"got distortion={intr.distortion!r}"
        )
        raise InvalidValue(msg)


def _image_lines(intr: Intrinsics, frame_rate: int, rgb: bool) -> list[str]:
    """``Camera.width``, ``height``, ``fps`` and ``RGB`` (ints in both formats)."""
    return [
        f"Camera.width: {t.integer(intr.width, 'width')}",
        f"Camera.height: {t.integer(intr.height, 'height')}",
        f"Camera.fps: {t.integer(frame_rate, 'fps')}",
        f"Camera.RGB: {1 if rgb else 0}",
    ]


def _old_depth_lines(bf: float, th_depth: float) -> list[str]:
    """The old format's depth keys: ``Camera.bf`` (baseline times fx) and ``ThDepth``."""
    return [f"Camera.bf: {t.real(bf, 'bf')}", f"ThDepth: {t.real(th_depth, 'th_depth')}"]


def _camera_lines(prefix: str, intr: Intrinsics, *, with_distortion: bool) -> list[str]:
    if intr.skew != 0.0:
        msg = f"ORB-SLAM3's pinhole model has no skew, got skew={intr.skew!r}"
        raise InvalidValue(msg)
    lines = [
        f"{prefix}.fx: {t.real(intr.fx, 'fx')}",
        f"{prefix}.fy: {t.real(intr.fy, 'fy')}",
        f"{prefix}.cx: {t.real(intr.cx, 'cx')}",
        f"{prefix}.cy: {t.real(intr.cy, 'cy')}",
    ]
    if with_distortion:
        k1, k2, p1, p2, k3 = intr.distortion
        lines += [
            f"{prefix}.k1: {t.real(k1, 'k1')}",
            f"{prefix}.k2: {t.real(k2, 'k2')}",
            f"{prefix}.p1: {t.real(p1, 'p1')}",
            f"{prefix}.p2: {t.real(p2, 'p2')}",
            f"{prefix}.k3: {t.real(k3, 'k3')}",
        ]
    return lines


def orbslam3_yaml(
    intr: Intrinsics,
    *,
    mode: OrbSlam3Mode,
    fps: float,
    version: OrbSlam3Version = "1.0",
    rgb: bool = True,
    baseline: float | None = None,
    th_depth: float = 40.0,
    depth_map_factor: float = 1.0,
    orb: OrbExtractorSettings | None = None,
    viewer: ViewerSettings | None = None,
) -> str:
    """An ORB-SLAM3 settings file for a simulated pinhole camera.

    The first line is ``%YAML:1.0`` (then ``---``, as ``cv::FileStorage`` writes).
    Reals always carry a decimal point or exponent, ints never do, so each key has
    the kind ORB-SLAM3 checks for (see the module docstring for the reader's rules).

    Args:
        intr: the (left) camera.
        mode: ``"monocular"``, ``"rgbd"`` or ``"stereo"`` (a rectified pair).
        fps: frame rate, a whole number (``Camera.fps`` is an int).
        version: ``"1.0"`` (``File.version: "1.0"``, ``Camera1.*``) or ``"old"``.
        rgb: ``Camera.RGB``: 1 when images arrive as rgb8 (Gazebo's default), 0 for bgr8.
        baseline: metres between the stereo cameras; for stereo it defaults to
            ``-P[0][3] / fx`` of ``intr``; for RGB-D to ``DEFAULT_RGBD_BASELINE``.
        th_depth: close/far threshold in baselines (``ThDepth`` / ``Stereo.ThDepth``).
        depth_map_factor: raw depth divided by this gives metres (RGB-D only).
        orb: ``ORBextractor.*`` values.
        viewer: ``Viewer.*`` values.

    Raises:
        InvalidValue: a value is out of range or of the wrong kind, the camera has skew
            (ORB-SLAM3's pinhole has none), or a stereo camera has distortion.
    """
    _check_mono(intr, mode, version)
    frame_rate = t.fps_int(fps, "fps")
    b = _baseline(intr, mode, baseline)
    thd = t.positive(th_depth, "th_depth")
    dmf = t.positive(depth_map_factor, "depth_map_factor")
    if mode != "rgbd" and depth_map_factor != 1.0:
        msg = f"depth_map_factor applies to rgbd only, got {depth_map_factor!r} for {mode}"
        raise InvalidValue(msg)

    lines: list[str] = [f"# ORB-SLAM3 settings ({mode}), written by sensorkit"]
    if version == "1.0":
        cam = "Camera1"
        lines.append('File.version: "1.0"')
        lines.append(f"Camera.type: {t.quoted('Rectified' if mode == 'stereo' else 'PinHole')}")
    else:
        cam = "Camera"
        lines.append('Camera.type: "PinHole"')
    # v1.0 treats the coefficients as optional (a distorted monocular image is then
    # undistorted every frame), the old format requires k1..p2; "Rectified" has none.
    distorted = version == "old" or (mode != "stereo" and intr.has_distortion)
    lines += _camera_lines(cam, intr, with_distortion=distorted)
    lines += _image_lines(intr, frame_rate, rgb)
    if mode != "monocular":
        if version == "1.0":
            lines += [
                f"Stereo.b: {t.real(b, 'baseline')}",
                f"Stereo.ThDepth: {t.real(thd, 'th_depth')}",
            ]
        else:
            lines += _old_depth_lines(b * intr.fx, thd)
    if mode == "rgbd":
        key = "RGBD.DepthMapFactor" if version == "1.0" else "DepthMapFactor"
        lines.append(f"{key}: {t.real(dmf, 'depth_map_factor')}")
    lines += _orb_lines(orb or OrbExtractorSettings())
    lines += _viewer_lines(viewer or ViewerSettings())
    return OPENCV_YAML_HEADER + "\n".join(lines) + "\n"


@dataclass(frozen=True)
class OrbImuSettings:
    """``IMU.*`` of a stereo-inertial file.

    ``T_b_c1`` maps left-camera (optical) coordinates into the IMU body frame ("Transformation
    from camera 0 to body-frame (imu)", Examples/Stereo-Inertial/EuRoC.yaml:63-64); the
    noises are continuous-time densities and walks (see :mod:`sensorkit.describe.imu_noise`).
    """

    T_b_c1: npt.ArrayLike
    noise_gyro: float
    noise_acc: float
    gyro_walk: float
    acc_walk: float
    frequency: float


RIGID_TOL = 1e-6
"""How far a transform's rotation block may be from orthonormal."""


def _rigid(name: str, T: npt.ArrayLike) -> list[float]:
    matrix = np.asarray(T, dtype=np.float64)
    if matrix.shape != (4, 4) or not np.isfinite(matrix).all():
        msg = f"{name} must be a finite 4x4 matrix, got shape {matrix.shape}"
        raise InvalidValue(msg)
    R = matrix[:3, :3]
    if (
        not np.allclose(R @ R.T, np.eye(3), atol=RIGID_TOL)
        or np.linalg.det(R) < 0
        or not np.array_equal(matrix[3], [0.0, 0.0, 0.0, 1.0])
    ):
        msg = f"{name} must be a rigid transform (proper rotation, last row 0 0 0 1)"
        raise InvalidValue(msg)
    return t.matrix_rows(matrix.tolist())


def _imu_lines(imu: OrbImuSettings, version: OrbSlam3Version) -> list[str]:
    values = {
        "NoiseGyro": imu.noise_gyro,
        "NoiseAcc": imu.noise_acc,
        "GyroWalk": imu.gyro_walk,
        "AccWalk": imu.acc_walk,
    }
    for key, value in values.items():
        t.positive(value, f"IMU.{key}")
    key = "IMU.T_b_c1" if version == "1.0" else "Tbc"
    lines = opencv_matrix_lines(key, 4, 4, _rigid(key, imu.T_b_c1), dt="f")
    lines += [f"IMU.{k}: {t.real(v, f'IMU.{k}')}" for k, v in values.items()]
    if version == "1.0":  # readParameter<float>: a real
        t.positive(imu.frequency, "IMU.Frequency")
        lines.append(f"IMU.Frequency: {t.real(imu.frequency, 'IMU.Frequency')}")
    else:  # ParseIMUParamFile: node.isInt()
        lines.append(f"IMU.Frequency: {t.integer(t.fps_int(imu.frequency, 'IMU.Frequency'))}")
    return lines


def orbslam3_stereo_yaml(
    left: Intrinsics,
    right: Intrinsics,
    *,
    T_c1_c2: npt.ArrayLike,
    fps: float,
    version: OrbSlam3Version = "1.0",
    rgb: bool = True,
    th_depth: float = 40.0,
    imu: OrbImuSettings | None = None,
    orb: OrbExtractorSettings | None = None,
    viewer: ViewerSettings | None = None,
) -> str:
    """An ORB-SLAM3 settings file for a stereo pair (stereo-inertial with ``imu``).

    ``T_c1_c2`` is the right camera's pose in the left camera's optical frame (it maps
    right-camera coordinates into left-camera ones; a horizontal pair's translation is
    ``[+baseline, 0, 0]``, as in Examples/Stereo/EuRoC.yaml:53-60).

    ``version="1.0"``: ``Camera.type "PinHole"``, ``Camera1.*``, ``Camera2.*`` (with
    ``k1..k3`` when a camera has distortion) and ``Stereo.T_c1_c2``; ORB-SLAM3 rectifies
    the pair itself, so any pair will do. ``version="old"``: one ``Camera.*`` set and
    ``Camera.bf`` = baseline * fx, which holds for a rectified pair only: same
    intrinsics, no distortion, parallel axes, the right camera straight along x.

    Raises:
        InvalidValue: a value is out of range or of the wrong kind, a camera has skew,
            the two images differ in size, a transform is not rigid, or (old format) the
            pair is not rectified.
    """
    _check_version(version)
    if (left.width, left.height) != (right.width, right.height):
        msg = (
            "ORB-SLAM3 reads one image size for both cameras, got "
            f"{left.width}x{left.height} and {right.width}x{right.height}"
        )
        raise InvalidValue(msg)
    T = np.asarray(T_c1_c2, dtype=np.float64)
    T_rows = _rigid("Stereo.T_c1_c2", T)
    baseline = math.hypot(*T[:3, 3])  # scaled: no overflow for a far but finite pair
    if baseline <= 0.0:
        msg = "the two cameras of a stereo pair must be apart (T_c1_c2 has no translation)"
        raise InvalidValue(msg)
    frame_rate = t.fps_int(fps, "fps")
    thd = t.positive(th_depth, "th_depth")
    mode = "stereo-inertial" if imu is not None else "stereo"
    lines: list[str] = [f"# ORB-SLAM3 settings ({mode}), written by sensorkit"]
    if version == "1.0":
        lines += ['File.version: "1.0"', 'Camera.type: "PinHole"']
        lines += _camera_lines("Camera1", left, with_distortion=left.has_distortion)
        lines += _camera_lines("Camera2", right, with_distortion=right.has_distortion)
    else:
        _check_rectified(left, right, T)
        lines.append('Camera.type: "PinHole"')
        lines += _camera_lines("Camera", left, with_distortion=True)
    lines += _image_lines(left, frame_rate, rgb)
    if version == "1.0":
        lines.append(f"Stereo.ThDepth: {t.real(thd, 'th_depth')}")
        lines += opencv_matrix_lines("Stereo.T_c1_c2", 4, 4, T_rows, dt="f")
    else:
        lines += _old_depth_lines(baseline * left.fx, thd)
    if imu is not None:
        lines += _imu_lines(imu, version)
    lines += _orb_lines(orb or OrbExtractorSettings())
    lines += _viewer_lines(viewer or ViewerSettings())
    return OPENCV_YAML_HEADER + "\n".join(lines) + "\n"


def _check_rectified(left: Intrinsics, right: Intrinsics, T: npt.NDArray[np.float64]) -> None:
    if left.has_distortion or right.has_distortion:
        msg = "the old format holds a rectified pair, which has no distortion"
        raise InvalidValue(msg)
    if left.K.tolist() != right.K.tolist():
        msg = (
            "the old format holds one camera matrix for both cameras, got "
            f"{left.K.tolist()} and {right.K.tolist()}"
        )
        raise InvalidValue(msg)
    off = T[:3, 3]
    if (
        not off[0] > 0.0
        or abs(off[1]) > RIGID_TOL
        or abs(off[2]) > RIGID_TOL
        or float(np.abs(T[:3, :3] - np.eye(3)).max()) > RIGID_TOL
    ):
        msg = (
            "the old format holds a rectified pair (parallel axes, the right camera along "
            "the left one's x axis); use the v1.0 file, which carries Stereo.T_c1_c2"
        )
        raise InvalidValue(msg)
