"""SK413-SK416 (issue 35 items 2 and 3): calibration against the image, and every child of a
sensor block accounted for. Each rule: a trigger, a near miss, its severity, and its pixel
threshold just over and just under.

Sources (read in the fetched repositories; the same lines are cited in
sensorkit/knowledge/sensor_blocks.py):
- P[0][3] = -f * hackBaseline: ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a46:
  gazebo_plugins/src/gazebo_ros_camera_utils.cpp:191-197, :610; ROS 2 hack_baseline and Tx:
  @ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:399, :458.
- ROS 1 D from <distortionK1..T2> unless <autoDistortion>: gazebo_ros_camera_utils.cpp
  :199-246, :559-584; Classic renders <distortion>: elysia-best/gazebo-classic@upstream/
  11.10.2+dfsg:gazebo/rendering/Camera.cc:184-187, :1630-1633.
- gz depth/RGBD cameras publish D, render none: gazebosim/gz-sensors@gz-sensors8 c8159af:
  src/DepthCameraSensor.cc:416-418, :433; src/CameraSensor.cc:716-725.
- vfov = 2 atan(tan(hfov/2) / aspect): gazebo-classic 11.10.2 gazebo/rendering/Camera.cc:2026;
  gazebosim/gz-rendering@gz-rendering8 ff0c5b8:ogre2/src/Ogre2Camera.cc:182.
- <camera><pose>: Classic composes it (gazebo/sensors/CameraSensor.cc:168-172); gz-sensors
  renders from the sensor's pose (@gz-sensors8:src/CameraSensor.cc:221).
"""

from __future__ import annotations

import math

import pytest
from builders import camera_sensor, gz_robot, robot

from sensorkit.base.findings import Severity

HFOV = 1.3962634
F = 640 / (2 * math.tan(HFOV / 2))  # the builders' 640x480 camera
FRAME = "<frame_name>camera_optical_frame</frame_name>"
FRAME1 = "<frameName>camera_optical_frame</frameName>"


def _of(check, text: str, target: str, rule: str, suffix: str = ".urdf") -> list:
    return [f for f in check(text, target=target, suffix=suffix).findings if f.rule == rule]


def _cam(inner: str = "", hfov: float = HFOV) -> str:
    return (
        f"<camera><horizontal_fov>{hfov}</horizontal_fov><image><width>640</width><height>480</height>"
        f"<format>R8G8B8</format></image><clip><near>0.05</near><far>50</far></clip>{inner}</camera>"
    )


# ------------------------------------------------------------------------ SK413


def test_sk413_hack_baseline_on_a_monocular_camera_is_an_error(check) -> None:
    [f] = _of(check, robot(camera=camera_sensor(params=FRAME + "<hack_baseline>0.07</hack_baseline>")), "classic", "SK413")
    assert f.severity is Severity.ERROR
    assert f"P[0][3] = {-F * 0.07:.4g}" in f.message  # -f * B, f from width and hfov
    assert f.consequence is not None and f.consequence.role.value == "calibration"


def test_sk413_ros1_reads_hackBaseline_and_focalLength(check) -> None:
    text = robot(camera=camera_sensor(params=FRAME1 + "<hackBaseline>0.1</hackBaseline><focalLength>500</focalLength>"))
    [f] = _of(check, text, "ros1", "SK413")
    assert "P[0][3] = -50" in f.message and f.severity is Severity.ERROR
    # the ROS 2 tag means nothing to the ROS 1 plugin (SK602's business, not a baseline)
    assert _of(check, robot(camera=camera_sensor(params=FRAME1 + "<hack_baseline>0.1</hack_baseline>")), "ros1", "SK413") == []


def test_sk413_ros2_tx_replaces_the_baseline(check) -> None:
    [f] = _of(check, robot(camera=camera_sensor(params=FRAME + "<hack_baseline>0.07</hack_baseline><Tx>-12</Tx>")), "classic", "SK413")
    assert "<Tx>" in f.message and "P[0][3] = -12" in f.message


