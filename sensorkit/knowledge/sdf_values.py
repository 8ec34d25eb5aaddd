"""What each simulator does with an image format or noise type it does not know (SK403, SK408).

Image format, Gazebo Classic 11 (classic, ros1):
- rendering::Camera::OgrePixelFormat logs "Error parsing image format (...), using default
  Ogre::PF_R8G8B8" and renders into PF_R8G8B8 (elysia-best/gazebo-classic@upstream/
  11.10.2+dfsg (gazebo11 release import): gazebo/rendering/Camera.cc:1023-1027; the image is
  read back in that format, Camera.cc:144-145 and :607-608);
- Ogre 1.x defines PF_BYTE_BGR = PF_R8G8B8 on a little-endian host (OGRECave/ogre@v1-9-0:
  OgreMain/include/OgrePixelFormat.h:98-101): the bytes are blue, green, red;
- gazebo_ros labels an unknown format BGR8 with 3 bytes a pixel: ROS 2 gazebo_ros_camera
  "Unsupported Gazebo ImageFormat, using BGR8" (ros-simulation/gazebo_ros_pkgs@ros2 (d52f7c4):
  gazebo_plugins/src/gazebo_ros_camera.cpp:336-339), ROS 1 GazeboRosCameraUtils
  (@noetic-devel (f9e1a46): gazebo_plugins/src/gazebo_ros_camera_utils.cpp:496-501).
So the image arrives labelled as what it is, with correct colours: a warning. The formats
Classic itself knows beyond sdformat's names (``CLASSIC_EXTRA_IMAGE_FORMATS``: Camera.cc:
1001-1012) render in their own layout, which gazebo_ros then labels BGR8: still an error.

Image format, Gazebo Sim (fortress, harmonic, jetty): sdformat's Camera::Load pushes
ELEMENT_INVALID "Camera sensor <image><format> has invalid value of ..." (gazebosim/
sdformat@sdf12 (b9417e5):src/Camera.cc:297-302; @sdf14 (8512585):src/Camera.cc:299-304), and gz-sim's
create service refuses an SDF with any error (gazebosim/gz-sim@gz-sim8 (b81e26d):
src/systems/user_commands/UserCommands.cc:925-930): the robot is not spawned: an error.

Noise type, Gazebo Classic: NoiseFactory::NewNoiseModel compares the type exactly and returns
a null NoisePtr for any but gaussian, gaussian_quantized, none, custom (Noise.cc:41-67);
every sensor that has one dereferences it: CameraSensor.cc:176-180 (SetCamera),
ImuSensor.cc:104-109 (Print), RaySensor.cc:490-494 and GpuRaySensor.cc:770-772 (Apply):
gzserver crashes: an error on every sensor.

Noise type, Gazebo Sim: sdformat lower-cases the type and takes only none, gaussian,
gaussian_quantized; anything else is an ELEMENT_MISSING error "Using a value of 'none'"
(sdf12:src/Noise.cc:88-102; sdf14:src/Noise.cc:90-104). Whether the error reaches gz-sim
depends on the owner: Camera::Load keeps it (sdf12:src/Camera.cc:376-377, sdf14:378-379), so
the robot is refused; Lidar::Load drops it (sdf12 and sdf14:src/Lidar.cc:176-177); Imu::Load
drops it on sdf12 (src/Imu.cc:104-105) and keeps it from sdf14 (src/Imu.cc:105-107). A
dropped error leaves type none, for which gz-sensors builds no noise model (gazebosim/
gz-sensors@gz-sensors8 (c8159af):src/ImuSensor.cc:164-167; src/Lidar.cc:173-186): the sensor
works without noise: a warning.
"""

from __future__ import annotations

# Formats Gazebo Classic's Camera::OgrePixelFormat maps beyond sdformat's names
# (Camera.cc:1001-1012): they render, but gazebo_ros labels them BGR8 with 3 bytes a pixel.
CLASSIC_EXTRA_IMAGE_FORMATS = frozenset({"FLOAT32", "FLOAT16", "L_UINT16", "RGB_UINT16"})

CLASSIC_UNKNOWN_FORMAT = (
    "Gazebo Classic logs 'Error parsing image format' and renders Ogre::PF_R8G8B8, which is "
    "blue-green-red bytes on a little-endian host, and gazebo_ros labels it bgr8: the image "
    "is right, but say what you mean (elysia-best/gazebo-classic@upstream/11.10.2+dfsg:"
    "gazebo/rendering/Camera.cc:1023-1027; OGRECave/ogre@v1-9-0:OgreMain/include/"
    "OgrePixelFormat.h:98-101; gazebo_ros_pkgs@ros2:gazebo_plugins/src/gazebo_ros_camera.cpp:336-339)"
)
GZ_UNKNOWN_FORMAT = (
    "sdformat reports 'Camera sensor <image><format> has invalid value' and Gazebo Sim refuses "
    "to spawn the robot (gazebosim/sdformat@sdf14:src/Camera.cc:299-304; gazebosim/gz-sim@gz-sim8:"
    "src/systems/user_commands/UserCommands.cc:925-930)"
)

CLASSIC_NOISE_TYPES = frozenset({"none", "gaussian", "gaussian_quantized", "custom"})
GZ_NOISE_TYPES = frozenset({"none", "gaussian", "gaussian_quantized"})  # compared lower-cased

# The sensor kinds (sensorkit.model.sensors.Sensor.kind) whose sdformat loader keeps a noise
# error on each Gazebo Sim target; the others run without noise.
_GZ_NOISE_ERROR_KEPT = {
    "fortress": frozenset({"camera", "depth", "rgbd", "multicamera"}),
    "harmonic": frozenset({"camera", "depth", "rgbd", "multicamera", "imu"}),
    "jetty": frozenset({"camera", "depth", "rgbd", "multicamera", "imu"}),
}


def noise_type_effect(target: str, kind: str, noise_type: str) -> tuple[bool, str] | None:
    """For a noise type the target does not know: (is it fatal, what happens); None if known."""
    if target in _GZ_NOISE_ERROR_KEPT:
        if noise_type.lower() in GZ_NOISE_TYPES:
            return None
        if kind in _GZ_NOISE_ERROR_KEPT[target]:
            return True, (
                "sdformat reports 'Noise type attribute is invalid' and Gazebo Sim refuses to spawn "
                "the robot (gazebosim/sdformat@sdf14:src/Noise.cc:98-104; gz-sim@gz-sim8:"
                "src/systems/user_commands/UserCommands.cc:925-930)"
            )
        loader = "sdf12:src/Imu.cc:104-105" if kind == "imu" else "sdf14:src/Lidar.cc:176-177"
        return False, (
            "sdformat takes it as 'none' and this sensor's loader drops the error, so the sensor "
            f"runs without noise (gazebosim/sdformat@sdf14:src/Noise.cc:98-104, {loader})"
        )
    if noise_type in CLASSIC_NOISE_TYPES:
        return None
    return True, (
        "Gazebo Classic's NoiseFactory returns no noise model for it (type names are "
        "case-sensitive) and the sensor dereferences it: gzserver crashes "
        "(elysia-best/gazebo-classic@upstream/11.10.2+dfsg:gazebo/sensors/Noise.cc:64-67)"
    )
