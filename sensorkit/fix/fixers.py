"""The fixers, one per rule (see :mod:`sensorkit.fix.registry` for the contract).

Each finds the element its finding is about in the model, locates it where it is
written, and edits only that element (an attribute value, a tag name, a child). Text a
xacro expression or a macro parameter produces is never rewritten: the fix would have to
be made where the value comes from.
"""

from __future__ import annotations

import math
import re
from xml.sax.saxutils import escape

from lxml import etree

from sensorkit.base.findings import Finding
from sensorkit.fix.registry import Fix, FixContext, Written, fixer
from sensorkit.fix.source import Deferred, Edit, NotFixable
from sensorkit.knowledge.gazebo_ros import (
    ROS1_CAMERA_RELATIVE,
    ROS1_ONLY,
    ROS1_RENAMES,
    ROS1_SENSOR_RATE_TAGS,
    ROS1_TO_ROS2_PARAMS,
    ROS1_TOPIC_REMAPS,
    ROS1_ZERO_MEANS_DEFAULT,
)
from sensorkit.model.frames import GZ_FRAME_TAGS, SensorFrames, optical_frame_at
from sensorkit.model.parse import child, children, local
from sensorkit.model.robot import all_plugins
from sensorkit.model.sensors import Plugin, Sensor
from sensorkit.model.targets import is_gz

_EXPR = re.compile(r"\$[{(]")
HALF_PI = math.pi / 2
ANGLE_TOL = math.radians(0.5)  # as SK502/SK505
OPTICAL_RPY_XACRO = "${-pi/2} 0 ${-pi/2}"
OPTICAL_RPY_URDF = f"{-HALF_PI!r} 0 {-HALF_PI!r}"


# ----------------------------------------------------------------------------- helpers


def _is_expr(raw: str | None) -> bool:
    return raw is not None and bool(_EXPR.search(raw))


def _num(v: float) -> str:
    """A number as URDF text: full precision, no trailing ``.0``, no ``-0``."""
    if v == 0:
        return "0"
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


def _sensor(fx: FixContext, f: Finding) -> Sensor:
    matches = [s for s in fx.robot.sensors if s.name == f.sensor]
    exact = [s for s in matches if s.source == f.source]
    if not (exact or matches):
        raise NotFixable(f"sensor {f.sensor!r} not found")
    return (exact or matches)[0]


def _text(fx: FixContext, el: etree._Element) -> tuple[Written, str]:
    """Where a text-only element is written, and its text as written."""
    w = fx.written(el)
    raw = w.file.raw_text(w.tag)
    if raw is None:
        raise NotFixable(f"<{w.tag.name}> at {w.where} holds more than text")
    return w, raw


def _name_sources(fx: FixContext, link: str) -> list[tuple[Written, str]]:
    """Places whose text evaluates to link name ``link``: its ``<link name>`` and the
    ``<gazebo reference>`` of blocks about it, as written."""
    out: list[tuple[Written, str]] = []
    elements: list[tuple[etree._Element, str]] = []
    lk = fx.robot.link_map.get(link)
    if lk is not None:
        elements.append((lk.element, "name"))
    elements += [(g.element, "reference") for g in fx.robot.gazebo if g.reference == link]
    for el, attr in elements:
        try:
            w = fx.written(el)
        except NotFixable:
            continue
        a = w.tag.attr(attr)
        if a is not None:
            out.append((w, a.raw))
    return out


