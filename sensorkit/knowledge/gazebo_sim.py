"""Gazebo Sim (Fortress, Harmonic, Jetty) facts consulted by rules, bridge generation and auto.

Sensor types that gz-sim never creates, per version. gz-sim turns an ``sdf::Sensor`` into
components in ``SdfEntityCreator::CreateEntities(const sdf::Sensor *)``, one branch per
``sdf::SensorType``; a type with no branch gets no sensor component, so no system creates the
sensor and it publishes nothing. The type strings map to ``sdf::SensorType`` in sdformat's
``Sensor::Load`` (src/Sensor.cc). Versions read: Fortress = gazebosim/gz-sim@ign-gazebo6 with
sdformat12 (ign-gazebo6:CMakeLists.txt:77), Harmonic = gz-sim@gz-sim8 with sdformat14
(gz-sim8:CMakeLists.txt:77), Jetty = gz-sim@gz-sim10 with sdformat 16 (gz-sim10:CMakeLists.txt:94).

Such a sensor is never bridged and never counted as evidence that a description targets
Gazebo Sim.
"""

from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True)
class NeverCreated:
    """A sensor type one Gazebo Sim version never creates: what it does instead, and the fix."""

    why: str
    use: str
    source: str


_GZ_VERSIONS = {"fortress": "Fortress", "harmonic": "Harmonic", "jetty": "Jetty"}
# (gz-sim ref, its sdformat ref, SdfEntityCreator.cc lines of the LIDAR branch, of the final else)
_REFS = {
    "fortress": ("ign-gazebo6", "sdf12", "912-918", "1028-1031"),
    "harmonic": ("gz-sim8", "sdf14", "1092-1098", "1226-1229"),
    "jetty": ("gz-sim10", "sdf16", "1126-1132", "1260-1263"),
}
# Sensor.cc lines mapping the type strings, per sdformat ref.
_SDF_LINES = {
    "sdf12": {
        "multicamera": "361-363",
        "lidar": "365-367",
        "rfid": "373-379",
        "sonar": "381-383",
        "wireless": "385-391",
        "wideangle": "311-313",
    },
    "sdf14": {
        "multicamera": "379-381",
        "lidar": "383-385",
        "rfid": "391-397",
        "sonar": "399-401",
        "wireless": "403-409",
    },
    "sdf16": {
        "multicamera": "383-385",
        "lidar": "387-389",
        "rfid": "395-401",
        "sonar": "403-405",
        "wireless": "407-413",
    },
}
_NO_BRANCH = "it has no branch in SdfEntityCreator, which logs 'Sensor type [N] not supported yet.'"
_NO_GZ_SENSOR = (
    'nothing: Gazebo Sim has no sensor of this kind (a plugin with type="custom" can implement one)'
)


