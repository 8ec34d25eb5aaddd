"""Recordings written for the tests with rosbags' own writers, in the three formats.

What goes into them is written here, from the simulators' source formulas and the
description's own joint origins, never from sensorkit's prediction code: a prediction
that went wrong would then disagree with the recording and fail the test.

The example car (examples/orbslam3_car, Gazebo Classic + ROS 2) as it records:

- camera_info of gazebo_ros_camera: fx = fy = W / (2 tan(hfov / 2)), cx = (W + 1) / 2,
  cy = (H + 1) / 2, D = 5 zeros, plumb_bob, R = I, P = [fx 0 cx -fx*hack_baseline;
  0 fy cy 0; 0 0 1 0] (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/
  gazebo_ros_camera.cpp:360-369 cx, cy and the focal length, :389-392 frame, size and
  model, :420-433 D and K, :455-466 P);
- images: R8G8B8 is rgb8 with step 3 W (gazebo_ros_camera.cpp:303-305, :598), the depth
  image 32FC1 with step 4 W (:660-667), the cloud x y z rgb FLOAT32 at 0, 4, 8, 16
  (:481-497); every header is stamped with the plugin's frame_name (:389, :499, :592, :661);
- LaserScan of gazebo_ros_ray_sensor: angle_min/max the SDF's, angle_increment
  (max - min) / (N - 1) with N = samples * resolution, range_min/max the SDF's, N ranges
  (gazebo_ros_pkgs@ros2 d52f7c4:gazebo_ros/include/gazebo_ros/conversions/sensor_msgs.hpp:
  62-81 copies Gazebo's scan; gazebosim/gazebo-classic@00f8300:gazebo/sensors/RaySensor.cc:
  171-175 the angle step, :190-196 the range count);
- /tf_static: robot_state_publisher's fixed joints, with the origins the car's URDF writes.
"""

from __future__ import annotations

import math
import shutil
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

FORMATS = ("ros1", "sqlite3", "mcap")

# REP 103 optical frame from the body frame: rpy (-pi/2, 0, -pi/2) as a quaternion
# (x, y, z, w); test_recording checks it maps optical z onto body x.
OPTICAL_Q = (-0.5, 0.5, -0.5, 0.5)
IDENTITY_Q = (0.0, 0.0, 0.0, 1.0)

T0 = 12 * 10**9  # the first stamp: sim time 12 s


def classic_camera_info(
    width: int, height: int, hfov: float, baseline: float = 0.0
) -> dict[str, Any]:
    """gazebo_ros_camera's camera_info (see the module docstring for the lines)."""
    f = width / (2.0 * math.tan(hfov / 2.0))
    cx, cy = (width + 1.0) / 2.0, (height + 1.0) / 2.0
    return {
        "width": width,
        "height": height,
        "distortion_model": "plumb_bob",
        "d": [0.0] * 5,
        "k": [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0],
        "r": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        "p": [f, 0.0, cx, -f * baseline, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0],
    }


def classic_scan(
    samples: int, resolution: float, lo: float, hi: float, rmin: float, rmax: float
) -> dict[str, Any]:
    """gazebo_ros_ray_sensor's LaserScan (see the module docstring for the lines)."""
    n = int(samples * resolution)
    return {
        "angle_min": lo,
        "angle_max": hi,
        "angle_increment": (hi - lo) / (n - 1),
        "time_increment": 0.0,
        "scan_time": 0.0,
        "range_min": rmin,
        "range_max": rmax,
        "ranges": [rmax] * n,
    }


@dataclass
class Stream:
    """One topic: its type, frame, rate and what each message holds."""

    msgtype: str
    frame: str
    rate: float
    fields: dict[str, Any]
    count: int = 8


@dataclass
class Scene:
    """A whole recording: topics and the static transforms (parent, child, xyz, q)."""

    streams: dict[str, Stream]
    tf_static: list[
        tuple[str, str, tuple[float, float, float], tuple[float, float, float, float]]
    ] = field(default_factory=list)

    def with_stream(self, topic: str, **changes: Any) -> Scene:
        streams = dict(self.streams)
        streams[topic] = replace(streams[topic], **changes)
        return Scene(streams, list(self.tf_static))

    def with_fields(self, topic: str, **changes: Any) -> Scene:
        return self.with_stream(topic, fields={**self.streams[topic].fields, **changes})

    def without(self, topic: str) -> Scene:
        return Scene({k: v for k, v in self.streams.items() if k != topic}, list(self.tf_static))

    def with_tf(
        self, child: str, xyz: tuple[float, float, float], q: tuple[float, float, float, float]
    ) -> Scene:
        tf = [(p, c, xyz, q) if c == child else (p, c, x, r) for p, c, x, r in self.tf_static]
        return Scene(dict(self.streams), tf)


