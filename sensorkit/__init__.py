"""sensorkit: correct-by-construction sensors for URDF/xacro robots on ROS 2 and Gazebo."""

__version__ = "0.1.0"
