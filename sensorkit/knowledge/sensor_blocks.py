"""What the simulators read of a sensor block beyond the schema table, and how a camera's
calibration reaches camera_info (issue 35 items 2 and 3; rules SK413-SK416).

Every fact carries its source; the repositories were fetched and the lines read:
sdformat (gazebosim/sdformat), Gazebo Classic 11.10.2 (as imported by Debian in
elysia-best/gazebo-classic@upstream/11.10.2+dfsg b64af31), gazebo_ros_pkgs
(ros-simulation/gazebo_ros_pkgs @noetic-devel f9e1a46, @ros2 d52f7c4), gz-sensors
(gazebosim/gz-sensors @ign-sensors6 7cfaddf, @gz-sensors8 c8159af, @gz-sensors10 ff8c92b),
gz-sim (gazebosim/gz-sim @gz-sim8 b81e26d) and gz-rendering (gazebosim/gz-rendering
@ign-rendering6 c39b130, @gz-rendering8 ff0c5b8, @gz-rendering10 af28689).
"""

from __future__ import annotations

# ---------------------------------------------------------------- names in any SDF schema
# Every direct child each element has had in any SDF version: the <element name=...> (and,
# for <sensor>, <include filename=...>) children of sdf/<v>/<element>.sdf for v in 1.0,
# 1.2, ..., 1.12 on gazebosim/sdformat@sdf16 9a26f90 (the branch holds every version's
# files). A name outside this set is in no SDF schema at all: sdformat keeps it as an
# unknown element (sources in sensorkit.knowledge.sdf_schema) and no simulator reads it.
# Names of older versions only (<imu><noise>, <imu><topic>, <camera><frame>, <sensor>
# <origin>/<frame>) are in the set on purpose: an SDF file of that version is converted
# (sdf/1.6/1_5.convert moves <imu><noise> into angular_velocity/linear_acceleration), so
# they are not judged here.
EVER_DEFINED: dict[str, frozenset[str]] = {
    "sensor": frozenset({
        "air_pressure", "air_speed", "altimeter", "always_on", "camera", "contact",
        "enable_metrics", "force_torque", "frame", "frame_id", "gps", "imu", "lidar",
        "logical_camera", "magnetometer", "navsat", "origin", "plugin", "pose", "ray", "rfid",
        "rfidtag", "sonar", "topic", "transceiver", "update_rate", "visualize",
    }),
    "camera": frozenset({
        "box_type", "camera_info_topic", "clip", "depth_camera", "distortion", "frame",
        "horizontal_fov", "image", "lens", "noise", "optical_frame_id", "pose", "save",
        "segmentation_type", "trigger_topic", "triggered", "visibility_mask",
    }),
    "ray": frozenset({"noise", "range", "scan", "visibility_mask"}),
    "lidar": frozenset({"noise", "range", "scan", "visibility_mask"}),
    "imu": frozenset({
        "angular_velocity", "enable_orientation", "linear_acceleration", "noise",
        "orientation_reference_frame", "topic",
    }),
}  # fmt: skip

# ----------------------------------------------------------- the vertical field of view
# No SDF version has a vertical field of view: the renderer derives it from horizontal_fov
# and the image's aspect, vfov = 2 atan(tan(hfov / 2) / (width / height)). Gazebo Classic:
# gazebo/rendering/Camera.cc:2017-2036 (UpdateFOV; with <lens><intrinsics> a custom
# projection instead, :2027-2030). Gazebo Sim: gz-sensors sets the aspect and hfov
# (@gz-sensors8 c8159af:src/CameraSensor.cc:266-267) and gz-rendering's ogre2 camera
# turns them into FOVy (@ign-rendering6 c39b130:ogre2/src/Ogre2Camera.cc:89-90,
# @gz-rendering8 ff0c5b8 and @gz-rendering10 af28689:ogre2/src/Ogre2Camera.cc:182-183;
# depth cameras @gz-rendering8:ogre2/src/Ogre2DepthCamera.cc:440-442).
VFOV_SOURCE = "gazebo-classic 11.10.2 gazebo/rendering/Camera.cc:2026; gz-rendering8 ogre2/src/Ogre2Camera.cc:182"