def _frame_target(
    fx: FixContext, s: Sensor, fr: SensorFrames
) -> tuple[Written, str, etree._Element | None]:
    """Where a sensor's frame is named: the element to write in (plugin or sensor), the
    tag, and the element already naming it (None: add one)."""
    if is_gz(fx.target):
        cam = s.camera
        if fr.image_frame is not None and fr.image_how == "optical_frame_id" and cam is not None:
            return (
                fx.written(cam.element),
                "optical_frame_id",
                child(cam.element, "optical_frame_id"),
            )
        tags = GZ_FRAME_TAGS[fx.target]
        tag = fr.how if fr.how in tags else tags[0]
        return fx.written(s.element), tag, child(s.element, tag)
    p, spec = fr.plugin, fr.spec
    if p is None or spec is None or not spec.frame_params:
        raise NotFixable(f"sensor {s.name!r} has no plugin sensorkit knows that names a frame")
    for ros1, ros2 in ROS1_RENAMES.get(p.library, {}).items():
        pending = child(p.element, ros1) is not None and child(p.element, ros2) is None
        if fx.target == "classic" and ros2 in spec.frame_params and pending:
            raise Deferred(f"its <{ros1}> becomes <{ros2}> first (SK602)")
    tag = fr.how if fr.how in spec.frame_params else spec.frame_params[0]
    return fx.written(p.element), tag, child(p.element, tag)


def _name_frame(
    fx: FixContext, s: Sensor, value: str, sources: list[tuple[Written, str]]
) -> tuple[list[Edit], frozenset[str]]:
    """Edits that make ``s`` stamp its data with frame ``value``."""
    fr = fx.ctx.frames_of(s)
    scope, tag, el = _frame_target(fx, s, fr)
    text = fx.text_for(value, sources, scope)
    claims = frozenset({f"frame:{scope.where}"})
    if el is None:
        return [scope.file.insert_child(scope.tag, [(0, f"<{tag}>{text}</{tag}>")])], claims
    w, raw = _text(fx, el)
    if _is_expr(raw):
        raise NotFixable(
            f"<{tag}>{raw.strip()}</{tag}> at {w.where} is a xacro expression: "
            "change it where its value comes from"
        )
    return [w.file.set_text(w.tag, text)], claims


def _body_frame_at(fx: FixContext, fr: SensorFrames) -> str | None:
    """A link at a lidar's render pose with the same orientation (x forward, z up)."""
    if fr.T_world_render is None:
        return None
    import numpy as np

    from sensorkit.model.transforms_np import rotation_angle

    robot = fx.robot
    names = ([fr.link] if fr.link else []) + [lk.name for lk in robot.links]
    for name in names:
        T = robot.T_world_link(name)
        if T is None or (fr.link and robot.tree_of(name) != robot.tree_of(fr.link)):
            continue
        if float(np.linalg.norm(T[:3, 3] - fr.T_world_render[:3, 3])) > 1e-3:
            continue
        if rotation_angle(fr.T_world_render[:3, :3].T @ T[:3, :3]) <= ANGLE_TOL:
            return name
    return None


# ----------------------------------------------------------------------------- SK505


_NUMBER = re.compile(r"(?<!\S)[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?!\S)")


def _mask_expressions(raw: str) -> str:
    """``raw`` with every ``${...}``/``$(...)`` replaced by as many ``x`` (not numbers)."""
    out = list(raw)
    i = 0
    while True:
        m = _EXPR.search(raw, i)
        if m is None:
            break
        close = "}" if m.group(0) == "${" else ")"
        depth, j = 0, m.end() - 1
        while j < len(raw):
            if raw[j] == m.group(0)[1]:
                depth += 1
            elif raw[j] == close:
                depth -= 1
                if depth == 0:
                    break
            j += 1
        for k in range(m.start(), min(j + 1, len(raw))):
            out[k] = "x"
        i = j + 1
    return "".join(out)


def exact_angles(raw: str, *, xacro: bool) -> str:
    """``raw`` with every literal angle within half a degree of a multiple of pi/2 written
    exactly (xacro: ``${-pi/2}``; URDF: full precision); expressions stay as they are."""
    masked = _mask_expressions(raw)
    parts: list[str] = []
    last = 0
    for m in _NUMBER.finditer(masked):
        v = float(m.group(0))
        for k in (0, -1, 1, -2, 2):
            exact = k * HALF_PI
            if v != exact and abs(v - exact) <= ANGLE_TOL:
                if k == 0:
                    text = "0"
                elif xacro:
                    text = {-1: "${-pi/2}", 1: "${pi/2}", -2: "${-pi}", 2: "${pi}"}[k]
                else:
                    text = _num(exact)
                parts += [raw[last : m.start()], text]
                last = m.end()
                break
    parts.append(raw[last:])
    return "".join(parts)


