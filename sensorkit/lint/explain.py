"""``sensorkit rules ID``: what a rule checks, why it matters, a bad and a good example.

Examples are short URDF fragments. tests/test_cli_conventions.py puts the SK502, SK505 and
SK602 ones into a robot: the bad one must trigger the rule and the good one must not.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Example:
    why: str  # what goes wrong at run time
    bad: str  # a fragment that triggers the rule
    good: str  # the same fragment written right


OPTICAL_JOINT = (
    '<joint name="camera_optical_joint" type="fixed">\n'
    '  <parent link="camera_link"/><child link="camera_optical_frame"/>\n'
    '  <origin xyz="0 0 0" rpy="{rpy}"/>\n'
    "</joint>"
)

EXAMPLES: dict[str, Example] = {
    "SK502": Example(
        why=(
            "ROS reads image data in an optical frame (z forward, x right, y down; REP 103). "
            "A camera that stamps its images with its body link (x forward, z up) makes RViz "
            "and every consumer place the point cloud rotated: it points at the sky or the floor."
        ),
        bad='<plugin name="cam" filename="libgazebo_ros_camera.so">\n'
        "  <frame_name>camera_link</frame_name>\n</plugin>",
        good='<plugin name="cam" filename="libgazebo_ros_camera.so">\n'
        "  <frame_name>camera_optical_frame</frame_name>\n</plugin>\n"
        + OPTICAL_JOINT.format(rpy="${-pi/2} 0 ${-pi/2}"),
    ),
    "SK505": Example(
        why=(
            "-1.57 is not -pi/2: the optical frame is off by 0.05 degrees, which a calibration "
            "or a long-range point cloud shows as a tilt."
        ),
        bad=OPTICAL_JOINT.format(rpy="-1.57 0 -1.57"),
        good=OPTICAL_JOINT.format(rpy="-1.5707963267948966 0 -1.5707963267948966"),
    ),
    "SK601": Example(
        why=(
            "ROS 1 plugin libraries do not exist in ROS 2's gazebo_plugins: Gazebo prints one "
            "line at start-up and the sensor publishes nothing."
        ),
        bad='<plugin name="laser" filename="libgazebo_ros_laser.so"/>',
        good='<plugin name="laser" filename="libgazebo_ros_ray_sensor.so">\n'
        "  <output_type>sensor_msgs/LaserScan</output_type>\n</plugin>",
    ),
    "SK602": Example(
        why="ROS 2 plugins do not read ROS 1 tags: the frame and topic you wrote are ignored.",
        bad='<plugin name="cam" filename="libgazebo_ros_camera.so">\n'
        "  <frameName>camera_optical_frame</frameName>\n</plugin>",
        good='<plugin name="cam" filename="libgazebo_ros_camera.so">\n'
        "  <frame_name>camera_optical_frame</frame_name>\n</plugin>",
    ),
    "SK412": Example(
        why=(
            "sdformat gives what a <lens><projection> or <intrinsics> block leaves out its "
            "defaults, fx=fy=277, cx=160, cy=120, whatever the image size: Gazebo Sim renders "
            "with them and publishes them in camera_info, so a right eye written with only "
            "<tx> sees a different image and stereo matching uses the wrong P."
        ),
        bad="<lens><projection><tx>-55.4</tx></projection></lens>",
        good="<lens><projection>\n  <p_fx>554.383</p_fx><p_fy>554.383</p_fy>"
        "<p_cx>320</p_cx><p_cy>240</p_cy>\n  <tx>-55.4</tx>\n</projection></lens>",
    ),
    "SK615": Example(
        why=(
            "ros_gz_bridge subscribes to the gz topic with the entry's gz type, and gz-transport "
            "runs a subscriber only for messages of its own type: a gpu_lidar publishes "
            "gz.msgs.LaserScan on its topic, so an entry that bridges it as an Image carries "
            "nothing and the ROS topic stays silent."
        ),
        bad="# a gpu_lidar with <topic>scan</topic>\n"
        "- gz_topic_name: scan\n  ros_topic_name: scan\n"
        "  ros_type_name: sensor_msgs/msg/Image\n  gz_type_name: gz.msgs.Image\n"
        "  direction: GZ_TO_ROS",
        good="- gz_topic_name: scan\n  ros_topic_name: scan\n"
        "  ros_type_name: sensor_msgs/msg/LaserScan\n  gz_type_name: gz.msgs.LaserScan\n"
        "  direction: GZ_TO_ROS",
    ),
    "SK301": Example(
        why=(
            "Gazebo drops a link without mass that a moving joint holds, and everything "
            "below it: the camera on it never exists in the simulation."
        ),
        bad='<link name="pan_link"/>',
        good='<link name="pan_link">\n  <inertial><mass value="0.05"/>\n'
        '  <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>\n</link>',
    ),
}


def explain(rule_id: str, fix: str) -> str:
    """The text of ``sensorkit rules ID``; ``fix``: how ``--fix`` fixes the rule (``safe``,
    ``unsafe``, ``safe/unsafe``, or ``""``: by hand), which the fix layer above knows."""
    from sensorkit.lint.rules import RULES

    info = RULES[rule_id]
    lines = [
        f"{rule_id} ({info.severity}): {info.title}",
        f"fix: {'with --fix (' + fix + ')' if fix else 'by hand'}",
        f"other tools: {info.existing}",
    ]
    ex = EXAMPLES.get(rule_id)
    if ex is not None:
        lines += ["", "why: " + ex.why, "", "bad:", _indent(ex.bad), "", "good:", _indent(ex.good)]
    return "\n".join(lines) + "\n"


def _indent(text: str) -> str:
    return "\n".join("    " + line for line in text.splitlines())
