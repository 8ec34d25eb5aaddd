"""What a plugin or a Gazebo Sim sensor publishes on, and which bridge entry carries it.

ROS 2 name resolution, the topics and services of gazebo_ros sensor plugins (after
remapping), the topics gz-sensors publishes (with a <topic> or on the scoped default) and
the matching of a gz topic against ros_gz_bridge entries. No rules: the topic, bridge and
frame rules read these, and so does ``sensorkit.describe``.
"""

from __future__ import annotations

import re

from sensorkit.knowledge.gazebo_sim import GZ_NAVSAT_SUFFIX, GZ_NAVSAT_TYPES, GZ_TYPE_DEFAULT_SUFFIX
from sensorkit.model.parse import text_of
from sensorkit.model.sensors import Plugin, Sensor


def resolve_name(name: str, ns: str, node: str) -> str:
    """ROS 2 name resolution (rcl) of a topic name for a node in ``ns``."""
    ns = "/" + ns.strip("/") if ns.strip("/") else ""
    if name.startswith("/"):
        return "/" + name.strip("/")
    if name.startswith("~"):
        rest = name[1:].lstrip("/")
        return f"{ns}/{node}" + (f"/{rest}" if rest else "")
    return f"{ns}/{name.strip('/')}"




def plugin_topics(p: Plugin, s: Sensor | None) -> list[str]:
    """Unresolved names a known sensor plugin publishes (before remapping)."""
    lib = p.library
    if lib == "gazebo_ros_camera" and s is not None:
        cam = p.param("camera_name") or s.name
        names = [f"{cam}/image_raw", f"{cam}/camera_info"]
        if s.kind == "depth":
            names += [f"{cam}/depth/image_raw", f"{cam}/depth/camera_info", f"{cam}/points"]
        if s.kind == "multicamera":
            names = []
            for c in s.cameras:
                names += [f"{cam}/{c.name}/image_raw", f"{cam}/{c.name}/camera_info"]
        # <triggered> is read from the plugin element, not the sensor's <camera>
        # (gazebo_ros_pkgs@d52f7c4 gazebo_plugins/src/gazebo_ros_camera.cpp:271
        # `_sdf->Get<bool>("triggered", false)`, _sdf being the plugin's SDF).
        if (p.param("triggered") or "").strip().lower() in ("true", "1"):
            names.append(f"{cam}/image_trigger")
        return names
    # Other sensor plugins: the topics the plugin table lists (gazebo_ros_camera's depend on
    # the sensor's kind, above). Parameters that rename a topic are ROS 1 only.
    from sensorkit.knowledge import plugins as known

    spec = known.lookup(p.filename, "ros2")
    if spec is None or spec.level != "sensor":
        return []
    return [
        p.param(param) or default if param else default for param, default in spec.topics if default
    ]


def plugin_services(p: Plugin) -> list[str]:
    """Unresolved names of services a known sensor plugin offers (remappable too)."""
    if p.library == "gazebo_ros_camera":
        # camera_info_manager creates "set_camera_info" relative to the node's namespace.
        return ["set_camera_info"]
    return []


def resolved_topics(p: Plugin, s: Sensor | None) -> list[tuple[str, str]]:
    """(unresolved, resolved-after-remapping) for a plugin's topics."""
    ns, node = p.namespace(), p.name
    rules = [(resolve_name(a, ns, node), resolve_name(b, ns, node)) for a, b, _ in p.remappings()]
    out = []
    for name in plugin_topics(p, s):
        full = resolve_name(name, ns, node)
        for src, dst in rules:
            if src == full:
                full = dst
                break
        out.append((name, full))
    return out


