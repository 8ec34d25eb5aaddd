"""Issue 23 on frames: each fact with a trigger and a near miss (inline robots)."""

from __future__ import annotations

from builders import OPTICAL, camera_sensor, inertial, joint, lidar_sensor, link, robot
from conftest import rules_of

SENSORS = '<gazebo><plugin filename="gz-sim-sensors-system" name="gz::sim::systems::Sensors"/></gazebo>'


def _tree(*parts: str, name: str = "robot") -> str:
    return f'<?xml version="1.0"?><robot name="{name}">' + "".join(parts) + "</robot>"


# --- fact 8: a ROS 1 velodyne <frameName> that names no link -----------------------

VELODYNE_PARAMS = "<topicName>points</topicName><frameName>{frame}</frameName><gaussianNoise>0.008</gaussianNoise>"


def _velodyne(frame: str) -> str:
    sensor = lidar_sensor(
        "vlp16", plugin="libgazebo_ros_velodyne_laser.so", params=VELODYNE_PARAMS.format(frame=frame)
    )
    return _tree(
        '<link name="base_link"/>', link("vlp16_link"), joint("vlp16_joint", "base_link", "vlp16_link", "0 0 0.3"),
        f'<gazebo reference="vlp16_link">{sensor}</gazebo>',
    )


def test_ros1_velodyne_frame_name_that_names_no_link_is_sk501(check) -> None:
    # lmark1/velodyne_simulator@e08185a:velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:119-124
    # reads <frameName>, :172-178 passes it through tf::resolve(prefix, frame_name_) with
    # the tf_prefix parameter (or robotNamespace, when not "/") and :316 stamps it.
    # tf::resolve (ros/geometry@noetic-devel:tf/src/tf.cpp:159-191) keeps a name that does
    # not start with "/" as is when the prefix is empty: "robot/vlp16_link" is stamped, and
    # no link has that name. Validated as ROS 1 (3 ROS 1-only tags), not as the ROS 2
    # port, so no lumping finding about a frame this plugin does not use.
    r = check(_velodyne("robot/vlp16_link"))
    assert r.target == "ros1"
    sk501 = [f for f in r.findings if f.rule == "SK501"]
    assert [f.frame for f in sk501] == ["robot/vlp16_link"]
    assert sk501[0].fix == "did you mean 'vlp16_link'?"
    assert not {"SK303", "SK503"} & rules_of(r)


def test_ros1_velodyne_frame_name_with_leading_slash_is_the_link(check) -> None:
    # near miss: tf.cpp:162-165 strips one leading "/", so "/vlp16_link" stamps vlp16_link.
    r = check(_velodyne("/vlp16_link"))
    assert r.target == "ros1"
    assert "SK501" not in rules_of(r)
    assert "SK501" not in rules_of(check(_velodyne("vlp16_link")))


def test_ros1_velodyne_macro_with_organize_cloud_is_still_ros1(check) -> None:
    # The hector-style macro the issue met: topicName, frameName, gaussianNoise and
    # organize_cloud. Upstream ROS 1 reads organize_cloud since 1.0.11 (effeed2, kept in
    # Winsleo/velodyne_simulator@a7cec2a, package.xml 1.0.13 catkin:
    # velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:128-133), so it is no sign of
    # the ROS 2 port: auto validates as ROS 1, SK501 on the declared frame, no lumping.
    params = VELODYNE_PARAMS + "<organize_cloud>false</organize_cloud>"
    sensor = lidar_sensor("vlp16", plugin="libgazebo_ros_velodyne_laser.so", params=params.format(frame="robot/vlp16_link"))
    r = check(_tree(
        '<link name="base_link"/>', link("vlp16_link"), joint("vlp16_joint", "base_link", "vlp16_link", "0 0 0.3"),
        f'<gazebo reference="vlp16_link">{sensor}</gazebo>',
    ))
    assert r.target == "ros1"
    assert [f.frame for f in r.findings if f.rule == "SK501"] == ["robot/vlp16_link"]
    assert not {"SK303", "SK503"} & rules_of(r)


# --- false class 1: Gazebo Sim stereo, two cameras on one link -----------------------

