"""gazebo_ros_pkgs by ROS generation: which plugin names exist, ROS 1 tags and their ROS 2 forms.

Plugin names are the library base names without ``libgazebo_ros_`` and ``.so``. Read from
ros-simulation/gazebo_ros_pkgs: ROS 2 ``gazebo_plugins/CMakeLists.txt`` (branch ``ros2``)
and ROS 1 ``gazebo_plugins/CMakeLists.txt`` (branch ``noetic-devel``); per-plugin
parameters and frames live in :mod:`sensorkit.knowledge.plugins`.
"""

from __future__ import annotations

from sensorkit.base.consequence import Role

# Gazebo Classic itself, lidar <range><min> 0 (the SDF default, gazebosim/sdformat@sdf12
# b9417e5:sdf/1.6/ray.sdf:50). A CPU `ray` sensor uses min only as each ray's start point
# (`start = (axis * minRange) + offset.Pos()`) and measures max - min from there
# (MultiRayShape::Init and ::Update in gazebo/physics/MultiRayShape.cc), so 0 is legal. That
# was read in the stored gazebosim/gazebo-classic history (a9bef0c and a later
# ignition::math version); the gazebo11 branch could not be fetched (snapshot over the size
# limit), so it is not pinned to gazebo11 lines. A `gpu_ray` passes min as its GPU laser
# camera's near clip (GpuRaySensor.cc: laserCam->SetNearClip(RangeMin())), and Ogre 1.x, like
# ogre-next, throws on a near clip <= 0; that path was not verified on gazebo11 either, so
# SK406 only notes it (info), never as an error.
CLASSIC_LIDAR_NEAR_CLIP_TYPES = frozenset({"gpu_ray"})

# Every plugin library gazebo_ros_pkgs builds, by generation (names without lib/.so).
# ROS 1: ros-simulation/gazebo_ros_pkgs@noetic-devel (f9e1a46):gazebo_plugins/CMakeLists.txt:191-340
# (add_library lines), gazebo_ros/CMakeLists.txt:91,97, gazebo_ros_control/CMakeLists.txt:69.
ROS1_LIBRARIES = frozenset(
    {
        "gazebo_ros_camera", "gazebo_ros_triggered_camera", "gazebo_ros_elevator",
        "gazebo_ros_multicamera", "gazebo_ros_triggered_multicamera", "gazebo_ros_depth_camera",
        "gazebo_ros_openni_kinect", "gazebo_ros_gpu_laser", "gazebo_ros_harness",
        "gazebo_ros_wheel_slip", "gazebo_ros_laser", "gazebo_ros_block_laser", "gazebo_ros_p3d",
        "gazebo_ros_imu", "gazebo_ros_imu_sensor", "gazebo_ros_f3d", "gazebo_ros_bumper",
        "gazebo_ros_projector", "gazebo_ros_prosilica", "gazebo_ros_force",
        "gazebo_ros_joint_state_publisher", "gazebo_ros_joint_pose_trajectory",
        "gazebo_ros_diff_drive", "gazebo_ros_tricycle_drive", "gazebo_ros_skid_steer_drive",
        "gazebo_ros_video", "gazebo_ros_planar_move", "gazebo_ros_hand_of_god",
        "gazebo_ros_ft_sensor", "gazebo_ros_range", "gazebo_ros_vacuum_gripper",
        "gazebo_ros_template", "gazebo_ros_utils", "gazebo_ros_camera_utils",
        "gazebo_ros_api_plugin", "gazebo_ros_paths_plugin", "gazebo_ros_control",
    }
)  # fmt: skip
# ROS 2: ros-simulation/gazebo_ros_pkgs@ros2 (d52f7c4):gazebo_plugins/CMakeLists.txt:57-457
# and gazebo_ros/CMakeLists.txt:42-144.
ROS2_LIBRARIES = frozenset(
    {
        "gazebo_ros_joint_state_publisher", "gazebo_ros_diff_drive", "gazebo_ros_force",
        "gazebo_ros_template", "gazebo_ros_camera", "gazebo_ros_imu_sensor",
        "gazebo_ros_gps_sensor", "gazebo_ros_ray_sensor", "gazebo_ros_p3d",
        "gazebo_ros_tricycle_drive", "gazebo_ros_video", "gazebo_ros_ft_sensor",
        "gazebo_ros_bumper", "gazebo_ros_harness", "gazebo_ros_hand_of_god",
        "gazebo_ros_ackermann_drive", "gazebo_ros_elevator", "gazebo_ros_vacuum_gripper",
        "gazebo_ros_joint_pose_trajectory", "gazebo_ros_planar_move", "gazebo_ros_projector",
        "gazebo_ros_wheel_slip", "gazebo_ros_node", "gazebo_ros_utils", "gazebo_ros_init",
        "gazebo_ros_factory", "gazebo_ros_properties", "gazebo_ros_state",
        "gazebo_ros_force_system",
    }
)  # fmt: skip

