"""``sensorkit intrinsics`` and ``sensorkit export`` end to end: golden intrinsics, every
exported file parsed back with the number kinds its reader demands, topics and frames
taken from the robot, and the ways the commands refuse to run."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml
from typer.testing import CliRunner

from sensorkit.cli import app

GOLDEN_FX = 205.46963709898583  # 640 / (2 tan(1.0)): 640x480, hfov 2.0 rad
OPTICAL_RPY = "-1.5707963267948966 0 -1.5707963267948966"
INERTIA = (
    '<inertial><mass value="0.1"/>'
    '<inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>'
)
BRIDGE_KEYS = {"ros_topic_name", "gz_topic_name", "ros_type_name", "gz_type_name", "direction"}


# --------------------------------------------------------------------------- fixtures


def _camera_block(
    width: int = 640, height: int = 480, hfov: float = 2.0, extra: str = "", name: str = "cam"
) -> str:
    return (
        f'<camera name="{name}"><horizontal_fov>{hfov}</horizontal_fov>'
        f"<image><width>{width}</width><height>{height}</height><format>R8G8B8</format></image>"
        f"<clip><near>0.05</near><far>20</far></clip>{extra}</camera>"
    )


def classic_camera(name: str = "front_camera", params: str = "", stype: str = "camera") -> str:
    return (
        f'<sensor name="{name}" type="{stype}"><update_rate>30</update_rate>{_camera_block()}'
        f'<plugin name="{name}_controller" filename="libgazebo_ros_camera.so">'
        f"<frame_name>{name}_optical_frame</frame_name>{params}</plugin></sensor>"
    )


def classic_lidar(name: str = "laser", output: str = "sensor_msgs/LaserScan") -> str:
    return (
        f'<sensor name="{name}" type="ray"><update_rate>10</update_rate><ray><scan><horizontal>'
        "<samples>360</samples><resolution>1</resolution><min_angle>-3.14159</min_angle>"
        "<max_angle>3.14159</max_angle></horizontal></scan>"
        "<range><min>0.12</min><max>12.0</max></range></ray>"
        f'<plugin name="{name}_controller" filename="libgazebo_ros_ray_sensor.so">'
        "<ros><remapping>~/out:=scan</remapping></ros>"
        f"<output_type>{output}</output_type><frame_name>{name}_link</frame_name></plugin></sensor>"
    )


def imu_sensor(gz: bool = False) -> str:
    tail = (
        "<topic>imu</topic><gz_frame_id>imu_link</gz_frame_id>"
        if gz
        else '<plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so">'
        "<ros><remapping>~/out:=imu</remapping></ros><frame_name>imu_link</frame_name></plugin>"
    )
    return f'<sensor name="imu" type="imu"><update_rate>100</update_rate>{tail}</sensor>'


def mounted(name: str, sensor: str, xyz: str = "0.2 0 0.3", optical: bool = True) -> str:
    """A body link ``<name>_link`` on base_link carrying ``sensor``, plus its optical frame."""
    parts = [
        f'<link name="{name}_link">{INERTIA}</link>',
        f'<joint name="{name}_joint" type="fixed"><parent link="base_link"/>'
        f'<child link="{name}_link"/><origin xyz="{xyz}" rpy="0 0 0"/></joint>',
    ]
    if optical:
        parts += [
            f'<link name="{name}_optical_frame"/>',
            f'<joint name="{name}_optical_joint" type="fixed"><parent link="{name}_link"/>'
            f'<child link="{name}_optical_frame"/><origin xyz="0 0 0" rpy="{OPTICAL_RPY}"/></joint>',
        ]
    parts.append(f'<gazebo reference="{name}_link">{sensor}</gazebo>')
    return "\n".join(parts)


def robot(*parts: str, name: str = "rover", extra: str = "") -> str:
    body = "\n".join(parts)
    return (
        f'<?xml version="1.0"?>\n<robot name="{name}">\n'
        f'<link name="base_link"><inertial><mass value="5"/>'
        '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>\n'
        f"{body}\n{extra}\n</robot>\n"
    )


CLASSIC_DRIVE = (
    '<gazebo><plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so"></plugin></gazebo>'
)
GZ_SYSTEM = (
    '<gazebo><plugin filename="gz-sim-sensors-system" name="gz::sim::systems::Sensors">'
    "<render_engine>ogre2</render_engine></plugin></gazebo>"
)


def classic_robot() -> str:
    return robot(
        mounted("front_camera", classic_camera("front_camera")),
        mounted(
            "depth",
            classic_camera(
                "depth", "<min_depth>0.2</min_depth><max_depth>8.0</max_depth>", stype="depth"
            ),
            xyz="0.2 0.1 0.3",
        ),
        mounted("laser", classic_lidar("laser"), xyz="0 0 0.4", optical=False),
        mounted("imu", imu_sensor(), xyz="0 0 0.1", optical=False),
        extra=CLASSIC_DRIVE,
    )


def gz_robot() -> str:
    cam = (
        '<sensor name="front_camera" type="camera"><update_rate>30</update_rate>'
        "<topic>front_camera/image_raw</topic><gz_frame_id>front_camera_optical_frame</gz_frame_id>"
        f"{_camera_block()}</sensor>"
    )
    rgbd = (
        '<sensor name="rgbd" type="rgbd_camera"><update_rate>15</update_rate><topic>rgbd</topic>'
        "<gz_frame_id>rgbd_optical_frame</gz_frame_id>"
        + _camera_block(
            extra="<depth_camera><clip><near>0.3</near><far>6.0</far></clip></depth_camera>"
        )
        + "</sensor>"
    )
    lidar = (
        '<sensor name="laser" type="gpu_lidar"><update_rate>10</update_rate><topic>scan</topic>'
        "<gz_frame_id>laser_link</gz_frame_id><lidar><scan><horizontal><samples>360</samples>"
        "<resolution>1</resolution><min_angle>-3.14159</min_angle><max_angle>3.14159</max_angle>"
        "</horizontal></scan><range><min>0.12</min><max>12</max></range></lidar></sensor>"
    )
    return robot(
        mounted("front_camera", cam),
        mounted("rgbd", rgbd, xyz="0.2 0.1 0.3"),
        mounted("laser", lidar, xyz="0 0 0.4", optical=False),
        mounted("imu", imu_sensor(gz=True), xyz="0 0 0.1", optical=False),
        extra=GZ_SYSTEM,
    )


@pytest.fixture
def classic_file(tmp_path: Path) -> Path:
    path = tmp_path / "classic.urdf"
    path.write_text(classic_robot())
    return path


@pytest.fixture
def gz_file(tmp_path: Path) -> Path:
    path = tmp_path / "gz.urdf"
    path.write_text(gz_robot())
    return path


def run(*args: str) -> Any:
    result = CliRunner().invoke(app, [str(a) for a in args])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return result


def one_line_error(result: Any) -> str:
    assert result.exit_code == 2, (result.stdout, result.stderr)
    assert result.stdout == ""
    message = result.stderr.strip()
    assert "\n" not in message and "Traceback" not in message, message
    assert message.startswith("sensorkit: ")
    return message


# --------------------------------------------------------------------------- readers


def _matrix(loader: Any, node: Any) -> dict[str, Any]:
    mapping: dict[str, Any] = loader.construct_mapping(node, deep=True)
    mapping["__opencv_matrix__"] = True
    return mapping


OpenCVLoader: Any = type("OpenCVLoader", (yaml.SafeLoader,), {})
OpenCVLoader.add_constructor("tag:yaml.org,2002:opencv-matrix", _matrix)


def load_opencv(path: Path) -> dict[str, Any]:
    """cv::FileStorage's YAML: ``%YAML:1.0`` first (a directive PyYAML refuses), then YAML."""
    first, rest = path.read_text().split("\n", 1)
    assert first == "%YAML:1.0", path
    data = yaml.load(rest, Loader=OpenCVLoader)
    assert isinstance(data, dict)
    return data


