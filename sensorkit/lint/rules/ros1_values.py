"""What an ignored ROS 1 tag costs under ROS 2: SK602's consequence (issue 35 item 1).

A ROS 2 plugin never reads a ROS 1 tag, so what it does is what it does without it: the
tag's ROS 2 form when written, else the ROS 2 default. ``consequence`` states that as a
:class:`~sensorkit.base.consequence.Consequence`: the role of the tag's value (from
``ROS1_PARAM_ROLE`` in sensorkit.knowledge.gazebo_ros, with sources), the value the ROS 1
tag holds (intended) and what the ROS 2 plugin uses (effective); severity_of makes it a
severity. A tag ROS 1 did not apply either changes nothing (info); a value sensorkit cannot
tell is UNKNOWN (info: a rule must know before it reports more).

A frame tag is compared as a frame (:mod:`sensorkit.lint.rules.coincide`): the frame
written and the one ROS 2 stamps are the same when they coincide, and for an IMU when they
are turned alike.
"""

from __future__ import annotations

import math

from sensorkit.base.consequence import UNKNOWN, Consequence, Role
from sensorkit.knowledge.gazebo_ros import (
    ROS1_CAMERA_RELATIVE,
    ROS1_PARAM_ROLE,
    ROS1_READ_BY_NO_PLUGIN,
    ROS1_RENAMES,
    ROS1_SENSOR_RATE_TAGS,
    ROS1_TOPIC_REMAPS,
    ROS1_UNUSED_BY_ROS1,
    ROS1_VALUE_SPELLINGS,
    ROS1_ZERO_MEANS_DEFAULT,
    ROS2_PLAIN_DEFAULTS,
)
from sensorkit.lint.rules.base import Context
from sensorkit.lint.rules.coincide import coincide_note, frame_consequence
from sensorkit.lint.rules.topic_names import resolve_name
from sensorkit.model.sensors import Plugin, Sensor

__all__ = ["consequence", "full_name", "same_name", "why"]

# ROS 1 camera utils' distortion tags and the SDF <distortion> child ROS 2 reads instead.
_DISTORTION = {
    "distortionK1": "k1",
    "distortionK2": "k2",
    "distortionK3": "k3",
    "distortionT1": "p1",
    "distortionT2": "p2",
}
_WHAT = {
    Role.FRAME: "the frame stamped is not the one written",
    Role.TOPIC: "the topic or namespace is not the one written",
    Role.CALIBRATION: "the calibration published is not the one written",
    Role.GEOMETRY: "the drive moves other joints or with other geometry than written",
}


def consequence(ctx: Context, p: Plugin, tag: str, value: str) -> tuple[Consequence, str]:
    """The consequence of ROS 1 ``tag`` holding ``value`` in ``p``, and words for the
    message (what ROS 2 does instead, or why nothing changes)."""
    role = ROS1_PARAM_ROLE.get(tag, Role.FLAG)
    unused = ROS1_READ_BY_NO_PLUGIN.get(tag) or ROS1_UNUSED_BY_ROS1.get(p.library, {}).get(tag)
    if unused is not None:
        # Applied by nothing in either generation: what it sets is nothing at all. The
        # words say what ROS 1 did with it (knowledge.gazebo_ros, with sources).
        return Consequence(Role.COSMETIC, value, None), f", and {unused}"
    if tag in ROS1_TOPIC_REMAPS.get(p.library, {}):
        ros1, ros2 = _topics(p, tag, value)
        shown = "" if ros1 == value else f" (ROS 1 resolved {value} to {ros1})"
        c = _compare(role, ros1, ros2)
        same_leaf = _same_leaf(p, tag, value, ros1, ros2, c)
        return (c, shown) if same_leaf is None else same_leaf
    ros2 = _ros2_value(ctx, p, tag)
    if ros2 is None:
        return Consequence(role, value, UNKNOWN), ""
    if tag in ROS1_ZERO_MEANS_DEFAULT | {"CxPrime", "focalLength"} and _number(value) == 0:
        # 0 means "computed" in ROS 1 (gazebo_ros_camera_utils.cpp:504-519), as the ROS 2
        # default is computed (gazebo_ros_camera.cpp:359-374).
        return (
            Consequence(role, value, ros2, equal=True),
            "; 0 means the computed default, which ROS 2 uses too",
        )
    if tag in ROS1_SENSOR_RATE_TAGS and p.sensor is not None:
        return _rate(value, ros2)
    if tag == "frameName" and p.sensor is not None and ros2:
        # A sensor plugin only stamps its frame; a drive's robotBaseFrame/odometryFrame are
        # published into TF as parent and child, where another name breaks the tree however
        # close the links sit, so only the sensor's frame is compared as a place.
        c = frame_consequence(ctx.robot, p.sensor, value, ros2)
        return c, coincide_note(ctx.robot, p.sensor, value, ros2) if c.equal else ""
    return _compare(role, value, ros2), ""


