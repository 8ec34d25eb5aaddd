"""Issue 8's false-positive classes and misses: each with a trigger and a near miss.

Robots are our own, written to reproduce one class each; the real robots that showed
them live in ../shared/corpus/realworld (labelled in tests/realworld, run by test_realworld.py).
"""

from __future__ import annotations

from builders import camera_sensor, inertial, joint, lidar_sensor, link, robot
from conftest import rules_of

from sensorkit.base.suggest import closest


def _tree(*parts: str) -> str:
    return '<?xml version="1.0"?><robot name="t">' + "".join(parts) + "</robot>"


TB = '<link name="a">' + inertial() + "</link>"


# --- "did you mean" ranks by shared words, not shortness ---------------------------


def test_did_you_mean_prefers_shared_words() -> None:
    assert closest("gnss_link", ["base_link", "gnss_antenna_link", "imu_link"]) == ["gnss_antenna_link"]
    assert closest("camera_optical_frame", ["base_link", "camera_link_optical"]) == ["camera_link_optical"]
    assert closest("lidar_lnk", ["base_link", "lidar_link"]) == ["lidar_link"]
    assert closest("ghost", ["a", "b"]) == []  # nothing plausible: no suggestion at all


def test_sk202_suggestion_uses_words(check) -> None:
    bad = _tree(TB, link("base_link"), link("gnss_antenna_link"), joint("j", "a", "base_link"),
                joint("g", "gnss_link", "gnss_antenna_link"))
    f = next(f for f in check(bad, target="classic").findings if f.rule == "SK202")
    assert f.fix == "did you mean 'gnss_antenna_link'?"


# --- SK207 only for a moving mimic ------------------------------------------------


def test_sk207_ignores_a_fixed_joint_with_mimic(check) -> None:
    # A fixed joint never moves: nothing reads its <mimic>.
    fixed = _tree(TB, link("b"), link("c"), joint("f", "a", "c"),
                  joint("j", "a", "b", extra='<mimic joint="f"/>'))
    assert "SK207" not in rules_of(check(fixed, target="classic"))
    moving = _tree(TB, link("b"), link("c"), joint("f", "a", "c"),
                   joint("j", "a", "b", type="continuous", extra='<axis xyz="0 0 1"/><mimic joint="f"/>'))
    assert "SK207" in rules_of(check(moving, target="classic"))


# --- SK405 depth-test resolution only where it is real -------------------------


def test_sk405_far_near_ratio_is_not_reported_on_classic(check) -> None:
    # agilexrobotics/limo_ros2 limo_gazebo.gazebo: a depth camera with near 0.02, far 300
    # (far/near 15000) was told "depth precision collapses". Gazebo Classic's depth camera
    # writes depth = gl_Position.w, the linear view depth, into a PF_FLOAT32_R texture
    # (gazebosim/gazebo-classic@310a1d6:media/materials/programs/depth_map.vert:10;
    # @0106de6:gazebo/rendering/DepthCamera.cc CreateDepthTexture): the ratio does not coarsen
    # it. Its 24-bit z-buffer (OGRECave/ogre@852f847:RenderSystems/GL/src/
    # OgreGLFBORenderTexture.cpp:468-471) lets surfaces within 0.27 m z-fight at 300 m, under
    # the 0.1%-of-range floor SK405 reports from.
    clip = "<camera><clip><near>0.02</near><far>300</far></clip></camera>"
    depth = robot(camera=camera_sensor(stype="depth", camera=clip))
    assert "SK405" not in rules_of(check(depth, target="classic"))
    assert "SK405" not in rules_of(check(depth, target="ros1"))
    # Nor on Gazebo Sim: reverse-Z float32 depth (gazebosim/gz-rendering@ff0c5b8:ogre2/src/
    # Ogre2DepthCamera.cc:655 PFG_D32_FLOAT; ignition-forks/ogre-next@40dcea7:OgreMain/src/
    # OgreRenderSystem.cpp:96 mReverseDepth(true)). See test_rules.py GZ_DEPTH_SOURCES.
    assert "SK405" not in rules_of(check(depth, target="harmonic"))
    # Near miss on classic: a clip that is simply wrong is still an error.
    bad = robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>5</near><far>1</far></clip></camera>"))
    assert "SK405" in rules_of(check(bad, target="classic"))


def test_sk405_precision_only_for_depth(check) -> None:
    clip = "<camera><clip><near>0.001</near><far>100</far></clip></camera>"
    assert "SK405" not in rules_of(check(robot(camera=camera_sensor(camera=clip)), target="classic"))
    assert "SK405" in rules_of(check(robot(camera=camera_sensor(stype="depth", camera=clip)), target="classic"))


# --- unknown plugins: at most info --------------------------------------------------

LUMPED_LIDAR = robot().replace('link("laser_link")', "")  # the default robot already lumps laser_link


