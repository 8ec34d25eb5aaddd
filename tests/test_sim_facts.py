"""Issue 9: what Gazebo Sim really does, each test citing the source it pins."""

from __future__ import annotations

from builders import gz_robot
from conftest import rules_of


def test_jetty_still_reads_gz_frame_id_deprecated(check) -> None:
    # gazebosim/gz-sensors@gz-sensors10 (ff8c92b):src/Sensor.cc:181-196: <frame_id> first,
    # then gz_frame_id with "//sensor/gz_frame_id is deprecated".
    report = check(gz_robot(), target="jetty")
    cam = report.robot.sensors[0]  # type: ignore[union-attr]
    assert cam.frame_tags["gz_frame_id"] == "camera_optical_frame"
    sk608 = [f for f in report.findings if f.rule == "SK608"]
    assert sk608 and all("deprecated" in f.message and "ignored" not in f.message for f in sk608)
    # Its frame is used: the camera's optical frame is checked, nothing says "ignored".
    assert "SK502" not in rules_of(report)
    both = gz_robot(camera_tags="<topic>cam</topic><frame_id>camera_optical_frame</frame_id><gz_frame_id>camera_link</gz_frame_id>")
    f = next(f for f in check(both, target="jetty").findings if f.rule == "SK608" and f.sensor == "front_camera")
    assert "<frame_id> takes precedence" in f.message


def test_harmonic_has_no_ignition_frame_id_fallback(check) -> None:
    # gazebosim/gz-sensors@gz-sensors8 (c8159af):src/Sensor.cc:184-195 reads gz_frame_id only.
    robot = gz_robot(camera_tags="<topic>cam</topic><ignition_frame_id>camera_optical_frame</ignition_frame_id>")
    f = next(f for f in check(robot, target="harmonic").findings if f.rule == "SK608" and f.sensor == "front_camera")
    assert "ignored by harmonic" in f.message
    # Fortress reads ignition_frame_id first, then gz_frame_id
    # (gazebosim/gz-sensors@ign-sensors6:src/Sensor.cc:146-166): no SK608 there.
    assert not [f for f in check(robot, target="fortress").findings if f.rule == "SK608"]


def test_gz_default_frame_is_the_scoped_sensor_name(check) -> None:
    # No frame tag: the frame is the sensor's name (gz-sensors Sensor.cc above), which
    # gz-sim sets to MODEL::LINK::SENSOR, the link after lumping
    # (gazebosim/gz-sim@gz-sim8:src/rendering/RenderUtil.cc:1719-1721).
    from sensorkit.model.frames import sensor_frames
    from sensorkit.model.sdf import convert

    report = check(gz_robot(camera_tags="<topic>cam</topic>"), target="harmonic")
    robot = report.robot
    assert robot is not None
    cam = next(s for s in robot.sensors if s.name == "front_camera")
    fr = sensor_frames(robot, cam, "harmonic", convert(robot))
    assert fr.is_default and fr.published == "rover::base_footprint::front_camera"  # lumped into the root


def test_sensor_types_gazebo_sim_never_creates(check) -> None:
    # ray/lidar parse as SensorType::LIDAR (gazebosim/sdformat@sdf14:src/Sensor.cc:383-390) and
    # gz-sim creates no CPU lidar (gazebosim/gz-sim@gz-sim8:src/SdfEntityCreator.cc:1092-1098);
    # multicamera has no branch at all (:1227-1229). Seen on husarion's rplidar files.
    ray = gz_robot().replace('type="gpu_lidar"', 'type="ray"')
    f = next(f for f in check(ray, target="harmonic").findings if f.rule == "SK613")
    assert f.sensor == "laser" and "gpu_lidar" in (f.fix or "")
    assert "SK613" not in rules_of(check(gz_robot(), target="harmonic"))
    assert "SK613" not in rules_of(check(ray, target="classic"))  # Classic creates ray sensors
    # Never evidence for Gazebo Sim: a lone type="lidar" no longer makes auto pick gz.
    from builders import lidar_sensor, robot

    lone = robot(lidar=lidar_sensor(stype="lidar", plugin="", tag="lidar"), camera="")
    assert check(lone).target == "classic"


def test_bridge_never_carries_a_sensor_gz_never_creates() -> None:
    from lxml import etree

    from sensorkit.describe.bridge import sensor_entries

    ray = etree.fromstring('<sensor name="l" type="ray"><topic>scan</topic><ray><scan><horizontal><samples>9</samples>'
                           "</horizontal></scan></ray></sensor>")
    assert sensor_entries(ray, "harmonic") == []
    gpu = etree.fromstring(etree.tostring(ray).replace(b'type="ray"', b'type="gpu_lidar"'))
    assert "sensor_msgs/msg/LaserScan" in [e.ros_type_name for e in sensor_entries(gpu, "harmonic")]


def _rgbd(tmp_path, frame: str, bridge_points: bool):  # type: ignore[no-untyped-def]
    from sensorkit.lint.engine import Options, validate_file

    robot = gz_robot(camera_type="rgbd_camera", camera_tags=f"<topic>rgbd</topic><gz_frame_id>{frame}</gz_frame_id>")
    (tmp_path / "r.urdf").write_text(robot)
    entries = ["rgbd/image", "rgbd/depth_image", "rgbd/camera_info", "scan"] + (["rgbd/points"] if bridge_points else [])
    (tmp_path / "bridge.yaml").write_text("".join(f"- topic_name: {t}\n  ros_type_name: x\n  gz_type_name: y\n  direction: GZ_TO_ROS\n" for t in entries))
    return validate_file(tmp_path / "r.urdf", Options(target="harmonic", bridges=(str(tmp_path / "bridge.yaml"),)))


