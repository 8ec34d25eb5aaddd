"""What the data on each sensor topic is: ROS message types and image encodings.

Consulted by ``sensorkit topics`` (and, through it, by the ``save_frames`` launch file
``sensorkit new`` writes). Roles are those of :func:`sensorkit.describe.sensor_topics.sensor_topics`
(``image``, ``camera_info``, ``depth_image``, ``depth_camera_info``, ``points``, ``scan``,
``range``, ``imu``, ``out``, ``trigger``).

Image encodings, by simulator:

- Gazebo Classic, ROS 2: gazebo_ros_camera turns the sensor's ``<image><format>`` into the
  encoding of the colour image with one table, and any other format into ``bgr8``; its depth
  image is always ``32FC1``.
- Gazebo Classic, ROS 1: gazebo_ros_camera_utils has the same table and fallback; the depth
  camera and openni_kinect plugins publish ``32FC1``, or ``16UC1`` (millimetres) with
  ``<useDepth16UC1Format>true</useDepth16UC1Format>``.
- Gazebo Sim: sdformat reads ``<format>`` into a pixel format, gz-sensors renders the few it
  supports (any other leaves the render camera at its default R8G8B8), and ros_gz_bridge
  maps the gz pixel format to a ROS encoding; a Bayer image has no ROS encoding there, so
  the bridge publishes an Image with an empty encoding and no data. Depth images are
  R_FLOAT32 (``32FC1``); an rgbd_camera's colour image is always RGB_INT8 (``rgb8``).

A missing ``<format>`` is sdformat's default ``R8G8B8``
(gazebosim/sdformat@sdf14:sdf/1.10/camera.sdf:32; @sdf10:sdf/1.7/camera.sdf:20, the SDF
version Gazebo 11 reads).
"""

from __future__ import annotations

SDF_DEFAULT_IMAGE_FORMAT = "R8G8B8"

# --------------------------------------------------------------------------- message types

# ROS 2 message type of each role. gazebo_ros_camera
# (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp):
# image_transport publishers (raw transport: sensor_msgs/msg/Image) at :189 and :243,
# CameraInfo at :202 and :253, PointCloud2 at :262, the std_msgs/Empty trigger subscription
# at :273; gazebo_ros_imu_sensor.cpp:95 Imu; gazebo_ros_ray_sensor.cpp:124 LaserScan and
# :133 Range (its other outputs: RAY_OUTPUT_MESSAGES).
ROS2_ROLE_TYPES: dict[str, str] = {
    "image": "sensor_msgs/msg/Image",
    "camera_info": "sensor_msgs/msg/CameraInfo",
    "depth_image": "sensor_msgs/msg/Image",
    "depth_camera_info": "sensor_msgs/msg/CameraInfo",
    "points": "sensor_msgs/msg/PointCloud2",
    "scan": "sensor_msgs/msg/LaserScan",
    "range": "sensor_msgs/msg/Range",
    "imu": "sensor_msgs/msg/Imu",
    "trigger": "std_msgs/msg/Empty",
}

# gazebo_ros_ray_sensor publishes what <output_type> names (gazebo_ros_ray_sensor.cpp:122-134);
# without it PointCloud2 (:116-120); any other value: "Invalid <output_type>" and no
# publisher (:135-138).
RAY_OUTPUT_MESSAGES: dict[str, str] = {
    "sensor_msgs/LaserScan": "sensor_msgs/msg/LaserScan",
    "sensor_msgs/PointCloud": "sensor_msgs/msg/PointCloud",
    "sensor_msgs/PointCloud2": "sensor_msgs/msg/PointCloud2",
    "sensor_msgs/Range": "sensor_msgs/msg/Range",
}
RAY_DEFAULT_OUTPUT = "sensor_msgs/PointCloud2"

# The "out" topic of ROS 2 sensor plugins other than camera, ray and IMU, by library:
# gazebo_ros_gps_sensor.cpp:79 NavSatFix.
ROS2_OUT_TYPES: dict[str, str] = {"gazebo_ros_gps_sensor": "sensor_msgs/msg/NavSatFix"}