@pytest.mark.parametrize(("baseline", "severity"), [(0.99 / F, Severity.INFO), (1.01 / F, Severity.ERROR)])
def test_sk413_one_pixel_at_one_metre(check, baseline: float, severity: Severity) -> None:
    [f] = _of(check, robot(camera=camera_sensor(params=FRAME + f"<hack_baseline>{baseline!r}</hack_baseline>")), "classic", "SK413")
    assert f.severity is severity


def test_sk413_near_misses(check) -> None:
    # no baseline, a zero baseline, a partner of the same image size, a gz target
    assert _of(check, robot(camera=camera_sensor()), "classic", "SK413") == []
    assert _of(check, robot(camera=camera_sensor(params=FRAME + "<hack_baseline>0</hack_baseline>")), "classic", "SK413") == []
    pair = camera_sensor("cam_left") + camera_sensor("cam_right", params=FRAME + "<hack_baseline>0.07</hack_baseline>")
    assert _of(check, robot(camera=pair), "classic", "SK413") == []


# ------------------------------------------------------------------------ SK414

R2 = (320 / F) ** 2 + (240 / F) ** 2
PER_K1 = F * R2 * math.hypot(320 / F, 240 / F)  # corner shift in px per unit of k1


def test_sk414_ros1_tags_the_image_does_not_have(check) -> None:
    text = robot(camera=camera_sensor(params=FRAME1 + "<distortionK1>-0.2</distortionK1>"))
    [f] = _of(check, text, "ros1", "SK414")
    assert f.severity is Severity.ERROR
    assert f"{0.2 * PER_K1:.3g} px" in f.message


def test_sk414_ros1_image_distortion_camera_info_lacks(check) -> None:
    text = robot(camera=camera_sensor(camera=_cam("<distortion><k1>-0.2</k1></distortion>"), params=FRAME1))
    [f] = _of(check, text, "ros1", "SK414")
    assert f.severity is Severity.ERROR


@pytest.mark.parametrize(("k1", "severity"), [(0.99 / PER_K1, Severity.INFO), (1.01 / PER_K1, Severity.ERROR)])
def test_sk414_one_pixel_at_the_corner(check, k1: float, severity: Severity) -> None:
    text = robot(camera=camera_sensor(params=FRAME1 + f"<distortionK1>{k1!r}</distortionK1>"))
    [f] = _of(check, text, "ros1", "SK414")
    assert f.severity is severity


def test_sk414_near_misses(check) -> None:
    same = robot(camera=camera_sensor(camera=_cam("<distortion><k1>-0.2</k1></distortion>"), params=FRAME1 + "<distortionK1>-0.2</distortionK1>"))
    auto = robot(camera=camera_sensor(camera=_cam("<distortion><k1>-0.2</k1></distortion>"), params=FRAME1 + "<autoDistortion>true</autoDistortion>"))
    ros2 = robot(camera=camera_sensor(camera=_cam("<distortion><k1>-0.2</k1></distortion>")))
    assert _of(check, same, "ros1", "SK414") == []
    assert _of(check, auto, "ros1", "SK414") == []
    assert _of(check, ros2, "classic", "SK414") == []  # ROS 2 publishes the rendered distortion


def test_sk414_gz_depth_camera_publishes_distortion_it_does_not_render(check) -> None:
    dist = "<distortion><k1>0.1</k1></distortion><clip>"
    [f] = _of(check, gz_robot(camera_type="depth_camera").replace("<clip>", dist), "harmonic", "SK414")
    assert f.severity is Severity.ERROR
    # a gz camera renders it (gz-sensors8 src/CameraSensor.cc:269-285): nothing to say
    assert _of(check, gz_robot().replace("<clip>", dist), "harmonic", "SK414") == []


# ------------------------------------------------------------------------ SK415


def _vfov_for(shift_px: float) -> float:
    """The vertical_fov whose rows' focal length puts the top edge ``shift_px`` beyond the image's."""
    fy_used = 240 / (math.tan(HFOV / 2) * 480 / 640)
    fy = fy_used * (1 + shift_px / 240)
    return 2 * math.atan(240 / fy)