# ROS 2 plugin names (libgazebo_ros_<name>.so), derived from the cited list above.
ROS2_PLUGINS = frozenset(lib.removeprefix("gazebo_ros_") for lib in ROS2_LIBRARIES)
# ROS 1 only, with what replaces each in ROS 2.
ROS1_ONLY: dict[str, str] = {
    "depth_camera": "libgazebo_ros_camera.so on a sensor of type depth",
    "openni_kinect": "libgazebo_ros_camera.so on a sensor of type depth",
    "multicamera": "libgazebo_ros_camera.so on a sensor of type multicamera",
    "triggered_camera": "libgazebo_ros_camera.so with <triggered>true</triggered>",
    "triggered_multicamera": "libgazebo_ros_camera.so on a multicamera sensor with <triggered>true</triggered>",
    "laser": "libgazebo_ros_ray_sensor.so with <output_type>sensor_msgs/LaserScan</output_type>",
    "gpu_laser": "libgazebo_ros_ray_sensor.so on a gpu_ray sensor with <output_type>sensor_msgs/LaserScan</output_type>",
    "block_laser": "libgazebo_ros_ray_sensor.so with <output_type>sensor_msgs/PointCloud2</output_type>",
    "range": "libgazebo_ros_ray_sensor.so with <output_type>sensor_msgs/Range</output_type>",
    "imu": "a sensor of type imu with libgazebo_ros_imu_sensor.so",
    "skid_steer_drive": "libgazebo_ros_diff_drive.so with <num_wheel_pairs>2</num_wheel_pairs>",
    "prosilica": "nothing in gazebo_plugins (use libgazebo_ros_camera.so)",
    "f3d": "nothing in gazebo_plugins (libgazebo_ros_ft_sensor.so measures joint wrenches)",
    "hokuyo_node": "nothing in gazebo_plugins (use libgazebo_ros_ray_sensor.so)",
    "camera_synchronizer": "nothing in gazebo_plugins",
    "vision_reconfigure": "nothing in gazebo_plugins",
    "control": "gazebo_ros2_control (libgazebo_ros2_control.so)",
}
# ROS 2 gazebo_ros names that ROS 1 gazebo_plugins never had, derived likewise.
ROS2_ONLY = frozenset(lib.removeprefix("gazebo_ros_") for lib in ROS2_LIBRARIES - ROS1_LIBRARIES)
ROS1_TO_ROS2_PARAMS: dict[str, str] = {
    "frameName": "<frame_name>",
    "cameraName": "<camera_name>",
    "robotNamespace": "<ros><namespace>",
    "hackBaseline": "<hack_baseline>",
    "baseline": "<hack_baseline>",
    "focalLength": "<focal_length>",
    "Cx": "<cx>",
    "Cy": "<cy>",
    "CxPrime": "nothing (ROS 2 has no CxPrime)",
    "pointCloudCutoff": "<min_depth>",
    "pointCloudCutoffMax": "<max_depth>",
    "imageTopicName": "the fixed name <camera_name>/image_raw plus <ros><remapping>",
    "cameraInfoTopicName": "the fixed name <camera_name>/camera_info plus <ros><remapping>",
    "depthImageTopicName": "the fixed name <camera_name>/depth/image_raw plus <ros><remapping>",
    "depthImageInfoTopicName": "the fixed name <camera_name>/depth/camera_info plus <ros><remapping>",
    "depthImageCameraInfoTopicName": "the fixed name <camera_name>/depth/camera_info plus <ros><remapping>",
    "pointCloudTopicName": "the fixed name <camera_name>/points plus <ros><remapping>",
    "distortionK1": "the SDF <camera><distortion><k1>",
    "distortionK2": "the SDF <camera><distortion><k2>",
    "distortionK3": "the SDF <camera><distortion><k3>",
    "distortionT1": "the SDF <camera><distortion><p1>",
    "distortionT2": "the SDF <camera><distortion><p2>",
    "updateRate": "the sensor's <update_rate> (or <update_rate> for model plugins)",
    "updateRateHZ": "the sensor's <update_rate>",
    "alwaysOn": "the sensor's <always_on>",
    "topicName": "<ros><remapping>~/out:=TOPIC</remapping>",
    "bodyName": "<frame_name>",
    "gaussianNoise": "an SDF <noise> block on the sensor",
    "xyzOffset": "the sensor's <pose>",
    "xyzOffsets": "the sensor's <pose>",
    "rpyOffset": "the sensor's <pose>",
    "rpyOffsets": "the sensor's <pose>",
    "serviceName": "nothing (ROS 2 has no calibration service)",
    "initialOrientationAsReference": "<initial_orientation_as_reference>",
    "leftJoint": "<left_joint>",
    "rightJoint": "<right_joint>",
    "leftFrontJoint": "<left_joint> (with <num_wheel_pairs>)",
    "rightFrontJoint": "<right_joint> (with <num_wheel_pairs>)",
    "leftRearJoint": "<left_joint> (with <num_wheel_pairs>)",
    "rightRearJoint": "<right_joint> (with <num_wheel_pairs>)",
    "wheelSeparation": "<wheel_separation>",
    "wheelDiameter": "<wheel_diameter>",
    "wheelTorque": "<max_wheel_torque>",
    "wheelAcceleration": "<max_wheel_acceleration>",
    "commandTopic": "<ros><remapping>cmd_vel:=TOPIC</remapping>",
    "odometryTopic": "<ros><remapping>odom:=TOPIC</remapping>",
    "odometryFrame": "<odometry_frame>",
    "robotBaseFrame": "<robot_base_frame>",
    "publishWheelTF": "<publish_wheel_tf>",
    "publishOdomTF": "<publish_odom_tf>",
    "publishWheelJointState": "a joint_state_publisher plugin",
    "odometrySource": "<odometry_source>",
    "rosDebugLevel": "nothing (use --ros-args --log-level)",
}
RAY_OUTPUT_TYPES = {
    "sensor_msgs/LaserScan",
    "sensor_msgs/PointCloud",
    "sensor_msgs/PointCloud2",
    "sensor_msgs/Range",
}

