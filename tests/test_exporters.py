"""Every export parsed back: keys, number kinds (ints are ints, reals are reals), values."""

from __future__ import annotations

import json
import math
import re
from typing import Any

import numpy as np
import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from sensorkit.describe.bridge import BridgeEntry, bridge_types, sensor_bridge_entries
from sensorkit.describe.intrinsics import (
    Intrinsics,
    InvalidValue,
    LaserScanParams,
    camera_intrinsics,
    laser_scan,
)
from sensorkit.exporters import (
    OrbExtractorSettings,
    amcl_yaml,
    bridge_yaml,
    camera_dict,
    camera_info_yaml,
    depthimage_to_laserscan_remappings,
    depthimage_to_laserscan_yaml,
    kalibr_camchain_yaml,
    laser_scan_dict,
    nav2_obstacle_layer_yaml,
    opencv_yaml,
    orbslam3_yaml,
    scan_yaml,
    slam_toolbox_yaml,
    to_json,
)
from sensorkit.exporters import _text as text

DIST = (-0.25, 0.12, 1e-05, -0.0003, 0.0)


@pytest.fixture
def cam() -> Intrinsics:
    return camera_intrinsics(640, 480, 2.0, "classic", distortion=DIST)


@pytest.fixture
def plain_cam() -> Intrinsics:
    return camera_intrinsics(640, 480, 2.0, "classic")


@pytest.fixture
def scan() -> LaserScanParams:
    return laser_scan(360, 1, -math.pi, math.pi, 0.12, 3.5)


# --------------------------------------------------------------------------- helpers


def _construct_matrix(loader: Any, node: Any) -> dict[str, Any]:
    mapping: dict[str, Any] = loader.construct_mapping(node, deep=True)
    return mapping


# A SafeLoader that also understands OpenCV's ``!!opencv-matrix`` tag.
OpenCVLoader: Any = type("OpenCVLoader", (yaml.SafeLoader,), {})
OpenCVLoader.add_constructor("tag:yaml.org,2002:opencv-matrix", _construct_matrix)


def load_opencv(doc: str) -> dict[str, Any]:
    """Check the OpenCV header, then parse the rest as YAML."""
    first, rest = doc.split("\n", 1)
    assert first == "%YAML:1.0"
    data = yaml.load(rest, Loader=OpenCVLoader)
    assert isinstance(data, dict)
    return data


def raw_values(doc: str) -> dict[str, str]:
    """The literal text after ``key:`` for every top-level key."""
    out: dict[str, str] = {}
    for line in doc.splitlines():
        match = re.match(r"^([A-Za-z0-9_.]+):\s*(.*)$", line)
        if match:
            assert match.group(1) not in out, f"duplicate key {match.group(1)}"
            out[match.group(1)] = match.group(2)
    return out


REAL_LITERAL = re.compile(r"^-?[0-9]+\.[0-9]*(e[+-][0-9]+)?$")
INT_LITERAL = re.compile(r"^-?[0-9]+$")


def assert_real(raw: str, key: str) -> None:
    assert REAL_LITERAL.match(raw), f"{key} must be a real literal, got {raw!r}"


def assert_int(raw: str, key: str) -> None:
    assert INT_LITERAL.match(raw), f"{key} must be an int literal, got {raw!r}"


def assert_floats(values: list[Any]) -> None:
    assert all(type(v) is float for v in values), values


# --------------------------------------------------------------------------- scalars


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_real_literal_round_trips_exactly(x: float) -> None:
    lit = text.real(x)
    assert REAL_LITERAL.match(lit), lit
    assert float(lit) == x
    loaded = yaml.safe_load(f"v: {lit}")["v"]
    assert type(loaded) is float
    assert loaded == x


def test_real_literal_details() -> None:
    assert text.real(500) == "500.0"
    assert text.real(-0.0) == "0.0"
    assert text.real(1e-05) == "1.0e-05"
    assert text.real(1e16) == "1.0e+16"
    assert text.real(np.float32(0.5)) == "0.5"
    for bad in (float("nan"), float("inf"), True, "1.0"):
        with pytest.raises(InvalidValue):
            text.real(bad)


def test_integer_literal_is_strict() -> None:
    assert text.integer(30) == "30"
    assert text.integer(np.int64(7)) == "7"
    for bad in (30.0, True, "30"):
        with pytest.raises(InvalidValue):
            text.integer(bad)


