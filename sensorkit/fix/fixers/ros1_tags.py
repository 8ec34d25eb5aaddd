"""SK602: ROS 1 plugin tags in their ROS 2 form.

Each tag a ROS 1 plugin read and its ROS 2 form reads otherwise: a renamed parameter
(``frameName`` -> ``frame_name``), ``robotNamespace`` -> ``<ros><namespace>``, a topic
name -> ``<ros><remapping>``, ``<remap>`` -> ``<remapping>``, and the rate or
``alwaysOn`` that became the sensor's own ``<update_rate>``/``<always_on>``.
"""

from __future__ import annotations

import re

from lxml import etree

from sensorkit.base.findings import Finding
from sensorkit.fix.registry import Fix, FixContext, fixer, is_expr
from sensorkit.fix.source import Deferred, NotFixable, escape
from sensorkit.knowledge.gazebo_ros import (
    ROS1_CAMERA_RELATIVE,
    ROS1_RENAMES,
    ROS1_SENSOR_RATE_TAGS,
    ROS1_TO_ROS2_PARAMS,
    ROS1_TOPIC_REMAPS,
    ROS1_ZERO_MEANS_DEFAULT,
)
from sensorkit.model.parse import child, children, local
from sensorkit.model.robot import all_plugins
from sensorkit.model.sensors import Plugin

__all__ = ["port_ros1_param"]

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
    w, raw = fx.written_text(el)
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
    w, raw = fx.written_text(el)
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
            cam, cam_raw = _value(cam_el), fx.written_text(cam_el)[1].strip()
            if is_expr(cam_raw) and not fx.written(p.element).encloses(fx.written(cam_el)):
                raise NotFixable("<camera_name> is written elsewhere")
            source, source_raw = f"{cam}/{base}", f"{cam_raw}/{base}"
        else:
            s = p.sensor
            if s is None:
                raise NotFixable("the camera plugin is not in a sensor")
            ws = fx.written(s.element)
            name_attr = ws.tag.attr("name")
            sensor_raw = name_attr.raw if name_attr is not None else s.name
            if not is_expr(sensor_raw):
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
    w, raw = fx.written_text(el)
    raw, value = raw.strip(), _value(el)
    ws = fx.written(s.element)
    if is_expr(raw) and not ws.encloses(w):
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
    wh, have_raw = fx.written_text(have)
    if is_expr(have_raw):
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
