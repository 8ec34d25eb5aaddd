"""SK602's severity by consequence (issue 23): a ROS 1 tag the ROS 2 plugin ignores is an
error only when its value moves a topic or frame or changes a calibration or a drive,
a warning when it changes a rate, noise, limit or flag, and info when its value is what
ROS 2 does anyway.

Sources (ros-simulation/gazebo_ros_pkgs, ros2 d52f7c4 and noetic-devel f9e1a46), as in
sensorkit/knowledge/gazebo_ros.py ROS1_PARAM_ROLE and ROS2_PLAIN_DEFAULTS:
- ROS 2 camera: camera_name defaults to the sensor's name (gazebo_ros_camera.cpp:179),
  cx/cy to (w + 1) / 2, (h + 1) / 2 (:359-363), focal_length 0 means computed (:366-374);
  ROS 1 camera utils: 0 means computed too (gazebo_ros_camera_utils.cpp:504-519).
- ROS 1 throttles at updateRate (gazebo_ros_camera_utils.cpp:441-444); ROS 2 publishes at
  the sensor's <update_rate>.
- ROS 2 IMU: initial_orientation_as_reference false (gazebo_ros_imu_sensor.cpp:74-82), no
  noise or offset of its own (:136-140); ROS 1's imu_sensor never used xyzOffset (:237-247
  "POSITION OFFSET, UNUSED") and never read bodyName.
- No ROS 1 plugin reads alwaysOn (noetic-devel: `git grep '"alwaysOn"'` finds nothing).
- ROS 2 diff drive: wheel_separation 0.34 (gazebo_ros_diff_drive.cpp:310), no joint without
  <left_joint> ("Plugin will not work.", :295-300).
"""

from __future__ import annotations

from collections.abc import Callable

import pytest
from builders import camera_sensor, lidar_sensor, robot

from sensorkit.lint.engine import FileReport

Check = Callable[..., FileReport]


def _sk602(report: FileReport) -> dict[str, tuple[str, str]]:
    """tag -> (severity, message) of each SK602 finding."""
    out = {}
    for f in report.findings:
        if f.rule == "SK602":
            tag = f.message.split(">", 1)[0].lstrip("<")
            out[tag] = (f.severity.label, f.message)
    return out


def _camera(params: str, extra: str = "<update_rate>30</update_rate>") -> str:
    return robot(camera=camera_sensor(params=params, extra=extra))


@pytest.mark.parametrize(
    ("params", "tag", "severity"),
    [
        # the data moves: error
        ("<frame_name>camera_optical_frame</frame_name><cameraName>cam</cameraName>", "cameraName", "error"),
        ("<frameName>camera_optical_frame</frameName>", "frameName", "error"),
        ("<frame_name>camera_optical_frame</frame_name><Cx>100</Cx>", "Cx", "error"),
        ("<frame_name>camera_optical_frame</frame_name><focalLength>900</focalLength>", "focalLength", "error"),
        ("<frame_name>camera_optical_frame</frame_name><imageTopicName>rgb/image</imageTopicName>", "imageTopicName", "error"),
        # works, not as tuned: warning
        ("<frame_name>camera_optical_frame</frame_name><updateRate>15</updateRate>", "updateRate", "warning"),
        ("<frame_name>camera_optical_frame</frame_name><distortionK1>0.1</distortionK1>", "distortionK1", "warning"),
        # what ROS 2 does anyway: info (near misses of the two above)
        ("<frame_name>camera_optical_frame</frame_name><cameraName>front_camera</cameraName>", "cameraName", "info"),
        ("<frame_name>camera_optical_frame</frame_name><frameName>/camera_optical_frame</frameName>", "frameName", "info"),
        ("<frame_name>camera_optical_frame</frame_name><Cx>0</Cx>", "Cx", "info"),
        ("<frame_name>camera_optical_frame</frame_name><Cx>320.5</Cx>", "Cx", "info"),
        ("<frame_name>camera_optical_frame</frame_name><Cy>0</Cy>", "Cy", "info"),
        ("<frame_name>camera_optical_frame</frame_name><focalLength>0</focalLength>", "focalLength", "info"),
        ("<frame_name>camera_optical_frame</frame_name><updateRate>0</updateRate>", "updateRate", "info"),
        ("<frame_name>camera_optical_frame</frame_name><updateRate>30</updateRate>", "updateRate", "info"),
        ("<frame_name>camera_optical_frame</frame_name><distortionK1>0.0</distortionK1>", "distortionK1", "info"),
        ("<frame_name>camera_optical_frame</frame_name><hackBaseline>0</hackBaseline>", "hackBaseline", "info"),
        ("<frame_name>camera_optical_frame</frame_name><imageTopicName>image_raw</imageTopicName>"
         "<cameraName>front_camera</cameraName>", "imageTopicName", "info"),
        ("<frame_name>camera_optical_frame</frame_name><alwaysOn>true</alwaysOn>", "alwaysOn", "info"),
    ],
)
def test_camera_tags_by_consequence(check: Check, params: str, tag: str, severity: str) -> None:
    found = _sk602(check(_camera(params), target="classic"))
    assert tag in found, found
    assert found[tag][0] == severity, found[tag][1]