def _same_leaf(
    p: Plugin, tag: str, value: str, ros1: str, ros2: str | None, c: Consequence
) -> tuple[Consequence, str] | None:
    """A topic tag whose written (relative) name is the ROS 2 plugin's own leaf, in a plugin
    whose namespace or camera name tag SK602 reports on its own line: ignoring this tag
    changes nothing, the topic differs only through that other tag. None otherwise.

    E.g. <imageTopicName>image_raw</imageTopicName> beside <cameraName>: ROS 2's camera
    publishes camera_name + "/image_raw" and "/camera_info" (ros-simulation/gazebo_ros_pkgs@ros2
    d52f7c47:gazebo_plugins/src/gazebo_ros_camera.cpp:187, :200), so the leaf written is the
    leaf used, and what moves the topic is <cameraName> (or <robotNamespace>), judged there."""
    if ros2 is None or c.changes_nothing or value.startswith(("/", "~")):
        return None
    leaf = ROS1_TOPIC_REMAPS[p.library][tag]
    if value.strip("/") != leaf:
        return None
    movers = ["robotNamespace"] + (["cameraName"] if p.library in ROS1_CAMERA_RELATIVE else [])
    written = [f"<{t}>" for t in movers if p.param(t) is not None]
    if not written:
        return None  # nothing else reports the move: this tag's finding keeps it
    note = (
        f": the name written, {value}, is the ROS 2 plugin's own (it publishes {ros2}, ROS 1 "
        f"published {ros1}); the topic differs only through {' and '.join(written)}, "
        "reported on its own line"
    )
    return Consequence(Role.TOPIC, value, leaf, equal=True), note


def _compare(role: Role, ros1: str, ros2: str | None) -> Consequence:
    if ros2 is None:
        return Consequence(role, ros1, UNKNOWN)
    return Consequence(role, ros1, ros2, equal=same_name(ros1, ros2))


def why(c: Consequence) -> str:
    """Words for what a differing value's role changes (empty when nothing changes)."""
    what = _WHAT.get(c.role)
    return f", so {what}" if what and c.severity.label == "error" else ""


def _rate(value: str, sensor_rate: str) -> tuple[Consequence, str]:
    """ROS 1 throttled publishing to the rate (0: not at all; gazebo_ros_camera_utils.cpp
    :441-444, gazebo_ros_imu_sensor.cpp:103-104); ROS 2 publishes at the sensor's rate."""
    v, r = _number(value), _number(sensor_rate)
    same = v is not None and r is not None and (v == 0 or (r > 0 and v >= r))
    note = (
        f"; the sensor updates at {sensor_rate} Hz, so a throttle of {value} changes nothing"
        if same
        else f": ROS 2 publishes at the sensor's {sensor_rate} Hz"
    )
    return Consequence(Role.RATE, value, sensor_rate, equal=same), note


def _ros2_value(ctx: Context, p: Plugin, tag: str) -> str | None:
    """What the ROS 2 plugin does in place of ``tag``, written as the tag's value; None when
    sensorkit cannot tell."""
    new = ROS1_RENAMES.get(p.library, {}).get(tag)
    if new is not None and p.param(new) is not None:
        return p.param(new)
    s = p.sensor
    plain = ROS2_PLAIN_DEFAULTS.get(p.library, {}).get(tag)
    if plain is not None:
        return plain
    if tag == "robotNamespace":
        return "/" + p.namespace().strip("/")
    if s is None:
        return None
    if tag == "frameName":
        fr = ctx.frames_of(s)
        return fr.published if fr.plugin is p else None
    if tag == "cameraName":
        return s.name
    if tag in ROS1_SENSOR_RATE_TAGS:
        return "0" if s.update_rate is None else _fmt(s.update_rate)
    return _camera_value(s, p, tag)


