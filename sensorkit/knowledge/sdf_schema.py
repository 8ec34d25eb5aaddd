"""Which children sdformat's schema allows in ``<sensor>``, ``<camera>``, ``<ray>``, ``<lidar>``, ``<imu>``.

A ``<gazebo reference>`` block of a URDF is pasted into the SDF that sdformat converts the
URDF to, and read against the schema of the sdformat the simulator links. An element the
schema does not define there is not an error: sdformat copies it as an unknown child
(gazebosim/sdformat@sdf9 9ee2d4f:src/parser.cc:1129-1140, logged with sdfdbg only; @sdf12
b9417e5:src/parser.cc:1867-1895 and @sdf14 8512585 / @sdf16 9a26f90:src/parser.cc:2016-2044,
a warning by the unrecognized-elements policy, and never for a name with a ``:`` prefix).
Nothing in the sensor reads it there: ``<camera>`` settings are read from ``<camera>``, so a
camera whose ``<image>`` sits directly under ``<sensor>`` runs at the default 320x240.

Which sdformat a target reads: Gazebo Classic 11 (targets classic, ros1) links sdformat9
(elysia-best/gazebo-classic@upstream/11.10.2+dfsg:cmake/SearchForStuff.cmake:612
``find_package(sdformat9 ...)``), Fortress sdformat12, Harmonic sdformat14, Jetty sdformat16
(see :mod:`sensorkit.knowledge.gazebo_sim`). sdformat converts the URDF as SDF 1.7 (@sdf9
:src/parser_urdf.cc:3334, @sdf12 :3410) or 1.11 (@sdf14 :3425, @sdf16 :3425) and up-converts
it to its own protocol version (CMakeLists.txt ``SDF_PROTOCOL_VERSION``: 1.7 @sdf9:27, 1.9
@sdf12:12, 1.11 @sdf14:12, 1.12 @sdf16:12), whose schema is the one that applies.

The table below is ours: the names of the direct children of each element, read from
``sdf/<version>/<element>.sdf`` of each branch, each with the line that defines it (an
``<element name=...>``, or for ``<sensor>`` mostly an ``<include filename=...>`` whose file
defines the element). None of these elements copies its children wholesale (no ``copy_data``).
"""

from __future__ import annotations

from dataclasses import dataclass

from sensorkit.base.consequence import Role

# target -> the sdformat branch it reads, its commit and the protocol version its schema is.
SDFORMAT_OF_TARGET = {
    "classic": "sdf9",
    "ros1": "sdf9",
    "fortress": "sdf12",
    "harmonic": "sdf14",
    "jetty": "sdf16",
}
_REFS = {
    "sdf9": ("9ee2d4f", "1.7"),
    "sdf12": ("b9417e5", "1.9"),
    "sdf14": ("8512585", "1.11"),
    "sdf16": ("9a26f90", "1.12"),
}

