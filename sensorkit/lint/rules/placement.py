"""SK410: a sensor setting written where sdformat's schema does not put it.

sdformat keeps an element its schema does not define as an unknown child, and the sensor
reads its settings only from their own element: ``<image>`` directly under ``<sensor>``
leaves the ``<camera>`` at 320x240, ``<plugin>`` inside ``<camera>`` is never loaded. The
schemas, per target, and the parser lines are in :mod:`sensorkit.knowledge.sdf_schema`.

Only a name the schema defines in the other element is reported (a misplaced setting);
an element defined nowhere near, or with a namespace prefix (SDF's custom elements, which
sdformat never warns about), is not: a plugin or simulator may read it, and sensorkit
cannot tell.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from lxml import etree

from sensorkit.base.consequence import Consequence, Role, same_value
from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.sdf_schema import (
    CAMERA_DEFAULTS,
    READ_ANYWAY,
    SETTING_DEFAULTS,
    SETTING_ROLE,
    Schema,
    schema,
)
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.parse import child, local, text_of
from sensorkit.model.sensors import Sensor
from sensorkit.model.targets import is_gz

# A sensor-level setting lost inside <camera>/<ray>/<imu>: <plugin> is never loaded (Gazebo
# Classic loads the sensor's own <plugin> children: elysia-best/gazebo-classic@upstream/
# 11.10.2+dfsg:gazebo/sensors/Sensor.cc:166-172; gz-sim those of sdf::Sensor, which reads
# them from <sensor>: gazebosim/sdformat@sdf14:src/Sensor.cc:423, gazebosim/gz-sim@gz-sim8:
# src/SdfEntityCreator.cc:1234-1235), <update_rate> falls to its default 0,
# "the sensor will generate data every cycle" (gazebosim/sdformat@sdf9 9ee2d4f:
# sdf/1.7/sensor.sdf:42-44, @sdf14 8512585:sdf/1.11/sensor.sdf:46-48). Each is judged by
# sensorkit.base.consequence (issue 35): the value written against the one that applies,
# with the setting's role from knowledge.sdf_schema SETTING_ROLE: a plugin never loaded
# (OUTPUT) an error, an update rate (RATE) a warning, a value equal to the default info.


def _plain(el: etree._Element) -> str | None:
    """The element's name, or None for comments and namespaced (custom) elements."""
    if not isinstance(el.tag, str) or el.tag.startswith("{") or ":" in el.tag:
        return None
    return local(el) or None


def _zero_noise(el: etree._Element) -> bool:
    """A <noise> that adds nothing: type none, or every number in it 0 (the type is an
    attribute, default none: gazebosim/sdformat@sdf9 9ee2d4f:sdf/1.7/noise.sdf:4)."""
    if el.get("type") == "none" or text_of(el, "type") == "none":
        return True
    texts = [(c.text or "").strip() for c in el.iter() if c is not el and len(c) == 0]
    try:
        return all(
            float(x) == 0.0 for x in texts if x and x not in ("gaussian", "gaussian_quantized")
        )
    except ValueError:
        return False


def _homes(s: Sensor, target: str) -> tuple[str, list[etree._Element]] | None:
    """The element a sensor's own settings live in, and its instances in the sensor."""
    if s.is_camera:
        return "camera", [c.element for c in s.cameras]
    if s.kind == "imu":
        imu = child(s.element, "imu")
        return "imu", [] if imu is None else [imu]
    if s.kind == "lidar":
        for tag in ("ray", "lidar"):
            el = child(s.element, tag)
            if el is not None:
                return tag, [el]
        classic_ray = not is_gz(target) or s.type in ("ray", "gpu_ray")
        return ("ray" if classic_ray else "lidar"), []
    return None


