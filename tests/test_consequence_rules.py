"""Issue 35 item 1: rules whose severity is computed from consequence (base.consequence),
each with a trigger that is an error and a near miss that is info because what the
simulator uses equals what was written. Sources beside each case and the rule."""

from __future__ import annotations

from builders import camera_sensor, gz_robot, joint, lidar_sensor, link, robot

from sensorkit.base.findings import Severity


def _of(report: object, rule: str) -> list:  # type: ignore[type-arg]
    return [f for f in report.findings if f.rule == rule]  # type: ignore[attr-defined]


# --- SK605: a shared camera_info carrying the same K/P is a duplicate ---------------------


def _gz_two_cameras(second_fov: str = "1.3962634", info_b: str = "shared/camera_info", same_link: bool = False) -> str:
    def cam(name: str, topic: str, fov: str, info: str) -> str:
        return (
            f'<sensor name="{name}" type="camera"><update_rate>30</update_rate><topic>{topic}</topic>'
            f"<gz_frame_id>camera_optical_frame</gz_frame_id><camera><camera_info_topic>{info}</camera_info_topic>"
            f"<horizontal_fov>{fov}</horizontal_fov><image><width>640</width><height>480</height></image>"
            "<clip><near>0.05</near><far>50</far></clip></camera></sensor>"
        )

    # back_link hangs on a moving joint: lumping keeps it a link of its own (camera_link
    # lumps into base_footprint), so its camera is on another gz link.
    other = "base_link" if same_link else "back_link"
    extra = (
        (link("back_link") + joint("back_joint", "base_link", "back_link", "-0.2 0 0.1", type="continuous",
                                   extra='<axis xyz="0 0 1"/>'))
        + f'<gazebo reference="{other}">{cam("cam_b", "cam_b/image", second_fov, info_b)}</gazebo>'
    )
    text = gz_robot(extra=extra)
    return text.replace("<topic>front_camera/image_raw</topic>", "<topic>cam_a/image</topic>").replace(
        "<camera><horizontal_fov>", "<camera><camera_info_topic>shared/camera_info</camera_info_topic><horizontal_fov>", 1
    )


def test_sk605_same_calibration_on_one_camera_info_topic_is_info(check) -> None:
    # gz-sensors8 CameraSensor reads <camera_info_topic> (CameraSensor.cc:662-676): both
    # cameras publish camera_info on /shared/camera_info with the same K and P.
    found = _of(check(_gz_two_cameras(), target="harmonic"), "SK605")
    assert [f.severity for f in found] == [Severity.INFO], [f.message for f in found]
    assert "the same calibration twice" in found[0].message


def test_sk605_different_calibration_on_one_camera_info_topic_is_an_error(check) -> None:
    found = _of(check(_gz_two_cameras(second_fov="1.2"), target="harmonic"), "SK605")
    assert [f.severity for f in found] == [Severity.ERROR]
    assert "hfov 1.2" in found[0].message and "hfov 1.39626" in found[0].message


def test_sk605_two_cameras_of_one_gz_link_are_never_called_the_same(check) -> None:
    # gz-sim gives the second camera of a link its own baseline (gz-sim8 Sensors.cc:1189-1224).
    found = _of(check(_gz_two_cameras(same_link=True), target="harmonic"), "SK605")
    assert [f.severity for f in found] == [Severity.ERROR]


def test_sk605_shared_images_stay_an_error(check) -> None:
    # Same camera_name on two ROS 2 cameras: image_raw and camera_info both shared.
    second = camera_sensor("back_camera", params="<camera_name>front_camera</camera_name><frame_name>camera_optical_frame</frame_name>")
    extra = link("back_link") + joint("back_joint", "base_link", "back_link", "-0.2 0 0.1") + f'<gazebo reference="back_link">{second}</gazebo>'
    found = _of(check(robot(extra=extra), target="classic"), "SK605")
    assert [f.severity for f in found] == [Severity.ERROR]


# --- SK406: a non-integer sample count, as sdformat's std::stoul reads it ----------------
# gazebosim/sdformat@sdf9 9ee2d4f:src/Param.cc:354-357 (sdf12 b9417e5:702-705, sdf14 8512585:
# 911-914): std::stoul(tmp, nullptr, base) reads the leading digits and ignores the rest.


def test_sk406_fractional_samples_truncate_to_the_same_lidar(check) -> None:
    for target in ("classic", "harmonic"):
        found = _of(check(robot(lidar=lidar_sensor(samples="666.5185185185185")), target=target), "SK406")
        assert [f.severity for f in found] == [Severity.INFO], [f.message for f in found]
        assert "the simulator uses 666" in found[0].message


def test_sk406_samples_that_are_not_a_number_stay_an_error(check) -> None:
    found = _of(check(robot(lidar=lidar_sensor(samples="many")), target="classic"), "SK406")
    assert [f.severity for f in found] == [Severity.ERROR]


# --- SK301: what the dropped links held ------------------------------------------------------
# sdformat's URDF conversion drops a massless link not lumped away and its subtree
# (gazebosim/sdformat@sdf9 9ee2d4f:src/parser_urdf.cc:2658-2760).