def load_yaml(path: Path) -> Any:
    return yaml.safe_load(path.read_text())


def literal(path: Path, key: str) -> str:
    """The text after ``key:`` (the kind OpenCV's reader sees: 30 is an int, 30.0 a real)."""
    (match,) = re.findall(rf"^{re.escape(key)}:\s*(.*)$", path.read_text(), re.MULTILINE)
    return str(match)


def reals(data: dict[str, Any], *keys: str) -> None:
    for key in keys:
        assert type(data[key]) is float, (key, data[key])


def ints(data: dict[str, Any], *keys: str) -> None:
    for key in keys:
        assert type(data[key]) is int, (key, data[key])


# --------------------------------------------------------------------------- intrinsics


def test_golden_intrinsics_classic(classic_file: Path) -> None:
    result = run("intrinsics", classic_file, "--sensor", "front_camera")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["target"] == "classic" and data["convention"] == "classic"
    (cam,) = data["cameras"]
    assert cam["fx"] == GOLDEN_FX and cam["fy"] == GOLDEN_FX
    assert (cam["cx"], cam["cy"]) == (320.5, 240.5)
    assert cam["K"] == [[GOLDEN_FX, 0.0, 320.5], [0.0, GOLDEN_FX, 240.5], [0.0, 0.0, 1.0]]
    assert cam["image_topic"] == "/front_camera/image_raw"
    assert cam["camera_info_topic"] == "/front_camera/camera_info"
    assert cam["frame_id"] == "front_camera_optical_frame"