def _gz_cam(name: str, y: float, frame: str, topic: str | None = None) -> str:
    return (
        f'<sensor name="{name}" type="camera"><pose>0 {y} 0 0 0 0</pose><update_rate>30</update_rate>'
        f"<topic>{topic or name + '/image_raw'}</topic><gz_frame_id>{frame}</gz_frame_id>"
        '<camera><horizontal_fov>1.2</horizontal_fov><image><width>640</width><height>480</height>'
        "<format>R8G8B8</format></image><clip><near>0.05</near><far>50</far></clip></camera></sensor>"
    )


def _gz_stereo(right_frame: str = "left_optical_frame", *, right_link: str = "stereo_link",
               left_topic: str | None = None, right_topic: str | None = None) -> str:
    return _tree(
        '<link name="base_link"/>', link("stereo_link", inertial()),
        joint("stereo_joint", "base_link", "stereo_link", "0.2 0 0.3"),
        link("other_link", inertial()),
        joint("other_joint", "base_link", "other_link", "0.2 0 0.3", type="revolute",
              extra='<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'),
        '<link name="left_optical_frame"/>',
        joint("left_optical_joint", "stereo_link", "left_optical_frame", "0 0.06 0", OPTICAL),
        '<link name="half_optical_frame"/>',
        joint("half_optical_joint", "stereo_link", "half_optical_frame", "0 0.01 0", OPTICAL),
        f'<gazebo reference="stereo_link">{_gz_cam("left", 0.06, "left_optical_frame", left_topic)}</gazebo>',
        f'<gazebo reference="{right_link}">{_gz_cam("right", -0.06, right_frame, right_topic)}</gazebo>',
        SENSORS,
    )


def _sk503(report: object) -> list[str]:
    return [f.sensor for f in report.findings if f.rule == "SK503"]  # type: ignore[attr-defined]


def test_gz_stereo_right_eye_in_left_optical_frame_is_not_sk503(check) -> None:
    # near miss: gz-sim gives the second camera on a link the baseline |y_right - y_left|
    # (gazebosim/gz-sim@ign-gazebo6:src/systems/sensors/Sensors.cc:831-861,
    # @gz-sim8:src/systems/sensors/Sensors.cc:1189-1224), which gz-sensors writes into
    # camera_info as P[3] = -fx * baseline (gazebosim/gz-sensors@ign-sensors6:
    # src/CameraSensor.cc:805-815, @gz-sensors8:src/CameraSensor.cc:794-804): the right eye
    # stamped with the left optical frame, 0.12 m to its left, is the ROS stereo convention.
    for target in ("fortress", "harmonic"):
        assert _sk503(check(_gz_stereo(), target=target)) == []


def test_gz_stereo_topic_swap_decides_the_right_eye(check) -> None:
    # Sensors.cc:851-855 (ign-gazebo6): the first camera is the right one when its topic
    # holds "right" and the second's "left". Here the description's first camera ("left",
    # at +0.06) is published on a "right" topic, so gz gives it the baseline, not the
    # second: the second, stamped 0.12 m away, keeps baseline 0 and SK503 stays.
    r = check(_gz_stereo(left_topic="stereo/right/image", right_topic="stereo/left/image"), target="harmonic")
    assert _sk503(r) == ["right"]


def test_gz_stereo_offset_that_is_not_the_baseline_is_sk503(check) -> None:
    # trigger: the right eye stamped with a frame 0.07 m to its left, not the 0.12 m baseline.
    assert _sk503(check(_gz_stereo("half_optical_frame"), target="harmonic")) == ["right"]


def test_gz_cameras_on_two_links_are_no_stereo_pair(check) -> None:
    # trigger: the second camera is on another link (a revolute joint: no lumping), so
    # gz-sim pairs nothing (Sensors.cc:842-844 looks the parent up) and the offset is real.
    r = check(_gz_stereo(right_link="other_link"), target="harmonic")
    assert _sk503(r) == ["right"]


# --- miss 3: an optical joint with the wrong rotation --------------------------------

WRONG = "-1.5707963267948966 0 1.5707963267948966"  # yaw +pi/2: the image looks backwards


def _fix(path, *, unsafe: bool = False):  # type: ignore[no-untyped-def]
    from sensorkit.fix.apply import fix_paths
    from sensorkit.lint.engine import Options

    return fix_paths([path], Options(target="classic"), unsafe=unsafe).files[0]