def test_unknown_plugin_gets_info_not_frame_errors(check) -> None:
    # A vendor's lidar plugin reading its own <frameId>: sensorkit cannot know its default.
    lid = robot(lidar='<sensor name="laser" type="ray"><ray><scan><horizontal><samples>360</samples>'
                '<min_angle>-3</min_angle><max_angle>3</max_angle></horizontal></scan><range><min>0.1</min>'
                '<max>10</max></range></ray><plugin name="l" filename="libacme_lidar_plugin.so">'
                "<frameId>camera_link</frameId></plugin></sensor>")
    report = check(lid, target="classic")
    rules = rules_of(report)
    assert "SK610" in rules
    assert not rules & {"SK303", "SK501", "SK503", "SK504", "SK607"}
    assert {f.severity.label for f in report.findings if f.rule == "SK610"} == {"info"}
    # Near miss: gazebo_ros_ray_sensor on the lumped laser_link without frame_name is SK303.
    known = robot(lidar=lidar_default_frame())
    assert "SK303" in rules_of(check(known, target="classic"))
    assert "SK610" not in rules_of(check(known, target="classic"))


def lidar_default_frame() -> str:
    from builders import lidar_sensor

    return lidar_sensor(params="<output_type>sensor_msgs/LaserScan</output_type>")


# --- placeholders and plugins that exist nowhere -----------------------------------


def test_placeholder_plugin_is_sk601(check) -> None:
    bad = robot(camera=camera_sensor(plugin="dummyfile"))
    f = next(f for f in check(bad, target="classic").findings if f.rule == "SK601")
    assert f.severity.label == "error" and "names no library" in f.message
    assert "SK601" not in rules_of(check(robot(), target="classic"))  # near miss: the real plugin


def test_placeholder_plugin_under_gz_is_a_warning(check) -> None:
    # gz-sim logs "Failed to load system plugin" and loads nothing; the sensor still
    # publishes (gazebosim/gz-sim@gz-sim8:src/SystemLoader.cc:92).
    from builders import gz_robot

    bad = gz_robot(camera_tags='<topic>cam</topic><gz_frame_id>camera_optical_frame</gz_frame_id><plugin name="d" filename="dummyfile"/>')
    f = next(f for f in check(bad, target="harmonic").findings if f.rule == "SK601")
    assert f.severity.label == "warning"
    assert "SK601" not in rules_of(check(gz_robot(), target="harmonic"))


# --- cascades: a plugin that cannot load carries the frame advice ------------------


def test_unloadable_plugin_folds_frame_advice_into_sk601(check) -> None:
    bad = robot(camera=camera_sensor(stype="depth", plugin="libgazebo_ros_openni_kinect.so", params="<frameName>camera_link</frameName>"))
    report = check(bad, target="classic")
    f = next(f for f in report.findings if f.rule == "SK601")
    assert "<frame_name>camera_optical_frame</frame_name>" in (f.fix or "")
    assert not rules_of(report) & {"SK502", "SK503", "SK303", "SK610"}
    # Near miss: the ROS 2 camera plugin with a ROS 1 tag loads, so its frame is checked.
    loads = check(robot(camera=camera_sensor(params="<frameName>camera_link</frameName>")), target="classic")
    assert {"SK602", "SK502"} <= rules_of(loads)


# --- ROS 1 descriptions: said once ---------------------------------------------------

ROS1_CAMERA = camera_sensor(params="<cameraName>cam</cameraName><imageTopicName>image_raw</imageTopicName>"
                            "<frameName>camera_optical_frame</frameName><updateRate>30</updateRate>")
ROS1_LASER = '<sensor name="laser" type="ray"><ray><scan><horizontal><samples>360</samples><min_angle>-3</min_angle><max_angle>3</max_angle></horizontal></scan><range><min>0.1</min><max>10</max></range></ray><plugin name="l" filename="libgazebo_ros_laser.so"><topicName>scan</topicName><frameName>laser_link</frameName></plugin></sensor>'


def test_ros1_description_is_said_once(check) -> None:
    report = check(robot(camera=ROS1_CAMERA, lidar=ROS1_LASER))
    assert report.target == "ros1" and "written for ROS 1" in report.target_reason
    rules = rules_of(report)
    assert "SK611" in rules and "SK602" not in rules and "SK601" not in rules
    assert len([f for f in report.findings if f.rule == "SK611"]) == 1
    # Near miss: a ROS 2 file (it has <ros> and frame_name) with one ROS 1 tag stays classic.
    ros2 = robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><updateRate>30</updateRate>"))
    r2 = check(ros2)
    assert r2.target == "classic" and "SK602" in rules_of(r2) and "SK611" not in rules_of(r2)
    # Asked for classic explicitly, every tag is listed for porting.
    ported = check(robot(camera=ROS1_CAMERA, lidar=ROS1_LASER), target="classic")
    assert len([f for f in ported.findings if f.rule == "SK602"]) == 4  # the camera's four tags
    assert "SK601" in rules_of(ported) and "SK611" not in rules_of(ported)  # gazebo_ros_laser is ROS 1 only


# --- SK105: an unknown element straight under <robot> ------------------------------


def test_unknown_robot_child_is_sk105(check) -> None:
    bad = robot(extra='<camera_sensor name="front"/>')
    f = next(f for f in check(bad, target="classic").findings if f.rule == "SK105")
    assert "directly under <robot>" in f.message
    ok = robot(extra='<transmission name="t"/><ros2_control name="c" type="system"/><material name="m"/>'
                     '<foo:bar xmlns:foo="http://example.com/foo"/>')
    assert "SK105" not in rules_of(check(ok, target="classic"))


# --- SK202 then SK203: what is cut off is named and still checked ------------------


