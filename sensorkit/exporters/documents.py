"""One camera's or one stereo pair's document in one format, and the IMU beside them.

What ``sensorkit intrinsics`` prints (:func:`intrinsics_output`: the cameras or the pair
``--sensor`` picks, in ``--format``) and the per-camera and per-pair documents
``sensorkit export`` writes (:func:`camera_document`, :func:`pair_document`), from a
:class:`~sensorkit.describe.sensorinfo.RobotInfo` and the format writers of this package.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Literal, get_args

from sensorkit.base.errors import InputError, UsageError
from sensorkit.describe.intrinsics import InvalidValue

if TYPE_CHECKING:
    from sensorkit.describe.sensorinfo import RobotInfo
    from sensorkit.describe.stereo import StereoPair
    from sensorkit.describe.views import CameraView, SensorInfo
    from sensorkit.exporters.orbslam3 import OrbImuSettings
    from sensorkit.model.transforms_np import Mat

__all__ = [
    "FORMATS",
    "PAIR_FORMATS",
    "camera_document",
    "camera_record",
    "intrinsics_document",
    "intrinsics_output",
    "pair_document",
    "pair_record",
    "select_cameras",
    "select_imu",
    "select_pair",
]

DEFAULT_FPS = 30
"""Frame rate written for ORB-SLAM3 when a camera's ``<update_rate>`` is 0 or missing."""

IntrinsicsFormat = Literal["json", "camera-info", "orbslam3", "orbslam3-v1", "kalibr", "opencv"]
FORMATS: tuple[str, ...] = get_args(IntrinsicsFormat)
SINGLE_DOCUMENT_FORMATS = frozenset(FORMATS) - {"json"}
PAIR_FORMATS = frozenset({"kalibr", "orbslam3", "orbslam3-v1"})
"""Formats that hold a whole stereo pair in one document."""

_BGR_FORMATS = frozenset({"B8G8R8", "BGR_INT8"})
_COLOUR_FORMATS = frozenset({"R8G8B8", "RGB_INT8", "R16G16B16", "RGB_INT16"}) | _BGR_FORMATS


def select_cameras(info: RobotInfo, name: str | None, fmt: str) -> list[CameraView]:
    """The cameras ``sensorkit intrinsics`` prints: all, or those ``name`` picks (a
    sensor name, or ``<sensor>/<camera>`` for one camera of a multicamera).

    Raises:
        UsageError: unknown format, no camera, an unknown name, or several cameras for
            a format that holds one.
    """
    if fmt not in FORMATS:
        msg = f"--format {fmt!r}: use " + ", ".join(FORMATS)
        raise UsageError(msg)
    cameras = info.cameras
    ids = ", ".join(c.id for c in cameras)
    if not cameras:
        msg = f"{info.robot.document.display}: the robot has no camera"
        if info.robot.sensors:
            msg += " (sensors: " + ", ".join(s.name for s in info.robot.sensors) + ")"
        raise UsageError(msg)
    if name is not None:
        picked = [c for c in cameras if name in (c.id, c.sensor.name)]
        for pair in info.stereo_pairs:
            if not picked and name in pair.aliases:
                picked = [pair.left, pair.right]
        if not picked:
            msg = f"--sensor {name}: no camera called {name!r} (cameras: {ids}{_pair_list(info)})"
            raise UsageError(msg)
        cameras = picked
    if fmt in SINGLE_DOCUMENT_FORMATS and len(cameras) > 1:
        msg = f"--format {fmt} holds one camera: pick one with --sensor (cameras: {ids})"
        if name is not None:
            listing = ", ".join(c.id for c in cameras)
            msg = (
                f"--format {fmt} holds one camera and {name!r} has {len(cameras)}: "
                f"pick one with --sensor (cameras: {listing})"
            )
        raise UsageError(msg)
    for cam in cameras:
        if cam.intrinsics is None:
            msg = f"camera {cam.id}: {cam.error}"
            raise InputError(msg)
    return cameras


def _pair_list(info: RobotInfo) -> str:
    if not info.stereo_pairs:
        return ""
    return "; stereo pairs: " + ", ".join(p.name for p in info.stereo_pairs)