@fixer(
    "SK505",
    "safe",
    "write the optical rotation exactly (`${-pi/2}` in xacro, `-1.5707963267948966` in URDF); "
    "only the approximate numbers change",
)
def exact_optical(fx: FixContext, f: Finding) -> Fix:
    joint = fx.robot.joint_map.get(f.joint or "")
    origin = child(joint.element, "origin") if joint is not None else None
    if origin is None:
        raise NotFixable(f"joint {f.joint!r} has no <origin> to edit")
    w = fx.written(origin)
    a = w.tag.attr("rpy")
    if a is None:
        raise NotFixable(f"<origin> at {w.where} has no rpy as written")
    new = exact_angles(a.raw, xacro=fx.xacro)
    if new == a.raw:
        raise NotFixable(
            f'rpy="{a.raw}" at {w.where} is computed by xacro: write the exact angle where its value comes from'
            if _is_expr(a.raw)
            else f'rpy="{a.raw}" at {w.where} holds no approximate angle'
        )
    return Fix(f, (w.file.set_attr(a, new),), f'rpy "{a.raw}" -> "{new}"')


# ----------------------------------------------------------------------------- SK601

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
    if a is None or _is_expr(a.raw):
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


# ----------------------------------------------------------------------------- SK602

_PARAM_RE = re.compile(r"^<(\w+)> is a ROS 1 parameter")


def _ros1_param(fx: FixContext, f: Finding) -> tuple[Plugin, etree._Element]:
    m = _PARAM_RE.match(f.message)
    tag = m.group(1) if m else "remap" if f.message.startswith("<remap ") else None
    for p in all_plugins(fx.robot):
        if (p.sensor.name if p.sensor else None) != f.sensor:
            continue
        ros = p.ros_block()
        pool = (
            p.param_elements()
            if tag != "remap"
            else children(ros, "remap")
            if ros is not None
            else []
        )
        for el in pool:
            if local(el) == tag and fx.robot.document.locate(el) == f.source:
                return p, el
    raise NotFixable("the ROS 1 tag is not found")


def _value(el: etree._Element) -> str:
    return (el.text or "").strip()


def _rename(fx: FixContext, f: Finding, p: Plugin, el: etree._Element, new: str) -> Fix:
    tag = local(el)
    w = fx.written(el)
    have = child(p.element, new)
    if have is not None:
        if _value(have) != _value(el):
            raise NotFixable(
                f"the plugin has <{new}>{_value(have)}</{new}> too: remove the <{tag}> you do not mean"
            )
        return Fix(f, (w.file.remove(w.tag),), f"remove <{tag}> (the plugin has the same <{new}>)")
    if tag in ROS1_ZERO_MEANS_DEFAULT:
        try:
            zero = float(_value(el)) == 0
        except ValueError:
            zero = False
        if zero:
            return Fix(
                f,
                (w.file.remove(w.tag),),
                f"remove <{tag}>0</{tag}> (0 meant the default in ROS 1; ROS 2 computes it when <{new}> is absent)",
            )
    claims = frozenset({f"param:{fx.written(p.element).where}:{new}"})
    return Fix(f, tuple(w.file.rename(w.tag, new)), f"<{tag}> -> <{new}>", claims=claims)