def test_bridged_xforward_cloud_is_sk614(tmp_path) -> None:
    # gz-sensors computes the cloud x-forward and stamps it with the optical frame
    # (https://github.com/gazebosim/gz-sensors/issues/488; @gz-sensors8:src/RgbdCameraSensor.cc:397).
    (tmp_path / "a").mkdir()
    f = next(f for f in _rgbd(tmp_path / "a", "camera_optical_frame", True).findings if f.rule == "SK614")
    assert "depth_image_proc" in (f.fix or "") and "/rgbd/points" in f.message
    # Near misses: the cloud not bridged, or stamped with the x-forward body frame (then it lands right).
    (tmp_path / "b").mkdir()
    assert "SK614" not in rules_of(_rgbd(tmp_path / "b", "camera_optical_frame", False))
    (tmp_path / "c").mkdir()
    assert "SK614" not in rules_of(_rgbd(tmp_path / "c", "camera_link", True))


STEREO = """<?xml version="1.0"?>
<robot name="s" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="{macros}/stereo_camera.urdf.xacro"/>
  <link name="base_link"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <xacro:sensorkit_stereo_camera name="stereo" parent="base_link" baseline="0.12" sim="{sim}" gz_version="{ver}">
    <origin xyz="0.2 0 0.3" rpy="0 0 0"/>
  </xacro:sensorkit_stereo_camera>
</robot>
"""


def _right_eye_p(tmp_path, sim: str, ver: str, target: str) -> tuple[list[list[float]], float]:  # type: ignore[no-untyped-def]
    import json

    from conftest import ROOT, run_cli

    path = tmp_path / f"{sim}_{ver}.urdf.xacro"
    path.write_text(STEREO.format(macros=ROOT / "macros", sim=sim, ver=ver))
    res = run_cli("intrinsics", str(path), "--target", target, "--format", "json")
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)
    cams = doc["cameras"] if isinstance(doc, dict) and "cameras" in doc else doc
    right = next(c for c in cams if "right" in json.dumps(c.get("sensor", c.get("name", ""))))
    return right["P"], right["K"][0][0]


def test_stereo_right_eye_p_on_gazebo_sim_carries_the_baseline(tmp_path) -> None:
    # gz-sensors fills P from <lens><projection>, tx included (gazebosim/gz-sensors@
    # gz-sensors8:src/CameraSensor.cc:741-752; @ign-sensors6:src/CameraSensor.cc:755-758);
    # the stereo macro writes tx = -fx * baseline for the right eye on every gz version.
    for ver in ("fortress", "harmonic", "jetty"):
        P, fx = _right_eye_p(tmp_path, "gz", ver, ver)
        assert P[0][3] == __import__("pytest").approx(-fx * 0.12, rel=1e-9), ver


def test_classic_p_overrides_are_the_published_p(check, tmp_path) -> None:
    # ROS 2 gazebo_ros_camera: P from P_fx, P_fy, P_cx, P_cy, Tx, Ty when given
    # (ros-simulation/gazebo_ros_pkgs@ros2:gazebo_plugins/src/gazebo_ros_camera.cpp:455-462).
    from builders import camera_sensor, robot

    from sensorkit.describe.published import published_intrinsics
    from sensorkit.model import load_robot

    params = ("<frame_name>camera_optical_frame</frame_name><P_fx>500</P_fx><P_fy>501</P_fy>"
              "<P_cx>320</P_cx><P_cy>240</P_cy><Tx>-60</Tx><Ty>1</Ty>")
    path = tmp_path / "r.urdf"
    path.write_text(robot(camera=camera_sensor(params=params)))
    r = load_robot(path).robot
    assert r is not None
    s = next(s for s in r.sensors if s.name == "front_camera")
    intr, _ = published_intrinsics(s, s.cameras[0], "classic")
    assert intr.P.tolist() == [[500.0, 0.0, 320.0, -60.0], [0.0, 501.0, 240.0, 1.0], [0.0, 0.0, 1.0, 0.0]]
    assert intr.K[0][0] != 500.0  # K keeps the focal length computed from the fov
    assert intr.baseline == __import__("pytest").approx(60 / 500)