def test_cut_off_subtree_is_named_and_its_sensors_checked(check) -> None:
    bad = robot(camera=camera_sensor(params="<frame_name>camera_link</frame_name>")).replace(
        '<parent link="base_link"/><child link="camera_link"/>', '<parent link="base_lnk"/><child link="camera_link"/>')
    report = check(bad, target="classic")
    rules = rules_of(report)
    assert {"SK202", "SK203", "SK502"} <= rules
    sk203 = next(f for f in report.findings if f.rule == "SK203")
    assert sk203.link == "camera_link" and "camera_optical_frame" in sk203.message
    # Near miss: the same camera properly attached has no SK203.
    assert "SK203" not in rules_of(check(robot(camera=camera_sensor(params="<frame_name>camera_link</frame_name>")), target="classic"))


# --- SK607 on Gazebo Sim: what the bridge carries ----------------------------------

BRIDGE = """- ros_topic_name: front_camera/image_raw
  gz_topic_name: front_camera/image_raw
  ros_type_name: sensor_msgs/msg/Image
  gz_type_name: gz.msgs.Image
  direction: GZ_TO_ROS
"""


def _gz(tmp_path, bridge_text: str | None, *, in_config: bool = False, camera_tags: str | None = None):  # type: ignore[no-untyped-def]
    from builders import gz_robot

    from sensorkit.lint.engine import Options, validate_file

    pkg = tmp_path / "rover_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>rover_description</name></package>")
    path = pkg / "urdf" / "rover.urdf"
    path.write_text(gz_robot(camera_tags=camera_tags))
    bridges: tuple[str, ...] = ()
    if bridge_text is not None:
        where = pkg / "config" if in_config else tmp_path
        where.mkdir(exist_ok=True)
        (where / "bridge.yaml").write_text(bridge_text)
        bridges = () if in_config else (str(where / "bridge.yaml"),)
    report = validate_file(path, Options(target="harmonic", bridges=bridges))
    assert not report.internal_errors and report.error is None, report.error
    return report


def test_gz_without_bridge_says_nothing_about_sensors_with_topics(tmp_path) -> None:
    report = _gz(tmp_path, None)
    assert "SK607" not in rules_of(report)  # no bridge known: nothing to compare with


def test_gz_no_topic_and_no_bridge_is_info_naming_the_scoped_topic(tmp_path) -> None:
    report = _gz(tmp_path, None, camera_tags="<gz_frame_id>camera_optical_frame</gz_frame_id>")
    f = next(f for f in report.findings if f.rule == "SK607")
    assert f.severity.label == "info" and "/sensor/front_camera/image" in f.message


def test_gz_bridge_lacking_a_sensor_is_an_error_only_for_it(tmp_path) -> None:
    # ros_gz_bridge bridges its entries only (gazebosim/ros_gz@jazzy 739cb42:ros_gz_bridge/
    # src/ros_gz_bridge.cpp:54-62): ROS receives nothing of the lidar (error, issue 35).
    report = _gz(tmp_path, BRIDGE)
    sk607 = [f for f in report.findings if f.rule == "SK607"]
    assert [f.sensor for f in sk607] == ["laser"] and sk607[0].severity.label == "error"
    assert "/scan" in sk607[0].message


def test_gz_bridge_found_in_package_config(tmp_path) -> None:
    full = BRIDGE + """- ros_topic_name: scan
  gz_topic_name: scan
  ros_type_name: sensor_msgs/msg/LaserScan
  gz_type_name: gz.msgs.LaserScan
  direction: GZ_TO_ROS
"""
    assert "SK607" not in rules_of(_gz(tmp_path, full, in_config=True))


def test_bridge_entry_matching_no_sensor_is_sk618_when_a_sensor_of_its_type_is_unbridged(tmp_path) -> None:
    # Issue 35 item 7: a misspelt gz topic while a sensor of the same message type stays
    # unbridged is SK618 (it was SK612), with the topic it meant; SK612 leaves it alone.
    typo = BRIDGE.replace("gz_topic_name: front_camera/image_raw", "gz_topic_name: front_camera/imag_raw")
    report = _gz(tmp_path, typo)
    f = next(f for f in report.findings if f.rule == "SK618")
    assert f.fix == "gz_topic_name: front_camera/image_raw" and f.line == 1
    assert "SK612" not in rules_of(report)
    assert not {"SK612", "SK618"} & rules_of(_gz(tmp_path / "b", BRIDGE))


def test_bad_bridge_file_is_a_usage_error(tmp_path) -> None:
    from conftest import run_cli

    (tmp_path / "r.urdf").write_text(__import__("builders").gz_robot())
    (tmp_path / "b.yaml").write_text("topics: {}\n")
    res = run_cli("validate", str(tmp_path / "r.urdf"), "--bridge", str(tmp_path / "b.yaml"))
    assert res.returncode == 2 and "b.yaml" in res.stderr and "Traceback" not in res.stderr


# --- sensors published by a model-level plugin -------------------------------------