# branch -> element -> {child name: line of its definition in sdf/<version>/<element>.sdf}
_CHILDREN: dict[str, dict[str, dict[str, int]]] = {
    "sdf9": {
        "sensor": {"always_on": 38, "update_rate": 42, "visualize": 46, "topic": 50, "enable_metrics": 54, "pose": 58, "plugin": 59, "air_pressure": 60, "altimeter": 61, "camera": 62, "contact": 63, "force_torque": 64, "gps": 65, "imu": 66, "lidar": 67, "logical_camera": 68, "magnetometer": 69, "navsat": 70, "ray": 71, "rfidtag": 72, "rfid": 73, "sonar": 74, "transceiver": 75},
        "camera": {"camera_info_topic": 8, "horizontal_fov": 12, "image": 16, "clip": 32, "save": 44, "depth_camera": 54, "noise": 72, "distortion": 85, "lens": 107, "visibility_mask": 186, "pose": 190},
        "ray": {"scan": 4, "range": 48, "noise": 61},
        "lidar": {"scan": 4, "range": 48, "noise": 61},
        "imu": {"orientation_reference_frame": 4, "angular_velocity": 83, "linear_acceleration": 100, "enable_orientation": 117},
    },
    "sdf12": {
        "sensor": {"always_on": 41, "update_rate": 45, "visualize": 49, "topic": 53, "enable_metrics": 57, "pose": 61, "plugin": 62, "air_pressure": 63, "altimeter": 64, "camera": 65, "contact": 66, "force_torque": 67, "gps": 68, "imu": 69, "lidar": 70, "logical_camera": 71, "magnetometer": 72, "navsat": 73, "ray": 74, "rfidtag": 75, "rfid": 76, "sonar": 77, "transceiver": 78},
        "camera": {"camera_info_topic": 8, "triggered": 12, "trigger_topic": 16, "horizontal_fov": 20, "image": 24, "clip": 40, "save": 52, "depth_camera": 62, "segmentation_type": 80, "box_type": 94, "noise": 107, "distortion": 120, "lens": 142, "visibility_mask": 221, "optical_frame_id": 225, "pose": 229},
        "ray": {"scan": 4, "range": 48, "noise": 61, "visibility_mask": 74},
        "lidar": {"scan": 4, "range": 48, "noise": 61, "visibility_mask": 74},
        "imu": {"orientation_reference_frame": 4, "angular_velocity": 83, "linear_acceleration": 100, "enable_orientation": 117},
    },
    "sdf14": {
        "sensor": {"always_on": 42, "update_rate": 46, "visualize": 50, "topic": 54, "enable_metrics": 58, "pose": 62, "plugin": 63, "air_pressure": 64, "air_speed": 65, "altimeter": 66, "camera": 67, "contact": 68, "force_torque": 69, "gps": 70, "imu": 71, "lidar": 72, "logical_camera": 73, "magnetometer": 74, "navsat": 75, "ray": 76, "rfidtag": 77, "rfid": 78, "sonar": 79, "transceiver": 80},
        "camera": {"triggered": 8, "camera_info_topic": 12, "trigger_topic": 16, "horizontal_fov": 20, "image": 24, "clip": 40, "save": 52, "depth_camera": 62, "segmentation_type": 80, "box_type": 94, "noise": 107, "distortion": 120, "lens": 142, "visibility_mask": 221, "optical_frame_id": 225, "pose": 229},
        "ray": {"scan": 4, "range": 48, "noise": 61, "visibility_mask": 74},
        "lidar": {"scan": 4, "range": 48, "noise": 61, "visibility_mask": 74},
        "imu": {"orientation_reference_frame": 4, "angular_velocity": 83, "linear_acceleration": 100, "enable_orientation": 117},
    },
    "sdf16": {
        "sensor": {"always_on": 42, "update_rate": 46, "visualize": 50, "topic": 54, "enable_metrics": 58, "frame_id": 62, "pose": 66, "plugin": 67, "air_pressure": 68, "air_speed": 69, "altimeter": 70, "camera": 71, "contact": 72, "force_torque": 73, "gps": 74, "imu": 75, "lidar": 76, "logical_camera": 77, "magnetometer": 78, "navsat": 79, "ray": 80, "rfidtag": 81, "rfid": 82, "sonar": 83, "transceiver": 84},
        "camera": {"triggered": 8, "camera_info_topic": 12, "trigger_topic": 16, "horizontal_fov": 20, "image": 24, "clip": 40, "save": 52, "depth_camera": 62, "segmentation_type": 80, "box_type": 94, "noise": 107, "distortion": 120, "lens": 142, "visibility_mask": 221, "optical_frame_id": 225, "pose": 229},
        "ray": {"scan": 4, "range": 48, "noise": 61, "visibility_mask": 74},
        "lidar": {"scan": 4, "range": 48, "noise": 61, "visibility_mask": 74},
        "imu": {"orientation_reference_frame": 4, "angular_velocity": 83, "linear_acceleration": 100, "enable_orientation": 117},
    },
}  # fmt: skip