def select_pair(info: RobotInfo, name: str | None, fmt: str) -> StereoPair | None:
    """The stereo pair ``name`` picks when ``fmt`` holds a pair (Kalibr, ORB-SLAM3): the
    multicamera's sensor name, the pair's stem (``front`` for ``front_left`` and
    ``front_right``) or ``LEFT+RIGHT``; else ``None``.

    Raises:
        InputError: an eye of the pair has intrinsics that cannot exist.
    """
    if name is None or fmt not in PAIR_FORMATS:
        return None
    for pair in info.stereo_pairs:
        if name in pair.aliases:
            for eye in (pair.left, pair.right):
                if eye.intrinsics is None:
                    msg = f"camera {eye.id}: {eye.error}"
                    raise InputError(msg)
            return pair
    return None


def select_imu(info: RobotInfo, name: str | None) -> tuple[SensorInfo | None, list[str]]:
    """The IMU ``T_cam_imu`` and the stereo-inertial files use: ``name`` (``--imu``), else
    the first, with a note naming it when the robot has several.

    Raises:
        UsageError: ``name`` is no IMU of the robot (the message lists them).
    """
    imus = info.imus
    listing = ", ".join(s.name for s in imus)
    if name is not None:
        for imu in imus:
            if imu.name == name:
                return imu, []
        msg = f"--imu {name}: no IMU called {name!r} " + (
            f"(IMUs: {listing})" if imus else "(the robot has no IMU)"
        )
        raise UsageError(msg)
    if not imus:
        return None, []
    notes = []
    if len(imus) > 1:
        notes.append(
            f"IMU {imus[0].name!r} is used (the first of {len(imus)}: {listing}); "
            "choose another with --imu NAME"
        )
    return imus[0], notes


def camera_record(view: CameraView, target: str) -> dict[str, object]:
    from sensorkit.exporters import camera_dict

    assert view.intrinsics is not None
    return camera_dict(
        view.intrinsics,
        camera=view.id,
        sensor=view.sensor.name,
        sensor_type=view.sensor.type,
        target=target,
        frame_id=view.frame,
        image_topic=view.image_topic,
        camera_info_topic=view.camera_info_topic,
        update_rate=view.sensor.update_rate,
        notes=list(view.notes),
    )


def _fps(view: CameraView, notes: list[str]) -> int:
    rate = view.fps
    if rate is None:
        notes.append(f"no positive <update_rate>: Camera.fps {DEFAULT_FPS}")
        return DEFAULT_FPS
    whole = max(1, round(rate))
    if whole != rate:
        notes.append(
            f"<update_rate> {rate:g} rounded to Camera.fps {whole} (ORB-SLAM3 wants an int)"
        )
    return whole


def _rgb(view: CameraView, notes: list[str]) -> bool:
    fmt = (view.spec.format or "R8G8B8").strip()
    if fmt not in _COLOUR_FORMATS:
        notes.append(f"image format {fmt}: Camera.RGB only matters for colour images")
    return fmt not in _BGR_FORMATS


def _T_cam_imu(view: CameraView, info: RobotInfo, imu: SensorInfo | None) -> Mat | None:
    """Kalibr's ``T_cam_imu``: IMU frame to the camera's optical frame."""
    from sensorkit.describe.stereo import T_world_optical
    from sensorkit.model.transforms_np import invert

    if imu is None or imu.T_world_render is None:
        return None
    T_world_cam = T_world_optical(info.robot, view, info.target)
    if T_world_cam is None:
        return None
    out: Mat = invert(T_world_cam) @ imu.T_world_render
    out[3] = (0.0, 0.0, 0.0, 1.0)
    return out


