"""Plugins sensorkit knows: which parameter holds the frame, its default, what it publishes.

One :class:`PluginSpec` per plugin family and ROS generation. A rule that needs to know
where a plugin stamps its data or what it publishes calls :func:`lookup`; a plugin that is
not in the table is *unknown*, and rules say at most ``info`` about it.

Every entry cites the source it was read from (``repo@path:line`` at the named branch).
"""

from __future__ import annotations

from dataclasses import dataclass

# Frame defaults (``PluginSpec.frame_default``):
LINK = "link"  # the <gazebo reference> link, after fixed-joint lumping when ``lumped``
WORLD = "world"  # the literal frame "world"
NONE = "none"  # stamps no frame / publishes no frame-carrying data
PARAM = "param"  # the default is another parameter's value (``frame_default_param``)
LITERAL = "literal"  # a fixed string (``frame_default_value``)


# How a model-level plugin finds the sensors it reads (``SensorOwnership.how``):
BY_NAME_SUFFIX = "name_suffix"  # sensors named <value of ``param``, default ""> + a suffix
BY_ROS2_CONTROL = "ros2_control"  # sensors named by the URDF's <ros2_control><sensor name=...>
BY_ROS_PARAMS = "ros_params"  # sensors named in ROS parameters, which a URDF does not hold


@dataclass(frozen=True)
class SensorOwnership:
    """Which sensors of the robot a model-level plugin looks up by name, as its source says.

    With BY_ROS_PARAMS the names are not in the description: the plugin *may* read any
    sensor of ``sensor_types``, and sensorkit cannot tell which.
    """

    how: str  # BY_NAME_SUFFIX, BY_ROS2_CONTROL or BY_ROS_PARAMS
    sensor_types: frozenset[str] = frozenset()  # SDF sensor types it reads (empty: any)
    param: str | None = None  # with BY_NAME_SUFFIX: the parameter holding the prefix
    suffixes: tuple[str, ...] = ()  # with BY_NAME_SUFFIX
    where: str = ""  # with BY_ROS_PARAMS: the parameters naming the sensors, in words
    source: str = ""  # repo@ref:path:line it was read from


@dataclass(frozen=True)
class PluginSpec:
    """What one plugin family does, as its source code says."""

    family: str  # a readable name: "gazebo_ros camera (ROS 2)"
    libraries: tuple[str, ...]  # library base names: libgazebo_ros_camera.so -> gazebo_ros_camera
    ros: (
        str  # "ros2" (gazebo_ros, ROS 2 Classic), "ros1" (gazebo_plugins, ROS 1), "gz" (Gazebo Sim)
    )
    level: str  # "sensor": inside <sensor>; "model": directly under <gazebo>; "visual": in <visual>
    sensor_types: frozenset[str] = frozenset()  # SDF sensor types it works on (empty: any/none)
    frame_params: tuple[str, ...] = ()  # parameters naming the frame, first present wins
    frame_default: str = NONE  # LINK, WORLD, NONE, PARAM or LITERAL
    frame_default_param: str | None = None  # with PARAM
    frame_default_value: str | None = None  # with LITERAL
    lumped: bool = False  # the LINK default follows fixed-joint lumping (gazebo_ros SensorFrameID)
    world_frame_ok: bool = False  # world/map is a meaningful frame (p3d, bumper)
    # The frame (given or default) passes through ROS 1 tf::resolve before it is stamped,
    # which drops a leading "/" (see TF_RESOLVE below and :func:`stamped_frame`).
    tf_resolve: bool = False
    # (parameter, default) pairs of topics it publishes, relative to its namespace;
    # a default of None means the topic exists only when the parameter is given, a parameter
    # of None a fixed name. In defaults "{sensor}" stands for the sensor's name and "{model}"
    # for the model's (the robot's) name.
    topics: tuple[tuple[str | None, str | None], ...] = ()
    # A parameter whose value prefixes every relative topic above (camera_name, cameraName),
    # and its default when absent ("" for none).
    topic_ns_param: str | None = None
    topic_ns_default: str | None = None
    # The sensors a model-level plugin reads by name (and publishes, or hands to
    # ros_control): see :class:`SensorOwnership`. None: it reads none.
    owns: SensorOwnership | None = None
    # A parameter naming a class the plugin loads, which decides what it reads
    # (gazebo_ros_control's <robotSimType>), and its default: see HARDWARE_SIMS.
    owner_class_param: str | None = None
    owner_class_default: str | None = None
    # Every SDF parameter the plugin's Load() reads, as its source says (empty: not recorded).
    # Where a library has a ROS 1 and a ROS 2 spec, both recorded, the parameters only one of
    # them reads tell which generation a description was written for (see
    # :func:`generation_params`, used by sensorkit.model.targets.ros1_evidence).
    params: frozenset[str] = frozenset()
    source: str = ""  # repo@path:line (branch) it was read from


# ROS 1 tf::resolve(prefix, frame_name) (ros/geometry@tf/src/tf.cpp:159-166, noetic-devel
# fe344b6): a frame_name starting with "/" is returned through strip_leading_slash
# (:195-206, which erases that one character), whatever the prefix; otherwise, with no
# prefix, the name is returned as is (:186-191). The prefix is the tf_prefix ROS parameter
# (tf::getPrefixParam, tf/include/tf/transform_listener.h:55-63, "" when unset), which a
# URDF does not hold: sensorkit models the unset case. So <frameName>/laser_link</frameName>
# stamps "laser_link", and the laser's default "/world" stamps "world".
TF_RESOLVE = "ros/geometry@tf/src/tf.cpp:159-166 (noetic-devel fe344b6)"


def stamped_frame(spec: PluginSpec, frame: str) -> str:
    """The frame id ``spec``'s plugin stamps when its frame parameter (or default) is
    ``frame``: ROS 1 plugins that call tf::resolve drop one leading "/" (TF_RESOLVE)."""
    if spec.tf_resolve and frame.startswith("/"):
        return frame[1:]
    return frame


# The parameters each velodyne_gazebo_plugins generation reads (PluginSpec.params).
# ROS 1: tier4/velodyne_simulator@velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:115-158
# (master fe021b6, the upstream ROS 1 code: robotNamespace, frameName, min_range, max_range,
# min_intensity, topicName, gaussianNoise); lmark1/velodyne_simulator's fork (master e08185a)
# reads the same at the same lines and adds staticTopicName/staticFrameName (:191).
# Upstream ROS 1 (1.0.11 and later, catkin) reads organize_cloud too: Kevin Hallenbeck's
# effeed2 "Add organize_cloud parameter to match velodyne_pointcloud" (2021-02-23), as kept
# in the ROS 1 fork Winsleo/velodyne_simulator@a7cec2a (package.xml 1.0.13, catkin):
# velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:128-133. So organize_cloud is no
# sign of the ROS 2 port (issue 23, fact 8).
VELODYNE_ROS1_PARAMS = frozenset(
    {
        "robotNamespace",
        "frameName",
        "organize_cloud",
        "min_range",
        "max_range",
        "min_intensity",
        "topicName",
        "gaussianNoise",
        "staticTopicName",
        "staticFrameName",
    }
)
# ROS 2 port: tier4/velodyne_simulator@velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp
# (prepare/humble 00759c8): :73 gazebo_ros::Node::Get(_sdf) reads <ros>
# (ros-simulation/gazebo_ros_pkgs@gazebo_ros/src/node.cpp:62, ros2 d52f7c4), :79 tf_prefix,
# :80 SensorFrameID reads frame_name (gazebo_ros/src/utils.cpp:55), :82-114 organize_cloud,
# min_range, max_range, min_intensity, gaussian_noise.
VELODYNE_ROS2_PARAMS = frozenset(
    {
        "ros",
        "tf_prefix",
        "frame_name",
        "organize_cloud",
        "min_range",
        "max_range",
        "min_intensity",
        "gaussian_noise",
    }
)