def _table(target: str) -> dict[str, NeverCreated]:
    gz, sdf, lidar_lines, else_lines = _REFS[target]
    lines = _SDF_LINES[sdf]
    creator = f"gazebosim/gz-sim@{gz}:src/SdfEntityCreator.cc"

    def row(why: str, use: str, key: str, gz_lines: str = else_lines) -> NeverCreated:
        return NeverCreated(
            why, use, f"gazebosim/sdformat@{sdf}:src/Sensor.cc:{lines[key]}; {creator}:{gz_lines}"
        )

    lidar = (
        "it parses as SensorType::LIDAR and gz-sim creates no CPU lidar: 'Sensor type LIDAR not "
        "supported yet. Try using a GPU LIDAR instead.'"
    )
    table = {
        "ray": row(lidar, 'type="gpu_lidar" with a <lidar> block', "lidar", lidar_lines),
        "lidar": row(
            lidar, 'type="gpu_lidar" (the CPU lidar is not implemented)', "lidar", lidar_lines
        ),
        "multicamera": row(
            _NO_BRANCH,
            'one <sensor type="camera"> per eye, each with its own <topic>',
            "multicamera",
        ),
        "sonar": row(
            _NO_BRANCH, 'a type="gpu_lidar" range sensor (Gazebo Sim has no sonar)', "sonar"
        ),
        "rfid": row(_NO_BRANCH, _NO_GZ_SENSOR, "rfid"),
        "rfidtag": row(_NO_BRANCH, _NO_GZ_SENSOR, "rfid"),
        "wireless_receiver": row(_NO_BRANCH, _NO_GZ_SENSOR, "wireless"),
        "wireless_transmitter": row(_NO_BRANCH, _NO_GZ_SENSOR, "wireless"),
    }
    if target == "fortress":
        # Fortress has no WIDE_ANGLE_CAMERA branch (ign-gazebo6:src/SdfEntityCreator.cc:902-1031);
        # Harmonic adds one (gz-sim8:src/SdfEntityCreator.cc:1125-1128; gz-sim10:1159-1162).
        wide = row(
            _NO_BRANCH,
            'type="camera" (Fortress has no wide-angle camera; Harmonic does)',
            "wideangle",
        )
        table["wideanglecamera"] = table["wide_angle_camera"] = wide
        # sdformat12 does not know "air_speed": Sensor::Load reports "the provided sensor type is
        # missing or invalid" (sdf12:src/Sensor.cc:393-397), and gz-sim's create service refuses
        # an SDF with errors (ign-gazebo6:src/systems/user_commands/UserCommands.cc:1135-1140).
        # Harmonic creates it (gz-sim8:src/SdfEntityCreator.cc:1139; sdf14:src/Sensor.cc:264-266).
        table["air_speed"] = NeverCreated(
            "sdformat 12 rejects the type ('the provided sensor type is missing or invalid'), and "
            "the create service refuses an SDF with errors",
            "Harmonic or newer, which creates air_speed sensors, or drop the sensor on Fortress",
            "gazebosim/sdformat@sdf12:src/Sensor.cc:393-397; "
            "gazebosim/gz-sim@ign-gazebo6:src/systems/user_commands/UserCommands.cc:1135-1140",
        )
    return table


GZ_NEVER_CREATED: dict[str, dict[str, NeverCreated]] = {t: _table(t) for t in _REFS}


def gz_never_created(target: str, sensor_type: str) -> NeverCreated | None:
    """The row for a sensor type this Gazebo Sim target never creates; None if it creates it
    (or the target is not Gazebo Sim)."""
    return GZ_NEVER_CREATED.get(target, {}).get(sensor_type)


def gz_version(target: str) -> str:
    return _GZ_VERSIONS.get(target, target)


# Depth and RGB-D clouds: gz-sensors computes them in its rendering convention, x forward,
# but stamps them with the camera's optical frame (z forward): "Gazebo uses the +x forward
# convention for all rendering sensors" (https://github.com/gazebosim/gz-sensors/issues/488,
# open; also #29). RgbdCameraSensor stamps the cloud with OpticalFrameId()
# (gazebosim/gz-sensors@gz-sensors8:src/RgbdCameraSensor.cc:397) and fills x, y, z as rendered
# (src/PointCloudUtil.cc:189-209); DepthCameraSensor likewise (src/DepthCameraSensor.cc:446-448).
GZ_XFORWARD_CLOUD_TYPES = frozenset({"depth_camera", "depth", "rgbd_camera", "rgbd"})
GZ_XFORWARD_CLOUD_NOTE = (
    "Gazebo Sim computes depth-camera clouds x-forward but stamps them with the optical frame "
    "(gz-sensors#488)"
)
CLOUD_FIX = (
    "build the cloud in ROS from the depth image and camera_info with depth_image_proc "
    "(point_cloud_xyz / point_cloud_xyzrgb), and do not bridge <topic>/points"
)