def test_gz_depth_camera_ignores_camera_info_topic_and_depth_clip(check) -> None:
    # DepthCameraSensor::Load calls Sensor::Load, not CameraSensor::Load, so
    # <camera_info_topic> is never read (gazebosim/gz-sensors@gz-sensors8:
    # src/DepthCameraSensor.cc:245-249; CameraSensor.cc:389-392 is where a camera reads it) and
    # depth renders within <clip> (DepthCameraSensor.cc:349-358); RgbdCameraSensor reads
    # <depth_camera><clip> (RgbdCameraSensor.cc:313-322) and publishes TOPIC/camera_info (:252).
    from lxml import etree

    from sensorkit.describe.bridge import sensor_entries
    from sensorkit.describe.published import depth_range
    from sensorkit.lint.rules.topic_names import gz_topics

    cam = ("<camera><horizontal_fov>1</horizontal_fov><image><width>64</width><height>48</height></image>"
           "<clip><near>0.1</near><far>10</far></clip><camera_info_topic>cam/info</camera_info_topic>"
           "<depth_camera><clip><near>0.3</near><far>4</far></clip></depth_camera></camera>")

    def sensor(stype: str) -> str:
        return f'<sensor name="d" type="{stype}"><topic>d/depth_image</topic>{cam}</sensor>'

    robot = gz_robot(extra=f'<gazebo reference="camera_link">{sensor("depth_camera")}{sensor("rgbd_camera").replace(chr(34) + "d" + chr(34), chr(34) + "r" + chr(34), 1)}</gazebo>')
    report = check(robot, target="harmonic")
    depth = next(s for s in report.robot.sensors if s.name == "d")  # type: ignore[union-attr]
    rgbd = next(s for s in report.robot.sensors if s.name == "r")  # type: ignore[union-attr]
    assert "/d/camera_info" in gz_topics(depth) and "/cam/info" not in gz_topics(depth)
    entries = sensor_entries(etree.fromstring(sensor("depth_camera")), "harmonic")
    assert "cam/info" not in {e.gz_topic_name for e in entries}
    assert depth_range(depth, depth.cameras[0], "harmonic")[:2] == (0.1, 10.0)
    assert depth_range(rgbd, rgbd.cameras[0], "harmonic")[:2] == (0.3, 4.0)
    # A plain camera does read <camera_info_topic>.
    plain = etree.fromstring(sensor("camera"))
    assert "cam/info" in {e.gz_topic_name for e in sensor_entries(plain, "harmonic")}


def test_gz_sensor_without_frame_tag_warns_its_frame_is_not_in_tf(check) -> None:
    # The frame falls back to the sensor's name (gazebosim/gz-sensors@gz-sensors8:
    # src/Sensor.cc:184-195), set by gz-sim to MODEL::LINK::SENSOR (gz-sim@gz-sim8:
    # src/rendering/RenderUtil.cc:1719-1721); robot_state_publisher never publishes it.
    f = next(f for f in check(gz_robot(camera_tags="<topic>cam</topic>"), target="harmonic").findings
             if f.rule == "SK501" and f.sensor == "front_camera")
    assert f.severity.label == "warning" and f.frame == "rover::base_footprint::front_camera"
    # the model part is the name the robot is spawned under (a launch may give another, as
    # osrf/vrx spawns its WAM-V robot as "wamv"): the message says so
    assert "MODEL being the name the robot is spawned under" in f.message
    # ros_gz_bridge hands ROS the frame with "::" turned into "/" (gazebosim/ros_gz@jazzy
    # 739cb42:ros_gz_bridge/src/convert/utils.cpp:47-49, std_msgs.cpp:171-175): the message
    # names what `ros2 topic echo` shows
    assert "hands to ROS as 'rover/base_footprint/front_camera'" in f.message
    assert f.fix == "add <gz_frame_id>camera_optical_frame</gz_frame_id> to the sensor (an optical frame at the camera)"
    assert "SK501" not in rules_of(check(gz_robot(), target="harmonic"))  # near miss: frame tags set



def test_fortress_maps_gz_sim_names_to_ignition_gazebo(check) -> None:
    # ignition-gazebo 6.16+ replaces "gz-sim" with "ignition-gazebo" in a plugin filename
    # (gazebosim/gz-sim@ign-gazebo6 aab5556:src/SystemLoader.cc:73-79): not an error on
    # Fortress, an info for older releases.
    f = next(f for f in check(gz_robot(), target="fortress").findings if f.rule == "SK601")
    assert f.severity.label == "info" and "6.16" in f.message
    ign = gz_robot().replace("gz-sim-sensors-system", "ignition-gazebo-sensors-system")
    assert "SK601" not in rules_of(check(ign, target="fortress"))


def test_sk409_on_gazebo_sim_says_the_image_follows_the_intrinsics(check) -> None:
    # gz-sensors builds the render projection from <lens><intrinsics> (gazebosim/gz-sensors@
    # gz-sensors8 c8159af:src/CameraSensor.cc:858-873, K from them at :729): camera_info
    # matches the image; horizontal_fov is what no longer holds. (Gazebo Classic renders with them but its camera_info does
    # not: the Classic tests below.)
    lens = "<lens><intrinsics><fx>400</fx><fy>400</fy><cx>320</cx><cy>240</cy><s>0</s></intrinsics></lens>"
    robot = gz_robot().replace("<clip><near>0.05</near><far>50</far></clip></camera>", "<clip><near>0.05</near><far>50</far></clip>" + lens + "</camera>", 1)
    f = next(f for f in check(robot, target="harmonic").findings if f.rule == "SK409")
    assert "renders with <lens><intrinsics> fx 400" in f.message and "camera_info will not" not in f.message
    assert "SK409" not in rules_of(check(robot.replace("<fx>400</fx>", "<fx>381.36</fx>"), target="harmonic"))


# --- SK409 on Gazebo Classic: the image follows <lens><intrinsics>, camera_info does not ----
# gazebo 11.10.2 (Debian's import, elysia-best/gazebo-classic@upstream/11.10.2+dfsg):
# gazebo/rendering/Camera.cc:190 Load calls LoadCameraIntrinsics, :194-209 reads
# <lens><intrinsics> fx fy cx cy s, :228-240 renders with setCustomProjectionMatrix (kept by
# CreateCamera :1534-1537 and UpdateFOV :2027-2030), :852-855 HFOV() stays <horizontal_fov>.
# camera_info: ros-simulation/gazebo_ros_pkgs@ros2 (d52f7c4):gazebo_plugins/src/
# gazebo_ros_camera.cpp:366-374 fx = <focal_length> or width / (2 tan(HFOV/2)), K :427-431;
# ROS 1 @noetic-devel (f9e1a46):gazebo_plugins/src/gazebo_ros_camera_utils.cpp:184-189
# (<focalLength>, 0 = computed), :512-519, K :586-590. Neither reads the intrinsics.