PLUGINS: tuple[PluginSpec, ...] = (
    # ---------------------------------------------------------------------------------------
    # gazebo_ros_pkgs, ROS 2 (gazebo_plugins): ros-simulation/gazebo_ros_pkgs branch ros2
    # (d52f7c4, what humble is released from); foxy (b6f7bf1) and galactic read the same
    # frame parameters and defaults on the lines cited.
    #
    # gazebo_ros::SensorFrameID (gazebo_ros/src/utils.cpp:52-61): <frame_name> if present,
    # else ScopedNameBase(sensor.ParentName()), i.e. the link Gazebo attached the sensor to,
    # which after URDF->SDF conversion is the link that survived fixed-joint lumping.
    # Topics are relative to the plugin node's <ros><namespace>; "~/out" is <node name>/out.
    # ---------------------------------------------------------------------------------------
    PluginSpec(
        family="gazebo_ros camera (ROS 2)",
        libraries=("gazebo_ros_camera",),
        ros="ros2",
        level="sensor",
        # gazebo_ros_camera.cpp:160-176: MultiCameraSensor, DepthCameraSensor or CameraSensor
        sensor_types=frozenset({"camera", "depth", "multicamera"}),
        frame_params=("frame_name",),
        frame_default=LINK,
        lumped=True,
        # gazebo_ros_camera.cpp:187 image_raw, :200 camera_info (not for multicamera: :213,:226
        # publish <camera_name>/<camera>/image_raw and .../camera_info); depth sensors only:
        # :241 depth/image_raw, :250 depth/camera_info, :260 points
        topics=(
            (None, "image_raw"),
            (None, "camera_info"),
            (None, "depth/image_raw"),
            (None, "depth/camera_info"),
            (None, "points"),
        ),
        # gazebo_ros_camera.cpp:179: camera_name defaults to the sensor's name
        topic_ns_param="camera_name",
        topic_ns_default="{sensor}",
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera.cpp:182 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros ray sensor (ROS 2)",
        libraries=("gazebo_ros_ray_sensor",),
        ros="ros2",
        level="sensor",
        # gazebo_ros_ray_sensor.cpp:174: subscribes to _sensor->Topic() (LaserScanStamped), no type
        # check: works on ray and gpu_ray
        sensor_types=frozenset({"ray", "gpu_ray"}),
        frame_params=("frame_name",),
        frame_default=LINK,
        lumped=True,
        # gazebo_ros_ray_sensor.cpp:119-134: every <output_type> publishes on "~/out"
        topics=((None, "~/out"),),
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_ray_sensor.cpp:113 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros IMU sensor (ROS 2)",
        libraries=("gazebo_ros_imu_sensor",),
        ros="ros2",
        level="sensor",
        sensor_types=frozenset({"imu"}),  # gazebo_ros_imu_sensor.cpp:69 ImuSensor
        frame_params=("frame_name",),
        frame_default=LINK,
        lumped=True,
        topics=((None, "~/out"),),  # gazebo_ros_imu_sensor.cpp:95-96
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_imu_sensor.cpp:102 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros GPS sensor (ROS 2)",
        libraries=("gazebo_ros_gps_sensor",),
        ros="ros2",
        level="sensor",
        sensor_types=frozenset({"gps"}),  # gazebo_ros_gps_sensor.cpp:73 GpsSensor
        frame_params=("frame_name",),
        frame_default=LINK,
        lumped=True,
        topics=((None, "~/out"), (None, "~/vel")),  # gazebo_ros_gps_sensor.cpp:79-82
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_gps_sensor.cpp:89 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros bumper (ROS 2)",
        libraries=("gazebo_ros_bumper",),
        ros="ros2",
        level="sensor",
        sensor_types=frozenset({"contact"}),  # gazebo_ros_bumper.cpp:78 ContactSensor
        frame_params=("frame_name",),
        frame_default=WORLD,  # gazebo_ros_bumper.cpp:99 Get("frame_name", "world")
        world_frame_ok=True,
        topics=((None, "bumper_states"),),  # gazebo_ros_bumper.cpp:91-92
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_bumper.cpp:99 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros force/torque sensor (ROS 2)",
        libraries=("gazebo_ros_ft_sensor",),
        ros="ros2",
        level="model",  # gazebo_ros_ft_sensor.cpp:226 GZ_REGISTER_MODEL_PLUGIN
        # With <body_name>: <frame_name>, default "world" (:128). With <joint_name>: the joint's
        # child link name, and <frame_name> is ignored with a warning (:142-147).
        frame_params=("frame_name",),
        frame_default=WORLD,
        world_frame_ok=True,
        topics=((None, "wrench"),),  # gazebo_ros_ft_sensor.cpp:159-160
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_ft_sensor.cpp:128 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros P3D ground truth (ROS 2)",
        libraries=("gazebo_ros_p3d",),
        ros="ros2",
        level="model",  # gazebo_ros_p3d.cpp:307 GZ_REGISTER_MODEL_PLUGIN
        # gazebo_ros_p3d.cpp:66 frame_name_{"world"}; :179-182 "world"/"map" (with or without
        # "/") are the world, any other name must be a link of the model. child_frame_id is
        # the <body_name> link's Gazebo name (:236).
        frame_params=("frame_name",),
        frame_default=WORLD,
        world_frame_ok=True,
        topics=((None, "odom"),),  # gazebo_ros_p3d.cpp:63 topic_name_{"odom"}, :126
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_p3d.cpp:170 (ros2 d52f7c4)",
    ),
    # Drive plugins: odometry is stamped <odometry_frame> (default "odom") with child frame
    # <robot_base_frame>; the robot-side frame is the one that must be a link, so it is the
    # frame parameter here. Odometry is published only with <publish_odom>true.
    PluginSpec(
        family="gazebo_ros diff drive (ROS 2)",
        libraries=("gazebo_ros_diff_drive",),
        ros="ros2",
        level="model",  # gazebo_ros_diff_drive.cpp:674
        frame_params=("robot_base_frame",),
        frame_default=LITERAL,
        frame_default_value="base_footprint",
        topics=((None, "odom"),),  # gazebo_ros_diff_drive.cpp:368-371 (publish_odom, default false)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_diff_drive.cpp:363 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros Ackermann drive (ROS 2)",
        libraries=("gazebo_ros_ackermann_drive",),
        ros="ros2",
        level="model",  # gazebo_ros_ackermann_drive.cpp:682
        frame_params=("robot_base_frame",),
        frame_default=LITERAL,
        frame_default_value="base_footprint",
        # gazebo_ros_ackermann_drive.cpp:384-409, each behind publish_odom / publish_distance /
        # publish_steerangle (all default false)
        topics=((None, "odom"), (None, "distance"), (None, "steerangle")),
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_ackermann_drive.cpp:381 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros tricycle drive (ROS 2)",
        libraries=("gazebo_ros_tricycle_drive",),
        ros="ros2",
        level="model",  # gazebo_ros_tricycle_drive.cpp:688
        frame_params=("robot_base_frame",),
        frame_default=LITERAL,
        frame_default_value="base_link",  # unlike the other drives: "base_link"
        # gazebo_ros_tricycle_drive.cpp:343-347 joint_states (publish_wheel_joint_state),
        # :354-357 odom (publish_odom)
        topics=((None, "joint_states"), (None, "odom")),
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_tricycle_drive.cpp:249 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros planar move (ROS 2)",
        libraries=("gazebo_ros_planar_move",),
        ros="ros2",
        level="model",  # gazebo_ros_planar_move.cpp:324
        frame_params=("robot_base_frame",),
        frame_default=LITERAL,
        frame_default_value="base_footprint",
        topics=((None, "odom"),),  # gazebo_ros_planar_move.cpp:171-174 (publish_odom, default true)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_planar_move.cpp:142 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros joint state publisher (ROS 2)",
        libraries=("gazebo_ros_joint_state_publisher",),
        ros="ros2",
        level="model",  # gazebo_ros_joint_state_publisher.cpp:204
        topics=((None, "joint_states"),),
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_joint_state_publisher.cpp:144 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros joint pose trajectory (ROS 2)",
        libraries=("gazebo_ros_joint_pose_trajectory",),
        ros="ros2",
        level="model",  # gazebo_ros_joint_pose_trajectory.cpp:279
        # subscribes only (:128); the reference link comes from each message's header (:222)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_joint_pose_trajectory.cpp:128 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros force (ROS 2)",
        libraries=("gazebo_ros_force",),
        ros="ros2",
        level="model",  # gazebo_ros_force.cpp:146
        # <force_frame> is a keyword, "world" or "link" (:82-92), not a TF frame; subscribes only
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_force.cpp:82 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros hand of god (ROS 2)",
        libraries=("gazebo_ros_hand_of_god",),
        ros="ros2",
        level="model",  # gazebo_ros_hand_of_god.cpp:203
        # <frame_id> (default "world", :109) names a TF frame outside the robot: it follows
        # "<frame_id>_desired" (:152), so it is not expected to be a link
        world_frame_ok=True,
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_hand_of_god.cpp:109 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros harness (ROS 2)",
        libraries=("gazebo_ros_harness",),
        ros="ros2",
        level="model",  # gazebo_ros_harness.cpp:106; subscribes only (:68, :78)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_harness.cpp:68 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros projector (ROS 2)",
        libraries=("gazebo_ros_projector",),
        ros="ros2",
        level="model",  # gazebo_ros_projector.cpp:126; <projector_link> default "projector_link"
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_projector.cpp:80 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros vacuum gripper (ROS 2)",
        libraries=("gazebo_ros_vacuum_gripper",),
        ros="ros2",
        level="model",  # gazebo_ros_vacuum_gripper.cpp:225
        topics=((None, "grasping"),),  # std_msgs/Bool, no frame
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_vacuum_gripper.cpp:134 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros video (ROS 2)",
        libraries=("gazebo_ros_video",),
        ros="ros2",
        level="visual",  # gazebo_ros_video.cpp:260 GZ_REGISTER_VISUAL_PLUGIN
        # subscribes to "~/image_raw" (:219-220), publishes nothing
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_video.cpp:220 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros wheel slip (ROS 2)",
        libraries=("gazebo_ros_wheel_slip",),
        ros="ros2",
        level="model",  # gazebo_ros_wheel_slip.cpp:438
        topics=((None, "wheel_slip"),),
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_wheel_slip.cpp:362 (ros2 d52f7c4)",
    ),
    PluginSpec(
        family="gazebo_ros elevator (ROS 2)",
        libraries=("gazebo_ros_elevator",),
        ros="ros2",
        level="model",  # gazebo_ros_elevator.cpp:88; subscribes only (:59)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_elevator.cpp:59 (ros2 d52f7c4)",
    ),
    # ---------------------------------------------------------------------------------------
    # gazebo_ros_pkgs, ROS 1 (gazebo_plugins): branch noetic-devel (f9e1a46).
    # Topics are relative to <robotNamespace>. Frames pass through tf::resolve(tf_prefix, ...).
    #
    # Camera family (GazeboRosCameraUtils, gazebo_ros_camera_utils.cpp): <frameName> only; when
    # absent frame_name_ keeps its empty initial value (member without initializer,
    # include/gazebo_plugins/gazebo_ros_camera_utils.h:142) although the debug message at
    # :147 says "defaults to /world": images and camera_info carry an EMPTY frame_id.
    # Topics live under <robotNamespace>/<cameraName> (:288); cameraName defaults to "" (:137).
    # ---------------------------------------------------------------------------------------
    PluginSpec(
        family="gazebo_plugins camera (ROS 1)",
        libraries=("gazebo_ros_camera",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"camera"}),  # gazebo_ros_camera.cpp:65 CameraPlugin::Load
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="",
        # gazebo_ros_camera_utils.cpp:124-135
        topics=(("imageTopicName", "image_raw"), ("cameraInfoTopicName", "camera_info")),
        topic_ns_param="cameraName",
        topic_ns_default="",
        tf_resolve=True,  # gazebo_ros_camera_utils.cpp:296-298 frame_name_ = tf::resolve(tf_prefix_, frame_name_)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera_utils.cpp:149 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins triggered camera (ROS 1)",
        libraries=("gazebo_ros_triggered_camera",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"camera"}),  # gazebo_ros_triggered_camera.cpp:60
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="",
        topics=(("imageTopicName", "image_raw"), ("cameraInfoTopicName", "camera_info")),
        topic_ns_param="cameraName",
        topic_ns_default="",
        tf_resolve=True,  # gazebo_ros_camera_utils.cpp:296-298 frame_name_ = tf::resolve(tf_prefix_, frame_name_) (GazeboRosCameraUtils::Load, gazebo_ros_triggered_camera.cpp:69)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera_utils.cpp:149 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins multicamera (ROS 1)",
        libraries=("gazebo_ros_multicamera",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"multicamera"}),  # gazebo_ros_multicamera.cpp:55
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="",
        # gazebo_ros_multicamera.cpp:84-94: cameras whose name contains "left"/"right" publish
        # under <cameraName>/left and <cameraName>/right; both share the one <frameName>
        topics=(("imageTopicName", "image_raw"), ("cameraInfoTopicName", "camera_info")),
        topic_ns_param="cameraName",
        topic_ns_default="",
        tf_resolve=True,  # gazebo_ros_camera_utils.cpp:296-298 frame_name_ = tf::resolve(tf_prefix_, frame_name_) (util->Load, gazebo_ros_multicamera.cpp:87,94)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera_utils.cpp:149 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins depth camera (ROS 1)",
        libraries=("gazebo_ros_depth_camera",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"depth"}),  # gazebo_ros_depth_camera.cpp:73 DepthCameraPlugin
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="",
        # gazebo_ros_depth_camera.cpp:92-95 set "ir/image_raw" / "ir/camera_info", but
        # GazeboRosCameraUtils::Load (called after, :143) resets them to "image_raw" /
        # "camera_info" (gazebo_ros_camera_utils.cpp:124,132): the ir/ defaults never apply.
        # :98-124 the rest.
        topics=(
            ("imageTopicName", "image_raw"),
            ("cameraInfoTopicName", "camera_info"),
            ("pointCloudTopicName", "points"),
            ("depthImageTopicName", "depth/image_raw"),
            ("depthImageCameraInfoTopicName", "depth/camera_info"),
            ("reflectanceTopicName", "reflectance"),
            ("normalsTopicName", "normals"),
        ),
        topic_ns_param="cameraName",
        topic_ns_default="",
        tf_resolve=True,  # gazebo_ros_camera_utils.cpp:296-298 frame_name_ = tf::resolve(tf_prefix_, frame_name_) (GazeboRosCameraUtils::Load, gazebo_ros_depth_camera.cpp:143)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera_utils.cpp:149 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins openni kinect (ROS 1)",
        libraries=("gazebo_ros_openni_kinect",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"depth"}),  # gazebo_ros_openni_kinect.cpp:68 DepthCameraPlugin
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="",
        # gazebo_ros_openni_kinect.cpp:79-99; as for the depth camera the ir/ image defaults are
        # overwritten by GazeboRosCameraUtils::Load (:117, camera_utils.cpp:124,132)
        topics=(
            ("imageTopicName", "image_raw"),
            ("cameraInfoTopicName", "camera_info"),
            ("pointCloudTopicName", "points"),
            ("depthImageTopicName", "depth/image_raw"),
            ("depthImageCameraInfoTopicName", "depth/camera_info"),
        ),
        topic_ns_param="cameraName",
        topic_ns_default="",
        tf_resolve=True,  # gazebo_ros_camera_utils.cpp:296-298 frame_name_ = tf::resolve(tf_prefix_, frame_name_) (GazeboRosCameraUtils::Load, gazebo_ros_openni_kinect.cpp:117)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera_utils.cpp:149 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins prosilica (ROS 1)",
        libraries=("gazebo_ros_prosilica",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"camera"}),  # gazebo_ros_prosilica.cpp:84 CameraPlugin::Load
        frame_params=("frameName",),  # via GazeboRosCameraUtils::Load (:91)
        frame_default=LITERAL,
        frame_default_value="",
        topics=(("imageTopicName", "image_raw"), ("cameraInfoTopicName", "camera_info")),
        topic_ns_param="cameraName",
        topic_ns_default="",
        tf_resolve=True,  # gazebo_ros_camera_utils.cpp:296-298 frame_name_ = tf::resolve(tf_prefix_, frame_name_) (GazeboRosCameraUtils::Load, gazebo_ros_prosilica.cpp:91)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera_utils.cpp:149 (noetic-devel f9e1a46)",
    ),
    # Laser family: the default frame is the literal "/world", which tf::resolve (TF_RESOLVE
    # above) turns into the stamped "world"; the default topic is ALSO "/world" (laser,
    # gpu_laser, block_laser) or "/range" (range).
    PluginSpec(
        family="gazebo_plugins laser (ROS 1)",
        libraries=("gazebo_ros_laser",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"ray"}),  # gazebo_ros_laser.cpp:81 RaySensor
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="/world",  # gazebo_ros_laser.cpp:88-94
        topics=(("topicName", "/world"),),  # gazebo_ros_laser.cpp:97-103
        tf_resolve=True,  # gazebo_ros_laser.cpp:137-138 frame_name_ = tf::resolve(tf_prefix_, frame_name_), stamped at :190
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_laser.cpp:91 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins GPU laser (ROS 1)",
        libraries=("gazebo_ros_gpu_laser",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"gpu_ray"}),  # gazebo_ros_gpu_laser.cpp:84 GpuRaySensor
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="/world",  # gazebo_ros_gpu_laser.cpp:91-97
        topics=(("topicName", "/world"),),  # gazebo_ros_gpu_laser.cpp:99-105
        tf_resolve=True,  # gazebo_ros_gpu_laser.cpp:140-141 tf::resolve, stamped at :195
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_gpu_laser.cpp:94 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins block laser (ROS 1)",
        libraries=("gazebo_ros_block_laser",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"ray"}),  # gazebo_ros_block_laser.cpp:100 RaySensor
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="/world",  # gazebo_ros_block_laser.cpp:109-115
        topics=(("topicName", "/world"),),  # gazebo_ros_block_laser.cpp:117-123
        tf_resolve=True,  # gazebo_ros_block_laser.cpp:165-168 tf::resolve, stamped at :289
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_block_laser.cpp:112 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins range (ROS 1)",
        libraries=("gazebo_ros_range",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"ray"}),  # gazebo_ros_range.cpp:102 RaySensor
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="/world",  # gazebo_ros_range.cpp:111-117
        topics=(("topicName", "/range"),),  # gazebo_ros_range.cpp:119-125
        tf_resolve=True,  # gazebo_ros_range.cpp:200-203 tf::resolve, stamped at :298
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_range.cpp:114 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins IMU sensor (ROS 1)",
        libraries=("gazebo_ros_imu_sensor",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"imu"}),
        # gazebo_ros_imu_sensor.cpp:202-210: <frameName> is required ("missing <frameName>,
        # cannot proceed"): no default, the plugin publishes nothing without it
        # Not tf_resolve: the value is stamped as given (body_name, :204 -> :138).
        frame_params=("frameName",),
        frame_default=NONE,
        # gazebo_ros_imu_sensor.cpp:190-198; namespace defaults to "/<model>/" (:182-185)
        topics=(("topicName", "imu_data"),),
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_imu_sensor.cpp:202 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins IMU model plugin (ROS 1)",
        libraries=("gazebo_ros_imu",),
        ros="ros1",
        level="model",  # gazebo_ros_imu.cpp:32 GZ_REGISTER_MODEL_PLUGIN
        # gazebo_ros_imu.cpp:130-136 <frameName>, defaulting to <bodyName> (required, :97-103)
        # Not tf_resolve: frame_name_ is stamped as given (:279).
        frame_params=("frameName", "bodyName"),
        frame_default=PARAM,
        frame_default_param="bodyName",
        topics=(("topicName", "/default_imu"),),  # gazebo_ros_imu.cpp:81-87
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_imu.cpp:133 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins P3D ground truth (ROS 1)",
        libraries=("gazebo_ros_p3d",),
        ros="ros1",
        level="model",  # gazebo_ros_p3d.cpp:30
        frame_params=("frameName",),
        frame_default=WORLD,  # gazebo_ros_p3d.cpp:89-95
        world_frame_ok=True,
        # Not tf_resolve: the stamp is tf::resolve(prefix, frame_name_) (:146, :254), but the
        # reference link is looked up by the unresolved name (:178 GetLink(frame_name_)),
        # which with a leading "/" names no link: "does not exist, will not publish" (:181).
        topics=(("topicName", None),),  # gazebo_ros_p3d.cpp:81-87: required
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_p3d.cpp:92 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins F3D force (ROS 1)",
        libraries=("gazebo_ros_f3d",),
        ros="ros1",
        level="model",  # gazebo_ros_f3d.cpp:32
        frame_params=("frameName",),
        frame_default=WORLD,  # gazebo_ros_f3d.cpp:89-96
        world_frame_ok=True,
        topics=(("topicName", None),),  # gazebo_ros_f3d.cpp:81-87: required
        tf_resolve=True,  # gazebo_ros_f3d.cpp:112-115 tf::resolve, stamped at :175
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_f3d.cpp:92 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins bumper (ROS 1)",
        libraries=("gazebo_ros_bumper",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"contact"}),  # gazebo_ros_bumper.cpp:74 ContactSensor
        frame_params=("frameName",),
        frame_default=WORLD,  # gazebo_ros_bumper.cpp:95-101
        world_frame_ok=True,
        topics=(("bumperTopicName", "bumper_states"),),  # gazebo_ros_bumper.cpp:88-91
        tf_resolve=True,  # gazebo_ros_bumper.cpp:113-116 tf::resolve, before the link lookup (:162-175) and the stamp (:151)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_bumper.cpp:98 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins force/torque sensor (ROS 1)",
        libraries=("gazebo_ros_ft_sensor",),
        ros="ros1",
        level="model",  # gazebo_ros_ft_sensor.cpp:32
        # no frame parameter: the frame is the child link of <jointName> (:82-84)
        topics=(("topicName", None),),  # gazebo_ros_ft_sensor.cpp:88-94: required
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_ft_sensor.cpp:84 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins diff drive (ROS 1)",
        libraries=("gazebo_ros_diff_drive",),
        ros="ros1",
        level="model",  # gazebo_ros_diff_drive.cpp:478
        # gazebo_ros_diff_drive.cpp:94-95 odometryFrame "odom", robotBaseFrame "base_footprint"
        frame_params=("robotBaseFrame",),
        frame_default=LITERAL,
        frame_default_value="base_footprint",
        # :93 odometryTopic "odom" (advertised with publishTf, :167-169); :150 joint_states
        # with publishWheelJointState
        topics=(("odometryTopic", "odom"), (None, "joint_states")),
        tf_resolve=True,  # gazebo_ros_diff_drive.cpp:407 resolveTF(robot_base_frame_) = tf::resolve (gazebo_ros_utils.cpp:52-53)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_diff_drive.cpp:95 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins skid steer drive (ROS 1)",
        libraries=("gazebo_ros_skid_steer_drive",),
        ros="ros1",
        level="model",  # gazebo_ros_skid_steer_drive.cpp:495
        frame_params=("robotBaseFrame",),  # :184-197 odometryFrame "odom", robotBaseFrame
        frame_default=LITERAL,
        frame_default_value="base_footprint",
        topics=(("odometryTopic", "odom"),),  # gazebo_ros_skid_steer_drive.cpp:176-181
        tf_resolve=True,  # gazebo_ros_skid_steer_drive.cpp:429-430 tf::resolve(tf_prefix_, robot_base_frame_)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_skid_steer_drive.cpp:192 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins planar move (ROS 1)",
        libraries=("gazebo_ros_planar_move",),
        ros="ros1",
        level="model",  # gazebo_ros_planar_move.cpp:331
        frame_params=("robotBaseFrame",),  # :82-103 odometryFrame "odom", robotBaseFrame
        frame_default=LITERAL,
        frame_default_value="base_footprint",
        topics=(("odometryTopic", "odom"),),  # gazebo_ros_planar_move.cpp:70-79
        tf_resolve=True,  # gazebo_ros_planar_move.cpp:266-267 tf::resolve(tf_prefix_, robot_base_frame_)
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_planar_move.cpp:94 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins joint state publisher (ROS 1)",
        libraries=("gazebo_ros_joint_state_publisher",),
        ros="ros1",
        level="model",
        topics=((None, "joint_states"),),
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_joint_state_publisher.cpp:102 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_plugins video (ROS 1)",
        libraries=("gazebo_ros_video",),
        ros="ros1",
        level="visual",  # gazebo_ros_video.cpp:265 GZ_REGISTER_VISUAL_PLUGIN
        # subscribes to <topicName> (default "image_raw", :160-168), publishes nothing
        source="ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_video.cpp:160 (noetic-devel f9e1a46)",
    ),
    PluginSpec(
        family="gazebo_ros_control (ROS 1)",
        libraries=("gazebo_ros_control",),
        ros="ros1",
        level="model",  # gazebo_ros_control_plugin.cpp:314; controllers, no sensor data
        # What it reads is decided by the RobotHWSim class it loads: <robotSimType>
        # (gazebo_ros_control_plugin.cpp:105-107), default DefaultRobotHWSim (:111), created
        # by name at :181; the classes sensorkit knows are in HARDWARE_SIMS.
        owner_class_param="robotSimType",
        owner_class_default="gazebo_ros_control/DefaultRobotHWSim",
        source="ros-simulation/gazebo_ros_pkgs@gazebo_ros_control/CMakeLists.txt:69 (noetic-devel f9e1a46)",
    ),
    # ---------------------------------------------------------------------------------------
    # ros2_control bridges: model level (system level for Gazebo Sim), no frame, no sensor
    # topics (sensors they expose go through controllers).
    # ---------------------------------------------------------------------------------------
    PluginSpec(
        family="gazebo_ros2_control (ROS 2)",
        libraries=("gazebo_ros2_control",),
        ros="ros2",
        level="model",  # gazebo_ros2_control_plugin.cpp:504 GZ_REGISTER_MODEL_PLUGIN (humble)
        # GazeboSystem reads each <ros2_control><sensor name> by the Gazebo sensor's leaf
        # name (gazebo_system.cpp:568-589, s->Name() != sensor_name at :578), IMU (:608) and
        # force-torque (:619) sensors.
        owns=SensorOwnership(
            how=BY_ROS2_CONTROL,
            sensor_types=frozenset({"imu", "force_torque"}),
            source="ros-controls/gazebo_ros2_control@humble 42d875b:gazebo_ros2_control/src/gazebo_system.cpp:568-619",
        ),
        source="ros-controls/gazebo_ros2_control@gazebo_ros2_control/CMakeLists.txt:31 (humble 42d875b)",
    ),
    PluginSpec(
        family="gz_ros2_control / ign_ros2_control (Gazebo Sim)",
        # gz_ros2_control/CMakeLists.txt:35 ${PROJECT_NAME}-system (rolling);
        # ign_ros2_control/CMakeLists.txt:53 ign_ros2_control-system (humble)
        libraries=("gz_ros2_control-system", "ign_ros2_control-system"),
        ros="gz",
        level="model",
        # GzSystem reads each IMU entity whose name a <ros2_control><sensor name> matches
        # (gz_system.cpp:426-448, comp.name == _name->Data() at :448; jazzy fa9ced4).
        owns=SensorOwnership(
            how=BY_ROS2_CONTROL,
            sensor_types=frozenset({"imu"}),
            source="ros-controls/gz_ros2_control@jazzy fa9ced4:gz_ros2_control/src/gz_system.cpp:426-448",
        ),
        source="ros-controls/gz_ros2_control@gz_ros2_control/CMakeLists.txt:35 (rolling e19b0ef)",
    ),
    # ---------------------------------------------------------------------------------------
    # velodyne_gazebo_plugins. ROS 1: lmark1/velodyne_simulator master (e08185a), one source
    # built twice (CMakeLists.txt:29 RayPlugin, :36 GpuRayPlugin). ROS 2: the port on
    # tier4/velodyne_simulator branch prepare/humble (00759c8), which builds only the CPU
    # library (velodyne_gazebo_plugins/CMakeLists.txt:22); tier4's "ros2" branch is still the
    # ROS 1 code. ros-drivers/velodyne_simulator itself was not available.
    # ---------------------------------------------------------------------------------------
    PluginSpec(
        family="velodyne laser (ROS 1)",
        libraries=("gazebo_ros_velodyne_laser",),
        ros="ros1",
        level="sensor",
        sensor_types=frozenset({"ray"}),  # GazeboRosVelodyneLaser.cpp:106-111 RaySensor
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="/world",  # GazeboRosVelodyneLaser.cpp:119-123
        topics=(("topicName", "/points"),),  # GazeboRosVelodyneLaser.cpp:147-151
        params=VELODYNE_ROS1_PARAMS,
        tf_resolve=True,  # GazeboRosVelodyneLaser.cpp:171-178 frame_name_ = tf::resolve(prefix, frame_name_), stamped at :316
        source="lmark1/velodyne_simulator@velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:121 (master e08185a)",
    ),
    PluginSpec(
        family="velodyne GPU laser (ROS 1)",
        libraries=("gazebo_ros_velodyne_gpu_laser",),
        ros="ros1",
        level="sensor",
        # GazeboRosVelodyneLaser.cpp:57-58 with GAZEBO_GPU_RAY, RaySensor means GpuRaySensor
        sensor_types=frozenset({"gpu_ray"}),
        frame_params=("frameName",),
        frame_default=LITERAL,
        frame_default_value="/world",
        topics=(("topicName", "/points"),),
        params=VELODYNE_ROS1_PARAMS,  # the same source file as the CPU library
        tf_resolve=True,  # the same source: GazeboRosVelodyneLaser.cpp:178
        source="lmark1/velodyne_simulator@velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:121 (master e08185a)",
    ),
    PluginSpec(
        family="velodyne laser (ROS 2 port)",
        libraries=("gazebo_ros_velodyne_laser",),
        ros="ros2",
        level="sensor",
        sensor_types=frozenset({"ray", "gpu_ray"}),  # :136 subscribes to the sensor's Topic()
        # GazeboRosVelodyneLaser.cpp:80 tf_resolve(<tf_prefix>, gazebo_ros::SensorFrameID(...))
        frame_params=("frame_name",),
        frame_default=LINK,
        lumped=True,
        topics=((None, "~/out"),),  # GazeboRosVelodyneLaser.cpp:118
        params=VELODYNE_ROS2_PARAMS,
        source="tier4/velodyne_simulator@velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:80 (prepare/humble 00759c8)",
    ),
    # ---------------------------------------------------------------------------------------
    # hector_gazebo_plugins: tu-darmstadt-ros-pkg/hector_gazebo, ROS 1 melodic-devel (de947fb),
    # ROS 2 humble-devel (f2ff0ac). Model plugins stamp <frameId>; IMU and magnetometer
    # default to the <bodyName> link (else the model's canonical link), GPS to "/world".
    # hector_gazebo_ros_baro lives in tu-darmstadt-ros-pkg/hector_quadrotor (noetic-devel).
    # ---------------------------------------------------------------------------------------
    PluginSpec(
        family="hector IMU (ROS 1)",
        libraries=("hector_gazebo_ros_imu",),
        ros="ros1",
        level="model",  # gazebo_ros_imu.cpp:516
        frame_params=("frameId", "bodyName"),  # :99 frame_id_ = link_name_, :102-103 frameId
        frame_default=PARAM,
        frame_default_param="bodyName",
        topics=(("topicName", "imu"),),  # gazebo_ros_imu.cpp:100, :105-106
        source="tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_imu.cpp:99 (melodic-devel de947fb)",
    ),
    PluginSpec(
        family="hector GPS (ROS 1)",
        libraries=("hector_gazebo_ros_gps",),
        ros="ros1",
        level="model",  # gazebo_ros_gps.cpp:307
        frame_params=("frameId",),
        frame_default=LITERAL,
        frame_default_value="/world",  # gazebo_ros_gps.cpp:92
        # gazebo_ros_gps.cpp:93-94, :121-125
        topics=(("topicName", "fix"), ("velocityTopicName", "fix_velocity")),
        source="tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_gps.cpp:92 (melodic-devel de947fb)",
    ),
    PluginSpec(
        family="hector magnetometer (ROS 1)",
        libraries=("hector_gazebo_ros_magnetic",),
        ros="ros1",
        level="model",  # gazebo_ros_magnetic.cpp:237
        frame_params=("frameId", "bodyName"),  # :93 frame_id_ = link_name_, :110-111 frameId
        frame_default=PARAM,
        frame_default_param="bodyName",
        topics=(("topicName", "magnetic"),),  # gazebo_ros_magnetic.cpp:69-72
        source="tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_magnetic.cpp:93 (melodic-devel de947fb)",
    ),
    PluginSpec(
        family="hector sonar (ROS 1)",
        libraries=("hector_gazebo_ros_sonar",),
        ros="ros1",
        level="sensor",  # gazebo_ros_sonar.cpp:191 GZ_REGISTER_SENSOR_PLUGIN
        sensor_types=frozenset({"ray"}),  # gazebo_ros_sonar.cpp:63 RaySensor
        frame_params=("frameId",),
        frame_default=LITERAL,
        frame_default_value="/sonar_link",  # gazebo_ros_sonar.cpp:84, not the sensor's link
        topics=(("topicName", "sonar"),),  # gazebo_ros_sonar.cpp:83, :93-94
        source="tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_sonar.cpp:84 (melodic-devel de947fb)",
    ),
    PluginSpec(
        family="hector barometer (ROS 1)",
        libraries=("hector_gazebo_ros_baro",),
        ros="ros1",
        level="model",  # gazebo_ros_baro.cpp:169
        # gazebo_ros_baro.cpp:61-67 link = <bodyName> or the canonical link, :78 its name, :86
        frame_params=("frameId", "bodyName"),
        frame_default=PARAM,
        frame_default_param="bodyName",
        # gazebo_ros_baro.cpp:79-80, :87-88
        topics=(("topicName", "pressure_height"), ("altimeterTopicName", "altimeter")),
        source="tu-darmstadt-ros-pkg/hector_quadrotor@hector_quadrotor_gazebo_plugins/src/gazebo_ros_baro.cpp:78 (noetic-devel 9ba4441)",
    ),
    PluginSpec(
        family="hector IMU (ROS 2)",
        libraries=("hector_gazebo_ros_imu",),
        ros="ros2",
        level="model",  # gazebo_ros_imu.cpp:532
        frame_params=("frameId", "bodyName"),  # :94 frame_id_ = link_name_, :97-98 frameId
        frame_default=PARAM,
        frame_default_param="bodyName",
        topics=(("topicName", "imu"),),  # gazebo_ros_imu.cpp:95, :100-101
        source="tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_imu.cpp:94 (humble-devel f2ff0ac)",
    ),
    PluginSpec(
        family="hector GPS (ROS 2)",
        libraries=("hector_gazebo_ros_gps",),
        ros="ros2",
        level="model",  # gazebo_ros_gps.cpp:366
        frame_params=("frameId",),
        frame_default=LITERAL,
        frame_default_value="/world",  # gazebo_ros_gps.cpp:91
        topics=(("topicName", "fix"), ("velocityTopicName", "fix_velocity")),  # :92-93, :120-124
        source="tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_gps.cpp:91 (humble-devel f2ff0ac)",
    ),
    PluginSpec(
        family="hector magnetometer (ROS 2)",
        libraries=("hector_gazebo_ros_magnetic",),
        ros="ros2",
        level="model",  # gazebo_ros_magnetic.cpp:231
        frame_params=("frameId", "bodyName"),  # :89 frame_id_ = link_name_, :106-107 frameId
        frame_default=PARAM,
        frame_default_param="bodyName",
        topics=(("topicName", "magnetic"),),  # gazebo_ros_magnetic.cpp:65-68
        source="tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_magnetic.cpp:89 (humble-devel f2ff0ac)",
    ),
    PluginSpec(
        family="hector sonar (ROS 2)",
        libraries=("hector_gazebo_ros_sonar",),
        ros="ros2",
        level="sensor",  # gazebo_ros_sonar.cpp:180
        sensor_types=frozenset({"ray"}),
        frame_params=("frameId",),
        frame_default=LITERAL,
        frame_default_value="/sonar_link",  # gazebo_ros_sonar.cpp:81
        topics=(("topicName", "sonar"),),  # gazebo_ros_sonar.cpp:80, :90-91
        source="tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_sonar.cpp:81 (humble-devel f2ff0ac)",
    ),
    # ---------------------------------------------------------------------------------------
    # pal-robotics/realsense_gazebo_plugin: a model plugin that looks up four sensors by the
    # fixed names <prefix>depth, <prefix>color, <prefix>ired1, <prefix>ired2
    # (RealSensePlugin.cpp:136-146, names from include/.../RealSensePlugin.h:32-35). Each
    # stream is stamped with its own *OpticalframeName (RealSensePlugin.cpp:91-101); unset,
    # it stays the empty string (struct CameraParams, RealSensePlugin.h:37-43). Topics have
    # no default either; the *CameraInfoTopicName parameters are read but not used for
    # publishing (advertiseCamera on the image topic, gazebo_ros_realsense.cpp:48-55).
    # ROS 1: melodic-devel (49ab134); ROS 2: foxy-devel (73b3061).
    # ---------------------------------------------------------------------------------------
    PluginSpec(
        family="realsense_gazebo_plugin (ROS 1)",
        libraries=("realsense_gazebo_plugin",),  # CMakeLists.txt:2 project, :34-35 add_library
        ros="ros1",
        level="model",  # gazebo_ros_realsense.cpp:13 GZ_REGISTER_MODEL_PLUGIN
        frame_params=(
            "colorOpticalframeName",
            "depthOpticalframeName",
            "infrared1OpticalframeName",
            "infrared2OpticalframeName",
        ),
        frame_default=LITERAL,
        frame_default_value="",
        # RealSensePlugin.cpp:67-89, :109-110 (point cloud only with <pointCloud>true)
        topics=(
            ("colorTopicName", None),
            ("depthTopicName", None),
            ("infrared1TopicName", None),
            ("infrared2TopicName", None),
            ("pointCloudTopicName", None),
        ),
        owns=SensorOwnership(
            how=BY_NAME_SUFFIX,
            param="prefix",  # RealSensePlugin.cpp:115-116, default "" (:37)
            # SensorManager::GetSensor(prefix + "depth"/"ired1"/"ired2"/"color"),
            # RealSensePlugin.cpp:135-147 (names: RealSensePlugin.h:32-35); Gazebo Classic
            # matches the sensor's own (leaf) name when no scoped name matches
            # (elysia-best/gazebo-classic@upstream/11.10.2+dfsg:gazebo/sensors/SensorManager.cc:550-561, :885)
            suffixes=("depth", "color", "ired1", "ired2"),
            source="pal-robotics/realsense_gazebo_plugin@melodic-devel 49ab134:src/RealSensePlugin.cpp:135-147",
        ),
        source="pal-robotics/realsense_gazebo_plugin@src/RealSensePlugin.cpp:92 (melodic-devel 49ab134)",
    ),
    PluginSpec(
        family="realsense_gazebo_plugin (ROS 2)",
        libraries=("realsense_gazebo_plugin",),  # CMakeLists.txt:2 project, :44-45 add_library
        ros="ros2",
        level="model",  # gazebo_ros_realsense.cpp:17
        frame_params=(
            "colorOpticalframeName",
            "depthOpticalframeName",
            "infrared1OpticalframeName",
            "infrared2OpticalframeName",
        ),
        frame_default=LITERAL,
        frame_default_value="",
        # RealSensePlugin.cpp:69-91, :111-112; gazebo_ros_realsense.cpp:54-65
        topics=(
            ("colorTopicName", None),
            ("depthTopicName", None),
            ("infrared1TopicName", None),
            ("infrared2TopicName", None),
            ("pointCloudTopicName", None),
        ),
        owns=SensorOwnership(
            how=BY_NAME_SUFFIX,
            param="prefix",  # RealSensePlugin.cpp:117-118, default "" (:38)
            suffixes=("depth", "color", "ired1", "ired2"),  # RealSensePlugin.h:32-35
            source="pal-robotics/realsense_gazebo_plugin@foxy-devel 73b3061:src/RealSensePlugin.cpp:139-149",
        ),
        source="pal-robotics/realsense_gazebo_plugin@src/RealSensePlugin.cpp:94 (foxy-devel 73b3061)",
    ),
    # ---------------------------------------------------------------------------------------
    # sjtu_drone (NovoG93/sjtu_drone, branch ros2): one model plugin; its odometry frames are
    # hard-coded "<node namespace>/odom" -> "<node namespace>/base_footprint"
    # (sjtu_drone_description/src/plugin_drone_private.cpp:350-352), no frame parameter.
    # ---------------------------------------------------------------------------------------
    PluginSpec(
        family="sjtu_drone plugin_drone (ROS 2)",
        libraries=("plugin_drone",),  # sjtu_drone_description/CMakeLists.txt:42
        ros="ros2",
        level="model",  # plugin_drone.cpp:162 GZ_REGISTER_MODEL_PLUGIN
        source="NovoG93/sjtu_drone@sjtu_drone_description/src/plugin_drone_private.cpp:351 (ros2 4a643e2)",
    ),
    # ---------------------------------------------------------------------------------------
    # Gazebo Sim systems (gazebosim/gz-sim, gz-sim8). gz_add_system installs an unversioned
    # lib<project>-<name>-system.so (src/systems/CMakeLists.txt:84 on gz-sim8: "gz-sim-...";
    # on ign-gazebo6 / Fortress, :82: "ignition-gazebo-..."). None stamps ROS frames.
    # ---------------------------------------------------------------------------------------
    PluginSpec(
        family="Gazebo Sim diff drive",
        libraries=("gz-sim-diff-drive-system", "ignition-gazebo-diff-drive-system"),
        ros="gz",
        level="model",  # DiffDrive.cc:659 GZ_ADD_PLUGIN
        # DiffDrive.cc:379-383 <frame_id> (default "<model>/odom", :566-568) and
        # <child_frame_id> (default "<model>/<canonical link>", :576-584) of odometry and tf
        frame_params=("child_frame_id",),
        frame_default=NONE,
        # DiffDrive.cc:361-366 odom_topic, :372-375 tf_topic
        topics=(("odom_topic", "/model/{model}/odometry"), ("tf_topic", "/model/{model}/tf")),
        source="gazebosim/gz-sim@src/systems/diff_drive/DiffDrive.cc:383 (gz-sim8 b81e26d)",
    ),
    PluginSpec(
        family="Gazebo Sim joint state publisher",
        libraries=(
            "gz-sim-joint-state-publisher-system",
            "ignition-gazebo-joint-state-publisher-system",
        ),
        ros="gz",
        level="model",  # JointStatePublisher.cc:351
        # JointStatePublisher.cc:102-104 <topic>, default "/world/<world>/model/<model>/joint_state"
        # (:190)
        topics=(("topic", None),),
        source="gazebosim/gz-sim@src/systems/joint_state_publisher/JointStatePublisher.cc:102 (gz-sim8 b81e26d)",
    ),
    PluginSpec(
        family="Gazebo Sim sensors",
        libraries=("gz-sim-sensors-system", "ignition-gazebo-sensors-system"),
        ros="gz",
        level="model",  # Sensors.cc:1364; renders camera/depth/lidar sensors for the world
        source="gazebosim/gz-sim@src/systems/sensors/Sensors.cc:1364 (gz-sim8 b81e26d)",
    ),
    PluginSpec(
        family="Gazebo Sim IMU",
        libraries=("gz-sim-imu-system", "ignition-gazebo-imu-system"),
        ros="gz",
        level="model",
        source="gazebosim/gz-sim@src/systems/imu/Imu.cc:361 (gz-sim8 b81e26d)",
    ),
    PluginSpec(
        family="Gazebo Sim NavSat",
        libraries=("gz-sim-navsat-system", "ignition-gazebo-navsat-system"),
        ros="gz",
        level="model",
        source="gazebosim/gz-sim@src/systems/navsat/NavSat.cc:297 (gz-sim8 b81e26d)",
    ),
    PluginSpec(
        family="Gazebo Sim contact",
        libraries=("gz-sim-contact-system", "ignition-gazebo-contact-system"),
        ros="gz",
        level="model",
        source="gazebosim/gz-sim@src/systems/contact/Contact.cc:320 (gz-sim8 b81e26d)",
    ),
    PluginSpec(
        family="Gazebo Sim pose publisher",
        libraries=("gz-sim-pose-publisher-system", "ignition-gazebo-pose-publisher-system"),
        ros="gz",
        level="model",
        source="gazebosim/gz-sim@src/systems/pose_publisher/PosePublisher.cc:618 (gz-sim8 b81e26d)",
    ),
    PluginSpec(
        family="Gazebo Sim detachable joint",
        libraries=("gz-sim-detachable-joint-system", "ignition-gazebo-detachable-joint-system"),
        ros="gz",
        level="model",
        source="gazebosim/gz-sim@src/systems/detachable_joint/DetachableJoint.cc:395 (gz-sim8 b81e26d)",
    ),
    PluginSpec(
        family="Gazebo Sim linear battery",
        libraries=(
            "gz-sim-linearbatteryplugin-system",
            "ignition-gazebo-linearbatteryplugin-system",
        ),
        ros="gz",
        level="model",
        source="gazebosim/gz-sim@src/systems/battery_plugin/LinearBatteryPlugin.cc:748 (gz-sim8 b81e26d)",
    ),
)