def car_scene() -> Scene:
    """The example car recorded in Gazebo Classic: its values from the URDF's call of the
    macros (640x480, hfov 2.0, 30 Hz; 360 samples from -pi to pi, 0.15-12 m, 10 Hz) put
    through the simulators' formulas above."""
    w, h = 640, 480
    info = classic_camera_info(w, h, 2.0)
    opt = "camera_optical_frame"
    image = {"width": w, "height": h, "encoding": "rgb8", "step": 3 * w, "data_bytes": 3 * w * h}
    depth = {"width": w, "height": h, "encoding": "32FC1", "step": 4 * w, "data_bytes": 4 * w * h}
    cloud = {
        "width": w,
        "height": h,
        "fields": [("x", 0), ("y", 4), ("z", 8), ("rgb", 16)],
        "point_step": 32,
    }
    scan = classic_scan(360, 1.0, -math.pi, math.pi, 0.15, 12.0)
    streams = {
        "/camera/image_raw": Stream("sensor_msgs/msg/Image", opt, 30.0, image),
        "/camera/camera_info": Stream("sensor_msgs/msg/CameraInfo", opt, 30.0, info),
        "/camera/depth/image_raw": Stream("sensor_msgs/msg/Image", opt, 30.0, depth),
        "/camera/depth/camera_info": Stream("sensor_msgs/msg/CameraInfo", opt, 30.0, info),
        "/camera/points": Stream("sensor_msgs/msg/PointCloud2", opt, 30.0, cloud),
        "/lidar/scan": Stream("sensor_msgs/msg/LaserScan", "lidar_link", 10.0, scan),
    }
    tf = [  # the car's fixed joints, as its URDF writes them
        ("base_link", "chassis_link", (0.0, 0.0, 0.1), IDENTITY_Q),
        ("chassis_link", "camera_link", (0.4, 0.0, 0.0), IDENTITY_Q),
        ("camera_link", "camera_optical_frame", (0.0, 0.0, 0.0), OPTICAL_Q),
        ("chassis_link", "lidar_link", (0.0, 0.0, 0.075), IDENTITY_Q),
    ]
    return Scene(streams, tf)


# --------------------------------------------------------------------------- writing


def _typestore(ros1: bool) -> Any:
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    if not ros1:
        return get_typestore(Stores.ROS2_HUMBLE)
    ts = get_typestore(Stores.ROS1_NOETIC)
    ts.register(
        get_types_from_msg("geometry_msgs/TransformStamped[] transforms", "tf2_msgs/msg/TFMessage")
    )
    return ts


