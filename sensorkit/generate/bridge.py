"""The ros_gz_bridge entries of a generated robot, read from what its xacro expands to.

No topic is written down twice: the macros say which gz topics they publish (their
``<topic>`` and ``<camera_info_topic>``), the drive plugins say theirs, and this module
reads them back from the expanded description. ROS names follow the Gazebo Classic
conventions of the same macros, so a robot publishes the same ROS topics on both
simulators:

- camera: ``<topic>`` (Image) and its camera_info topic (CameraInfo), same names;
- rgbd_camera ``X``: ``X/image`` -> ``X/image_raw``, ``X/depth_image`` ->
  ``X/depth/image_raw``, ``X/camera_info`` and ``X/points`` kept (one camera_info serves
  both images: the depth image is registered to the colour image);
- depth_camera: ``<topic>`` (depth Image), camera_info, ``<topic>/points``;
- 2D lidar (one vertical sample): ``<topic>`` (LaserScan) and ``<topic>/points``;
- 3D lidar ``X/scan``: ``X/scan/points`` -> ``X/points`` (PointCloud2). Its gz LaserScan
  holds every layer in one ranges array, which no ROS LaserScan consumer reads right, so
  it is not bridged;
- imu: ``<topic>`` (Imu);
- DiffDrive: cmd_vel (ROS_TO_GZ), odom, tf (to ``/tf``); JointStatePublisher:
  joint_states; and ``/clock`` always.
"""

from __future__ import annotations

from collections.abc import Iterable

from lxml import etree

from sensorkit.exporters.bridge import BridgeEntry, bridge_yaml, sensor_bridge_entries
from sensorkit.knowledge.gazebo_sim import GZ_READS_CAMERA_INFO_TOPIC, GZ_XFORWARD_CLOUD_TYPES

_SENSOR_TYPES = {
    "camera",
    "depth_camera",
    "depth",
    "rgbd_camera",
    "rgbd",
    "gpu_lidar",
    "gpu_ray",
    "imu",
}  # not ray/lidar/multicamera: gz-sim never creates them (sensorkit/knowledge/gazebo_sim.py)


def _msg_prefix(gz_version: str) -> str:
    return "ignition.msgs." if gz_version == "fortress" else "gz.msgs."


def _rel(topic: str) -> str:
    """gz-transport and a root-namespace ROS node read ``a/b`` and ``/a/b`` alike."""
    return topic.strip().strip("/")


def _text(el: etree._Element, path: str) -> str | None:
    found = el.find(path)
    text = None if found is None else found.text
    if text is None or not text.strip():
        return None
    return str(text).strip()


def _vertical_samples(sensor: etree._Element) -> int:
    for path in ("lidar/scan/vertical/samples", "ray/scan/vertical/samples"):
        text = _text(sensor, path)
        if text is not None:
            try:
                return int(float(text))
            except (ValueError, OverflowError):  # not a number, or inf
                return 1
    return 1


def published_entries(
    sensor: etree._Element, gz_version: str, topic: str | None = None
) -> list[BridgeEntry]:
    """Every gz topic an expanded ``<sensor>`` publishes, as GZ_TO_ROS entries whose ROS
    name is the gz name: what a bridge could carry, before :func:`sensor_entries` chooses.

    ``topic`` stands in for the sensor's ``<topic>`` (a sensor without one publishes under
    its scoped name); none and no ``<topic>``, or a type gz-sim does not create: empty.
    """
    stype = sensor.get("type") or ""
    topic = topic or _text(sensor, "topic")
    if stype not in _SENSOR_TYPES or topic is None:
        return []
    info_topic = (
        _text(sensor, "camera/camera_info_topic") if stype in GZ_READS_CAMERA_INFO_TOPIC else None
    )
    out: list[BridgeEntry] = []
    for entry in sensor_bridge_entries(stype, _rel(topic), gz_version=gz_version):
        gz_name = _rel(entry.gz_topic_name)
        if entry.ros_type_name.endswith("/CameraInfo") and info_topic is not None:
            gz_name = _rel(info_topic)
        out.append(entry._replace(gz_topic_name=gz_name, ros_topic_name=gz_name))
    return out