def test_golden_intrinsics_gz(gz_file: Path) -> None:
    result = run("intrinsics", gz_file)
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["target"] == "harmonic" and data["convention"] == "gz"
    cams = {c["camera"]: c for c in data["cameras"]}
    assert set(cams) == {"front_camera", "rgbd"}
    for cam in cams.values():
        assert abs(cam["fx"] - GOLDEN_FX) < 1e-4 and abs(cam["fy"] - GOLDEN_FX) < 1e-4
        assert (cam["cx"], cam["cy"]) == (320.0, 240.0)
    assert cams["rgbd"]["image_topic"] == "/rgbd/image_raw"


@pytest.mark.parametrize(
    ("convention", "cx", "cy"),
    [("gz", 320.0, 240.0), ("ideal", 319.5, 239.5), ("classic", 320.5, 240.5)],
)
def test_convention_overrides_the_target(
    classic_file: Path, convention: str, cx: float, cy: float
) -> None:
    result = run("intrinsics", classic_file, "--sensor", "front_camera", "--convention", convention)
    assert result.exit_code == 0, result.stderr
    (cam,) = json.loads(result.stdout)["cameras"]
    assert (cam["convention"], cam["cx"], cam["cy"]) == (convention, cx, cy)
    assert abs(cam["fx"] - GOLDEN_FX) < 1e-4


def test_target_option_sets_the_convention(classic_file: Path) -> None:
    result = run("intrinsics", classic_file, "--sensor", "front_camera", "--target", "jetty")
    (cam,) = json.loads(result.stdout)["cameras"]
    assert (cam["cx"], cam["cy"]) == (320.0, 240.0)


def test_classic_plugin_values_are_read(tmp_path: Path) -> None:
    params = "<cx>300.25</cx><cy>0</cy><focal_length>250.0</focal_length><hack_baseline>0.07</hack_baseline>"
    path = tmp_path / "r.urdf"
    path.write_text(robot(mounted("cam", classic_camera("cam", params))))
    (cam,) = json.loads(run("intrinsics", path).stdout)["cameras"]
    # ROS 2 uses any value present verbatim, 0 included
    assert (cam["fx"], cam["cx"], cam["cy"]) == (250.0, 300.25, 0.0)
    assert cam["P"][0][3] == -250.0 * 0.07


def test_ros1_names_and_zero_means_computed(tmp_path: Path) -> None:
    params = "<Cx>0</Cx><Cy>100.5</Cy><focalLength>0</focalLength><cx>1.0</cx>"
    path = tmp_path / "r.urdf"
    path.write_text(robot(mounted("cam", classic_camera("cam", params))))
    (cam,) = json.loads(run("intrinsics", path, "--target", "ros1").stdout)["cameras"]
    assert (cam["fx"], cam["cx"], cam["cy"]) == (GOLDEN_FX, 320.5, 100.5)


def test_missing_size_takes_sdf_defaults_with_a_note(tmp_path: Path) -> None:
    sensor = (
        '<sensor name="cam" type="camera"><camera><image><format>R8G8B8</format></image></camera>'
        '<plugin name="c" filename="libgazebo_ros_camera.so"/></sensor>'
    )
    path = tmp_path / "r.urdf"
    path.write_text(robot(mounted("cam", sensor)))
    result = run("intrinsics", path)
    (cam,) = json.loads(result.stdout)["cameras"]
    assert (cam["width"], cam["height"], cam["cx"]) == (320, 240, 160.5)
    assert abs(cam["hfov"] - 1.047) < 1e-12
    assert "SDF's default 320" in result.stderr