@pytest.mark.parametrize(
    "value", ["camera", "/scan", "a b", "true", "on", "x: y", "#c", "~", "1.0"]
)
def test_strings_load_back_as_the_same_string(value: str) -> None:
    assert yaml.safe_load(f"v: {text.string(value)}")["v"] == value


# --------------------------------------------------------------------------- camera_info


def test_camera_info_yaml(cam: Intrinsics) -> None:
    doc = camera_info_yaml(cam, camera_name="front_camera")
    data = yaml.safe_load(doc)
    assert list(data) == [
        "image_width",
        "image_height",
        "camera_name",
        "camera_matrix",
        "distortion_model",
        "distortion_coefficients",
        "rectification_matrix",
        "projection_matrix",
    ]
    assert type(data["image_width"]) is int
    assert data["image_width"] == 640
    assert type(data["image_height"]) is int
    assert data["image_height"] == 480
    assert data["camera_name"] == "front_camera"
    assert data["distortion_model"] == "plumb_bob"
    shapes = {
        "camera_matrix": (3, 3),
        "distortion_coefficients": (1, 5),
        "rectification_matrix": (3, 3),
        "projection_matrix": (3, 4),
    }
    for key, (rows, cols) in shapes.items():
        block = data[key]
        assert list(block) == ["rows", "cols", "data"]
        assert (block["rows"], block["cols"]) == (rows, cols)
        assert type(block["rows"]) is int
        assert type(block["cols"]) is int
        assert len(block["data"]) == rows * cols
        assert_floats(block["data"])
    assert data["camera_matrix"]["data"] == cam.K.flatten().tolist()
    assert data["distortion_coefficients"]["data"] == list(DIST)
    assert data["rectification_matrix"]["data"] == np.eye(3).flatten().tolist()
    assert data["projection_matrix"]["data"] == cam.P.flatten().tolist()
    assert data["camera_matrix"]["data"][0] == 205.46963709898583


def test_camera_info_hack_baseline_in_projection() -> None:
    right = camera_intrinsics(640, 480, 2.0, "classic", hack_baseline=0.07)
    data = yaml.safe_load(camera_info_yaml(right))
    assert data["projection_matrix"]["data"][3] == -205.46963709898583 * 0.07


def test_camera_info_quotes_awkward_names(plain_cam: Intrinsics) -> None:
    data = yaml.safe_load(camera_info_yaml(plain_cam, camera_name="yes"))
    assert data["camera_name"] == "yes"
    with pytest.raises(InvalidValue, match="camera_name"):
        camera_info_yaml(plain_cam, camera_name="")


# --------------------------------------------------------------------------- ORB-SLAM3

V1_FLOAT_KEYS = [
    "Camera1.fx",
    "Camera1.fy",
    "Camera1.cx",
    "Camera1.cy",
    "ORBextractor.scaleFactor",
    "Viewer.KeyFrameSize",
    "Viewer.KeyFrameLineWidth",
    "Viewer.GraphLineWidth",
    "Viewer.PointSize",
    "Viewer.CameraSize",
    "Viewer.CameraLineWidth",
    "Viewer.ViewpointX",
    "Viewer.ViewpointY",
    "Viewer.ViewpointZ",
    "Viewer.ViewpointF",
]
V1_INT_KEYS = [
    "Camera.width",
    "Camera.height",
    "Camera.fps",
    "Camera.RGB",
    "ORBextractor.nFeatures",
    "ORBextractor.nLevels",
    "ORBextractor.iniThFAST",
    "ORBextractor.minThFAST",
]
OLD_FLOAT_KEYS = [
    "Camera.fx",
    "Camera.fy",
    "Camera.cx",
    "Camera.cy",
    "Camera.k1",
    "Camera.k2",
    "Camera.p1",
    "Camera.p2",
    "Camera.k3",
    *V1_FLOAT_KEYS[4:],
]


def _check_orb(doc: str, float_keys: list[str], int_keys: list[str]) -> dict[str, Any]:
    data = load_opencv(doc)
    raw = raw_values(doc)
    for key in float_keys:
        assert key in raw, key
        assert_real(raw[key], key)
        assert type(data[key]) is float, key
    for key in int_keys:
        assert key in raw, key
        assert_int(raw[key], key)
        assert type(data[key]) is int, key
    return data


