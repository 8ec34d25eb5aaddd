"""``README.md`` of a generated package: its sensors, how to try it, RViz2, topics, frames.

One section per function, each a list of lines; :func:`readme` joins them in order.
Pure: same spec, same bytes.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from sensorkit.generate.rviz import rviz_unshown_groups

if TYPE_CHECKING:
    from sensorkit.describe.bridge import BridgeEntry
    from sensorkit.generate.render import CameraImage, Regen
    from sensorkit.generate.rviz import Unshown
    from sensorkit.generate.spec import RobotSpec

__all__ = ["readme"]


def _simulated(spec: RobotSpec) -> bool:
    return spec.sim in ("gz", "classic")


def _head(spec: RobotSpec, regen: Regen) -> list[str]:
    """The title, description and sensor table."""
    lines = [
        f"# {spec.package}",
        "",
        f"{spec.description}",
        "",
        f"Written by `sensorkit new {regen.yaml_name}`: change the YAML (`{regen.yaml_at}` from",
        "this folder) and generate again rather than editing these files by hand; from the",
        f"folder holding this package: `sensorkit new {regen.yaml_arg} -o {spec.package} --force`.",
        "",
        "| sensor | type | parent | xyz | rpy |",
        "|---|---|---|---|---|",
    ]
    for s in spec.sensors:
        lines.append(f"| {s.name} | {s.type} | {s.parent} | {s.xyz} | {s.rpy} |")
    return lines


def _try_it(spec: RobotSpec, xacro_rel: str) -> list[str]:
    lines = [
        "",
        "## Try it",
        "",
        "```bash",
        f"sensorkit validate {xacro_rel}",
        f"sensorkit render preview {xacro_rel}",
        f"xacro {xacro_rel} sim:=none > /tmp/{spec.name}.urdf && check_urdf /tmp/{spec.name}.urdf",
        "```",
        "",
        "In a colcon workspace (`src/` holding this folder):",
        "",
        "```bash",
        f"colcon build --packages-select {spec.package} && source install/setup.bash",
        f"ros2 launch {spec.package} description.launch.py   # robot_state_publisher only",
        f"ros2 launch {spec.package} display.launch.py       # the model in RViz2, joint sliders",
    ]
    if _simulated(spec):
        lines.append(f"ros2 launch {spec.package} sim.launch.py           # the simulator too")
    return [*lines, "```", ""]


def _rviz(spec: RobotSpec, unshown: Sequence[Unshown], fixed_frame: str) -> list[str]:
    lines = ["## RViz2", ""]
    rviz_file = f"`rviz/{spec.name}.rviz` (fixed frame `{fixed_frame}`)"
    if _simulated(spec):
        lines += [
            f"`display.launch.py` opens {rviz_file}: the robot",
            "model, TF and one display per sensor topic, subscribed best effort (which receives",
            "from reliable and best-effort publishers alike). `gui:=false` starts",
            "joint_state_publisher instead of the slider window.",
            "",
            "The sensor displays show data while the simulator runs. `sim.launch.py` already",
            "runs robot_state_publisher and the simulator publishes the joint states, so open",
            "RViz2 alone beside it:",
            "",
            "```bash",
            f"rviz2 -d install/{spec.package}/share/{spec.package}/rviz/{spec.name}.rviz "
            "--ros-args -p use_sim_time:=true",
            "```",
            "",
        ]
    else:
        lines += [
            f"`display.launch.py` opens {rviz_file}: the robot",
            "model and TF (no simulator, so no sensor topics sensorkit can name). `gui:=false`",
            "starts joint_state_publisher instead of the slider window.",
            "",
        ]
    if unshown:
        lines += ["Not shown:", ""]
        for mtype, why, names in rviz_unshown_groups(unshown):
            listed = ", ".join(f"`{n}`" for n in names)
            lines.append(f"- {mtype} ({listed}): {why}")
        lines.append("")
    return lines


def _topics(spec: RobotSpec, entries: Sequence[BridgeEntry], xacro_rel: str) -> list[str]:
    lines: list[str] = []
    if spec.sim == "gz":
        lines += [
            f"## Topics (Gazebo Sim {spec.gz_version.capitalize()}, "
            "bridged by `config/bridge.yaml`)",
            "",
            "| ROS topic | ROS type | gz topic | direction |",
            "|---|---|---|---|",
        ]
        for e in entries:
            ros, gz = f"`{e.ros_topic_name}`", f"`{e.gz_topic_name}`"
            lines.append(f"| {ros} | {e.ros_type_name} | {gz} | {e.direction} |")
        lines += [
            "",
            f"The world (`worlds/{spec.name}.sdf`) loads the Sensors and Imu systems that",
            "the sensors need; another world must load them too.",
            "",
        ]
    elif spec.sim == "classic":
        lines += [
            "## Topics (Gazebo Classic)",
            "",
            "Each sensor's gazebo_ros plugin publishes straight to ROS; the topics are listed",
            "in the header of its macro in `urdf/sensors/`.",
            "",
        ]
    if _simulated(spec):
        lines += [
            "Every topic with its message type, frame_id, encoding and rate:",
            "",
            "```bash",
            f"sensorkit topics {xacro_rel}",
            "```",
            "",
        ]
    return lines


def _save_frames(spec: RobotSpec, images: Sequence[CameraImage]) -> list[str]:
    if not images:
        return []
    lines = [
        "## Save camera frames",
        "",
        "With the simulation running, write a frame of every camera every 5 seconds of",
        "message time into `frames/<topic, its slashes as __>/` (colour as PNG; depth as",
        "16-bit PNG in millimetres, 0 = no depth, or with `format:=npy` as received):",
        "",
        "```bash",
        f"ros2 launch {spec.package} save_frames.launch.py interval:=5.0 folder:=frames",
        "```",
        "",
        "| topic | encoding | sensor |",
        "|---|---|---|",
    ]
    for i in images:
        kind = f"{i.encoding or '?'}{' (depth)' if i.depth else ''}"
        lines.append(f"| `{i.topic}` | {kind} | {i.sensor} |")
    return [
        *lines,
        "",
        "The node (`scripts/save_frames.py`) needs rclpy, sensor_msgs and numpy.",
        "",
    ]


def readme(
    spec: RobotSpec,
    regen: Regen,
    entries: Sequence[BridgeEntry],
    images: Sequence[CameraImage] = (),
    unshown: Sequence[Unshown] = (),
    fixed_frame: str = "base_link",
) -> str:
    """The text of ``README.md``: ``entries`` are the bridge's (Gazebo Sim), ``images``
    the camera images save_frames saves, ``unshown`` the topics RViz2 has no display for."""
    xacro_rel = f"urdf/{spec.name}.urdf.xacro"
    lines = [
        *_head(spec, regen),
        *_try_it(spec, xacro_rel),
        *_rviz(spec, unshown, fixed_frame),
        *_topics(spec, entries, xacro_rel),
        *_save_frames(spec, images),
    ]
    return "\n".join(lines)