@rule(
    "SK410",
    "error/warning/info",
    "a sensor setting written where sdformat's schema for the target's SDF version does not put "
    "it, so it is lost: <camera>/<ray>/<lidar>/<imu> settings directly under <sensor> (the camera "
    "runs at its default 320x240, 1.047 rad), <plugin>, <update_rate> and other sensor-level tags "
    "inside them. Severity by consequence: the value written against the one that applies (the "
    "default, or the copy its own element sets): equal is info; a differing geometry, "
    "calibration, topic or a plugin never loaded an error; a rate, noise or flag a warning; two "
    "differing copies, of which sensorkit cannot tell the one meant, a warning. Unknown names and "
    "namespaced custom elements are never reported",
    formats=("urdf", "sdf"),
)
def misplaced_settings(ctx: Context) -> Iterator[Finding]:
    top = schema(ctx.target, "sensor")
    if top is None:
        return
    for s in ctx.robot.sensors:
        homes = _homes(s, ctx.target)
        if homes is None:
            continue
        home_schema = schema(ctx.target, homes[0])
        if home_schema is None:
            continue
        yield from _under_sensor(ctx, s, top, home_schema, homes[1])
        for home in homes[1]:
            yield from _inside_home(ctx, s, top, home_schema, home)


def _value(el: etree._Element) -> str | dict[str, str]:
    """What a setting holds: its text, or its leaf children's texts by name."""
    leaves = {
        local(c): (c.text or "").strip()
        for c in el
        if isinstance(c.tag, str) and len(c) == 0
    }
    return leaves if len(el) else (el.text or "").strip()


def _shown(value: object) -> str:
    if isinstance(value, dict):
        return ", ".join(f"{k} {v}" for k, v in value.items()) or "nothing"
    return str(value)


def _same(written: str | dict[str, str], used: object, *, default: bool = True) -> bool:
    """Whether a written setting holds what applies anyway: ``used`` a default (a number, a
    word, or children's defaults by name: a child left out takes its default) or, with
    ``default=False``, the copy read (the same children, the same values)."""
    if isinstance(used, dict) or isinstance(written, dict):
        if not (isinstance(used, dict) and isinstance(written, dict)):
            return False
        if not set(written) <= set(used) or (not default and set(written) != set(used)):
            return False
        return all(same_value(written.get(k, v), v) for k, v in used.items())
    return same_value(written, used)


def _same_fov(written: str, default: float, s: Sensor) -> bool:
    """Whether a field of view lost to the default draws the same image: the image edge moves
    by at most SK409's one pixel (EDGE_PX) at the width the camera runs with (1.0471976,
    pi/3, is the default 1.047 to 0.07 px at 640 wide)."""
    from sensorkit.knowledge.limits import EDGE_PX
    from sensorkit.model.parse import parse_float

    h, _ = parse_float(written)
    if h is None or not 0 < h < math.pi:
        return False
    cam = s.camera
    width = cam.width if cam is not None and cam.width else 320
    fx_written, fx_used = 1 / math.tan(h / 2), 1 / math.tan(default / 2)
    return width / 2 * abs(fx_written - fx_used) / fx_used <= EDGE_PX


def _role(name: str) -> Role:
    return SETTING_ROLE.get(name, Role.GEOMETRY)