@pytest.mark.parametrize("mode", ["monocular", "rgbd", "stereo"])
def test_orbslam3_v1(mode: str, plain_cam: Intrinsics) -> None:
    doc = orbslam3_yaml(plain_cam, mode=mode, fps=30, baseline=None if mode != "stereo" else 0.12)  # type: ignore[arg-type]
    floats = list(V1_FLOAT_KEYS)
    if mode != "monocular":
        floats += ["Stereo.b", "Stereo.ThDepth"]
    if mode == "rgbd":
        floats.append("RGBD.DepthMapFactor")
    data = _check_orb(doc, floats, V1_INT_KEYS)
    raw = raw_values(doc)
    assert raw["File.version"] == '"1.0"'
    assert data["File.version"] == "1.0"
    assert raw["Camera.fps"] == "30"
    assert data["Camera.type"] == ("Rectified" if mode == "stereo" else "PinHole")
    assert data["Camera1.fx"] == plain_cam.fx
    assert data["Camera1.cx"] == plain_cam.cx
    assert (data["Camera.width"], data["Camera.height"]) == (640, 480)
    assert data["Camera.RGB"] == 1
    assert not any(k.startswith("Camera.f") and k != "Camera.fps" for k in data)
    assert "Camera1.k1" not in data  # no distortion: the optional keys are left out
    if mode == "rgbd":
        assert data["RGBD.DepthMapFactor"] == 1.0
        assert data["Stereo.b"] == 0.08
    if mode == "stereo":
        assert data["Stereo.b"] == 0.12
        assert "RGBD.DepthMapFactor" not in data
    if mode == "monocular":
        assert not any(k.startswith(("Stereo.", "RGBD.")) for k in data)


@pytest.mark.parametrize("mode", ["monocular", "rgbd", "stereo"])
def test_orbslam3_old_format(mode: str, plain_cam: Intrinsics) -> None:
    doc = orbslam3_yaml(
        plain_cam,
        mode=mode,  # type: ignore[arg-type]
        fps=30,
        version="old",
        baseline=0.1 if mode == "stereo" else None,
    )
    floats = list(OLD_FLOAT_KEYS)
    if mode != "monocular":
        floats += ["Camera.bf", "ThDepth"]
    if mode == "rgbd":
        floats.append("DepthMapFactor")
    data = _check_orb(doc, floats, V1_INT_KEYS)
    assert "File.version" not in data
    assert data["Camera.type"] == "PinHole"
    assert data["Camera.fx"] == plain_cam.fx
    raw = raw_values(doc)
    assert raw["Camera.k1"] == "0.0"  # a real, never the int 0 ParseCamParamFile refuses
    if mode == "stereo":
        assert data["Camera.bf"] == 0.1 * plain_cam.fx
    if mode == "rgbd":
        assert data["Camera.bf"] == 0.08 * plain_cam.fx
        assert data["DepthMapFactor"] == 1.0


def test_orbslam3_v1_distortion_and_reals(cam: Intrinsics) -> None:
    doc = orbslam3_yaml(cam, mode="monocular", fps=30.0, rgb=False)
    keys = [f"Camera1.{k}" for k in ("k1", "k2", "p1", "p2", "k3")]
    data = _check_orb(doc, [*V1_FLOAT_KEYS, *keys], V1_INT_KEYS)
    assert [data[k] for k in keys] == list(DIST)
    assert raw_values(doc)["Camera1.p1"] == "1.0e-05"
    assert raw_values(doc)["Camera.fps"] == "30"
    assert data["Camera.RGB"] == 0


def test_orbslam3_round_focal_length_is_still_a_real() -> None:
    intr = Intrinsics(640, 480, 500.0, 500.0, 320.0, 240.0)
    raw = raw_values(orbslam3_yaml(intr, mode="monocular", fps=15, version="old"))
    assert raw["Camera.fx"] == "500.0"
    assert raw["Camera.cx"] == "320.0"


def test_orbslam3_stereo_baseline_from_right_camera() -> None:
    right = camera_intrinsics(640, 480, 2.0, "classic", hack_baseline=0.07)
    data = load_opencv(orbslam3_yaml(right, mode="stereo", fps=30))
    assert data["Stereo.b"] == pytest.approx(0.07, rel=1e-15)