def _ros_block(
    fx: FixContext, p: Plugin, el: etree._Element, line: str, title: str, f: Finding
) -> Fix:
    """Put ``line`` into the plugin's ``<ros>`` (made in place of ``el`` if absent) and
    remove ``el``."""
    w = fx.written(el)
    ros = p.ros_block()
    if ros is not None:
        wr = fx.written(ros)
        edits = (wr.file.insert_child(wr.tag, [(0, line)]), w.file.remove(w.tag))
        return Fix(f, edits, title)
    block = [(0, "<ros>"), (1, line), (0, "</ros>")]
    claims = frozenset({f"ros:{fx.written(p.element).where}"})
    return Fix(f, (w.file.replace(w.tag, block),), title, claims=claims)


def _namespace(fx: FixContext, f: Finding, p: Plugin, el: etree._Element) -> Fix:
    w, raw = _text(fx, el)
    value = _value(el)
    ns = p.namespace()
    ros = p.ros_block()
    if ros is not None and child(ros, "namespace") is not None:
        if ns.strip("/") != value.strip("/"):
            raise NotFixable(
                f"the plugin has <ros><namespace>{ns}</namespace> too: remove the one you do not mean"
            )
        return Fix(
            f,
            (w.file.remove(w.tag),),
            "remove <robotNamespace> (the plugin has the same <ros><namespace>)",
        )
    if not value.strip("/"):
        return Fix(
            f,
            (w.file.remove(w.tag),),
            f"remove <robotNamespace>{value}</robotNamespace> (the root namespace is ROS 2's default)",
        )
    return _ros_block(
        fx,
        p,
        el,
        f"<namespace>{raw.strip()}</namespace>",
        "<robotNamespace> -> <ros><namespace>",
        f,
    )


def _join(*parts: str) -> str:
    return "/".join(x.strip("/") for x in parts if x.strip("/"))


def _topic(fx: FixContext, f: Finding, p: Plugin, el: etree._Element, base: str) -> Fix:
    tag = local(el)
    w, raw = _text(fx, el)
    raw, value = raw.strip(), _value(el)
    if not value:
        raise NotFixable(f"<{tag}> is empty")
    source, source_raw = base, base
    cam, cam_raw = "", ""
    if p.library in ROS1_CAMERA_RELATIVE:
        if child(p.element, "cameraName") is not None and child(p.element, "camera_name") is None:
            raise Deferred("its <cameraName> becomes <camera_name> first (SK602)")
        cam_el = child(p.element, "camera_name")
        if cam_el is not None:
            cam, cam_raw = _value(cam_el), _text(fx, cam_el)[1].strip()
            if _is_expr(cam_raw) and not fx.written(p.element).encloses(fx.written(cam_el)):
                raise NotFixable("<camera_name> is written elsewhere")
            source, source_raw = f"{cam}/{base}", f"{cam_raw}/{base}"
        else:
            s = p.sensor
            if s is None:
                raise NotFixable("the camera plugin is not in a sensor")
            ws = fx.written(s.element)
            name_attr = ws.tag.attr("name")
            sensor_raw = name_attr.raw if name_attr is not None else s.name
            if not _is_expr(sensor_raw):
                sensor_raw = escape(s.name)
            source, source_raw = f"{s.name}/{base}", f"{sensor_raw}/{base}"
    # ROS 1 advertised a relative name under <cameraName> (cameras) or the namespace.
    absolute = value.startswith("/")
    target = value if absolute else _join(cam, value)
    target_raw = raw if absolute else (f"{cam_raw}/{raw.lstrip('/')}" if cam_raw else raw)
    if not absolute and _join(source) == _join(target):
        return Fix(f, (w.file.remove(w.tag),), f"remove <{tag}> (ROS 2 publishes {source} already)")
    for src, dst, _ in p.remappings():
        if _join(src) == _join(source):
            if _join(dst) == _join(target) and dst.startswith("/") == target.startswith("/"):
                return Fix(f, (w.file.remove(w.tag),), f"remove <{tag}> (already remapped)")
            raise NotFixable(f"the plugin remaps {src} to {dst} already")
    return _ros_block(
        fx,
        p,
        el,
        f"<remapping>{source_raw}:={target_raw}</remapping>",
        f"<{tag}> -> <ros><remapping>{source}:={target}",
        f,
    )