@pytest.mark.parametrize("fmt", ["camera-info", "orbslam3", "orbslam3-v1", "kalibr", "opencv"])
def test_single_document_formats(classic_file: Path, tmp_path: Path, fmt: str) -> None:
    result = run("intrinsics", classic_file, "--sensor", "front_camera", "--format", fmt)
    assert result.exit_code == 0, result.stderr
    doc = tmp_path / "doc.yaml"
    doc.write_text(result.stdout)
    if fmt == "camera-info":
        data = load_yaml(doc)
        assert data["camera_matrix"]["data"][:3] == [GOLDEN_FX, 0.0, 320.5]
    elif fmt == "kalibr":
        data = load_yaml(doc)["cam0"]
        assert data["intrinsics"] == [GOLDEN_FX, GOLDEN_FX, 320.5, 240.5]
        assert len(data["T_cam_imu"]) == 4  # the robot has an IMU
    elif fmt == "opencv":
        data = load_opencv(doc)
        assert data["camera_matrix"]["data"][2] == 320.5
    else:
        data = load_opencv(doc)
        key = "Camera1.fx" if fmt == "orbslam3-v1" else "Camera.fx"
        assert data[key] == GOLDEN_FX


# --------------------------------------------------------------------------- export


@pytest.fixture
def classic_export(classic_file: Path, tmp_path: Path) -> tuple[Path, Any]:
    out = tmp_path / "out"
    result = run("export", classic_file, "--out", out)
    assert result.exit_code == 0, result.stderr
    return out, result


def test_export_lists_every_file_it_wrote(classic_export: tuple[Path, Any]) -> None:
    out, result = classic_export
    listed = sorted(result.stdout.split())
    on_disk = sorted(p.as_posix() for p in out.rglob("*") if p.is_file())
    assert listed == on_disk
    assert "wrote" in result.stderr and str(out) in result.stderr
    names = {p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()}
    camera = {
        "camera_info.yaml",
        "orbslam3.yaml",
        "orbslam3_v1.yaml",
        "kalibr.yaml",
        "opencv.yaml",
        "intrinsics.json",
        "sensor.json",
    }
    depth = camera | {"depthimage_to_laserscan.yaml", "orbslam3_rgbd.yaml", "orbslam3_rgbd_v1.yaml"}
    lidar = {
        "scan.yaml",
        "slam_toolbox.yaml",
        "nav2_obstacle_layer.yaml",
        "amcl.yaml",
        "sensor.json",
    }
    expected = (
        {f"front_camera/{n}" for n in camera}
        | {f"depth/{n}" for n in depth}
        | {f"laser/{n}" for n in lidar}
        | {"imu/sensor.json"}
    )
    assert names == expected  # classic: no bridge.yaml
    assert not [p for p in out.parent.iterdir() if p.name.startswith(".out.")]  # no temp left


def test_exported_camera_info_and_opencv(classic_export: tuple[Path, Any]) -> None:
    out, _ = classic_export
    info = load_yaml(out / "front_camera/camera_info.yaml")
    ints(info, "image_width", "image_height")
    assert info["camera_name"] == "front_camera"
    assert info["camera_matrix"]["rows"] == 3 and info["camera_matrix"]["cols"] == 3
    assert info["camera_matrix"]["data"] == [
        GOLDEN_FX,
        0.0,
        320.5,
        0.0,
        GOLDEN_FX,
        240.5,
        0.0,
        0.0,
        1.0,
    ]
    assert info["distortion_model"] == "plumb_bob"
    assert (
        info["distortion_coefficients"]["cols"] == len(info["distortion_coefficients"]["data"]) == 5
    )
    assert len(info["projection_matrix"]["data"]) == 12
    assert all(type(v) is float for v in info["projection_matrix"]["data"])

    cv = load_opencv(out / "front_camera/opencv.yaml")
    ints(cv, "image_width", "image_height")
    for key, shape in (("camera_matrix", (3, 3)), ("distortion_coefficients", (1, 5))):
        matrix = cv[key]
        assert matrix["__opencv_matrix__"] and matrix["dt"] == "d"
        assert (matrix["rows"], matrix["cols"]) == shape
        assert all(type(v) is float for v in matrix["data"])

    data = json.loads((out / "front_camera/intrinsics.json").read_text())
    assert (data["fx"], data["cx"], data["cy"]) == (GOLDEN_FX, 320.5, 240.5)


