"""Facts from plugin source code that rules rely on (sensorkit.knowledge.plugins).

Each test pins one fact and cites the line it was read from.
"""

from __future__ import annotations

import re

import pytest

from sensorkit.knowledge import plugins as known
from sensorkit.knowledge.plugins import PLUGINS, lookup


def _spec(name: str, ros: str) -> known.PluginSpec:
    spec = lookup(name, ros)
    assert spec is not None, f"{name} ({ros}) is not known"
    return spec


# ---- the table itself --------------------------------------------------------------------

SOURCE = re.compile(r"^[\w.-]+/[\w.-]+@\S+:\d+")


@pytest.mark.parametrize("spec", PLUGINS, ids=lambda s: s.family)
def test_every_entry_cites_its_source(spec: known.PluginSpec) -> None:
    assert SOURCE.match(spec.source), spec.source


@pytest.mark.parametrize("spec", PLUGINS, ids=lambda s: s.family)
def test_every_entry_is_well_formed(spec: known.PluginSpec) -> None:
    assert spec.libraries
    assert spec.ros in ("ros1", "ros2", "gz")
    assert spec.level in ("sensor", "model", "visual")
    assert spec.frame_default in (known.LINK, known.WORLD, known.NONE, known.PARAM, known.LITERAL)
    assert (spec.frame_default == known.PARAM) == (spec.frame_default_param is not None)
    assert (spec.frame_default == known.LITERAL) == (spec.frame_default_value is not None)
    assert not spec.lumped or spec.frame_default == known.LINK
    assert not spec.sensor_types or spec.level == "sensor"
    for lib in spec.libraries:
        assert not lib.startswith("lib") and not lib.endswith(".so"), lib


def test_no_library_twice_for_the_same_ros() -> None:
    seen: set[tuple[str, str]] = set()
    for spec in PLUGINS:
        for lib in spec.libraries:
            assert (lib, spec.ros) not in seen, (lib, spec.ros)
            seen.add((lib, spec.ros))


def test_unknown_plugins_give_none() -> None:
    assert lookup("libnot_a_real_plugin.so", "ros2") is None
    assert lookup("libgazebo_ros_camera.so", "gz") is None


def test_lookup_accepts_filenames_paths_and_bare_names() -> None:
    spec = _spec("libgazebo_ros_camera.so", "ros2")
    assert lookup("gazebo_ros_camera", "ros2") is spec
    assert lookup("/opt/ros/humble/lib/libgazebo_ros_camera.so", "ros2") is spec


def test_one_library_differs_by_generation() -> None:
    # same file name, different code: ROS 2 gazebo_plugins vs ROS 1 gazebo_plugins
    assert _spec("libgazebo_ros_camera.so", "ros2") is not _spec("libgazebo_ros_camera.so", "ros1")


# ---- gazebo_ros_pkgs ROS 2 ----------------------------------------------------------------


def test_ros2_camera_frame_is_frame_name_else_lumped_link() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera.cpp:182 (ros2)
    # -> gazebo_ros/src/utils.cpp:52-61 SensorFrameID: <frame_name> else the parent link
    spec = _spec("libgazebo_ros_camera.so", "ros2")
    assert spec.frame_params == ("frame_name",)
    assert spec.frame_default == known.LINK
    assert spec.lumped


def test_ros2_camera_accepts_camera_depth_multicamera() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera.cpp:160-176 (ros2)
    spec = _spec("libgazebo_ros_camera.so", "ros2")
    assert spec.level == "sensor"
    assert spec.sensor_types == {"camera", "depth", "multicamera"}


def test_ros2_camera_topics_under_camera_name_defaulting_to_sensor_name() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera.cpp:179 camera_name,
    # :187 image_raw, :200 camera_info, :241 depth/image_raw, :250 depth/camera_info, :260 points
    spec = _spec("libgazebo_ros_camera.so", "ros2")
    assert spec.topic_ns_param == "camera_name"
    assert spec.topic_ns_default == "{sensor}"
    names = {default for _, default in spec.topics}
    assert names == {"image_raw", "camera_info", "depth/image_raw", "depth/camera_info", "points"}