def test_a_harmless_tag_says_nothing_changes_and_fails_nothing(check: Check) -> None:
    report = check(_camera("<frame_name>camera_optical_frame</frame_name><Cy>0</Cy>"), target="classic")
    sev, message = _sk602(report)["Cy"]
    assert sev == "info" and "nothing changes" in message and "240.5" in message
    assert not [f for f in report.findings if f.severity.label == "error"], report.findings


def test_a_topic_tag_names_both_topics(check: Check) -> None:
    sev, message = _sk602(
        check(_camera("<frame_name>camera_optical_frame</frame_name><imageTopicName>rgb/image</imageTopicName>"), target="classic")
    )["imageTopicName"]
    assert sev == "error"
    assert "/front_camera/image_raw" in message and "/rgb/image" in message


def test_ray_topic_name_equal_to_the_remapped_out_is_info(check: Check) -> None:
    # ~/out remapped to scan resolves to /scan; ROS 1's topicName scan is /scan too.
    same = lidar_sensor(params="<ros><remapping>~/out:=scan</remapping></ros><topicName>scan</topicName>"
                        "<output_type>sensor_msgs/LaserScan</output_type><frame_name>laser_link</frame_name>")
    other = same.replace("<topicName>scan</topicName>", "<topicName>base/scan</topicName>")
    assert _sk602(check(robot(lidar=same), target="classic"))["topicName"][0] == "info"
    assert _sk602(check(robot(lidar=other), target="classic"))["topicName"][0] == "error"


IMU = (
    '<gazebo reference="base_link"><sensor name="imu" type="imu"><update_rate>100</update_rate>'
    '<plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so">{params}</plugin></sensor></gazebo>'
)


@pytest.mark.parametrize(
    ("params", "tag", "severity"),
    [
        ("<initialOrientationAsReference>false</initialOrientationAsReference>", "initialOrientationAsReference", "info"),
        ("<initialOrientationAsReference>true</initialOrientationAsReference>", "initialOrientationAsReference", "warning"),
        ("<gaussianNoise>0.0</gaussianNoise>", "gaussianNoise", "info"),
        ("<gaussianNoise>0.01</gaussianNoise>", "gaussianNoise", "warning"),
        ("<rpyOffset>0 0 0</rpyOffset>", "rpyOffset", "info"),
        ("<rpyOffset>0 0 1.57</rpyOffset>", "rpyOffset", "error"),
        ("<xyzOffset>0.1 0 0</xyzOffset>", "xyzOffset", "info"),  # unused by ROS 1 too
        ("<bodyName>imu_link</bodyName>", "bodyName", "info"),  # read by no ROS 1 imu_sensor
        ("<updateRateHZ>100</updateRateHZ>", "updateRateHZ", "info"),
        ("<updateRateHZ>10</updateRateHZ>", "updateRateHZ", "warning"),
    ],
)
def test_imu_tags_by_consequence(check: Check, params: str, tag: str, severity: str) -> None:
    found = _sk602(check(robot(extra=IMU.format(params=params)), target="classic"))
    assert found[tag][0] == severity, found[tag][1]


DRIVE = (
    '<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so">'
    "<left_joint>l</left_joint><right_joint>r</right_joint>{params}</plugin></gazebo>"
)


@pytest.mark.parametrize(
    ("params", "tag", "severity"),
    [
        ("<wheelSeparation>0.5</wheelSeparation>", "wheelSeparation", "error"),
        ("<wheelSeparation>0.34</wheelSeparation>", "wheelSeparation", "info"),
        ("<odometrySource>world</odometrySource>", "odometrySource", "info"),
        ("<odometrySource>encoder</odometrySource>", "odometrySource", "warning"),
        ("<rosDebugLevel>na</rosDebugLevel>", "rosDebugLevel", "info"),
        ("<leftJoint>l</leftJoint>", "leftJoint", "info"),  # its ROS 2 form says the same
    ],
)
def test_drive_tags_by_consequence(check: Check, params: str, tag: str, severity: str) -> None:
    found = _sk602(check(robot(extra=DRIVE.format(params=params)), target="classic"))
    assert found[tag][0] == severity, found[tag][1]


def test_a_ros1_joint_without_its_ros2_form_leaves_the_drive_without_joints(check: Check) -> None:
    extra = '<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so"><leftJoint>l</leftJoint></plugin></gazebo>'
    assert _sk602(check(robot(extra=extra), target="classic"))["leftJoint"][0] == "error"


def test_remap_that_changes_nothing_is_info(check: Check) -> None:
    base = '<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so"><left_joint>l</left_joint><right_joint>r</right_joint><ros>{}</ros></plugin></gazebo>'
    same = check(robot(extra=base.format('<remap from="cmd_vel" to="/cmd_vel"/>')), target="classic")
    other = check(robot(extra=base.format('<remap from="cmd_vel" to="/robot/cmd_vel"/>')), target="classic")
    assert [f.severity.label for f in same.findings if f.rule == "SK602"] == ["info"]
    assert [f.severity.label for f in other.findings if f.rule == "SK602"] == ["error"]