def _validate(path):  # type: ignore[no-untyped-def]
    from sensorkit.lint.engine import Options, validate_file

    return validate_file(path, Options(target="classic"))


def test_sk502_on_a_dedicated_optical_link_points_at_its_joint_rpy(check, tmp_path) -> None:
    text = robot(optical_rpy=WRONG)
    (f,) = [f for f in check(text, target="classic").findings if f.rule == "SK502"]
    line = text.splitlines().index(next(x for x in text.splitlines() if 'name="camera_optical_joint"' in x)) + 1
    assert (f.joint, f.line) == ("camera_optical_joint", line)
    assert f.fix == "write rpy=\"-1.5707963267948966 0 -1.5707963267948966\" on joint 'camera_optical_joint'"
    path = tmp_path / "rover.urdf"
    path.write_text(text)
    ff = _fix(path)  # safe: the rpy is corrected in place, no second optical frame
    assert len(ff.applied) == 1
    new = path.read_text()
    assert new == text.replace(f'rpy="{WRONG}"', f'rpy="{OPTICAL}"')
    assert "SK502" not in {x.rule for x in _validate(path).findings}


def test_sk502_in_xacro_writes_pi_over_two(check, tmp_path) -> None:
    text = robot(optical_rpy="${-pi/2} 0 ${pi/2}").replace(
        '<robot name="rover">', '<robot name="rover" xmlns:xacro="http://www.ros.org/wiki/xacro">'
    )
    path = tmp_path / "rover.urdf.xacro"
    path.write_text(text)
    (f,) = [f for f in _validate(path).findings if f.rule == "SK502"]
    assert f.joint == "camera_optical_joint"
    # a xacro expression is not rewritten: it says where to change it
    ff = _fix(path)
    assert not ff.applied and path.read_text() == text
    path.write_text(text.replace("${-pi/2} 0 ${pi/2}", WRONG))
    _fix(path)
    assert 'rpy="${-pi/2} 0 ${-pi/2}"' in path.read_text()


def test_sk502_on_an_optical_link_with_other_roles_is_refused(check, tmp_path) -> None:
    # near miss for the in-place fix: a link hangs off the optical frame, so turning it
    # would move that link too; the finding stays on the sensor and the fix is refused
    # with the reason, never a second optical frame beside the wrong one.
    extra = '<link name="marker"/>' + joint("marker_joint", "camera_optical_frame", "marker", "0 0 0.1")
    text = robot(optical_rpy=WRONG, extra=extra)
    (f,) = [f for f in check(text, target="classic").findings if f.rule == "SK502"]
    assert f.joint is None
    path = tmp_path / "rover.urdf"
    path.write_text(text)
    ff = _fix(path, unsafe=True)
    assert path.read_text() == text
    assert any("links hang off 'camera_optical_frame'" in n.text for n in ff.notes if n.finding.rule == "SK502")


def _optical_named(name: str, rpy: str, parent_rpy: str = "0 0 0") -> str:
    return _tree(
        '<link name="base_link"/>', link("cam2_link"),
        joint("cam2_joint", "base_link", "cam2_link", "0.1 0 0.2", parent_rpy),
        f'<link name="{name}"/>', joint("cam2_optical_joint", "cam2_link", name, "0 0 0", rpy),
    )


def test_sk508_link_named_optical_that_is_not(check) -> None:
    r = check(_optical_named("cam2_optical_frame", "0 0 0"), target="classic")
    (f,) = [f for f in r.findings if f.rule == "SK508"]
    assert (f.link, f.joint, f.severity.name) == ("cam2_optical_frame", "cam2_optical_joint", "WARNING")
    assert "SK508" in rules_of(check(_optical_named("cam2_link_optical", "0 0 1.5707963267948966"), target="classic"))


def test_sk508_near_misses(check) -> None:
    # a correct optical link; one optical from a link above its parent (its parent is an
    # intermediate frame already turned); a name where "optical" is no optical frame
    # (PX4's optical_flow_link, an optical-flow sensor's body, x forward).
    assert "SK508" not in rules_of(check(_optical_named("cam2_optical_frame", OPTICAL), target="classic"))
    turned = _tree(
        '<link name="base_link"/>', '<link name="cam_color_frame"/>',
        joint("a", "base_link", "cam_color_frame", "0 0 0", OPTICAL),
        '<link name="cam_color_optical_frame"/>', joint("b", "cam_color_frame", "cam_color_optical_frame"),
    )
    assert "SK508" not in rules_of(check(turned, target="classic"))
    assert "SK508" not in rules_of(check(_optical_named("optical_flow_link", "0 0 0"), target="classic"))


