"""Issue 23 (severity): an error is a sensor that will not work as written; each case pinned here
with the simulator line that decides it, a trigger and a near miss.

Sources are read from the simulators' own trees:
- Gazebo Classic 11: elysia-best/gazebo-classic@upstream/11.10.2+dfsg (gazebo11 release import);
- Ogre 1.9 (Classic's renderer): OGRECave/ogre@v1-9-0;
- gazebo_ros: ros-simulation/gazebo_ros_pkgs@ros2 (d52f7c4) and @noetic-devel (f9e1a46);
- sdformat: gazebosim/sdformat@sdf12 (b9417e5, Fortress) and @sdf14 (8512585, Harmonic);
- gz-sim: gazebosim/gz-sim@gz-sim8 (b81e26d); gz-sensors: gazebosim/gz-sensors@gz-sensors8 (c8159af).
"""

from __future__ import annotations

from builders import camera_sensor, lidar_sensor, robot

from sensorkit.base.findings import Severity


def _severities(report: object, rule: str) -> list[Severity]:
    return [f.severity for f in report.findings if f.rule == rule]  # type: ignore[attr-defined]


def _camera(fmt: str = "R8G8B8", noise: str = "") -> str:
    return camera_sensor(camera=(
        '<camera><horizontal_fov>1.3962634</horizontal_fov>'
        f'<image><width>640</width><height>480</height><format>{fmt}</format></image>'
        f'<clip><near>0.05</near><far>50</far></clip>{noise}</camera>'
    ))


# --- SK403: an unknown image format -------------------------------------------------


def test_sk403_unknown_format_is_a_warning_on_classic(check) -> None:
    # Classic renders an unknown format as Ogre::PF_R8G8B8 (gazebo/rendering/Camera.cc:1023-1027
    # "Error parsing image format (...), using default Ogre::PF_R8G8B8"), which Ogre 1.9 makes
    # PF_BYTE_BGR on a little-endian host (OgreMain/include/OgrePixelFormat.h:98-101), and
    # gazebo_ros labels it BGR8, 3 bytes a pixel (ros2 gazebo_plugins/src/gazebo_ros_camera.cpp:
    # 336-339; noetic gazebo_plugins/src/gazebo_ros_camera_utils.cpp:496-501): right colours.
    for target in ("classic", "ros1"):
        assert _severities(check(robot(camera=_camera("RGB8")), target=target), "SK403") == [Severity.WARNING]
        assert _severities(check(robot(camera=_camera("R8G8B8")), target=target), "SK403") == []


def test_sk403_classic_only_format_stays_an_error(check) -> None:
    # FLOAT32 is Classic's own alias (Camera.cc:1007) rendered 4 bytes a pixel, which gazebo_ros
    # does not know and labels bgr8 with 3 bytes a pixel (gazebo_ros_camera.cpp:336-339).
    assert _severities(check(robot(camera=_camera("FLOAT32")), target="classic"), "SK403") == [Severity.ERROR]


def test_sk403_unknown_format_is_an_error_on_gz(check) -> None:
    # sdformat: ELEMENT_INVALID "Camera sensor <image><format> has invalid value of"
    # (sdf12:src/Camera.cc:297-302; sdf14:src/Camera.cc:299-304); gz-sim refuses an SDF with
    # any error (gz-sim8:src/systems/user_commands/UserCommands.cc:925-930).
    for target in ("fortress", "harmonic", "jetty"):
        assert _severities(check(robot(camera=_camera("RGB8")), target=target), "SK403") == [Severity.ERROR]
        assert _severities(check(robot(camera=_camera("RGB_INT8")), target=target), "SK403") == []


# --- SK408: an unknown noise type ----------------------------------------------------

NOISE = '<noise type="{t}"><mean>0</mean><stddev>0.01</stddev></noise>'
IMU = (
    '<gazebo reference="base_link"><sensor name="imu" type="imu"><update_rate>100</update_rate>'
    '<imu><angular_velocity><x>{n}</x></angular_velocity></imu></sensor></gazebo>'
)


def _imu_robot(t: str) -> str:
    return robot(extra=IMU.format(n=NOISE.format(t=t)))


def test_sk408_unknown_noise_crashes_classic(check) -> None:
    # NoiseFactory::NewNoiseModel returns a null NoisePtr for an unknown type (gazebo/sensors/
    # Noise.cc:64-67) and the sensors dereference it: CameraSensor.cc:176-180, ImuSensor.cc:104-109,
    # RaySensor.cc:490-494. Type names are compared exactly, so 'Gaussian' is unknown there too.
    for target in ("classic", "ros1"):
        assert _severities(check(robot(camera=_camera(noise=NOISE.format(t="Gaussian"))), target=target),
                           "SK408") == [Severity.ERROR]
        assert _severities(check(robot(lidar=lidar_sensor(noise=NOISE.format(t="foo"))), target=target),
                           "SK408") == [Severity.ERROR]
        assert _severities(check(_imu_robot("foo"), target=target), "SK408") == [Severity.ERROR]
        assert _severities(check(_imu_robot("custom"), target=target), "SK408") == []  # Noise.cc:55