# What an element in no schema was meant to set, where sensorkit can tell: (element, name)
# -> the role of the value (sensorkit.base.consequence.Role names). Anything else in no
# schema is ignored with a consequence sensorkit cannot tell (info).
MEANT: dict[tuple[str, str], str] = {
    ("camera", "vertical_fov"): "geometry",
    ("camera", "vfov"): "geometry",
    # No SDF version gives the IMU's orientation a noise (see EVER_DEFINED): it is noise-free.
    # Gazebo Classic reads noise from <angular_velocity> and <linear_acceleration> only
    # (gazebo/sensors/ImuSensor.cc:89-150, 11.10.2).
    ("imu", "orientation"): "noise",
}

# ------------------------------------------------------------------- <camera><pose>
# Gazebo Classic renders a camera from its sensor's <pose> composed with <camera><pose>:
# gazebo/sensors/CameraSensor.cc:168-172, DepthCameraSensor.cc:110-114,
# MultiCameraSensor.cc:156-159, WideAngleCameraSensor.cc:115-119 (11.10.2).
# Gazebo Sim renders it from the sensor's pose only: gz-sim gives the sensor entity the
# sensor's <pose> (@gz-sim8 b81e26d:src/SdfEntityCreator.cc:1078), gz-sensors takes the
# sensor's RawPose (@gz-sensors8:src/Sensor.cc:203, @ign-sensors6:src/Sensor.cc:175,
# @gz-sensors10:src/Sensor.cc:205) and puts the rendering camera there
# (@gz-sensors8:src/CameraSensor.cc:221, @ign-sensors6:src/CameraSensor.cc:486,
# @gz-sensors10:src/CameraSensor.cc:156; every camera type alike, @gz-sensors8:
# src/DepthCameraSensor.cc:361, RgbdCameraSensor.cc:328, ThermalCameraSensor.cc:311,
# SegmentationCameraSensor.cc:379, BoundingBoxCameraSensor.cc:331,
# WideAngleCameraSensor.cc:250). sdformat loads <camera><pose> into
# sdf::Camera::RawPose (@sdf12 b9417e5:src/Camera.cc:380-381), which nothing in gz-sim's
# or gz-sensors' src/ reads (`git grep RawPose` on those branches: only the sensor's, and
# gz-sim's msgs conversions).
CAMERA_POSE_READ = {
    "classic": True,
    "ros1": True,
    "fortress": False,
    "harmonic": False,
    "jetty": False,
}
CAMERA_POSE_SOURCE = (
    "gz-sensors8 src/CameraSensor.cc:221 (SetLocalPose(this->Pose()), the sensor's pose; "
    "gz-sim8 src/SdfEntityCreator.cc:1078)"
)

# ------------------------------------------------------------------ hack_baseline
# camera_info P[0][3] = -f * baseline, f the published focal length. ROS 1
# GazeboRosCameraUtils reads <hackBaseline> (default 0) @noetic-devel f9e1a46:
# gazebo_plugins/src/gazebo_ros_camera_utils.cpp:191-197 and writes P[3] at :610; ROS 2
# gazebo_ros_camera reads <hack_baseline> (default 0) @ros2 d52f7c4:gazebo_plugins/src/
# gazebo_ros_camera.cpp:399 and writes p[3] = <Tx> if given, else -f * hack_baseline
# (:458). A monocular camera's P[0][3] is 0 (sensor_msgs/CameraInfo: "For monocular
# cameras, Tx = Ty = 0", ros2/common_interfaces@rolling:sensor_msgs/msg/CameraInfo.msg:93-98).
HACK_BASELINE_TAG = {"ros1": "hackBaseline", "ros2": "hack_baseline"}
HACK_BASELINE_SOURCE = {
    "ros1": "gazebo_ros_pkgs noetic-devel gazebo_plugins/src/gazebo_ros_camera_utils.cpp:191-197, :610",
    "ros2": "gazebo_ros_pkgs ros2 gazebo_plugins/src/gazebo_ros_camera.cpp:399, :458",
}
# ROS 2 only: <Tx> replaces -f * hack_baseline in P[0][3] (gazebo_ros_camera.cpp:458).
ROS2_TX_TAG = "Tx"

