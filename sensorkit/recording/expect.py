"""What each topic of a recording should be, from what ``describe`` predicts.

One :class:`Expected` per ROS topic a sensor publishes (``sensorkit topics``'s list: on
Gazebo Sim the bridged ones), with the sensor and camera behind it, whose camera_info
(``sensorkit intrinsics``), LaserScan geometry and frames the checks compare with.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from sensorkit.recording.bag import normal_type
from sensorkit.recording.tf import frame_name

if TYPE_CHECKING:
    from sensorkit.describe.sensorinfo import RobotInfo
    from sensorkit.describe.topics import RobotTopics, Topic
    from sensorkit.describe.views import CameraView, SensorInfo

__all__ = ["SENSOR_TYPES", "Expected", "expectations", "ros_frame"]

# Message types of sensor data: a topic of one of these that no sensor of the description
# predicts is said (SK801, info).
SENSOR_TYPES = frozenset(
    {
        "sensor_msgs/msg/Image",
        "sensor_msgs/msg/CompressedImage",
        "sensor_msgs/msg/CameraInfo",
        "sensor_msgs/msg/LaserScan",
        "sensor_msgs/msg/MultiEchoLaserScan",
        "sensor_msgs/msg/PointCloud2",
        "sensor_msgs/msg/PointCloud",
        "sensor_msgs/msg/Imu",
        "sensor_msgs/msg/Range",
        "sensor_msgs/msg/NavSatFix",
        "sensor_msgs/msg/MagneticField",
    }
)


def ros_frame(frame: str) -> str:
    """A predicted frame as a recording holds it: ros_gz_bridge turns ``::`` into ``/`` in
    every frame it carries (gazebosim/ros_gz@jazzy 739cb42:ros_gz_bridge/src/convert/
    utils.cpp:47-49), and tf2 has no leading ``/``."""
    return frame_name(frame.replace("::", "/"))


@dataclass(frozen=True)
class Expected:
    """A topic the description predicts, with the sensor (and camera) that publishes it."""

    topic: Topic
    sensor: SensorInfo
    camera: CameraView | None
    info: RobotInfo  # the robot (and target) the sensor belongs to

    @property
    def name(self) -> str:
        return self.topic.name or ""

    @property
    def type(self) -> str | None:
        return normal_type(self.topic.type) if self.topic.type else None

    @property
    def frame(self) -> str | None:
        return ros_frame(self.topic.frame) if self.topic.frame else None


def expectations(info: RobotInfo, topics: RobotTopics) -> dict[str, Expected]:
    """The published ROS topics of ``topics``, by name (the first sensor of a name that two
    publish: validate's SK605 says so), each with its sensor and camera from ``info``."""
    sensors = {s.name: s for s in info.sensors}
    cameras = {c.id: c for c in info.cameras}
    out: dict[str, Expected] = {}
    for t in topics.ros_topics:
        if t.direction != "publishes" or t.name is None or t.name in out:
            continue
        sensor = sensors.get(t.sensor)
        if sensor is None:
            continue
        camera = cameras.get(t.camera) if t.camera is not None else None
        out[t.name] = Expected(t, sensor, camera, info)
    return out
