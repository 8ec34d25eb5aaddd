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

from collections.abc import Iterator

from lxml import etree

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.sdf_schema import CAMERA_DEFAULTS, READ_ANYWAY, Schema, schema
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
# sdf/1.7/sensor.sdf:42-44, @sdf14 8512585:sdf/1.11/sensor.sdf:46-48): both errors; others
# (<always_on>, <topic>, <visualize>, ...) warnings.


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
    "error/warning",
    "a sensor setting written where sdformat's schema for the target's SDF version does not put "
    "it, so it is lost: <camera>/<ray>/<lidar>/<imu> settings directly under <sensor> (error: the "
    "camera runs at its default 320x240, 1.047 rad), <plugin> or <update_rate> inside them (error), "
    "other sensor-level tags there (warning); a copy its own element also sets (warning). Unknown "
    "names and namespaced custom elements are never reported",
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
        if homes and all(child(h, name) is not None for h in homes):
            yield ctx.finding(
                "SK410",
                Severity.WARNING,
                f"sensor {s.name!r}: <{name}> directly under <sensor> is never read ({why}); "
                f"<{tag}> sets its own <{name}>, which is the one used",
                el,
                sensor=s.name,
                fix=f"remove the <{name}> under <sensor>",
            )
            continue
        default = CAMERA_DEFAULTS.get(name) if tag == "camera" else None
        runs = f"its default {default}" if default else f"sdformat's default <{name}>"
        zero = name == "noise" and _zero_noise(el)
        if zero:
            runs += " (none), which the zero noise written would have been anyway"
        yield ctx.finding(
            "SK410",
            Severity.WARNING if zero else Severity.ERROR,
            f"sensor {s.name!r}: <{name}> directly under <sensor> is never read ({why}); the {tag} "
            f"runs with {runs}, not the values written",
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
        if name != "plugin" and child(s.element, name) is not None:
            sev, what = Severity.WARNING, f"<sensor> sets its own <{name}>, which is the one used"
        elif name == "plugin":
            sev, what = Severity.ERROR, "the plugin is never loaded, so it publishes nothing"
        elif name == "update_rate":
            sev, what = Severity.ERROR, "the sensor updates every simulation step"
        else:
            sev, what = Severity.WARNING, "the sensor runs with sdformat's default"
        yield ctx.finding(
            "SK410",
            sev,
            f"sensor {s.name!r}: <{name}> inside <{tag}> is never read ({why}): {what}",
            el,
            sensor=s.name,
            fix=f"move <{name}> directly under <sensor>",
        )
