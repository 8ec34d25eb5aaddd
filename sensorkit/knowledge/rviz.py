"""RViz2 facts consulted by ``sensorkit new`` when it writes ``rviz/<robot>.rviz``.

Which display of rviz_default_plugins shows which message type: each ``<class>`` of
ros2/rviz ``rviz_default_plugins/plugins_description.xml`` names the ``<message_type>`` it
shows (@humble 9b35482: Image :103-112, LaserScan :125-134, PointCloud :146-155,
PointCloud2 :157-166, Range :201-210). No class there shows ``sensor_msgs/msg/Imu`` on any
branch (humble, jazzy 591594e, rolling f7112b1); a CameraInfo display
(``rviz_default_plugins/CameraInfo``, @jazzy :49-58) exists from Jazzy on only (ros2/rviz#1166,
commit 4ad1eba), not in Humble, the ROS 2 of Gazebo Classic and Fortress.

Quality of service. RViz2's ``Reliability Policy`` of a topic is the subscription's; a best
effort subscription receives from reliable and best-effort publishers alike, a reliable one
from reliable publishers only (the QoS compatibility table of
https://docs.ros.org/en/jazzy/Concepts/Intermediate/About-Quality-of-Service-Settings.html).
Simulated sensors publish reliable by default, but both
simulators let a user override that:

- Gazebo Classic: gazebo_ros_camera creates its image, camera_info and depth image publishers
  with ``rclcpp::SensorDataQoS().reliable()`` and its depth camera_info and points with
  ``rclcpp::QoS(1)`` (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:
  gazebo_plugins/src/gazebo_ros_camera.cpp:189-191, :202-204, :243-245, :253-254, :262-263);
  gazebo_ros_ray_sensor and gazebo_ros_imu_sensor ``SensorDataQoS().reliable()``
  (gazebo_ros_ray_sensor.cpp:110, gazebo_ros_imu_sensor.cpp:95-96). Each goes through
  ``gazebo_ros::QoS::get_publisher_qos``, which applies the ``<ros><qos>`` overrides of the
  plugin's SDF (gazebo_ros/include/gazebo_ros/qos.hpp:137-143).
- Gazebo Sim: ros_gz_bridge publishes to ROS with ``rclcpp::QoS(rclcpp::KeepLast(queue_size))``,
  reliable and volatile, and allows overriding depth, durability, history and reliability
  (gazebosim/ros_gz@humble 5cc92f8:ros_gz_bridge/src/factory.hpp:46-64; @jazzy 739cb42:
  factory.hpp:59-79).

So every sensor display subscribes best effort, volatile, keep last 5 (RViz2's default depth,
``qos_profile(5)`` in rviz_common/include/rviz_common/ros_topic_display.hpp@humble:72-74).

The robot model: robot_state_publisher publishes ``robot_description`` with
``rclcpp::QoS(1).transient_local()`` (ros/robot_state_publisher@01a7be1:
src/robot_state_publisher.cpp, the ``description_pub_``), and RViz2's RobotModel display
subscribes transient local by default (rviz_default_plugins/src/rviz_default_plugins/
displays/robot_model/robot_model_display.cpp@humble:138), so a late RViz still gets it.
"""

from __future__ import annotations

# ROS 2 message type -> the rviz_default_plugins display class that shows it.
RVIZ_DISPLAYS: dict[str, str] = {
    "sensor_msgs/msg/Image": "rviz_default_plugins/Image",
    "sensor_msgs/msg/LaserScan": "rviz_default_plugins/LaserScan",
    "sensor_msgs/msg/PointCloud2": "rviz_default_plugins/PointCloud2",
    "sensor_msgs/msg/PointCloud": "rviz_default_plugins/PointCloud",
    "sensor_msgs/msg/Range": "rviz_default_plugins/Range",
}

# Message types a sensor may publish that get no display, with why.
NO_RVIZ_DISPLAY: dict[str, str] = {
    "sensor_msgs/msg/Imu": (
        "rviz_default_plugins has no Imu display (imu_tools' rviz_imu_plugin has one)"
    ),
    "sensor_msgs/msg/CameraInfo": (
        "rviz_default_plugins has a CameraInfo display from Jazzy on only, none on Humble; "
        "the Image display shows the picture"
    ),
}

# The QoS of every sensor display (see the module docstring).
SENSOR_QOS: dict[str, str | int] = {
    "Depth": 5,
    "Durability Policy": "Volatile",
    "History Policy": "Keep Last",
    "Reliability Policy": "Best Effort",
}
# robot_state_publisher's robot_description: one message, kept for late subscribers.
DESCRIPTION_QOS: dict[str, str | int] = {
    "Depth": 1,
    "Durability Policy": "Transient Local",
    "History Policy": "Keep Last",
    "Reliability Policy": "Reliable",
}