_LENS = "<lens><intrinsics><fx>{fx}</fx><fy>{fx}</fy><cx>320</cx><cy>240</cy><s>0</s></intrinsics></lens>"


def _classic_lens(fx: str | None, params: str = "<frame_name>camera_optical_frame</frame_name>",
                  *, stype: str = "camera", plugin: str = "libgazebo_ros_camera.so") -> str:
    from builders import camera_sensor, robot

    lens = "" if fx is None else _LENS.format(fx=fx)
    cam = ("<camera><horizontal_fov>1.3962634</horizontal_fov><image><width>640</width>"
           "<height>480</height><format>R8G8B8</format></image>"
           f"<clip><near>0.05</near><far>50</far></clip>{lens}</camera>")
    return robot(camera=camera_sensor(camera=cam, params=params, stype=stype, plugin=plugin))


def test_sk409_on_classic_says_the_image_follows_the_intrinsics_not_camera_info(check) -> None:
    # width 640, horizontal_fov 1.3962634 -> camera_info fx 381.3612; the image renders fx 400
    f = next(f for f in check(_classic_lens("400"), target="classic").findings if f.rule == "SK409")
    # camera_info puts the image edge 320 * 18.64 / 400 = 14.9 px off: a wrong calibration
    # (issue 23; the 1 px floor is tests/test_severity_audit.py's)
    assert f.severity.label == "error"
    assert "renders the image with <lens><intrinsics> fx 400" in f.message
    assert "camera_info fx 381.3612" in f.message and "from width 640 and horizontal_fov 1.39626" in f.message
    assert f.fix is not None and "horizontal_fov to 1.349482" in f.fix
    # near misses: intrinsics that agree with horizontal_fov; no intrinsics at all
    assert "SK409" not in rules_of(check(_classic_lens("381.3613"), target="classic"))
    assert "SK409" not in rules_of(check(_classic_lens(None), target="classic"))


def test_sk409_on_classic_compares_the_intrinsics_with_focal_length(check) -> None:
    # <focal_length> is what camera_info carries: equal to fx, image and camera_info agree
    # (horizontal_fov is overridden, as sdformat says: gazebosim/sdformat@sdf9:
    # sdf/1.7/camera.sdf:146-147 "overrides horizontal_fov"), so no finding...
    agree = "<frame_name>camera_optical_frame</frame_name><focal_length>400</focal_length>"
    assert "SK409" not in rules_of(check(_classic_lens("400", agree), target="classic"))
    # ... and fx agreeing with horizontal_fov is no help when <focal_length> says otherwise
    other = "<frame_name>camera_optical_frame</frame_name><focal_length>500</focal_length>"
    f = next(f for f in check(_classic_lens("381.3613", other), target="classic").findings if f.rule == "SK409")
    assert "camera_info fx 500.0000 (from <focal_length>" in f.message
    assert f.fix is not None and "remove <focal_length>" in f.fix


def test_sk409_on_ros1_reads_focal_length_as_ros1_spells_it(check) -> None:
    ros1 = "<frameName>camera_optical_frame</frameName><cameraName>front</cameraName>"
    f = next(f for f in check(_classic_lens("400", ros1), target="ros1").findings if f.rule == "SK409")
    assert "camera_info fx 381.3612" in f.message
    # <focalLength> 0 means "computed" (gazebo_ros_camera_utils.cpp:517-519): still 381.36
    zero = ros1 + "<focalLength>0</focalLength>"
    assert "SK409" in rules_of(check(_classic_lens("400", zero), target="ros1"))
    agree = ros1 + "<focalLength>400</focalLength>"
    assert "SK409" not in rules_of(check(_classic_lens("400", agree), target="ros1"))


def test_sk409_on_classic_needs_a_camera_info_and_a_pinhole_image(check) -> None:
    # no ROS plugin: no camera_info to disagree with the image
    assert "SK409" not in rules_of(check(_classic_lens("400", "", plugin=""), target="classic"))
    # WideAngleCamera stitches six cameras; intrinsics "cannot be used with" it
    # (gazebosim/sdformat@sdf9:sdf/1.7/camera.sdf:145)
    assert "SK409" not in rules_of(check(_classic_lens("400", stype="wideanglecamera"), target="classic"))


def test_classic_camera_info_note_says_the_image_uses_the_intrinsics(tmp_path) -> None:
    from sensorkit.describe.published import published_intrinsics
    from sensorkit.model import load_robot

    path = tmp_path / "r.urdf"
    path.write_text(_classic_lens("400"))
    r = load_robot(path).robot
    assert r is not None
    s = next(s for s in r.sensors if s.name == "front_camera")
    intr, notes = published_intrinsics(s, s.cameras[0], "classic")
    assert intr.K[0][0] == __import__("pytest").approx(640 / (2 * __import__("math").tan(1.3962634 / 2)))  # from the fov
    assert any("renders the image with them" in n and "never reads them" in n for n in notes)