# ROS 1 (ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a46, gazebo_plugins/src/): camera
# topics as on ROS 2 (Image, CameraInfo; gazebo_ros_depth_camera.cpp:149 and
# gazebo_ros_openni_kinect.cpp:123 PointCloud2); the others by plugin library:
# gazebo_ros_laser.cpp:143 and gazebo_ros_gpu_laser.cpp:146 LaserScan,
# gazebo_ros_block_laser.cpp:178 PointCloud, gazebo_ros_range.cpp:208 Range,
# gazebo_ros_imu_sensor.cpp:85 and gazebo_ros_imu.cpp:169 Imu.
ROS1_LIBRARY_TYPES: dict[str, str] = {
    "gazebo_ros_laser": "sensor_msgs/LaserScan",
    "gazebo_ros_gpu_laser": "sensor_msgs/LaserScan",
    "gazebo_ros_block_laser": "sensor_msgs/PointCloud",
    "gazebo_ros_range": "sensor_msgs/Range",
    "gazebo_ros_imu_sensor": "sensor_msgs/Imu",
    "gazebo_ros_imu": "sensor_msgs/Imu",
}


def ros1_type(ros2_type: str) -> str:
    """``sensor_msgs/msg/Image`` as ROS 1 spells it: ``sensor_msgs/Image``."""
    return ros2_type.replace("/msg/", "/")


# --------------------------------------------------------------------------- encodings

# Gazebo Classic colour images: <image><format> -> sensor_msgs encoding.
# ROS 2: gazebo_ros_camera.cpp:296-335 (ros2 d52f7c4); ROS 1: the same table in
# gazebo_plugins/src/gazebo_ros_camera_utils.cpp:447-494 (noetic-devel f9e1a46).
CLASSIC_IMAGE_ENCODINGS: dict[str, str] = {
    "L8": "mono8",
    "L_INT8": "mono8",
    "L16": "mono16",
    "L_INT16": "mono16",
    "R8G8B8": "rgb8",
    "RGB_INT8": "rgb8",
    "B8G8R8": "bgr8",
    "BGR_INT8": "bgr8",
    "R16G16B16": "rgb16",
    "RGB_INT16": "rgb16",
    "BAYER_RGGB8": "bayer_rggb8",
    "BAYER_BGGR8": "bayer_bggr8",
    "BAYER_GBRG8": "bayer_gbrg8",
    "BAYER_GRBG8": "bayer_grbg8",
}
# Any other format: "Unsupported Gazebo ImageFormat, using BGR8" (gazebo_ros_camera.cpp:336-340;
# ROS 1 gazebo_ros_camera_utils.cpp:496-500).
CLASSIC_UNSUPPORTED_ENCODING = "bgr8"
# gazebo_ros_camera's depth image: TYPE_32FC1, metres (gazebo_ros_camera.cpp:660-667).
CLASSIC_DEPTH_ENCODING = "32FC1"
# ROS 1 depth plugins: 32FC1, or 16UC1 when <useDepth16UC1Format> is true
# (gazebo_ros_depth_camera.cpp:136-140, :737-746; gazebo_ros_openni_kinect.cpp:111-114, :431-438).
ROS1_DEPTH_16UC1_PARAM = "useDepth16UC1Format"
ROS1_DEPTH_LIBRARIES = frozenset({"gazebo_ros_depth_camera", "gazebo_ros_openni_kinect"})