def camera_document(
    view: CameraView,
    fmt: str,
    info: RobotInfo,
    notes: list[str],
    *,
    mode: str = "monocular",
    imu: SensorInfo | None = None,
) -> str:
    """One camera in one single-document format (Kalibr's ``T_cam_imu`` from ``imu``).

    Raises:
        InvalidValue: the format cannot hold this camera (Kalibr: k3 or skew; a missing
            image topic for Kalibr's ``rostopic``).
    """
    from sensorkit.exporters import (
        camera_info_yaml,
        kalibr_camchain_yaml,
        opencv_yaml,
        orbslam3_yaml,
    )

    intr = view.intrinsics
    assert intr is not None
    if fmt == "camera-info":
        return camera_info_yaml(intr, camera_name=view.name)
    if fmt == "opencv":
        return opencv_yaml(intr)
    if fmt in ("orbslam3", "orbslam3-v1"):
        return orbslam3_yaml(
            intr,
            mode=mode,  # type: ignore[arg-type]
            fps=_fps(view, notes),
            version="1.0" if fmt == "orbslam3-v1" else "old",
            rgb=_rgb(view, notes),
        )
    if fmt == "kalibr":
        if view.image_topic is None:
            msg = "no image topic for Kalibr's rostopic (the camera publishes nothing to ROS)"
            raise InvalidValue(msg)
        return kalibr_camchain_yaml(
            intr, rostopic=view.image_topic, T_cam_imu=_T_cam_imu(view, info, imu)
        )
    msg = f"format {fmt!r} is not a single-document format"
    raise UsageError(msg)


def intrinsics_document(
    info: RobotInfo, cameras: Sequence[CameraView], fmt: str, *, imu: str | None = None
) -> tuple[str, list[str]]:
    """``sensorkit intrinsics`` output for ``cameras`` in ``fmt``, and notes for stderr.

    ``json``: ``{"robot", "file", "target", "target_reason", "convention", "cameras":
    [...], "stereo_pairs": [...]}``, each camera the exporter's ``camera_dict`` plus its
    sensor, topics and frame, each pair of two listed cameras its baseline and transforms.
    Every other format holds exactly one camera (see :func:`select_cameras`); ORB-SLAM3
    files are monocular; Kalibr's ``T_cam_imu`` is from ``imu`` (see :func:`select_imu`).

    Raises:
        InvalidValue: the format cannot hold the camera.
        UsageError: ``imu`` is no IMU of the robot.
    """
    from sensorkit.exporters import to_json

    chosen, imu_notes = select_imu(info, imu)
    notes = [f"{c.id}: {n}" for c in cameras for n in c.notes]
    if fmt == "json":
        ids = {c.id for c in cameras}
        data: dict[str, object] = {
            "robot": info.robot.name,
            "file": info.robot.document.display,
            "target": info.target,
            "target_reason": info.target_reason,
            "convention": info.convention,
            "cameras": [camera_record(c, info.target) for c in cameras],
            "stereo_pairs": [
                pair_record(p) for p in info.stereo_pairs if p.left.id in ids and p.right.id in ids
            ],
        }
        return to_json(data), notes
    (view,) = cameras
    extra: list[str] = []
    text = camera_document(view, fmt, info, extra, imu=chosen)
    if fmt == "kalibr" and chosen is not None:
        notes += imu_notes
    return text, notes + [f"{view.id}: {n}" for n in extra]


def pair_record(pair: StereoPair) -> dict[str, object]:
    def rows(T: Mat) -> list[list[float]]:
        return [[float(v) for v in row] for row in T]

    return {
        "name": pair.name,
        "left": pair.left.id,
        "right": pair.right.id,
        "detected_from": pair.how,
        "baseline": pair.baseline,
        "rectified": pair.rectified,
        "left_frame_id": pair.left.frame,
        "right_frame_id": pair.right.frame,
        "T_left_right": rows(pair.T_left_right),
        "T_right_left": rows(pair.T_right_left),
        "notes": list(pair.notes),
    }


def _imu_settings(
    pair: StereoPair, info: RobotInfo, imu: SensorInfo, notes: list[str]
) -> OrbImuSettings:
    from sensorkit.describe.imu_noise import imu_noise
    from sensorkit.exporters.orbslam3 import OrbImuSettings
    from sensorkit.model.transforms_np import invert

    T_cam_imu = _T_cam_imu(pair.left, info, imu)
    if T_cam_imu is None:
        msg = f"IMU {imu.name!r} or camera {pair.left.id} is not on a link of the robot"
        raise InvalidValue(msg)
    noise, noise_notes = imu_noise(imu.sensor, info.target)
    notes.extend(f"IMU {imu.name!r}: {n}" for n in noise_notes)
    return OrbImuSettings(
        T_b_c1=invert(T_cam_imu),
        noise_gyro=noise.gyro_noise_density,
        noise_acc=noise.accel_noise_density,
        gyro_walk=noise.gyro_random_walk,
        acc_walk=noise.accel_random_walk,
        frequency=noise.rate,
    )