# Which camera sensors read <camera><camera_info_topic>: only CameraSensor::Load does
# (gazebosim/gz-sensors@gz-sensors8 c8159af:src/CameraSensor.cc:389-392; @gz-sensors10 ff8c92b:
# :324-327; @ign-sensors6 7cfaddf: :379-382). The other camera sensors call Sensor::Load, not
# CameraSensor::Load, and then AdvertiseInfo() with no topic, so camera_info goes to the
# default, a sibling "camera_info" of their topic (CameraSensor.cc:662-676; gz-sensors10:
# 597-611): DepthCameraSensor (src/DepthCameraSensor.cc:249, :297), WideAngleCameraSensor
# (src/WideAngleCameraSensor.cc:152, :199, the same lines on gz-sensors8 and gz-sensors10),
# ThermalCameraSensor (src/ThermalCameraSensor.cc:184, :231) and BoundingBoxCameraSensor
# (src/BoundingBoxCameraSensor.cc:167, :237). RgbdCameraSensor always uses TOPIC/camera_info
# (src/RgbdCameraSensor.cc:252).
GZ_READS_CAMERA_INFO_TOPIC = frozenset({"camera"})
# Wide-angle cameras: WideAngleCameraSensor publishes its image on <topic> (gz-sensors8
# c8159af:src/WideAngleCameraSensor.cc:174-176) and camera_info beside it (:199). It was added
# in gz-sensors7 (gazebosim/gz-sensors 6c18e47, #171): ign-sensors6 (Fortress) has no
# src/WideAngleCameraSensor.cc, and gz-sim creates the sensor from gz-sim8 on
# (gazebosim/gz-sim@gz-sim8 b81e26d:src/SdfEntityCreator.cc:1125-1128; @gz-sim10 ccd6694:
# 1159-1162; @ign-gazebo6 aab5556 has no WIDE_ANGLE_CAMERA branch). sdformat reads both
# spellings (gazebosim/sdformat@sdf14 8512585:src/Sensor.cc:329).
GZ_WIDE_ANGLE_TYPES = frozenset({"wideanglecamera", "wide_angle_camera"})
GZ_NO_WIDE_ANGLE_RELEASES = frozenset({"fortress"})

# Which read <camera><depth_camera><clip>: RgbdCameraSensor does
# (src/RgbdCameraSensor.cc:313-322); DepthCameraSensor renders depth within the camera's own
# <clip> (src/DepthCameraSensor.cc:349-358).
GZ_READS_DEPTH_CLIP = frozenset({"rgbd_camera", "rgbd"})


# Which sensors stamp their data with gz-sensors' Sensor::FrameId(): the frame tag the
# version reads, else the sensor's name (sensorkit.model.frames.GZ_FRAME_TAGS), which gz-sim
# sets to MODEL::LINK::SENSOR. SK501 warns for them when they have no frame tag.
# By kind (sensorkit.model.sensors): cameras (gazebosim/gz-sim@gz-sim8:
# src/rendering/RenderUtil.cc:1719-1721), lidars (gz-sensors@gz-sensors8:src/Lidar.cc:260-266)
# and IMUs (gz-sensors8:src/ImuSensor.cc:255-257, named by gz-sim8:src/systems/imu/Imu.cc:194-197).
GZ_FRAMED_KINDS = frozenset({"camera", "depth", "rgbd", "multicamera", "lidar", "imu"})
# And by type, NavSat (its kind is "other"): sdformat reads type "navsat" and "gps" alike as
# SensorType::NAVSAT (gazebosim/sdformat@sdf12 b9417e5:src/Sensor.cc:326-333, @sdf14 8512585:
# :344-351, @sdf16 9a26f90:348-355) and gz-sim gives both a NavSat component
# (gazebosim/gz-sim@ign-gazebo6 aab5556:src/SdfEntityCreator.cc:965-969, @gz-sim8 b81e26d:
# 1163-1167, @gz-sim10 ccd6694:1197-1201). The NavSat system (not the Sensors system) creates
# the sensor and names it MODEL::LINK::SENSOR, as the Imu system does
# (src/systems/navsat/NavSat.cc:177-180 on all three). NavSatSensor writes FrameId() into the
# message's own frame_id field, not into the header (gazebosim/gz-sensors@ign-sensors6 7cfaddf:
# src/NavSatSensor.cc:161; @gz-sensors8 c8159af and @gz-sensors10 ff8c92b: :174), and
# ros_gz_bridge makes that field NavSatFix.header.frame_id with "::" turned into "/"
# (gazebosim/ros_gz@humble 5cc92f8:ros_gz_bridge/src/convert/sensor_msgs.cpp:518; @jazzy
# 739cb42 and @ros2 a4d00a9: :516; src/convert/utils.cpp:47-49 on all three): MODEL/LINK/SENSOR,
# which robot_state_publisher never publishes.
GZ_NAVSAT_TYPES = frozenset({"navsat", "gps"})
# What a NavSat sensor with no <topic> publishes on: its scoped name + "/navsat"
# (gz-sim@gz-sim8:src/systems/navsat/NavSat.cc:182-186, the same on ign-gazebo6 and gz-sim10;
# gz-sensors' own "/navsat" fallback, src/NavSatSensor.cc:107-108, is never reached under gz-sim).
GZ_NAVSAT_SUFFIX = "/navsat"
# gz-sim's PosePublisher with <publish_sensor_pose> true (default false: gazebosim/gz-sim@gz-sim8
# b81e26d:src/systems/pose_publisher/PosePublisher.cc:113, read at :224) publishes every
# sensor's pose from MODEL::LINK to MODEL::LINK::SENSOR (:436-448, header keys :590-596), the
# very name the sensor stamps, and ros_gz_bridge turns "::" into "/" in those TF frames
# (ros_gz@jazzy:ros_gz_bridge/src/convert/std_msgs.cpp:171-175, geometry_msgs.cpp:251-256) as
# in the data's: a launch that bridges it to /tf, with robot_state_publisher's frame_prefix
# "MODEL/", puts the sensor's frame in the robot's tree (osrf/vrx@93ae8d0 does:
# vrx_gz/src/vrx_gz/bridges.py:40-46, vrx_ros/src/pose_tf_broadcaster.cc:43,70,
# vrx_gz/src/vrx_gz/launch.py:377).
GZ_SENSOR_POSE_PARAM = "publish_sensor_pose"