def test_sk415_vertical_fov_against_the_renderers(check) -> None:
    text = robot(camera=camera_sensor(camera=_cam("<vertical_fov>0.8</vertical_fov>")))
    [f] = _of(check, text, "classic", "SK415")
    assert f.severity is Severity.ERROR
    effective = 2 * math.atan(math.tan(HFOV / 2) * 480 / 640)
    assert f"{effective:.4f} rad, not 0.8" in f.message


@pytest.mark.parametrize(("shift", "severity"), [(0.9, Severity.INFO), (1.1, Severity.ERROR)])
def test_sk415_vertical_fov_one_pixel(check, shift: float, severity: Severity) -> None:
    text = robot(camera=camera_sensor(camera=_cam(f"<vertical_fov>{_vfov_for(shift)!r}</vertical_fov>")))
    [f] = _of(check, text, "harmonic", "SK415")
    assert f.severity is severity


def test_sk415_imu_orientation_noise_is_a_warning(check) -> None:
    imu = (
        '<sensor name="imu" type="imu"><update_rate>100</update_rate><imu><orientation><x><noise type="gaussian">'
        "<mean>0</mean><stddev>0.002</stddev></noise></x></orientation></imu>"
        '<plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so"><frame_name>laser_link</frame_name></plugin></sensor>'
    )
    [f] = _of(check, robot(lidar=imu), "classic", "SK415")
    assert f.severity is Severity.WARNING
    zero = imu.replace("0.002", "0")
    [g] = _of(check, robot(lidar=zero), "classic", "SK415")
    assert g.severity is Severity.INFO


def test_sk415_an_element_of_unknown_meaning_is_info(check) -> None:
    text = robot(camera=camera_sensor(camera=_cam("<depth_image><width>640</width></depth_image>")))
    [f] = _of(check, text, "classic", "SK415")
    assert f.severity is Severity.INFO and "<depth_image>" in f.message


def test_sk415_near_misses(check) -> None:
    # schema names, namespaced custom elements, gz frame tags (SK608) and misplaced settings
    # (SK410) are not reported; names inside <plugin> are the plugin's business
    assert _of(check, robot(), "classic", "SK415") == []
    custom = camera_sensor(camera=_cam('<my:tag xmlns:my="urn:x">1</my:tag><ignition_frame_id>x</ignition_frame_id>'))
    assert _of(check, robot(camera=custom), "classic", "SK415") == []
    misplaced = camera_sensor(camera=_cam("<update_rate>5</update_rate>"))
    assert _of(check, robot(camera=misplaced), "classic", "SK415") == []
    plugin = camera_sensor(params=FRAME + "<vertical_fov>0.8</vertical_fov>")
    assert _of(check, robot(camera=plugin), "classic", "SK415") == []


# ------------------------------------------------------------------------ SK416


@pytest.mark.parametrize(
    ("pose", "severity"),
    [
        ("0.1 0 0 0 0 0", Severity.ERROR),
        ("0.0009 0 0 0 0 0", Severity.INFO),
        ("0.0011 0 0 0 0 0", Severity.ERROR),
        (f"0 0 0 0 0 {math.radians(0.49)!r}", Severity.INFO),
        (f"0 0 0 0 0 {math.radians(0.51)!r}", Severity.ERROR),
    ],
)
def test_sk416_camera_pose_on_gz(check, pose: str, severity: Severity) -> None:
    text = gz_robot().replace("<clip>", f"<pose>{pose}</pose><clip>")
    [f] = _of(check, text, "harmonic", "SK416")
    assert f.severity is severity


def test_sk416_classic_reads_the_camera_pose(check) -> None:
    text = robot(camera=camera_sensor(camera=_cam("<pose>0.1 0 0 0 0 0</pose>")))
    assert _of(check, text, "classic", "SK416") == []
    assert _of(check, gz_robot(), "harmonic", "SK416") == []


# ------------------------------------------------------------------------ SK409 on ROS 1