@pytest.mark.parametrize(
    "lib",
    ["gazebo_ros_ray_sensor", "gazebo_ros_imu_sensor", "gazebo_ros_gps_sensor"],
)
def test_ros2_sensor_plugins_use_sensor_frame_id(lib: str) -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_ray_sensor.cpp:113,
    # gazebo_ros_imu_sensor.cpp:102, gazebo_ros_gps_sensor.cpp:89 (ros2)
    spec = _spec(lib, "ros2")
    assert spec.frame_params == ("frame_name",)
    assert spec.frame_default == known.LINK
    assert spec.lumped


def test_ros2_ray_sensor_publishes_out() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_ray_sensor.cpp:119-134 (ros2)
    spec = _spec("libgazebo_ros_ray_sensor.so", "ros2")
    assert spec.topics == ((None, "~/out"),)
    assert spec.sensor_types == {"ray", "gpu_ray"}


def test_ros2_imu_publishes_out() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_imu_sensor.cpp:95-96 (ros2)
    assert _spec("libgazebo_ros_imu_sensor.so", "ros2").topics == ((None, "~/out"),)


def test_ros2_p3d_is_world_referenced() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_p3d.cpp:66,170-182 (ros2)
    spec = _spec("libgazebo_ros_p3d.so", "ros2")
    assert spec.level == "model"
    assert spec.frame_params == ("frame_name",)
    assert spec.frame_default == known.WORLD
    assert spec.world_frame_ok
    assert spec.topics == ((None, "odom"),)  # gazebo_ros_p3d.cpp:63


def test_ros2_bumper_defaults_to_world() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_bumper.cpp:99 (ros2)
    spec = _spec("libgazebo_ros_bumper.so", "ros2")
    assert spec.frame_default == known.WORLD
    assert spec.world_frame_ok
    assert spec.sensor_types == {"contact"}


def test_ros2_ft_sensor_is_a_model_plugin() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_ft_sensor.cpp:226,128 (ros2)
    spec = _spec("libgazebo_ros_ft_sensor.so", "ros2")
    assert spec.level == "model"
    assert spec.frame_default == known.WORLD


def test_ros2_diff_drive_base_frame_defaults_to_base_footprint() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_diff_drive.cpp:363 (ros2)
    spec = _spec("libgazebo_ros_diff_drive.so", "ros2")
    assert spec.frame_params == ("robot_base_frame",)
    assert spec.frame_default_value == "base_footprint"


def test_ros2_tricycle_drive_base_frame_defaults_to_base_link() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_tricycle_drive.cpp:249 (ros2)
    assert _spec("libgazebo_ros_tricycle_drive.so", "ros2").frame_default_value == "base_link"


def test_ros2_force_frame_is_a_keyword_not_a_frame() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_force.cpp:82-92 (ros2)
    assert _spec("libgazebo_ros_force.so", "ros2").frame_params == ()


def test_ros2_video_is_a_visual_plugin() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_video.cpp:260 (ros2)
    assert _spec("libgazebo_ros_video.so", "ros2").level == "visual"


# ---- gazebo_ros_pkgs ROS 1 ----------------------------------------------------------------


def test_ros1_camera_reads_frame_name_and_defaults_to_empty() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera_utils.cpp:146-149
    # and include/gazebo_plugins/gazebo_ros_camera_utils.h:142 (noetic-devel): no default
    spec = _spec("libgazebo_ros_camera.so", "ros1")
    assert spec.frame_params == ("frameName",)
    assert spec.frame_default == known.LITERAL
    assert spec.frame_default_value == ""
    assert not spec.lumped


def test_ros1_camera_topics_under_camera_name() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_camera_utils.cpp:124-140,288
    spec = _spec("libgazebo_ros_camera.so", "ros1")
    assert spec.topic_ns_param == "cameraName"
    assert ("imageTopicName", "image_raw") in spec.topics
    assert ("cameraInfoTopicName", "camera_info") in spec.topics


