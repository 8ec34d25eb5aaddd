"""Every example validates with no error and no warning, passes check_urdf, publishes the
topics its spec promises, and the generated one is exactly what ``sensorkit new`` makes."""

from __future__ import annotations

import math
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from lxml import etree

from sensorkit.base.findings import Severity
from sensorkit.describe.intrinsics import camera_intrinsics
from sensorkit.generate import new_package
from sensorkit.lint.engine import Options, validate_file

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
ORB = EXAMPLES / "orbslam3_car" / "urdf" / "orbslam3_car.urdf.xacro"
HUMBLE = EXAMPLES / "humble_three_sensors" / "urdf" / "robot_with_sensors.xacro"
HARMONIC_DIR = EXAMPLES / "harmonic_robot"
HARMONIC_PKG = HARMONIC_DIR / "harmonic_robot_description"
HARMONIC = HARMONIC_PKG / "urdf" / "harmonic_robot.urdf.xacro"
ROBOT_FILES = [ORB, HUMBLE, HARMONIC]


def expand(path: Path, *args: str) -> etree._Element:
    venv = Path(sys.executable).with_name("xacro")
    exe = [str(venv)] if venv.exists() else [shutil.which("xacro") or "xacro"]
    proc = subprocess.run(
        [*exe, str(path), *args], capture_output=True, text=True, timeout=60, check=False
    )
    assert proc.returncode == 0, proc.stderr
    return etree.fromstring(proc.stdout.encode())


def joint_to(robot: etree._Element, child: str) -> etree._Element:
    """The joint whose child is ``child``."""
    (joint,) = robot.xpath("joint[child/@link=$child]", child=child)
    return joint


def classic_topics(robot: etree._Element) -> dict[str, tuple[str, str]]:
    """ROS topic -> (sensor, frame) for gazebo_ros camera and ray plugins (ROS 2 rules)."""
    out: dict[str, tuple[str, str]] = {}
    for sensor in robot.iter("sensor"):
        plugin = sensor.find("plugin")
        if plugin is None:
            continue
        ns = (plugin.findtext("ros/namespace") or "").strip("/")
        prefix = f"/{ns}/" if ns else "/"
        frame = plugin.findtext("frame_name") or ""
        if plugin.get("filename") == "libgazebo_ros_camera.so":
            cam = plugin.findtext("camera_name") or sensor.get("name")
            suffixes = ["image_raw", "camera_info"]
            if sensor.get("type") == "depth":
                suffixes += ["depth/image_raw", "depth/camera_info", "points"]
            for s in suffixes:
                out[f"{prefix}{cam}/{s}"] = (sensor.get("name"), frame)
        else:
            for remap in plugin.findall("ros/remapping"):
                src, _, dst = (remap.text or "").partition(":=")
                if src.strip() == "~/out":
                    out[f"{prefix}{dst.strip()}"] = (sensor.get("name"), frame)
    return out


@pytest.mark.parametrize("path", ROBOT_FILES, ids=lambda p: p.parent.parent.name)
def test_example_validates_with_no_error_and_no_warning(path: Path) -> None:
    report = validate_file(path, Options())
    assert report.error is None, report.error
    assert not report.internal_errors, report.internal_errors
    bad = [(f.rule, f.message) for f in report.findings if f.severity >= Severity.WARNING]
    assert not bad, bad


