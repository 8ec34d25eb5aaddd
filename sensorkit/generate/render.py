"""The text of the generated package's files, from a checked :class:`RobotSpec`.

The README, the RViz2 configuration and the bridge YAML have modules of their own
(:mod:`sensorkit.generate.readme`, :mod:`sensorkit.generate.rviz`,
:mod:`sensorkit.exporters.bridge`); the RViz2 configuration's template is filled
with :func:`fill` too.

Package skeleton files come from ``templates/package/*.in`` with ``@key@``
placeholders (CMake's ``configure_file`` style, so ``${PROJECT_NAME}`` in CMake and
``$(arg ...)`` in xacro pass through untouched). The top-level robot xacro is assembled
here because its shape depends on the sensors. Every function is pure: same spec,
same bytes.
"""

from __future__ import annotations

import json
import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from xml.sax.saxutils import escape, quoteattr

from sensorkit.base.resources import templates_dir
from sensorkit.generate.spec import RobotSpec

_PLACEHOLDER = re.compile(r"@([a-z_]+)@")
SAVE_FRAMES_NODE = "scripts/save_frames.py"


@dataclass(frozen=True)
class CameraImage:
    """A camera image topic the generated save_frames launch file saves."""

    topic: str
    encoding: str  # "" when sensorkit cannot say
    sensor: str
    depth: bool


def fill(template_name: str, values: Mapping[str, str]) -> str:
    """``templates/package/<template_name>`` with every ``@key@`` replaced.

    Raises:
        KeyError: the template names a key ``values`` lacks (a bug in sensorkit).
    """
    text = (templates_dir() / "package" / template_name).read_text(encoding="utf-8")

    def sub(match: re.Match[str]) -> str:
        return values[match.group(1)]

    return _PLACEHOLDER.sub(sub, text)


def _common(spec: RobotSpec) -> dict[str, str]:
    return {
        "package": spec.package,
        "robot": spec.name,
        "namespace": spec.namespace,
        "sim": spec.sim,
        "gz_version": spec.gz_version,
    }


def exec_depends(spec: RobotSpec, *, python_node: bool = False) -> list[str]:
    deps = ["xacro", "robot_state_publisher", "launch", "launch_ros", "ament_index_python"]
    deps += ["joint_state_publisher", "joint_state_publisher_gui", "rviz2"]  # display.launch.py
    if spec.sim == "gz":
        deps += ["ros_gz_sim", "ros_gz_bridge"]
    elif spec.sim == "classic":
        deps += ["gazebo_ros", "gazebo_plugins"]
    if python_node:  # scripts/save_frames.py
        deps += ["rclpy", "sensor_msgs", "python3-numpy"]
    return deps


def package_xml(spec: RobotSpec, *, python_node: bool = False) -> str:
    deps = "".join(
        f"  <exec_depend>{d}</exec_depend>\n" for d in exec_depends(spec, python_node=python_node)
    )
    return fill(
        "package.xml.in",
        {
            **_common(spec),
            "version": spec.version,
            "description": escape(spec.description),
            "maintainer_email": escape(spec.maintainer_email),
            "maintainer_name": escape(spec.maintainer_name),
            "license": escape(spec.license),
            "exec_depends": deps,
        },
    )


def cmakelists(spec: RobotSpec, install_dirs: Sequence[str], programs: Sequence[str] = ()) -> str:
    block = ""
    if programs:
        block = (
            "\n# Python nodes, where ros2 run and launch_ros look for executables.\n"
            f"install(\n  PROGRAMS {' '.join(programs)}\n  DESTINATION lib/${{PROJECT_NAME}}\n)\n"
        )
    return fill(
        "CMakeLists.txt.in",
        {**_common(spec), "install_dirs": " ".join(install_dirs), "install_programs": block},
    )


def save_frames_launch(spec: RobotSpec, images: Sequence[CameraImage]) -> str:
    """``launch/save_frames.launch.py``: the save_frames node on every camera image."""
    rows = [
        (i.topic, f"{i.encoding or '?'}{' depth' if i.depth else ''}", f"[{i.sensor}]")
        for i in images
    ]
    widths = [max(len(r[k]) for r in rows) for k in range(2)]
    lines = [f"    {a.ljust(widths[0])}  {b.ljust(widths[1])}  {c}" for a, b, c in rows]
    target = (
        "Gazebo Classic" if spec.sim == "classic" else f"Gazebo Sim {spec.gz_version.capitalize()}"
    )
    return fill(
        "save_frames.launch.py.in",
        {
            **_common(spec),
            "target": target,
            "topic_lines": "\n".join(lines),
            "topics": "".join(
                f"    ({json.dumps(i.topic)}, {json.dumps(i.encoding)}),\n" for i in images
            ),
        },
    )


def save_frames_node() -> str:
    """``scripts/save_frames.py``, the same for every robot."""
    return (templates_dir() / "package" / "save_frames.py").read_text(encoding="utf-8")


def description_launch(spec: RobotSpec) -> str:
    return fill("description.launch.py.in", _common(spec))


