"""Findings the fresh robots of issue 35 showed false, or errors that change nothing: each
rule's trigger and near miss, with the simulator's source for what it now says."""

from __future__ import annotations

from builders import inertial, joint, link

from sensorkit.base.findings import Severity


def _world_robot(led_body: str = "", below: str = "", preserve: bool = False) -> str:
    """A robot fixed to 'world', with a massless 'led_ring_link' fixed to world beside it
    (NiryoRobotics/ned_ros niryo_ned2.urdf.xacro:30 and :274-278)."""
    keep = (
        '<gazebo reference="joint_led_ring"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
        if preserve else ""
    )
    return (
        '<?xml version="1.0"?><robot name="arm"><link name="world"/>'
        + link("base_link", inertial(1.0, 0.01))
        + joint("joint_world", "world", "base_link")
        + f'<link name="led_ring_link">{led_body}</link>'
        + joint("joint_led_ring", "world", "led_ring_link", "0 0 0.0923")
        + below + keep + "</robot>"
    )


_VISUAL = '<visual><geometry><cylinder length="0.002" radius="0.08"/></geometry></visual>'
_CHILD = link("ring_arm", inertial() + _VISUAL) + joint(
    "ring_joint", "led_ring_link", "ring_arm", type="revolute",
    extra='<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>',
)


def _sk301(check, text: str, target: str = "classic"):
    return [f for f in check(text, target=target).findings if f.rule == "SK301"]


def test_sk301_massless_link_fixed_to_world_holding_nothing_is_no_finding(check) -> None:
    # sdformat never lumps into 'world' (gazebosim/sdformat@sdf9 9ee2d4f3:
    # src/parser_urdf.cc:412; @sdf12 b9417e5b :421; @sdf14 8512585c :424), and CreateSDF
    # does not return early for a link whose fixed parent joint it reduces (parentJointReduced:
    # sdf9 :2679-2683; sdf12 :2697-2701; sdf14 :2700-2704): the link is not created (zero
    # mass, sdf9 :2765-2772) and its children are still converted (sdf9 :2776-2780). With
    # nothing in it, nothing changes and sdformat prints nothing: no finding, on every target.
    for target in ("classic", "fortress", "harmonic"):
        assert _sk301(check, _world_robot(), target) == [], target


def test_sk301_massless_link_fixed_to_world_loses_only_what_it_holds(check) -> None:
    # A visual on it is lost (the link is never created): an error, that says the links
    # below are kept.
    (f,) = _sk301(check, _world_robot(led_body=_VISUAL))
    assert f.severity is Severity.ERROR
    assert "the links below it are still converted" in f.message and "led_ring_link" in f.message
    # A link below it on a revolute joint is converted, not dropped: its joint names a
    # parent the SDF lacks (CreateJoint writes the URDF parent: sdf9 :3066), which
    # sensorkit does not follow further: info, and 'ring_arm' is not said to be lost.
    (g,) = _sk301(check, _world_robot(below=_CHILD))
    assert g.severity is Severity.INFO and "ring_arm" in g.message
    assert "everything below it" not in g.message


def test_sk301_preserved_fixed_joint_to_world_drops_the_subtree(check) -> None:
    # With preserveFixedJoint the joint is not one sdformat reduces: CreateSDF returns before
    # the children (sdf9 :2683-2760): the link and everything below it are dropped.
    (f,) = _sk301(check, _world_robot(below=_CHILD, preserve=True))
    assert "everything below it" in f.message and "ring_arm" in f.message
    assert f.severity is Severity.ERROR  # ring_arm's visual is lost


def test_sk301_a_massless_link_lumped_into_a_real_parent_is_no_finding(check) -> None:
    # The near miss of the common case: fixed to a link with mass, it is lumped (sdf9 :412-463).
    text = _world_robot().replace(
        joint("joint_led_ring", "world", "led_ring_link", "0 0 0.0923"),
        joint("joint_led_ring", "base_link", "led_ring_link", "0 0 0.0923"),
    )
    assert _sk301(check, text) == []