def test_sk502_on_gazebo_sim_says_what_breaks_there(check) -> None:
    # On Gazebo Sim the native cloud is x-forward (https://github.com/gazebosim/gz-sensors/issues/488),
    # so a body frame breaks the image consumers, not Gazebo's own points.
    body = gz_robot(camera_type="rgbd_camera", camera_tags="<topic>rgbd</topic><gz_frame_id>camera_link</gz_frame_id>")
    f = next(f for f in check(body, target="harmonic").findings if f.rule == "SK502")
    assert "depth_image_proc" in f.message and "camera_info" in f.message
    classic = next(f for f in check(__import__("builders").robot(camera=__import__("builders").camera_sensor(params="<frame_name>camera_link</frame_name>")), target="classic").findings if f.rule == "SK502")
    assert "depth_image_proc" not in classic.message and "points up at the sky" in classic.message


# --- NavSat on Gazebo Sim ------------------------------------------------------------------

def _navsat(tags: str = "", stype: str = "navsat", extra: str = "") -> str:
    from builders import joint, link

    sensor = f'<gazebo reference="gps_link"><sensor name="gps" type="{stype}"><update_rate>1</update_rate>{tags}</sensor></gazebo>'
    return gz_robot(extra=link("gps_link") + joint("gps_joint", "base_link", "gps_link", "0 0 0.3") + sensor + extra)


POSE_PUBLISHER = ('<gazebo><plugin filename="gz-sim-pose-publisher-system" name="gz::sim::systems::PosePublisher">'
                  "<publish_sensor_pose>true</publish_sensor_pose><use_pose_vector_msg>true</use_pose_vector_msg></plugin></gazebo>")


def test_gz_navsat_without_frame_tag_warns_its_frame_is_not_in_tf(check) -> None:
    # gz-sim's NavSat system names the sensor MODEL::LINK::SENSOR, as the Imu system does
    # (gazebosim/gz-sim@gz-sim8 b81e26d:src/systems/navsat/NavSat.cc:177-180); NavSatSensor
    # puts FrameId(), that name without a frame tag (gz-sensors@gz-sensors8:src/Sensor.cc:
    # 184-195), in the message's own frame_id (gazebosim/gz-sensors@gz-sensors8 c8159af:
    # src/NavSatSensor.cc:174), which ros_gz_bridge makes NavSatFix.header.frame_id, "::" -> "/"
    # (gazebosim/ros_gz@jazzy 739cb42:ros_gz_bridge/src/convert/sensor_msgs.cpp:516,
    # src/convert/utils.cpp:47-49): MODEL/LINK/SENSOR, which robot_state_publisher never has.
    f = next(f for f in check(_navsat(), target="harmonic").findings if f.rule == "SK501")
    assert f.severity.label == "warning" and f.sensor == "gps"
    assert f.frame == "rover::base_footprint::gps"  # the fixed joints lump gps_link into the root
    assert f.fix == "add <gz_frame_id>gps_link</gz_frame_id> to the sensor"
    # sdformat reads type "gps" as SensorType::NAVSAT too (gazebosim/sdformat@sdf14 8512585:
    # src/Sensor.cc:344-351), and gz-sim gives it the same NavSat component
    # (gz-sim@gz-sim8:src/SdfEntityCreator.cc:1163-1167).
    assert "SK501" in rules_of(check(_navsat(stype="gps"), target="harmonic"))
    # Fortress and Jetty: the same system and sensor code (gz-sim@ign-gazebo6 aab5556 and
    # @gz-sim10 ccd6694:src/systems/navsat/NavSat.cc:177-180; gz-sensors@ign-sensors6 7cfaddf:
    # src/NavSatSensor.cc:161, @gz-sensors10 ff8c92b:174).
    assert "SK501" in rules_of(check(_navsat(), target="fortress"))
    assert "SK501" in rules_of(check(_navsat(), target="jetty"))


def test_gz_navsat_near_misses_say_nothing(check) -> None:
    # The frame tag each version reads (sensorkit.model.frames.GZ_FRAME_TAGS) names a link.
    assert "SK501" not in rules_of(check(_navsat("<gz_frame_id>gps_link</gz_frame_id>"), target="harmonic"))
    assert "SK501" not in rules_of(check(_navsat("<ignition_frame_id>gps_link</ignition_frame_id>"), target="fortress"))
    assert "SK501" not in rules_of(check(_navsat("<frame_id>gps_link</frame_id>"), target="jetty"))
    # Harmonic ignores ignition_frame_id (gz-sensors@gz-sensors8:src/Sensor.cc:184-195): the
    # frame is the scoped name again, and SK608 says the tag is ignored.
    ignored = rules_of(check(_navsat("<ignition_frame_id>gps_link</ignition_frame_id>"), target="harmonic"))
    assert {"SK501", "SK608"} <= ignored
    # Gazebo Classic: the frame is the gazebo_ros plugin's business, not this warning's.
    classic = check(_navsat('<plugin name="gps_plugin" filename="libgazebo_ros_gps_sensor.so"/>', stype="gps"), target="classic")
    assert "SK501" not in rules_of(classic)
    # A type sensorkit knows nothing of on Gazebo Sim: no claim about its frame.
    assert "SK501" not in rules_of(check(_navsat(stype="air_pressure"), target="harmonic"))