# Lidar <range><min> 0. It is the SDF default (gazebosim/sdformat@sdf12 b9417e5:
# sdf/1.6/ray.sdf:50 and sdf/1.9/lidar.sdf:50, @sdf14 8512585:sdf/1.11/lidar.sdf:50, all
# `<element name="min" type="double" default="0" required="1">`), and sdf::Lidar takes it
# unchecked (@sdf12:src/Lidar.cc:162-163). sdformat reads "gpu_ray" and "gpu_lidar" alike as
# SensorType::GPU_LIDAR (@sdf12:src/Sensor.cc:334-336, @sdf14:352-354). On a GPU lidar
# gz-sensors makes it the ray camera's near clip: `gpuRays->SetNearClipPlane(this->RangeMin())`
# (gazebosim/gz-sensors@ign-sensors6 7cfaddf:src/GpuLidarSensor.cc:200, @gz-sensors8 c8159af:
# :198, @gz-sensors10 ff8c92b:193). gz-rendering's ogre2 GpuRays scales it to the cube
# cameras' near clip, `nearClipCube = NearClipPlane() * 2 / sqrt(3) * 0.5`, 0 for 0
# (gazebosim/gz-rendering@ign-rendering6 c39b130:ogre2/src/Ogre2GpuRays.cc:1273-1274,
# @gz-rendering8 ff0c5b8:1181-1182, @gz-rendering10 af28689:1182-1183) and hands it to Ogre
# (`setNearClipDistance(this->dataPtr->nearClipCube)`: ign-rendering6 :628,:1057;
# gz-rendering8 :783,:1048; gz-rendering10 :784,:1049), whose Frustum::setNearClipDistance
# throws "Near clip distance must be greater than zero." for `nearPlane <= 0`
# (ignition-forks/ogre-next@40dcea7 (v2.2.4) and @7449a36 (2.3):OgreMain/src/OgreFrustum.cpp:
# 145-149). So on Gazebo Sim such a GPU lidar never renders. The CPU Lidar base class only
# clamps ranges to [min, max] with it (gz-sensors@gz-sensors8:src/Lidar.cc:523), and gz-sim
# never creates a CPU lidar anyway (GZ_NEVER_CREATED above).
# Nothing catches that exception: Ogre2GpuRays::PreRender creates the textures and calls
# ConfigureCamera (gz-rendering8 ff0c5b8:ogre2/src/Ogre2GpuRays.cc:1273-1276, :1184, :783;
# ign-rendering6 c39b130: :1361-1364, :1276), called from the Sensors system's render thread,
# a std::thread running `this->scene->PreRender()` with no try
# (gazebosim/gz-sim@ign-gazebo6 aab5556:src/systems/sensors/Sensors.cc:349, :407-433;
# @gz-sim8 b81e26d: :469, :528-559; no `catch` in Sensors.cc, gz-sensors8
# src/GpuLidarSensor.cc or src/RenderingSensor.cc), so std::terminate aborts the whole
# `gz sim` server process, every other sensor and the physics with it.
GZ_LIDAR_NEAR_CLIP_TYPES = frozenset({"gpu_lidar", "gpu_ray"})
# Jetty's gz-rendering10 refuses a near clip <= 0 before it reaches Ogre: BaseCamera::
# SetNearClipPlane logs "Near clip distance must be a finite number greater than 0." and
# returns, keeping the near clip it had, 0.01 m (gazebosim/gz-rendering@gz-rendering10
# af28689:include/gz/rendering/base/BaseCamera.hh:731-740, default `nearClip = 0.01` at :227;
# added by gazebosim/gz-rendering#1082, 1f4def6). Ogre2GpuRays does not override it. Harmonic's
# gz-rendering8 (ff0c5b8: :724-727) and Fortress's ign-rendering6 (c39b130: :699-702) store 0.
# By target: the near clip in metres a requested 0 leaves.
GZ_NEAR_CLIP_KEPT: dict[str, float] = {"jetty": 0.01}