def test_orbslam3_custom_extractor(plain_cam: Intrinsics) -> None:
    orb = OrbExtractorSettings(n_features=1500, scale_factor=1.25)
    data = load_opencv(orbslam3_yaml(plain_cam, mode="monocular", fps=30, orb=orb))
    assert data["ORBextractor.nFeatures"] == 1500
    assert data["ORBextractor.scaleFactor"] == 1.25


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"mode": "monocular", "fps": 29.97}, "fps"),
        ({"mode": "monocular", "fps": 0}, "fps"),
        ({"mode": "monocular", "fps": True}, "fps"),
        ({"mode": "monocular", "fps": 30, "baseline": 0.1}, "baseline"),
        ({"mode": "stereo", "fps": 30}, "baseline"),
        ({"mode": "stereo", "fps": 30, "baseline": -0.1}, "baseline"),
        ({"mode": "rgbd", "fps": 30, "depth_map_factor": 0.0}, "depth_map_factor"),
        ({"mode": "monocular", "fps": 30, "depth_map_factor": 1000.0}, "depth_map_factor"),
        ({"mode": "rgbd", "fps": 30, "th_depth": float("nan")}, "th_depth"),
        ({"mode": "fisheye", "fps": 30}, "mode"),
        ({"mode": "monocular", "fps": 30, "version": "2.0"}, "version"),
        ({"mode": "monocular", "fps": 30, "orb": OrbExtractorSettings(n_levels=0)}, "n_levels"),
        (
            {"mode": "monocular", "fps": 30, "orb": OrbExtractorSettings(scale_factor=1.0)},
            "scale_factor",
        ),
    ],
)
def test_orbslam3_refuses_bad_values(
    plain_cam: Intrinsics, kwargs: dict[str, Any], match: str
) -> None:
    with pytest.raises(ValueError, match=match):
        orbslam3_yaml(plain_cam, **kwargs)


def test_orbslam3_refuses_distorted_stereo_and_skew(cam: Intrinsics) -> None:
    with pytest.raises(InvalidValue, match="distortion"):
        orbslam3_yaml(cam, mode="stereo", fps=30, baseline=0.1)
    skewed = Intrinsics(640, 480, 500.0, 500.0, 320.0, 240.0, skew=1.0)
    with pytest.raises(InvalidValue, match="skew"):
        orbslam3_yaml(skewed, mode="monocular", fps=30)


# --------------------------------------------------------------------------- OpenCV


def test_opencv_yaml(cam: Intrinsics) -> None:
    doc = opencv_yaml(cam)
    assert doc.startswith("%YAML:1.0\n---\n")
    data = load_opencv(doc)
    assert list(data) == ["image_width", "image_height", "camera_matrix", "distortion_coefficients"]
    assert type(data["image_width"]) is int
    assert type(data["image_height"]) is int
    assert "!!opencv-matrix" in doc
    for key, shape in (("camera_matrix", (3, 3)), ("distortion_coefficients", (1, 5))):
        block = data[key]
        assert (block["rows"], block["cols"]) == shape
        assert block["dt"] == "d"
        assert len(block["data"]) == shape[0] * shape[1]
        assert_floats(block["data"])
    assert data["camera_matrix"]["data"] == cam.K.flatten().tolist()
    assert data["distortion_coefficients"]["data"] == list(DIST)


# --------------------------------------------------------------------------- Kalibr


def test_kalibr_camchain(cam: Intrinsics) -> None:
    T = np.eye(4)
    T[:3, 3] = [0.05, -0.01, 0.02]
    data = yaml.safe_load(kalibr_camchain_yaml(cam, rostopic="/cam0/image_raw", T_cam_imu=T))
    assert list(data) == ["cam0"]
    cam0 = data["cam0"]
    assert cam0["camera_model"] == "pinhole"
    assert cam0["intrinsics"] == [cam.fx, cam.fy, cam.cx, cam.cy]
    assert_floats(cam0["intrinsics"])
    assert cam0["distortion_model"] == "radtan"
    assert cam0["distortion_coeffs"] == list(DIST[:4])
    assert len(cam0["distortion_coeffs"]) == 4
    assert_floats(cam0["distortion_coeffs"])
    assert cam0["resolution"] == [640, 480]
    assert all(type(v) is int for v in cam0["resolution"])
    assert cam0["rostopic"] == "/cam0/image_raw"
    assert np.array_equal(np.array(cam0["T_cam_imu"]), T)
    for row in cam0["T_cam_imu"]:
        assert_floats(row)


