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

``ThDepth`` is in baselines: points closer than ``ThDepth * b`` metres are "close".
``DepthMapFactor`` divides the raw depth: 1.0 for Gazebo's 32FC1 metres, 1000.0 for
16UC1 millimetres, 5000.0 for TUM PNGs.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from sensorkit.exporters import _text as t
from sensorkit.exporters.opencv import OPENCV_YAML_HEADER
from sensorkit.intrinsics import Intrinsics, InvalidValue

__all__ = [
    "DEFAULT_RGBD_BASELINE",
    "OrbExtractorSettings",
    "OrbSlam3Mode",
    "OrbSlam3Version",
    "ViewerSettings",
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
    value = t.finite(baseline, "baseline")
    if value <= 0.0:
        msg = f"baseline must be greater than zero, got {baseline!r}"
        raise InvalidValue(msg)
    return value


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
    if mode not in ("monocular", "rgbd", "stereo"):
        msg = f"mode must be monocular, rgbd or stereo, got {mode!r}"
        raise InvalidValue(msg)
    if version not in ("1.0", "old"):
        msg = f"version must be '1.0' or 'old', got {version!r}"
        raise InvalidValue(msg)
    if intr.skew != 0.0:
        msg = f"ORB-SLAM3's pinhole model has no skew, got skew={intr.skew!r}"
        raise InvalidValue(msg)
    if mode == "stereo" and intr.has_distortion:
        msg = (
            "stereo is exported as a rectified pair, which must have no distortion, "
            f"got distortion={intr.distortion!r}"
        )
        raise InvalidValue(msg)
    frame_rate = t.fps_int(fps, "fps")
    b = _baseline(intr, mode, baseline)
    thd = t.finite(th_depth, "th_depth")
    if thd <= 0.0:
        msg = f"th_depth must be greater than zero, got {th_depth!r}"
        raise InvalidValue(msg)
    dmf = t.finite(depth_map_factor, "depth_map_factor")
    if dmf <= 0.0:
        msg = f"depth_map_factor must be greater than zero, got {depth_map_factor!r}"
        raise InvalidValue(msg)
    if mode != "rgbd" and depth_map_factor != 1.0:
        msg = f"depth_map_factor applies to rgbd only, got {depth_map_factor!r} for {mode}"
        raise InvalidValue(msg)

    k1, k2, p1, p2, k3 = intr.distortion
    lines: list[str] = [f"# ORB-SLAM3 settings ({mode}), written by sensorkit"]
    if version == "1.0":
        cam = "Camera1"
        lines.append('File.version: "1.0"')
        lines.append(f"Camera.type: {t.quoted('Rectified' if mode == 'stereo' else 'PinHole')}")
    else:
        cam = "Camera"
        lines.append('Camera.type: "PinHole"')
    lines += [
        f"{cam}.fx: {t.real(intr.fx, 'fx')}",
        f"{cam}.fy: {t.real(intr.fy, 'fy')}",
        f"{cam}.cx: {t.real(intr.cx, 'cx')}",
        f"{cam}.cy: {t.real(intr.cy, 'cy')}",
    ]
    # v1.0 treats the coefficients as optional (a distorted monocular image is then
    # undistorted every frame), the old format requires k1..p2; "Rectified" has none.
    if version == "old" or (mode != "stereo" and intr.has_distortion):
        lines += [
            f"{cam}.k1: {t.real(k1, 'k1')}",
            f"{cam}.k2: {t.real(k2, 'k2')}",
            f"{cam}.p1: {t.real(p1, 'p1')}",
            f"{cam}.p2: {t.real(p2, 'p2')}",
            f"{cam}.k3: {t.real(k3, 'k3')}",
        ]
    lines += [
        f"Camera.width: {t.integer(intr.width, 'width')}",
        f"Camera.height: {t.integer(intr.height, 'height')}",
        f"Camera.fps: {t.integer(frame_rate, 'fps')}",
        f"Camera.RGB: {1 if rgb else 0}",
    ]
    if mode != "monocular":
        if version == "1.0":
            lines += [
                f"Stereo.b: {t.real(b, 'baseline')}",
                f"Stereo.ThDepth: {t.real(thd, 'th_depth')}",
            ]
        else:
            lines += [
                f"Camera.bf: {t.real(b * intr.fx, 'bf')}",
                f"ThDepth: {t.real(thd, 'th_depth')}",
            ]
    if mode == "rgbd":
        key = "RGBD.DepthMapFactor" if version == "1.0" else "DepthMapFactor"
        lines.append(f"{key}: {t.real(dmf, 'depth_map_factor')}")
    lines += _orb_lines(orb or OrbExtractorSettings())
    lines += _viewer_lines(viewer or ViewerSettings())
    return OPENCV_YAML_HEADER + "\n".join(lines) + "\n"