# sdformat's defaults for the values a <lens><intrinsics> or <lens><projection> block leaves
# out. sdf::Camera::Load reads each with `Get<double>(tag, current)` once the block is there
# (gazebosim/sdformat@sdf14 8512585:src/Camera.cc:421-435 intrinsics, :437-452 projection;
# @sdf12 b9417e5 (Fortress) and @sdf13 31bbc9b: :419-433, :435-450), and Element::Get falls
# back to the element description's default for a child that is not written
# (@sdf14:include/sdf/Element.hh:1075-1077, `else if (this->HasElementDescription(_key))
# result.first = this->ElementDescription(_key)->Get<T>(_errors)`); the parser also adds the required intrinsics children with their
# defaults (@sdf14:src/parser.cc:2046-2076). Those defaults: @sdf12, @sdf13 and @sdf14
# sdf/1.9/camera.sdf:181-193 (fx 277, fy 277, cx 160, cy 120, s 0, required="1") and
# :200-215 (p_fx 277, p_fy 277, p_cx 160, p_cy 120, tx 0, ty 0, required="0"); the private
# members start with the same numbers (@sdf14:src/Camera.cc:181-208). gz-sensors then renders
# with them and publishes them: camera_info K from LensIntrinsics*, P from LensProjection*
# (gazebosim/gz-sensors@gz-sensors8 c8159af:src/CameraSensor.cc:729-735 K, :744-752 P); the
# render projection is built from <intrinsics> (:858-873), then from <projection> (:898-914);
# the same on @ign-sensors6 7cfaddf (Fortress: Load :257-271, :309-325; K :740-746, P :755-763)
# and @gz-sensors10 ff8c92b (Jetty: P :679-687, render :783, :824; sdformat@sdf16 9a26f90:
# src/Camera.cc:411-441, sdf/1.9/camera.sdf:181-209 the same defaults).
# Gazebo Classic (sdformat9) reads the same intrinsics defaults (@sdf9:sdf/1.7/camera.sdf:
# 146-158) through `sdfIntrinsics->Get<double>("fx")` and renders with them
# (elysia-best/gazebo-classic@debian/11.10.2+dfsg-1:gazebo/rendering/Camera.cc:194-210,
# Camera::LoadCameraIntrinsics); it never reads <lens><projection> (no "projection" or "p_fx"
# element is read anywhere under gazebo/).
SDF_LENS_INTRINSICS_DEFAULTS: dict[str, float] = {
    "fx": 277.0,
    "fy": 277.0,
    "cx": 160.0,
    "cy": 120.0,
    "s": 0.0,
}
SDF_LENS_PROJECTION_DEFAULTS: dict[str, float] = {
    "p_fx": 277.0,
    "p_fy": 277.0,
    "p_cx": 160.0,
    "p_cy": 120.0,
    "tx": 0.0,
    "ty": 0.0,
}
# The values whose default makes a wrong camera: focal lengths and principal point (a left-out
# skew, tx or ty is 0, which is what a mono camera or a left eye means).
LENS_DEFAULTED_TAGS: dict[str, tuple[str, ...]] = {
    "intrinsics": ("fx", "fy", "cx", "cy"),
    "projection": ("p_fx", "p_fy", "p_cx", "p_cy"),
}
# Which <lens> blocks each simulator reads (sources above).
LENS_BLOCKS_READ: dict[str, tuple[str, ...]] = {
    "gz": ("intrinsics", "projection"),
    "classic": ("intrinsics",),
}


