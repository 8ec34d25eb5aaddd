"""Targets: what the description will run on, and how ``auto`` picks one."""

from __future__ import annotations

from collections.abc import Container
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from sensorkit.model.robot import Robot
    from sensorkit.model.sensors import Plugin

TARGETS = ("classic", "ros1", "fortress", "harmonic", "jetty")
GZ_TARGETS = ("fortress", "harmonic", "jetty")
# Sensor types only Gazebo Sim creates ("lidar" is not one: gz-sim never creates it,
# see sensorkit/knowledge/gazebo_sim.py).
GZ_SENSOR_TYPES = {
    "gpu_lidar",
    "rgbd_camera",
    "depth_camera",
    "boundingbox_camera",
    "segmentation_camera",
}


def is_gz(target: str) -> bool:
    return target in GZ_TARGETS


def is_gz_plugin(filename: str) -> bool:
    base = filename.rsplit("/", 1)[-1]
    return base.startswith(
        (
            "gz-sim",
            "libgz-sim",
            "ignition-gazebo",
            "libignition-gazebo",
            "gz_ros2_control",
            "libgz_ros2_control",
            "ign_ros2_control",
            "libign_ros2_control",
        )
    )


def is_classic_plugin(filename: str) -> bool:
    base = filename.rsplit("/", 1)[-1]
    return base.startswith(("libgazebo_ros", "gazebo_ros", "libgazebo_plugins"))


# ROS 2-only parameters of gazebo_ros plugins (ROS 1 spells them in camelCase).
ROS2_PARAMS = frozenset(
    {
        "ros",
        "frame_name",
        "camera_name",
        "output_type",
        "hack_baseline",
        "min_depth",
        "max_depth",
        "odometry_frame",
        "robot_base_frame",
        "left_joint",
        "right_joint",
        "wheel_separation",
        "wheel_diameter",
        "publish_odom",
        "publish_odom_tf",
        "publish_wheel_tf",
        "max_wheel_torque",
        "max_wheel_acceleration",
        "body_name",
        "reference_link_name",
    }
)
ROS1_MIN_EVIDENCE = (
    3  # fewer ROS 1 tags than this are mistakes in a ROS 2 file, reported one by one
)


@dataclass
class Ros1Evidence:
    """What in a robot says ROS 1 (or ROS 2): the plugins and tags found."""

    plugins: list[str] = field(default_factory=list)  # ROS 1-only gazebo_ros plugins
    tags: list[str] = field(default_factory=list)  # ROS 1 parameter tags in gazebo_ros plugins
    ros2: list[str] = field(default_factory=list)  # anything only ROS 2 has

    @property
    def is_ros1(self) -> bool:
        return not self.ros2 and len(self.plugins) + len(self.tags) >= ROS1_MIN_EVIDENCE

    def describe(self) -> str:
        parts = []
        if self.plugins:
            parts.append(
                f"{len(self.plugins)} ROS 1-only plugin{'s' if len(self.plugins) > 1 else ''}"
            )
        if self.tags:
            parts.append(f"{len(self.tags)} ROS 1 tag{'s' if len(self.tags) > 1 else ''}")
        return ", ".join(parts)

    def tally_params(
        self, plugin: Plugin, ros1: Container[str], ros2: Container[str], where: str
    ) -> None:
        """Tally ``plugin``'s parameters: a tag in ``ros1`` under ``tags``, one in ``ros2``
        under ``ros2`` as ``where<tag>``."""
        from sensorkit.model.parse import local

        for el in plugin.param_elements():
            tag = local(el)
            if tag in ros1:
                self.tags.append(tag)
            elif tag in ros2:
                self.ros2.append(f"{where}<{tag}>")


def ros1_evidence(robot: Robot) -> Ros1Evidence:
    """What marks the description's gazebo_ros plugins as ROS 1 or ROS 2."""
    from sensorkit.knowledge.gazebo_ros import (
        ROS1_LIBRARIES,
        ROS1_ONLY,
        ROS1_TO_ROS2_PARAMS,
        ROS2_LIBRARIES,
        ROS2_ONLY,
    )
    from sensorkit.knowledge.plugins import generation_params
    from sensorkit.model.parse import local
    from sensorkit.model.robot import all_plugins

    out = Ros1Evidence()
    for p in all_plugins(robot):
        lib = p.library
        # A third-party plugin with a ROS 1 and a ROS 2 spec in sensorkit.knowledge.plugins:
        # the parameters only one generation's source reads say which one the file targets
        # (velodyne's ROS 1 plugin reads <topicName>/<frameName>, its ROS 2 port <ros> and
        # <frame_name>; the sources are cited on the specs).
        ros1_only, ros2_only = generation_params(p.filename)
        if ros1_only or ros2_only:
            out.tally_params(p, ros1_only, ros2_only, f"{p.filename} ")
            continue
        if not lib.startswith("gazebo_ros"):
            continue
        name = lib[len("gazebo_ros_") :] if lib.startswith("gazebo_ros_") else lib
        if lib == "gazebo_ros_control" or name in ROS1_ONLY:
            out.plugins.append(p.filename)
        elif name in ROS2_ONLY or lib == "gazebo_ros2_control":
            out.ros2.append(p.filename)
        if lib not in ROS1_LIBRARIES and lib not in ROS2_LIBRARIES:
            # A vendor's gazebo_ros_* plugin has parameters of its own (kobuki's
            # wheel_separation is ROS 1); only the <ros> block, gazebo_ros::Node's, says ROS 2.
            if any(local(el) == "ros" for el in p.param_elements()):
                out.ros2.append(f"{p.filename} <ros>")
            continue
        out.tally_params(p, ROS1_TO_ROS2_PARAMS, ROS2_PARAMS, "")
    return out