def sensor_entries(sensor: etree._Element, gz_version: str) -> list[BridgeEntry]:
    """GZ_TO_ROS entries for one expanded ``<sensor>`` (empty if it has no ``<topic>``)."""
    stype = sensor.get("type") or ""
    topic = _text(sensor, "topic")
    if topic is None:
        return []
    topic = _rel(topic)
    out: list[BridgeEntry] = []
    vertical = _vertical_samples(sensor)
    for entry in published_entries(sensor, gz_version):
        if stype in GZ_XFORWARD_CLOUD_TYPES and entry.ros_type_name.endswith("/PointCloud2"):
            continue  # x-forward cloud stamped optical: not bridged (see the file's header)
        gz_name = entry.gz_topic_name
        ros_name = gz_name
        kind = entry.ros_type_name
        if stype in ("rgbd_camera", "rgbd"):
            if gz_name == f"{topic}/image":
                ros_name = f"{topic}/image_raw"
            elif gz_name == f"{topic}/depth_image":
                ros_name = f"{topic}/depth/image_raw"
        if stype in ("gpu_lidar", "gpu_ray", "lidar", "ray") and vertical > 1:
            if kind.endswith("/LaserScan"):
                continue
            if topic.endswith("/scan"):
                ros_name = f"{topic[: -len('/scan')]}/points"
        out.append(entry._replace(ros_topic_name=ros_name))
    return out


def _plugin_entries(plugin: etree._Element, gz_version: str) -> list[BridgeEntry]:
    name = plugin.get("name") or ""
    prefix = _msg_prefix(gz_version)
    out: list[BridgeEntry] = []
    if name.endswith("::DiffDrive"):
        topic = _text(plugin, "topic")
        if topic:
            out.append(
                BridgeEntry(
                    _rel(topic),
                    _rel(topic),
                    "geometry_msgs/msg/Twist",
                    prefix + "Twist",
                    "ROS_TO_GZ",
                )
            )
        odom = _text(plugin, "odom_topic")
        if odom:
            out.append(
                BridgeEntry(
                    _rel(odom),
                    _rel(odom),
                    "nav_msgs/msg/Odometry",
                    prefix + "Odometry",
                    "GZ_TO_ROS",
                )
            )
        tf = _text(plugin, "tf_topic")
        if tf:
            out.append(
                BridgeEntry(
                    "/tf", _rel(tf), "tf2_msgs/msg/TFMessage", prefix + "Pose_V", "GZ_TO_ROS"
                )
            )
    elif name.endswith("::JointStatePublisher"):
        topic = _text(plugin, "topic")
        if topic:
            out.append(
                BridgeEntry(
                    _rel(topic),
                    _rel(topic),
                    "sensor_msgs/msg/JointState",
                    prefix + "Model",
                    "GZ_TO_ROS",
                )
            )
    return out


def bridge_entries(robot: etree._Element, gz_version: str) -> list[BridgeEntry]:
    """Every entry the expanded ``robot`` needs: ``/clock``, the drive, then each sensor."""
    prefix = _msg_prefix(gz_version)
    entries = [
        BridgeEntry("/clock", "/clock", "rosgraph_msgs/msg/Clock", prefix + "Clock", "GZ_TO_ROS")
    ]
    for gazebo in robot.iter("gazebo"):
        for plugin in gazebo.findall("plugin"):
            entries += _plugin_entries(plugin, gz_version)
    for gazebo in robot.iter("gazebo"):
        for sensor in gazebo.iter("sensor"):
            entries += sensor_entries(sensor, gz_version)
    return entries


CLOUD_HEADER = (
    "# Depth-camera clouds are not bridged: Gazebo Sim computes them x-forward but stamps\n"
    "# them with the optical frame (gz-sensors#488), so RViz would show them on their side.\n"
    "# Build them from the depth image and camera_info with depth_image_proc.\n"
)


def bridge_file_text(
    entries: Iterable[BridgeEntry], *, robot: str, gz_version: str, by: str = "sensorkit new"
) -> str:
    """The ``config/bridge.yaml`` text: a short header, then the entries."""
    header = (
        f"# ros_gz_bridge configuration for {robot} on Gazebo Sim ({gz_version}),\n"
        f"# written by {by} from the topics the robot description declares.\n"
        "#   ros2 run ros_gz_bridge parameter_bridge --ros-args -p config_file:=bridge.yaml\n"
        + CLOUD_HEADER
    )
    return header + bridge_yaml(entries)