def gz_topics(s: Sensor) -> list[str]:
    """Topics a gz sensor publishes, from its <topic> (empty: gz's scoped default)."""
    if not s.topic:
        return []
    base = "/" + s.topic.strip("/")
    own = _own_subtopics(s, base)
    if own:
        return own
    if s.kind == "rgbd":
        return [f"{base}/image", f"{base}/depth_image", f"{base}/points", f"{base}/camera_info"]
    if s.kind == "depth":
        return [base, f"{base}/points", _info_topic(s, base)]
    if s.kind in ("camera", "multicamera"):
        return [base, _info_topic(s, base)]
    if s.kind == "lidar":
        return [base, f"{base}/points"]
    return [base]


def _own_subtopics(s: Sensor, base: str) -> list[str]:
    """A segmentation or bounding-box camera's topics (knowledge.gazebo_sim.gz_own_subtopics)."""
    from sensorkit.knowledge.gazebo_sim import gz_own_subtopics

    cam = s.camera
    box_type = text_of(cam.element, "box_type") if cam is not None else None
    return [topic for topic, _, _ in gz_own_subtopics(s.type, base, box_type)]


def _info_topic(s: Sensor, base: str) -> str:
    from sensorkit.knowledge.gazebo_sim import GZ_READS_CAMERA_INFO_TOPIC

    cam = s.camera
    if cam is not None and cam.camera_info_topic and s.type in GZ_READS_CAMERA_INFO_TOPIC:
        return "/" + cam.camera_info_topic.strip("/")
    parent = base.rsplit("/", 1)[0]
    return f"{parent}/camera_info"


# What a Gazebo Sim sensor with no <topic> publishes on: its scoped name plus a suffix
# (gazebosim/gz-sim@gz-sim8:src/rendering/RenderUtil.cc:1723-1725 sets
# scopedName(entity) + suffix, suffixes at :1737-1744; IMU: src/systems/imu/Imu.cc:201).
# The scoped name is /world/WORLD/model/MODEL/link/LINK/sensor/NAME.
GZ_DEFAULT_SUFFIX = {
    "camera": "/image",
    "depth": "/depth_image",
    "rgbd": "/image",  # rgbd_camera's suffix is "" and it publishes BASE/image, BASE/depth_image
    "lidar": "/scan",
    "imu": "/imu",
}


def norm_topic(topic: str) -> str:
    return "/" + topic.strip().strip("/")


def gz_primary_topic(s: Sensor) -> str | None:
    """The gz topic that carries a sensor's main data (None for kinds sensorkit does not know)."""
    suffix = GZ_TYPE_DEFAULT_SUFFIX.get(s.type) or GZ_DEFAULT_SUFFIX.get(s.kind)
    if suffix is None and s.type in GZ_NAVSAT_TYPES:
        # NavSat (kind "other"): gz-sim's NavSat system publishes scopedName + "/navsat"
        # (gazebosim/gz-sim@gz-sim8:src/systems/navsat/NavSat.cc:182-186), with a <topic>
        # on that topic alone (gz-sensors@gz-sensors8:src/NavSatSensor.cc:107-111).
        suffix = GZ_NAVSAT_SUFFIX
    if suffix is None:
        return None
    if s.topic:
        topics = gz_topics(s)
        return topics[0] if topics else None
    return f"/sensor/{s.name}{suffix}"  # the tail of the scoped name


def is_bridged(topic: str, scoped: bool, bridged: set[str]) -> bool:
    """``topic`` is carried by one of the bridged gz topics.

    A scoped topic is matched by its tail (``/sensor/NAME/image``): the world and model
    names are the launch's. Placeholders that a launch file fills in before starting the
    bridge (``<namespace>``, ``$(var x)``) match any one name.
    """
    if scoped:
        tail = topic.rstrip("/") + "/"
        return any(tail in b + "/" for b in bridged)
    want = norm_topic(topic)
    for b in bridged:
        if "<" in b or "$(" in b:
            parts = re.split(r"<[^>]*>|\$\([^)]*\)", b)
            if re.fullmatch("[^/]*".join(re.escape(x) for x in parts), want):
                return True
        elif b == want:
            return True
    return False