def test_exported_orbslam3_kinds(classic_export: tuple[Path, Any]) -> None:
    out, _ = classic_export
    old_path = out / "front_camera/orbslam3.yaml"
    old = load_opencv(old_path)
    assert old["Camera.type"] == "PinHole"
    reals(old, "Camera.fx", "Camera.fy", "Camera.cx", "Camera.cy", "Camera.k1", "Camera.k2")
    reals(old, "Camera.p1", "Camera.p2", "ORBextractor.scaleFactor")
    ints(old, "Camera.width", "Camera.height", "Camera.RGB", "ORBextractor.nFeatures")
    ints(old, "ORBextractor.nLevels", "ORBextractor.iniThFAST", "ORBextractor.minThFAST")
    assert old["Camera.fps"] == 30
    assert old["Camera.fx"] == GOLDEN_FX

    v1_path = out / "front_camera/orbslam3_v1.yaml"
    v1 = load_opencv(v1_path)
    assert v1["File.version"] == "1.0" and literal(v1_path, "File.version") == '"1.0"'
    reals(v1, "Camera1.fx", "Camera1.fy", "Camera1.cx", "Camera1.cy", "ORBextractor.scaleFactor")
    ints(v1, "Camera.width", "Camera.height", "Camera.fps", "Camera.RGB", "ORBextractor.nFeatures")
    assert literal(v1_path, "Camera.fps") == "30"  # 30.0 aborts ORB-SLAM3
    assert v1["Camera.RGB"] == 1  # R8G8B8

    rgbd = load_opencv(out / "depth/orbslam3_rgbd.yaml")
    reals(rgbd, "Camera.bf", "ThDepth", "DepthMapFactor")
    assert rgbd["DepthMapFactor"] == 1.0  # Gazebo's depth is 32FC1 metres
    rgbd1 = load_opencv(out / "depth/orbslam3_rgbd_v1.yaml")
    reals(rgbd1, "Stereo.b", "Stereo.ThDepth", "RGBD.DepthMapFactor", "Camera1.fx")
    ints(rgbd1, "Camera.fps", "Camera.width")


def test_exported_kalibr(classic_export: tuple[Path, Any]) -> None:
    out, _ = classic_export
    cam = load_yaml(out / "front_camera/kalibr.yaml")["cam0"]
    assert cam["camera_model"] == "pinhole" and cam["distortion_model"] == "radtan"
    assert cam["intrinsics"] == [GOLDEN_FX, GOLDEN_FX, 320.5, 240.5]
    assert all(type(v) is float for v in cam["intrinsics"] + cam["distortion_coeffs"])
    assert len(cam["distortion_coeffs"]) == 4
    assert cam["resolution"] == [640, 480] and all(type(v) is int for v in cam["resolution"])
    assert cam["rostopic"] == "/front_camera/image_raw"
    # IMU at (0, 0, 0.1), camera body at (0.2, 0, 0.3): in the optical frame (x right,
    # y down, z forward) the IMU is 0.2 m up (y = +0.2 down-axis) and 0.2 m behind
    T = cam["T_cam_imu"]
    assert [row[3] for row in T[:3]] == pytest.approx([0.0, 0.2, -0.2])
    rotation = [v for row in T[:3] for v in row[:3]]
    assert rotation == pytest.approx([0, -1, 0, 0, 0, -1, 1, 0, 0])  # R_optical_body
    assert T[3] == [0.0, 0.0, 0.0, 1.0]


def test_depthimage_to_laserscan_uses_the_body_frame(classic_export: tuple[Path, Any]) -> None:
    out, _ = classic_export
    path = out / "depth/depthimage_to_laserscan.yaml"
    params = load_yaml(path)["depthimage_to_laserscan"]["ros__parameters"]
    assert params["output_frame"] == "depth_link"  # not depth_optical_frame
    assert params["range_min"] == 0.2 and params["range_max"] == 8.0
    reals(params, "range_min", "range_max", "scan_time")
    ints(params, "scan_height")
    assert "depth:=/depth/depth/image_raw" in path.read_text()
    assert "depth_camera_info:=/depth/depth/camera_info" in path.read_text()