def _header(ts: Any, ros1: bool, stamp: int, frame: str) -> Any:
    Time = ts.types["builtin_interfaces/msg/Time"]
    Header = ts.types["std_msgs/msg/Header"]
    t = Time(sec=stamp // 10**9, nanosec=stamp % 10**9)
    return Header(seq=0, stamp=t, frame_id=frame) if ros1 else Header(stamp=t, frame_id=frame)


def _message(ts: Any, ros1: bool, s: Stream, stamp: int) -> Any:
    header = _header(ts, ros1, stamp, s.frame)
    f = s.fields
    T = ts.types[s.msgtype]
    if s.msgtype == "sensor_msgs/msg/Image":
        data = np.zeros(f["data_bytes"], dtype=np.uint8)
        return T(
            header=header,
            height=f["height"],
            width=f["width"],
            encoding=f["encoding"],
            is_bigendian=0,
            step=f["step"],
            data=data,
        )
    if s.msgtype == "sensor_msgs/msg/CameraInfo":
        roi = ts.types["sensor_msgs/msg/RegionOfInterest"](
            x_offset=0, y_offset=0, height=0, width=0, do_rectify=False
        )
        names = ("D", "K", "R", "P") if ros1 else ("d", "k", "r", "p")
        arrays = {n: np.array(f[n.lower()], dtype=np.float64) for n in names}
        return T(
            header=header,
            height=f["height"],
            width=f["width"],
            distortion_model=f["distortion_model"],
            binning_x=0,
            binning_y=0,
            roi=roi,
            **arrays,
        )
    if s.msgtype == "sensor_msgs/msg/LaserScan":
        ranges = np.array(f["ranges"], dtype=np.float32)
        keys = (
            "angle_min",
            "angle_max",
            "angle_increment",
            "time_increment",
            "scan_time",
            "range_min",
            "range_max",
        )
        return T(
            header=header,
            **{k: f[k] for k in keys},
            ranges=ranges,
            intensities=np.zeros(0, dtype=np.float32),
        )
    if s.msgtype == "sensor_msgs/msg/PointCloud2":
        # An empty data array: only the layout (fields, size) is what the tests look at.
        PF = ts.types["sensor_msgs/msg/PointField"]
        fields = [PF(name=n, offset=o, datatype=7, count=1) for n, o in f["fields"]]
        return T(
            header=header,
            height=f["height"],
            width=f["width"],
            fields=fields,
            is_bigendian=False,
            point_step=f["point_step"],
            row_step=f["point_step"] * f["width"],
            data=np.zeros(0, dtype=np.uint8),
            is_dense=True,
        )
    if s.msgtype == "sensor_msgs/msg/Imu":
        V = ts.types["geometry_msgs/msg/Vector3"]
        Q = ts.types["geometry_msgs/msg/Quaternion"]
        cov = np.zeros(9, dtype=np.float64)
        return T(
            header=header,
            orientation=Q(x=0.0, y=0.0, z=0.0, w=1.0),
            orientation_covariance=cov,
            angular_velocity=V(x=0.0, y=0.0, z=0.0),
            angular_velocity_covariance=cov,
            linear_acceleration=V(x=0.0, y=0.0, z=9.8),
            linear_acceleration_covariance=cov,
        )
    msg = f"no writer for {s.msgtype}"
    raise AssertionError(msg)


def _tf_message(ts: Any, ros1: bool, stamp: int, entries: list[Any]) -> Any:
    TS = ts.types["geometry_msgs/msg/TransformStamped"]
    Tr = ts.types["geometry_msgs/msg/Transform"]
    V = ts.types["geometry_msgs/msg/Vector3"]
    Q = ts.types["geometry_msgs/msg/Quaternion"]
    items = [
        TS(
            header=_header(ts, ros1, stamp, parent),
            child_frame_id=child,
            transform=Tr(
                translation=V(x=xyz[0], y=xyz[1], z=xyz[2]),
                rotation=Q(x=q[0], y=q[1], z=q[2], w=q[3]),
            ),
        )
        for parent, child, xyz, q in entries
    ]
    return ts.types["tf2_msgs/msg/TFMessage"](transforms=items)


def _records(scene: Scene) -> list[tuple[int, str, Stream | None]]:
    """(time, topic, stream) of every message, in time order; /tf_static first."""
    out: list[tuple[int, str, Stream | None]] = []
    if scene.tf_static:
        out.append((T0, "/tf_static", None))
    for topic, s in scene.streams.items():
        for i in range(s.count):
            out.append((T0 + round(i * 1e9 / s.rate), topic, s))
    out.sort(key=lambda r: (r[0], r[1]))
    return out


def write_bag(scene: Scene, path: Path, fmt: str, *, compress: bool = False) -> Path:
    """Write ``scene`` as ``fmt`` (ros1: ``path``.bag; sqlite3 or mcap: a rosbag2
    folder ``path``); returns the path to give sensorkit. ``compress``: MCAP's chunks
    compressed with zstd (rosbag2's "storage" compression)."""
    ros1 = fmt == "ros1"
    ts = _typestore(ros1)
    if ros1:
        from rosbags.rosbag1 import Writer as Writer1

        out = path.with_suffix(".bag")
        writer: Any = Writer1(out)
    else:
        from rosbags.rosbag2 import StoragePlugin, Writer

        out = path
        plugin = StoragePlugin.MCAP if fmt == "mcap" else StoragePlugin.SQLITE3
        writer = Writer(out, version=9, storage_plugin=plugin)
        if compress and fmt == "mcap":
            from rosbags.rosbag2 import CompressionFormat, CompressionMode

            writer.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
    serialize: Callable[[Any, str], Any] = ts.serialize_ros1 if ros1 else ts.serialize_cdr
    with writer:
        conns: dict[str, Any] = {}
        if scene.tf_static:
            conns["/tf_static"] = writer.add_connection(
                "/tf_static", "tf2_msgs/msg/TFMessage", typestore=ts
            )
        for topic, s in scene.streams.items():
            conns[topic] = writer.add_connection(topic, s.msgtype, typestore=ts)
        for stamp, topic, s in _records(scene):
            if s is None:
                msg = _tf_message(ts, ros1, stamp, scene.tf_static)
                writer.write(conns[topic], stamp, serialize(msg, "tf2_msgs/msg/TFMessage"))
            else:
                writer.write(
                    conns[topic], stamp, serialize(_message(ts, ros1, s, stamp), s.msgtype)
                )
    return out


def bare_mcap(folder: Path, dest: Path) -> Path:
    """The .mcap file of a rosbag2 folder, on its own (no metadata.yaml beside it)."""
    (mcap,) = folder.glob("*.mcap")
    shutil.copyfile(mcap, dest)
    return dest


# --------------------------------------------------------------------------- Gazebo Sim


def gz_camera_info(width: int, height: int, hfov: float) -> dict[str, Any]:
    """gz-sensors' camera_info, bridged by ros_gz_bridge: K from the lens intrinsics, which
    the sensorkit macros write as fx = fy = W / (2 tan(hfov / 2)), cx = W / 2, cy = H / 2
    (the values gz itself derives without them: gazebosim/gz-rendering@gz-rendering8
    ff0c5b8f:src/Utils.cc:170-185 projectionToCameraIntrinsic, called by gazebosim/
    gz-sensors@gz-sensors8 c8159af:src/CameraSensor.cc:844-856), K[1] = 0 (:729-738), P
    from the projection with tx = 0 (:740-756), D = k1 k2 p1 p2 k3 (:716-724), PLUMB_BOB
    bridged as "plumb_bob" (gazebosim/ros_gz@jazzy 739cb42:ros_gz_bridge/src/convert/
    sensor_msgs.cpp:230-231)."""
    f = width / (2.0 * math.tan(hfov / 2.0))
    cx, cy = width / 2.0, height / 2.0
    return {
        "width": width,
        "height": height,
        "distortion_model": "plumb_bob",
        "d": [0.0] * 5,
        "k": [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0],
        "r": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        "p": [f, 0.0, cx, 0.0, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0],
    }


def harmonic_scene() -> Scene:
    """The Harmonic example robot (examples/harmonic_robot) through its bridge.yaml: its
    values from the URDF's macro calls (a 1280x720 camera, hfov 1.5; a 640x480 RGB-D
    camera, hfov 1.0472, pitched 0.2 rad; a 900x16 gpu_lidar's cloud; an IMU at 100 Hz).
    The gpu_lidar's cloud has x y z intensity ring (gz-sensors@gz-sensors8
    c8159af:src/GpuLidarSensor.cc:138-141), the rgbd_camera's depth image is 32FC1 and its
    image rgb8 (src/RgbdCameraSensor.cc:525, :636; ros_gz_bridge sensor_msgs.cpp:126-160)."""
    w, h = 640, 480
    rgbd_opt, front_opt = "rgbd_camera_optical_frame", "front_camera_optical_frame"

    def image(width: int, height: int, encoding: str, depth: int) -> dict[str, Any]:
        step = depth * width
        return {
            "width": width,
            "height": height,
            "encoding": encoding,
            "step": step,
            "data_bytes": step * height,
        }

    cloud = {
        "width": 900,
        "height": 16,
        "fields": [("x", 0), ("y", 4), ("z", 8), ("intensity", 16), ("ring", 20)],
        "point_step": 32,
    }
    streams = {
        "/front_camera/image_raw": Stream(
            "sensor_msgs/msg/Image", front_opt, 30.0, image(1280, 720, "rgb8", 3)
        ),
        "/front_camera/camera_info": Stream(
            "sensor_msgs/msg/CameraInfo", front_opt, 30.0, gz_camera_info(1280, 720, 1.5)
        ),
        "/rgbd_camera/image_raw": Stream(
            "sensor_msgs/msg/Image", rgbd_opt, 30.0, image(w, h, "rgb8", 3)
        ),
        "/rgbd_camera/depth/image_raw": Stream(
            "sensor_msgs/msg/Image", rgbd_opt, 30.0, image(w, h, "32FC1", 4)
        ),
        "/rgbd_camera/camera_info": Stream(
            "sensor_msgs/msg/CameraInfo", rgbd_opt, 30.0, gz_camera_info(w, h, 1.0472)
        ),
        "/lidar/points": Stream("sensor_msgs/msg/PointCloud2", "lidar_link", 10.0, cloud),
        "/imu/imu": Stream("sensor_msgs/msg/Imu", "imu_link", 100.0, {}),
    }
    pitch = (0.0, math.sin(0.1), 0.0, math.cos(0.1))  # rpy 0 0.2 0
    tf = [  # the robot's sensor joints, as its URDF writes them
        ("base_link", "front_camera_link", (0.26, 0.0, 0.08), IDENTITY_Q),
        ("front_camera_link", front_opt, (0.0, 0.0, 0.0), OPTICAL_Q),
        ("base_link", "rgbd_camera_link", (0.22, 0.0, 0.15), pitch),
        ("rgbd_camera_link", rgbd_opt, (0.0, 0.0, 0.0), OPTICAL_Q),
        ("base_link", "lidar_link", (0.0, 0.0, 0.25), IDENTITY_Q),
        ("base_link", "imu_link", (0.0, 0.0, 0.02), IDENTITY_Q),
    ]
    return Scene(streams, tf)