def test_sk508_leaves_a_stamped_frame_to_sk502(check) -> None:
    r = check(robot(optical_rpy=WRONG), target="classic")
    assert "SK502" in rules_of(r) and "SK508" not in rules_of(r)


# --- miss 4: units: a sensor more than 10 m from the link it hangs off ----------------

def _mounted(xyz: str, pose: str = "0 0 0 0 0 0", root: str = "base_link") -> str:
    cam = camera_sensor(params="<frame_name>cam_optical_frame</frame_name>", extra=f"<pose>{pose}</pose>")
    return _tree(
        f'<link name="{root}"/>' if root == "world" else "", link("base_link"),
        joint("root_joint", "world", "base_link") if root == "world" else "",
        link("cam_link"), joint("cam_joint", "base_link", "cam_link", xyz),
        '<link name="cam_optical_frame"/>', joint("cam_optical_joint", "cam_link", "cam_optical_frame", "0 0 0", OPTICAL),
        f'<gazebo reference="cam_link">{cam}</gazebo>',
    )


def test_sk509_millimetres_written_as_metres(check) -> None:
    r = check(_mounted("150 0 300"), target="classic")
    (f,) = [f for f in r.findings if f.rule == "SK509"]
    assert (f.sensor, f.link, f.severity.name) == ("front_camera", "base_link", "WARNING")
    assert "335.41 m" in f.message
    # the sensor <pose> counts too (on a link that is not lumped: its joint's parent)
    moving = _mounted("0.15 0 0.3", pose="12 0 0 0 0 0").replace('type="fixed"><parent link="base_link"/><child link="cam_link"/>', 'type="revolute"><parent link="base_link"/><child link="cam_link"/>')
    moving = moving.replace('<origin xyz="0.15 0 0.3" rpy="0 0 0"/></joint>', '<origin xyz="0.15 0 0.3" rpy="0 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>', 1)
    assert "SK509" in rules_of(check(moving, target="classic"))


def test_sk509_near_misses(check) -> None:
    assert "SK509" not in rules_of(check(_mounted("9 0 0"), target="classic"))
    assert "SK509" not in rules_of(check(_mounted("0.15 0 0.3"), target="classic"))


def test_sk509_a_sensor_fixed_to_the_world_is_not_measured(check) -> None:
    # a camera on a fixed joint to a link named world stands in the world (a scene
    # camera 20 m away), not on the robot
    cam = camera_sensor(params="<frame_name>cam_link</frame_name>")
    scene = _tree(
        '<link name="world"/>', link("base_link"), joint("root_joint", "world", "base_link"),
        link("cam_link"), joint("cam_joint", "world", "cam_link", "20 0 5"),
        f'<gazebo reference="cam_link">{cam}</gazebo>',
    )
    assert "SK509" not in rules_of(check(scene, target="classic"))


def test_sk502_does_not_blame_an_optical_joint_that_writes_the_optical_rotation(check) -> None:
    # near miss (ROBOTIS OP3's head camera): the optical joint is right, the sensor's
    # <pose> turns the camera; the finding stays on the sensor and names no joint.
    cam = camera_sensor(extra="<update_rate>30</update_rate><pose>0 0 0 -1.5708 0 -3.141592</pose>")
    (f,) = [f for f in check(robot(camera=cam), target="classic").findings if f.rule == "SK502"]
    assert f.joint is None


def test_sk508_leaves_a_frame_a_lidar_stamps_to_sk504(check) -> None:
    lid = lidar_sensor(params="<frame_name>laser_optical_frame</frame_name>")
    text = _tree(
        '<link name="base_link"/>', link("laser_link"), joint("laser_joint", "base_link", "laser_link", "0 0 0.2"),
        '<link name="laser_optical_frame"/>', joint("lo", "laser_link", "laser_optical_frame", "0 0 0", "0 0 1.5707963267948966"),
        f'<gazebo reference="laser_link">{lid}</gazebo>',
    )
    r = check(text, target="classic")
    assert "SK504" in rules_of(r) and "SK508" not in rules_of(r)
