"""The sensor macros under test and what each one must produce.

Shared by the macro tests: one row per macro file, with the links, joints, sensors and
topics the brief fixes for it, so a test can be written once and run over every macro and
every simulator variant.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

MACROS_DIR = Path(__file__).resolve().parents[1] / "macros"

XACRO_NS = "http://www.ros.org/wiki/xacro"

#: (sim, gz_version) pairs every macro is expanded with. gz_version only matters for gz.
SIM_VARIANTS: list[tuple[str, str]] = [
    ("classic", "harmonic"),
    ("gz", "fortress"),
    ("gz", "harmonic"),
    ("gz", "jetty"),
    ("none", "harmonic"),
]

#: The sensor-level frame tag each Gazebo Sim version reads.
GZ_FRAME_TAG = {"fortress": "ignition_frame_id", "harmonic": "gz_frame_id", "jetty": "frame_id"}

#: ROS 2 gazebo_plugins file names.
CLASSIC_PLUGIN = {
    "camera": "libgazebo_ros_camera.so",
    "ray": "libgazebo_ros_ray_sensor.so",
    "imu": "libgazebo_ros_imu_sensor.so",
}

#: Parameter names only the ROS 1 plugins read; the ROS 2 ones ignore them silently.
ROS1_TAGS = frozenset(
    {
        "frameName",
        "cameraName",
        "topicName",
        "updateRate",
        "updateRateHZ",
        "robotNamespace",
        "hackBaseline",
        "imageTopicName",
        "cameraInfoTopicName",
        "depthImageTopicName",
        "depthImageCameraInfoTopicName",
        "pointCloudTopicName",
        "pointCloudCutoff",
        "pointCloudCutoffMax",
        "focalLength",
        "distortionK1",
        "bodyName",
        "gaussianNoise",
        "alwaysOn",
    }
)

OPTICAL_RPY = (-math.pi / 2, 0.0, -math.pi / 2)


@dataclass(frozen=True)
class Eye:
    """One rendering origin of a camera macro: a sensor and the optical frame it stamps."""

    sensor_suffix: str  # appended to the instance name to get the sensor name
    optical_suffix: str  # appended to the instance name to get the optical frame
    y_sign: int  # eye offset along y, in units of baseline / 2


@dataclass(frozen=True)
class MacroCase:
    """What one macro file defines and must produce for an instance called ``name``."""

    key: str
    file: str
    macro: str
    kind: str  # camera | depth | stereo | lidar_2d | lidar_3d | imu
    classic_type: str
    gz_type: str
    plugin: str  # key of CLASSIC_PLUGIN
    eyes: tuple[Eye, ...] = ()

    @property
    def path(self) -> Path:
        return MACROS_DIR / self.file

    def links(self, name: str) -> list[str]:
        return [f"{name}_link"] + [f"{name}{eye.optical_suffix}" for eye in self.eyes]

    def joints(self, name: str) -> list[str]:
        optical = [f"{name}{eye.optical_suffix.replace('_frame', '_joint')}" for eye in self.eyes]
        return [f"{name}_joint", *optical]

    def sensors(self, name: str) -> list[str]:
        if self.eyes:
            return [f"{name}{eye.sensor_suffix}" for eye in self.eyes]
        return [name]

    def frame(self, name: str, sensor: str) -> str:
        """The frame id messages of ``sensor`` must carry."""
        for eye in self.eyes:
            if sensor == f"{name}{eye.sensor_suffix}":
                return f"{name}{eye.optical_suffix}"
        return f"{name}_link"

    def expected_topics(self, name: str, sim: str, namespace: str) -> set[str]:
        """Fully qualified ROS (classic) or gz topic names for one instance."""
        ns = namespace.strip("/")
        if sim == "classic":
            base = f"/{ns}/{name}" if ns else f"/{name}"
            return {f"{base}/{t}" for t in CLASSIC_TOPICS[self.kind]}
        if sim == "gz":
            base = f"{ns}/{name}" if ns else name
            return {f"{base}/{t}" for t in GZ_TOPICS[self.kind]}
        return set()


CLASSIC_TOPICS = {
    "camera": ["image_raw", "camera_info"],
    "depth": ["image_raw", "camera_info", "depth/image_raw", "depth/camera_info", "points"],
    "stereo": ["left/image_raw", "left/camera_info", "right/image_raw", "right/camera_info"],
    "lidar_2d": ["scan"],
    "lidar_3d": ["points"],
    "imu": ["imu"],
}

GZ_TOPICS = {
    "camera": ["image_raw", "camera_info"],
    "depth": ["image", "depth_image", "points", "camera_info"],
    "stereo": ["left/image_raw", "left/camera_info", "right/image_raw", "right/camera_info"],
    "lidar_2d": ["scan", "scan/points"],
    "lidar_3d": ["scan", "scan/points"],
    "imu": ["imu"],
}

CENTRE_EYE = (Eye("", "_optical_frame", 0),)
STEREO_EYES = (
    Eye("_left", "_left_optical_frame", +1),
    Eye("_right", "_right_optical_frame", -1),
)

CASES: list[MacroCase] = [
    MacroCase(
        key="camera",
        file="camera.urdf.xacro",
        macro="sensorkit_camera",
        kind="camera",
        classic_type="camera",
        gz_type="camera",
        plugin="camera",
        eyes=CENTRE_EYE,
    ),
    MacroCase(
        key="depth_camera",
        file="depth_camera.urdf.xacro",
        macro="sensorkit_depth_camera",
        kind="depth",
        classic_type="depth",
        gz_type="rgbd_camera",
        plugin="camera",
        eyes=CENTRE_EYE,
    ),
    MacroCase(
        key="stereo_camera",
        file="stereo_camera.urdf.xacro",
        macro="sensorkit_stereo_camera",
        kind="stereo",
        classic_type="camera",
        gz_type="camera",
        plugin="camera",
        eyes=STEREO_EYES,
    ),
    MacroCase(
        key="lidar_2d",
        file="lidar_2d.urdf.xacro",
        macro="sensorkit_lidar_2d",
        kind="lidar_2d",
        classic_type="ray",
        gz_type="gpu_lidar",
        plugin="ray",
    ),
    MacroCase(
        key="lidar_3d",
        file="lidar_3d.urdf.xacro",
        macro="sensorkit_lidar_3d",
        kind="lidar_3d",
        classic_type="ray",
        gz_type="gpu_lidar",
        plugin="ray",
    ),
    MacroCase(
        key="imu",
        file="imu.urdf.xacro",
        macro="sensorkit_imu",
        kind="imu",
        classic_type="imu",
        gz_type="imu",
        plugin="imu",
    ),
]

CASE_IDS = [case.key for case in CASES]