def test_gz_sensor_pose_published_to_tf_is_not_reported(check) -> None:
    # PosePublisher with <publish_sensor_pose> publishes MODEL::LINK -> MODEL::LINK::SENSOR
    # (gazebosim/gz-sim@gz-sim8 b81e26d:src/systems/pose_publisher/PosePublisher.cc:436-448,
    # the world scope removed by removeParentScope, src/Util.cc:403-411), and ros_gz_bridge
    # turns "::" into "/" in TF frames (ros_gz@jazzy 739cb42:ros_gz_bridge/src/convert/
    # tf2_msgs.cpp:42-52, geometry_msgs.cpp:245-257, std_msgs.cpp:171-175) as in the data's:
    # osrf/vrx bridges it to /tf with robot_state_publisher's frame_prefix "wamv/" (osrf/vrx@
    # 93ae8d0: vrx_gz/src/vrx_gz/bridges.py:40-46, vrx_ros/src/pose_tf_broadcaster.cc:43,70,
    # vrx_gz/src/vrx_gz/launch.py:377), so its sensors' frames are in TF. Whether a launch
    # does that sensorkit cannot see: no SK501 for any kind, the navsat or the camera.
    report = check(_navsat(extra=POSE_PUBLISHER), target="harmonic")
    assert not [f for f in report.findings if f.rule == "SK501" and f.sensor == "gps"]
    cam = gz_robot(camera_tags="<topic>cam</topic>", extra=POSE_PUBLISHER)
    assert not [f for f in check(cam, target="harmonic").findings if f.rule == "SK501"]
    # Near misses: <publish_sensor_pose> false (its default, PosePublisher.cc:113) or absent,
    # and a camera whose frame tag names no link (that error stands: the tag is read).
    off = POSE_PUBLISHER.replace("<publish_sensor_pose>true", "<publish_sensor_pose>false")
    assert [f for f in check(_navsat(extra=off), target="harmonic").findings if f.rule == "SK501" and f.sensor == "gps"]
    cam_off = gz_robot(camera_tags="<topic>cam</topic>", extra=off)
    assert [f for f in check(cam_off, target="harmonic").findings if f.rule == "SK501" and f.sensor == "front_camera"]
    absent = POSE_PUBLISHER.replace("<publish_sensor_pose>true</publish_sensor_pose>", "")
    assert [f for f in check(_navsat(extra=absent), target="harmonic").findings if f.rule == "SK501" and f.sensor == "gps"]
    wrong = gz_robot(camera_tags="<topic>cam</topic><gz_frame_id>no_such_link</gz_frame_id>", extra=POSE_PUBLISHER)
    missing = [f for f in check(wrong, target="harmonic").findings if f.rule == "SK501"]
    assert [(f.sensor, f.severity.label) for f in missing] == [("front_camera", "error")]


def test_gz_navsat_publishes_on_its_scoped_topic(check, tmp_path) -> None:
    # No <topic>: gz-sim's NavSat system publishes on scopedName + "/navsat"
    # (gazebosim/gz-sim@gz-sim8 b81e26d:src/systems/navsat/NavSat.cc:182-186).
    f = next(f for f in check(_navsat(), target="harmonic").findings if f.rule == "SK607")
    assert f.severity.label == "info" and f.sensor == "gps"
    assert "/world/WORLD/model/MODEL/link/base_footprint/sensor/gps/navsat" in f.message
    # With a bridge known, a <topic> no entry names is a warning; an entry naming it, nothing.
    from sensorkit.lint.engine import Options, validate_file

    path = tmp_path / "rover.urdf"
    path.write_text(_navsat("<topic>gps/fix</topic><gz_frame_id>gps_link</gz_frame_id>"))
    entry = ("- ros_topic_name: gps/fix\n  gz_topic_name: gps/fix\n  ros_type_name: sensor_msgs/msg/NavSatFix\n"
             "  gz_type_name: gz.msgs.NavSat\n  direction: GZ_TO_ROS\n")
    others = ("- ros_topic_name: front_camera/image_raw\n  gz_topic_name: front_camera/image_raw\n"
              "  ros_type_name: sensor_msgs/msg/Image\n  gz_type_name: gz.msgs.Image\n  direction: GZ_TO_ROS\n"
              "- ros_topic_name: scan\n  gz_topic_name: scan\n  ros_type_name: sensor_msgs/msg/LaserScan\n"
              "  gz_type_name: gz.msgs.LaserScan\n  direction: GZ_TO_ROS\n")

    def sk607(text: str) -> list:  # type: ignore[type-arg]
        bridge = tmp_path / "bridge.yaml"
        bridge.write_text(text)
        report = validate_file(path, Options(target="harmonic", bridges=(str(bridge),)))
        return [f for f in report.findings if f.rule == "SK607"]

    lacking = sk607(others)
    assert [(f.sensor, f.severity.label) for f in lacking] == [("gps", "error")]  # ROS gets no fix (issue 35)
    assert "/gps/fix" in lacking[0].message
    assert sk607(others + entry) == []