def _to_sensor(fx: FixContext, f: Finding, p: Plugin, el: etree._Element, sdf_tag: str) -> Fix:
    """A ROS 1 plugin tag whose ROS 2 form is the sensor's own ``sdf_tag``."""
    tag = local(el)
    s = p.sensor
    if s is None:
        raise NotFixable(f"<{tag}> is on a model plugin: no sensor to move it to")
    w, raw = _text(fx, el)
    raw, value = raw.strip(), _value(el)
    ws = fx.written(s.element)
    if _is_expr(raw) and not ws.encloses(w):
        raise NotFixable(f"<{tag}> is computed by xacro outside the sensor")

    def same(a: str, b: str) -> bool:
        try:
            return float(a) == float(b)
        except ValueError:
            return (a.lower() in ("1", "true")) == (b.lower() in ("1", "true"))

    remove = w.file.remove(w.tag)
    if tag in ROS1_SENSOR_RATE_TAGS and same(value, "0"):
        return Fix(
            f,
            (remove,),
            f"remove <{tag}>0</{tag}> (unthrottled in ROS 1: the sensor's rate applies)",
        )
    have = child(s.element, sdf_tag)
    claims = frozenset({f"sensor:{ws.where}:{sdf_tag}"})
    if have is None:
        # A sensor rate the sensor did not have is what ROS 1 published at (safe); an
        # <always_on> ROS 1 never read changes behaviour (unsafe).
        before = p.element
        wp = fx.written(before)
        add = wp.file.insert_before(wp.tag, [(0, f"<{sdf_tag}>{raw}</{sdf_tag}>")])
        return Fix(
            f,
            (add, remove),
            f"<{tag}> -> the sensor's <{sdf_tag}>{value}</{sdf_tag}>",
            safe=tag != "alwaysOn",
            claims=claims,
        )
    if same(value, _value(have)):
        return Fix(f, (remove,), f"remove <{tag}> (the sensor has the same <{sdf_tag}>)")
    wh, have_raw = _text(fx, have)
    if _is_expr(have_raw):
        raise NotFixable(
            f"the sensor's <{sdf_tag}> is a xacro expression: decide the {sdf_tag} by hand"
        )
    return Fix(
        f,
        (wh.file.set_text(wh.tag, raw), remove),
        f"<{tag}> -> the sensor's <{sdf_tag}> ({_value(have)} -> {value})",
        safe=False,
        claims=claims,
    )


def _remap(fx: FixContext, f: Finding, el: etree._Element) -> Fix:
    w = fx.written(el)
    src, dst = w.tag.attr("from"), w.tag.attr("to")
    if src is None or dst is None:
        raise NotFixable("<remap> lacks from or to")
    line = f"<remapping>{src.raw}:={dst.raw}</remapping>"
    return Fix(f, (w.file.replace(w.tag, [(0, line)]),), f"<remap> -> {line}")


@fixer(
    "SK602",
    "safe/unsafe",
    "each ROS 1 tag with a direct ROS 2 form, in the ROS 2 layout: `frameName` -> `frame_name`, "
    "`cameraName` -> `camera_name` (and the other renames the plugin reads), `robotNamespace` -> "
    "`<ros><namespace>`, topic names -> `<ros><remapping>`, `<remap>` -> `<remapping>`, `updateRate` "
    "-> the sensor's `<update_rate>` (unsafe when the sensor has another one)",
)
def port_ros1_param(fx: FixContext, f: Finding) -> Fix:
    p, el = _ros1_param(fx, f)
    tag = local(el)
    if tag == "remap":
        return _remap(fx, f, el)
    lib = p.library
    if tag in ROS1_RENAMES.get(lib, {}):
        return _rename(fx, f, p, el, ROS1_RENAMES[lib][tag])
    if tag == "robotNamespace":
        return _namespace(fx, f, p, el)
    if tag in ROS1_TOPIC_REMAPS.get(lib, {}):
        return _topic(fx, f, p, el, ROS1_TOPIC_REMAPS[lib][tag])
    if tag in ROS1_SENSOR_RATE_TAGS:
        return _to_sensor(fx, f, p, el, "update_rate")
    if tag == "alwaysOn":
        return _to_sensor(fx, f, p, el, "always_on")
    raise NotFixable(
        f"<{tag}> has no direct ROS 2 form in {p.filename} ({ROS1_TO_ROS2_PARAMS.get(tag, 'none')}): port it by hand"
    )


