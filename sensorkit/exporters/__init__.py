"""Exporters: pure functions from intrinsics and scan geometry to configuration text.

Each returns a string (or, for JSON, a dict) and never touches the file system;
:func:`sensorkit.base.atomic.write_text` publishes any of them safely. Reals are written exactly
(``repr``, always with a decimal point), ints without one, so each reader sees the
kind it checks for.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sensorkit.base.lazy import lazy_exports

if TYPE_CHECKING:
    from sensorkit.exporters.bridge import bridge_yaml
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

# Each name's module, imported on first use (PEP 562): a command that needs one
# exporter (render preview: camera_info and camera_dict) does not import the other
# six (some 7 ms of start-up).
_MODULE = {
    "OrbExtractorSettings": "orbslam3",
    "OrbImuSettings": "orbslam3",
    "ViewerSettings": "orbslam3",
    "amcl_yaml": "lidar",
    "bridge_yaml": "bridge",
    "camera_dict": "data",
    "camera_info_yaml": "camera_info",
    "depthimage_to_laserscan_remappings": "depth_scan",
    "depthimage_to_laserscan_yaml": "depth_scan",
    "kalibr_camchain_yaml": "kalibr",
    "kalibr_stereo_camchain_yaml": "kalibr",
    "laser_scan_dict": "data",
    "nav2_obstacle_layer_yaml": "lidar",
    "opencv_yaml": "opencv",
    "orbslam3_stereo_yaml": "orbslam3",
    "orbslam3_yaml": "orbslam3",
    "scan_yaml": "lidar",
    "slam_toolbox_yaml": "lidar",
    "stereo_camera_infos": "camera_info",
    "to_json": "data",
}


__getattr__ = lazy_exports(__name__, _MODULE, globals())


def __dir__() -> list[str]:
    return sorted({*globals(), *_MODULE})


__all__ = [
    "OrbExtractorSettings",
    "OrbImuSettings",
    "ViewerSettings",
    "amcl_yaml",
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
    "slam_toolbox_yaml",
    "stereo_camera_infos",
    "to_json",
]