@pytest.mark.parametrize("path", ROBOT_FILES, ids=lambda p: p.parent.parent.name)
def test_example_passes_check_urdf(path: Path, tmp_path: Path) -> None:
    exe = shutil.which("check_urdf") or "/usr/bin/check_urdf"
    if not Path(exe).exists():
        pytest.fail("check_urdf is missing: apt-get install liburdfdom-tools")
    urdf = tmp_path / "robot.urdf"
    urdf.write_bytes(etree.tostring(expand(path)))
    proc = subprocess.run([exe, str(urdf)], capture_output=True, text=True, timeout=20, check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr


@pytest.mark.parametrize("folder", ["orbslam3_car", "humble_three_sensors", "harmonic_robot"])
def test_example_readme_says_what_to_try(folder: str) -> None:
    text = (EXAMPLES / folder / "README.md").read_text()
    assert "sensorkit validate examples/" in text
    assert "sensorkit render preview examples/" in text
    for cmd in re.findall(r"sensorkit (?:validate|render preview) (examples/\S+)", text):
        assert (ROOT / cmd).is_file(), cmd


def test_orbslam3_car_matches_the_tutorial() -> None:
    robot = expand(ORB)
    joint = joint_to(robot, "chassis_link")
    assert joint.find("parent").get("link") == "base_link"
    box = robot.find("link[@name='chassis_link']/visual/geometry/box").get("size")
    assert [float(v) for v in box.split()] == [0.6, 0.3, 0.1]
    cam_joint = joint_to(robot, "camera_link")
    assert cam_joint.find("parent").get("link") == "chassis_link"
    assert [float(v) for v in cam_joint.find("origin").get("xyz").split()] == [0.4, 0, 0]

    cam = robot.find(".//sensor[@name='camera']")
    assert cam.get("type") == "depth"
    assert float(cam.findtext("update_rate")) == 30
    assert float(cam.findtext("camera/horizontal_fov")) == 2.0
    assert cam.findtext("camera/image/width") == "640"
    assert cam.findtext("camera/image/height") == "480"
    assert cam.findtext("camera/image/format") == "R8G8B8"
    assert float(cam.findtext("camera/clip/far")) == 10.0
    assert cam.find("camera/distortion") is None  # zero distortion
    assert cam.find("plugin").get("filename") == "libgazebo_ros_camera.so"

    topics = classic_topics(robot)
    for t in ("image_raw", "camera_info", "depth/image_raw", "depth/camera_info", "points"):
        assert topics[f"/camera/{t}"] == ("camera", "camera_optical_frame"), t
    optical = joint_to(robot, "camera_optical_frame").find("origin").get("rpy").split()
    assert [round(float(v), 6) for v in optical] == [
        round(-math.pi / 2, 6),
        0,
        round(-math.pi / 2, 6),
    ]

    lidar = robot.find(".//sensor[@type='ray']")
    assert lidar.findtext("ray/scan/horizontal/samples") == "360"
    assert float(lidar.findtext("update_rate")) == 10
    assert float(lidar.findtext("ray/range/min")) == 0.15
    assert float(lidar.findtext("ray/range/max")) == 12.0
    assert float(lidar.findtext("ray/noise/stddev")) == 0.01
    assert any(t.endswith("/scan") for t in topics)

    k = camera_intrinsics(640, 480, 2.0, "classic")
    assert (k.fx, k.fy, k.cx, k.cy) == (205.46963709898583, 205.46963709898583, 320.5, 240.5)
    readme = (EXAMPLES / "orbslam3_car" / "README.md").read_text()
    assert "fx = fy = 205.46963709898583, cx = 320.5, cy = 240.5" in readme


def test_humble_three_sensors_topics() -> None:
    robot = expand(HUMBLE)
    topics = classic_topics(robot)
    assert set(topics) >= {
        "/front_camera/image_raw",
        "/front_camera/camera_info",
        "/depth_camera/depth/image_raw",
        "/depth_camera/points",
        "/laser/scan",
    }
    assert topics["/depth_camera/points"][1] == "depth_camera_optical_frame"
    assert topics["/laser/scan"][1] == "laser_link"
    usb = robot.find(".//sensor[@name='front_camera']/camera")
    assert (usb.findtext("image/width"), usb.findtext("image/height")) == ("640", "480")
    assert float(usb.findtext("horizontal_fov")) == 1.3962634
    kinect = robot.find(".//sensor[@name='depth_camera']/camera")
    assert float(kinect.findtext("horizontal_fov")) == 1.0472
    assert (float(kinect.findtext("clip/near")), float(kinect.findtext("clip/far"))) == (0.05, 10)
    pitch = joint_to(robot, "depth_camera_link").find("origin").get("rpy").split()
    assert [float(v) for v in pitch] == [0, 0.2, 0]
    scan = robot.find(".//sensor[@name='laser']/ray")
    assert scan.findtext("scan/horizontal/samples") == "360"
    assert float(scan.findtext("scan/horizontal/min_angle")) == pytest.approx(-math.pi)
    assert float(scan.findtext("scan/horizontal/max_angle")) == pytest.approx(math.pi)
    assert (float(scan.findtext("range/min")), float(scan.findtext("range/max"))) == (0.15, 12)

    # Each sensor is its own macro taking prefix and parent_link.
    folder = HUMBLE.parent
    for file, macro in (
        ("camera", "usb_camera"),
        ("depth_camera", "kinect_camera"),
        ("lidar", "rplidar"),
    ):
        root = etree.parse(str(folder / f"{file}.xacro")).getroot()
        m = root.find(f"{{http://www.ros.org/wiki/xacro}}macro[@name='{macro}']")
        assert m is not None and {"prefix", "parent_link"} <= set(m.get("params").split())
    prefixed = classic_topics(expand(HUMBLE, "prefix:=left_"))
    assert "/left_laser/scan" in prefixed and "/left_front_camera/image_raw" in prefixed


def test_harmonic_robot_is_exactly_what_sensorkit_new_makes(tmp_path: Path) -> None:
    # generated beside a copy of the YAML, as the example lies beside its own: the header
    # names the YAML by its path from the package (../robot.yaml)
    shutil.copy(HARMONIC_DIR / "robot.yaml", tmp_path / "robot.yaml")
    out = tmp_path / "harmonic_robot_description"
    result = new_package(tmp_path / "robot.yaml", out)
    committed = sorted(
        p.relative_to(HARMONIC_PKG).as_posix() for p in HARMONIC_PKG.rglob("*") if p.is_file()
    )
    assert committed == result.files, "regenerate: see examples/harmonic_robot/README.md"
    for rel in result.files:
        assert (out / rel).read_bytes() == (HARMONIC_PKG / rel).read_bytes(), (
            f"{rel} differs from a fresh `sensorkit new`: regenerate examples/harmonic_robot"
        )


def test_harmonic_robot_has_the_four_sensors_and_a_full_bridge() -> None:
    spec = yaml.safe_load((HARMONIC_DIR / "robot.yaml").read_text())
    assert spec["sim"] == "gz" and spec["gz_version"] == "harmonic"
    assert sorted(s["type"] for s in spec["sensors"]) == [
        "camera",
        "depth_camera",
        "imu",
        "lidar_3d",
    ]
    robot = expand(HARMONIC)
    types = sorted(s.get("type") for s in robot.iter("sensor"))
    assert types == ["camera", "gpu_lidar", "imu", "rgbd_camera"]
    assert robot.find(".//sensor/gz_frame_id") is not None  # the Harmonic frame tag
    bridge = yaml.safe_load((HARMONIC_PKG / "config" / "bridge.yaml").read_text())
    gz = {e["gz_topic_name"] for e in bridge}
    for sensor in robot.iter("sensor"):
        topic = sensor.findtext("topic")
        assert any(g == topic or g.startswith(f"{topic}/") for g in gz), topic
    assert all(e["gz_type_name"].startswith("gz.msgs.") for e in bridge)