def test_sk408_unknown_noise_on_gz_by_sensor(check) -> None:
    # sdformat takes an unknown type as 'none' with an error (sdf12:src/Noise.cc:88-102;
    # sdf14:src/Noise.cc:90-104). Camera::Load keeps the error (sdf12:src/Camera.cc:376-377),
    # so gz-sim refuses the robot (UserCommands.cc:925-930); Lidar::Load drops it
    # (sdf14:src/Lidar.cc:176-177) and gz-sensors builds no noise for 'none'
    # (gz-sensors8:src/Lidar.cc:173-186): the lidar works without noise.
    cam = robot(camera=_camera(noise=NOISE.format(t="foo")))
    lidar = robot(lidar=lidar_sensor(stype="gpu_lidar", tag="lidar", plugin="", noise=NOISE.format(t="foo")))
    for target in ("fortress", "harmonic", "jetty"):
        assert _severities(check(cam, target=target), "SK408") == [Severity.ERROR]
        assert _severities(check(lidar, target=target), "SK408") == [Severity.WARNING]
        # sdformat lower-cases the type (sdf14:src/Noise.cc:90): 'Gaussian' is gaussian.
        assert _severities(check(robot(camera=_camera(noise=NOISE.format(t="Gaussian"))), target=target),
                           "SK408") == []
    # An IMU's noise error is dropped by sdf12's Imu::Load (src/Imu.cc:104-105), kept from sdf14
    # (src/Imu.cc:105-107); gz-sensors builds no noise for 'none' (gz-sensors8:src/ImuSensor.cc:164-167).
    assert _severities(check(_imu_robot("foo"), target="fortress"), "SK408") == [Severity.WARNING]
    assert _severities(check(_imu_robot("foo"), target="harmonic"), "SK408") == [Severity.ERROR]


def test_sk408_custom_is_unknown_to_gazebo_sim(check) -> None:
    # Classic takes 'custom' (gazebo/sensors/Noise.cc:55-63); sdformat takes only none, gaussian,
    # gaussian_quantized (sdf12:src/Noise.cc:90-102): on a camera the robot is refused.
    cam = robot(camera=_camera(noise=NOISE.format(t="custom")))
    assert _severities(check(cam, target="classic"), "SK408") == []
    assert _severities(check(cam, target="harmonic"), "SK408") == [Severity.ERROR]


# --- SK409: a wrong calibration is an error, a rounding a warning ----------------------
# camera_info's fx comes from the plugin's focal length, else width / (2 tan(hfov / 2))
# (ros-simulation/gazebo_ros_pkgs@ros2 (d52f7c4):gazebo_plugins/src/gazebo_ros_camera.cpp:366-374),
# while Gazebo Classic renders the image with horizontal_fov (elysia-best/gazebo-classic@
# upstream/11.10.2+dfsg:gazebo/rendering/Camera.cc:852-855). Width 640 and horizontal_fov
# 1.3962634 give fx 381.3612. The floor is sensorkit's: camera_info moving the image edge
# (320 px from the centre) by more than 1 px.


def _focal(f: str) -> str:
    return robot(camera=camera_sensor(params=f"<frame_name>camera_optical_frame</frame_name><focal_length>{f}</focal_length>"))


def test_sk409_focal_length_off_by_pixels_is_an_error(check) -> None:
    # 350: the edge lands 320 * 31.36 / 381.36 = 26 px off
    assert _severities(check(_focal("350"), target="classic"), "SK409") == [Severity.ERROR]
    # 381: 320 * 0.36 / 381.36 = 0.3 px, a rounding: a warning
    assert _severities(check(_focal("381"), target="classic"), "SK409") == [Severity.WARNING]
    assert _severities(check(_focal("381.36124"), target="classic"), "SK409") == []


def test_sk409_gz_k_off_the_projection(check) -> None:
    # gz-sensors renders with <projection> and publishes K from <intrinsics> (gazebosim/
    # gz-sensors@gz-sensors8 (c8159af):src/CameraSensor.cc:898-914 and :729-739).
    def lens(k_fx: str, k_cx: str = "320") -> str:
        return robot(camera=camera_sensor(plugin="", camera=(
            "<camera><horizontal_fov>1.3962634</horizontal_fov><image><width>640</width><height>480</height>"
            "<format>R8G8B8</format></image><clip><near>0.05</near><far>50</far></clip><lens>"
            f"<intrinsics><fx>{k_fx}</fx><fy>381.3612</fy><cx>{k_cx}</cx><cy>240</cy><s>0</s></intrinsics>"
            "<projection><p_fx>381.3612</p_fx><p_fy>381.3612</p_fy><p_cx>320</p_cx><p_cy>240</p_cy>"
            "<tx>0</tx><ty>0</ty></projection></lens></camera>")))
    assert _severities(check(lens("400"), target="harmonic"), "SK409") == [Severity.ERROR]
    assert _severities(check(lens("381.8"), target="harmonic"), "SK409") == [Severity.WARNING]
    # a principal point: an error past SK411's floor (10 % of the width), a warning below
    assert _severities(check(lens("381.3612", "400"), target="harmonic"), "SK409") == [Severity.ERROR]
    assert _severities(check(lens("381.3612", "330"), target="harmonic"), "SK409") == [Severity.WARNING]