def test_ros1_depth_camera_image_default_is_not_ir() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_depth_camera.cpp:92-95 is
    # overwritten by gazebo_ros_camera_utils.cpp:124 (Load called at depth_camera.cpp:143)
    spec = _spec("libgazebo_ros_openni_kinect.so", "ros1")
    assert ("imageTopicName", "image_raw") in spec.topics
    assert ("pointCloudTopicName", "points") in spec.topics
    assert spec.frame_params == ("frameName",)


@pytest.mark.parametrize("lib", ["gazebo_ros_laser", "gazebo_ros_gpu_laser", "gazebo_ros_range"])
def test_ros1_lasers_default_to_slash_world(lib: str) -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_laser.cpp:91,
    # gazebo_ros_gpu_laser.cpp:94, gazebo_ros_range.cpp:114 (noetic-devel)
    spec = _spec(lib, "ros1")
    assert spec.frame_params == ("frameName",)
    assert spec.frame_default_value == "/world"
    assert not spec.world_frame_ok


def test_ros1_laser_topic_default_is_world_too() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_laser.cpp:97-103 (noetic-devel)
    assert _spec("libgazebo_ros_laser.so", "ros1").topics == (("topicName", "/world"),)


def test_ros1_imu_model_plugin_frame_defaults_to_body_name() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_imu.cpp:130-136 (noetic-devel)
    spec = _spec("libgazebo_ros_imu.so", "ros1")
    assert spec.level == "model"
    assert spec.frame_params[0] == "frameName"
    assert spec.frame_default == known.PARAM
    assert spec.frame_default_param == "bodyName"


def test_ros1_imu_sensor_requires_frame_name() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_imu_sensor.cpp:202-210
    spec = _spec("libgazebo_ros_imu_sensor.so", "ros1")
    assert spec.frame_params == ("frameName",)
    assert spec.frame_default == known.NONE
    assert spec.topics == (("topicName", "imu_data"),)


def test_ros1_p3d_is_world_referenced_with_required_topic() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_plugins/src/gazebo_ros_p3d.cpp:81-95 (noetic-devel)
    spec = _spec("libgazebo_ros_p3d.so", "ros1")
    assert spec.frame_params == ("frameName",)
    assert spec.world_frame_ok
    assert spec.topics == (("topicName", None),)


def test_ros1_control_has_no_frame() -> None:
    # ros-simulation/gazebo_ros_pkgs@gazebo_ros_control/src/gazebo_ros_control_plugin.cpp:314
    spec = _spec("libgazebo_ros_control.so", "ros1")
    assert spec.level == "model"
    assert spec.frame_params == () and spec.topics == ()


# ---- third-party plugins ------------------------------------------------------------------


def test_velodyne_ros1_reads_frame_name_camel_case() -> None:
    # lmark1/velodyne_simulator@velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:119-151
    for lib in ("gazebo_ros_velodyne_laser", "gazebo_ros_velodyne_gpu_laser"):
        spec = _spec(lib, "ros1")
        assert spec.frame_params == ("frameName",)
        assert spec.frame_default_value == "/world"
        assert spec.topics == (("topicName", "/points"),)


def test_velodyne_ros2_port_uses_sensor_frame_id() -> None:
    # tier4/velodyne_simulator@velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:80,118
    spec = _spec("libgazebo_ros_velodyne_laser.so", "ros2")
    assert spec.frame_params == ("frame_name",)
    assert spec.lumped
    assert spec.topics == ((None, "~/out"),)


def test_hector_imu_frame_id_defaults_to_body() -> None:
    # tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_imu.cpp:99-106
    spec = _spec("libhector_gazebo_ros_imu.so", "ros1")
    assert spec.level == "model"
    assert spec.frame_params[0] == "frameId"
    assert spec.frame_default_param == "bodyName"
    assert spec.topics == (("topicName", "imu"),)


