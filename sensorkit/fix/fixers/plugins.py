"""SK601: a plugin swapped for the one the target loads.

A ROS 1-only sensor plugin with a one-to-one ROS 2 form becomes that form (its library,
and the parameters the ROS 1 plugin implied); on Fortress a ``gz-sim`` library is written
``ignition-gazebo``. Only the ``filename`` as written changes, and children are added.
"""

from __future__ import annotations

from sensorkit.base.findings import Finding
from sensorkit.fix.registry import Fix, FixContext, Written, fixer, is_expr
from sensorkit.fix.source import Edit, NotFixable
from sensorkit.knowledge.gazebo_ros import ROS1_ONLY
from sensorkit.model.parse import child
from sensorkit.model.robot import all_plugins
from sensorkit.model.sensors import Plugin

__all__ = ["port_plugin"]

# ROS 1-only sensor plugins whose ROS 2 form is one plugin with the same data: library,
# the sensor types it works on, and the <output_type> the ROS 1 plugin's message was
# (gazebo_ros_laser/gpu_laser: LaserScan; gazebo_ros_block_laser.cpp:178 PointCloud;
# gazebo_ros_range: Range). See sensorkit.knowledge.gazebo_ros.ROS1_ONLY.
_PORTS: dict[str, tuple[str, frozenset[str], str | None]] = {
    "laser": (
        "libgazebo_ros_ray_sensor.so",
        frozenset({"ray", "gpu_ray"}),
        "sensor_msgs/LaserScan",
    ),
    "gpu_laser": (
        "libgazebo_ros_ray_sensor.so",
        frozenset({"ray", "gpu_ray"}),
        "sensor_msgs/LaserScan",
    ),
    "block_laser": (
        "libgazebo_ros_ray_sensor.so",
        frozenset({"ray", "gpu_ray"}),
        "sensor_msgs/PointCloud",
    ),
    "range": ("libgazebo_ros_ray_sensor.so", frozenset({"ray", "gpu_ray"}), "sensor_msgs/Range"),
    "depth_camera": ("libgazebo_ros_camera.so", frozenset({"depth"}), None),
    "openni_kinect": ("libgazebo_ros_camera.so", frozenset({"depth"}), None),
    "multicamera": ("libgazebo_ros_camera.so", frozenset({"multicamera"}), None),
    "triggered_camera": ("libgazebo_ros_camera.so", frozenset({"camera"}), None),
}
# Once a ROS 1 plugin is swapped for its ROS 2 form, sensorkit checks its parameters and
# frame (SK601 folds those in while the plugin cannot load): findings of these rules on
# the same sensor were there all along, not made by the swap.
_REVEALED = frozenset({"SK303", "SK501", "SK502", "SK503", "SK504", "SK602", "SK606", "SK609"})


def _plugin_at(fx: FixContext, f: Finding) -> Plugin:
    for p in all_plugins(fx.robot):
        if p.source == f.source and (p.sensor.name if p.sensor else None) == f.sensor:
            return p
    raise NotFixable("the plugin is not found")


def _swap_library(fx: FixContext, p: Plugin, new: str) -> tuple[Written, Edit, str]:
    w = fx.written(p.element)
    a = w.tag.attr("filename")
    if a is None or is_expr(a.raw):
        raise NotFixable(
            f"the plugin filename at {w.where} is computed by xacro: change it where its value comes from"
        )
    base = a.raw.rsplit("/", 1)[-1]
    return w, w.file.set_attr(a, a.raw[: len(a.raw) - len(base)] + new), a.raw


@fixer(
    "SK601",
    "safe",
    "swap a ROS 1-only sensor plugin for its one-to-one ROS 2 form (`libgazebo_ros_laser.so` -> "
    "`libgazebo_ros_ray_sensor.so` with its `<output_type>`, depth/openni -> "
    "`libgazebo_ros_camera.so`, ...); on Fortress write `ignition-gazebo` for `gz-sim`",
)
def port_plugin(fx: FixContext, f: Finding) -> Fix:
    p = _plugin_at(fx, f)
    name = p.filename.rsplit("/", 1)[-1]
    if fx.target == "fortress" and name.startswith(("gz-sim", "libgz-sim")):
        new = name.replace("libgz-sim", "libignition-gazebo").replace("gz-sim", "ignition-gazebo")
        _, edit, old = _swap_library(fx, p, new)
        return Fix(f, (edit,), f'filename "{old}" -> "{new}"')
    lib = p.library
    ros_name = lib.removeprefix("gazebo_ros_") if lib.startswith("gazebo_ros_") else None
    if fx.target != "classic" or ros_name not in ROS1_ONLY:
        raise NotFixable("no one-to-one replacement: " + (f.fix or "see the finding"))
    if ros_name not in _PORTS or p.sensor is None:
        raise NotFixable(f"{p.filename} has no one-to-one ROS 2 form ({ROS1_ONLY[ros_name]})")
    new, types, output = _PORTS[ros_name]
    s = p.sensor
    if s.type not in types:
        raise NotFixable(
            f"{new} does not work on a sensor of type {s.type!r} ({'/'.join(sorted(types))})"
        )
    w, edit, old = _swap_library(fx, p, new)
    edits = [edit]
    added: list[str] = []
    if output is not None and child(p.element, "output_type") is None:
        added.append(f"<output_type>{output}</output_type>")
    if ros_name == "range":
        radiation = child(p.element, "radiation")
        if radiation is not None:  # gazebo_ros_range.cpp:127-134 -> ray_sensor.cpp:144-156
            edits += fx.written(radiation).file.rename(fx.written(radiation).tag, "radiation_type")
        elif child(p.element, "radiation_type") is None:
            added.append("<radiation_type>ultrasound</radiation_type>")  # ROS 1's default
    if ros_name == "triggered_camera" and child(p.element, "triggered") is None:
        added.append("<triggered>true</triggered>")
    if added:
        edits.append(w.file.insert_child(w.tag, [(0, t) for t in added]))
    title = f'filename "{old}" -> "{new}"' + (f", add {' '.join(added)}" if added else "")
    return Fix(f, tuple(edits), title, reveals=_REVEALED)