def test_lidar_exports_carry_the_remapped_topic_and_range(classic_export: tuple[Path, Any]) -> None:
    out, _ = classic_export
    scan = load_yaml(out / "laser/scan.yaml")
    assert scan["header"]["frame_id"] == "laser_link"
    assert scan["range_max"] == 12.0 and scan["range_min"] == 0.12
    assert scan["angle_min"] == -3.14159 and scan["angle_max"] == 3.14159
    assert scan["angle_increment"] == pytest.approx(2 * 3.14159 / 359)
    reals(scan, "angle_min", "angle_max", "angle_increment", "time_increment", "scan_time")

    slam = load_yaml(out / "laser/slam_toolbox.yaml")["slam_toolbox"]["ros__parameters"]
    assert slam["scan_topic"] == "/scan"  # ~/out:=scan in the root namespace
    assert slam["max_laser_range"] == 12.0

    nav = load_yaml(out / "laser/nav2_obstacle_layer.yaml")
    layer = nav["local_costmap"]["local_costmap"]["ros__parameters"]["obstacle_layer"]
    source = layer[layer["observation_sources"]]
    assert source["topic"] == "/scan" and source["data_type"] == "LaserScan"
    assert source["obstacle_max_range"] <= 12.0 and source["raytrace_max_range"] <= 12.0

    amcl = load_yaml(out / "laser/amcl.yaml")["amcl"]["ros__parameters"]
    assert amcl["scan_topic"] == "/scan"
    assert (amcl["laser_min_range"], amcl["laser_max_range"]) == (0.12, 12.0)

    record = json.loads((out / "laser/sensor.json").read_text())
    assert record["topics"] == {"scan": "/scan"} and record["frame_id"] == "laser_link"
    assert record["scan"]["samples"] == 360