def lens_block_values(block: str, written: dict[str, float]) -> dict[str, float]:
    """Every value of a written ``<lens>`` block (``"intrinsics"`` or ``"projection"``, keyed by
    its SDF tags) as sdformat loads it: the written ones, sdformat's default for the rest."""
    defaults = (
        SDF_LENS_INTRINSICS_DEFAULTS if block == "intrinsics" else SDF_LENS_PROJECTION_DEFAULTS
    )
    return {tag: written.get(tag, default) for tag, default in defaults.items()}


# The gz message type a Gazebo Sim sensor advertises on each of its topics, in the order
# sensorkit.lint.rules.topic_names.gz_topics lists them (SK615). Read in gz-sensors
# (gazebosim/gz-sensors@gz-sensors8 c8159af; ign-sensors6 7cfaddf the same types):
# - camera: Image on the topic (src/CameraSensor.cc:395; ign-sensors6 :385), CameraInfo on
#   camera_info (:685; :696);
# - depth camera: Image on the topic (src/DepthCameraSensor.cc:274; :301), PointCloudPacked
#   on TOPIC/points (:302; :344), CameraInfo (CameraSensor::AdvertiseInfo, :297);
# - rgbd camera: Image on TOPIC/image and TOPIC/depth_image (src/RgbdCameraSensor.cc:201,
#   :215; :210, :224), PointCloudPacked on TOPIC/points (:229; :238), CameraInfo on
#   TOPIC/camera_info (:252);
# - gpu lidar: LaserScan on the topic (src/Lidar.cc:130; :129), PointCloudPacked on
#   TOPIC/points (src/GpuLidarSensor.cc:151-155; :153);
# - imu: IMU (src/ImuSensor.cc:142; :140); navsat: NavSat (src/NavSatSensor.cc:111; :98);
#   magnetometer: Magnetometer (src/MagnetometerSensor.cc:108; :107); altimeter: Altimeter
#   (src/AltimeterSensor.cc:106; :105); air_pressure: FluidPressure
#   (src/AirPressureSensor.cc:117; :116).
_CAMERA_MSGS = ("Image", "CameraInfo")
_DEPTH_MSGS = ("Image", "PointCloudPacked", "CameraInfo")
_RGBD_MSGS = ("Image", "Image", "PointCloudPacked", "CameraInfo")
_LIDAR_MSGS = ("LaserScan", "PointCloudPacked")
# Segmentation and bounding-box cameras publish on topics of their own, not TOPIC and a
# sibling camera_info (issue 35 item 8):
# - SegmentationCameraSensor: Image on TOPIC/colored_map and TOPIC/labels_map, CameraInfo on
#   TOPIC/camera_info, a child, not a sibling (gazebosim/gz-sensors@gz-sensors8 c8159af:
#   src/SegmentationCameraSensor.cc:78-81 suffixes, :197-213 advertised, :238 camera_info;
#   @gz-sensors10 ff8c92b the same lines; @ign-sensors6 7cfaddf :76-79, :196-211, :225);
# - BoundingBoxCameraSensor: the boxes on TOPIC (AnnotatedOriented3DBox_V for <box_type> 3d,
#   else AnnotatedAxisAligned2DBox_V), Image on TOPIC + "_image" (gz-sensors8
#   src/BoundingBoxCameraSensor.cc:190-212; box types :150-165; ign-sensors6 :183-207), and
#   CameraInfo as a sibling "camera_info" (AdvertiseInfo() with no topic, :237).
# With no <topic>, gz-sim names them scopedName + "/segmentation" and "/boundingbox"
# (gazebosim/gz-sim@gz-sim8 b81e26d:src/rendering/RenderUtil.cc:1742-1743, :1723-1725;
# @ign-gazebo6 aab5556 :1692-1693; @gz-sim10 ccd6694 :1742-1743). sdformat reads
# "segmentation" and "boundingbox" as the same types (@sdf14 8512585:src/Sensor.cc:315-324).
# ros_gz_bridge pairs the boxes with vision_msgs Detection2DArray / Detection3DArray
# (gazebosim/ros_gz@humble 5cc92f8:ros_gz_bridge/ros_gz_bridge/mappings.py:111,113; @jazzy
# 739cb42 :114,116).
GZ_SEGMENTATION_TYPES = frozenset({"segmentation_camera", "segmentation"})
GZ_BOUNDINGBOX_TYPES = frozenset({"boundingbox_camera", "boundingbox"})
GZ_TYPE_DEFAULT_SUFFIX: dict[str, str] = {
    **dict.fromkeys(GZ_SEGMENTATION_TYPES, "/segmentation"),
    **dict.fromkeys(GZ_BOUNDINGBOX_TYPES, "/boundingbox"),
}