# What ``sensorkit validate --fix`` may rewrite (SK602): ROS 1 tags whose ROS 2 form is a
# direct one, per ROS 2 library that reads it. Read from ros-simulation/gazebo_ros_pkgs
# @ros2 (d52f7c4) and @noetic-devel (f9e1a46); nothing else in the tables is a guess.
#
# Same value, other tag name. ROS 2: gazebo_ros/src/utils.cpp:52-61 (frame_name, every
# sensor plugin through SensorFrameID); gazebo_plugins/src/gazebo_ros_camera.cpp:179
# camera_name, :361-364 cx/cy, :372 focal_length, :399 hack_baseline, :476-478 min_depth/
# max_depth; gazebo_ros_imu_sensor.cpp:76-82 initial_orientation_as_reference;
# gazebo_ros_diff_drive.cpp:257-380. ROS 1: gazebo_ros_camera_utils.cpp:140-197,
# gazebo_ros_openni_kinect.cpp:101-108, gazebo_ros_imu_sensor.cpp:48-56,
# gazebo_ros_diff_drive.cpp:92-103.
ROS1_RENAMES: dict[str, dict[str, str]] = {
    "gazebo_ros_camera": {
        "frameName": "frame_name",
        "cameraName": "camera_name",
        "hackBaseline": "hack_baseline",
        "focalLength": "focal_length",
        "Cx": "cx",
        "Cy": "cy",
        "pointCloudCutoff": "min_depth",
        "pointCloudCutoffMax": "max_depth",
    },
    "gazebo_ros_ray_sensor": {"frameName": "frame_name"},
    "gazebo_ros_imu_sensor": {
        "frameName": "frame_name",
        "initialOrientationAsReference": "initial_orientation_as_reference",
    },
    "gazebo_ros_gps_sensor": {"frameName": "frame_name"},
    "gazebo_ros_diff_drive": {
        "leftJoint": "left_joint",
        "rightJoint": "right_joint",
        "wheelSeparation": "wheel_separation",
        "wheelDiameter": "wheel_diameter",
        "wheelTorque": "max_wheel_torque",
        "wheelAcceleration": "max_wheel_acceleration",
        "updateRate": "update_rate",
        "odometryFrame": "odometry_frame",
        "robotBaseFrame": "robot_base_frame",
        "publishWheelTF": "publish_wheel_tf",
        "publishOdomTF": "publish_odom_tf",
    },
}
# ROS 1 tags where 0 means "compute the default" (gazebo_ros_camera_utils.cpp:506-509 for
# Cx and Cy) while ROS 2 takes 0 literally (gazebo_ros_camera.cpp:361-364 defaults only
# when the tag is absent): a 0 is dropped, not renamed.
ROS1_ZERO_MEANS_DEFAULT = frozenset({"Cx", "Cy"})
# ROS 1 topic tags and the ROS 2 name they become a remapping of. ROS 1 advertises them
# relative to robotNamespace/cameraName for cameras (gazebo_ros_camera_utils.cpp:288) and
# to robotNamespace otherwise (gazebo_ros_laser.cpp:131, gazebo_ros_imu_sensor.cpp:83,
# gazebo_ros_diff_drive.cpp via GazeboRos); ROS 2 publishes camera topics as
# <camera_name>/... (gazebo_ros_camera.cpp:187-262), ray and IMU data on ~/out
# (gazebo_ros_ray_sensor.cpp:119-134, gazebo_ros_imu_sensor.cpp:95-96), and diff drive
# subscribes cmd_vel and publishes odom (gazebo_ros_diff_drive.cpp), all relative to
# <ros><namespace>; <ros><remapping> renames them (gazebo_ros/src/node.cpp:62-95).
ROS1_TOPIC_REMAPS: dict[str, dict[str, str]] = {
    "gazebo_ros_camera": {
        "imageTopicName": "image_raw",
        "cameraInfoTopicName": "camera_info",
        "depthImageTopicName": "depth/image_raw",
        "depthImageCameraInfoTopicName": "depth/camera_info",
        "pointCloudTopicName": "points",
    },
    "gazebo_ros_ray_sensor": {"topicName": "~/out"},
    "gazebo_ros_imu_sensor": {"topicName": "~/out"},
    "gazebo_ros_diff_drive": {"commandTopic": "cmd_vel", "odometryTopic": "odom"},
    # ROS 2 planar move subscribes cmd_vel and publishes odom (ros2 d52f7c4:
    # gazebo_plugins/src/gazebo_ros_planar_move.cpp:162-163, :173-174); p3d publishes its
    # topic_name_ "odom" (gazebo_ros_p3d.cpp:63, :126-128), where ROS 1 took <topicName>
    # (noetic-devel f9e1a46:gazebo_plugins/src/gazebo_ros_p3d.cpp:81-87).
    "gazebo_ros_planar_move": {"commandTopic": "cmd_vel", "odometryTopic": "odom"},
    "gazebo_ros_p3d": {"topicName": "odom"},
}
# Camera topics are relative to the camera name in both generations (see above).
ROS1_CAMERA_RELATIVE = frozenset({"gazebo_ros_camera"})
# ROS 1 sensor plugins' rate tags: the plugin throttled its publishing to this rate (0:
# unthrottled; gazebo_ros_camera_utils.cpp:151-157 and :441-444,
# gazebo_ros_imu_sensor.cpp:214-223). ROS 2 sensor plugins publish at the sensor's own
# <update_rate>, so that is where the rate goes.
ROS1_SENSOR_RATE_TAGS = frozenset({"updateRate", "updateRateHZ"})
# Where Gazebo Classic takes a camera's focal length (SK409). The image: gazebo11's
# rendering::Camera reads <lens><intrinsics> (fx fy cx cy s) and renders with a projection
# built from them (gazebo 11.10.2, as imported by Debian in elysia-best/gazebo-classic@
# upstream/11.10.2+dfsg:gazebo/rendering/Camera.cc:190 Load calls LoadCameraIntrinsics,
# :194-209 reads <lens><intrinsics>, :228-240 setCustomProjectionMatrix, kept by
# CreateCamera :1534-1537 and UpdateFOV :2027-2030; present since 11.0.0; CameraSensor.cc
# :156-157 hands it the sensor's <camera>). sdformat documents it: fx "overrides
# horizontal_fov" (gazebosim/sdformat@sdf9:sdf/1.7/camera.sdf:144-147). camera_info: the
# ROS plugin's focal length parameter, else width / (2 tan(HFOV / 2)), where HFOV() is
# <horizontal_fov> (Camera.cc:852-855), never the intrinsics: ROS 2 ros-simulation/
# gazebo_ros_pkgs@ros2 (d52f7c4):gazebo_plugins/src/gazebo_ros_camera.cpp:366-374 and
# K :427-431; ROS 1 @noetic-devel (f9e1a46):gazebo_plugins/src/gazebo_ros_camera_utils.cpp
# :184-189 (0 means computed), :512-519 and K :586-590.
CLASSIC_FOCAL_LENGTH_PARAM = {"ros2": "focal_length", "ros1": "focalLength"}
# Sensor types whose image is not the intrinsics projection: WideAngleCamera stitches six
# cameras, and sdformat says intrinsics "cannot be used with WideAngleCamera"
# (gazebosim/sdformat@sdf9:sdf/1.7/camera.sdf:145).
CLASSIC_NO_INTRINSICS_TYPES = frozenset({"wideanglecamera", "wide_angle_camera"})