# ----------------------------------------------------------------------------- SK502/503


def _optical_frame(fx: FixContext, f: Finding, s: Sensor, fr: SensorFrames) -> Fix:
    existing = optical_frame_at(fx.robot, fr.T_world_render)
    if existing is not None:
        edits, claims = _name_frame(fx, s, existing, _name_sources(fx, existing))
        return Fix(
            f,
            tuple(edits),
            f"publish in {existing!r}, the optical frame at the camera",
            claims=claims,
        )
    return _add_optical_frame(fx, f, s, fr)


def _add_optical_frame(fx: FixContext, f: Finding, s: Sensor, fr: SensorFrames) -> Fix:
    """Unsafe: a new ``LINK_optical_frame`` at the camera, and the sensor published in it."""
    robot = fx.robot
    link = fr.link
    if link is None or link not in robot.link_map:
        raise NotFixable("the sensor's link is not found")
    new_link, new_joint = f"{link}_optical_frame", f"{link}_optical_joint"
    for name, kind in ((new_link, "link"), (new_joint, "joint")):
        if name in robot.link_map or name in robot.joint_map:
            raise NotFixable(
                f"a {kind} {name!r} exists already but is not the camera's optical frame"
            )
    wl = fx.written(robot.link_map[link].element)
    a = wl.tag.attr("name")
    if a is None:
        raise NotFixable(f"<link> at {wl.where} has no name as written")
    import numpy as np

    from sensorkit.model.transforms_np import R_BODY_OPTICAL, matrix_to_rpy

    pose = s.pose
    if pose.rpy == (0.0, 0.0, 0.0):
        xyz = " ".join(_num(v) for v in pose.xyz)
        rpy = OPTICAL_RPY_XACRO if fx.xacro else OPTICAL_RPY_URDF
    else:
        T = pose.matrix()
        R = np.asarray(T[:3, :3]) @ R_BODY_OPTICAL
        xyz = " ".join(_num(float(v)) for v in T[:3, 3])
        rpy = " ".join(_num(v) for v in matrix_to_rpy(R))
    moved = pose.xyz != (0.0, 0.0, 0.0) or pose.rpy != (0.0, 0.0, 0.0)
    if moved and fx.copies_of(wl) > 1:
        raise NotFixable(
            f"{wl.where} is in a xacro macro used {fx.copies_of(wl)} times with a sensor <pose>: add the optical frame there by hand"
        )
    name_raw = a.raw if _is_expr(a.raw) else escape(link, {'"': "&quot;"})
    if not _is_expr(a.raw) and fx.copies_of(wl) > 1:
        raise NotFixable(
            f"{wl.where} is in a xacro macro used {fx.copies_of(wl)} times: add the optical frame there by hand"
        )
    lines = [
        (0, f'<joint name="{name_raw}_optical_joint" type="fixed">'),
        (1, f'<parent link="{name_raw}"/>'),
        (1, f'<child link="{name_raw}_optical_frame"/>'),
        (1, f'<origin xyz="{xyz}" rpy="{rpy}"/>'),
        (0, "</joint>"),
        (0, f'<link name="{name_raw}_optical_frame"/>'),
    ]
    add = wl.file.insert_after(wl.tag, lines)
    edits, claims = _name_frame(fx, s, new_link, [(wl, f"{a.raw}_optical_frame")])
    return Fix(
        f,
        (add, *edits),
        f"add link {new_link!r} (fixed joint {new_joint!r}, the exact optical rotation) and publish in it",
        safe=False,
        claims=claims | {f"optical:{wl.where}"},
    )