def _camera_value(s: Sensor, p: Plugin, tag: str) -> str | None:
    cam = s.camera
    if cam is None or p.library != "gazebo_ros_camera":
        return None
    if tag in _DISTORTION:
        return _fmt(cam.distortion.get(_DISTORTION[tag], 0.0))
    if tag in ("Cx", "CxPrime") and cam.width:
        # ROS 2: cx defaults to (width + 1) / 2 (gazebo_ros_camera.cpp:359-360); P's cx is cx.
        return p.param("cx") or _fmt((cam.width + 1) / 2)
    if tag == "Cy" and cam.height:
        return _fmt((cam.height + 1) / 2)  # gazebo_ros_camera.cpp:362-363
    if tag == "focalLength" and cam.width and cam.hfov:
        return _fmt(cam.width / (2 * math.tan(cam.hfov / 2)))  # gazebo_ros_camera.cpp:366-374
    return None


def _topics(p: Plugin, tag: str, value: str) -> tuple[str, str | None]:
    """The name ROS 1 published ``tag`` on, and the name the ROS 2 plugin uses instead.

    ROS 1 named it relative to robotNamespace, and for cameras to robotNamespace/cameraName
    (noetic-devel f9e1a46:gazebo_plugins/src/gazebo_ros_camera_utils.cpp:288,
    gazebo_ros_imu_sensor.cpp:86-88 and :175-198, gazebo_ros_diff_drive.cpp via GazeboRos).
    ROS 2 names are in ``ROS1_TOPIC_REMAPS``' comment."""
    ns1 = (p.param("robotNamespace") or "").strip("/")
    ros2 = ROS1_TOPIC_REMAPS[p.library][tag]
    if p.library in ROS1_CAMERA_RELATIVE:
        base = "/".join(x for x in (ns1, (p.param("cameraName") or "").strip("/")) if x)
        camera = p.param("camera_name") or (p.sensor.name if p.sensor else None)
        if camera is None:
            return value, None
        ros2 = f"{camera}/{ros2}"
    else:
        base = ns1
    ros1 = (
        "/" + value.strip("/")
        if value.startswith("/")
        else "/" + "/".join(x for x in (base, value.strip("/")) if x)
    )
    return ros1, full_name(p, ros2)


def full_name(p: Plugin, name: str) -> str:
    """A name the ROS 2 plugin uses, resolved in its namespace, after its remappings."""
    ns, node = p.namespace(), p.name
    full = resolve_name(name, ns, node)
    for src, dst, _ in p.remappings():
        if resolve_name(src, ns, node) == full:
            return resolve_name(dst, ns, node)
    return full


def _number(text: str) -> float | None:
    try:
        return float(text)
    except ValueError:
        return None


def _fmt(x: float) -> str:
    return f"{x:g}"


def same_name(a: str, b: str) -> bool:
    """Equal as numbers (vectors too), booleans, names or ROS 1 spellings of a ROS 2 value."""
    a, b = a.strip(), b.strip()
    for table in ROS1_VALUE_SPELLINGS.values():
        a = table.get(a, a)
    words_a, words_b = a.split(), b.split()
    if words_a and len(words_a) == len(words_b):
        try:
            return all(
                math.isclose(float(x), float(y), rel_tol=1e-6, abs_tol=1e-9)
                for x, y in zip(words_a, words_b, strict=True)
            )
        except ValueError:
            pass
    bools = {"true": "1", "false": "0", "1": "1", "0": "0"}
    if a.lower() in bools and b.lower() in bools:
        return bools[a.lower()] == bools[b.lower()]
    # Names: ROS 1's tf::resolve drops a leading "/" from a frame (see stamped_frame), and
    # topic names here are already resolved.
    return a.removeprefix("/") == b.removeprefix("/")
