"""Stereo pairs exported as pairs, read back as their consumers read them.

Robots: sensorkit's own ``sensorkit_stereo_camera`` macro (with the ``sensorkit_imu`` macro)
expanded for Gazebo Classic and for Gazebo Sim, and a hand-written Classic ``multicamera``.

What each consumer reads, and where that is written down:

- Kalibr camchain: top-level keys are the cameras (``numCameras`` = ``len(self.data)``,
  ethz-asl/kalibr@aslam_offline_calibration/kalibr/python/kalibr_common/ConfigReader.py:753-754);
  ``cam1.T_cn_cnm1`` = T_c1_c0 "takes cam0 to cam1 coordinates" and ``T_cam_imu`` takes IMU
  coordinates to the camera's (github.com/ethz-asl/kalibr/wiki/yaml-formats; read at
  ConfigReader.py:688-718).
- ORB-SLAM3 v1.0: ``Camera.type "PinHole"``, ``Camera1.*``, ``Camera2.*``, the 4x4
  ``Stereo.T_c1_c2`` whose translation norm is the baseline, ``Stereo.ThDepth``
  (UZ-SLAMLab/ORB_SLAM3@src/Settings.cc:276-352), ``IMU.T_b_c1`` and ``IMU.*`` (:414-432),
  laid out as Examples/Stereo-Inertial/EuRoC.yaml:18-78; matrices ``dt: f``, since
  ``Converter::toSophus`` reads ``at<float>`` (src/Converter.cc:195-201, :300). Old format:
  ``Camera.bf`` (src/Tracking.cc:1133-1148), ``Tbc`` and an int ``IMU.Frequency``
  (:1301-1350).
- camera_info: the right camera of a horizontal pair has ``Tx = -fx' * B``, the left Tx = 0
  (ros2/common_interfaces@rolling:sensor_msgs/msg/CameraInfo.msg:93-98).
"""

from __future__ import annotations

import json
import math
import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from sensorkit.cli import app
from sensorkit.describe.intrinsics import Intrinsics, InvalidValue
from sensorkit.describe.sensorinfo import describe, load
from sensorkit.exporters import (
    OrbImuSettings,
    kalibr_stereo_camchain_yaml,
    orbslam3_stereo_yaml,
    stereo_camera_infos,
)
from sensorkit.exporters.opencv import opencv_matrix_lines

try:
    from macro_cases import MACROS_DIR, XACRO_NS
except ImportError:  # tests/ collected as a package
    from tests.macro_cases import MACROS_DIR, XACRO_NS

BASELINE = 0.12
WIDTH, HEIGHT, HFOV = 640, 480, 1.3962634  # the stereo macro's defaults
FX = WIDTH / (2.0 * math.tan(HFOV / 2.0))
IMU_RATE = 100.0  # the IMU macro's defaults
GYRO_STDDEV, ACCEL_STDDEV = 2e-4, 1.7e-2
EYE = 1e-9

BASE_LINK = (
    '<link name="base_link"><inertial><mass value="2.0"/>'
    '<inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial></link>'
)
INERTIA = (
    '<inertial><mass value="0.1"/>'
    '<inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>'
)
OPTICAL_RPY = "-1.5707963267948966 0 -1.5707963267948966"


# --------------------------------------------------------------------------- robots


def macro_robot(sim: str, *, imus: tuple[str, ...] = ("imu",), extra: str = "") -> str:
    """The stereo macro at (0.2, 0, 0.3) and IMU macros at (0, 0.1 k, 0.1), for ``sim``."""
    imu_calls = "\n".join(
        f'  <xacro:sensorkit_imu name="{name}" parent="base_link" sim="{sim}">'
        f'<origin xyz="0 {0.1 * k:.1f} 0.1" rpy="0 0 0"/></xacro:sensorkit_imu>'
        for k, name in enumerate(imus)
    )
    return f"""<?xml version="1.0"?>
<robot name="rig" xmlns:xacro="{XACRO_NS}">
  <xacro:include filename="{MACROS_DIR / "stereo_camera.urdf.xacro"}"/>
  <xacro:include filename="{MACROS_DIR / "imu.urdf.xacro"}"/>
  {BASE_LINK}
  <xacro:sensorkit_stereo_camera name="front" parent="base_link" baseline="{BASELINE}" sim="{sim}">
    <origin xyz="0.2 0 0.3" rpy="0 0 0"/>
  </xacro:sensorkit_stereo_camera>
{imu_calls}
{extra}
</robot>
"""


def _camera(name: str, pose: str = "", extra: str = "") -> str:
    return (
        f'<camera name="{name}">{pose}<horizontal_fov>{HFOV}</horizontal_fov>'
        f"<image><width>{WIDTH}</width><height>{HEIGHT}</height><format>R8G8B8</format></image>"
        f"<clip><near>0.05</near><far>20</far></clip>{extra}</camera>"
    )


