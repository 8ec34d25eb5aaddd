"""One sensor under one target as its consumers see it, and each of its cameras.

:class:`SensorInfo` (where the sensor is, what it publishes, its geometry) and
:class:`CameraView` (one camera's camera_info, topics and frame) are what
:func:`sensorkit.describe.sensorinfo.describe` fills for every sensor of a robot.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from sensorkit.describe.intrinsics import Intrinsics, LaserScanParams
    from sensorkit.model.sensors import CameraSpec, Sensor
    from sensorkit.model.transforms_np import Mat

__all__ = ["CameraView", "SensorInfo"]


@dataclass
class CameraView:
    """One camera as its consumers see it: camera_info, topics, frame."""

    sensor: Sensor
    spec: CameraSpec
    id: str  # the sensor name; "<sensor>/<camera>" for each camera of a multicamera
    name: str  # the camera_name written into camera_info files
    intrinsics: Intrinsics | None
    error: str | None
    notes: list[str]
    image_topic: str | None
    camera_info_topic: str | None
    frame: str | None  # the frame its images are stamped with

    @property
    def fps(self) -> float | None:
        """The sensor's ``<update_rate>``, when positive."""
        rate = self.sensor.update_rate
        return rate if rate is not None and rate > 0 else None


@dataclass
class SensorInfo:
    """A sensor under one target: where it is, what it publishes, and its geometry."""

    sensor: Sensor
    link: str | None  # its <gazebo reference>, when that is a link
    frame: str | None  # the frame its data is stamped with
    frame_how: str  # frame_name, gz_frame_id, default, ...
    frame_is_default: bool
    body_frame: str | None  # x-forward link at its render pose
    T_world_render: Mat | None
    topics: dict[str, str]
    has_colour: bool = False  # a camera with a colour (or grey) image, not depth only
    topic_notes: list[str] = field(default_factory=list)  # why topics are missing
    cameras: list[CameraView] = field(default_factory=list)
    scan: LaserScanParams | None = None
    vertical: LaserScanParams | None = None
    scan_error: str | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def name(self) -> str:
        return self.sensor.name