# The RobotHWSim classes gazebo_ros_control (ROS 1) loads by <robotSimType>, and the sensors
# each reads (None: none). A class not listed is unknown: it may read sensors by name, and
# sensorkit cannot tell which.
HARDWARE_SIMS: dict[str, SensorOwnership | None] = {
    # Joints only: default_robot_hw_sim.cpp looks up no sensor (no SensorManager call in
    # the file; ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a46).
    "gazebo_ros_control/DefaultRobotHWSim": None,
    # PAL's RobotHWSim: IMU sensors by the Gazebo sensor name in the ROS parameter
    # imu/<id>/gazebo_sensor_name (pal_hardware_gazebo.cpp:263-280: getIds(nh, "imu"),
    # fetchParam "gazebo_sensor_name", SensorManager::GetSensor). Its force-torque values
    # come from a joint (force_torque/<id>/sensor_joint, model->GetJoint, :175-181), not
    # from a Gazebo sensor.
    "pal_hardware_gazebo/PalHardwareGazebo": SensorOwnership(
        how=BY_ROS_PARAMS,
        sensor_types=frozenset({"imu"}),
        where="the ROS parameters imu/<id>/gazebo_sensor_name",
        source="pal-robotics/pal_hardware_gazebo@melodic-devel 320e672:src/pal_hardware_gazebo.cpp:263-280",
    ),
    # PAL's transmission variant derives from RobotHWSim directly
    # (include/pal_hardware_gazebo/pal_hardware_transmission_gazebo.h:44) and reads no sensor.
    "pal_hardware_gazebo/PalHardwareTransmissionGazebo": None,
}