# Read by the simulator from an element although the schema does not define it there (or
# not in every version), so never reported as lost: the gz frame tags, read from <sensor>
# by gz-sensors (gazebosim/gz-sensors@ign-sensors6 7cfaddf:src/Sensor.cc:148-158,
# @gz-sensors8 c8159af:src/Sensor.cc:188, @gz-sensors10 ff8c92b:src/Sensor.cc:187) and
# checked where they are by SK608. Not <optical_frame_id>: sdformat reads it from <camera>
# only (gazebosim/sdformat@sdf12 b9417e5:src/Camera.cc:383-388, @sdf14 8512585:385-390), so
# one written directly under <sensor> is lost like any other camera setting there (SK410).
READ_ANYWAY = frozenset({"gz_frame_id", "ignition_frame_id", "frame_id"})

# What the camera runs with when a setting is missing from <camera> (sdf/<v>/camera.sdf:
# horizontal_fov default 1.047 @sdf9:12, @sdf12/@sdf14/@sdf16:20; image width 320, height
# 240 @sdf9:18,21, else :26,29; clip near .1, far 100 @sdf9:35,39, else :43,47).
CAMERA_DEFAULTS = {
    "image": "320x240",
    "horizontal_fov": "1.047 rad",
    "clip": "near 0.1 m, far 100 m",
}
# The same defaults as values, to compare with what a misplaced setting holds (issue 35:
# a setting sdformat never reads whose value is the default that applies anyway changes
# nothing). Image format default R8G8B8: gazebosim/sdformat@sdf9 9ee2d4f:sdf/1.7/camera.sdf:24.
# Sensor-level: always_on false, update_rate 0, visualize false (sdf/1.7/sensor.sdf:38, 42, 46).
SETTING_DEFAULTS: dict[tuple[str, str], float | str | dict[str, float | str]] = {
    ("camera", "horizontal_fov"): 1.047,
    ("camera", "image"): {"width": 320, "height": 240, "format": "R8G8B8"},
    ("camera", "clip"): {"near": 0.1, "far": 100},
    ("sensor", "update_rate"): 0,
    ("sensor", "always_on"): "false",
    ("sensor", "visualize"): "false",
}
# What a sensor setting does for the data ROS receives (sensorkit.base.consequence.Role), by
# element name; any other name of <camera>, <ray>/<lidar> or <imu> sets the data's geometry.
SETTING_ROLE: dict[str, Role] = {
    "noise": Role.NOISE,
    "angular_velocity": Role.NOISE,
    "linear_acceleration": Role.NOISE,
    "distortion": Role.CALIBRATION,
    "lens": Role.CALIBRATION,
    "save": Role.FLAG,
    "depth_camera": Role.FLAG,
    "plugin": Role.OUTPUT,
    "update_rate": Role.RATE,
    "topic": Role.TOPIC,
    "always_on": Role.FLAG,
    "enable_metrics": Role.FLAG,
    "visualize": Role.COSMETIC,
    "pose": Role.GEOMETRY,
    "frame": Role.FRAME,
    # <optical_frame_id> is read from <camera> only (sdformat Camera.cc:383-388 sdf12,
    # :385-390 sdf14): misplaced, the images keep the frame the sensor would stamp anyway.
    "optical_frame_id": Role.FRAME,
}


@dataclass(frozen=True)
class Schema:
    """The children one sdformat allows in one element, and where that is written."""

    branch: str
    version: str
    element: str
    children: frozenset[str]

    def cite(self, name: str | None = None) -> str:
        commit = _REFS[self.branch][0]
        path = f"gazebosim/sdformat@{self.branch} {commit}:sdf/{self.version}/{self.element}.sdf"
        if name is None or name not in self.children:
            return path
        return f"{path}:{_CHILDREN[self.branch][self.element][name]}"


def schema(target: str, element: str) -> Schema | None:
    """The schema ``target``'s sdformat applies to ``element`` (sensor, camera, ray, lidar, imu)."""
    branch = SDFORMAT_OF_TARGET.get(target)
    if branch is None or element not in _CHILDREN[branch]:
        return None
    return Schema(branch, _REFS[branch][1], element, frozenset(_CHILDREN[branch][element]))