# What an ignored ROS 1 tag sets, as the role of its value (SK602's severity, issue 35: the
# one computation in sensorkit.base.consequence, when the value differs from what the ROS 2
# plugin does without it; equal is info whatever the role):
#   FRAME, TOPIC:  a frame, topic or namespace (the data goes elsewhere, or TF cannot place
#                  it as the user meant): error;
#   CALIBRATION:   what camera_info or the IMU orientation says: error;
#   GEOMETRY:      the joints and wheel geometry a drive plugin moves: error;
#   RATE, NOISE, LIMIT, FLAG: the sensor works, not as tuned: warning.
# Tags no plugin reads or applies (ROS1_READ_BY_NO_PLUGIN, ROS1_UNUSED_BY_ROS1) change
# nothing: info.
_FRAME_TAGS = ("frameName", "bodyName", "odometryFrame", "robotBaseFrame")
ROS1_PARAM_ROLE: dict[str, Role] = {
    **dict.fromkeys(_FRAME_TAGS, Role.FRAME),
    **dict.fromkeys(
        (
            "cameraName",
            "robotNamespace",
            "imageTopicName",
            "cameraInfoTopicName",
            "depthImageTopicName",
            "depthImageCameraInfoTopicName",
            "pointCloudTopicName",
            "topicName",
            "commandTopic",
            "odometryTopic",
            "remap",
        ),
        Role.TOPIC,
    ),
    **dict.fromkeys(
        ("hackBaseline", "focalLength", "Cx", "Cy", "CxPrime", "rpyOffset", "rpyOffsets"),
        Role.CALIBRATION,
    ),
    **dict.fromkeys(
        (
            "leftJoint",
            "rightJoint",
            "leftFrontJoint",
            "rightFrontJoint",
            "leftRearJoint",
            "rightRearJoint",
            "wheelSeparation",
            "wheelDiameter",
        ),
        Role.GEOMETRY,
    ),
    **dict.fromkeys(("updateRate", "updateRateHZ"), Role.RATE),
    "gaussianNoise": Role.NOISE,
    **dict.fromkeys(
        ("wheelTorque", "wheelAcceleration", "pointCloudCutoff", "pointCloudCutoffMax"), Role.LIMIT
    ),
    # The ROS 1 camera utils put distortionK1..T2 in camera_info only, never in the image
    # (noetic-devel f9e1a46:gazebo_plugins/src/gazebo_ros_camera_utils.cpp:199-237 read
    # them, :580-584 fill D); ROS 2 takes D from the SDF <distortion> the image is rendered
    # with (ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:402-414). Ignoring them
    # makes camera_info agree with the image: a flag's worth (warning), not a broken
    # calibration.
    **dict.fromkeys(
        (
            "distortionK1",
            "distortionK2",
            "distortionK3",
            "distortionT1",
            "distortionT2",
            "xyzOffset",
            "xyzOffsets",
            "initialOrientationAsReference",
            "publishWheelTF",
            "publishOdomTF",
            "publishWheelJointState",
            "odometrySource",
        ),
        Role.FLAG,
    ),
}
# Tags whose value changes nothing in either generation, with what ROS 1 did with them (the
# words SK602 says; ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a46, gazebo_plugins and
# gazebo_ros). alwaysOn: `git grep '"alwaysOn"'` finds no reader. <baseline> and
# <depthImageInfoTopicName>: `git grep -n 'baseline\|depthImageInfo' noetic-devel --
# gazebo_plugins gazebo_ros` finds only hackBaseline (gazebo_ros_camera_utils.cpp:191-197,
# gazebo_ros_multicamera.cpp:92-93) and depthImageCameraInfoTopicName
# (gazebo_ros_depth_camera.cpp:121-124, gazebo_ros_openni_kinect.cpp:96-99): no ROS 1
# plugin reads either, so ROS 2 ignoring them changes nothing (issue 35 item 8).
# rosDebugLevel is read, for the log level only (gazebo_ros_utils.cpp:60, :82-84).
ROS1_READ_BY_NO_PLUGIN: dict[str, str] = {
    "alwaysOn": "no ROS 1 gazebo_ros_pkgs plugin read it either",
    "baseline": "no ROS 1 gazebo_ros_pkgs plugin read it either",
    "depthImageInfoTopicName": "no ROS 1 gazebo_ros_pkgs plugin read it either",
    "rosDebugLevel": "ROS 1 read it for the log level only",
}
# Tags the ROS 1 plugin of the same library never read, or read and never applied: they
# change nothing in either generation (other ROS 1 plugins may read the same tag, so the
# words name the library). gazebo_ros_imu_sensor (noetic-devel f9e1a46:
# gazebo_plugins/src/gazebo_ros_imu_sensor.cpp): frameName is its frame (:200-210);
# bodyName and serviceName it never reads (they are the model plugin gazebo_ros_imu's:
# gazebo_ros_imu.cpp:73-79, :97-103); xyzOffset it reads under "POSITION OFFSET, UNUSED"
# (:237-247) and applies only offset.Rot() (:107). ROS 1's gazebo_ros_imu (:105-111, :252)
# and gazebo_ros_p3d (:97-103, :301) do apply an xyzOffset.
ROS1_UNUSED_BY_ROS1: dict[str, dict[str, str]] = {
    "gazebo_ros_imu_sensor": {
        "bodyName": "ROS 1's libgazebo_ros_imu_sensor.so never read it either (it stamps <frameName>)",
        "serviceName": "ROS 1's libgazebo_ros_imu_sensor.so never read it either",
        "xyzOffset": (
            "ROS 1's libgazebo_ros_imu_sensor.so read it but applied only the rotation offset "
            "(its position offset is unused)"
        ),
    },
}
# What the ROS 2 plugin does when the tag's ROS 2 form is absent, for tags whose ROS 2
# behaviour is a plain value (names and camera numbers are computed by the rule from the
# sensor). ros-simulation/gazebo_ros_pkgs@ros2 (d52f7c4): gazebo_ros_diff_drive.cpp:257-258
# (max_wheel_acceleration 0, max_wheel_torque 5), :310 wheel_separation 0.34, :326
# wheel_diameter 0.15, :345 update_rate 100, :362-365 odometry_frame "odom",
# robot_base_frame "base_footprint", odometry_source 1 (WORLD), :379-380 publish_wheel_tf
# and publish_odom_tf false; gazebo_ros_planar_move.cpp:141-145 odom/base_footprint and
# update_rate 20, :182 publish_odom_tf true; gazebo_ros_imu_sensor.cpp:74-82
# initial_orientation_as_reference false; gazebo_ros_camera.cpp:476-478 min_depth 0.4,
# max_depth infinity, :399 hack_baseline 0. ROS 2's IMU plugin adds no noise and no offset
# of its own (gazebo_ros_imu_sensor.cpp:136-140 copies the sensor's readings).
# With no <left_joint>/<right_joint> the drive has no joint and does not start
# ("Inconsistent number of joints specified. Plugin will not work.", gazebo_ros_diff_drive.cpp
# :261-300): "(none)".
ROS2_PLAIN_DEFAULTS: dict[str, dict[str, str]] = {
    "gazebo_ros_diff_drive": {
        "leftJoint": "(none)",
        "rightJoint": "(none)",
        "wheelAcceleration": "0",
        "wheelTorque": "5",
        "wheelSeparation": "0.34",
        "wheelDiameter": "0.15",
        "updateRate": "100",
        "odometryFrame": "odom",
        "robotBaseFrame": "base_footprint",
        "odometrySource": "1",
        "publishWheelTF": "false",
        "publishOdomTF": "false",
        "publishWheelJointState": "false",
    },
    "gazebo_ros_planar_move": {
        "odometryFrame": "odom",
        "robotBaseFrame": "base_footprint",
        "updateRate": "20",
        "publishOdomTF": "true",
    },
    # ROS 2 p3d: no <body_name>, "Missing <body_name>, cannot proceed" and no publisher
    # (gazebo_ros_p3d.cpp:111-113); <frame_name> defaults to world (:66, :170-174).
    "gazebo_ros_p3d": {"bodyName": "(none)", "frameName": "world"},
    "gazebo_ros_imu_sensor": {
        "initialOrientationAsReference": "false",
        "gaussianNoise": "0",
        "xyzOffset": "0 0 0",
        "rpyOffset": "0 0 0",
        "xyzOffsets": "0 0 0",
        "rpyOffsets": "0 0 0",
    },
    "gazebo_ros_camera": {
        "pointCloudCutoff": "0.4",
        "pointCloudCutoffMax": "inf",
        "hackBaseline": "0",
        "baseline": "0",
    },
}
# ROS 1 spellings of a ROS 2 value: odometrySource "world"/"encoder" (noetic-devel
# f9e1a46:gazebo_plugins/src/gazebo_ros_diff_drive.cpp:104-107, enum ENCODER 0, WORLD 1)
# is the ROS 2 integer.
ROS1_VALUE_SPELLINGS: dict[str, dict[str, str]] = {"odometrySource": {"world": "1", "encoder": "0"}}