def test_sensor_types_never_created_are_per_version(check) -> None:
    # Fortress: gazebosim/gz-sim@ign-gazebo6:src/SdfEntityCreator.cc:902-1031 has no
    # WIDE_ANGLE_CAMERA branch, so "wideanglecamera" (SensorType::WIDE_ANGLE_CAMERA,
    # gazebosim/sdformat@sdf12:src/Sensor.cc:311-313) falls into the final else: "Sensor type [N]
    # not supported yet." (:1028-1031).
    wide = gz_robot(camera_type="wideanglecamera")
    f = next(f for f in check(wide, target="fortress").findings if f.rule == "SK613")
    assert f.sensor == "front_camera" and "Fortress" in f.message and 'type="camera"' in (f.fix or "")
    # Near miss: Harmonic and Jetty create it (gz-sim@gz-sim8:src/SdfEntityCreator.cc:1125-1128
    # `components::WideAngleCamera`; @gz-sim10:1159-1162), and a plain camera everywhere (:902).
    assert "SK613" not in rules_of(check(wide, target="harmonic"))
    assert "SK613" not in rules_of(check(wide, target="jetty"))
    assert "SK613" not in rules_of(check(gz_robot(), target="fortress"))
    # No version creates a sonar: SensorType::SONAR (sdformat@sdf14:src/Sensor.cc:399-401) has no
    # branch in gz-sim@gz-sim8:src/SdfEntityCreator.cc (else :1226-1229; gz-sim10 :1260-1263).
    sonar = gz_robot().replace('type="gpu_lidar"', 'type="sonar"')
    for target, version in (("harmonic", "Harmonic"), ("jetty", "Jetty"), ("fortress", "Fortress")):
        f = next(f for f in check(sonar, target=target).findings if f.rule == "SK613")
        assert f.sensor == "laser" and version in f.message and "gpu_lidar" in (f.fix or "")
    assert "SK613" not in rules_of(check(sonar, target="classic"))
    # air_speed: sdformat12 does not know it ("the provided sensor type is missing or invalid",
    # sdf12:src/Sensor.cc:393-397); Harmonic creates it (gz-sim8:src/SdfEntityCreator.cc:1139).
    air = gz_robot().replace('type="gpu_lidar"', 'type="air_speed"')
    assert "SK613" in rules_of(check(air, target="fortress"))
    assert "SK613" not in rules_of(check(air, target="harmonic"))


def test_never_created_table_cites_each_version() -> None:
    from sensorkit.knowledge.gazebo_sim import GZ_NEVER_CREATED

    assert set(GZ_NEVER_CREATED) == {"fortress", "harmonic", "jetty"}
    assert "wideanglecamera" in GZ_NEVER_CREATED["fortress"]
    assert "wideanglecamera" not in GZ_NEVER_CREATED["harmonic"]
    assert "air_speed" not in GZ_NEVER_CREATED["jetty"]
    refs = {"fortress": "@ign-gazebo6:", "harmonic": "@gz-sim8:", "jetty": "@gz-sim10:"}
    for target, rows in GZ_NEVER_CREATED.items():
        for kind in ("ray", "lidar", "multicamera", "sonar", "rfid", "rfidtag", "wireless_receiver"):
            assert refs[target] in rows[kind].source, (target, kind)


def _wide_sensor(stype: str) -> str:
    return (f'<sensor name="wide" type="{stype}"><update_rate>30</update_rate><topic>wide/image</topic>'
            "<gz_frame_id>camera_optical_frame</gz_frame_id><camera><horizontal_fov>3.5</horizontal_fov>"
            "<image><width>64</width><height>48</height></image><clip><near>0.1</near><far>10</far></clip>"
            "<camera_info_topic>wide/info</camera_info_topic></camera></sensor>")


def test_gz_wideanglecamera_ignores_camera_info_topic(check, tmp_path) -> None:
    # Only CameraSensor::Load reads <camera_info_topic> (gazebosim/gz-sensors@gz-sensors8 c8159af:
    # src/CameraSensor.cc:389-392; @gz-sensors10 ff8c92b: :324-327). WideAngleCameraSensor::Load
    # calls Sensor::Load (src/WideAngleCameraSensor.cc:152 on both) and AdvertiseInfo() (:199),
    # whose default is the sibling camera_info of <topic> (gz-sensors8 CameraSensor.cc:662-676).
    # It publishes its image on <topic> (gz-sensors8 WideAngleCameraSensor.cc:174-176).
    from lxml import etree

    from sensorkit.describe.bridge import sensor_entries
    from sensorkit.describe.sensor_topics import sensor_topics
    from sensorkit.lint.engine import Options, validate_file
    from sensorkit.lint.rules.topic_names import gz_topics

    for stype in ("wideanglecamera", "wide_angle_camera"):  # sdformat@sdf14 8512585:src/Sensor.cc:329
        el = etree.fromstring(_wide_sensor(stype))
        for release in ("harmonic", "jetty"):
            assert [e.gz_topic_name for e in sensor_entries(el, release)] == ["wide/image", "wide/camera_info"]
        # Fortress has no WideAngleCameraSensor (added in gz-sensors7 by 6c18e47, #171; gz-sim
        # creates it from gz-sim8 b81e26d:src/SdfEntityCreator.cc:1125-1128): nothing to bridge
        assert sensor_entries(el, "fortress") == []
    robot = gz_robot(extra=f'<gazebo reference="camera_link">{_wide_sensor("wideanglecamera")}</gazebo>')
    wide = next(s for s in check(robot, target="harmonic").robot.sensors if s.name == "wide")  # type: ignore[union-attr]
    assert "/wide/camera_info" in gz_topics(wide) and "/wide/info" not in gz_topics(wide)
    assert sensor_topics(wide, "harmonic")[0]["camera_info"] == "/wide/camera_info"
    # SK607 knows the topics it publishes: a bridge carrying only its camera_info is seen as
    # the camera's (the warning names the image it lacks), not as no entry at all
    path = tmp_path / "wide.urdf"
    path.write_text(robot)
    yaml = tmp_path / "bridge.yaml"
    yaml.write_text("- ros_topic_name: wide/camera_info\n  gz_topic_name: wide/camera_info\n"
                    "  ros_type_name: sensor_msgs/msg/CameraInfo\n  gz_type_name: gz.msgs.CameraInfo\n"
                    "  direction: GZ_TO_ROS\n")
    report = validate_file(path, Options(target="harmonic", bridges=(str(yaml),)))
    sk607 = [f for f in report.findings if f.rule == "SK607" and f.sensor == "wide"]
    assert len(sk607) == 1 and "bridges its camera_info (/wide/camera_info) but not its image" in sk607[0].message
    yaml.write_text(yaml.read_text().replace("wide/camera_info", "wide/info"))
    report = validate_file(path, Options(target="harmonic", bridges=(str(yaml),)))
    sk607 = [f for f in report.findings if f.rule == "SK607" and f.sensor == "wide"]
    assert len(sk607) == 1 and "names any of its topics" in sk607[0].message


