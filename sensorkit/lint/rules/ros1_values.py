"""What an ignored ROS 1 tag costs under ROS 2: SK602's severity by consequence.

A ROS 2 plugin never reads a ROS 1 tag, so what it does is what it does without it: the
tag's ROS 2 form when written, else the ROS 2 default. ``consequence`` compares that with
the value the ROS 1 tag holds. Equal (or a tag no plugin ever read): info, nothing
changes. Different: the tag's role says how much (``ROS1_PARAM_ROLE`` in
sensorkit.knowledge.gazebo_ros, with sources). Not known: a warning, since sensorkit cannot
say the value changes anything.
"""

from __future__ import annotations

import math

from sensorkit.base.findings import Severity
from sensorkit.knowledge.gazebo_ros import (
    ROS1_CAMERA_RELATIVE,
    ROS1_PARAM_ROLE,
    ROS1_RENAMES,
    ROS1_SENSOR_RATE_TAGS,
    ROS1_TOPIC_REMAPS,
    ROS1_UNUSED_BY_ROS1,
    ROS1_VALUE_SPELLINGS,
    ROS1_ZERO_MEANS_DEFAULT,
    ROS2_PLAIN_DEFAULTS,
)
from sensorkit.lint.rules.base import Context
from sensorkit.lint.rules.topic_names import resolve_name
from sensorkit.model.sensors import Plugin, Sensor

__all__ = ["consequence", "full_name"]

_BY_ROLE = {
    "name": (Severity.ERROR, "the topic, namespace or frame is not the one written"),
    "calibration": (Severity.ERROR, "the calibration published is not the one written"),
    "drive": (Severity.ERROR, "the drive moves other joints or with other geometry than written"),
    "behaviour": (Severity.WARNING, "the sensor works, not as tuned"),
}
# ROS 1 camera utils' distortion tags and the SDF <distortion> child ROS 2 reads instead.
_DISTORTION = {
    "distortionK1": "k1",
    "distortionK2": "k2",
    "distortionK3": "k3",
    "distortionT1": "p1",
    "distortionT2": "p2",
}


def consequence(ctx: Context, p: Plugin, tag: str, value: str) -> tuple[Severity, str]:
    """(severity, what to add to the message) for ROS 1 ``tag`` holding ``value`` in ``p``."""
    role = ROS1_PARAM_ROLE.get(tag, "behaviour")
    if role == "nothing" or tag in ROS1_UNUSED_BY_ROS1.get(p.library, ()):
        return Severity.INFO, ", and no ROS 1 plugin used it either: nothing changes"
    if tag in ROS1_TOPIC_REMAPS.get(p.library, {}):
        return _compare(role, value, *_topics(p, tag, value))
    ros2 = _ros2_value(ctx, p, tag)
    if ros2 is None:
        return Severity.WARNING, " and says nothing"
    if tag in ROS1_ZERO_MEANS_DEFAULT | {"CxPrime", "focalLength"} and _number(value) == 0:
        # 0 means "computed" in ROS 1 (gazebo_ros_camera_utils.cpp:504-519), as the ROS 2
        # default is computed (gazebo_ros_camera.cpp:359-374).
        return (
            Severity.INFO,
            f"; 0 means the computed default, which ROS 2 uses too ({ros2}): nothing changes",
        )
    if tag in ROS1_SENSOR_RATE_TAGS and p.sensor is not None:
        return _rate(value, ros2)
    return _compare(role, value, value, ros2)


def _compare(role: str, value: str, ros1: str, ros2: str | None) -> tuple[Severity, str]:
    if ros2 is None:
        return Severity.WARNING, " and says nothing"
    if _same(ros1, ros2):
        return Severity.INFO, f"; ROS 2 does the same without it ({ros2}): nothing changes"
    severity, what = _BY_ROLE.get(role, _BY_ROLE["behaviour"])
    shown = ros1 if ros1 == value else f"{value}, i.e. {ros1}"
    return severity, f": ROS 2 uses {ros2} where this says {shown}, so {what}"


def _rate(value: str, sensor_rate: str) -> tuple[Severity, str]:
    """ROS 1 throttled publishing to the rate (0: not at all; gazebo_ros_camera_utils.cpp
    :441-444, gazebo_ros_imu_sensor.cpp:103-104); ROS 2 publishes at the sensor's rate."""
    v, r = _number(value), _number(sensor_rate)
    if v is not None and r is not None and (v == 0 or (r > 0 and v >= r)):
        return (
            Severity.INFO,
            f"; the sensor updates at {sensor_rate} Hz, so a throttle of {value} changes nothing",
        )
    return Severity.WARNING, f": ROS 2 publishes at the sensor's {sensor_rate} Hz, not {value} Hz"


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


def _same(a: str, b: str) -> bool:
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