def test_sk406_one_vertical_sample_at_a_fine_resolution_says_both_values(check) -> None:
    # bitcraze/crazyflie-simulation model.sdf:47-58: a gpu_lidar with one vertical sample at
    # resolution 0.01. gz-sensors publishes max(1, floor(samples x resolution)) rows
    # (gazebosim/gz-sensors@gz-sensors8 c8159af:src/Lidar.cc:389-397, Lidar::VerticalRangeCount)
    # and renders <samples> rows (src/GpuLidarSensor.cc:212-214): 1 written, 1 published.
    from builders import gz_robot

    vertical = (
        "<vertical><samples>1</samples><resolution>0.01</resolution>"
        "<min_angle>0</min_angle><max_angle>0</max_angle></vertical>"
    )
    text = gz_robot().replace("</horizontal></scan>", f"</horizontal>{vertical}</scan>")
    found = [f for f in check(text, target="harmonic").findings if f.rule == "SK406"]
    assert [f.severity for f in found] == [Severity.INFO]
    msg = found[0].message
    assert "publishes 1 row, the 1 sample written" in msg and "written 1 row; the simulator uses 1 row" in msg
    assert "not a whole beam count" not in msg
    assert found[0].consequence is not None and found[0].consequence.changes_nothing
    # Near miss: two samples at 0.01 still give one row, not the two written: a warning.
    two = text.replace(
        "<samples>1</samples><resolution>0.01</resolution><min_angle>0</min_angle><max_angle>0",
        "<samples>2</samples><resolution>0.01</resolution><min_angle>-0.1</min_angle><max_angle>0.1",
    )
    assert [f.severity for f in check(two, target="harmonic").findings if f.rule == "SK406"] == [Severity.WARNING]


def _imu(params: str) -> str:
    from builders import robot

    imu = (
        '<link name="imu_link">' + inertial() + "</link>" + joint("imu_joint", "base_link", "imu_link")
        + '<gazebo reference="imu_link"><sensor name="imu_sensor" type="imu"><update_rate>100</update_rate>'
        f'<plugin filename="libgazebo_ros_imu_sensor.so" name="imu_plugin">{params}</plugin></sensor></gazebo>'
    )
    return robot(extra=imu)


def test_sk602_xyz_offset_says_what_ros1_did_with_it(check) -> None:
    # nasa-jpl/osr-rover-code gazebo.urdf.xacro:145. ROS 1's imu sensor plugin reads
    # <xyzOffset> under "POSITION OFFSET, UNUSED" and applies only offset.Rot()
    # (ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a460:gazebo_plugins/src/
    # gazebo_ros_imu_sensor.cpp:237-247, :107), while ROS 1's gazebo_ros_imu (:105-111, :252)
    # and gazebo_ros_p3d (:97-103, :301) apply theirs: "no ROS 1 plugin used it" was false.
    found = {
        f.message.split(">")[0].lstrip("<"): f
        for f in check(_imu("<frame_name>imu_link</frame_name><xyzOffset>0.1 0 0</xyzOffset><bodyName>imu_link</bodyName>"), target="classic").findings
        if f.rule == "SK602"
    }
    xyz, body = found["xyzOffset"], found["bodyName"]
    assert xyz.severity is Severity.INFO and body.severity is Severity.INFO
    assert "libgazebo_ros_imu_sensor.so read it but applied only the rotation offset" in xyz.message
    assert "libgazebo_ros_imu_sensor.so never read it either" in body.message
    assert all("no ROS 1 plugin" not in f.message for f in found.values())
    # Near miss: the ROS 2 tags alone say nothing.
    assert [f for f in check(_imu("<frame_name>imu_link</frame_name>"), target="classic").findings if f.rule == "SK602"] == []


def _bb2(params: str) -> str:
    # esa-prl/rover_config bb2.gazebo:8-40: a ROS 1 camera plugin under ROS 2, sensor
    # 'loc_cam/left', <cameraName>loc_cam</cameraName>.
    from builders import camera_sensor, robot

    return robot(camera=camera_sensor("loc_cam/left", params="<frame_name>camera_optical_frame</frame_name>" + params))


def _sk602_by_tag(check, text: str) -> dict[str, tuple[Severity, str]]:
    return {
        f.message.split(">")[0].lstrip("<"): (f.severity, f.message)
        for f in check(text, target="classic").findings
        if f.rule == "SK602"
    }