def _dropped(body: str) -> str:
    return robot(extra=f'<link name="w">{body}</link>' + joint("wj", "base_link", "w", type="continuous", extra='<axis xyz="0 1 0"/>'))


def test_sk301_a_dropped_body_is_an_error_a_tf_only_link_info(check) -> None:
    box = '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
    assert [f.severity for f in _of(check(_dropped(box), target="classic"), "SK301")] == [Severity.ERROR]
    found = _of(check(_dropped(""), target="classic"), "SK301")
    assert [f.severity for f in found] == [Severity.INFO]
    assert "only TF knows them" in found[0].message


def test_sk301_a_dropped_sensor_is_an_error(check) -> None:
    assert [f.severity for f in _of(check(robot(camera_joint_type="revolute", camera_body=""), target="classic"), "SK301")] == [Severity.ERROR]


# --- SK303: the survivor frame against the link, for the sensor's data ---------------------
# gazebo_ros::SensorFrameID returns the link after lumping (ros-simulation/gazebo_ros_pkgs@ros2
# d52f7c4:gazebo_ros/src/utils.cpp:52-61).


def _imu_lumped(rpy: str) -> str:
    imu = (
        link("imu_link") + joint("imu_joint", "base_link", "imu_link", "0.1 0 0.05", rpy)
        + '<gazebo reference="imu_link"><sensor name="imu" type="imu"><update_rate>100</update_rate>'
        '<plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so"/></sensor></gazebo>'
    )
    return robot(extra=imu)


def test_sk303_imu_translated_only_is_info_and_turned_is_an_error(check) -> None:
    # The IMU's message does not depend on where its frame sits
    # (gazebo_ros_imu_sensor.cpp:102, :135-140).
    found = _of(check(_imu_lumped("0 0 0"), target="classic"), "SK303")
    assert [f.severity for f in found] == [Severity.INFO]
    assert "written imu_link; the simulator uses base_footprint" in found[0].message
    assert [f.severity for f in _of(check(_imu_lumped("0 0 0.02"), target="classic"), "SK303")] == [Severity.ERROR]


def test_sk303_a_lidar_moved_by_lumping_is_an_error(check) -> None:
    lid = lidar_sensor(params="<output_type>sensor_msgs/LaserScan</output_type>")
    found = _of(check(robot(lidar=lid), target="classic"), "SK303")
    assert [f.severity for f in found] == [Severity.ERROR]


# --- SK608: an ignored gz frame tag, by the frame stamped instead ---------------------------
# Harmonic's gz-sensors reads gz_frame_id only (gazebosim/gz-sensors@gz-sensors8 c8159af:
# src/Sensor.cc:184-195); without it the frame is the scoped sensor name.


def test_sk608_ignored_tag_is_an_error_when_another_frame_is_stamped(check) -> None:
    only = gz_robot(lidar_tags="<topic>scan</topic><ignition_frame_id>laser_link</ignition_frame_id>")
    found = _of(check(only, target="harmonic"), "SK608")
    assert [f.severity for f in found] == [Severity.ERROR]
    assert "written laser_link; the simulator uses" in found[0].message
    both = gz_robot(lidar_tags="<topic>scan</topic><ignition_frame_id>laser_link</ignition_frame_id><gz_frame_id>laser_link</gz_frame_id>")
    assert [f.severity for f in _of(check(both, target="harmonic"), "SK608")] == [Severity.INFO]


def test_sk608_two_tags_naming_different_frames_is_a_warning(check) -> None:
    # gz_frame_id read, ignition_frame_id ignored, each naming another frame: which one was
    # meant is not known, so no error is promised.
    two = gz_robot(lidar_tags="<topic>scan</topic><ignition_frame_id>base_link</ignition_frame_id><gz_frame_id>laser_link</gz_frame_id>")
    found = _of(check(two, target="harmonic"), "SK608")
    assert [f.severity for f in found] == [Severity.WARNING]
    assert "written base_link; the simulator uses laser_link" in found[0].message


# --- the declared-severity check (conftest) -------------------------------------------------


def test_a_severity_its_rule_does_not_declare_is_caught() -> None:
    # conftest wraps Context.finding for the whole suite: SK503 declares "error" only, so a
    # warning from it (the mutation "SK503 reported as a warning") is recorded and fails the
    # test that made it; a declared one is not.
    import conftest

    from sensorkit.base.findings import SourceRef
    from sensorkit.lint.rules.base import Context

    before = len(conftest._UNDECLARED)
    Context.finding(object(), "SK503", Severity.ERROR, "m", SourceRef(None, None))  # type: ignore[arg-type]
    assert len(conftest._UNDECLARED) == before
    Context.finding(object(), "SK503", Severity.WARNING, "m", SourceRef(None, None))  # type: ignore[arg-type]
    assert len(conftest._UNDECLARED) == before + 1 and "SK503 made warning" in conftest._UNDECLARED[-1]
    del conftest._UNDECLARED[before:]