def test_hector_sonar_default_frame_is_a_fixed_name() -> None:
    # tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_sonar.cpp:84
    spec = _spec("libhector_gazebo_ros_sonar.so", "ros1")
    assert spec.level == "sensor"
    assert spec.frame_default == known.LITERAL
    assert spec.frame_default_value == "/sonar_link"


def test_hector_gps_default_frame_is_world() -> None:
    # tu-darmstadt-ros-pkg/hector_gazebo@hector_gazebo_plugins/src/gazebo_ros_gps.cpp:92
    assert _spec("libhector_gazebo_ros_gps.so", "ros1").frame_default_value == "/world"


@pytest.mark.parametrize("ros", ["ros1", "ros2"])
def test_realsense_plugin_is_model_level_with_sensor_params(ros: str) -> None:
    # pal-robotics/realsense_gazebo_plugin@src/RealSensePlugin.cpp:91-118,136-146
    spec = _spec("librealsense_gazebo_plugin.so", ros)
    assert spec.level == "model"
    assert spec.owns is not None and spec.owns.param == "prefix"
    assert "depthOpticalframeName" in spec.frame_params
    assert "colorOpticalframeName" in spec.frame_params


@pytest.mark.parametrize(
    ("name", "ros"),
    [
        ("libgazebo_ros2_control.so", "ros2"),
        ("gz_ros2_control-system", "gz"),
        ("libign_ros2_control-system.so", "gz"),
    ],
)
def test_ros2_control_bridges_have_no_frame(name: str, ros: str) -> None:
    # ros-controls/gazebo_ros2_control@gazebo_ros2_control/CMakeLists.txt:31,
    # ros-controls/gz_ros2_control@gz_ros2_control/CMakeLists.txt:35
    spec = _spec(name, ros)
    assert spec.level == "model"
    assert spec.frame_params == () and spec.topics == ()


# ---- Gazebo Sim systems -------------------------------------------------------------------


def test_gz_diff_drive_names_its_child_frame() -> None:
    # gazebosim/gz-sim@src/systems/diff_drive/DiffDrive.cc:379-383 (gz-sim8)
    spec = _spec("gz-sim-diff-drive-system", "gz")
    assert spec.frame_params == ("child_frame_id",)
    assert lookup("libignition-gazebo-diff-drive-system.so", "gz") is spec


def test_gz_systems_know_both_library_prefixes() -> None:
    # gazebosim/gz-sim@src/systems/CMakeLists.txt:84 (gz-sim8) and :82 (ign-gazebo6)
    for system in ("joint-state-publisher", "sensors", "imu", "navsat", "pose-publisher"):
        assert lookup(f"gz-sim-{system}-system", "gz") is not None
        assert lookup(f"ignition-gazebo-{system}-system", "gz") is not None


def test_velodyne_generations_read_different_parameters() -> None:
    # ROS 1: tier4/velodyne_simulator@master fe021b6:GazeboRosVelodyneLaser.cpp:115-158;
    # ROS 2 port: prepare/humble 00759c8:GazeboRosVelodyneLaser.cpp:73-114.
    ros1_only, ros2_only = known.generation_params("libgazebo_ros_velodyne_laser.so")
    assert {"topicName", "frameName", "gaussianNoise", "robotNamespace"} <= ros1_only
    assert {"ros", "frame_name", "gaussian_noise", "tf_prefix"} <= ros2_only
    # Both read organize_cloud: upstream ROS 1 since 1.0.11 (effeed2; Winsleo/velodyne_simulator
    # @a7cec2a, 1.0.13 catkin: GazeboRosVelodyneLaser.cpp:128-133), so it marks neither.
    assert not {"min_range", "max_range", "min_intensity", "organize_cloud"} & (ros1_only | ros2_only)
    # The GPU library has no ROS 2 port; the CPU port's parameters stand for it (one source).
    assert known.generation_params("libgazebo_ros_velodyne_gpu_laser.so") == (ros1_only, ros2_only)
    # Near miss: gazebo_ros_pkgs' plugins are told apart by sensorkit.knowledge.gazebo_ros.
    assert known.generation_params("libgazebo_ros_camera.so") == (frozenset(), frozenset())
