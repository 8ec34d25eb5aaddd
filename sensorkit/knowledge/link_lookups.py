"""Model-level plugins that look up a link or joint by the name a parameter holds, and stop
(publishing nothing) when Gazebo has none of that name.

Gazebo Classic builds a URDF's model after fixed-joint lumping (sdformat's parser_urdf.cc):
a link that hangs on a fixed joint is merged into its parent and the joint goes, so a plugin
that asks the model (or the world) for that link or joint by name gets nothing. SK616
(sensorkit.lint.rules.model_plugins) applies this table to a robot; sensorkit.model.sdf's
``Conversion`` says which links lumping merged.

Every entry cites the lines that read the parameter, look the name up and return.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["LINK_LOOKUPS", "LinkLookup", "lookups_of"]

GRP_NOETIC = "ros-simulation/gazebo_ros_pkgs@noetic-devel f9e1a46"
GRP_ROS2 = "ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4"
HECTOR = "tu-darmstadt-ros-pkg/hector_gazebo@melodic-devel de947fb"


@dataclass(frozen=True)
class LinkLookup:
    """A parameter of a plugin naming a link (``kind`` "link") or joint ("joint") that the
    plugin looks up at load, and returns without publishing when it is not found."""

    library: str  # library base name: libgazebo_ros_imu.so -> gazebo_ros_imu
    ros: str  # "ros1" (target ros1) or "ros2" (target classic)
    param: str
    kind: str  # "link" or "joint"
    publishes: str  # what the plugin would publish, in words
    source: str  # repo@ref:path:lines
    unless: str | None = None  # a parameter whose presence means this one is not read


LINK_LOOKUPS: tuple[LinkLookup, ...] = (
    LinkLookup(
        "gazebo_ros_imu",
        "ros1",
        "bodyName",
        "link",
        "IMU data",
        # world_->EntityByName(link_name_); "bodyName: %s does not exist" and return
        f"{GRP_NOETIC}:gazebo_plugins/src/gazebo_ros_imu.cpp:151-162",
    ),
    LinkLookup(
        "gazebo_ros_p3d",
        "ros1",
        "bodyName",
        "link",
        "ground-truth odometry",
        # _parent->GetLink(link_name_); "bodyName: %s does not exist" and return
        f"{GRP_NOETIC}:gazebo_plugins/src/gazebo_ros_p3d.cpp:73-79",
    ),
    LinkLookup(
        "gazebo_ros_p3d",
        "ros1",
        "frameName",
        "link",
        "ground-truth odometry",
        # a frameName other than world/map: GetLink(frame_name_); "does not exist, will not
        # publish pose" and return from Load, before the update is connected
        f"{GRP_NOETIC}:gazebo_plugins/src/gazebo_ros_p3d.cpp:171-184",
    ),
    LinkLookup(
        "gazebo_ros_f3d",
        "ros1",
        "bodyName",
        "link",
        "the force on the link",
        f"{GRP_NOETIC}:gazebo_plugins/src/gazebo_ros_f3d.cpp:74-79",
    ),
    LinkLookup(
        "gazebo_ros_ft_sensor",
        "ros1",
        "jointName",
        "joint",
        "force-torque data",
        f"{GRP_NOETIC}:gazebo_plugins/src/gazebo_ros_ft_sensor.cpp:75-80",
    ),
    # hector_gazebo_plugins (ROS 1): bodyName looked up with _model->GetLink, else the
    # model's canonical link; "bodyName: %s does not exist" and return
    LinkLookup(
        "hector_gazebo_ros_imu",
        "ros1",
        "bodyName",
        "link",
        "IMU data",
        f"{HECTOR}:hector_gazebo_plugins/src/gazebo_ros_imu.cpp:80-96",
    ),
    LinkLookup(
        "hector_gazebo_ros_gps",
        "ros1",
        "bodyName",
        "link",
        "GPS fixes",
        f"{HECTOR}:hector_gazebo_plugins/src/gazebo_ros_gps.cpp:75-89",
    ),
    LinkLookup(
        "hector_gazebo_ros_magnetic",
        "ros1",
        "bodyName",
        "link",
        "magnetic field data",
        f"{HECTOR}:hector_gazebo_plugins/src/gazebo_ros_magnetic.cpp:75-90",
    ),
    LinkLookup(
        "gazebo_ros_p3d",
        "ros2",
        "body_name",
        "link",
        "ground-truth odometry",
        # model->GetLink(link_name); "body_name: %s does not exist" and return
        f"{GRP_ROS2}:gazebo_plugins/src/gazebo_ros_p3d.cpp:118-124",
    ),
    LinkLookup(
        "gazebo_ros_ft_sensor",
        "ros2",
        "body_name",
        "link",
        "force-torque data",
        # _model->GetLink(link_name); "Link [%s] does not exist. Aborting" and return
        f"{GRP_ROS2}:gazebo_plugins/src/gazebo_ros_ft_sensor.cpp:115-126",
    ),
    LinkLookup(
        "gazebo_ros_ft_sensor",
        "ros2",
        "joint_name",
        "joint",
        "force-torque data",
        # read only without <body_name>: _model->GetJoint(joint_name); "Joint [%s] does not
        # exist. Aborting" and return
        f"{GRP_ROS2}:gazebo_plugins/src/gazebo_ros_ft_sensor.cpp:129-140",
        unless="body_name",
    ),
)


def lookups_of(filename_or_library: str, ros: str) -> list[LinkLookup]:
    """The name lookups of a plugin library for ``ros`` ("ros1" or "ros2")."""
    base = filename_or_library.rsplit("/", 1)[-1]
    base = base[3:] if base.startswith("lib") else base
    base = base[:-3] if base.endswith(".so") else base
    return [x for x in LINK_LOOKUPS if x.library == base and x.ros == ros]