def display_launch(spec: RobotSpec) -> str:
    """``launch/display.launch.py``: robot_state_publisher, joint_state_publisher(_gui), rviz2."""
    note = ""
    if spec.sim in ("gz", "classic"):
        note = (
            "\nThe sensor displays of the configuration carry data only while the simulator runs;\n"
            "sim.launch.py already runs robot_state_publisher and the simulator publishes the\n"
            "joint states, so open RViz2 alone beside it:\n\n"
            f"    share=$(ros2 pkg prefix {spec.package})/share/{spec.package}\n"
            f"    rviz2 -d $share/rviz/{spec.name}.rviz --ros-args -p use_sim_time:=true\n"
        )
    return fill("display.launch.py.in", {**_common(spec), "sim_note": note})


def sim_launch(spec: RobotSpec) -> str | None:
    if spec.sim == "gz":
        return fill("sim_gz.launch.py.in", _common(spec))
    if spec.sim == "classic":
        return fill("sim_classic.launch.py.in", _common(spec))
    return None


def world_sdf(spec: RobotSpec) -> str | None:
    if spec.sim != "gz":
        return None
    fortress = spec.gz_version == "fortress"
    return fill(
        "world.sdf.in",
        {
            **_common(spec),
            "sys_file": "ignition-gazebo-" if fortress else "gz-sim-",
            "sys_class": "ignition::gazebo::systems::" if fortress else "gz::sim::systems::",
        },
    )


def _attrs(pairs: Sequence[tuple[str, str]], indent: str) -> str:
    """Attributes on one line if short, else one per line under the tag."""
    parts = [f"{k}={quoteattr(v)}" for k, v in pairs]
    line = " ".join(parts)
    if len(line) <= 72:
        return " " + line
    return "\n" + "\n".join(f"{indent}    {p}" for p in parts)


@dataclass(frozen=True)
class Regen:
    """Where the robot YAML a package was generated from lies, as its files say it: the
    YAML stays the user's file, outside the package (``new`` never writes an input into
    its output), so the header and README name it by its path from the package, and
    the command that generates again names the folder by the package's name (the folder
    ROS users give a package; a package generated elsewhere stays byte for byte the same)."""

    yaml_name: str  # the YAML's file name (what add-* looks for beside the package)
    yaml_at: str  # its path from the package folder: "../robot.yaml"
    yaml_arg: str  # its path from the package's parent folder, where `new` runs again


def regen_for(spec_path: Path, pkg: Path) -> Regen:
    """The :class:`Regen` of the YAML at ``spec_path`` for the package folder ``pkg``."""
    spec, out = Path(os.path.realpath(spec_path)), Path(os.path.realpath(pkg))
    return Regen(
        spec.name,
        Path(os.path.relpath(spec, out)).as_posix(),
        Path(os.path.relpath(spec, out.parent)).as_posix(),
    )


def robot_xacro(spec: RobotSpec, regen: Regen) -> str:
    """The top-level ``urdf/<robot>.urdf.xacro``: include the base and each sensor macro
    (relative paths, so plain ``xacro`` expands it anywhere) and call them."""
    base = spec.base_macro
    types = list(dict.fromkeys(s.type for s in spec.sensors))
    lines = [
        '<?xml version="1.0"?>',
        "<!--",
        f"  {spec.name}: a {spec.base} base with {len(spec.sensors)} sensor"
        f"{'' if len(spec.sensors) == 1 else 's'}, written by `sensorkit new {regen.yaml_name}`.",
        f"  Change {regen.yaml_at} (the path is from the package folder) rather than editing",
        "  this file, and generate again with force from the folder holding the package:",
        f"  `sensorkit new {regen.yaml_arg} -o {spec.package}` (it replaces the whole package).",
        "",
        "  Argument:",
        f"    sim   classic | gz | none (default {spec.sim}). none gives the links and joints",
        "          only, for a real robot whose drivers publish the sensor data.",
        "",
        "  Sensors (type, parent link):",
    ]
    for s in spec.sensors:
        lines.append(f"    {s.name} ({s.type}) on {s.parent} at xyz {s.xyz} rpy {s.rpy}")
    if not spec.sensors:
        lines.append("    none")
    lines += [
        "-->",
        f'<robot name="{spec.name}" xmlns:xacro="http://www.ros.org/wiki/xacro">',
        "",
        f'  <xacro:arg name="sim" default="{spec.sim}"/>',
        "",
        f'  <xacro:include filename="{base.file.name}"/>',
    ]
    for t in types:
        lines.append(f'  <xacro:include filename="sensors/{t}.urdf.xacro"/>')
    shared = [
        ("sim", "$(arg sim)"),
        ("gz_version", spec.gz_version),
        ("namespace", spec.namespace),
    ]
    lines += [
        "",
        f"  <xacro:{base.macro}{_attrs([*spec.base_params.items(), *shared], '  ')}/>",
    ]
    for s in spec.sensors:
        pairs = [("name", s.name), ("parent", s.parent), *s.options.items(), *shared]
        macro = s.macro.macro
        lines += [
            "",
            f"  <xacro:{macro}{_attrs(pairs, '  ')}>",
            f'    <origin xyz="{s.xyz}" rpy="{s.rpy}"/>',
            f"  </xacro:{macro}>",
        ]
    lines += ["", "</robot>", ""]
    return "\n".join(lines)
