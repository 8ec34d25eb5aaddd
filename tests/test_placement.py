"""SK410 (a sensor setting where sdformat's schema does not put it) and SK411 (a camera
plugin's principal point far from the image centre): triggers and near misses.

Sources, read at the lines cited (also in sensorkit/knowledge/sdf_schema.py and
gazebo_ros.py): sdformat copies an element its schema does not define as an unknown child
(gazebosim/sdformat@sdf9 9ee2d4f:src/parser.cc:1129-1140; @sdf14 8512585:src/parser.cc:
2016-2044, never for a name with a ':' prefix); <image> is defined inside <camera>
(@sdf9:sdf/1.7/camera.sdf:16, @sdf14:sdf/1.11/camera.sdf:24) with default width 320, height
240 (@sdf9:sdf/1.7/camera.sdf:18,21); <plugin> and <update_rate> in <sensor> (@sdf9:sdf/1.7/
sensor.sdf:59, :42). ROS 1 GazeboRosCameraUtils keeps a non-zero <Cx>/<Cy> and computes only
0 as (width + 1) / 2 (ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a46:gazebo_plugins/src/
gazebo_ros_camera_utils.cpp:167-181, :506-509); ROS 2 gazebo_ros_camera keeps a written 0
(@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:360-364); Gazebo Classic renders a
symmetric frustum (elysia-best/gazebo-classic@upstream/11.10.2+dfsg:gazebo/rendering/
Camera.cc:2033-2035).
"""

from __future__ import annotations

from collections.abc import Callable

from builders import camera_sensor, gz_robot, lidar_sensor, robot

from sensorkit.base.findings import Severity
from sensorkit.knowledge.sdf_schema import schema
from sensorkit.lint.rules.principal import far_from_centre

IMAGE = "<image><width>640</width><height>480</height></image>"
FOV = "<horizontal_fov>1.3962634</horizontal_fov>"
CLIP = "<clip><near>0.05</near><far>50</far></clip>"


def _of(report, rule: str):  # type: ignore[no-untyped-def]
    return [f for f in report.findings if f.rule == rule]


def test_schema_table() -> None:
    for target in ("classic", "ros1", "fortress", "harmonic", "jetty"):
        cam, top = schema(target, "camera"), schema(target, "sensor")
        assert cam is not None and top is not None
        assert {"image", "horizontal_fov", "clip", "noise", "lens"} <= cam.children
        assert {"plugin", "update_rate", "always_on", "topic", "pose", "camera", "ray"} <= top.children
        assert "image" not in top.children and "plugin" not in cam.children
    classic_cam = schema("classic", "camera")
    assert classic_cam is not None
    assert classic_cam.cite("image").endswith("sdf/1.7/camera.sdf:16")
    harmonic_cam = schema("harmonic", "camera")
    assert harmonic_cam is not None and harmonic_cam.cite("image").endswith("sdf/1.11/camera.sdf:24")
    # optical_frame_id is a camera child from SDF 1.9 (sdformat12) on, not in 1.7
    assert "optical_frame_id" not in classic_cam.children and "optical_frame_id" in harmonic_cam.children


def test_camera_settings_under_sensor_are_an_error(check: Callable) -> None:
    bad = robot(camera=camera_sensor(camera=f"{FOV}{IMAGE}{CLIP}"))
    found = _of(check(bad, target="classic"), "SK410")
    assert {f.severity for f in found} == {Severity.ERROR}
    assert len(found) == 3
    msg = " ".join(f.message for f in found)
    assert "320x240" in msg and "1.047 rad" in msg and "sdf/1.7/camera.sdf:16" in msg
    # on Harmonic, read against SDF 1.11; its <camera> has its own <image>: a warning
    gz = gz_robot(camera_tags=f"<topic>front_camera/image_raw</topic>{IMAGE}")
    found = _of(check(gz, target="harmonic"), "SK410")
    assert [f.severity for f in found] == [Severity.WARNING] and "sdf/1.11/camera.sdf:24" in found[0].message