def _under_sensor(
    ctx: Context, s: Sensor, top: Schema, home: Schema, homes: list[etree._Element]
) -> Iterator[Finding]:
    """<camera>/<ray>/<imu> settings written directly under <sensor>."""
    tag = home.element
    for el in s.element:
        name = _plain(el)
        if name is None or name in top.children or name in READ_ANYWAY:
            continue
        if name not in home.children:
            continue
        why = (
            f"sdformat {home.branch} (SDF {home.version}) defines <{name}> inside <{tag}> "
            f"({home.cite(name)}), not in <sensor> ({top.cite()}): it keeps it as an unknown element"
        )
        written = _value(el)
        if homes and all(child(h, name) is not None for h in homes):
            own = child(homes[0], name)
            assert own is not None
            used = _value(own)
            text = (
                f"sensor {s.name!r}: <{name}> directly under <sensor> is never read ({why}); "
                f"<{tag}> sets its own <{name}>, which is the one used"
            )
            fix = f"remove the <{name}> under <sensor>"
            if _same(written, used, default=False):
                c = Consequence(_role(name), _shown(written), _shown(used), equal=True)
                yield ctx.judged("SK410", c, text, el, sensor=s.name, fix=fix)
            else:
                # Two different values written: which one the author meant sensorkit cannot
                # tell, so it promises no broken sensor (a warning, not the role's error).
                yield ctx.finding(
                    "SK410",
                    Severity.WARNING,
                    f"{text} (written {_shown(written)} here; the simulator uses {_shown(used)})",
                    el,
                    sensor=s.name,
                    fix=fix,
                )
            continue
        default = SETTING_DEFAULTS.get((tag, name)) if tag == "camera" else None
        if default is not None:
            used_text = f"its default {CAMERA_DEFAULTS.get(name, _shown(default))}"
            equal = _same(written, default)
            if name == "horizontal_fov" and isinstance(written, str) and isinstance(default, float):
                equal = _same_fov(written, default, s)
        elif name == "noise":
            # <noise type> defaults to none (gazebosim/sdformat@sdf9 9ee2d4f:sdf/1.7/noise.sdf:4)
            used_text, equal = "no noise", _zero_noise(el)
        else:
            used_text, equal = f"sdformat's default <{name}>", False
        c = Consequence(_role(name), _shown(written), used_text, equal=equal)
        yield ctx.judged(
            "SK410",
            c,
            f"sensor {s.name!r}: <{name}> directly under <sensor> is never read ({why}); the {tag} "
            f"runs with {used_text}",
            el,
            sensor=s.name,
            fix=f"move <{name}> inside <{tag}>",
        )


def _inside_home(
    ctx: Context, s: Sensor, top: Schema, home: Schema, home_el: etree._Element
) -> Iterator[Finding]:
    """Sensor-level tags (<plugin>, <update_rate>, ...) written inside <camera>/<ray>/<imu>."""
    tag = home.element
    for el in home_el:
        name = _plain(el)
        if name is None or name in home.children or name in READ_ANYWAY:
            continue
        if name not in top.children or name == tag:
            continue
        why = (
            f"sdformat {home.branch} (SDF {home.version}) defines <{name}> in <sensor> "
            f"({top.cite(name)}), not inside <{tag}> ({home.cite()})"
        )
        written = _value(el)
        own = child(s.element, name)
        if name == "plugin":
            what = "the plugin is never loaded, so it publishes nothing"
            c = Consequence(Role.OUTPUT, f"plugin {el.get('filename', '')}".strip(), "no plugin")
        elif own is not None:
            what = f"<sensor> sets its own <{name}>, which is the one used"
            c = Consequence(_role(name), _shown(written), _shown(_value(own)), equal=_same(written, _value(own), default=False))
        else:
            default = SETTING_DEFAULTS.get(("sensor", name))
            if default is None:
                what = "the sensor runs with sdformat's default"
                c = Consequence(_role(name), _shown(written), f"sdformat's default <{name}>")
            else:
                what = f"the sensor runs with sdformat's default {default}" + (
                    ": it updates every simulation step" if name == "update_rate" else ""
                )
                c = Consequence(_role(name), _shown(written), default, equal=_same(written, default))
        if own is not None and name != "plugin" and not c.equal:
            # Two different values written: sensorkit cannot tell which was meant.
            yield ctx.finding(
                "SK410",
                Severity.WARNING,
                f"sensor {s.name!r}: <{name}> inside <{tag}> is never read ({why}): {what} "
                f"(written {_shown(written)} here; the simulator uses {_shown(_value(own))})",
                el,
                sensor=s.name,
                fix=f"move <{name}> directly under <sensor>",
            )
            continue
        yield ctx.judged(
            "SK410",
            c,
            f"sensor {s.name!r}: <{name}> inside <{tag}> is never read ({why}): {what}",
            el,
            sensor=s.name,
            fix=f"move <{name}> directly under <sensor>",
        )
