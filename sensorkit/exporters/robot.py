"""A whole robot's export: the folder ``sensorkit export`` writes, one subfolder per sensor.

Built on :func:`sensorkit.describe.sensorinfo.describe` (what each sensor publishes), the
documents of :mod:`sensorkit.exporters.documents` and the format writers of this package;
:func:`publish_export` writes the folder atomically.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from sensorkit.base.errors import UsageError
from sensorkit.describe.intrinsics import Intrinsics, InvalidValue
from sensorkit.describe.published import depth_range
from sensorkit.exporters.documents import (
    camera_document,
    camera_record,
    pair_document,
    pair_record,
    select_imu,
)

if TYPE_CHECKING:
    from sensorkit.describe.sensorinfo import RobotInfo
    from sensorkit.describe.stereo import StereoPair
    from sensorkit.describe.views import CameraView, SensorInfo

__all__ = ["ExportFiles", "export_files", "publish_export"]

_TOP_LEVEL_NAMES = ("bridge.yaml",)


@dataclass
class ExportFiles:
    """The export as text, before anything is written.

    ``files`` maps a POSIX path relative to the output folder to its text; ``notes``
    are for information; ``skipped`` names files a sensor should have had and why
    they could not be produced (the robot needs a fix).
    """

    info: RobotInfo
    files: dict[str, str] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)
    folders: dict[str, str] = field(default_factory=dict)  # sensor name -> folder


def _folder(name: str, taken: set[str]) -> str:
    base = re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._") or "sensor"
    out, k = base, 2
    while out.lower() in taken or out.lower() in _TOP_LEVEL_NAMES:
        out, k = f"{base}_{k}", k + 1
    taken.add(out.lower())
    return out


def _attempt(
    plan: ExportFiles, path: str, what: str, make: Callable[[], str], *, limit: bool = False
) -> None:
    """Add ``path`` from ``make()``. An impossible value skips it with the reason: as a
    note when the format cannot hold the camera (``limit``), else as a skipped file."""
    try:
        plan.files[path] = make()
    except InvalidValue as exc:
        if limit:
            plan.notes.append(f"{path} not written: {what} cannot hold this camera: {exc}")
        else:
            plan.skipped.append(f"{path}: {what}: {exc}")


def _sensor_record(s: SensorInfo, target: str) -> dict[str, object]:
    from sensorkit.exporters import laser_scan_dict

    record: dict[str, object] = {
        "name": s.name,
        "type": s.sensor.type,
        "kind": s.sensor.kind,
        "target": target,
        "link": s.link,
        "frame_id": s.frame,
        "frame_from": s.frame_how,
        "body_frame": s.body_frame,
        "update_rate": s.sensor.update_rate,
        "topics": dict(s.topics),
        "cameras": [c.id for c in s.cameras],
        "notes": list(s.notes),
    }
    if s.T_world_render is not None:
        record["T_root_sensor"] = [[float(v) for v in row] for row in s.T_world_render]
    if s.scan is not None:
        record["scan"] = laser_scan_dict(s.scan)
    if s.vertical is not None:
        record["vertical"] = laser_scan_dict(s.vertical)
    return record


def _export_camera(
    plan: ExportFiles, s: SensorInfo, view: CameraView, folder: str, imu: SensorInfo | None
) -> None:
    from sensorkit.exporters import depthimage_to_laserscan_yaml, to_json

    info = plan.info
    plan.notes.extend(f"{view.id}: {n}" for n in view.notes)
    if view.intrinsics is None:
        plan.skipped.append(f"{folder}/: camera files: {view.error}")
        return
    intr = view.intrinsics
    notes: list[str] = []

    def document(fmt: str, mode: str = "monocular") -> Callable[[], str]:
        return lambda: camera_document(view, fmt, info, notes, mode=mode, imu=imu)

    _attempt(plan, f"{folder}/camera_info.yaml", "camera_info", document("camera-info"))
    _attempt(plan, f"{folder}/opencv.yaml", "OpenCV", document("opencv"))
    _attempt(
        plan,
        f"{folder}/intrinsics.json",
        "JSON",
        lambda: to_json(camera_record(view, info.target)),
    )
    if s.has_colour:
        _attempt(plan, f"{folder}/orbslam3.yaml", "ORB-SLAM3", document("orbslam3"), limit=True)
        _attempt(
            plan, f"{folder}/orbslam3_v1.yaml", "ORB-SLAM3", document("orbslam3-v1"), limit=True
        )
        if view.image_topic is None:
            plan.skipped.append(
                f"{folder}/kalibr.yaml: no image topic for Kalibr's rostopic "
                "(the camera publishes nothing to ROS)"
            )
        else:
            _attempt(plan, f"{folder}/kalibr.yaml", "Kalibr", document("kalibr"), limit=True)
    else:
        plan.notes.append(
            f"{view.id}: publishes a depth image only, so no ORB-SLAM3 or Kalibr files "
            "(an rgbd_camera publishes colour and depth)"
        )
    if s.sensor.is_depth:
        if s.has_colour:  # Gazebo's depth images are 32FC1 metres: DepthMapFactor 1.0
            for name, fmt in (
                ("orbslam3_rgbd.yaml", "orbslam3"),
                ("orbslam3_rgbd_v1.yaml", "orbslam3-v1"),
            ):
                _attempt(plan, f"{folder}/{name}", "ORB-SLAM3", document(fmt, "rgbd"), limit=True)
        lo, hi, range_notes = depth_range(s.sensor, view.spec, info.target)
        notes.extend(range_notes)
        depth_topic = s.topics.get("depth_image")
        depth_info = s.topics.get("depth_camera_info")
        path = f"{folder}/depthimage_to_laserscan.yaml"
        if s.body_frame is None:
            plan.skipped.append(
                f"{path}: no link sits at the camera's pose with x forward to stamp the scan "
                "with; add a fixed link there (the camera's body frame)"
            )
        elif depth_topic is None or depth_info is None:
            plan.skipped.append(f"{path}: the camera publishes no depth image topic to ROS")
        else:
            body = s.body_frame
            _attempt(
                plan,
                path,
                "depthimage_to_laserscan",
                lambda: depthimage_to_laserscan_yaml(
                    intr,
                    depth_topic=depth_topic,
                    depth_camera_info_topic=depth_info,
                    output_frame=body,
                    range_min=lo,
                    range_max=hi,
                    fps=view.fps,
                ),
            )
    plan.notes.extend(f"{view.id}: {n}" for n in dict.fromkeys(notes))


def _export_lidar(plan: ExportFiles, s: SensorInfo, folder: str) -> None:
    from sensorkit.exporters import (
        amcl_yaml,
        nav2_obstacle_layer_yaml,
        scan_yaml,
        slam_toolbox_yaml,
    )

    if s.scan is None:
        plan.skipped.append(f"{folder}/: lidar files: {s.scan_error}")
        return
    scan = s.scan
    plan.files[f"{folder}/scan.yaml"] = scan_yaml(scan, frame_id=s.frame)
    consumers = ("slam_toolbox.yaml", "nav2_obstacle_layer.yaml", "amcl.yaml")
    if s.vertical is not None:
        plan.notes.append(
            f"{s.name}: a 3D lidar ({s.vertical.samples} layers): no LaserScan consumer files "
            f"({', '.join(consumers)}); feed its points to a 3D pipeline or pointcloud_to_laserscan"
        )
        return
    topic = s.topics.get("scan")
    if topic is None:
        if s.topics:
            published = ", ".join(f"{k} {v}" for k, v in s.topics.items())
            why = f"it publishes no sensor_msgs/LaserScan ({published}); set <output_type>sensor_msgs/LaserScan</output_type>"
        else:
            why = "it publishes no LaserScan topic to ROS"
        plan.skipped.extend(f"{folder}/{name}: {why}" for name in consumers)
        return
    _attempt(
        plan,
        f"{folder}/slam_toolbox.yaml",
        "slam_toolbox",
        lambda: slam_toolbox_yaml(scan, scan_topic=topic),
    )
    _attempt(
        plan,
        f"{folder}/nav2_obstacle_layer.yaml",
        "Nav2",
        lambda: nav2_obstacle_layer_yaml(scan, topic=topic),
    )
    _attempt(plan, f"{folder}/amcl.yaml", "AMCL", lambda: amcl_yaml(scan, scan_topic=topic))


def _export_pair(plan: ExportFiles, pair: StereoPair, folder: str, imu: SensorInfo | None) -> None:
    """A stereo pair's folder: ``stereo.json``; ``left.yaml``/``right.yaml`` camera_info
    (a rectified pair); ``kalibr_camchain.yaml``; ORB-SLAM3 ``orbslam3_stereo.yaml`` (old
    format) and ``orbslam3_stereo_v1.yaml``, with an IMU ``orbslam3_stereo_inertial.yaml``
    and ``orbslam3_stereo_inertial_v1.yaml``."""
    from sensorkit.exporters import camera_info_yaml, to_json
    from sensorkit.exporters.camera_info import stereo_camera_infos

    info = plan.info
    plan.notes.extend(f"{pair.name}: {n}" for n in pair.notes)
    plan.files[f"{folder}/stereo.json"] = to_json(pair_record(pair))
    left, right = pair.left.intrinsics, pair.right.intrinsics
    if left is None or right is None:
        bad = pair.left if left is None else pair.right
        plan.skipped.append(f"{folder}/: stereo files: camera {bad.id}: {bad.error}")
        return
    notes: list[str] = []
    if pair.rectified:
        if left.P[:, :3].tolist() != right.P[:, :3].tolist():
            notes.append(
                "the eyes' P differ in fx', fy', cx' or cy': left.yaml/right.yaml keep each "
                "eye's own (stereo_image_proc expects one rectified camera)"
            )
        pair_infos = stereo_camera_infos(left, right, pair.baseline)

        def camera_info(intr: Intrinsics, name: str) -> Callable[[], str]:
            return lambda: camera_info_yaml(intr, camera_name=name)

        for side, eye, intr in zip(
            ("left", "right"), (pair.left, pair.right), pair_infos, strict=True
        ):
            _attempt(plan, f"{folder}/{side}.yaml", "camera_info", camera_info(intr, eye.name))
    else:
        plan.notes.append(
            f"{folder}/left.yaml, right.yaml not written: camera_info's Tx describes a "
            "rectified pair only"
        )

    def document(fmt: str, inertial: bool = False) -> Callable[[], str]:
        return lambda: pair_document(pair, fmt, info, notes, imu=imu, inertial=inertial)

    if pair.left.image_topic is None or pair.right.image_topic is None:
        plan.skipped.append(
            f"{folder}/kalibr_camchain.yaml: no image topic for Kalibr's rostopic "
            "(an eye publishes nothing to ROS)"
        )
    else:
        _attempt(plan, f"{folder}/kalibr_camchain.yaml", "Kalibr", document("kalibr"), limit=True)
    files = [("orbslam3_stereo", "orbslam3"), ("orbslam3_stereo_v1", "orbslam3-v1")]
    for stem, fmt in files:
        _attempt(plan, f"{folder}/{stem}.yaml", "ORB-SLAM3", document(fmt), limit=True)
    if imu is not None:
        for stem, fmt in files:
            name = stem.replace("stereo", "stereo_inertial")
            _attempt(plan, f"{folder}/{name}.yaml", "ORB-SLAM3", document(fmt, True), limit=True)
    plan.notes.extend(f"{pair.name}: {n}" for n in dict.fromkeys(notes))


def _bridge(plan: ExportFiles) -> None:
    from sensorkit.describe.bridge import bridge_entries, model_bridge_entries
    from sensorkit.exporters.bridge import bridge_file_text

    info = plan.info
    for s in info.sensors:
        if not s.topics and s.sensor.kind in ("camera", "depth", "rgbd", "lidar", "imu"):
            why = "; ".join(s.topic_notes) or "no topic"
            plan.skipped.append(f"bridge.yaml: sensor {s.name!r} is not bridged: {why}")
    try:
        if info.robot.sdf is not None:
            entries = model_bridge_entries(info.robot, info.target)
        else:
            entries = bridge_entries(info.robot.document.root, info.target)
        plan.files["bridge.yaml"] = bridge_file_text(
            entries, robot=info.robot.name, gz_version=info.target, by="sensorkit export"
        )
    except InvalidValue as exc:
        plan.skipped.append(f"bridge.yaml: {exc}")


def export_files(info: RobotInfo, *, imu: str | None = None) -> ExportFiles:
    """Every file ``sensorkit export`` writes, as text (nothing touches the disk).

    Per sensor, in a folder named after it: ``sensor.json`` (frames, topics); cameras
    ``camera_info.yaml``, ``opencv.yaml``, ``intrinsics.json`` and, with a colour image,
    ``orbslam3.yaml`` (old format), ``orbslam3_v1.yaml``, ``kalibr.yaml``; depth and
    RGB-D cameras ``depthimage_to_laserscan.yaml`` and, with colour,
    ``orbslam3_rgbd.yaml``/``orbslam3_rgbd_v1.yaml``; each camera of a multicamera in a
    subfolder; 2D lidars ``scan.yaml``, ``slam_toolbox.yaml``, ``nav2_obstacle_layer.yaml``,
    ``amcl.yaml`` (3D lidars ``scan.yaml``). Each stereo pair in ``stereo_<left>_<right>``
    (see :func:`_export_pair`). Gazebo Sim targets add ``bridge.yaml``. ``T_cam_imu`` and
    the stereo-inertial files use the IMU ``imu`` names (see :func:`select_imu`).

    Raises:
        UsageError: ``imu`` is no IMU of the robot.
    """
    from sensorkit.exporters import to_json
    from sensorkit.model.targets import is_gz

    plan = ExportFiles(info)
    chosen, imu_notes = select_imu(info, imu)
    if chosen is not None and (info.stereo_pairs or any(s.has_colour for s in info.sensors)):
        plan.notes.extend(imu_notes)
    taken: set[str] = set()
    for s in info.sensors:
        folder = _folder(s.name, taken)
        plan.folders[s.name] = folder
        plan.files[f"{folder}/sensor.json"] = to_json(_sensor_record(s, info.target))
        plan.notes.extend(f"{s.name}: {n}" for n in s.notes)
        if s.frame_is_default and s.frame is not None and is_gz(info.target):
            plan.notes.append(
                f"{s.name}: its data is stamped {s.frame!r} (gz's scoped default), which is no TF frame"
            )
        if s.sensor.is_camera:
            inner: set[str] = set()
            multi = len(s.cameras) > 1
            for view in s.cameras:
                sub = f"{folder}/{_folder(view.spec.name or view.id, inner)}" if multi else folder
                _export_camera(plan, s, view, sub, chosen)
        elif s.sensor.kind == "lidar":
            _export_lidar(plan, s, folder)
    for pair in info.stereo_pairs:
        folder = _folder(f"stereo_{pair.left.id}_{pair.right.id}", taken)
        _export_pair(plan, pair, folder, chosen)
    if is_gz(info.target):
        _bridge(plan)
    return plan


def publish_export(
    files: Mapping[str, str], out: Path, *, force: bool = False, inputs: Iterable[Path] = ()
) -> list[Path]:
    """Write ``files`` (relative POSIX path -> text) into the folder ``out``, atomically.

    Everything is written into a temporary folder beside ``out`` and renamed into place
    in one step, so ``out`` holds the old export or the new one, never a mix. ``out``
    must be missing or empty unless ``force`` (then it is replaced whole; the current
    folder, its parents, the home folder and any folder holding one of ``inputs`` are
    never replaced).

    Returns:
        The paths written, under ``out``, in ``files`` order.

    Raises:
        UsageError: ``out`` is a file, or a non-empty folder without ``force``, or
            protected; a path in ``files`` is absolute or climbs out.
        OSError: the file system refused (nothing is left behind).
    """
    from sensorkit.base.atomic import check_replaceable, staged_folder, write_text

    check_replaceable(out, force=force, inputs=inputs)
    given, out = out, out.absolute()
    for rel in files:
        parts = Path(rel).parts
        if Path(rel).is_absolute() or ".." in parts or not parts:
            msg = f"export path {rel!r} must stay inside the output folder"
            raise UsageError(msg)
    with staged_folder(out) as temp:
        for rel, text in files.items():
            target = temp / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            write_text(target, text, fsync=False)  # the folder is published as a whole
    return [given / rel for rel in files]