def test_near_misses(check: Callable) -> None:
    # settings in <camera>, Gazebo's own sensor-level tags, a namespaced custom element,
    # an unknown name defined nowhere near: nothing
    good = robot(
        camera=camera_sensor(
            extra="<update_rate>30</update_rate><always_on>true</always_on><visualize>true</visualize>"
            '<topic>cam</topic><pose>0 0 0 0 0 0</pose><custom:thing xmlns:custom="http://x">1</custom:thing>'
            "<my_own_setting>1</my_own_setting>",
        )
    )
    assert not _of(check(good, target="classic"), "SK410")
    assert not _of(check(robot(), target="ros1"), "SK410")
    assert not _of(check(gz_robot(), target="harmonic"), "SK410")
    assert not _of(check(robot(lidar=lidar_sensor()), target="classic"), "SK410")


def test_a_copy_its_element_also_sets_is_info_when_equal_and_a_warning_when_not(check: Callable) -> None:
    # Issue 35: the copy <camera> reads holds the same values, so nothing changes (info). Two
    # different values: which was meant sensorkit cannot tell, so a warning, not an error.
    cam = f"{IMAGE}<camera>{FOV}{IMAGE}{CLIP}</camera>"
    found = _of(check(robot(camera=camera_sensor(camera=cam)), target="classic"), "SK410")
    assert [f.severity for f in found] == [Severity.INFO]
    other = IMAGE.replace("640", "1280")
    cam = f"{other}<camera>{FOV}{IMAGE}{CLIP}</camera>"
    found = _of(check(robot(camera=camera_sensor(camera=cam)), target="classic"), "SK410")
    assert [f.severity for f in found] == [Severity.WARNING]
    assert "width 1280" in found[0].message and "width 640" in found[0].message


def test_sensor_level_tags_inside_camera_and_ray(check: Callable) -> None:
    # Issue 35: a plugin never loaded publishes nothing (OUTPUT: error); an update rate lost
    # to sdformat's default 0 changes the rate only (RATE: a warning, was an error); an
    # update rate of 0 written there is the default anyway (info).
    cam = f'<camera>{FOV}{IMAGE}{CLIP}<update_rate>30</update_rate><plugin name="p" filename="libgazebo_ros_camera.so"/></camera>'
    found = _of(check(robot(camera=camera_sensor(camera=cam, extra="", plugin="")), target="classic"), "SK410")
    assert sorted(f.severity for f in found) == [Severity.WARNING, Severity.ERROR]
    assert any("written 30; the simulator uses 0" in f.message for f in found)
    cam = f"<camera>{FOV}{IMAGE}{CLIP}<update_rate>0</update_rate></camera>"
    found = _of(check(robot(camera=camera_sensor(camera=cam, extra="")), target="classic"), "SK410")
    assert [f.severity for f in found] == [Severity.INFO]
    # <range> written under <sensor> of a ray sensor
    lid = lidar_sensor().replace("<update_rate>10</update_rate>", "<update_rate>10</update_rate><range><min>0.1</min><max>30</max></range>")
    found = _of(check(robot(lidar=lid), target="classic"), "SK410")
    assert [f.severity for f in found] == [Severity.WARNING]  # the <ray> sets its own <range>


def test_far_from_centre() -> None:
    assert not far_from_centre((640 + 1) / 2, 640) and not far_from_centre(319.5, 640)
    assert far_from_centre(0.0045, 640) and far_from_centre(0, 640)
    assert not far_from_centre(2.5, 4)  # one pixel at least


def _ros1_camera(params: str) -> str:
    return robot(
        camera=camera_sensor(plugin="libgazebo_ros_camera.so", params=f"<frameName>camera_optical_frame</frameName>{params}")
    )


def test_principal_point_ros1(check: Callable) -> None:
    found = _of(check(_ros1_camera("<Cx>0.0045</Cx><Cy>0.0032</Cy>"), target="ros1"), "SK411")
    assert [f.severity for f in found] == [Severity.ERROR, Severity.ERROR]
    assert "pixels, not metres" in found[0].message
    # near misses: 0 means computed in ROS 1; the plugin's own default; the centre as (w-1)/2
    for near in ("<Cx>0</Cx><Cy>0</Cy>", "<Cx>320.5</Cx><Cy>240.5</Cy>", "<Cx>319.5</Cx><Cy>239.5</Cy>", ""):
        assert not _of(check(_ros1_camera(near), target="ros1"), "SK411"), near


