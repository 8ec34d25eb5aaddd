"""Every rule: a case that triggers it and a near miss that must not."""

from __future__ import annotations

import pytest
from builders import OPTICAL, camera_sensor, gz_robot, inertial, joint, lidar_sensor, link, robot
from conftest import rules_of

from sensorkit.findings import Severity
from sensorkit.rules import RULES

CLEAN = robot()
GZ_CLEAN = gz_robot()
TB = '<link name="a">' + inertial() + "</link>"


def _tree(*parts: str) -> str:
    return '<?xml version="1.0"?><robot name="t">' + "".join(parts) + "</robot>"


# (rule, triggering description, near miss, target, file suffix)
CASES: list[tuple[str, str, str, str, str]] = [
    ("SK104",
     robot(extra='<link name="m"><visual><geometry><mesh filename="meshes/nothere.stl"/></geometry></visual>' + inertial() + "</link>" + joint("mj", "base_link", "m")),
     robot(extra='<link name="m"><visual><geometry><mesh filename="model://somewhere/x.stl"/></geometry></visual>' + inertial() + "</link>" + joint("mj", "base_link", "m")),
     "classic", ".urdf"),
    ("SK105",
     robot(extra='<link name="x"><intertial><mass values="1"/></intertial></link>' + joint("xj", "base_link", "x")),
     robot(extra='<link name="x">' + inertial() + "</link>" + joint("xj", "base_link", "x")),
     "classic", ".urdf"),
    ("SK105",
     robot(extra='<link name="x"><inertial><mass values="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>' + joint("xj", "base_link", "x")),
     robot(extra='<link name="x"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>' + joint("xj", "base_link", "x")),
     "classic", ".urdf"),
    ("SK105",
     robot(extra='<link name="x">' + inertial() + '<gazebo><material>Gazebo/Red</material></gazebo></link>' + joint("xj", "base_link", "x")),
     robot(extra='<link name="x">' + inertial() + '</link><gazebo reference="x"><material>Gazebo/Red</material></gazebo>' + joint("xj", "base_link", "x")),
     "classic", ".urdf"),
    ("SK201", _tree(TB, TB), _tree(TB, '<link name="b"/>', joint("j", "a", "b")), "classic", ".urdf"),
    ("SK202", _tree(TB, joint("j", "a", "ghost")), _tree(TB, '<link name="b"/>', joint("j", "a", "b")), "classic", ".urdf"),
    ("SK203", _tree(TB, '<link name="b"/>'), _tree(TB, '<link name="b"/>', joint("j", "a", "b")), "classic", ".urdf"),
    ("SK204", _tree(TB, link("b"), joint("j1", "a", "b"), joint("j2", "b", "a")), _tree(TB, link("b"), joint("j1", "a", "b")), "classic", ".urdf"),
    ("SK204", _tree(TB, joint("j", "a", "a")), _tree(TB), "classic", ".urdf"),
    ("SK204", _tree(TB, link("b"), link("c"), joint("j1", "a", "c"), joint("j2", "b", "c"), joint("j3", "a", "b")),
     _tree(TB, link("b"), link("c"), joint("j1", "a", "c"), joint("j3", "a", "b")), "classic", ".urdf"),
    ("SK205", _tree(TB, link("b"), joint("j", "a", "b", type="revolute", extra='<axis xyz="0 0 1"/>')),
     _tree(TB, link("b"), joint("j", "a", "b", type="revolute", extra='<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>')), "classic", ".urdf"),
    ("SK205", _tree(TB, link("b"), joint("j", "a", "b", type="hinge")), _tree(TB, link("b"), joint("j", "a", "b", type="continuous", extra='<axis xyz="0 0 1"/>')), "classic", ".urdf"),
    ("SK205", _tree(TB, link("b"), joint("j", "a", "b", type="prismatic", extra='<limit lower="1" upper="-1" effort="1" velocity="1"/>')),
     _tree(TB, link("b"), joint("j", "a", "b", type="prismatic", extra='<limit lower="-1" upper="1" effort="1" velocity="1"/>')), "classic", ".urdf"),
    ("SK206", _tree(TB, link("b"), joint("j", "a", "b", xyz="0 nan 0")), _tree(TB, link("b"), joint("j", "a", "b", xyz="0 1e-3 0")), "classic", ".urdf"),
    ("SK206", _tree(TB, link("b"), joint("j", "a", "b", type="continuous", extra='<axis xyz="0 0 0"/>')),
     _tree(TB, link("b"), joint("j", "a", "b", type="continuous", extra='<axis xyz="0 0 1"/>')), "classic", ".urdf"),
    ("SK206", _tree(TB, link("b"), joint("j", "a", "b", rpy="0 0")), _tree(TB, link("b"), joint("j", "a", "b", rpy="0 0 0")), "classic", ".urdf"),
    ("SK207", _tree(TB, link("b"), joint("j", "a", "b", type="continuous", extra='<axis xyz="0 0 1"/><mimic joint="nope"/>')),
     _tree(TB, link("b"), link("c"), joint("j0", "a", "c", type="continuous", extra='<axis xyz="0 0 1"/>'),
           joint("j", "a", "b", type="continuous", extra='<axis xyz="0 0 1"/><mimic joint="j0"/>')), "classic", ".urdf"),
    ("SK301", robot(camera_joint_type="revolute", camera_body=""), robot(camera_joint_type="revolute"), "classic", ".urdf"),
    ("SK301", robot(extra='<link name="w"/>' + joint("wj", "base_link", "w", type="continuous", extra='<axis xyz="0 1 0"/>')),
     robot(extra='<link name="w"/>' + joint("wj", "base_link", "w")), "classic", ".urdf"),
    ("SK302", robot(camera_body='<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3"/></inertial>'),
     robot(camera_body='<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="2"/></inertial>'), "classic", ".urdf"),
    ("SK302", robot(camera_body='<inertial><mass value="1"/><inertia ixx="-1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'),
     robot(camera_body='<inertial><mass value="1"/><inertia ixx="1" ixy="0.1" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'), "classic", ".urdf"),
    ("SK303", robot(camera=camera_sensor(params="")), robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name>")), "classic", ".urdf"),
    ("SK304", _tree(link("a", inertial(1.0, 0.1)), link("b"), joint("j", "a", "b")), _tree('<link name="a"/>', link("b"), joint("j", "a", "b")), "classic", ".urdf"),
    ("SK401", robot(extra='<gazebo reference="no_such_link"><material>Gazebo/Red</material></gazebo>'),
     robot(extra='<gazebo reference="laser_joint"><preserveFixedJoint>false</preserveFixedJoint></gazebo>'), "classic", ".urdf"),
    ("SK402", robot(lidar=lidar_sensor(name="front_camera")), robot(lidar=lidar_sensor(name="laser")), "classic", ".urdf"),
    ("SK403", robot(camera=camera_sensor(camera='<camera><image><width>640</width><height>-480</height></image></camera>')),
     robot(camera=camera_sensor(camera='<camera><image><width>640</width><height>480</height></image></camera>')), "classic", ".urdf"),
    ("SK403", robot(camera=camera_sensor(camera='<camera><image><width>64.5</width><format>RGB888</format></image></camera>')),
     robot(camera=camera_sensor(camera='<camera><image><width>64</width><format>B8G8R8</format></image></camera>')), "classic", ".urdf"),
    ("SK404", robot(camera=camera_sensor(camera="<camera><horizontal_fov>3.3</horizontal_fov></camera>")),
     robot(camera=camera_sensor(camera="<camera><horizontal_fov>2.5</horizontal_fov></camera>")), "classic", ".urdf"),
    ("SK405", robot(camera=camera_sensor(camera="<camera><clip><near>5</near><far>1</far></clip></camera>")),
     robot(camera=camera_sensor(camera="<camera><clip><near>0.05</near><far>100</far></clip></camera>")), "classic", ".urdf"),
    ("SK405", robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.001</near><far>10</far></clip></camera>")),
     robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.01</near><far>10</far></clip></camera>")), "classic", ".urdf"),
    # Depth precision is a depth sensor's concern: the same clip on a colour camera is fine.
    # (Gazebo Sim only: Gazebo Classic publishes linear float32 depth, see test_trust.py
    # test_sk405_far_near_ratio_is_not_reported_on_classic.)
    ("SK405", robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.02</near><far>1000</far></clip></camera>")),
     robot(camera=camera_sensor(camera="<camera><clip><near>0.02</near><far>1000</far></clip></camera>")), "harmonic", ".urdf"),
    ("SK405", robot(camera=camera_sensor(stype="depth", params="<frame_name>camera_optical_frame</frame_name><min_depth>0.01</min_depth>", camera="<camera><clip><near>0.1</near><far>10</far></clip></camera>")),
     robot(camera=camera_sensor(stype="depth", params="<frame_name>camera_optical_frame</frame_name><min_depth>0.1</min_depth>", camera="<camera><clip><near>0.1</near><far>10</far></clip></camera>")), "classic", ".urdf"),
    ("SK406", robot(lidar=lidar_sensor(min_angle="1", max_angle="-1")), robot(lidar=lidar_sensor(min_angle="-1", max_angle="1")), "classic", ".urdf"),
    ("SK406", robot(lidar=lidar_sensor(rmin="0", rmax="12")), robot(lidar=lidar_sensor(rmin="0.05", rmax="12")), "classic", ".urdf"),
    ("SK406", robot(lidar=lidar_sensor(samples="0")), robot(lidar=lidar_sensor(samples="1", min_angle="0", max_angle="0")), "classic", ".urdf"),
    ("SK406", robot(lidar=lidar_sensor(samples="360", resolution="0.33")), robot(lidar=lidar_sensor(samples="360", resolution="0.5")), "classic", ".urdf"),
    ("SK406", robot(lidar=lidar_sensor(vertical="<vertical><samples>16</samples><min_angle>0.3</min_angle><max_angle>-0.3</max_angle></vertical>", params="<output_type>sensor_msgs/PointCloud2</output_type><frame_name>laser_link</frame_name>")),
     robot(lidar=lidar_sensor(vertical="<vertical><samples>16</samples><min_angle>-0.3</min_angle><max_angle>0.3</max_angle></vertical>", params="<output_type>sensor_msgs/PointCloud2</output_type><frame_name>laser_link</frame_name>")), "classic", ".urdf"),
    ("SK407", robot(camera=camera_sensor(extra="")), robot(camera=camera_sensor(extra="<update_rate>15</update_rate>")), "classic", ".urdf"),
    ("SK408", robot(lidar=lidar_sensor(noise="<noise><type>gaussian</type><mean>0</mean><stddev>-0.01</stddev></noise>")),
     robot(lidar=lidar_sensor(noise="<noise><type>gaussian</type><mean>0</mean><stddev>0.01</stddev></noise>")), "classic", ".urdf"),
    ("SK408", robot(lidar=lidar_sensor(noise="<noise><type>gauss</type><stddev>0.01</stddev></noise>")),
     robot(lidar=lidar_sensor(noise="<noise><type>gaussian_quantized</type><stddev>0.01</stddev></noise>")), "classic", ".urdf"),
    ("SK409", robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><focal_length>500</focal_length>")),
     robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><focal_length>381.3612981450099</focal_length>")), "classic", ".urdf"),
    ("SK501", robot(camera=camera_sensor(params="<frame_name>camera_optcal_frame</frame_name>")), CLEAN, "classic", ".urdf"),
    ("SK502", robot(camera=camera_sensor(params="<frame_name>camera_link</frame_name>")), CLEAN, "classic", ".urdf"),
    ("SK502", robot(optical_rpy="0 0 -1.5707963267948966"), robot(optical_rpy="-1.5680 0 -1.5708"), "classic", ".urdf"),
    ("SK503", robot(optical_xyz="0.1 0 0"), robot(optical_xyz="0.0005 0 0"), "classic", ".urdf"),
    ("SK504", robot(lidar=lidar_sensor(params="<output_type>sensor_msgs/LaserScan</output_type><frame_name>camera_optical_frame</frame_name><ros><remapping>~/out:=scan</remapping></ros>"),
                    extra=""),
     CLEAN, "classic", ".urdf"),
    ("SK505", robot(optical_rpy="-1.57 0 -1.57"), robot(optical_rpy="-1.5708 0 -1.5708"), "classic", ".urdf"),
    ("SK506", robot(extra='<link name="camera_depth_frame"/>' + joint("cdj", "camera_link", "camera_depth_frame", rpy=OPTICAL),
                    camera=camera_sensor(params="<frame_name>camera_depth_frame</frame_name>")), CLEAN, "classic", ".urdf"),
    ("SK507", robot(extra='<link name="odom"/>' + joint("oj", "odom", "base_footprint")), robot(extra='<link name="world"/>' + joint("wj", "world", "base_footprint")), "classic", ".urdf"),
    ("SK601", robot(lidar=lidar_sensor(plugin="libgazebo_ros_laser.so", params="<frame_name>laser_link</frame_name>")), CLEAN, "classic", ".urdf"),
    ("SK601", robot(camera=camera_sensor(stype="depth", plugin="libgazebo_ros_openni_kinect.so")), robot(camera=camera_sensor(stype="depth")), "classic", ".urdf"),
    ("SK601", GZ_CLEAN.replace("</robot>", '<gazebo><plugin filename="libgazebo_ros_diff_drive.so" name="dd"/></gazebo></robot>'), GZ_CLEAN, "harmonic", ".urdf"),
    ("SK601", GZ_CLEAN, GZ_CLEAN.replace("gz-sim-sensors-system", "ignition-gazebo-sensors-system"), "fortress", ".urdf"),
    ("SK602", robot(camera=camera_sensor(params="<frameName>camera_optical_frame</frameName>")), CLEAN, "classic", ".urdf"),
    ("SK602", robot(extra='<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so"><ros><remap from="cmd_vel" to="/cmd_vel"/></ros></plugin></gazebo>'),
     robot(extra='<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so"><ros><remapping>cmd_vel:=/cmd_vel</remapping></ros></plugin></gazebo>'), "classic", ".urdf"),
    ("SK603", robot(lidar=lidar_sensor(plugin="libgazebo_ros_camera.so")), CLEAN, "classic", ".urdf"),
    ("SK604", robot(lidar=lidar_sensor().replace('name="laser_controller"', 'name="front_camera_controller"')),
     robot(lidar=lidar_sensor().replace('name="laser_controller"', 'name="front_camera_controller"').replace("<ros>", "<ros><namespace>lidar</namespace>")), "classic", ".urdf"),
    ("SK605", robot(lidar=lidar_sensor(params="<ros><remapping>~/out:=front_camera/image_raw</remapping></ros><output_type>sensor_msgs/LaserScan</output_type><frame_name>laser_link</frame_name>")),
     robot(lidar=lidar_sensor(params="<ros><remapping>~/out:=front_camera/scan</remapping></ros><output_type>sensor_msgs/LaserScan</output_type><frame_name>laser_link</frame_name>")), "classic", ".urdf"),
    ("SK605", gz_robot(lidar_tags="<topic>front_camera/image_raw</topic><gz_frame_id>laser_link</gz_frame_id>"), GZ_CLEAN, "harmonic", ".urdf"),
    ("SK606", robot(lidar=lidar_sensor(params="<ros><remapping>~/out:=scan</remapping></ros><frame_name>laser_link</frame_name>")), CLEAN, "classic", ".urdf"),
    ("SK606", robot(lidar=lidar_sensor(params="<ros><remapping>~/out:=scan</remapping></ros><output_type>sensor_msgs/msg/LaserScan</output_type><frame_name>laser_link</frame_name>")), CLEAN, "classic", ".urdf"),
    ("SK607", robot(lidar=lidar_sensor(plugin="")), CLEAN, "classic", ".urdf"),
    ("SK607", gz_robot(lidar_tags="<gz_frame_id>laser_link</gz_frame_id>"), GZ_CLEAN, "harmonic", ".urdf"),
    ("SK608", gz_robot(lidar_tags="<topic>scan</topic><ignition_frame_id>laser_link</ignition_frame_id><gz_frame_id>laser_link</gz_frame_id>"), GZ_CLEAN, "harmonic", ".urdf"),
    ("SK608", GZ_CLEAN, GZ_CLEAN.replace("gz_frame_id", "frame_id"), "jetty", ".urdf"),
    ("SK613", gz_robot().replace('type="gpu_lidar"', 'type="ray"'), GZ_CLEAN, "harmonic", ".urdf"),
    ("SK610", robot(camera=camera_sensor(plugin="libacme_camera.so", params="<frameId>camera_optical_frame</frameId>")),
     robot(camera=camera_sensor()), "classic", ".urdf"),
    ("SK611", robot(camera=camera_sensor(params="<cameraName>cam</cameraName><frameName>camera_optical_frame</frameName><updateRate>30</updateRate>"),
                    lidar=lidar_sensor(plugin="libgazebo_ros_laser.so", params="<topicName>scan</topicName><frameName>laser_link</frameName>")),
     robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><updateRate>30</updateRate>")), "auto", ".urdf"),
    ("SK609", robot(camera=camera_sensor(params="<ros><remapping>image_raw:=front/image</remapping></ros><frame_name>camera_optical_frame</frame_name>")),
     robot(camera=camera_sensor(params="<ros><remapping>set_camera_info:=front_camera/set_camera_info</remapping><remapping>front_camera/image_raw:=front/image</remapping></ros><frame_name>camera_optical_frame</frame_name>")), "classic", ".urdf"),
    ("SK609", robot(lidar=lidar_sensor(params="<ros><remapping>scan:=/scan</remapping></ros><output_type>sensor_msgs/LaserScan</output_type><frame_name>laser_link</frame_name>")),
     robot(lidar=lidar_sensor(params="<ros><remapping>~/out:=/scan</remapping></ros><output_type>sensor_msgs/LaserScan</output_type><frame_name>laser_link</frame_name>")), "classic", ".urdf"),
]


def test_clean_robots_are_clean(check) -> None:
    for text, target in ((CLEAN, "classic"), (GZ_CLEAN, "harmonic"), (GZ_CLEAN.replace("gz-sim-sensors-system", "ignition-gazebo-sensors-system").replace("gz_frame_id", "ignition_frame_id"), "fortress")):
        report = check(text, target=target)
        assert [f for f in report.findings if f.severity >= Severity.WARNING] == [], report.findings


@pytest.mark.parametrize(("rule", "bad", "good", "target", "suffix"), CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_rule_triggers_and_near_miss_does_not(check, rule: str, bad: str, good: str, target: str, suffix: str) -> None:
    hit = check(bad, target=target, suffix=suffix)
    assert rule in rules_of(hit), [(f.rule, f.message) for f in hit.findings]
    finding = next(f for f in hit.findings if f.rule == rule)
    assert finding.fix, f"{rule} has no fix"
    assert finding.file and finding.line, f"{rule} has no location"
    miss = check(good, target=target, suffix=suffix)
    assert rule not in rules_of(miss), [(f.rule, f.message) for f in miss.findings if f.rule == rule]


def test_every_rule_has_a_case() -> None:
    # The loaders' rules: test_loading.py; SK612 and SK614 need a bridge file: test_trust.py
    # and test_sim_facts.py.
    covered = {c[0] for c in CASES} | {"SK101", "SK102", "SK103", "SK612", "SK614"}
    assert covered == set(RULES)


def test_sk502_says_what_the_data_looks_like(check) -> None:
    f = next(f for f in check(robot(camera=camera_sensor(params="<frame_name>camera_link</frame_name>")), target="classic").findings if f.rule == "SK502")
    assert "points up" in f.message and f.frame == "camera_link"
    assert f.fix == "publish in 'camera_optical_frame', which is already an optical frame at the camera"
    no_optical = robot(camera=camera_sensor(params="<frame_name>camera_link</frame_name>"), optical_rpy="0 0 0")
    f = next(f for f in check(no_optical, target="classic").findings if f.rule == "SK502")
    assert "${-pi/2}" in (f.fix or "") and "camera_link_optical_frame" in (f.fix or "")


def test_sk503_names_the_offset(check) -> None:
    f = next(f for f in check(robot(optical_xyz="0.4 0 0"), target="classic").findings if f.rule == "SK503")
    assert "400.0 mm" in f.message and "x +0.4000" in f.message


def test_sk301_names_what_is_lost(check) -> None:
    f = next(f for f in check(robot(camera_joint_type="revolute", camera_body=""), target="classic").findings if f.rule == "SK301")
    assert "camera_optical_frame" in f.message and "front_camera" in f.message


def test_sk601_names_the_replacement(check) -> None:
    report = check(robot(camera=camera_sensor(stype="depth", plugin="libgazebo_ros_openni_kinect.so")), target="classic")
    f = next(f for f in report.findings if f.rule == "SK601")
    assert "libgazebo_ros_camera.so" in (f.fix or "")


def test_severity_of_sk405_warning_vs_error(check) -> None:
    warn = check(robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.001</near><far>10</far></clip></camera>")), target="classic")
    err = check(robot(camera=camera_sensor(camera="<camera><clip><near>5</near><far>1</far></clip></camera>")), target="classic")
    assert {f.severity for f in warn.findings if f.rule == "SK405"} == {Severity.WARNING}
    assert {f.severity for f in err.findings if f.rule == "SK405"} == {Severity.ERROR}


def test_auto_target(check) -> None:
    assert check(CLEAN).target == "classic"
    assert check(GZ_CLEAN).target == "harmonic"
    fortress = GZ_CLEAN.replace("gz_frame_id", "ignition_frame_id")
    assert check(fortress).target == "fortress"