def test_kalibr_without_imu(plain_cam: Intrinsics) -> None:
    data = yaml.safe_load(kalibr_camchain_yaml(plain_cam, rostopic="/c", camera_id="cam1"))
    assert "T_cam_imu" not in data["cam1"]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"T_cam_imu": np.eye(3)}, "4x4"),
        ({"T_cam_imu": np.diag([1.0, 1.0, 1.0, 2.0])}, "last row"),
        ({"T_cam_imu": np.diag([2.0, 1.0, 1.0, 1.0])}, "rotation"),
        ({"T_cam_imu": np.diag([-1.0, 1.0, 1.0, 1.0])}, "rotation"),
        ({"camera_id": "left"}, "camera_id"),
        ({"rostopic": ""}, "rostopic"),
    ],
)
def test_kalibr_refuses(plain_cam: Intrinsics, kwargs: dict[str, Any], match: str) -> None:
    args: dict[str, Any] = {"rostopic": "/cam0/image_raw", **kwargs}
    with pytest.raises(InvalidValue, match=match):
        kalibr_camchain_yaml(plain_cam, **args)


def test_kalibr_refuses_k3_and_skew() -> None:
    k3 = camera_intrinsics(640, 480, 2.0, "classic", distortion=(0.1, 0.0, 0.0, 0.0, 0.01))
    with pytest.raises(InvalidValue, match="k3"):
        kalibr_camchain_yaml(k3, rostopic="/c")
    skewed = Intrinsics(640, 480, 500.0, 500.0, 320.0, 240.0, skew=0.5)
    with pytest.raises(InvalidValue, match="skew"):
        kalibr_camchain_yaml(skewed, rostopic="/c")


# --------------------------------------------------------------------------- JSON


def test_json_round_trip(cam: Intrinsics, scan: LaserScanParams) -> None:
    data = camera_dict(cam, camera_name="front", frame_id="front_optical_frame")
    back = json.loads(to_json(data))
    assert back == data
    assert back["fx"] == cam.fx
    assert back["K"] == cam.K.tolist()
    assert back["P"] == cam.P.tolist()
    assert back["distortion"] == list(DIST)
    assert back["hfov"] == cam.hfov
    assert back["camera_name"] == "front"
    scan_back = json.loads(to_json(laser_scan_dict(scan, topic="/scan")))
    assert scan_back["samples"] == 360
    assert scan_back["angle_increment"] == scan.angle_increment
    assert scan_back["topic"] == "/scan"


def test_json_refuses_nan_and_clashes(cam: Intrinsics) -> None:
    with pytest.raises(InvalidValue):
        to_json(camera_dict(cam, note=float("nan")))
    with pytest.raises(InvalidValue, match="fx"):
        camera_dict(cam, fx=1.0)


# --------------------------------------------------------------------------- lidar


def test_scan_yaml(scan: LaserScanParams) -> None:
    data = yaml.safe_load(scan_yaml(scan, frame_id="base_scan"))
    assert data["header"] == {"frame_id": "base_scan"}
    keys = [
        "angle_min",
        "angle_max",
        "angle_increment",
        "time_increment",
        "scan_time",
        "range_min",
        "range_max",
    ]
    for key in keys:
        assert type(data[key]) is float, key
        assert data[key] == getattr(scan, key), key
    assert data["angle_increment"] == 2 * math.pi / 359
    assert "header" not in yaml.safe_load(scan_yaml(scan))


def test_slam_toolbox_yaml(scan: LaserScanParams) -> None:
    params = yaml.safe_load(slam_toolbox_yaml(scan))["slam_toolbox"]["ros__parameters"]
    assert params == {"scan_topic": "/scan", "max_laser_range": 3.5}
    assert type(params["max_laser_range"]) is float
    shorter = yaml.safe_load(slam_toolbox_yaml(scan, max_laser_range=3, scan_topic="/lidar"))
    assert shorter["slam_toolbox"]["ros__parameters"]["max_laser_range"] == 3.0
    with pytest.raises(InvalidValue, match="max_laser_range"):
        slam_toolbox_yaml(scan, max_laser_range=12.0)