# The <ros2_control><hardware><plugin> classes of the ros2_control simulator plugins, whose
# sensor reading the plugin specs above record (``owns``). gazebo_ros2_control and
# gz_ros2_control load the class a block names by pluginlib; any other class (a fork's, a
# project's own) decides what it reads, and sensorkit cannot tell (sensorkit.model.owners).
ROS2_CONTROL_SYSTEMS = frozenset(
    {
        # ros-controls/gazebo_ros2_control@humble 42d875b:gazebo_ros2_control/gazebo_hardware_plugins.xml:3
        "gazebo_ros2_control/GazeboSystem",
        # ros-controls/gz_ros2_control@jazzy fa9ced4:gz_ros2_control/gz_hardware_plugins.xml:3,11
        "gz_ros2_control/GazeboSimSystem",
        # ros-controls/gz_ros2_control@humble 4cb90a2:ign_ros2_control/ign_hardware_plugins.xml:3
        "ign_ros2_control/IgnitionSystem",
    }
)


def lookup(filename_or_library: str, ros: str) -> PluginSpec | None:
    """The spec of a plugin for ``ros`` ("ros2", "ros1" or "gz"), or None when unknown."""
    base = filename_or_library.rsplit("/", 1)[-1]
    if base.startswith("lib"):
        base = base[3:]
    if base.endswith(".so"):
        base = base[:-3]
    return _INDEX.get((base, ros))