def test_sk602_topic_tag_whose_leaf_is_the_ros2_default_changes_nothing(check) -> None:
    # ROS 2's camera publishes camera_name + "/image_raw" and + "/camera_info"
    # (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c47:gazebo_plugins/src/gazebo_ros_camera.cpp:187,
    # :200): the leaves written are the leaves used; the topic moves only through
    # <cameraName> (ROS 2 takes camera_name, default the sensor name: :179), an error on its line.
    found = _sk602_by_tag(check, _bb2(
        "<cameraName>loc_cam</cameraName><imageTopicName>image_raw</imageTopicName>"
        "<cameraInfoTopicName>camera_info</cameraInfoTopicName>"
    ))
    assert found["cameraName"][0] is Severity.ERROR
    for tag in ("imageTopicName", "cameraInfoTopicName"):
        sev, msg = found[tag]
        assert sev is Severity.INFO, msg
        assert "the topic differs only through <cameraName>, reported on its own line" in msg
        assert "nothing changes" in msg
    assert "it publishes /loc_cam/left/image_raw, ROS 1 published /loc_cam/image_raw" in found["imageTopicName"][1]


def test_sk602_topic_tag_whose_leaf_differs_stays_an_error(check) -> None:
    # Near misses: a leaf other than ROS 2's own is a topic the data no longer reaches; and
    # with no <cameraName> or <robotNamespace> to report the move, the tag's own line keeps it.
    found = _sk602_by_tag(check, _bb2("<cameraName>loc_cam</cameraName><imageTopicName>image_color</imageTopicName>"))
    assert found["imageTopicName"][0] is Severity.ERROR
    found = _sk602_by_tag(check, _bb2("<imageTopicName>image_raw</imageTopicName>"))
    assert found["imageTopicName"][0] is Severity.ERROR


def _sdf_leg(ixx: str) -> str:
    return (
        '<?xml version="1.0"?><sdf version="1.9"><model name="spot"><link name="body">'
        '<inertial><mass>16</mass><inertia><ixx>0.1</ixx><iyy>0.5</iyy><izz>0.5</izz>'
        "<ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial></link>"
        '<link name="front_left_lower_leg"><pose>0.3 0.1 -0.3 0 0 0</pose><inertial><mass>0.3</mass>'
        f"<inertia><ixx>{ixx}</ixx><iyy>0.0074</iyy><izz>0.0001</izz>"
        "<ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial></link>"
        '<joint name="knee" type="revolute"><parent>body</parent><child>front_left_lower_leg</child>'
        "<axis><xyz>0 1 0</xyz><limit><lower>-1</lower><upper>1</upper></limit></axis></joint>"
        "</model></sdf>"
    )


def test_sk302_sdf_number_with_trailing_words_is_the_number_sdformat_reads(check) -> None:
    # g1y5x3/spot_ros2_gazebo model.sdf:826: <ixx>0.00743438Source Control</ixx>. sdformat
    # parses a double with std::stod and no end pointer (gazebosim/sdformat@sdf9 9ee2d4f3:
    # src/Param.cc:359-362; @sdf12 b9417e5b:src/Param.cc:707-709; @sdf14 8512585c:
    # src/Param.cc:916-919): it reads 0.00743438 and ignores the words, without a word.
    for target in ("classic", "harmonic"):
        found = [f for f in check(_sdf_leg("0.00743438Source Control"), target=target, suffix=".sdf").findings if f.rule == "SK302"]
        assert [f.severity for f in found] == [Severity.INFO], (target, [f.message for f in found])
        assert "sdformat reads the 0.00743438 it starts with and ignores 'Source Control'" in found[0].message
    # Digits after the number leave what was meant unclear: a warning naming what is read.
    found = [f for f in check(_sdf_leg("0.0074,5"), target="harmonic", suffix=".sdf").findings if f.rule == "SK302"]
    assert [f.severity for f in found] == [Severity.WARNING] and "sdformat reads 0.0074 and ignores ',5'" in found[0].message
    # Near miss: a number alone says nothing; a text with no number first stays an error.
    assert [f for f in check(_sdf_leg("0.00743438"), target="harmonic", suffix=".sdf").findings if f.rule == "SK302"] == []
    found = [f for f in check(_sdf_leg("Source Control"), target="harmonic", suffix=".sdf").findings if f.rule == "SK302"]
    assert [f.severity for f in found] == [Severity.ERROR] and "is not a number" in found[0].message