def test_nav2_obstacle_layer_yaml(scan: LaserScanParams) -> None:
    data = yaml.safe_load(nav2_obstacle_layer_yaml(scan, topic="/scan"))
    layer = data["local_costmap"]["local_costmap"]["ros__parameters"]["obstacle_layer"]
    assert layer["plugin"] == "nav2_costmap_2d::ObstacleLayer"
    assert layer["enabled"] is True
    assert layer["observation_sources"] == "scan"
    source = layer["scan"]
    assert source["topic"] == "/scan"
    assert source["data_type"] == "LaserScan"
    assert source["marking"] is True
    assert source["clearing"] is True
    assert source["inf_is_valid"] is True
    for key in ("obstacle_max_range", "raytrace_max_range", "max_obstacle_height"):
        assert type(source[key]) is float, key
    assert source["obstacle_max_range"] == 2.5
    assert source["raytrace_max_range"] == 3.0
    assert source["obstacle_max_range"] <= scan.range_max
    assert source["raytrace_max_range"] <= scan.range_max


def test_nav2_defaults_clamp_to_a_short_lidar() -> None:
    short = laser_scan(180, 1, -1.5, 1.5, 0.05, 2.0)
    source = yaml.safe_load(nav2_obstacle_layer_yaml(short, costmap="global_costmap"))[
        "global_costmap"
    ]["global_costmap"]["ros__parameters"]["obstacle_layer"]["scan"]
    assert source["obstacle_max_range"] == 2.0
    assert source["raytrace_max_range"] == 2.0
    with pytest.raises(InvalidValue, match="raytrace_max_range"):
        nav2_obstacle_layer_yaml(short, raytrace_max_range=2.5)
    with pytest.raises(InvalidValue, match="obstacle_max_range"):
        nav2_obstacle_layer_yaml(short, obstacle_max_range=-1.0)


def test_amcl_yaml(scan: LaserScanParams) -> None:
    params = yaml.safe_load(amcl_yaml(scan))["amcl"]["ros__parameters"]
    assert params == {"scan_topic": "scan", "laser_min_range": 0.12, "laser_max_range": 3.5}
    assert type(params["laser_min_range"]) is float
    with pytest.raises(InvalidValue, match="laser_max_range"):
        amcl_yaml(scan, laser_max_range=4.0)
    with pytest.raises(InvalidValue, match="laser_min_range"):
        amcl_yaml(scan, laser_min_range=3.5)


# --------------------------------------------------------------------------- depth -> scan


def test_depthimage_to_laserscan_yaml(plain_cam: Intrinsics) -> None:
    doc = depthimage_to_laserscan_yaml(
        plain_cam,
        depth_topic="/cam/depth/image_raw",
        depth_camera_info_topic="/cam/depth/camera_info",
        output_frame="cam_link",
        range_min=0.4,
        range_max=8,
        fps=20,
    )
    assert "depth:=/cam/depth/image_raw" in doc
    assert "depth_camera_info:=/cam/depth/camera_info" in doc
    params = yaml.safe_load(doc)["depthimage_to_laserscan"]["ros__parameters"]
    assert params == {
        "scan_time": 0.05,
        "range_min": 0.4,
        "range_max": 8.0,
        "scan_height": 1,
        "output_frame": "cam_link",
    }
    assert type(params["scan_height"]) is int
    assert type(params["range_max"]) is float


def test_depthimage_to_laserscan_remappings() -> None:
    assert depthimage_to_laserscan_remappings(
        depth_topic="/d", depth_camera_info_topic="/d_info", scan_topic="/scan"
    ) == {"depth": "/d", "depth_camera_info": "/d_info", "scan": "/scan"}


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"output_frame": "cam_optical_frame"}, "output_frame"),
        ({"output_frame": "cam_optical"}, "output_frame"),
        ({"scan_height": 0}, "scan_height"),
        ({"scan_height": 481}, "scan_height"),
        ({"scan_height": 2.0}, "scan_height"),
        ({"range_min": 9.0}, "range_min"),
        ({"range_max": float("inf")}, "range_max"),
        ({"fps": 0}, "fps"),
    ],
)
def test_depthimage_to_laserscan_refuses(
    plain_cam: Intrinsics, kwargs: dict[str, Any], match: str
) -> None:
    args: dict[str, Any] = {
        "depth_topic": "/d",
        "depth_camera_info_topic": "/i",
        "output_frame": "cam_link",
        "range_min": 0.4,
        "range_max": 8.0,
        **kwargs,
    }
    with pytest.raises(InvalidValue, match=match):
        depthimage_to_laserscan_yaml(plain_cam, **args)


# --------------------------------------------------------------------------- bridge