def pair_document(
    pair: StereoPair,
    fmt: str,
    info: RobotInfo,
    notes: list[str],
    *,
    imu: SensorInfo | None = None,
    inertial: bool = False,
) -> str:
    """One stereo pair in a pair format: Kalibr camchain (``cam0`` left, ``cam1`` right,
    ``T_cam_imu`` of each from ``imu``), ORB-SLAM3 stereo (``orbslam3``: old format,
    ``orbslam3-v1``: v1.0), stereo-inertial with ``inertial`` (needs ``imu``).

    Raises:
        InvalidValue: the format cannot hold the pair (see the writers), or an eye
            publishes no image topic (Kalibr's ``rostopic``).
    """
    from sensorkit.exporters.kalibr import kalibr_stereo_camchain_yaml
    from sensorkit.exporters.orbslam3 import orbslam3_stereo_yaml

    left, right = pair.left.intrinsics, pair.right.intrinsics
    assert left is not None and right is not None
    if fmt == "kalibr":
        topics = (pair.left.image_topic, pair.right.image_topic)
        if topics[0] is None or topics[1] is None:
            msg = "no image topic for Kalibr's rostopic (an eye publishes nothing to ROS)"
            raise InvalidValue(msg)
        T_cam_imu = None
        if imu is not None:
            T_left, T_right = _T_cam_imu(pair.left, info, imu), _T_cam_imu(pair.right, info, imu)
            T_cam_imu = (T_left, T_right) if T_left is not None and T_right is not None else None
        return kalibr_stereo_camchain_yaml(
            left,
            right,
            rostopics=(topics[0], topics[1]),
            T_cn_cnm1=pair.T_right_left,
            T_cam_imu=T_cam_imu,
        )
    if fmt in ("orbslam3", "orbslam3-v1"):
        imu_settings = None
        if inertial:
            if imu is None:
                msg = "stereo-inertial needs an IMU"
                raise InvalidValue(msg)
            imu_settings = _imu_settings(pair, info, imu, notes)
        if pair.left.fps != pair.right.fps:
            notes.append(
                f"the eyes update at {pair.left.fps} and {pair.right.fps} Hz: Camera.fps "
                "is the left one's"
            )
        return orbslam3_stereo_yaml(
            left,
            right,
            T_c1_c2=pair.T_left_right,
            fps=_fps(pair.left, notes),
            version="1.0" if fmt == "orbslam3-v1" else "old",
            rgb=_rgb(pair.left, notes),
            imu=imu_settings,
        )
    msg = f"format {fmt!r} does not hold a stereo pair (use {', '.join(sorted(PAIR_FORMATS))})"
    raise UsageError(msg)


def intrinsics_output(
    info: RobotInfo, sensor: str | None, fmt: str, *, imu: str | None = None
) -> tuple[str, list[str]]:
    """What ``sensorkit intrinsics`` prints, and its notes: a stereo pair's document when
    ``sensor`` names a pair and ``fmt`` holds one (ORB-SLAM3 stereo-inertial when ``imu``
    is given), else :func:`intrinsics_document` of :func:`select_cameras`.

    Raises:
        UsageError: see :func:`select_cameras` and :func:`select_imu`.
        InputError: a chosen camera's intrinsics cannot exist.
        InvalidValue: the format cannot hold the camera or pair.
    """
    pair = select_pair(info, sensor, fmt)
    if pair is None:
        cameras = select_cameras(info, sensor, fmt)
        return intrinsics_document(info, cameras, fmt, imu=imu)
    chosen, imu_notes = select_imu(info, imu)
    inertial = imu is not None and fmt != "kalibr"
    notes = [f"{pair.name}: {n}" for n in pair.notes]
    notes += [f"{c.id}: {n}" for c in (pair.left, pair.right) for n in c.notes]
    extra: list[str] = []
    text = pair_document(pair, fmt, info, extra, imu=chosen, inertial=inertial)
    if fmt == "kalibr" and chosen is not None:
        notes += imu_notes
    return text, notes + [f"{pair.name}: {n}" for n in dict.fromkeys(extra)]