def detect_target(robot: Robot) -> tuple[str, str]:
    """(target, why) for ``--target auto``.

    Gazebo Sim evidence (gz/ignition system plugins, gz-only sensor types, gz frame tags)
    against Gazebo Classic evidence (gazebo_ros plugins); the larger wins, a tie or no
    evidence at all gives ``classic`` (ROS 2 with Gazebo Classic). ``ros1`` only for a
    description written wholly for ROS 1 (at least ``ROS1_MIN_EVIDENCE`` ROS 1 plugins or
    tags and nothing only ROS 2 has): SK611 then says so once, instead of one SK602 per
    tag; a ROS 2 file with a few ROS 1 tags stays ``classic`` and each tag is reported.
    A package.xml up from the file decides ROS 1 (``catkin``) or ROS 2 (``ament_*``) when
    Gazebo Sim does not win (sensorkit.loading.package_xml). Among gz versions: ``ignition_*`` names mean fortress, a sensor ``<frame_id>`` jetty,
    anything else harmonic. An SDF model with no evidence either way gives a gz target
    (harmonic): SDF with gazebo_ros plugins is a Gazebo Classic model, and says so.
    """
    from sensorkit.loading.package_xml import package_generation

    gz, classic, version = _evidence(robot)
    if len(gz) > len(classic):
        return version, f"auto: {gz[0]}"
    package = package_generation(robot.document.path)
    if package is not None and (classic or robot.sdf is None):
        # The package says which ROS the description is built for; the plugins and tags
        # only say it when nothing else does (macros copied from a ROS 2 package hold <ros>
        # blocks in a catkin package: issue 35). An SDF model with no Classic plugin keeps
        # its Gazebo Sim default (a catkin package may run Ignition: osrf/subt).
        target = "ros1" if package.ros == "ros1" else "classic"
        return target, f"auto: {package.why}" + (f"; {classic[0]}" if classic else "")
    if classic:
        ev = ros1_evidence(robot)
        if ev.is_ros1:
            return "ros1", f"auto: written for ROS 1 ({ev.describe()})"
        return "classic", f"auto: {classic[0]}"
    if robot.sdf is not None:  # SDF is Gazebo Sim's own format; Classic's plugins say Classic
        return version, "auto: an SDF model with no simulator-specific tags; assuming Gazebo Sim"
    return "classic", "auto: no simulator-specific tags; assuming ROS 2 with Gazebo Classic"


def _evidence(robot: Robot) -> tuple[list[str], list[str], str]:
    """(Gazebo Sim evidence, Gazebo Classic evidence, the gz version the former suggests)."""
    from sensorkit.model.robot import all_plugins

    gz: list[str] = []
    classic: list[str] = []
    fortress = jetty = False
    for p in all_plugins(robot):
        if is_gz_plugin(p.filename):
            gz.append(p.filename)
            fortress |= "ignition" in p.filename or "ign_" in p.filename
        elif is_classic_plugin(p.filename):
            classic.append(p.filename)
    for s in robot.sensors:
        if s.type in GZ_SENSOR_TYPES:
            gz.append(f"sensor type {s.type}")
        for tag in s.frame_tags:
            gz.append(f"<{tag}>")
            fortress |= tag == "ignition_frame_id"
            jetty |= tag == "frame_id"
    version = "fortress" if fortress else "jetty" if jetty else "harmonic"
    return gz, classic, version


def robot_simulator(robot: Robot) -> tuple[str, str | None, str] | None:
    """``(sim, gz_version, why)`` the robot's own plugins and sensors say it runs on, as
    the ``sim`` of sensorkit's macros (``gz`` or ``classic``), or None when nothing in it
    is simulator-specific. The same evidence and the same weighing as :func:`detect_target`
    (``add-*`` without ``--sim`` follows what ``validate --target auto`` sees); a ROS 1
    description gives ``classic``, the only Gazebo Classic the macros write.
    """
    gz, classic, version = _evidence(robot)
    if len(gz) > len(classic):
        return "gz", version, gz[0]
    if classic:
        return "classic", None, classic[0]
    return None