def gz_boxes_msg(box_type: str | None) -> str:
    """The gz message a bounding-box camera publishes its boxes in, by <box_type>
    (sdformat's default is "2d")."""
    return "AnnotatedOriented3DBox_V" if (box_type or "").strip() == "3d" else "AnnotatedAxisAligned2DBox_V"


def gz_own_subtopics(stype: str, base: str, box_type: str | None = None) -> list[tuple[str, str, str]]:
    """``(gz topic, role, gz message)`` of a segmentation or bounding-box camera publishing
    under ``base`` (its <topic>, or scoped name and suffix); empty for any other type."""
    if stype in GZ_SEGMENTATION_TYPES:
        return [
            (f"{base}/colored_map", "colored_map", "Image"),
            (f"{base}/labels_map", "labels_map", "Image"),
            (f"{base}/camera_info", "camera_info", "CameraInfo"),
        ]
    if stype in GZ_BOUNDINGBOX_TYPES:
        parts = [p for p in base.split("/")[:-1] if p]  # CameraSensor::AdvertiseInfo's sibling
        info = ("/" if base.startswith("/") else "") + "/".join([*parts, "camera_info"])
        return [
            (base, "boxes", gz_boxes_msg(box_type)),
            (f"{base}_image", "image", "Image"),
            (info, "camera_info", "CameraInfo"),
        ]
    return []


GZ_SENSOR_TOPIC_MSGS: dict[str, tuple[str, ...]] = {
    "camera": _CAMERA_MSGS,
    "depth_camera": _DEPTH_MSGS,
    "depth": _DEPTH_MSGS,
    "rgbd_camera": _RGBD_MSGS,
    "rgbd": _RGBD_MSGS,
    "gpu_lidar": _LIDAR_MSGS,
    "gpu_ray": _LIDAR_MSGS,
    "imu": ("IMU",),
    "navsat": ("NavSat",),
    "magnetometer": ("Magnetometer",),
    "altimeter": ("Altimeter",),
    "air_pressure": ("FluidPressure",),
}

# The ROS types ros_gz_bridge pairs with each of those gz types (gazebosim/ros_gz@jazzy
# 739cb42:ros_gz_bridge/README.md:28 GPSFix-NavSat, :32 Altimeter, :50 CameraInfo,
# :51 FluidPressure, :52 Image, :53 Imu-IMU, :56 LaserScan, :57 MagneticField-Magnetometer,
# :58 NavSatFix-NavSat, :59 PointCloud2-PointCloudPacked; humble 5cc92f8 README.md:35-65
# the same pairs, spelled ignition::msgs). Written without "/msg/" for comparison.
GZ_TO_ROS_TYPES: dict[str, frozenset[str]] = {
    "Image": frozenset({"sensor_msgs/Image"}),
    "CameraInfo": frozenset({"sensor_msgs/CameraInfo"}),
    "PointCloudPacked": frozenset({"sensor_msgs/PointCloud2"}),
    "LaserScan": frozenset({"sensor_msgs/LaserScan"}),
    "IMU": frozenset({"sensor_msgs/Imu"}),
    "NavSat": frozenset({"sensor_msgs/NavSatFix", "gps_msgs/GPSFix"}),
    "Magnetometer": frozenset({"sensor_msgs/MagneticField"}),
    "FluidPressure": frozenset({"sensor_msgs/FluidPressure"}),
    "Altimeter": frozenset({"ros_gz_interfaces/Altimeter"}),
    "AnnotatedAxisAligned2DBox_V": frozenset({"vision_msgs/Detection2DArray"}),
    "AnnotatedOriented3DBox_V": frozenset({"vision_msgs/Detection3DArray"}),
}

# A subscriber of another type gets nothing: gz-transport runs a subscription's callback
# only when its type is the published message's type (or the generic one)
# (gazebosim/gz-transport@gz-transport13 e57e131e:src/NodeShared.cc:601-602, the same at
# :574-575 for raw handlers; ign-transport11 2edc82f8 :608-609, gz-transport14 f1a871e1
# :601). ros_gz_bridge subscribes with the gz type of the entry, so an entry whose types do
# not match what the sensor publishes carries nothing.