def test_sk409_reads_the_ros1_focalLength(check) -> None:
    # ROS 1 camera utils read <focalLength> (ros-simulation/gazebo_ros_pkgs@noetic-devel
    # f9e1a46:gazebo_plugins/src/gazebo_ros_camera_utils.cpp:183-189); <focal_length> is
    # the ROS 2 plugin's tag and means nothing to them.
    [f] = _of(check, robot(camera=camera_sensor(params=FRAME1 + "<focalLength>500</focalLength>")), "ros1", "SK409")
    assert "focalLength 500" in f.message and f.severity is Severity.ERROR
    assert _of(check, robot(camera=camera_sensor(params=FRAME1 + "<focal_length>500</focal_length>")), "ros1", "SK409") == []
    assert _of(check, robot(camera=camera_sensor(params=FRAME1 + f"<focalLength>{F!r}</focalLength>")), "ros1", "SK409") == []


# ------------------------------------------------------------------------ SK417


@pytest.mark.parametrize(
    ("params", "target", "found"),
    [
        (FRAME + "<cx>321.6</cx>", "classic", True),  # 1.6 px: over 1.5
        (FRAME + "<cx>321.4</cx>", "classic", False),  # 1.4 px: under
        (FRAME + "<cx>320.5</cx>", "classic", False),  # gazebo_ros's own default
        (FRAME + "<cy>250</cy>", "classic", True),
        (FRAME + "<cx>400</cx>", "classic", False),  # 80 px > 10 %: SK411's, not both
        (FRAME1 + "<Cx>0</Cx>", "ros1", False),  # ROS 1: 0 means computed
        (FRAME1 + "<Cx>324</Cx>", "ros1", True),
    ],
)
def test_sk417_principal_point_off_centre(check, params: str, target: str, found: bool) -> None:
    # Classic renders the principal point at the centre (elysia-best/gazebo-classic@upstream/
    # 11.10.2+dfsg:gazebo/rendering/Camera.cc:2033-2035); ROS 2 publishes <cx> as written
    # (gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:360-364), ROS 1
    # <Cx> with 0 computed (@noetic-devel f9e1a46:gazebo_ros_camera_utils.cpp:506-509).
    got = _of(check, robot(camera=camera_sensor(params=params)), target, "SK417")
    assert bool(got) is found, [f.message for f in got]
    assert all(f.severity is Severity.ERROR for f in got)
    if "<cx>400" in params:
        assert _of(check, robot(camera=camera_sensor(params=params)), target, "SK411")


def test_sk414_classic_depth_image_is_not_distorted(check) -> None:
    # the distortion compositor sits on the camera's main viewport (elysia-best/gazebo-classic@
    # upstream/11.10.2+dfsg:gazebo/rendering/Distortion.cc:467-473), the depth image has its
    # own (DepthCamera.cc:658-669); gazebo_ros_camera publishes depth/camera_info with the
    # SDF D (gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:407-414, :697-703)
    dist = _cam("<distortion><k1>0.1</k1></distortion>")
    [f] = _of(check, robot(camera=camera_sensor(stype="depth", camera=dist)), "classic", "SK414")
    assert f.severity is Severity.ERROR and "depth image" in f.message
    assert _of(check, robot(camera=camera_sensor(stype="camera", camera=dist)), "classic", "SK414") == []
    assert _of(check, robot(camera=camera_sensor(stype="depth", camera=_cam("<distortion><k1>0</k1></distortion>"))), "classic", "SK414") == []


@pytest.mark.parametrize(
    "camera",
    [
        _cam("<vertical_fov>1e-320</vertical_fov>", hfov=1e-320),
        _cam("<vertical_fov>nan</vertical_fov><distortion><k1>1e308</k1></distortion>"),
        _cam("<vertical_fov>3.2</vertical_fov><pose>nan 0 0 0 0 0</pose>", hfov=3.1),
    ],
)
def test_hostile_numbers_give_findings_not_tracebacks(check, camera: str) -> None:
    params = FRAME1 + "<hackBaseline>1e308</hackBaseline><focalLength>1e308</focalLength><distortionK1>inf</distortionK1><Cx>1e400</Cx>"
    for target in ("ros1", "classic", "harmonic"):
        check(robot(camera=camera_sensor(stype="depth", camera=camera, params=params)), target=target)