def multicamera_robot(
    *,
    plugin: str = "libgazebo_ros_camera.so",
    params: str = f"<hack_baseline>{BASELINE}</hack_baseline>",
    right_pose: str = f"0 -{BASELINE} 0 0 0 0",
    left_extra: str = "",
    with_imu: bool = True,
) -> str:
    """A hand-written Classic multicamera "stereo": left at the link, right ``right_pose``."""
    cams = _camera("left", extra=left_extra) + _camera("right", f"<pose>{right_pose}</pose>")
    sensor = (
        f'<sensor name="stereo" type="multicamera"><update_rate>20</update_rate>{cams}'
        f'<plugin name="stereo_controller" filename="{plugin}">'
        f"<frame_name>stereo_optical_frame</frame_name><frameName>stereo_optical_frame</frameName>"
        f"{params}</plugin></sensor>"
    )
    imu = (
        '<sensor name="imu" type="imu"><update_rate>200</update_rate>'
        '<plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so">'
        "<ros><remapping>~/out:=imu</remapping></ros></plugin></sensor>"
    )
    return f"""<?xml version="1.0"?>
<robot name="multi">
  {BASE_LINK}
  <link name="stereo_link">{INERTIA}</link>
  <joint name="stereo_joint" type="fixed"><parent link="base_link"/><child link="stereo_link"/>
    <origin xyz="0.3 0 0.2" rpy="0 0 0"/></joint>
  <link name="stereo_optical_frame"/>
  <joint name="stereo_optical_joint" type="fixed"><parent link="stereo_link"/>
    <child link="stereo_optical_frame"/><origin xyz="0 0 0" rpy="{OPTICAL_RPY}"/></joint>
  <link name="imu_link">{INERTIA}</link>
  <joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_link"/>
    <origin xyz="0 0 0.05" rpy="0 0 0"/></joint>
  <gazebo reference="stereo_link">{sensor}</gazebo>
  <gazebo reference="imu_link">{imu if with_imu else ""}</gazebo>
</robot>
"""


def two_cameras_robot(
    right_params: str = "", *, names: tuple[str, str] = ("cam_a", "cam_b")
) -> str:
    """Two Classic camera sensors on one link, the second ``BASELINE`` to the right."""

    def sensor(name: str, y: float, params: str) -> str:
        return (
            f'<sensor name="{name}" type="camera"><update_rate>30</update_rate>'
            f"<pose>0 {y} 0 0 0 0</pose>{_camera(name)}"
            f'<plugin name="{name}_controller" filename="libgazebo_ros_camera.so">{params}</plugin>'
            "</sensor>"
        )

    a, b = names
    return f"""<?xml version="1.0"?>
<robot name="pair">
  {BASE_LINK}
  <link name="rig_link">{INERTIA}</link>
  <joint name="rig_joint" type="fixed"><parent link="base_link"/><child link="rig_link"/>
    <origin xyz="0.2 0 0.3" rpy="0 0 0"/></joint>
  <gazebo reference="rig_link">{sensor(a, BASELINE / 2, "")}{sensor(b, -BASELINE / 2, right_params)}</gazebo>
</robot>
"""


@pytest.fixture
def write(tmp_path: Path) -> Any:
    counter = iter(range(10**6))

    def put(text: str, suffix: str = ".urdf.xacro") -> Path:
        path = tmp_path / f"robot{next(counter)}{suffix}"
        path.write_text(text)
        return path

    return put


# --------------------------------------------------------------------------- readers


def run(*args: object) -> Any:
    result = CliRunner().invoke(app, [str(a) for a in args])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return result


def ok(*args: object) -> Any:
    result = run(*args)
    assert result.exit_code == 0, (result.stdout, result.stderr)
    return result


def _matrix(loader: Any, node: Any) -> dict[str, Any]:
    mapping: dict[str, Any] = loader.construct_mapping(node, deep=True)
    mapping["__opencv_matrix__"] = True
    return mapping


OpenCVLoader: Any = type("OpenCVLoader", (yaml.SafeLoader,), {})
OpenCVLoader.add_constructor("tag:yaml.org,2002:opencv-matrix", _matrix)


def load_opencv(text: str) -> dict[str, Any]:
    """cv::FileStorage's YAML: ``%YAML:1.0`` first (a directive PyYAML refuses), then YAML
    with ``!!opencv-matrix`` nodes; with OpenCV installed, cross-checked with its reader."""
    first, rest = text.split("\n", 1)
    assert first == "%YAML:1.0"
    data = yaml.load(rest, Loader=OpenCVLoader)
    assert isinstance(data, dict)
    try:
        import cv2  # type: ignore[import-not-found]
    except ImportError:
        return data
    storage = cv2.FileStorage(text, cv2.FILE_STORAGE_READ | cv2.FILE_STORAGE_MEMORY)
    for key, value in data.items():
        node = storage.getNode(key)
        if isinstance(value, dict):
            assert np.allclose(node.mat(), matrix(value), atol=1e-6), key
        elif isinstance(value, str):
            assert node.isString() and node.string() == value, key
        elif isinstance(value, float):
            assert node.isReal() and node.real() == pytest.approx(value), key
        else:
            assert node.isInt() and int(node.real()) == value, key
    return data


def matrix(node: dict[str, Any]) -> np.ndarray[Any, Any]:
    assert node["__opencv_matrix__"]
    return np.array(node["data"], dtype=np.float64).reshape(node["rows"], node["cols"])