@fixer(
    "SK502",
    "safe/unsafe",
    "point the frame parameter at the optical frame already at the camera (safe); with none, add "
    "`LINK_optical_frame` on a fixed joint with the exact rotation and point at it (unsafe)",
)
def optical_frame(fx: FixContext, f: Finding) -> Fix:
    s = _sensor(fx, f)
    return _optical_frame(fx, f, s, fx.ctx.frames_of(s))


@fixer(
    "SK503",
    "safe/unsafe",
    "point the frame parameter at a frame at the render origin: the camera's optical frame or the "
    "lidar's own link (safe); a camera with none gets `LINK_optical_frame` (unsafe)",
)
def frame_at_origin(fx: FixContext, f: Finding) -> Fix:
    s = _sensor(fx, f)
    fr = fx.ctx.frames_of(s)
    if s.is_camera:
        return _optical_frame(fx, f, s, fr)
    body = _body_frame_at(fx, fr)
    if body is None:
        raise NotFixable(f"no link sits where {s.name!r} measures: add one at its <pose> by hand")
    edits, claims = _name_frame(fx, s, body, _name_sources(fx, body))
    return Fix(f, tuple(edits), f"publish in {body!r}, the link at the sensor", claims=claims)


# ----------------------------------------------------------------------------- SK303


@fixer(
    "SK303",
    "safe",
    "add the frame parameter (`<frame_name>` on ROS 2) naming the sensor's own link (a camera's "
    "optical frame)",
)
def explicit_frame(fx: FixContext, f: Finding) -> Fix:
    s = _sensor(fx, f)
    fr = fx.ctx.frames_of(s)
    if fr.link is None:
        raise NotFixable("the sensor's link is not found")
    frame = fr.link
    if s.is_camera:
        found = optical_frame_at(fx.robot, fr.T_world_render)
        if found is None:
            raise NotFixable("no optical frame at the camera yet (SK502's unsafe fix adds one)")
        frame = found
    edits, claims = _name_frame(fx, s, frame, _name_sources(fx, frame))
    return Fix(f, tuple(edits), f"name the frame {frame!r} in the plugin", claims=claims)


# ----------------------------------------------------------------------------- SK301

_PLACEHOLDER = [
    (0, "<inertial>"),
    (
        1,
        "<!-- sensorkit fix: a placeholder so Gazebo keeps this link (10 g, inertia of a 3 cm cube); put in the real mass and inertia -->",
    ),
    (1, '<mass value="0.01"/>'),
    (1, '<inertia ixx="1.5e-06" ixy="0" ixz="0" iyy="1.5e-06" iyz="0" izz="1.5e-06"/>'),
    (0, "</inertial>"),
]


@fixer(
    "SK301",
    "unsafe",
    "give a link without `<inertial>` a small documented placeholder (10 g, a 3 cm cube's inertia)",
)
def placeholder_inertial(fx: FixContext, f: Finding) -> Fix:
    link = fx.robot.link_map.get(f.link or "")
    if link is None:
        raise NotFixable(f"link {f.link!r} not found")
    if link.inertial is not None:
        raise NotFixable(
            f"link {link.name!r} has an <inertial> with zero mass: put in its real mass"
        )
    w = fx.written(link.element)
    return Fix(
        f,
        (w.file.insert_child(w.tag, _PLACEHOLDER),),
        f"add a placeholder <inertial> (10 g) to {link.name!r}",
        safe=False,
    )


__all__ = ["exact_angles"]