def gz_msg_name(gz_type: str) -> str:
    """``gz.msgs.Image``, ``ignition.msgs.Image``, ``ignition::msgs::Image`` -> ``Image``."""
    return gz_type.replace("::", ".").rsplit(".", 1)[-1]


def ros_msg_name(ros_type: str) -> str:
    """``sensor_msgs/msg/Image`` -> ``sensor_msgs/Image`` (the ROS 1 spelling)."""
    return ros_type.strip().replace("/msg/", "/")


# The Sensors system renders. Only it enables sensor creation in gz-sim's RenderUtil
# (gazebosim/gz-sim@gz-sim8_8.14.0:src/systems/sensors/Sensors.cc:808-810, the one
# SetEnableSensors(true, ...) in src/; @ignition-gazebo6_6.16.0: :526), and its CreateSensor
# makes the gz-sensors object of each rendering type (gz-sim8 Sensors.cc:1119-1169: CAMERA,
# DEPTH_CAMERA, GPU_LIDAR, RGBD_CAMERA, THERMAL_CAMERA, BOUNDINGBOX_CAMERA,
# SEGMENTATION_CAMERA, WIDE_ANGLE_CAMERA; ign-gazebo6 :777-812 the same but the wide angle
# camera). Without it these sensors are entities with no sensor behind them: no image, no
# scan. The SDF type strings that parse as those types:
# gazebosim/sdformat@sdformat14_14.9.0:src/Sensor.cc:279-352.
GZ_RENDERING_SENSOR_TYPES = frozenset(
    {
        "camera",
        "depth", "depth_camera",
        "rgbd", "rgbd_camera",
        "thermal", "thermal_camera",
        "segmentation", "segmentation_camera",
        "boundingbox", "boundingbox_camera",
        "wideanglecamera", "wide_angle_camera",
        "gpu_ray", "gpu_lidar",
    }
)  # fmt: skip
GZ_SENSORS_SYSTEM_SOURCE = {
    "fortress": "gazebosim/gz-sim@ignition-gazebo6_6.16.0:src/systems/sensors/Sensors.cc:526, 777-812",
    "harmonic": "gazebosim/gz-sim@gz-sim8_8.14.0:src/systems/sensors/Sensors.cc:808-810, 1119-1169",
    "jetty": "gazebosim/gz-sim@gz-sim10_10.4.0:src/systems/sensors/Sensors.cc:808-810, 1119-1169",
}
# Its library and class, any spelling a release loads: gz-sim maps ignition-gazebo to gz-sim
# (gz-sim8 src/SystemLoader.cc:67-75) and Fortress gz-sim to ignition-gazebo from 6.16
# (ign-gazebo6 src/SystemLoader.cc:73-79); installed names carry the major version
# (libgz-sim8-sensors-system.so); the class is registered under both names (ign-gazebo6
# Sensors.cc:1034-1037, gz-sim8 :1371).
GZ_SENSORS_SYSTEM_FILE = re.compile(r"^(lib)?(gz-sim|ignition-gazebo)\d*-sensors-system(\.so)?$")
GZ_SENSORS_SYSTEM_CLASS = re.compile(r"^(gz::sim|ignition::gazebo)::systems::Sensors$")
# When a world lists no <plugin> that loads, gz-sim loads the default server.config
# (gz-sim8 src/SimulationRunner.cc:1762-1769, src/ServerConfig.cc:971-1010;
# ign-gazebo6 src/SimulationRunner.cc:199-206), which as installed holds Physics,
# UserCommands and SceneBroadcaster, not Sensors (gz-sim8 include/gz/sim/server.config),
# but a user may have edited it (~/.gz/sim/<N>/server.config): only a world that lists
# systems is judged.


def gz_sensors_system_line(target: str) -> str:
    """The world <plugin> line of the Sensors system for ``target`` (Fortress spells it
    ignition-gazebo; render_engine ogre2 is the default, Sensors.cc:700-701)."""
    if target == "fortress":
        lib, cls = "ignition-gazebo-sensors-system", "ignition::gazebo::systems::Sensors"
    else:
        lib, cls = "gz-sim-sensors-system", "gz::sim::systems::Sensors"
    return (
        f'<plugin filename="{lib}" name="{cls}"><render_engine>ogre2</render_engine></plugin>'
    )
