"""Targets: what the description will run on, and how ``auto`` picks one."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from sensorkit.model.robot import Robot

TARGETS = ("classic", "ros1", "fortress", "harmonic", "jetty")
GZ_TARGETS = ("fortress", "harmonic", "jetty")
GZ_SENSOR_TYPES = {
    "gpu_lidar",
    "lidar",
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


def detect_target(robot: Robot) -> tuple[str, str]:
    """(target, why) for ``--target auto``.

    Gazebo Sim evidence (gz/ignition system plugins, gz-only sensor types, gz frame tags)
    against Gazebo Classic evidence (gazebo_ros plugins); the larger wins, a tie or no
    evidence at all gives ``classic`` (ROS 2 with Gazebo Classic). ``ros1`` is never
    guessed: sensorkit is for ROS 2, so ROS 1 plugins are reported, not accommodated.
    Among gz versions: ``ignition_*`` names mean fortress, a sensor ``<frame_id>`` jetty,
    anything else harmonic.
    """
    from sensorkit.model.sensors import all_plugins

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
    if len(gz) > len(classic):
        version = "fortress" if fortress else "jetty" if jetty else "harmonic"
        return version, f"auto: {gz[0]}"
    if classic:
        return "classic", f"auto: {classic[0]}"
    return "classic", "auto: no simulator-specific tags; assuming ROS 2 with Gazebo Classic"