_INDEX: dict[tuple[str, str], PluginSpec] = {
    (lib, spec.ros): spec for spec in PLUGINS for lib in spec.libraries
}


def generation_params(filename_or_library: str) -> tuple[frozenset[str], frozenset[str]]:
    """(ROS 1-only, ROS 2-only) parameters of a plugin library both ROS generations build.

    A parameter the library's ROS 1 spec reads and its ROS 2 spec does not (``topicName``
    of velodyne's laser) marks a description written for ROS 1, and the other way round.
    Empty sets when the library lacks either spec or either spec has no recorded params.
    """
    one, two = lookup(filename_or_library, "ros1"), lookup(filename_or_library, "ros2")
    if one is not None and one.params and two is None:
        # A ROS 1 library built from the same source as one that has a ROS 2 port reads the
        # same parameters (velodyne's gpu library: the CPU source built twice,
        # lmark1/velodyne_simulator@velodyne_gazebo_plugins/CMakeLists.txt:29,36), so the
        # port's parameters tell the generations apart for it too.
        two = next(
            (
                spec
                for spec in PLUGINS
                if spec.ros == "ros2"
                and spec.params
                and any(
                    (sib := lookup(lib, "ros1")) is not None and sib.params == one.params
                    for lib in spec.libraries
                )
            ),
            None,
        )
    if one is None or two is None or not one.params or not two.params:
        return frozenset(), frozenset()
    return one.params - two.params, two.params - one.params