# Gazebo Sim. sdformat reads <format> into sdf::PixelFormatType: its own names
# (kPixelFormatNames) and the old ones below; anything else is UNKNOWN_PIXEL_FORMAT
# (gazebosim/sdformat@sdf14:src/Camera.cc:28-49, :1157-1186; @sdf12 (Fortress) :26-47,
# :1155-1184; @sdf16 (Jetty) :28-49, :1134-1163).
SDF_PIXEL_FORMAT_NAMES = frozenset(
    {
        "L_INT8", "L_INT16", "RGB_INT8", "RGBA_INT8", "BGRA_INT8", "RGB_INT16", "RGB_INT32",
        "BGR_INT8", "BGR_INT16", "BGR_INT32", "R_FLOAT16", "RGB_FLOAT16", "R_FLOAT32",
        "RGB_FLOAT32", "BAYER_RGGB8", "BAYER_BGGR8", "BAYER_GBRG8", "BAYER_GRBG8",
    }
)  # fmt: skip
SDF_OLD_PIXEL_FORMATS: dict[str, str] = {
    "R8G8B8": "RGB_INT8",
    "L8": "L_INT8",
    "L16": "L_INT16",
    "B8G8R8": "BGR_INT8",
    "BAYER_RGGB8": "BAYER_RGGB8",
    "BAYER_BGGR8": "BAYER_BGGR8",
    "BAYER_GBRG8": "BAYER_GBRG8",
    "BAYER_GRBG8": "BAYER_GRBG8",
}
# The pixel formats a gz-sensors camera renders, by target; any other: "Unsupported pixel
# format" and the render camera keeps its default PF_R8G8B8, published as RGB_INT8.
# gazebosim/gz-sensors@ign-sensors6 7cfaddf:src/CameraSensor.cc:222-238 (no Bayer on Fortress),
# @gz-sensors8 c8159af:src/CameraSensor.cc:288-316 and :527-571, @gz-sensors10
# ff8c92b:src/CameraSensor.cc:223-251; the default: gazebosim/gz-rendering@ign-rendering6
# c39b130a:include/gz/rendering/base/BaseCamera.hh:479, @gz-rendering8
# ff0c5b8f:...BaseCamera.hh:496, @gz-rendering10 af28689e:...BaseCamera.hh:497.
_GZ_BAYER = frozenset({"BAYER_RGGB8", "BAYER_BGGR8", "BAYER_GBRG8", "BAYER_GRBG8"})
GZ_CAMERA_PIXEL_FORMATS: dict[str, frozenset[str]] = {
    "fortress": frozenset({"RGB_INT8", "L_INT8", "L_INT16"}),
    "harmonic": frozenset({"RGB_INT8", "L_INT8", "L_INT16"}) | _GZ_BAYER,
    "jetty": frozenset({"RGB_INT8", "L_INT8", "L_INT16"}) | _GZ_BAYER,
}
GZ_CAMERA_FALLBACK_FORMAT = "RGB_INT8"
# Depth images: R_FLOAT32 (gz-sensors8:src/DepthCameraSensor.cc:585, RgbdCameraSensor.cc:525);
# an rgbd_camera's colour image is RGB_INT8 whatever <format> says (RgbdCameraSensor.cc:636;
# ign-sensors6 :691, gz-sensors10 :617).
GZ_DEPTH_PIXEL_FORMAT = "R_FLOAT32"
GZ_RGBD_IMAGE_PIXEL_FORMAT = "RGB_INT8"
# ros_gz_bridge, gz.msgs.Image -> sensor_msgs/msg/Image: pixel format -> encoding
# (gazebosim/ros_gz@humble 5cc92f8:ros_gz_bridge/src/convert/sensor_msgs.cpp:126-160, the
# same lines @jazzy 739cb42). Any other: "Unsupported pixel format" and return before
# encoding and data are set (:161-165), and the message is published as it is
# (ros_gz_bridge/src/factory.hpp:146-150).
ROS_GZ_ENCODINGS: dict[str, str] = {
    "L_INT8": "mono8",
    "L_INT16": "mono16",
    "RGB_INT8": "rgb8",
    "RGBA_INT8": "rgba8",
    "BGRA_INT8": "bgra8",
    "RGB_INT16": "rgb16",
    "BGR_INT8": "bgr8",
    "BGR_INT16": "bgr16",
    "R_FLOAT32": "32FC1",
}

# --------------------------------------------------------------------------- point clouds

# The fields of the sensor_msgs/PointCloud2 a simulator publishes, by ROS generation and
# sensor kind (``sensorkit check-recording`` compares a recorded cloud with them).
# Gazebo Classic, ROS 2: gazebo_ros_camera's depth cloud x y z rgb, FLOAT32
# (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:481-497);
# gazebo_ros_ray_sensor's PointCloud2 x y z intensity, FLOAT32
# (@ros2 d52f7c4:gazebo_ros/include/gazebo_ros/conversions/sensor_msgs.hpp:213-218).
# Gazebo Sim through ros_gz_bridge (PointCloudPacked's fields as they are): depth_camera and
# rgbd_camera "xyz" and rgb (gazebosim/gz-sensors@gz-sensors8 c8159af:
# src/DepthCameraSensor.cc:446-451, src/RgbdCameraSensor.cc:397-400), gpu_lidar "xyz",
# intensity and ring (src/GpuLidarSensor.cc:138-141); "xyz" becomes the fields x, y, z
# (gazebosim/gz-msgs@gz-msgs10 292056c:core/include/gz/msgs/PointCloudPackedUtils.hh:98-103).
# ROS 1 plugins are not listed: their clouds are not checked beyond x, y, z.
POINT_CLOUD_FIELDS: dict[tuple[str, str], tuple[str, ...]] = {
    ("ros2", "depth"): ("x", "y", "z", "rgb"),
    ("ros2", "lidar"): ("x", "y", "z", "intensity"),
    ("gz", "depth"): ("x", "y", "z", "rgb"),
    ("gz", "rgbd"): ("x", "y", "z", "rgb"),
    ("gz", "lidar"): ("x", "y", "z", "intensity", "ring"),
}
# Without these a cloud cannot be placed at all.
POINT_CLOUD_XYZ: tuple[str, ...] = ("x", "y", "z")