def test_gz_plain_camera_keeps_its_camera_info_topic(check) -> None:
    # Near miss: CameraSensor::Load reads <camera_info_topic> (gazebosim/gz-sensors@gz-sensors8
    # c8159af:src/CameraSensor.cc:389-392; @ign-sensors6 7cfaddf: :379-382).
    from lxml import etree

    from sensorkit.describe.bridge import sensor_entries
    from sensorkit.describe.sensor_topics import sensor_topics
    from sensorkit.lint.rules.topic_names import gz_topics

    el = etree.fromstring(_wide_sensor("camera"))
    for release in ("fortress", "harmonic", "jetty"):
        assert [e.gz_topic_name for e in sensor_entries(el, release)] == ["wide/image", "wide/info"]
    robot = gz_robot(extra=f'<gazebo reference="camera_link">{_wide_sensor("camera")}</gazebo>')
    cam = next(s for s in check(robot, target="harmonic").robot.sensors if s.name == "wide")  # type: ignore[union-attr]
    assert "/wide/info" in gz_topics(cam) and "/wide/camera_info" not in gz_topics(cam)
    assert sensor_topics(cam, "harmonic")[0]["camera_info"] == "/wide/info"


def _gz_lens(lens: str) -> str:
    return gz_robot().replace("<clip><near>0.05</near><far>50</far></clip></camera>", "<clip><near>0.05</near><far>50</far></clip><lens>" + lens + "</lens></camera>", 1)


def test_sk409_on_gazebo_sim_the_projection_wins_and_k_must_follow(check) -> None:
    # gz-sensors builds the render projection from <intrinsics> and then again from
    # <projection> p_fx, p_fy, p_cx, p_cy, so the projection wins (gazebosim/gz-sensors@
    # gz-sensors8 c8159af:src/CameraSensor.cc:858-873 then :898-914; @gz-sensors10 ff8c92b
    # :802-837; @ign-sensors6 7cfaddf :290-325). camera_info K is <intrinsics> (else taken
    # from horizontal_fov, :844-857), P is <projection> (:729-739, :744-757).
    intr = "<intrinsics><fx>400</fx><fy>400</fy><cx>320</cx><cy>240</cy><s>0</s></intrinsics>"
    proj = "<projection><p_fx>{}</p_fx><p_fy>400</p_fy><p_cx>320</p_cx><p_cy>240</p_cy><tx>0</tx><ty>0</ty></projection>"
    for target in ("fortress", "harmonic", "jetty"):
        f = next(f for f in check(_gz_lens(intr + proj.format(450)), target=target).findings if f.rule == "SK409")
        assert "renders the image with <lens><projection> (p_fx 450" in f.message
        assert "camera_info K carries fx 400.0000 (from <lens><intrinsics>)" in f.message
    # no <intrinsics>: K comes from horizontal_fov 1.3962634 at width 640 (fx 381.36)
    f = next(f for f in check(_gz_lens(proj.format(450)), target="harmonic").findings if f.rule == "SK409")
    assert "p_fx 450" in f.message and "fx 381.3612 (from width 640 and horizontal_fov 1.39626)" in f.message
    # near miss: projection and K agree (and with horizontal_fov): nothing to say
    ok = intr.replace("400</fx>", "381.3613</fx>").replace("400</fy>", "381.3613</fy>")
    agree = proj.replace("400</p_fy>", "381.3613</p_fy>").format(381.3613)
    assert "SK409" not in rules_of(check(_gz_lens(ok + agree), target="harmonic"))
    assert "SK409" not in rules_of(check(_gz_lens(agree.replace("<p_fy>381.3613</p_fy>", "")), target="harmonic"))
    # near miss: intrinsics off horizontal_fov, but the projection renders what horizontal_fov
    # says: the old intrinsics-vs-fov warning would be wrong; K-vs-projection is what is off
    f = next(f for f in check(_gz_lens(intr + agree), target="harmonic").findings if f.rule == "SK409")
    assert "K does not match the image" in f.message and "spans" not in f.message


def test_sk409_on_gazebo_sim_projection_off_horizontal_fov_names_p_fx(check) -> None:
    # K and projection agree but both are off horizontal_fov: the image spans what p_fx
    # gives (gz-sensors@gz-sensors8 c8159af:src/CameraSensor.cc:898-914)
    intr = "<intrinsics><fx>400</fx><fy>400</fy><cx>320</cx><cy>240</cy><s>0</s></intrinsics>"
    proj = "<projection><p_fx>400</p_fx><p_fy>400</p_fy><p_cx>320</p_cx><p_cy>240</p_cy></projection>"
    f = next(f for f in check(_gz_lens(intr + proj), target="harmonic").findings if f.rule == "SK409")
    assert "lens p_fx 400" in f.message and "renders with <lens><projection> p_fx 400" in f.message
    assert f.fix is not None and f.fix.startswith("set p_fx to 381.36")