# --- issue 35: a frame tag is judged as a frame; tags no ROS 1 plugin read ----------------
# An IMU's message is filled from the sensor and only stamped with the frame
# (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_imu_sensor.cpp:102
# frame_id, :135-140 orientation, angular_velocity, linear_acceleration), so a frame that
# differs from the written one by a translation only carries the same data.


def _imu_on_lumped_link(rpy: str) -> str:
    imu = (
        '<link name="imu_link"/><joint name="imu_joint" type="fixed"><parent link="base_link"/>'
        f'<child link="imu_link"/><origin xyz="0.1 0.02 0.05" rpy="{rpy}"/></joint>'
        '<gazebo reference="imu_link"><sensor name="imu" type="imu"><update_rate>100</update_rate>'
        '<plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so"><frameName>imu_link</frameName>'
        "</plugin></sensor></gazebo>"
    )
    return robot(extra=imu)


def test_imu_frame_tag_translated_only_changes_nothing(check: Check) -> None:
    # imu_link lumps into base_footprint (massless, fixed): ROS 2 stamps base_footprint
    # (gazebo_ros/src/utils.cpp:52-61), which sits elsewhere but is turned alike.
    sev, msg = _sk602(check(_imu_on_lumped_link("0 0 0"), target="classic"))["frameName"]
    assert sev == "info", msg
    assert "written imu_link; the simulator uses base_footprint" in msg


def test_imu_frame_tag_turned_is_an_error(check: Check) -> None:
    sev, msg = _sk602(check(_imu_on_lumped_link("0 0 0.02"), target="classic"))["frameName"]
    assert sev == "error", msg  # 1.1 degrees: over SK5xx's 0.5 degree
    assert _sk602(check(_imu_on_lumped_link("0 0 0.008"), target="classic"))["frameName"][0] == "info"  # 0.46 degree


def test_camera_frame_tag_must_coincide_in_place_too(check: Check) -> None:
    # A camera's data depends on where its frame sits: the frame written and the one used
    # must coincide within 1 mm and 0.5 degree.
    def cam(xyz: str) -> str:
        extra = (
            '<link name="camera_lens"/><joint name="lens_joint" type="fixed"><parent link="camera_optical_frame"/>'
            f'<child link="camera_lens"/><origin xyz="{xyz}" rpy="0 0 0"/></joint>'
        )
        params = "<frame_name>camera_optical_frame</frame_name><frameName>camera_lens</frameName>"
        return robot(camera=camera_sensor(params=params), extra=extra)

    assert _sk602(check(cam("0 0 0.0009"), target="classic"))["frameName"][0] == "info"
    assert _sk602(check(cam("0 0 0.0011"), target="classic"))["frameName"][0] == "error"


def test_baseline_is_read_by_no_ros1_plugin(check: Check) -> None:
    # noetic-devel f9e1a46: only hackBaseline is read (gazebo_ros_camera_utils.cpp:191-197,
    # gazebo_ros_multicamera.cpp:92-93); `git grep '"baseline"'` finds no reader.
    found = _sk602(check(_camera("<frame_name>camera_optical_frame</frame_name><baseline>0.2</baseline>"), target="classic"))
    assert found["baseline"][0] == "info", found
    found = _sk602(check(_camera("<frame_name>camera_optical_frame</frame_name><hackBaseline>0.2</hackBaseline>"), target="classic"))
    assert found["hackBaseline"][0] == "error", found


def test_every_sk602_message_says_written_and_used(check: Check) -> None:
    report = check(_camera("<frame_name>camera_optical_frame</frame_name><cameraName>cam</cameraName>"
                           "<updateRate>15</updateRate>"), target="classic")
    found = [f for f in report.findings if f.rule == "SK602"]
    assert found and all("written " in f.message and f.consequence is not None for f in found)


def test_p3d_and_planar_move_tags_are_known(check: Check) -> None:
    # ROS 2 p3d without <body_name> "cannot proceed" (gazebo_ros_p3d.cpp:111-113): its ROS 1
    # bodyName ignored is an error; planar_move subscribes cmd_vel (gazebo_ros_planar_move.cpp:
    # 162-163), so a ROS 1 commandTopic cmd_vel changes nothing, another name does.
    p3d = ('<gazebo><plugin name="gt" filename="libgazebo_ros_p3d.so"><bodyName>base_link</bodyName>'
           "<topicName>odom</topicName><frameName>map</frameName></plugin></gazebo>")
    found = _sk602(check(robot(extra=p3d), target="classic"))
    assert found["bodyName"][0] == "error" and found["topicName"][0] == "info", found
    assert found["frameName"][0] == "error", found  # stamped world, not map (gazebo_ros_p3d.cpp:66)
    planar = ('<gazebo><plugin name="pm" filename="libgazebo_ros_planar_move.so"><commandTopic>cmd_vel</commandTopic>'
              "<odometryTopic>base/odom</odometryTopic></plugin></gazebo>")
    found = _sk602(check(robot(extra=planar), target="classic"))
    assert found["commandTopic"][0] == "info" and found["odometryTopic"][0] == "error", found
