"""``rviz/<robot>.rviz``: the RViz2 configuration ``sensorkit new`` writes and
``launch/display.launch.py`` opens.

Global options, panels, tools and view follow ros2/rviz ``rviz_common/default.rviz``
(@humble 9b35482); the displays are written as RViz2 saves them, each with ``Class``,
``Enabled``, ``Name``, ``Value`` and its topic as a mapping of ``Value`` and the QoS fields
(``Depth``, ``Durability Policy``, ``History Policy``, ``Reliability Policy``;
rviz_common/src/rviz_common/properties/qos_profile_property.cpp@humble:69-103), keys in the
sorted order RViz2 writes, as in ros-navigation/navigation2@9ff2dc5:
nav2_bringup/rviz/nav2_default_view.rviz. The sensor displays are one per topic
``sensorkit topics`` lists (on Gazebo Sim, under the names the written bridge gives them),
with the class :data:`sensorkit.knowledge.rviz.RVIZ_DISPLAYS` names for its message type.
"""

from __future__ import annotations

import json
import re
import textwrap
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import yaml

from sensorkit.generate.render import fill
from sensorkit.knowledge.rviz import (
    DESCRIPTION_QOS,
    NO_RVIZ_DISPLAY,
    RVIZ_DISPLAYS,
    SENSOR_QOS,
)

if TYPE_CHECKING:
    from lxml import etree

    from sensorkit.describe.topics import Topic
    from sensorkit.generate.spec import RobotSpec


@dataclass(frozen=True)
class SensorDisplay:
    """One sensor topic and the RViz2 display class that shows it."""

    topic: str
    type: str
    display: str  # e.g. "rviz_default_plugins/Image"
    sensor: str


@dataclass(frozen=True)
class Unshown:
    """A sensor topic the configuration has no display for, and why."""

    topic: str
    type: str
    why: str


def sensor_displays(topics: Sequence[Topic]) -> tuple[list[SensorDisplay], list[Unshown]]:
    """The display of every topic a sensor publishes to ROS (one per name, in order), and
    the topics left without one."""
    shown: list[SensorDisplay] = []
    unshown: list[Unshown] = []
    seen: set[str] = set()
    for t in topics:
        if t.name is None or t.direction != "publishes" or t.name in seen:
            continue
        seen.add(t.name)
        mtype = t.type or "?"
        display = RVIZ_DISPLAYS.get(mtype)
        if display is not None:
            shown.append(SensorDisplay(t.name, mtype, display, t.sensor))
        else:
            why = NO_RVIZ_DISPLAY.get(mtype, f"rviz_default_plugins has no display for {mtype}")
            unshown.append(Unshown(t.name, mtype, why))
    return shown, unshown


def rviz_unshown_groups(unshown: Sequence[Unshown]) -> list[tuple[str, str, list[str]]]:
    """``(message type, why, topics)`` of the topics without an RViz display, by type."""
    groups: dict[str, tuple[str, list[str]]] = {}
    for u in unshown:
        groups.setdefault(u.type, (u.why, []))[1].append(u.topic)
    return [(mtype, why, names) for mtype, (why, names) in groups.items()]


def root_link(robot: etree._Element) -> str | None:
    """The link no joint has as its child (None when there is not exactly one)."""
    links = [link.get("name") or "" for link in robot.findall("link")]
    children = {c.get("link") for c in robot.findall("joint/child")}
    roots = [name for name in links if name not in children]
    return roots[0] if len(roots) == 1 else None


def fixed_frame(spec: RobotSpec, robot: etree._Element) -> str:
    """RViz's Fixed Frame: ``base_footprint`` when the base macro makes it, else the root
    link of the expanded robot, else ``base_link``."""
    if "base_footprint" in spec.base_macro.link_patterns:
        return "base_footprint"
    return root_link(robot) or "base_link"


# --------------------------------------------------------------------------- YAML text

_PLAIN = re.compile(r"^[A-Za-z0-9/<][A-Za-z0-9_/<>;.() -]*$")
_RESERVED = {"true", "false", "null", "yes", "no", "on", "off", "y", "n"}


