"""Gazebo Sim (Fortress, Harmonic, Jetty) facts consulted by rules, bridge generation and auto.

Sensor types that sdformat parses but gz-sim never creates, with what to use instead:

- ``ray`` and ``lidar`` parse as ``SensorType::LIDAR`` (gazebosim/sdformat@sdf14:
  src/Sensor.cc:383-390); gz-sim creates no CPU lidar: "Sensor type LIDAR not supported yet.
  Try using a GPU LIDAR instead." (gazebosim/gz-sim@gz-sim8:src/SdfEntityCreator.cc:1092-1098;
  @ign-gazebo6:src/SdfEntityCreator.cc:917; @gz-sim10:src/SdfEntityCreator.cc:1131).
- ``multicamera`` parses as ``SensorType::MULTICAMERA`` (sdformat@sdf14:src/Sensor.cc:379-382)
  and has no branch in SdfEntityCreator: "Sensor type [...] not supported yet."
  (gz-sim@gz-sim8:src/SdfEntityCreator.cc:1227-1229; @ign-gazebo6:1031; @gz-sim10:1263).

Such a sensor publishes nothing on any Gazebo Sim version, so it is never bridged and never
counted as evidence that a description targets Gazebo Sim.
"""

from __future__ import annotations

GZ_UNSUPPORTED_SENSOR_TYPES: dict[str, str] = {
    "ray": 'type="gpu_lidar" with a <lidar> block',
    "lidar": 'type="gpu_lidar" (the CPU lidar is not implemented)',
    "multicamera": 'one <sensor type="camera"> per eye, each with its own <topic>',
}


# Depth and RGB-D clouds: gz-sensors computes them in its rendering convention, x forward,
# but stamps them with the camera's optical frame (z forward): "Gazebo uses the +x forward
# convention for all rendering sensors" (https://github.com/gazebosim/gz-sensors/issues/488,
# open; also #29). RgbdCameraSensor stamps the cloud with OpticalFrameId()
# (gazebosim/gz-sensors@gz-sensors8:src/RgbdCameraSensor.cc:397) and fills x, y, z as rendered
# (src/PointCloudUtil.cc:189-209); DepthCameraSensor likewise (src/DepthCameraSensor.cc:446-448).
GZ_XFORWARD_CLOUD_TYPES = frozenset({"depth_camera", "depth", "rgbd_camera", "rgbd"})
GZ_XFORWARD_CLOUD_NOTE = (
    "Gazebo Sim computes depth-camera clouds x-forward but stamps them with the optical frame "
    "(gz-sensors#488)"
)
CLOUD_FIX = (
    "build the cloud in ROS from the depth image and camera_info with depth_image_proc "
    "(point_cloud_xyz / point_cloud_xyzrgb), and do not bridge <topic>/points"
)


# Which camera sensors read <camera><camera_info_topic>: only CameraSensor::Load does
# (gazebosim/gz-sensors@gz-sensors8:src/CameraSensor.cc:389-392). DepthCameraSensor::Load
# calls Sensor::Load, not CameraSensor::Load (src/DepthCameraSensor.cc:245-249), so its
# camera_info goes to the default, a sibling "camera_info" of its topic (CameraSensor.cc:
# 662-674); RgbdCameraSensor always uses TOPIC/camera_info (src/RgbdCameraSensor.cc:252).
GZ_READS_CAMERA_INFO_TOPIC = frozenset({"camera", "wideanglecamera", "wide_angle_camera"})
# Which read <camera><depth_camera><clip>: RgbdCameraSensor does
# (src/RgbdCameraSensor.cc:313-322); DepthCameraSensor renders depth within the camera's own
# <clip> (src/DepthCameraSensor.cc:349-358).
GZ_READS_DEPTH_CLIP = frozenset({"rgbd_camera", "rgbd"})


# Which sensors stamp their data with gz-sensors' Sensor::FrameId(): the frame tag the
# version reads, else the sensor's name (sensorkit.model.frames.GZ_FRAME_TAGS), which gz-sim
# sets to MODEL::LINK::SENSOR. SK501 warns for them when they have no frame tag.
# By kind (sensorkit.model.sensors): cameras (gazebosim/gz-sim@gz-sim8:
# src/rendering/RenderUtil.cc:1719-1721), lidars (gz-sensors@gz-sensors8:src/Lidar.cc:260-266)
# and IMUs (gz-sensors8:src/ImuSensor.cc:255-257, named by gz-sim8:src/systems/imu/Imu.cc:194-197).
GZ_FRAMED_KINDS = frozenset({"camera", "depth", "rgbd", "multicamera", "lidar", "imu"})