def test_principal_point_ros2(check: Callable) -> None:
    cam = robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><cx>0</cx><cy>240.5</cy>"))
    found = _of(check(cam, target="classic"), "SK411")
    assert len(found) == 1 and found[0].severity == Severity.ERROR and "<cx> 0" in found[0].message
    ok = robot(camera=camera_sensor(params="<frame_name>camera_optical_frame</frame_name><cx>320.5</cx><cy>240.5</cy>"))
    assert not _of(check(ok, target="classic"), "SK411")
    # a camera rendered with <lens><intrinsics> is not judged (SK409's ground)
    lens = f"<camera>{FOV}{IMAGE}{CLIP}<lens><intrinsics><fx>381.36</fx><fy>381.36</fy><cx>0</cx><cy>240</cy><s>0</s></intrinsics></lens></camera>"
    with_lens = robot(camera=camera_sensor(camera=lens, params="<frame_name>camera_optical_frame</frame_name><cx>0</cx>"))
    assert not _of(check(with_lens, target="classic"), "SK411")


def test_noise_under_sensor(check: Callable) -> None:
    # <noise> after </ray>: lost; a zero noise is the default none anyway (info), a real one
    # changes the noise only (a warning; issue 35: noise is tuning, not wrong data)
    def lid(noise: str) -> str:
        return robot(lidar=lidar_sensor().replace("</ray>", f"</ray>{noise}"))

    zero = _of(check(lid("<noise><type>gaussian</type><mean>0.0</mean><stddev>0.0</stddev></noise>"), target="classic"), "SK410")
    assert [f.severity for f in zero] == [Severity.INFO]
    real = _of(check(lid('<noise type="gaussian"><mean>0</mean><stddev>0.01</stddev></noise>'), target="classic"), "SK410")
    assert [f.severity for f in real] == [Severity.WARNING]


def test_camera_settings_under_sensor_equal_to_the_default_change_nothing(check: Callable) -> None:
    # Issue 35: a setting sdformat never reads whose value is the default that applies anyway
    # (sdf/1.7/camera.sdf:12 horizontal_fov 1.047, :18/:21 320x240, :24 R8G8B8, :35/:39 clip
    # 0.1/100) is info; one value off the default is the error of a camera that does not
    # see as written.
    def cam(fov: str, image: str, clip: str) -> str:
        return robot(camera=camera_sensor(camera=f"{fov}{image}{clip}"))  # no <camera> at all

    same = cam(
        "<horizontal_fov>1.047</horizontal_fov>",
        "<image><width>320</width><height>240</height><format>R8G8B8</format></image>",
        "<clip><near>0.1</near><far>100</far></clip>",
    )
    found = _of(check(same, target="classic"), "SK410")
    assert [f.severity for f in found] == [Severity.INFO] * 3, [f.message for f in found]
    assert all("nothing changes" in f.message for f in found)
    # a child left out takes its default too
    part = cam("", "<image><width>320</width></image>", "")
    assert [f.severity for f in _of(check(part, target="classic"), "SK410")] == [Severity.INFO]
    off = cam("<horizontal_fov>1.06</horizontal_fov>", "<image><width>321</width></image>",
              "<clip><near>0.1</near><far>100.5</far></clip>")
    found = _of(check(off, target="classic"), "SK410")
    assert [f.severity for f in found] == [Severity.ERROR] * 3
    assert any("written 1.06; the simulator uses its default 1.047 rad" in f.message for f in found)


def test_a_lost_field_of_view_within_a_pixel_of_the_default_changes_nothing(check: Callable) -> None:
    # pi/3 written where 1.047 applies: the image edge moves 0.07 px at 640 wide (SK409's
    # 1 px floor); 1.06 moves it by several pixels.
    def cam(fov: str) -> str:
        return robot(camera=camera_sensor(camera=f"<horizontal_fov>{fov}</horizontal_fov><camera>{IMAGE}{CLIP}</camera>"))

    assert [f.severity for f in _of(check(cam("1.0471975511965976"), target="classic"), "SK410")] == [Severity.INFO]
    assert [f.severity for f in _of(check(cam("1.06"), target="classic"), "SK410")] == [Severity.ERROR]
