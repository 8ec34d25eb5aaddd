"""How large a sensor can plausibly be: one place for validate's warnings and render's budget.

The plausibility limits are not simulator constants: they sit well above every real sensor
sensorkit knows (a 4K camera has 3840 x 2160 = 8.3 MP; an Ouster OS2-128 casts 128 x 2048 =
262,144 rays per scan, a Hesai Pandar128 128 x 1800 = 230,400), so a description beyond them
is almost surely a typo, and rendering it would exhaust a workstation. ``render preview``
refuses above them unless raised with ``--max-pixels`` / ``--max-rays``.

The one hard limit is the message size on Gazebo Sim:
- gz-sensors copies each camera frame into one gz-msgs ``Image`` protobuf
  (gazebosim/gz-sensors@9ba02f2 src/CameraSensor.cc:511
  ``msg.set_data(data, this->dataPtr->camera->ImageMemorySize())``);
- protobuf refuses to serialize a message over ``INT_MAX`` bytes
  (protocolbuffers/protobuf@4c9df8e src/google/protobuf/message_lite.cc,
  ``MessageLite::SerializePartialToCodedStream``: ``if (size > INT_MAX)`` logs
  "exceeded maximum protobuf size of 2GB" and returns false), so such a frame is never
  published.
"""

from __future__ import annotations

import math

# sensorkit's materiality floors (issue 35, "tests at the limits"): not simulator constants,
# but the one value each comparison of one kind uses, so that a mutation of any of them is
# seen by every rule that relies on it (tests/test_limits.py holds a case just over and just
# under each, rule by rule).
# - Two frames, or a frame and where a sensor renders, are at one place within POSITION_TOL
#   (SK503, SK416, SK510, the frames-coincide test behind SK303/SK602/SK608, optical_frame_at
#   for SK501/SK502/SK503's fixes, the recording checks SK80x, --fix's frame choice).
# - A rotation is the one meant within ANGLE_TOL (SK502, SK504, SK505, SK506, SK508, SK614,
#   SK416, SK510, the optical joint SK502 blames, --fix's angle snapping, SK80x).
# - A camera_info or field of view that moves the image's edge by at most EDGE_PX pixels
#   changes no pixel a user sees (SK409, SK410's field of view, SK413/SK414/SK417, SK415).
POSITION_TOL = 1e-3  # m
ANGLE_TOL = math.radians(0.5)  # rad
EDGE_PX = 1.0  # pixels

PLAUSIBLE_CAMERA_PIXELS = 4096 * 4096
PLAUSIBLE_LIDAR_RAYS = 1_000_000
PROTOBUF_MAX_BYTES = 2**31 - 1

# Bytes per pixel of sdformat's <image><format> values (gz-rendering PixelUtil spellings).
BYTES_PER_PIXEL = {
    "L8": 1, "L_INT8": 1, "BAYER_RGGB8": 1, "BAYER_BGGR8": 1, "BAYER_GBRG8": 1,
    "BAYER_GRBG8": 1, "L16": 2, "L_INT16": 2, "R_FLOAT16": 2, "R_FLOAT32": 4,
    "R8G8B8": 3, "B8G8R8": 3, "RGB_INT8": 3, "BGR_INT8": 3, "RGB_INT16": 6,
    "R16G16B16": 6, "RGB_FLOAT16": 6, "RGB_FLOAT32": 12, "RGBA_INT8": 4, "BGRA_INT8": 4,
}  # fmt: skip


def frame_bytes(width: int, height: int, fmt: str | None, depth: bool) -> int:
    """Bytes of one image: depth images are 32-bit floats, colour R8G8B8 unless said."""
    per = 4 if depth else BYTES_PER_PIXEL.get(fmt or "R8G8B8", 3)
    return width * height * per

# Gazebo Classic sensor types whose second sensor of one name on one link makes gzserver
# abort: both sensors are created (gazebosim/gazebo-classic@upstream/11.10.2+dfsg, Debian
# import elysia-best/gazebo-classic: gazebo/physics/Link.cc:185-209 calls createSensor for
# every <sensor>; gazebo/sensors/SensorManager.cc:488-531 CreateSensor has no duplicate
# check), and each names an Ogre render texture after link and sensor name: a camera
# "<model::link>::<name>_RttTex" (gazebo/sensors/CameraSensor.cc:146,167), a depth camera
# "<name>_RttTex_Image" (gazebo/sensors/DepthCameraSensor.cc:101-102). Ogre throws
# ERR_DUPLICATE_ITEM "Resource with the name ... already exists" for the second
# (OGRECave/ogre@006d77cb82da7b069cdb3188628dc047e4422b40:OgreMain/src/OgreResourceManager.cpp,
# ResourceManager::addImpl), uncaught around sensor->Init() (SensorManager.cc:320) and
# sensors::run_once() (gazebo/Server.cc:651,696).
CLASSIC_TEXTURE_NAMED_TYPES = frozenset({"camera", "depth"})


def as_float(n: int) -> float:
    """``float(n)``, infinite for an int too large for a float (``float`` raises there)."""
    return float(n) if n < 2**1000 else math.inf
