"""Which sensors a model-level plugin reads by name, and so publishes (or hands to ros_control).

The knowledge is data in :mod:`sensorkit.knowledge.plugins` (``PluginSpec.owns``, and
``HARDWARE_SIMS`` for gazebo_ros_control's ``<robotSimType>``); :func:`sensor_owner`
applies it to one robot. SK607 and ``sensorkit topics`` both ask it, so they agree.
"""

from __future__ import annotations

from dataclasses import dataclass

from sensorkit.knowledge.plugins import (
    BY_NAME_SUFFIX,
    BY_ROS2_CONTROL,
    BY_ROS_PARAMS,
    HARDWARE_SIMS,
    ROS2_CONTROL_SYSTEMS,
    SensorOwnership,
    lookup,
)
from sensorkit.model.parse import local
from sensorkit.model.robot import Robot
from sensorkit.model.sensors import Plugin, Sensor
from sensorkit.model.targets import is_gz

__all__ = ["Owner", "sensor_owner"]


@dataclass(frozen=True)
class Owner:
    """A model-level plugin that reads a sensor (``certain``) or may read it (not certain:
    the names are outside the description, or the plugin's class is unknown)."""

    plugin: Plugin | None  # None: a <ros2_control> block no known plugin loads
    how: str  # readable: "reads it by name (source)"
    certain: bool


def _generation(target: str) -> str:
    return "gz" if is_gz(target) else "ros1" if target == "ros1" else "ros2"


def _ros2_control_sensors(robot: Robot) -> dict[str, str]:
    """Each ``<ros2_control><sensor name>`` of the description, to the hardware class its
    block loads (``<hardware><plugin>``; "" when none is written)."""
    out: dict[str, str] = {}
    for block in robot.document.root:
        if local(block) != "ros2_control":
            continue
        hardware = next((el for el in block if local(el) == "hardware"), None)
        plugin = (
            next((el for el in hardware if local(el) == "plugin"), None)
            if hardware is not None
            else None
        )
        cls = (plugin.text or "").strip() if plugin is not None else ""
        for el in block:
            if local(el) == "sensor":
                out.setdefault(el.get("name", ""), cls)
    return out


def _ros2_control_names(robot: Robot) -> set[str]:
    return set(_ros2_control_sensors(robot))


def _apply(robot: Robot, p: Plugin, owns: SensorOwnership, s: Sensor) -> Owner | None:
    if owns.how == BY_ROS2_CONTROL and s.name in _ros2_control_names(robot):
        cls = _ros2_control_sensors(robot)[s.name]
        if cls not in ROS2_CONTROL_SYSTEMS:
            # gazebo_ros2_control loads each block's <hardware><plugin> class by pluginlib
            # (ros-controls/gazebo_ros2_control@humble 42d875b:gazebo_ros2_control/src/
            # gazebo_ros2_control_plugin.cpp:301-310): a class of a fork or of the project
            # decides what it reads, which sensorkit cannot tell.
            return Owner(
                p,
                f"{p.filename} hands it to the <ros2_control> hardware class {cls or '(none written)'}, "
                "which sensorkit does not know",
                False,
            )
    if owns.sensor_types and s.type not in owns.sensor_types:
        return None
    if owns.how == BY_NAME_SUFFIX:
        prefix = (p.param(owns.param) or "") if owns.param else ""
        if s.name in {prefix + x for x in owns.suffixes}:
            return Owner(p, f"{p.filename} reads it by name ({owns.source})", True)
    elif owns.how == BY_ROS2_CONTROL:
        if s.name in _ros2_control_names(robot):
            return Owner(
                p, f"{p.filename} reads it as a <ros2_control> sensor ({owns.source})", True
            )
    elif owns.how == BY_ROS_PARAMS:
        return Owner(
            p,
            f"{p.filename} reads {'/'.join(sorted(owns.sensor_types)) or 'sensors'} named in "
            f"{owns.where} ({owns.source}), which a robot description does not hold",
            False,
        )
    return None


def _names_it(p: Plugin, s: Sensor) -> bool:
    """A plugin sensorkit does not know names the sensor among its parameters."""
    return any(
        el is not p.element and isinstance(el.tag, str) and (el.text or "").strip() == s.name
        for el in p.element.iter()
    )


def _owner_of(robot: Robot, p: Plugin, s: Sensor, target: str) -> Owner | None:
    spec = lookup(p.filename, _generation(target))
    if spec is None:
        # A plugin sensorkit does not know that names the sensor may read it (ArduPilot's
        # <imuName>: ArduPilot/ardupilot_gazebo@main 082a0fe:src/ArduPilotPlugin.cc:807-812,
        # 1111-1187 subscribes to the IMU it names; @gazebo11 e72ecf5:src/ArduPilotPlugin.cc:
        # 627-683 looks it up in the SensorManager) and send its data anywhere, on every
        # target: sensorkit cannot tell (issue 35).
        if _names_it(p, s):
            return Owner(p, f"{p.filename} (a plugin sensorkit does not know) names it", False)
        return None
    if spec.owns is not None:
        return _apply(robot, p, spec.owns, s)
    if spec.owner_class_param is None:
        return None
    cls = (p.param(spec.owner_class_param) or spec.owner_class_default or "").strip()
    if cls in HARDWARE_SIMS:
        owns = HARDWARE_SIMS[cls]
        return None if owns is None else _apply(robot, p, owns, s)
    return Owner(
        p,
        f"{p.filename} loads <{spec.owner_class_param}>{cls}</{spec.owner_class_param}>, a class "
        "sensorkit does not know, which may read sensors by name",
        False,
    )


def sensor_owner(robot: Robot, s: Sensor, target: str) -> Owner | None:
    """The model-level plugin that reads ``s`` (a certain one first), or None."""
    found = [o for p in robot.model_plugins if (o := _owner_of(robot, p, s, target)) is not None]
    if not found and s.name in _ros2_control_names(robot) and not _known_ros2_control(robot, target):
        # A <ros2_control> block names it and no ros2_control plugin sensorkit knows loads
        # the block (a fork, or a plugin of the project's own): sensorkit cannot tell.
        return Owner(
            None,
            "a <ros2_control> block names it, and no ros2_control plugin sensorkit knows loads "
            "that block",
            False,
        )
    return next((o for o in found if o.certain), found[0] if found else None)


def _known_ros2_control(robot: Robot, target: str) -> bool:
    """Whether a model plugin sensorkit knows reads the <ros2_control> blocks."""
    for p in robot.model_plugins:
        spec = lookup(p.filename, _generation(target))
        if spec is not None and spec.owns is not None and spec.owns.how == BY_ROS2_CONTROL:
            return True
    return False