def _scalar(value: Any) -> str:
    """A YAML scalar as RViz2 writes it: plain where that reads back as the same string
    (``160; 160; 164``, ``<Fixed Frame>``), else double-quoted (a JSON string is a YAML
    double-quoted scalar)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    text = str(value)
    if (
        _PLAIN.match(text)
        and not text.endswith(" ")
        and text.lower() not in _RESERVED
        and yaml.safe_load(f"k: {text}") == {"k": text}
    ):
        return text
    return json.dumps(text)


def _mapping(values: Mapping[str, Any], indent: str) -> list[str]:
    lines: list[str] = []
    for key in sorted(values):
        value = values[key]
        if isinstance(value, Mapping):
            lines.append(f"{indent}{key}:")
            lines += _mapping(value, indent + "  ")
        else:
            lines.append(f"{indent}{key}: {_scalar(value)}")
    return lines


def _list_item(values: Mapping[str, Any], indent: str) -> list[str]:
    """A mapping as one ``- `` item of a list at ``indent``."""
    lines = _mapping(values, indent + "  ")
    lines[0] = f"{indent}- {lines[0][len(indent) + 2 :]}"
    return lines


def _topic(name: str, qos: Mapping[str, str | int]) -> dict[str, Any]:
    return {**qos, "Value": name}


def _displays(spec: RobotSpec, sensors: Sequence[SensorDisplay]) -> list[dict[str, Any]]:
    ns = spec.namespace.strip("/")
    description = f"/{ns}/robot_description" if ns else "/robot_description"
    out: list[dict[str, Any]] = [
        {
            "Alpha": 0.5,
            "Cell Size": 1,
            "Class": "rviz_default_plugins/Grid",
            "Color": "160; 160; 164",
            "Enabled": True,
            "Name": "Grid",
            "Plane": "XY",
            "Plane Cell Count": 10,
            "Reference Frame": "<Fixed Frame>",
            "Value": True,
        },
        {
            "Alpha": 1,
            "Class": "rviz_default_plugins/RobotModel",
            "Collision Enabled": False,
            "Description File": "",
            "Description Source": "Topic",
            "Description Topic": _topic(description, DESCRIPTION_QOS),
            "Enabled": True,
            "Name": "RobotModel",
            "TF Prefix": "",
            "Update Interval": 0,
            "Value": True,
            "Visual Enabled": True,
        },
        {
            "Class": "rviz_default_plugins/TF",
            "Enabled": True,
            "Name": "TF",
            "Show Axes": True,
            "Show Names": False,
            "Value": True,
        },
    ]
    for d in sensors:
        entry: dict[str, Any] = {
            "Class": d.display,
            "Enabled": True,
            "Name": d.topic.lstrip("/"),
            "Topic": _topic(d.topic, SENSOR_QOS),
            "Value": True,
        }
        if d.display == "rviz_default_plugins/Image":
            # Scale each image to its own range: depth images are metres (32FC1).
            entry["Normalize Range"] = True
        out.append(entry)
    return out


def _about(spec: RobotSpec, sensors: Sequence[SensorDisplay], unshown: Sequence[Unshown]) -> str:
    if spec.sim == "classic":
        target = "Gazebo Classic"
    elif spec.sim == "gz":
        target = f"Gazebo Sim {spec.gz_version.capitalize()} (as config/bridge.yaml names them)"
    else:
        target = ""
    if target:
        text = (
            "The robot model (from robot_description), TF and one display per sensor topic "
            f"`sensorkit topics` lists for {target}, each subscribed best effort, which "
            "receives from reliable and best-effort publishers alike; the sensor displays "
            "show data only while the simulator runs."
        )
    else:
        text = (
            "The robot model (from robot_description) and TF; sim: none has no simulator, "
            "so no sensor topics sensorkit can name."
        )
    lines = textwrap.wrap(text, 86)
    if unshown:
        lines += ["", "Not shown:"]
        for mtype, why, names in rviz_unshown_groups(unshown):
            lines += textwrap.wrap(
                f"{mtype} ({', '.join(names)}): {why}",
                86,
                initial_indent="  ",
                subsequent_indent="    ",
                break_on_hyphens=False,
            )
    return "".join(f"# {line}\n" if line else "#\n" for line in lines)


def rviz_config(
    spec: RobotSpec,
    frame: str,
    sensors: Sequence[SensorDisplay] = (),
    unshown: Sequence[Unshown] = (),
) -> str:
    """The text of ``rviz/<robot>.rviz``."""
    lines: list[str] = []
    for display in _displays(spec, sensors):
        lines += _list_item(display, "    ")
    return fill(
        "display.rviz.in",
        {
            "robot": spec.name,
            "about": _about(spec, sensors, unshown),
            "displays": "\n".join(lines),
            "fixed_frame": _scalar(frame),
        },
    )