def test_pointcloud_lidar_gets_no_laserscan_consumers(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(
        robot(mounted("laser", classic_lidar(output="sensor_msgs/PointCloud2"), optical=False))
    )
    out = tmp_path / "out"
    result = run("export", path, "--out", out)
    assert result.exit_code == 1  # some files could not be produced; the rest are written
    assert (out / "laser/scan.yaml").is_file()
    assert not (out / "laser/slam_toolbox.yaml").exists()
    assert "output_type" in result.stderr and "slam_toolbox.yaml" in result.stderr


def test_gz_export_bridges_every_sensor_topic(gz_file: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = run("export", gz_file, "--out", out)
    assert result.exit_code == 0, result.stderr
    entries = load_yaml(out / "bridge.yaml")
    assert isinstance(entries, list) and entries
    for entry in entries:
        assert isinstance(entry, dict) and set(entry) == BRIDGE_KEYS, entry
        assert entry["direction"] in ("GZ_TO_ROS", "ROS_TO_GZ", "BIDIRECTIONAL")
        assert entry["gz_type_name"].startswith("gz.msgs.")
    gz_names = {e["gz_topic_name"].strip("/") for e in entries}
    wanted = {
        "front_camera/image_raw",
        "front_camera/camera_info",
        "rgbd/image",
        "rgbd/depth_image",
        "rgbd/camera_info",
        "scan",
        "scan/points",
        "imu",
    }
    assert wanted <= gz_names
    assert "rgbd/points" not in gz_names  # x-forward cloud stamped optical: gz-sensors#488
    types = {e["gz_topic_name"].strip("/"): e["ros_type_name"] for e in entries}
    assert types["scan"] == "sensor_msgs/msg/LaserScan"
    assert types["imu"] == "sensor_msgs/msg/Imu"

    # the files name the ROS topics that bridge creates
    ros_names = {"/" + e["ros_topic_name"].strip("/") for e in entries}
    slam = load_yaml(out / "laser/slam_toolbox.yaml")["slam_toolbox"]["ros__parameters"]
    assert slam["scan_topic"] == "/scan" and slam["scan_topic"] in ros_names
    kalibr = load_yaml(out / "rgbd/kalibr.yaml")["cam0"]
    assert kalibr["rostopic"] == "/rgbd/image_raw" and kalibr["rostopic"] in ros_names
    assert kalibr["intrinsics"][2:] == [320.0, 240.0]
    d2l = load_yaml(out / "rgbd/depthimage_to_laserscan.yaml")["depthimage_to_laserscan"]
    assert d2l["ros__parameters"]["output_frame"] == "rgbd_link"
    assert (d2l["ros__parameters"]["range_min"], d2l["ros__parameters"]["range_max"]) == (0.3, 6.0)
    assert load_yaml(out / "laser/scan.yaml")["header"]["frame_id"] == "laser_link"
    v1 = load_opencv(out / "rgbd/orbslam3_rgbd_v1.yaml")
    assert v1["Camera.fps"] == 15 and type(v1["Camera.fps"]) is int


def test_gz_sensor_without_topic_is_reported(tmp_path: Path) -> None:
    text = gz_robot().replace("<topic>imu</topic>", "")
    path = tmp_path / "r.urdf"
    path.write_text(text)
    out = tmp_path / "out"
    result = run("export", path, "--out", out)
    assert result.exit_code == 1
    assert "imu" in result.stderr and "<topic>" in result.stderr
    entries = load_yaml(out / "bridge.yaml")
    assert "scan" in {e["gz_topic_name"] for e in entries}  # the others are still bridged


def test_gz_depth_camera_has_no_colour_files(tmp_path: Path) -> None:
    sensor = (
        '<sensor name="depth" type="depth_camera"><update_rate>30</update_rate>'
        f"<topic>depth</topic>{_camera_block()}</sensor>"
    )
    path = tmp_path / "r.urdf"
    path.write_text(robot(mounted("depth", sensor), extra=GZ_SYSTEM))
    out = tmp_path / "out"
    result = run("export", path, "--out", out, "--target", "harmonic")
    assert result.exit_code == 0, result.stderr
    names = {p.name for p in (out / "depth").iterdir()}
    assert "depthimage_to_laserscan.yaml" in names and "camera_info.yaml" in names
    assert not {"orbslam3.yaml", "orbslam3_rgbd.yaml", "kalibr.yaml"} & names
    assert "depth image only" in result.stderr


def test_multicamera_exports_each_camera(tmp_path: Path) -> None:
    right = _camera_block(name="right").replace(">", "><pose>0 -0.07 0 0 0 0</pose>", 1)
    cams = _camera_block(name="left") + right
    sensor = (
        f'<sensor name="stereo" type="multicamera"><update_rate>20</update_rate>{cams}'
        '<plugin name="stereo_controller" filename="libgazebo_ros_camera.so">'
        "<hack_baseline>0.07</hack_baseline></plugin></sensor>"
    )
    path = tmp_path / "r.urdf"
    path.write_text(robot(mounted("stereo", sensor)))
    result = run("intrinsics", path)
    ids = [c["camera"] for c in json.loads(result.stdout)["cameras"]]
    assert ids == ["stereo/left", "stereo/right"]
    one_line_error(run("intrinsics", path, "--sensor", "stereo", "--format", "opencv"))
    right = run("intrinsics", path, "--sensor", "stereo/right", "--format", "kalibr")
    assert yaml.safe_load(right.stdout)["cam0"]["rostopic"] == "/stereo/right/image_raw"
    out = tmp_path / "out"
    assert run("export", path, "--out", out).exit_code == 0
    assert (out / "stereo/left/orbslam3.yaml").is_file()
    assert (out / "stereo/right/camera_info.yaml").is_file()
    assert (out / "stereo/sensor.json").is_file()


# --------------------------------------------------------------------------- errors


def test_unknown_sensor_names_the_cameras(classic_file: Path) -> None:
    message = one_line_error(run("intrinsics", classic_file, "--sensor", "nope"))
    assert "'nope'" in message and "front_camera" in message and "depth" in message


def test_robot_without_camera(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(robot(mounted("laser", classic_lidar(), optical=False)))
    message = one_line_error(run("intrinsics", path))
    assert "no camera" in message


@pytest.mark.parametrize("fmt", ["camera-info", "orbslam3", "orbslam3-v1", "kalibr", "opencv"])
def test_single_document_format_needs_sensor(classic_file: Path, fmt: str) -> None:
    message = one_line_error(run("intrinsics", classic_file, "--format", fmt))
    assert "--sensor" in message and "front_camera" in message and "depth" in message


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--format", "yaml"], "--format"),
        (["--convention", "pinhole"], "--convention"),
        (["--target", "gazebo11"], "unknown target"),
        (["--arg", "novalue"], "NAME:=VALUE"),
    ],
)
def test_bad_options(classic_file: Path, args: list[str], needle: str) -> None:
    assert needle in one_line_error(run("intrinsics", classic_file, *args))


def test_unreadable_robot(tmp_path: Path) -> None:
    path = tmp_path / "broken.urdf"
    path.write_text("<robot name='x'><link name='a'></robot>")
    one_line_error(run("intrinsics", path))
    one_line_error(run("export", path, "--out", tmp_path / "out"))
    assert not (tmp_path / "out").exists()
    one_line_error(run("intrinsics", tmp_path / "missing.urdf"))


def test_bad_camera_is_an_input_error(tmp_path: Path) -> None:
    sensor = classic_camera("cam").replace("<horizontal_fov>2.0<", "<horizontal_fov>3.5<")
    path = tmp_path / "r.urdf"
    path.write_text(robot(mounted("cam", sensor), mounted("laser", classic_lidar(), optical=False)))
    assert "hfov" in one_line_error(run("intrinsics", path))
    out = tmp_path / "out"
    result = run("export", path, "--out", out)
    assert result.exit_code == 1 and "hfov" in result.stderr
    assert (out / "laser/scan.yaml").is_file() and not (out / "cam/camera_info.yaml").exists()


def test_non_empty_out_is_refused_unless_force(classic_file: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    message = one_line_error(run("export", classic_file, "--out", out))
    assert "not empty" in message and "--force" in message
    assert [p.name for p in out.iterdir()] == ["keep.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["classic.urdf", "out"]

    result = run("export", classic_file, "--out", out, "--force")
    assert result.exit_code == 0, result.stderr
    assert not (out / "keep.txt").exists() and (out / "laser/scan.yaml").is_file()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["classic.urdf", "out"]


def test_force_never_replaces_the_folder_holding_the_robot(classic_file: Path) -> None:
    message = one_line_error(run("export", classic_file, "--out", classic_file.parent, "--force"))
    assert "classic.urdf" in message
    assert classic_file.is_file()


def test_force_never_replaces_a_folder_holding_an_include(tmp_path: Path) -> None:
    parts = tmp_path / "parts"
    parts.mkdir()
    (parts / "cam.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        + mounted("cam", classic_camera("cam"))
        + "</robot>"
    )
    main = tmp_path / "robot.urdf.xacro"
    main.write_text(
        robot('<xacro:include filename="parts/cam.xacro"/>').replace(
            "<robot ", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" ', 1
        )
    )
    message = one_line_error(run("export", main, "--out", parts, "--force"))
    assert "holds cam.xacro" in message
    assert (parts / "cam.xacro").is_file()


def test_empty_out_is_used_and_out_file_refused(classic_file: Path, tmp_path: Path) -> None:
    out = tmp_path / "empty"
    out.mkdir()
    assert run("export", classic_file, "--out", out).exit_code == 0
    assert (out / "front_camera/camera_info.yaml").is_file()
    one_line_error(run("export", classic_file, "--out", classic_file))


def test_out_must_not_be_the_current_folder(
    classic_file: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    assert "subfolder" in one_line_error(run("export", classic_file, "--out", "."))
    assert list(work.iterdir()) == []
    result = run("export", classic_file, "--out", "exp")  # the paths are printed as given
    assert result.exit_code == 0, result.stderr
    assert "exp/front_camera/camera_info.yaml" in result.stdout.split()


def test_format_limits_are_notes_not_failures(tmp_path: Path) -> None:
    distortion = "<distortion><k1>-0.2</k1><k2>0.05</k2><k3>0.01</k3></distortion>"
    sensor = classic_camera("cam").replace("</camera>", distortion + "</camera>")
    path = tmp_path / "r.urdf"
    path.write_text(robot(mounted("cam", sensor)))
    out = tmp_path / "out"
    result = run("export", path, "--out", out)
    assert result.exit_code == 0, result.stderr
    assert not (out / "cam/kalibr.yaml").exists()
    assert "kalibr.yaml not written" in result.stderr and "k3" in result.stderr
    info = load_yaml(out / "cam/camera_info.yaml")
    assert info["distortion_coefficients"]["data"] == [-0.2, 0.05, 0.0, 0.0, 0.01]
    old = load_opencv(out / "cam/orbslam3.yaml")
    assert (old["Camera.k1"], old["Camera.k3"]) == (-0.2, 0.01)


def test_cli_does_not_import_pybullet() -> None:
    code = (
        "import sys, sensorkit.cli, sensorkit.cli.export, sensorkit.describe.sensorinfo;"
        "print([m for m in ('pybullet', 'trimesh', 'sensorkit.render') if m in sys.modules])"
    )
    res = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=False
    )
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip() == "[]", res.stdout


def test_golden_value_is_the_formula() -> None:
    assert 640 / (2 * math.tan(1.0)) == GOLDEN_FX