def test_stod_prefix_reads_what_strtod_reads() -> None:
    from sensorkit.model.parse import stod_prefix

    assert stod_prefix("0.00743438Source Control") == (0.00743438, "Source Control")
    assert stod_prefix(" 1e-3kg") == (0.001, "kg")
    assert stod_prefix("1.5") is None and stod_prefix("abc") is None and stod_prefix("") is None
    assert stod_prefix(".5.5") == (0.5, ".5")


def _crazyflie(rel: str, mount: str = "0 0 0.1 0 0 0") -> str:
    # bitcraze/crazyflie-simulation model.sdf:43-44: a gpu_lidar on the body link posed
    # relative_to 'crazyflie/base_link', a frame the model does not have.
    return (
        '<?xml version="1.0"?><sdf version="1.9"><model name="crazyflie">'
        '<link name="crazyflie/body"><inertial><mass>0.025</mass><inertia><ixx>1.6e-5</ixx>'
        "<iyy>1.6e-5</iyy><izz>2.9e-5</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial>"
        f'<sensor name="multiranger" type="gpu_lidar"><pose relative_to="{rel}">0 0 0.1 0 0 0</pose>'
        "<topic>lidar</topic><update_rate>10</update_rate><lidar><scan><horizontal><samples>4</samples>"
        "<resolution>1</resolution><min_angle>-3.14</min_angle><max_angle>1.57</max_angle></horizontal>"
        "</scan><range><min>0.01</min><max>3.49</max></range></lidar></sensor></link>"
        f'<frame name="crazyflie/lidar_mount" attached_to="crazyflie/body"><pose>{mount}</pose></frame>'
        "</model></sdf>"
    )


def _sk510(check, text: str) -> list[tuple[Severity, str]]:
    return [(f.severity, f.message) for f in check(text, target="harmonic", suffix=".sdf").findings if f.rule == "SK510"]


def test_sk510_unknown_frame_is_a_warning_that_says_where_the_sensor_is(check) -> None:
    # gz-sim falls back to the raw pose when the semantic pose does not resolve
    # (gazebosim/gz-sim@gz-sim8 b81e26dab:src/SdfEntityCreator.cc:131-141; the renderer
    # src/rendering/RenderUtil.cc:1333-1338; gazebosim/gz-sensors@gz-sensors8 c8159af:
    # src/Sensor.cc:198-204): the lidar works at 0 0 0.1 in its link. libsdformat does not
    # report it at load: a sensor is no vertex of the pose graph (gazebosim/sdformat@sdf14
    # 8512585c:src/FrameSemantics.cc:296-519); resolving returns POSE_RELATIVE_TO_INVALID.
    ((sev, msg),) = _sk510(check, _crazyflie("crazyflie/base_link"))
    assert sev is Severity.WARNING, msg
    assert "libsdformat reports nothing at load" in msg and "POSE_RELATIVE_TO_INVALID" in msg
    assert "which frame was meant is not known" in msg


def test_sk510_typo_of_a_frame_elsewhere_is_an_error(check) -> None:
    # 'crazyflie/lidar_mnt' is two letters from 'crazyflie/lidar_mount', 0.1 m above the body:
    # placed there the lidar would sit 100 mm from where gz-sim puts it.
    ((sev, msg),) = _sk510(check, _crazyflie("crazyflie/lidar_mnt"))
    assert sev is Severity.ERROR and "100.0 mm" in msg, msg
    # Near misses: the same typo of a frame at the link's own place changes nothing (a
    # warning); the frame's own name is no finding.
    ((sev, msg),) = _sk510(check, _crazyflie("crazyflie/lidar_mnt", mount="0 0 0.0005 0 0 0"))
    assert sev is Severity.WARNING and "same place and rotation" in msg, msg
    assert _sk510(check, _crazyflie("crazyflie/lidar_mount")) == []