def test_sensor_published_by_model_plugin_counts(check) -> None:
    # A model plugin sensorkit does not know that names the sensor may read it: "cannot tell",
    # info, never the warning that nothing publishes it (issue 35 item 4: it was silent, as if
    # sensorkit knew the plugin reads it); a known one (realsense) reads what its table entry
    # says: tests/test_sensor_owners.py.
    bare = camera_sensor(plugin="")
    model = '<gazebo><plugin name="rs" filename="libacme_camera_rig.so"><colorCameraName>front_camera</colorCameraName></plugin></gazebo>'
    found = [f for f in check(robot(camera=bare, extra=model), target="classic").findings if f.rule == "SK607"]
    assert [f.severity.label for f in found] == ["info"] and "cannot tell" in found[0].message
    other = model.replace(">front_camera<", ">rear_camera<")
    found = [f for f in check(robot(camera=bare, extra=other), target="classic").findings if f.rule == "SK607"]
    assert [f.severity.label for f in found] == ["error"]  # the lidar's gazebo_ros plugin: meant for ROS


# --- stereo: the right eye in the left eye's optical frame -------------------------


def _stereo(baseline: str) -> str:
    right = camera_sensor("right_camera", params=f"<frame_name>camera_optical_frame</frame_name><camera_name>right</camera_name><hack_baseline>{baseline}</hack_baseline>")
    extra = ('<link name="right_link">' + inertial() + "</link>" + joint("right_joint", "camera_link", "right_link", "0 -0.07 0")
             + f'<gazebo reference="right_link">{right}</gazebo>')
    return robot(extra=extra)


def test_stereo_right_eye_in_left_optical_frame_is_the_ros_convention(check) -> None:
    assert "SK503" not in rules_of(check(_stereo("0.07"), target="classic"))
    wrong = [f for f in check(_stereo("0.12"), target="classic").findings if f.rule == "SK503"]
    assert [f.sensor for f in wrong] == ["right_camera"]


# --- world frames of world-referenced plugins ---------------------------------------


def test_bumper_in_world_frame_is_valid(check) -> None:
    contact = ('<sensor name="bumper" type="contact"><contact><collision>c</collision></contact>'
               '<plugin name="b" filename="libgazebo_ros_bumper.so"><frame_name>world</frame_name></plugin></sensor>')
    extra = f'<gazebo reference="base_link">{contact}</gazebo>'
    assert "SK501" not in rules_of(check(robot(extra=extra), target="classic"))
    camera_world = robot(camera=camera_sensor(params="<frame_name>world</frame_name>"))
    assert "SK501" in rules_of(check(camera_world, target="classic"))


# --- SK102 in a macro points into the macro's file ----------------------------------


def test_sk102_in_a_macro_points_at_the_macro(tmp_path) -> None:
    from sensorkit.lint.engine import validate_file

    (tmp_path / "sensors.xacro").write_text(
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="cam" params="name">\n    <link name="${name}_link"/>\n'
        '    <joint name="${name}_joint" type="fixed">\n      <origin xyz="${offset_x} 0 0"/>\n'
        '      <parent link="base_link"/><child link="${name}_link"/>\n    </joint>\n'
        "  </xacro:macro>\n</robot>\n")
    (tmp_path / "robot.urdf.xacro").write_text(
        '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="sensors.xacro"/>\n  <link name="base_link"/>\n  <xacro:cam name="front"/>\n</robot>\n')
    f = next(f for f in validate_file(tmp_path / "robot.urdf.xacro").findings if f.rule == "SK102")
    assert f.file is not None and f.file.endswith("sensors.xacro") and f.line == 6


# --- the same findings from any folder ----------------------------------------------


def test_same_findings_from_any_folder(tmp_path) -> None:
    import json

    from conftest import run_cli

    pkg = tmp_path / "ws" / "src" / "rover_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "meshes").mkdir()
    (pkg / "meshes" / "body.stl").write_text("solid x\nendsolid x\n")
    (pkg / "package.xml").write_text("<package><name>rover_description</name></package>")
    mesh = '<link name="body"><visual><geometry><mesh filename="package://rover_description/meshes/body.stl"/></geometry></visual>' + inertial() + "</link>" + joint("bj", "base_link", "body")
    (pkg / "urdf" / "robot.urdf").write_text(robot(extra=mesh))

    def findings(cwd, path: str) -> list[tuple[str, int | None]]:
        res = run_cli("validate", path, "--format", "json", cwd=cwd)
        assert res.returncode in (0, 1), res.stderr
        return sorted((f["rule"], f["line"]) for f in json.loads(res.stdout)["findings"])

    here = findings(pkg / "urdf", "robot.urdf")
    assert here == findings(tmp_path, "ws/src/rover_description/urdf/robot.urdf")
    assert here == findings(pkg, "urdf/robot.urdf")
    assert all(rule != "SK103" for rule, _ in here)


