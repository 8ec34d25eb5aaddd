"""Exporters: pure functions from intrinsics and scan geometry to configuration text.

Each returns a string (or, for JSON, a dict) and never touches the file system;
:func:`sensorkit.atomic.write_text` publishes any of them safely. Reals are written exactly
(``repr``, always with a decimal point), ints without one, so each reader sees the
kind it checks for.
"""

from __future__ import annotations

from sensorkit.exporters.bridge import (
    BridgeEntry,
    bridge_types,
    bridge_yaml,
    sensor_bridge_entries,
)
from sensorkit.exporters.camera_info import camera_info_yaml, stereo_camera_infos
from sensorkit.exporters.data import camera_dict, laser_scan_dict, to_json
from sensorkit.exporters.depth_scan import (
    depthimage_to_laserscan_remappings,
    depthimage_to_laserscan_yaml,
)
from sensorkit.exporters.kalibr import kalibr_camchain_yaml, kalibr_stereo_camchain_yaml
from sensorkit.exporters.lidar import (
    amcl_yaml,
    nav2_obstacle_layer_yaml,
    scan_yaml,
    slam_toolbox_yaml,
)
from sensorkit.exporters.opencv import opencv_yaml
from sensorkit.exporters.orbslam3 import (
    OrbExtractorSettings,
    OrbImuSettings,
    ViewerSettings,
    orbslam3_stereo_yaml,
    orbslam3_yaml,
)

__all__ = [
    "BridgeEntry",
    "OrbExtractorSettings",
    "OrbImuSettings",
    "ViewerSettings",
    "amcl_yaml",
    "bridge_types",
    "bridge_yaml",
    "camera_dict",
    "camera_info_yaml",
    "depthimage_to_laserscan_remappings",
    "depthimage_to_laserscan_yaml",
    "kalibr_camchain_yaml",
    "kalibr_stereo_camchain_yaml",
    "laser_scan_dict",
    "nav2_obstacle_layer_yaml",
    "opencv_yaml",
    "orbslam3_stereo_yaml",
    "orbslam3_yaml",
    "scan_yaml",
    "sensor_bridge_entries",
    "slam_toolbox_yaml",
    "stereo_camera_infos",
    "to_json",
]