# ---------------------------------------------------------------------- distortion
# Where the image is distorted and where camera_info D comes from.
# Gazebo Classic renders <camera><distortion> into the image: gazebo/rendering/Camera.cc
# :184-187 loads it, :1630-1633 attaches it to the camera (11.10.2).
# ROS 2 gazebo_ros_camera fills D from that same distortion (@ros2:gazebo_plugins/src/
# gazebo_ros_camera.cpp:407-414), so D and the image agree.
# ROS 1 GazeboRosCameraUtils fills D from its own <distortionK1..T2> tags, default 0
# (@noetic-devel:gazebo_plugins/src/gazebo_ros_camera_utils.cpp:199-237, D at :580-584),
# and from the SDF distortion only when <autoDistortion> is true (:239-246, :559-566).
ROS1_DISTORTION_TAGS = {
    "k1": "distortionK1",
    "k2": "distortionK2",
    "k3": "distortionK3",
    "p1": "distortionT1",
    "p2": "distortionT2",
}
ROS1_AUTO_DISTORTION_TAG = "autoDistortion"
ROS1_DISTORTION_SOURCE = (
    "gazebo_ros_camera_utils.cpp:199-246, :559-584 (noetic-devel); gazebo-classic "
    "gazebo/rendering/Camera.cc:184-187, :1630-1633"
)
# Gazebo Sim: gz-sensors' CameraSensor renders a non-zero distortion (@gz-sensors8:src/
# CameraSensor.cc:269-285, @gz-sensors10:src/CameraSensor.cc:204-220, @ign-sensors6:
# src/CameraSensor.cc:213-219) and PopulateInfo writes the SDF coefficients into
# camera_info D (@gz-sensors8:src/CameraSensor.cc:716-725, @gz-sensors10:651-660,
# @ign-sensors6:727-735). Depth and RGBD cameras call the same PopulateInfo
# (@gz-sensors8:src/DepthCameraSensor.cc:433, RgbdCameraSensor.cc:383; @gz-sensors10
# :434, :368; @ign-sensors6 :517, :439) but never distort their image ("\todo(nkoenig)
# Port Distortion class": @gz-sensors8:src/DepthCameraSensor.cc:416-418,
# RgbdCameraSensor.cc:374-376; @gz-sensors10 :417-419, :359-361; @ign-sensors6 :522-524,
# :444-446).
# Gazebo Classic's depth image is not distorted either: the distortion compositor goes on
# the camera's main viewport (gazebo/rendering/Distortion.cc:467-473), and a depth camera
# renders depth through a viewport of its own (DepthCamera.cc:223-239, :658-669), while ROS 2
# gazebo_ros_camera publishes depth/camera_info with the same D (gazebo_ros_camera.cpp:697-703,
# D from :407-414). Sensor types Classic creates a depth camera for:
CLASSIC_DEPTH_TYPES = frozenset({"depth", "depth_camera"})
CLASSIC_DEPTH_DISTORTION_SOURCE = (
    "gazebo-classic 11.10.2 gazebo/rendering/Distortion.cc:467-473 (compositor on the main viewport), "
    "DepthCamera.cc:658-669 (the depth viewport); gazebo_ros_camera.cpp:407-414, :697-703 (ros2)"
)
GZ_DISTORTION_NOT_RENDERED = frozenset({"depth", "depth_camera", "rgbd", "rgbd_camera"})
GZ_DISTORTION_SOURCE = (
    "gz-sensors8 src/DepthCameraSensor.cc:416-418, :433 and RgbdCameraSensor.cc:374-376, "
    ":383 (D from PopulateInfo, src/CameraSensor.cc:716-725)"
)