def test_dangling_non_fixed_joint_crashes_no_rule(check) -> None:
    # Once a KeyError in SK301: a revolute joint to a link that does not exist.
    bad = _tree(TB, '<joint name="j" type="revolute"><parent link="a"/><child link="ghost"/><axis xyz="0 0 1"/>'
                '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    report = check(bad, target="classic")  # the fixture asserts no internal error
    assert "SK202" in rules_of(report)


def test_sk401_error_only_when_a_sensor_or_plugin_is_lost(check) -> None:
    styling = robot(extra='<gazebo reference="forearm_link"><material>Gazebo/Grey</material></gazebo>')
    f = next(f for f in check(styling, target="classic").findings if f.rule == "SK401")
    assert f.severity.label == "warning"
    lost = robot(camera=camera_sensor()).replace('<gazebo reference="camera_link">', '<gazebo reference="cam_link">')
    f = next(f for f in check(lost, target="classic").findings if f.rule == "SK401")
    assert f.severity.label == "error" and "its sensor" in f.message


def test_axis_of_a_fixed_joint_is_not_read(check) -> None:
    # urdfdom parses <axis> only for moving joints (ros/urdfdom@9a1f5b4:urdf_parser/src/joint.cpp:425);
    # seen on kortex gen3_lite.urdf's tool_frame_joint.
    fixed = _tree(TB, link("b"), joint("j", "a", "b", extra='<axis xyz="0 0 0"/>'))
    assert "SK206" not in rules_of(check(fixed, target="classic"))
    moving = _tree(TB, link("b"), joint("j", "a", "b", type="continuous", extra='<axis xyz="0 0 0"/>'))
    assert "SK206" in rules_of(check(moving, target="classic"))


def test_imu_read_by_ros2_control_counts_as_published(check) -> None:
    # gazebo_ros2_control reads <ros2_control><sensor name> by the Gazebo sensor's name
    # (ros-controls/gazebo_ros2_control@humble:gazebo_ros2_control/src/gazebo_system.cpp:554-589).
    imu = '<gazebo reference="base_link"><sensor name="imu_sensor" type="imu"><update_rate>50</update_rate></sensor></gazebo>'
    control = ('<ros2_control name="sys" type="system"><hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>'
               '<sensor name="imu_sensor"><state_interface name="orientation.x"/></sensor></ros2_control>'
               '<gazebo><plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control"/></gazebo>')
    assert "SK607" not in rules_of(check(robot(extra=imu + control), target="classic"))
    no_plugin = control.split("<gazebo>", maxsplit=1)[0]  # the ros2_control block alone loads nothing in Gazebo
    assert "SK607" in rules_of(check(robot(extra=imu + no_plugin), target="classic"))


def test_sk402_only_for_sensors_that_share_a_link(check) -> None:
    # sdformat refuses a duplicate sensor name within one link (gazebosim/sdformat@sdf14:
    # src/Link.cc:167, src/Utils.hh:128-136); on different links the names are scoped apart.
    apart = robot(lidar=__import__("builders").lidar_sensor(name="front_camera"), camera_joint_type="revolute")
    assert "SK402" not in rules_of(check(apart, target="classic"))
    merged = robot(lidar=__import__("builders").lidar_sensor(name="front_camera"))  # both lumped into base_link
    assert "SK402" in rules_of(check(merged, target="classic"))


def test_sk402_per_simulator(check) -> None:
    # Gazebo Classic 11 creates both sensors of one name on one link (gazebosim/gazebo-classic@
    # upstream/11.10.2+dfsg via elysia-best/gazebo-classic: gazebo/physics/Link.cc:185-209,
    # gazebo/sensors/SensorManager.cc:488-531). Two depth cameras then both name their render
    # texture "<name>_RttTex_Image" (gazebo/sensors/DepthCameraSensor.cc:101-102) and two cameras
    # "<model::link>::<name>_RttTex" (CameraSensor.cc:146,167): Ogre throws for the second
    # (OGRECave/ogre@006d77cb:OgreMain/src/OgreResourceManager.cpp ResourceManager::addImpl),
    # uncaught (SensorManager.cc:320, gazebo/Server.cc:696): gzserver aborts.

    def sk402(urdf: str, target: str) -> list[str]:
        return [f.severity.label for f in check(urdf, target=target).findings if f.rule == "SK402"]

    depths = robot(camera=camera_sensor(stype="depth"), lidar=camera_sensor(stype="depth", plugin_name="p2"))
    assert sk402(depths, "classic") == ["error"]
    cameras = robot(camera=camera_sensor(), lidar=camera_sensor(plugin_name="p2"))
    assert sk402(cameras, "classic") == ["error"]
    # A camera and a depth camera of one name name different textures; a lidar none: both
    # work, only a look-up by scoped name finds the first (SensorManager.cc:883-888).
    mixed = robot(camera=camera_sensor(stype="depth"), lidar=camera_sensor(plugin_name="p2"))
    assert sk402(mixed, "classic") == ["warning"]
    lidar = robot(lidar=lidar_sensor(name="front_camera"))
    assert sk402(lidar, "classic") == ["warning"]
    # Gazebo Sim: sdformat refuses any duplicate in one link (gazebosim/sdformat@sdf14:src/Link.cc:167).
    assert sk402(lidar, "harmonic") == ["error"]
    assert sk402(robot(lidar=lidar_sensor()), "classic") == []


def test_range_sensors_may_share_a_topic(check) -> None:
    def sonar(name: str, link: str) -> str:
        return (f'<gazebo reference="{link}"><sensor name="{name}" type="ray"><update_rate>10</update_rate><ray><scan><horizontal>'
                '<samples>5</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle></horizontal></scan><range><min>0.02</min>'
                f'<max>3</max></range></ray><plugin name="{name}_p" filename="libgazebo_ros_ray_sensor.so"><ros><remapping>~/out:=/sonar_base</remapping></ros>'
                f"<output_type>{{t}}</output_type><frame_name>{link}</frame_name></plugin></sensor></gazebo>")
    links = link("s1") + joint("s1j", "base_link", "s1", "0.2 0.1 0") + link("s2") + joint("s2j", "base_link", "s2", "0.2 -0.1 0")
    two = links + sonar("sonar_1", "s1") + sonar("sonar_2", "s2")
    assert "SK605" not in rules_of(check(robot(extra=two.replace("{t}", "sensor_msgs/Range")), target="classic"))
    assert "SK605" in rules_of(check(robot(extra=two.replace("{t}", "sensor_msgs/LaserScan")), target="classic"))


def test_topic_rules_read_the_plugin_table(check) -> None:
    # gazebo_ros_gps_sensor publishes ~/out and ~/vel (sensorkit/knowledge/plugins.py, with its
    # source): remapping ~/vel changes something, so SK609 stays quiet; a typo does not.
    def gps(remap: str) -> str:
        return ('<gazebo reference="base_link"><sensor name="gps" type="gps"><update_rate>5</update_rate>'
                f'<plugin name="gps_p" filename="libgazebo_ros_gps_sensor.so"><ros><remapping>{remap}</remapping></ros>'
                "<frame_name>base_link</frame_name></plugin></sensor></gazebo>")
    assert "SK609" not in rules_of(check(robot(extra=gps("~/vel:=gps/vel")), target="classic"))
    assert "SK609" in rules_of(check(robot(extra=gps("~/velocity:=gps/vel")), target="classic"))


def test_ros1_topics_are_not_judged_with_ros2_names(check) -> None:
    # ROS 1 topic names (robotNamespace, bumperTopicName, tf_prefix) are not modelled: the
    # ROS 2 default 'bumper_states' must not make two ROS 1 bumpers collide (seen on PR2).
    def bumper(name: str, lk: str) -> str:
        return (f'<gazebo reference="{lk}"><sensor name="{name}" type="contact"><contact><collision>c</collision></contact>'
                f'<plugin name="{name}_p" filename="libgazebo_ros_bumper.so"><bumperTopicName>{name}</bumperTopicName>'
                "<frameName>world</frameName></plugin></sensor></gazebo>")
    two = bumper("b1", "base_link") + bumper("b2", "camera_link")
    assert "SK605" not in rules_of(check(robot(extra=two), target="ros1"))


def test_third_party_frame_parameter_naming_a_missing_link_is_sk501(check) -> None:
    # hector_gazebo_ros_imu reads <frameId> (sensorkit/knowledge/plugins.py cites
    # tu-darmstadt-ros-pkg/hector_gazebo): a frame that is no link cannot be placed by TF.
    def hector(frame: str) -> str:
        return ('<gazebo><plugin name="imu" filename="libhector_gazebo_ros_imu.so"><bodyName>base_link</bodyName>'
                f"<frameId>{frame}</frameId><topicName>imu</topicName></plugin></gazebo>")
    f = next(f for f in check(robot(extra=hector("imu_lnk")), target="ros1").findings if f.rule == "SK501")
    assert f.frame == "imu_lnk" and "<frameId>" in f.message
    assert "SK501" not in rules_of(check(robot(extra=hector("base_link")), target="ros1"))


def _ros1_laser(frame: str | None) -> str:
    tag = "" if frame is None else f"<frameName>{frame}</frameName>"
    return ROS1_LASER.replace("<frameName>laser_link</frameName>", tag)


def _published(report, name: str, target: str):  # type: ignore[no-untyped-def]
    from sensorkit.model.frames import sensor_frames
    from sensorkit.model.sdf import convert

    robot_ = report.robot
    assert robot_ is not None
    s = next(s for s in robot_.sensors if s.name == name)
    return sensor_frames(robot_, s, target, convert(robot_))


def test_ros1_frame_name_loses_its_leading_slash(check) -> None:
    # ROS 1 tf::resolve(prefix, frame_name) returns strip_leading_slash(frame_name) when it
    # starts with "/" (ros/geometry@noetic-devel fe344b6:tf/src/tf.cpp:159-166, :195-206),
    # and gazebo_plugins passes the frame through it before stamping
    # (ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a46:gazebo_plugins/src/
    # gazebo_ros_laser.cpp:137-138, stamped at :190; gazebo_ros_camera_utils.cpp:296-298).
    # Near miss: /laser_link stamps laser_link, a link: no SK501.
    report = check(robot(camera=ROS1_CAMERA, lidar=_ros1_laser("/laser_link")), target="ros1")
    assert "SK501" not in rules_of(report)
    assert _published(report, "laser", "ros1").published == "laser_link"
    from sensorkit.describe.sensorinfo import describe  # what `sensorkit topics` prints

    assert report.robot is not None
    laser = next(i for i in describe(report.robot, "ros1").sensors if i.sensor.name == "laser")
    assert laser.frame == "laser_link"
    cam = camera_sensor(params="<cameraName>cam</cameraName><frameName>/camera_optical_frame</frameName>")
    report = check(robot(camera=cam, lidar=ROS1_LASER), target="ros1")
    assert "SK501" not in rules_of(report)
    assert _published(report, "front_camera", "ros1").published == "camera_optical_frame"
    # Trigger: a frame naming no link, with and without the slash, still is SK501, and the
    # finding names the frame as stamped.
    for given in ("laser_lnk", "/laser_lnk"):
        report = check(robot(camera=ROS1_CAMERA, lidar=_ros1_laser(given)), target="ros1")
        f = next(f for f in report.findings if f.rule == "SK501")
        assert f.frame == "laser_lnk" and f.sensor == "laser"


def test_ros1_laser_default_frame_is_world(check) -> None:
    # gazebo_ros_laser.cpp:88-92 (noetic-devel f9e1a46) defaults frame_name_ to "/world",
    # then :138 tf::resolve drops the slash (tf.cpp:162-166): the scan is stamped "world".
    report = check(robot(camera=ROS1_CAMERA, lidar=_ros1_laser(None)), target="ros1")
    fr = _published(report, "laser", "ros1")
    assert fr.is_default and fr.published == "world"


def test_ros1_model_plugin_frames_follow_tf_resolve(check) -> None:
    # diff drive: gazebo_ros_diff_drive.cpp:407 resolveTF(robot_base_frame_), which is
    # tf::resolve (gazebo_ros_utils.cpp:52-53, noetic-devel f9e1a46): /base_link is base_link.
    def plugin(lib: str, tag: str, frame: str) -> str:
        return f'<gazebo><plugin name="p" filename="{lib}"><{tag}>{frame}</{tag}><topicName>t</topicName></plugin></gazebo>'

    drive = "libgazebo_ros_diff_drive.so"
    assert "SK501" not in rules_of(check(robot(extra=plugin(drive, "robotBaseFrame", "/base_link")), target="ros1"))
    f = next(f for f in check(robot(extra=plugin(drive, "robotBaseFrame", "/base_lnk")), target="ros1").findings if f.rule == "SK501")
    assert f.frame == "base_lnk"
    # p3d stamps tf::resolve(prefix, frame_name_) (gazebo_ros_p3d.cpp:146) but looks the link
    # up by the unresolved name (:178 GetLink(frame_name_); :181 "does not exist, will not
    # publish"): /base_link still names no link there.
    p3d = plugin("libgazebo_ros_p3d.so", "frameName", "/base_link").replace("<topicName>", "<bodyName>base_link</bodyName><topicName>")
    assert "SK501" in rules_of(check(robot(extra=p3d), target="ros1"))


def test_ros2_frame_name_keeps_its_leading_slash(check) -> None:
    # ROS 2 gazebo_ros::SensorFrameID returns <frame_name> as written
    # (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_ros/src/utils.cpp:52-57); nothing in
    # gazebo_ros strips a slash, so /laser_link is no link and stays SK501.
    laser = lidar_sensor(params="<frame_name>/laser_link</frame_name>")
    report = check(robot(lidar=laser), target="classic")
    assert _published(report, "laser", "classic").published == "/laser_link"
    assert "SK501" in rules_of(report)


def test_vendor_gazebo_ros_plugins_parameters_are_not_ros2_evidence(check) -> None:
    # kobuki's ROS 1 libgazebo_ros_kobuki.so spells wheel_separation in snake_case; only
    # gazebo_ros_pkgs' own parameters (and a <ros> block) tell ROS 2 apart (seen on turtlebot).
    kobuki = '<gazebo><plugin name="k" filename="libgazebo_ros_kobuki.so"><wheel_separation>0.23</wheel_separation></plugin></gazebo>'
    report = check(robot(camera=ROS1_CAMERA, lidar=ROS1_LASER, extra=kobuki))
    assert report.target == "ros1"
    ros2_vendor = kobuki.replace("<wheel_separation>", "<ros><namespace>/</namespace></ros><wheel_separation>")
    assert check(robot(camera=ROS1_CAMERA, lidar=ROS1_LASER, extra=ros2_vendor)).target == "classic"


def test_sk604_only_for_plugins_that_load(check) -> None:
    # pmb2's two openni_kinect plugins share a name, but under ROS 2 neither loads (SK601):
    # no node is made, so no node-name clash either.
    two = (camera_sensor("a", stype="depth", plugin="{p}", plugin_name="same")
           + camera_sensor("b", stype="depth", plugin="{p}", plugin_name="same"))
    extra = f'<gazebo reference="base_link">{two}</gazebo>'
    ros1 = robot(extra=extra.replace("{p}", "libgazebo_ros_openni_kinect.so"))
    assert "SK604" not in rules_of(check(ros1, target="classic"))
    ros2 = robot(extra=extra.replace("{p}", "libgazebo_ros_camera.so"))
    assert "SK604" in rules_of(check(ros2, target="classic"))


# --- third-party plugins: the parameters each generation reads say which it is ------------


def _velodyne(name: str, params: str, plugin: str = "libgazebo_ros_velodyne_laser.so", stype: str = "ray") -> str:
    from builders import lidar_sensor

    # Both sensors' plugins are called as in velodyne_description's macros (VLP-16.urdf.xacro).
    return lidar_sensor(name, stype=stype, plugin=plugin, params=params).replace(
        f'name="{name}_controller"', 'name="gazebo_ros_laser_controller"'
    )


def _velodyne_ros1(frame: str, topic: str) -> str:
    # The tags tier4/velodyne_simulator@master fe021b6:velodyne_description/urdf/VLP-16.urdf.xacro
    # writes, read by the ROS 1 plugin (velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:115-158).
    return (f"<topicName>{topic}</topicName><frameName>{frame}</frameName><min_range>0.9</min_range>"
            "<max_range>130.0</max_range><gaussianNoise>0.008</gaussianNoise>")


def _velodyne_ros2(frame: str, ros: str = "") -> str:
    # The ROS 2 port's tags (prepare/humble 00759c8: GazeboRosVelodyneLaser.cpp:73-114).
    return (f"{ros}<tf_prefix></tf_prefix><frame_name>{frame}</frame_name><organize_cloud>false</organize_cloud>"
            "<min_range>0.9</min_range><max_range>130.0</max_range><gaussian_noise>0.008</gaussian_noise>")


def test_ros1_velodyne_description_is_ros1(check) -> None:
    # tier4/velodyne_simulator master (ROS 1): example.urdf.xacro was taken for ROS 2 and got
    # SK303/SK503 (frame_name default), SK604 and SK605 (the ROS 2 node and ~/out), all false.
    # Parameters velodyne's ROS 1 spec reads and its ROS 2 spec does not (topicName, frameName,
    # gaussianNoise: sensorkit/knowledge/plugins.py VELODYNE_ROS1_PARAMS) are ROS 1 evidence.
    two = robot(camera=_velodyne("velodyne2", _velodyne_ros1("camera_link", "/velodyne_points2")),
                lidar=_velodyne("velodyne", _velodyne_ros1("laser_link", "/velodyne_points")))
    report = check(two)
    assert report.target == "ros1" and "written for ROS 1" in report.target_reason
    assert not rules_of(report) & {"SK303", "SK503", "SK602", "SK604", "SK605", "SK610"}
    # One sensor's three ROS 1-only tags are enough; the GPU library (the same source built
    # twice: CMakeLists.txt:29,36) reads the same tags.
    one = robot(camera=camera_sensor(params="<frameName>camera_optical_frame</frameName>"),
                lidar=_velodyne("velodyne", _velodyne_ros1("laser_link", "/velodyne_points"),
                        plugin="libgazebo_ros_velodyne_gpu_laser.so", stype="gpu_ray"))
    assert check(one).target == "ros1"


def test_ros2_velodyne_description_stays_ros2(check) -> None:
    # Near miss: the ROS 2 port (tier4/velodyne_simulator prepare/humble) with its <ros> block.
    ns = "<ros><namespace>/{n}</namespace><remapping>~/out:={n}_points</remapping></ros>"
    ros2 = robot(camera=_velodyne("velodyne2", _velodyne_ros2("camera_link", ns.format(n="velodyne2"))),
                 lidar=_velodyne("velodyne", _velodyne_ros2("laser_link", ns.format(n="velodyne"))))
    report = check(ros2)
    assert report.target == "classic"
    assert not rules_of(report) & {"SK611", "SK604", "SK605"}
    # Without <ros>, the port's own snake_case tags (frame_name, gaussian_noise, organize_cloud)
    # still say ROS 2, against a file with more ROS 1 tags elsewhere: and then the two plugins
    # of one name are one ROS 2 node, which gazebo_ros refuses (SK604 is still reported).
    bare = robot(camera=ROS1_CAMERA, lidar=_velodyne("velodyne", _velodyne_ros2("laser_link")),
                 extra=f'<gazebo reference="base_link">{_velodyne("velodyne2", _velodyne_ros2("base_link"))}</gazebo>')
    r2 = check(bare)
    assert r2.target == "classic" and "SK604" in rules_of(r2)


def test_sk604_is_not_reported_under_ros1(check) -> None:
    # ROS 1 gzserver is one node, "gazebo" (gazebo_ros_api_plugin.cpp:126); plugins open
    # NodeHandles in it, so two plugins of one name make no clash (trigger: the same robot
    # under classic, where each is a gazebo_ros::Node of that name).
    two = (camera_sensor("a", plugin_name="same") + camera_sensor("b", plugin_name="same"))
    r = robot(extra=f'<gazebo reference="base_link">{two}</gazebo>')
    assert "SK604" in rules_of(check(r, target="classic"))
    assert "SK604" not in rules_of(check(r, target="ros1"))


def test_closest_is_the_n_best_by_score_however_it_prunes() -> None:
    """``closest`` spells out a candidate only while it could still place (SK401 on PR2
    took 55-70 ms): its answer must stay the ``n`` best by ``score`` among the qualified,
    ties by name, as ranking every candidate gives."""
    import difflib
    import random

    from sensorkit.base.suggest import GENERIC, score, words

    def qualifies(name: str, c: str) -> bool:
        if (set(words(name)) & set(words(c))) - GENERIC:
            return True
        return difflib.SequenceMatcher(None, name.lower(), c.lower()).ratio() >= 0.7

    rnd = random.Random(7)
    vocab = ["link", "frame", "optical", "base", "r", "l", "gripper", "camera", "front",
             "laser", "imu", "wheel", "palm", "tilt", "head", "cam1", "Cam", "depth"]  # fmt: skip

    def name() -> str:
        parts = [rnd.choice(vocab) for _ in range(rnd.randint(1, 4))]
        if rnd.random() < 0.3:
            parts[0] += rnd.choice("abcxyz")
        return rnd.choice("_-/").join(parts)

    for _ in range(1500):
        pool = [name() for _ in range(rnd.randint(0, 50))]
        q, n = name(), rnd.choice([1, 1, 2, 5])
        ranked = sorted(
            ((score(q, c), c) for c in dict.fromkeys(pool) if c != q and qualifies(q, c)),
            key=lambda t: (-t[0], t[1]),
        )
        assert closest(q, pool, n) == [c for _, c in ranked[:n]], (q, pool, n)
