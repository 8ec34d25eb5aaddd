"""Every rule: a case that triggers it and a near miss that must not."""

from __future__ import annotations

import pytest
from builders import OPTICAL, camera_sensor, gz_robot, inertial, joint, lidar_sensor, link, robot
from conftest import rules_of

from sensorkit.base.findings import Severity
from sensorkit.lint.rules import RULES

CLEAN = robot()
GZ_CLEAN = gz_robot()
TB = '<link name="a">' + inertial() + "</link>"


def _tree(*parts: str) -> str:
    return '<?xml version="1.0"?><robot name="t">' + "".join(parts) + "</robot>"


_SDF_LEG = (
    '<?xml version="1.0"?><sdf version="1.9"><model name="m"><link name="leg"><inertial><mass>0.3</mass>'
    "<inertia><ixx>{ixx}</ixx><iyy>0.0074</iyy><izz>0.0001</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz>"
    "</inertia></inertial></link></model></sdf>"
)

# (rule, triggering description, near miss, target, file suffix)
CASES: list[tuple[str, str, str, str, str]] = [
    ("SK410",
     robot(camera=camera_sensor(camera="<image><width>640</width><height>480</height></image>")),
     robot(camera=camera_sensor()), "classic", ".urdf"),
    ("SK411",
     robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><cx>0.0045</cx>")),
     robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><cx>320.5</cx>")), "classic", ".urdf"),
    # SK413-SK416: sources and thresholds in test_calibration_rules.py
    ("SK413", robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><hack_baseline>0.07</hack_baseline>")),
     robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><hack_baseline>0</hack_baseline>")), "classic", ".urdf"),
    ("SK414", robot(camera=camera_sensor(params="<frameName>camera_optical_frame</frameName><distortionK1>-0.2</distortionK1>")),
     robot(camera=camera_sensor(params="<frameName>camera_optical_frame</frameName><distortionK1>0</distortionK1>")), "ros1", ".urdf"),
    ("SK415", robot(camera=camera_sensor(camera='<camera><horizontal_fov>1.3962634</horizontal_fov><vertical_fov>0.8</vertical_fov><image><width>640</width><height>480</height></image></camera>')),
     robot(camera=camera_sensor(camera='<camera><horizontal_fov>1.3962634</horizontal_fov><image><width>640</width><height>480</height></image></camera>')), "classic", ".urdf"),
    ("SK417", robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><cx>325</cx>")),
     robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><cx>320.5</cx>")), "classic", ".urdf"),
    ("SK416", gz_robot().replace("<clip>", "<pose>0.1 0 0 0 0 0</pose><clip>"), gz_robot(), "harmonic", ".urdf"),
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
    # Gazebo Classic resolves visibility with Ogre 1.9's 24-bit GL_DEPTH24_STENCIL8 z-buffer
    # (OGRECave/ogre@852f847:RenderSystems/GL/src/OgreGLFBORenderTexture.cpp:112-123,468-471):
    # at the far clip surfaces closer than far^2 (far-near)/(far near 2^24) can z-fight. Reported
    # from 0.1% of the range, i.e. far/near > ~16777: 180/0.01 = 18000 (band 0.19 m at 180 m)
    # triggers, 160/0.01 = 16000 (0.15 m at 160 m, under 0.16) does not.
    ("SK405", robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.01</near><far>180</far></clip></camera>")),
     robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.01</near><far>160</far></clip></camera>")), "classic", ".urdf"),
    # A tiny near alone is no finding: the published depth is gl_Position.w in float32
    # (gazebosim/gazebo-classic@310a1d6:media/materials/programs/depth_map.vert:10), and
    # near 0.001 / far 10 z-fights only within ~6 mm at 10 m (0.06%).
    ("SK405", robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.001</near><far>100</far></clip></camera>")),
     robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.001</near><far>10</far></clip></camera>")), "classic", ".urdf"),
    # Depth-test resolution is a depth sensor's concern: the same clip on a colour camera is fine.
    ("SK405", robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.02</near><far>1000</far></clip></camera>")),
     robot(camera=camera_sensor(camera="<camera><clip><near>0.02</near><far>1000</far></clip></camera>")), "classic", ".urdf"),
    # ROS 1 runs Gazebo Classic: the same depth camera, the same z-buffer.
    ("SK405", robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.02</near><far>1000</far></clip></camera>")),
     robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.02</near><far>300</far></clip></camera>")), "ros1", ".urdf"),
    ("SK405", robot(camera=camera_sensor(stype="depth", params="<frame_name>camera_optical_frame</frame_name><min_depth>0.01</min_depth>", camera="<camera><clip><near>0.1</near><far>10</far></clip></camera>")),
     robot(camera=camera_sensor(stype="depth", params="<frame_name>camera_optical_frame</frame_name><min_depth>0.1</min_depth>", camera="<camera><clip><near>0.1</near><far>10</far></clip></camera>")), "classic", ".urdf"),
    ("SK406", robot(lidar=lidar_sensor(min_angle="1", max_angle="-1")), robot(lidar=lidar_sensor(min_angle="-1", max_angle="1")), "classic", ".urdf"),
    # Range min 0 is the SDF default (gazebosim/sdformat@sdf12 b9417e5:sdf/1.6/ray.sdf:50) and
    # legal on a Classic CPU ray; a negative min is not (tests/test_lidar_range_min.py has the rest).
    ("SK406", robot(lidar=lidar_sensor(rmin="-0.1", rmax="12")), robot(lidar=lidar_sensor(rmin="0", rmax="12")), "classic", ".urdf"),
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
    # SK412: sdformat@sdf9:sdf/1.7/camera.sdf:146-158 defaults, gazebo-classic@11.10.2:gazebo/rendering/Camera.cc:194-210
    # (more, with Gazebo Sim, in tests/test_lens_defaults.py)
    ("SK412", robot(camera=camera_sensor(camera='<camera><horizontal_fov>1.3962634</horizontal_fov><image><width>640</width><height>480</height></image>'
                                             '<lens><intrinsics><fx>381.3613</fx><fy>381.3613</fy></intrinsics></lens></camera>')),
     robot(camera=camera_sensor(camera='<camera><horizontal_fov>1.3962634</horizontal_fov><image><width>640</width><height>480</height></image>'
                                      '<lens><intrinsics><fx>381.3613</fx><fy>381.3613</fy><cx>320</cx><cy>240</cy></intrinsics></lens></camera>')),
     "classic", ".urdf"),
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
    ("SK508", robot(extra='<link name="rear_optical_frame"/>' + joint("rear_optical_joint", "base_link", "rear_optical_frame")), robot(extra='<link name="rear_optical_frame"/>' + joint("rear_optical_joint", "base_link", "rear_optical_frame", rpy=OPTICAL)), "classic", ".urdf"),
    ("SK509", robot(lidar=lidar_sensor(params="<frame_name>laser_link</frame_name>").replace("<update_rate>", "<pose>0 0 250 0 0 0</pose><update_rate>", 1)), robot(lidar=lidar_sensor(params="<frame_name>laser_link</frame_name>").replace("<update_rate>", "<pose>0 0 9 0 0 0</pose><update_rate>", 1)), "classic", ".urdf"),
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
    # The fresh robots' findings (test_fresh_findings.py holds the sources): a massless link
    # fixed to world is not created, so a visual on it is lost (sdformat@sdf9 9ee2d4f3:
    # src/parser_urdf.cc:412, :2679-2683, :2765-2772); holding nothing, it is no finding.
    ("SK301", _tree('<link name="world"/>', TB, joint("jw", "world", "a"), '<link name="ring"><visual><geometry><box size="1 1 1"/></geometry></visual></link>', joint("jr", "world", "ring")),
     _tree('<link name="world"/>', TB, joint("jw", "world", "a"), '<link name="ring"/>', joint("jr", "world", "ring")), "classic", ".urdf"),
    # sdformat reads a double with std::stod (@sdf14 8512585c:src/Param.cc:916-919): the number
    # before trailing words is the one simulated: info.
    ("SK302", _SDF_LEG.format(ixx="0.0074Source Control"), _SDF_LEG.format(ixx="0.0074"), "harmonic", ".sdf"),
    # One vertical sample, published as one row (gz-sensors8 c8159af:src/Lidar.cc:389-397): info.
    ("SK406", GZ_CLEAN.replace("</horizontal></scan>", "</horizontal><vertical><samples>1</samples><resolution>0.01</resolution><min_angle>0</min_angle><max_angle>0</max_angle></vertical></scan>"),
     GZ_CLEAN.replace("</horizontal></scan>", "</horizontal><vertical><samples>1</samples><resolution>1</resolution><min_angle>0</min_angle><max_angle>0</max_angle></vertical></scan>"), "harmonic", ".urdf"),
]


def test_clean_robots_are_clean(check) -> None:
    for text, target in ((CLEAN, "classic"), (GZ_CLEAN, "harmonic"), (GZ_CLEAN.replace("gz-sim-sensors-system", "ignition-gazebo-sensors-system").replace("gz_frame_id", "ignition_frame_id"), "fortress")):
        report = check(text, target=target)
        assert [f for f in report.findings if f.severity >= Severity.WARNING] == [], report.findings


# The severity each trigger of CASES must have, in CASES' order per rule (issue 35: every
# rule's trigger asserts its severity; a rule made an error a warning, or the reverse, fails).
TRIGGER_SEVERITY: dict[str, tuple[Severity, ...]] = {
    "SK410": (Severity.ERROR,),
    "SK411": (Severity.ERROR,),
    # SK413-SK417 (calibration and sensor blocks): each trigger is more than a pixel off
    # (thresholds and sources in test_calibration_rules.py).
    "SK413": (Severity.ERROR,),
    "SK414": (Severity.ERROR,),
    "SK415": (Severity.ERROR,),
    "SK416": (Severity.ERROR,),
    "SK417": (Severity.ERROR,),
    "SK104": (Severity.WARNING,),
    "SK105": (Severity.WARNING, Severity.WARNING, Severity.WARNING,),
    "SK201": (Severity.ERROR,),
    "SK202": (Severity.ERROR,),
    "SK203": (Severity.ERROR,),
    "SK204": (Severity.ERROR, Severity.ERROR, Severity.ERROR,),
    "SK205": (Severity.ERROR, Severity.ERROR, Severity.ERROR,),
    "SK206": (Severity.ERROR, Severity.ERROR, Severity.ERROR,),
    "SK207": (Severity.ERROR,),
    "SK301": (Severity.ERROR, Severity.INFO, Severity.ERROR,),
    "SK302": (Severity.WARNING, Severity.WARNING, Severity.INFO,),
    "SK303": (Severity.ERROR,),
    "SK304": (Severity.INFO,),
    "SK401": (Severity.WARNING,),
    "SK402": (Severity.WARNING,),
    "SK403": (Severity.ERROR, Severity.WARNING,),
    "SK404": (Severity.ERROR,),
    "SK405": (Severity.ERROR, Severity.WARNING, Severity.WARNING, Severity.WARNING, Severity.WARNING, Severity.WARNING,),
    "SK406": (Severity.WARNING, Severity.ERROR, Severity.ERROR, Severity.WARNING, Severity.WARNING, Severity.INFO,),
    "SK407": (Severity.WARNING,),
    "SK408": (Severity.ERROR, Severity.ERROR,),
    "SK409": (Severity.ERROR,),
    "SK412": (Severity.WARNING,),
    "SK501": (Severity.ERROR,),
    "SK502": (Severity.ERROR, Severity.ERROR,),
    "SK503": (Severity.ERROR,),
    "SK504": (Severity.ERROR,),
    "SK505": (Severity.INFO,),
    "SK506": (Severity.INFO,),
    "SK507": (Severity.WARNING,),
    "SK508": (Severity.WARNING,),
    "SK509": (Severity.WARNING,),
    "SK601": (Severity.ERROR, Severity.ERROR, Severity.ERROR, Severity.INFO,),
    "SK602": (Severity.ERROR, Severity.INFO,),
    "SK603": (Severity.ERROR,),
    "SK604": (Severity.ERROR,),
    "SK605": (Severity.ERROR, Severity.ERROR,),
    "SK606": (Severity.WARNING, Severity.ERROR,),
    # SK607 by consequence (issue 35): the camera's gazebo_ros plugin says the robot is meant
    # for ROS, so a lidar with none publishes nothing ROS should get (error); no bridge known
    # and the scoped default topic: cannot tell (info)
    "SK607": (Severity.ERROR, Severity.INFO,),
    "SK608": (Severity.INFO, Severity.WARNING,),  # the ignored tag names the frame read (issue 35); deprecated
    "SK613": (Severity.ERROR,),
    "SK610": (Severity.INFO,),
    "SK611": (Severity.WARNING,),
    "SK609": (Severity.WARNING, Severity.WARNING,),
}


def test_every_trigger_has_its_severity() -> None:
    counts: dict[str, int] = {}
    for rule, *_ in CASES:
        counts[rule] = counts.get(rule, 0) + 1
    assert counts == {r: len(v) for r, v in TRIGGER_SEVERITY.items()}


@pytest.mark.parametrize(("rule", "bad", "good", "target", "suffix"), CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_rule_triggers_and_near_miss_does_not(check, rule: str, bad: str, good: str, target: str, suffix: str) -> None:
    hit = check(bad, target=target, suffix=suffix)
    assert rule in rules_of(hit), [(f.rule, f.message) for f in hit.findings]
    finding = next(f for f in hit.findings if f.rule == rule)
    nth = sum(1 for c in CASES[: CASES.index((rule, bad, good, target, suffix))] if c[0] == rule)
    assert finding.severity is TRIGGER_SEVERITY[rule][nth], (finding.severity, finding.message)
    assert finding.fix, f"{rule} has no fix"
    assert finding.file and finding.line, f"{rule} has no location"
    miss = check(good, target=target, suffix=suffix)
    assert rule not in rules_of(miss), [(f.rule, f.message) for f in miss.findings if f.rule == rule]


def test_sk201_and_sk204_on_names_and_parents_that_repeat(check) -> None:
    """What the per-name maps' fast paths must still find: an empty name, a name used three
    times (reported twice), and a second parent; a self-joint is no parent joint."""
    msgs = [
        (f.rule, f.message)
        for f in check(
            _tree(
                TB, link("b"), link("b"), link("b"), '<link name=""/>',
                joint("j", "a", "b"), joint("j", "a", "c"), link("c"),
                joint("k", "c", "c"), joint("m", "b", "c"),
            )
        ).findings
        if f.rule in ("SK201", "SK204")
    ]
    assert ("SK201", "a <link> has no name") in msgs
    assert msgs.count(("SK201", "link name 'b' is used 3 times")) == 2
    assert ("SK201", "joint name 'j' is used 2 times") in msgs
    assert ("SK204", "joint 'k' joins link 'c' to itself") in msgs
    assert ("SK204", "link 'c' has 2 parent joints: j, m") in msgs
    assert not any("'b' has" in m for _, m in msgs)
    # with the self-joint alone beside one parent, c has one parent joint
    one = check(_tree(TB, link("c"), joint("j", "a", "c"), joint("k", "c", "c")))
    assert [f.message for f in one.findings if f.rule == "SK204"] == [
        "joint 'k' joins link 'c' to itself"
    ]


def test_sk202_names_each_missing_or_unknown_end(check) -> None:
    """Every way a joint's ends can fail, each reported once; a joint whose two links
    exist is not reported (the rule's fast path)."""
    text = _tree(
        TB, link("b"), link("c"),
        joint("ok", "a", "b"),
        '<joint name="noparent" type="fixed"><child link="c"/></joint>',
        '<joint name="nochild" type="fixed"><parent link="a"/></joint>',
        joint("ghostparent", "ghost", "c"),
        joint("ghostchild", "b", "ghost2"),
    )
    msgs = sorted(f.message for f in check(text).findings if f.rule == "SK202")
    assert msgs == sorted([
        "joint 'noparent' has no <parent link=\"...\"/>",
        "joint 'nochild' has no <child link=\"...\"/>",
        "joint 'ghostparent' names parent link 'ghost', which does not exist",
        "joint 'ghostchild' names child link 'ghost2', which does not exist",
    ]), msgs


def test_every_rule_has_a_case() -> None:
    # The loaders' rules: test_loading.py; SK612 and SK614 need a bridge file: test_trust.py
    # and test_sim_facts.py; SK615 needs a bridge too: test_launch_rules.py; SK106 a launch
    # file beside the robot: test_launch_e2e.py; the SDF-only rules: test_sdf_rules.py.
    # SK616: test_model_plugins.py; SK617-SK619 need a bridge or a launch file: test_bridge_flow.py.
    covered = {c[0] for c in CASES} | {"SK101", "SK102", "SK103", "SK106", "SK612", "SK614", "SK615"}
    covered |= {"SK616", "SK617", "SK618", "SK619"}
    covered |= {"SK620"}  # a world's systems: SDF only, test_sdf_sensor_rules.py
    covered |= {"SK107", "SK208", "SK209", "SK510"}
    # check-recording's rules read a bag: test_recording.py holds a trigger and a near miss
    # of each (test_every_recording_rule_has_a_trigger_and_a_near_miss).
    covered |= {rid for rid, info in RULES.items() if "recording" in info.formats}
    assert covered == set(RULES)


def test_every_rule_that_runs_on_sdf_has_an_sdf_trigger_and_near_miss() -> None:
    """A rule runs on SDF only with SDF cases of its own (issue 28): the sensor and plugin
    rules' table in test_sdf_sensor_rules.py, the frame and mass rules' in
    test_sdf_frame_rules.py, the SDF-only rules in test_sdf_rules.py, the loaders' rules in
    test_sdf_input.py (SK101, SK102, SK103, SK104)."""
    from test_sdf_frame_rules import ON_SDF
    from test_sdf_sensor_rules import CASES as SENSOR_CASES

    cased = set(SENSOR_CASES) | set(ON_SDF) | {"SK107", "SK208", "SK209", "SK510"}
    cased |= {"SK619"}  # a launch file's bridge: test_bridge_flow.py's SDF case
    cased |= {"SK101", "SK102", "SK103", "SK104"}
    on_sdf = {rid for rid, info in RULES.items() if "sdf" in info.formats}
    assert on_sdf == cased, (sorted(on_sdf - cased), sorted(cased - on_sdf))


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
    warn = check(robot(camera=camera_sensor(stype="depth", camera="<camera><clip><near>0.001</near><far>100</far></clip></camera>")), target="classic")
    err = check(robot(camera=camera_sensor(camera="<camera><clip><near>5</near><far>1</far></clip></camera>")), target="classic")
    assert {f.severity for f in warn.findings if f.rule == "SK405"} == {Severity.WARNING}
    assert {f.severity for f in err.findings if f.rule == "SK405"} == {Severity.ERROR}


def test_sk405_classic_message_states_the_z_fighting_band(check) -> None:
    # near 0.001, far 100 on Gazebo Classic: 24-bit depth test (OGRECave/ogre@852f847:
    # RenderSystems/GL/src/OgreGLFBORenderTexture.cpp:468-471, GL_DEPTH24_STENCIL8 preferred),
    # band = 100^2 * 99.999 / (100 * 0.001) * 2^-24 = 0.596 m at the far clip; the published
    # depth is linear float32 (gazebosim/gazebo-classic@310a1d6:media/materials/programs/
    # depth_map.vert:10, @f62d0cd:depth_map.frag:12), so the message must not claim the values
    # themselves lose precision.
    clip = "<camera><clip><near>0.001</near><far>100</far></clip></camera>"
    report = check(robot(camera=camera_sensor(stype="depth", camera=clip)), target="classic")
    (f,) = [f for f in report.findings if f.rule == "SK405"]
    assert f.severity is Severity.WARNING
    assert "~0.6 m apart at the far clip (100 m)" in f.message and "z-fight" in f.message
    assert "collapses" not in f.message and "linear float32" in f.message


GZ_DEPTH_SOURCES = """
Gazebo Sim's ogre2 depth camera: PFG_D32_FLOAT depth texture (gazebosim/gz-rendering@ff0c5b8
(gz-rendering8):ogre2/src/Ogre2DepthCamera.cc:655,679; ignition-rendering6_6.6.4@9ee7e96:670,694;
gz-rendering9@f61bf36:655,679), depth recovered as B / (z - A)
(ogre2/src/media/materials/programs/GLSL/depth_camera_fs.glsl:107) with Ogre's
getProjectionParamsAB (Ogre2DepthCamera.cc:470-476), and ogre-next renders reverse-Z by default
(ignition-forks/ogre-next@40dcea7 (v2.2.4):OgreMain/src/OgreRenderSystem.cpp:96;
RenderSystems/GL3Plus/src/OgreGL3PlusRenderSystem.cpp:3262-3270 glClipControl(GL_ZERO_TO_ONE)):
the published depth keeps ~2^-24 of the distance for any near and far/near.
"""


@pytest.mark.parametrize("target", ["fortress", "harmonic", "jetty"])
@pytest.mark.parametrize(("near", "far"), [("0.001", "10"), ("0.02", "1000"), ("0.001", "1000")])
def test_sk405_no_depth_precision_warning_on_gazebo_sim(check, target: str, near: str, far: str) -> None:
    # See GZ_DEPTH_SOURCES: neither a tiny near nor a huge far/near coarsens Gazebo Sim's depth.
    assert GZ_DEPTH_SOURCES
    clip = f"<clip><near>{near}</near><far>{far}</far></clip>"
    desc = gz_robot(camera_type="depth_camera").replace("<clip><near>0.05</near><far>50</far></clip>", clip)
    assert clip in desc
    assert "SK405" not in rules_of(check(desc, target=target))
    # The same clip is still reported on Gazebo Classic when its 24-bit z-buffer band is wide
    # (far/near > ~16777), and a broken clip is still an error on Gazebo Sim.
    classic = robot(camera=camera_sensor(stype="depth", camera=f"<camera>{clip}</camera>"))
    assert ("SK405" in rules_of(check(classic, target="classic"))) == (float(far) / float(near) > 16777)
    broken = desc.replace(clip, "<clip><near>5</near><far>1</far></clip>")
    assert "SK405" in rules_of(check(broken, target=target))


def test_auto_target(check) -> None:
    assert check(CLEAN).target == "classic"
    assert check(GZ_CLEAN).target == "harmonic"
    fortress = GZ_CLEAN.replace("gz_frame_id", "ignition_frame_id")
    assert check(fortress).target == "fortress"