def assert_rigid(T: np.ndarray[Any, Any]) -> None:
    assert T.shape == (4, 4)
    assert np.allclose(T[:3, :3] @ T[:3, :3].T, np.eye(3), atol=1e-12)
    assert np.linalg.det(T[:3, :3]) == pytest.approx(1.0)
    assert T[3].tolist() == [0.0, 0.0, 0.0, 1.0]


def literal(text: str, key: str) -> str:
    (match,) = re.findall(rf"^{re.escape(key)}:\s*(.*)$", text, re.MULTILINE)
    return str(match)


def kalibr_pair(data: dict[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    assert set(data) == {"cam0", "cam1"}  # every top-level key is a camera to Kalibr
    return data["cam0"], data["cam1"]


def T_world(xyz: tuple[float, float, float], optical: bool) -> np.ndarray[Any, Any]:
    T = np.eye(4)
    T[:3, 3] = xyz
    if optical:
        T[:3, :3] = [[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]
    return T


LEFT_EYE = T_world((0.2, BASELINE / 2, 0.3), optical=True)
RIGHT_EYE = T_world((0.2, -BASELINE / 2, 0.3), optical=True)


# --------------------------------------------------------------------------- detection


@pytest.mark.parametrize(
    ("sim", "target", "cx"), [("classic", "classic", 320.5), ("gz", "harmonic", 320.0)]
)
def test_macro_pair_is_described(write: Any, sim: str, target: str, cx: float) -> None:
    info = describe(load(write(macro_robot(sim))), "auto")
    assert info.target == target
    (pair,) = info.stereo_pairs
    assert (pair.name, pair.left.id, pair.right.id) == ("front", "front_left", "front_right")
    assert pair.left.frame == "front_left_optical_frame"
    assert pair.right.frame == "front_right_optical_frame"
    assert pair.baseline == pytest.approx(BASELINE, abs=EYE) and pair.rectified
    expected = np.eye(4)
    expected[0, 3] = BASELINE
    assert np.allclose(pair.T_left_right, expected, atol=EYE)
    assert np.allclose(pair.T_right_left @ pair.T_left_right, np.eye(4), atol=EYE)
    # the macro pins the right eye's Tx to -fx * baseline on both simulators
    assert pair.right.intrinsics is not None and pair.left.intrinsics is not None
    assert pair.right.intrinsics.baseline == pytest.approx(BASELINE)
    assert pair.left.intrinsics.cx == cx
    assert pair.notes == []


def test_multicamera_pair_is_described(write: Any) -> None:
    info = describe(load(write(multicamera_robot(), ".urdf")), "auto")
    (pair,) = info.stereo_pairs
    assert (pair.name, pair.left.id, pair.right.id, pair.how) == (
        "stereo",
        "stereo/left",
        "stereo/right",
        "multicamera",
    )
    assert pair.rectified and pair.baseline == pytest.approx(BASELINE)
    said = " ".join(pair.notes)
    # gazebo_ros_camera (ROS 2) reads <hack_baseline> for every camera of a multicamera
    assert "stereo/left's camera_info carries P[0][3]" in said
    assert "both eyes are stamped 'stereo_optical_frame'" in said


def test_ros1_multicamera_pair(write: Any) -> None:
    text = multicamera_robot(
        plugin="libgazebo_ros_multicamera.so",
        params=f"<hackBaseline>{BASELINE}</hackBaseline><cameraName>stereo</cameraName>",
    )
    info = describe(load(write(text, ".urdf")), "ros1")
    (pair,) = info.stereo_pairs
    assert (pair.left.id, pair.right.id) == ("stereo/left", "stereo/right")
    # ROS 1 forces the left eye's baseline to 0 (gazebo_ros_multicamera.cpp:84-88)
    assert not any("left's camera_info carries" in n for n in pair.notes)


def test_multicamera_eyes_ordered_by_where_they_sit(write: Any) -> None:
    # "right" placed to the left of "left": the pair follows the geometry, with a note
    info = describe(
        load(write(multicamera_robot(right_pose=f"0 {BASELINE} 0 0 0 0"), ".urdf")), "auto"
    )
    (pair,) = info.stereo_pairs
    assert (pair.left.id, pair.right.id) == ("stereo/right", "stereo/left")
    assert any("whatever their names say" in n for n in pair.notes)


def test_pair_from_the_right_eyes_projection(write: Any) -> None:
    text = two_cameras_robot(f"<hack_baseline>{BASELINE}</hack_baseline>")
    (pair,) = describe(load(write(text, ".urdf")), "auto").stereo_pairs
    assert (pair.name, pair.how) == ("cam_a+cam_b", "projection Tx")
    assert pair.baseline == pytest.approx(BASELINE)


def test_no_pair_without_names_or_baseline(write: Any) -> None:
    assert describe(load(write(two_cameras_robot(), ".urdf")), "auto").stereo_pairs == []


def test_baseline_that_disagrees_with_the_kinematics_is_noted(write: Any) -> None:
    text = two_cameras_robot("<hack_baseline>0.07</hack_baseline>", names=("s_left", "s_right"))
    (pair,) = describe(load(write(text, ".urdf")), "auto").stereo_pairs
    assert pair.name == "s" and pair.baseline == pytest.approx(BASELINE)
    assert any("baseline is 0.07 m" in n and "0.12 m apart" in n for n in pair.notes)


def test_named_pair_in_the_wrong_order_is_not_a_pair(write: Any) -> None:
    text = two_cameras_robot(names=("s_right", "s_left"))  # s_left sits to the right
    info = describe(load(write(text, ".urdf")), "auto")
    assert info.stereo_pairs == []
    (right,) = [s for s in info.sensors if s.name == "s_right"]
    assert any("not exported as a stereo pair" in n for n in right.notes)


# --------------------------------------------------------------------------- writers


def _eye(**kw: Any) -> Intrinsics:
    base: dict[str, Any] = {
        "width": WIDTH,
        "height": HEIGHT,
        "fx": FX,
        "fy": FX,
        "cx": 320.0,
        "cy": 240.0,
    }
    return Intrinsics(**{**base, **kw})


def _T(x: float = BASELINE, yaw: float = 0.0) -> np.ndarray[Any, Any]:
    T = np.eye(4)
    c, s = math.cos(yaw), math.sin(yaw)
    T[:3, :3] = [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]  # about the optical y (down) axis
    T[0, 3] = x
    return T


def test_kalibr_stereo_writer() -> None:
    T_c1_c0 = np.linalg.inv(_T())
    text = kalibr_stereo_camchain_yaml(
        _eye(), _eye(), rostopics=("/l/image_raw", "/r/image_raw"), T_cn_cnm1=T_c1_c0
    )
    cam0, cam1 = kalibr_pair(yaml.safe_load(text))
    assert "T_cam_imu" not in cam0 and "T_cam_imu" not in cam1
    assert np.array(cam1["T_cn_cnm1"]).tolist() == T_c1_c0.tolist()
    with pytest.raises(InvalidValue, match="T_cn_cnm1 rotation"):
        kalibr_stereo_camchain_yaml(
            _eye(), _eye(), rostopics=("/l", "/r"), T_cn_cnm1=np.diag([1.0, 1.0, -1.0, 1.0])
        )
    with pytest.raises(InvalidValue, match="k3"):
        kalibr_stereo_camchain_yaml(
            _eye(),
            _eye(distortion=(0.0, 0.0, 0.0, 0.0, 0.1)),
            rostopics=("/l", "/r"),
            T_cn_cnm1=T_c1_c0,
        )


def test_orbslam3_stereo_writer_v1_takes_any_rigid_pair() -> None:
    T = _T(yaw=0.05)
    text = orbslam3_stereo_yaml(_eye(), _eye(cx=330.0), T_c1_c2=T, fps=20, version="1.0")
    data = load_opencv(text)
    assert np.allclose(matrix(data["Stereo.T_c1_c2"]), T)
    assert (data["Camera1.cx"], data["Camera2.cx"]) == (320.0, 330.0)
    with pytest.raises(InvalidValue, match="rigid"):
        orbslam3_stereo_yaml(_eye(), _eye(), T_c1_c2=np.diag([2.0, 1.0, 1.0, 1.0]), fps=20)
    with pytest.raises(InvalidValue, match="one image size"):
        orbslam3_stereo_yaml(_eye(), _eye(width=320), T_c1_c2=_T(), fps=20)
    with pytest.raises(InvalidValue, match="apart"):
        orbslam3_stereo_yaml(_eye(), _eye(), T_c1_c2=np.eye(4), fps=20)


def test_a_far_but_finite_baseline_is_measured_without_overflow() -> None:
    # Regression (test_fuzz's export target): numpy's norm squares each coordinate, so a
    # pair 1e200 m apart overflowed with a RuntimeWarning on stderr. The v1.0 file needs
    # only a positive baseline; the old one writes baseline * fx, which then overflows for
    # real and is refused in one line.
    T = _T(x=1e200)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        text = orbslam3_stereo_yaml(_eye(), _eye(), T_c1_c2=T, fps=20, version="1.0")
        assert matrix(load_opencv(text)["Stereo.T_c1_c2"])[0, 3] == 1e200
        with pytest.raises(InvalidValue, match="bf"):
            orbslam3_stereo_yaml(_eye(), _eye(), T_c1_c2=_T(x=1e307), fps=20, version="old")


@pytest.mark.parametrize(
    ("right", "T", "match"),
    [
        ({"cx": 330.0}, _T(), "one camera matrix"),
        ({"distortion": (0.1, 0.0, 0.0, 0.0, 0.0)}, _T(), "no distortion"),
        ({}, _T(yaw=0.05), "rectified pair"),
    ],
)
def test_orbslam3_stereo_writer_old_needs_a_rectified_pair(
    right: dict[str, Any], T: np.ndarray[Any, Any], match: str
) -> None:
    with pytest.raises(InvalidValue, match=match):
        orbslam3_stereo_yaml(_eye(), _eye(**right), T_c1_c2=T, fps=20, version="old")


def test_orbslam3_stereo_inertial_writer_kinds() -> None:
    imu = OrbImuSettings(
        T_b_c1=np.eye(4),
        noise_gyro=1e-4,
        noise_acc=1e-3,
        gyro_walk=1e-5,
        acc_walk=1e-3,
        frequency=200.0,
    )
    v1 = orbslam3_stereo_yaml(_eye(), _eye(), T_c1_c2=_T(), fps=30, imu=imu)
    old = orbslam3_stereo_yaml(_eye(), _eye(), T_c1_c2=_T(), fps=30, version="old", imu=imu)
    assert literal(v1, "IMU.Frequency") == "200.0" and literal(old, "IMU.Frequency") == "200"
    assert "IMU.T_b_c1: !!opencv-matrix" in v1 and "Tbc: !!opencv-matrix" in old
    assert literal(old, "IMU.NoiseGyro") == "0.0001"
    with pytest.raises(InvalidValue, match=r"IMU\.NoiseAcc"):
        orbslam3_stereo_yaml(
            _eye(),
            _eye(),
            T_c1_c2=_T(),
            fps=30,
            imu=OrbImuSettings(np.eye(4), 1e-4, 0.0, 1e-5, 1e-3, 200.0),
        )


def test_stereo_camera_infos() -> None:
    left, right = stereo_camera_infos(_eye(baseline_tx=-5.0, p_ty=1.0), _eye(p_fx=400.0), BASELINE)
    assert (left.P[0, 3], left.P[1, 3]) == (0.0, 0.0)
    assert right.P[0, 3] == -400.0 * BASELINE and right.baseline == pytest.approx(BASELINE)
    with pytest.raises(InvalidValue, match="baseline"):
        stereo_camera_infos(_eye(), _eye(), 0.0)


def test_opencv_matrix_dt() -> None:
    assert "   dt: f" in opencv_matrix_lines("m", 1, 1, [1.0], dt="f")
    with pytest.raises(InvalidValue, match="dt"):
        opencv_matrix_lines("m", 1, 1, [1.0], dt="u")


# --------------------------------------------------------------------------- Kalibr


@pytest.mark.parametrize(("sim", "cx"), [("classic", 320.5), ("gz", 320.0)])
def test_kalibr_camchain(write: Any, tmp_path: Path, sim: str, cx: float) -> None:
    robot = write(macro_robot(sim))
    result = ok("intrinsics", robot, "--sensor", "front", "--format", "kalibr")
    cam0, cam1 = kalibr_pair(yaml.safe_load(result.stdout))
    for cam, eye in ((cam0, "left"), (cam1, "right")):
        assert cam["camera_model"] == "pinhole" and cam["distortion_model"] == "radtan"
        assert cam["intrinsics"] == pytest.approx([FX, FX, cx, (HEIGHT + (sim == "classic")) / 2])
        assert all(type(v) is float for v in cam["intrinsics"])
        assert cam["distortion_coeffs"] == [0.0, 0.0, 0.0, 0.0]
        assert cam["resolution"] == [WIDTH, HEIGHT] and all(
            type(v) is int for v in cam["resolution"]
        )
        assert cam["rostopic"] == f"/front/{eye}/image_raw"
    assert "T_cn_cnm1" not in cam0
    assert (cam0["cam_overlaps"], cam1["cam_overlaps"]) == ([1], [0])
    T = np.array(cam1["T_cn_cnm1"])
    assert_rigid(T)
    # T_c1_c0 takes left-eye coordinates into the right eye's: the left eye sits the
    # baseline along the right eye's -x (its "right" axis points away from the left eye)
    assert np.allclose(T[:3, :3], np.eye(3), atol=EYE)
    assert T[:3, 3] == pytest.approx([-BASELINE, 0.0, 0.0], abs=EYE)
    assert float(np.linalg.norm(T[:3, 3])) == pytest.approx(BASELINE, abs=EYE)
    # T_cam_imu for each camera, consistent with the chain: T_c1_i = T_c1_c0 T_c0_i
    T0, T1 = np.array(cam0["T_cam_imu"]), np.array(cam1["T_cam_imu"])
    assert_rigid(T0)
    assert_rigid(T1)
    assert np.allclose(T1, T @ T0, atol=EYE)
    imu = T_world((0.0, 0.0, 0.1), optical=False)
    assert np.allclose(T0, np.linalg.inv(LEFT_EYE) @ imu, atol=EYE)
    assert np.allclose(T1, np.linalg.inv(RIGHT_EYE) @ imu, atol=EYE)


def test_kalibr_camchain_of_a_multicamera(write: Any) -> None:
    robot = write(multicamera_robot(), ".urdf")
    result = ok("intrinsics", robot, "--sensor", "stereo", "--format", "kalibr")
    cam0, cam1 = kalibr_pair(yaml.safe_load(result.stdout))
    assert (cam0["rostopic"], cam1["rostopic"]) == (
        "/stereo/left/image_raw",
        "/stereo/right/image_raw",
    )
    assert np.array(cam1["T_cn_cnm1"])[:3, 3] == pytest.approx([-BASELINE, 0.0, 0.0])
    # one camera of the multicamera still prints that camera alone
    one = ok("intrinsics", robot, "--sensor", "stereo/right", "--format", "kalibr")
    assert set(yaml.safe_load(one.stdout)) == {"cam0"}


def test_pair_names_are_listed_for_an_unknown_sensor(write: Any) -> None:
    result = run("intrinsics", write(macro_robot("classic")), "--sensor", "nope")
    assert result.exit_code == 2
    assert "front_left" in result.stderr and "stereo pairs: front" in result.stderr


def test_json_lists_the_pair(write: Any) -> None:
    data = json.loads(ok("intrinsics", write(macro_robot("gz"))).stdout)
    (pair,) = data["stereo_pairs"]
    assert (pair["left"], pair["right"], pair["rectified"]) == ("front_left", "front_right", True)
    assert pair["baseline"] == pytest.approx(BASELINE)
    assert np.array(pair["T_left_right"])[:3, 3] == pytest.approx([BASELINE, 0.0, 0.0])


# --------------------------------------------------------------------------- ORB-SLAM3


@pytest.mark.parametrize("sim", ["classic", "gz"])
def test_orbslam3_v1_stereo(write: Any, sim: str) -> None:
    robot = write(macro_robot(sim))
    text = ok("intrinsics", robot, "--sensor", "front", "--format", "orbslam3-v1").stdout
    data = load_opencv(text)
    assert data["File.version"] == "1.0" and data["Camera.type"] == "PinHole"
    info = describe(load(robot), "auto")
    (pair,) = info.stereo_pairs
    for key, eye in (("Camera1", pair.left), ("Camera2", pair.right)):
        intr = eye.intrinsics
        assert intr is not None
        got = [data[f"{key}.{k}"] for k in ("fx", "fy", "cx", "cy")]
        assert got == [intr.fx, intr.fy, intr.cx, intr.cy]
        assert all(type(v) is float for v in got)
        assert f"{key}.k1" not in data  # no distortion: nothing to undistort
    for key in ("Camera.width", "Camera.height", "Camera.fps", "Camera.RGB"):
        assert type(data[key]) is int, key
    assert type(data["Stereo.ThDepth"]) is float
    assert "dt: f" in text.split("Stereo.T_c1_c2:", 1)[1].split("data", 1)[0]
    T = matrix(data["Stereo.T_c1_c2"])
    assert_rigid(T)
    assert T[:3, 3] == pytest.approx([BASELINE, 0.0, 0.0], abs=EYE)
    # ORB-SLAM3 takes b = |t| and bf = b * Camera1.fx (Settings.cc:347-348)
    assert float(np.linalg.norm(T[:3, 3])) * data["Camera1.fx"] == pytest.approx(FX * BASELINE)
    assert "IMU.T_b_c1" not in data  # plain stereo without --imu


def test_orbslam3_old_stereo_has_bf(write: Any) -> None:
    text = ok(
        "intrinsics", write(macro_robot("classic")), "--sensor", "front", "--format", "orbslam3"
    ).stdout
    data = load_opencv(text)
    assert "File.version" not in data and data["Camera.type"] == "PinHole"
    assert data["Camera.fx"] == pytest.approx(FX) and data["Camera.cx"] == 320.5
    assert data["Camera.bf"] == pytest.approx(FX * BASELINE) and "." in literal(text, "Camera.bf")
    assert type(data["Camera.bf"]) is float and type(data["ThDepth"]) is float
    for key in ("Camera.k1", "Camera.k2", "Camera.p1", "Camera.p2"):
        assert data[key] == 0.0 and type(data[key]) is float  # the old reader requires reals


def test_orbslam3_stereo_inertial_with_imu(write: Any) -> None:
    robot = write(macro_robot("gz"))
    result = ok("intrinsics", robot, "--sensor", "front", "--format", "orbslam3-v1", "--imu", "imu")
    data = load_opencv(result.stdout)
    T_b_c1 = matrix(data["IMU.T_b_c1"])
    assert_rigid(T_b_c1)
    imu = T_world((0.0, 0.0, 0.1), optical=False)
    assert np.allclose(T_b_c1, np.linalg.inv(imu) @ LEFT_EYE, atol=EYE)
    # per-sample stddev -> density: stddev / sqrt(rate) (ORB-SLAM3 multiplies it back,
    # Tracking.cc:613-614)
    assert data["IMU.NoiseGyro"] == pytest.approx(GYRO_STDDEV / math.sqrt(IMU_RATE))
    assert data["IMU.NoiseAcc"] == pytest.approx(ACCEL_STDDEV / math.sqrt(IMU_RATE))
    assert data["IMU.Frequency"] == IMU_RATE and type(data["IMU.Frequency"]) is float
    # the simulated bias does not walk: EuRoC's walks, said on stderr
    assert data["IMU.GyroWalk"] == pytest.approx(1.9393e-05)
    assert data["IMU.AccWalk"] == pytest.approx(3.0e-03)
    assert "random walk" in result.stderr and "EuRoC" in result.stderr


def test_orbslam3_walks_from_gz_dynamic_bias(write: Any) -> None:
    noise = (
        "<noise type='gaussian'><mean>0</mean><stddev>0.001</stddev>"
        "<dynamic_bias_stddev>3e-5</dynamic_bias_stddev>"
        "<dynamic_bias_correlation_time>1000</dynamic_bias_correlation_time></noise>"
    )
    axes = "".join(f"<{a}>{noise}</{a}>" for a in "xyz")
    imu = (
        '<link name="imu2_link">' + INERTIA + "</link>"
        '<joint name="imu2_joint" type="fixed"><parent link="base_link"/><child link="imu2_link"/>'
        '<origin xyz="0 0 0" rpy="0 0 0"/></joint>'
        '<gazebo reference="imu2_link"><sensor name="imu2" type="imu"><update_rate>400</update_rate>'
        f"<topic>imu2</topic><imu><angular_velocity>{axes}</angular_velocity></imu></sensor></gazebo>"
    )
    robot = write(macro_robot("gz", extra=imu))
    result = ok(
        "intrinsics", robot, "--sensor", "front", "--format", "orbslam3-v1", "--imu", "imu2"
    )
    data = load_opencv(result.stdout)
    assert data["IMU.GyroWalk"] == pytest.approx(3e-5)  # gz-sensors' dynamic bias density
    assert data["IMU.NoiseGyro"] == pytest.approx(0.001 / 20.0)
    assert data["IMU.NoiseAcc"] == pytest.approx(2.0e-03)  # no accelerometer noise: EuRoC's
    assert "no accelerometer noise" in result.stderr


# --------------------------------------------------------------------------- export


@pytest.mark.parametrize("sim", ["classic", "gz"])
def test_export_writes_the_pair_folder(write: Any, tmp_path: Path, sim: str) -> None:
    out = tmp_path / "out"
    result = ok("export", write(macro_robot(sim)), "--out", out)
    folder = out / "stereo_front_left_front_right"
    assert {p.name for p in folder.iterdir()} == {
        "stereo.json",
        "left.yaml",
        "right.yaml",
        "kalibr_camchain.yaml",
        "orbslam3_stereo.yaml",
        "orbslam3_stereo_v1.yaml",
        "orbslam3_stereo_inertial.yaml",
        "orbslam3_stereo_inertial_v1.yaml",
    }
    assert (out / "front_left/camera_info.yaml").is_file()  # each eye keeps its own folder
    # camera_info pair: Tx = Ty = 0 on the left, Tx = -fx' * B on the right
    left = yaml.safe_load((folder / "left.yaml").read_text())
    right = yaml.safe_load((folder / "right.yaml").read_text())
    P_left = np.array(left["projection_matrix"]["data"]).reshape(3, 4)
    P_right = np.array(right["projection_matrix"]["data"]).reshape(3, 4)
    assert P_left[0, 3] == 0.0 and P_left[1, 3] == 0.0
    assert P_right[0, 3] == pytest.approx(-P_right[0, 0] * BASELINE) and P_right[1, 3] == 0.0
    assert P_right[0, 0] == pytest.approx(FX)
    assert left["camera_matrix"] == right["camera_matrix"]
    assert left["rectification_matrix"]["data"] == [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    # the same P as the simulator publishes for each eye
    cameras = json.loads(ok("intrinsics", write(macro_robot(sim))).stdout)["cameras"]
    published = {c["camera"]: c for c in cameras}
    assert P_right.tolist() == published["front_right"]["P"]
    assert P_left.tolist() == published["front_left"]["P"]
    # stereo-inertial old format: Tbc and an int IMU.Frequency
    old = (folder / "orbslam3_stereo_inertial.yaml").read_text()
    data = load_opencv(old)
    assert literal(old, "IMU.Frequency") == "100"
    assert np.allclose(
        matrix(data["Tbc"]),
        matrix(
            load_opencv((folder / "orbslam3_stereo_inertial_v1.yaml").read_text())["IMU.T_b_c1"]
        ),
    )
    kalibr = yaml.safe_load((folder / "kalibr_camchain.yaml").read_text())
    assert "T_cam_imu" in kalibr["cam0"] and "T_cam_imu" in kalibr["cam1"]
    assert "not written" not in result.stderr


def test_export_multicamera_pair_without_imu(write: Any, tmp_path: Path) -> None:
    robot = write(multicamera_robot(with_imu=False), ".urdf")
    out = tmp_path / "out"
    result = run("export", robot, "--out", out)
    folder = out / "stereo_stereo_left_stereo_right"
    assert (folder / "kalibr_camchain.yaml").is_file()
    assert (folder / "orbslam3_stereo_v1.yaml").is_file()
    right = yaml.safe_load((folder / "right.yaml").read_text())
    assert right["projection_matrix"]["data"][3] == pytest.approx(-FX * BASELINE)
    left = yaml.safe_load((folder / "left.yaml").read_text())
    assert left["projection_matrix"]["data"][3] == 0.0  # though Gazebo publishes it there
    assert "stereo/left's camera_info carries" in result.stderr


def test_unrectified_pair_keeps_the_whole_transform(write: Any, tmp_path: Path) -> None:
    # the right eye toed in by 0.05 rad and 1 cm low
    text = multicamera_robot(right_pose=f"0 -{BASELINE} -0.01 0 0 0.05")
    robot = write(text, ".urdf")
    (pair,) = describe(load(robot), "auto").stereo_pairs
    assert not pair.rectified
    out = tmp_path / "out"
    result = ok("export", robot, "--out", out)
    folder = out / "stereo_stereo_left_stereo_right"
    names = {p.name for p in folder.iterdir()}
    assert "left.yaml" not in names and "orbslam3_stereo.yaml" not in names
    assert (
        "rectified pair only" in result.stderr
        and "orbslam3_stereo.yaml not written" in result.stderr
    )
    T_c1_c2 = matrix(
        load_opencv((folder / "orbslam3_stereo_v1.yaml").read_text())["Stereo.T_c1_c2"]
    )
    T_cn_cnm1 = np.array(
        yaml.safe_load((folder / "kalibr_camchain.yaml").read_text())["cam1"]["T_cn_cnm1"]
    )
    assert_rigid(T_c1_c2)
    assert np.allclose(T_c1_c2 @ T_cn_cnm1, np.eye(4), atol=1e-6)
    assert np.allclose(T_c1_c2, pair.T_left_right, atol=1e-6)  # dt: f keeps 7 digits; written exact
    assert abs(T_c1_c2[1, 3] - 0.01) < 1e-9  # 1 cm low: +y (down) in the left optical frame


def test_distorted_pair_goes_to_v1_only(write: Any, tmp_path: Path) -> None:
    distortion = "<distortion><k1>-0.1</k1><k2>0.01</k2><p1>0.001</p1><p2>0.0</p2></distortion>"
    robot = write(multicamera_robot(left_extra=distortion), ".urdf")
    out = tmp_path / "out"
    result = ok("export", robot, "--out", out)
    folder = out / "stereo_stereo_left_stereo_right"
    data = load_opencv((folder / "orbslam3_stereo_v1.yaml").read_text())
    assert data["Camera1.k1"] == -0.1 and "Camera2.k1" not in data
    assert not (folder / "orbslam3_stereo.yaml").exists()
    assert "orbslam3_stereo.yaml not written" in result.stderr


# --------------------------------------------------------------------------- --imu


def test_imu_option_chooses_the_imu(write: Any) -> None:
    robot = write(macro_robot("classic", imus=("imu_a", "imu_b")))
    args = ("intrinsics", robot, "--sensor", "front", "--format", "kalibr")
    first = ok(*args)
    assert "IMU 'imu_a' is used (the first of 2: imu_a, imu_b)" in first.stderr
    assert "--imu" in first.stderr
    chosen = ok(*args, "--imu", "imu_b")
    assert "is used" not in chosen.stderr
    T_a = np.array(yaml.safe_load(first.stdout)["cam0"]["T_cam_imu"])
    T_b = np.array(yaml.safe_load(chosen.stdout)["cam0"]["T_cam_imu"])
    for T, y in ((T_a, 0.0), (T_b, 0.1)):
        imu = T_world((0.0, y, 0.1), optical=False)
        assert np.allclose(T, np.linalg.inv(LEFT_EYE) @ imu, atol=EYE)
    # one camera too, and the export
    single = ok(
        "intrinsics", robot, "--sensor", "front_left", "--format", "kalibr", "--imu", "imu_b"
    )
    assert np.allclose(np.array(yaml.safe_load(single.stdout)["cam0"]["T_cam_imu"]), T_b)


def test_imu_option_for_export(write: Any, tmp_path: Path) -> None:
    robot = write(macro_robot("gz", imus=("imu_a", "imu_b")))
    out = tmp_path / "out"
    result = ok("export", robot, "--out", out, "--imu", "imu_b")
    assert "is used" not in result.stderr
    folder = out / "stereo_front_left_front_right"
    T_b_c1 = matrix(
        load_opencv((folder / "orbslam3_stereo_inertial_v1.yaml").read_text())["IMU.T_b_c1"]
    )
    imu_b = T_world((0.0, 0.1, 0.1), optical=False)
    assert np.allclose(T_b_c1, np.linalg.inv(imu_b) @ LEFT_EYE, atol=EYE)
    T = np.array(yaml.safe_load((out / "front_left/kalibr.yaml").read_text())["cam0"]["T_cam_imu"])
    assert np.allclose(T, np.linalg.inv(LEFT_EYE) @ imu_b, atol=EYE)
    again = ok("export", robot, "--out", tmp_path / "out2")
    assert "IMU 'imu_a' is used (the first of 2: imu_a, imu_b)" in again.stderr


@pytest.mark.parametrize("command", ["intrinsics", "export"])
def test_unknown_imu_is_a_usage_error(write: Any, tmp_path: Path, command: str) -> None:
    robot = write(macro_robot("classic", imus=("imu_a", "imu_b")))
    extra = (
        ("--out", tmp_path / "out")
        if command == "export"
        else ("--format", "kalibr", "--sensor", "front")
    )
    result = run(command, robot, *extra, "--imu", "nope")
    assert result.exit_code == 2 and result.stdout == ""
    message = result.stderr.strip()
    assert "\n" not in message and message.startswith("sensorkit: ")
    assert "'nope'" in message and "imu_a, imu_b" in message
    assert not (tmp_path / "out").exists()


def test_imu_option_on_a_robot_without_imu(write: Any) -> None:
    result = run("intrinsics", write(two_cameras_robot(), ".urdf"), "--imu", "imu")
    assert result.exit_code == 2 and "the robot has no IMU" in result.stderr