def test_bridge_yaml_round_trip() -> None:
    entries = [
        BridgeEntry(
            "/scan", "/lidar", "sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan", "GZ_TO_ROS"
        ),
        ("/imu", "/imu", "sensor_msgs/msg/Imu", "gz.msgs.IMU", "GZ_TO_ROS"),
    ]
    data = yaml.safe_load(bridge_yaml(entries))
    assert isinstance(data, list)
    assert len(data) == 2
    for item in data:
        assert list(item) == [
            "ros_topic_name",
            "gz_topic_name",
            "ros_type_name",
            "gz_type_name",
            "direction",
        ]
    assert data[0] == {
        "ros_topic_name": "/scan",
        "gz_topic_name": "/lidar",
        "ros_type_name": "sensor_msgs/msg/LaserScan",
        "gz_type_name": "gz.msgs.LaserScan",
        "direction": "GZ_TO_ROS",
    }


def test_bridge_yaml_refuses_nothing_and_nonsense() -> None:
    with pytest.raises(InvalidValue, match="nothing to bridge"):
        bridge_yaml([])
    with pytest.raises(InvalidValue, match="direction"):
        bridge_yaml([("/a", "/a", "sensor_msgs/msg/Imu", "gz.msgs.IMU", "BOTH")])
    with pytest.raises(InvalidValue, match="twice"):
        bridge_yaml([("/a", "/a", "t", "g", "GZ_TO_ROS"), ("/a", "/b", "t", "g", "GZ_TO_ROS")])
    with pytest.raises(InvalidValue, match="gz_topic_name"):
        bridge_yaml([("/a", "", "t", "g", "GZ_TO_ROS")])


@pytest.mark.parametrize(
    ("kind", "ros_type", "gz_name"),
    [
        ("image", "sensor_msgs/msg/Image", "Image"),
        ("camera_info", "sensor_msgs/msg/CameraInfo", "CameraInfo"),
        ("laser_scan", "sensor_msgs/msg/LaserScan", "LaserScan"),
        ("points", "sensor_msgs/msg/PointCloud2", "PointCloudPacked"),
        ("imu", "sensor_msgs/msg/Imu", "IMU"),
    ],
)
def test_bridge_types(kind: str, ros_type: str, gz_name: str) -> None:
    assert bridge_types(kind, "harmonic") == (ros_type, f"gz.msgs.{gz_name}")  # type: ignore[arg-type]
    assert bridge_types(kind, "Fortress") == (ros_type, f"ignition.msgs.{gz_name}")  # type: ignore[arg-type]


def test_bridge_types_refuses_unknowns() -> None:
    with pytest.raises(InvalidValue, match="kind"):
        bridge_types("odometry", "harmonic")  # type: ignore[arg-type]
    with pytest.raises(InvalidValue, match="gz_version"):
        bridge_types("image", "humble")


def test_sensor_bridge_entries_topics() -> None:
    cam = sensor_bridge_entries("camera", "/front/image", gz_version="harmonic")
    assert [e.gz_topic_name for e in cam] == ["/front/image", "/front/camera_info"]
    bare = sensor_bridge_entries("camera", "camera", gz_version="harmonic")
    assert [e.gz_topic_name for e in bare] == ["camera", "/camera_info"]
    rgbd = sensor_bridge_entries("rgbd_camera", "/rgbd", gz_version="jetty")
    assert [e.gz_topic_name for e in rgbd] == [
        "/rgbd/image",
        "/rgbd/depth_image",
        "/rgbd/points",
        "/rgbd/camera_info",
    ]
    lidar = sensor_bridge_entries("gpu_lidar", "/scan", gz_version="fortress")
    assert [(e.gz_topic_name, e.gz_type_name) for e in lidar] == [
        ("/scan", "ignition.msgs.LaserScan"),
        ("/scan/points", "ignition.msgs.PointCloudPacked"),
    ]
    depth = sensor_bridge_entries("depth_camera", "/d/depth", gz_version="harmonic")
    assert [e.gz_topic_name for e in depth] == ["/d/depth", "/d/camera_info", "/d/depth/points"]
    imu = sensor_bridge_entries("imu", "/imu", gz_version="harmonic")
    assert imu == [BridgeEntry("/imu", "/imu", "sensor_msgs/msg/Imu", "gz.msgs.IMU", "GZ_TO_ROS")]
    data = yaml.safe_load(bridge_yaml(cam + rgbd))
    assert all(item["direction"] == "GZ_TO_ROS" for item in data)
    with pytest.raises(InvalidValue, match="sensor_type"):
        sensor_bridge_entries("sonar", "/s", gz_version="harmonic")