# The principal point camera_info carries (SK411). Gazebo Classic renders a sensor camera
# without <lens><intrinsics> through a symmetric frustum (aspect ratio and FOVy only:
# elysia-best/gazebo-classic@upstream/11.10.2+dfsg:gazebo/rendering/Camera.cc:2033-2035;
# with intrinsics, a custom projection: :2027-2030), so the image's principal point is its
# centre. ROS 1 GazeboRosCameraUtils reads <Cx>/<Cy> (ros-simulation/gazebo_ros_pkgs@
# noetic-devel f9e1a46:gazebo_plugins/src/gazebo_ros_camera_utils.cpp:167-181), replaces
# only 0 by (width + 1) / 2, (height + 1) / 2 (:506-509) and publishes them as K[2], K[5]
# (:588, :591) and P[2], P[6] (:609, :613); the camera, depth camera, openni kinect,
# multicamera, triggered camera and prosilica plugins all use it. ROS 2 gazebo_ros_camera
# takes <cx>/<cy> with default (width + 1) / 2, (height + 1) / 2, a written 0 kept as 0
# (@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:360-364), into k[2], k[5]
# (:429, :432). Per generation: (cx tag, cy tag, a written 0 means "computed").
PRINCIPAL_POINT_PARAMS = {"ros1": ("Cx", "Cy", True), "ros2": ("cx", "cy", False)}
PRINCIPAL_POINT_FAMILIES = frozenset(
    {
        "gazebo_ros camera (ROS 2)",
        "gazebo_plugins camera (ROS 1)",
        "gazebo_plugins triggered camera (ROS 1)",
        "gazebo_plugins multicamera (ROS 1)",
        "gazebo_plugins depth camera (ROS 1)",
        "gazebo_plugins openni kinect (ROS 1)",
        "gazebo_plugins prosilica (ROS 1)",
    }
)
