"""Everything a sensor block holds is accounted for (issue 35 item 3).

SK415: a child of ``<sensor>``, ``<camera>``, ``<ray>``/``<lidar>`` or ``<imu>`` that no SDF
version defines (``<vertical_fov>`` in ``<camera>``): sdformat keeps it as an unknown element
and the simulator never reads it. Misplaced names, defined in the other element, are SK410's;
namespaced custom elements and the gz frame tags (read from ``<sensor>``, SK608's) are not
judged; names inside ``<plugin>`` are the plugin's business.
SK416: a ``<pose>`` inside ``<camera>`` on Gazebo Sim, which renders the camera from the
sensor's pose only (Gazebo Classic composes the two).

Sources in :mod:`sensorkit.knowledge.sensor_blocks` and :mod:`sensorkit.knowledge.sdf_schema`.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from lxml import etree

from sensorkit.base.consequence import UNKNOWN, Consequence, Role
from sensorkit.base.findings import Finding
from sensorkit.knowledge.limits import ANGLE_TOL, EDGE_PX, POSITION_TOL
from sensorkit.knowledge.sdf_schema import READ_ANYWAY, SDFORMAT_OF_TARGET
from sensorkit.knowledge.sensor_blocks import (
    CAMERA_POSE_READ,
    CAMERA_POSE_SOURCE,
    EVER_DEFINED,
    MEANT,
    VFOV_SOURCE,
)
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.parse import child, local, parse_float
from sensorkit.model.sensors import CameraSpec, Sensor
from sensorkit.model.targets import is_gz

_HOMES = ("camera", "ray", "lidar", "imu")
_SCHEMA = "gazebosim/sdformat@sdf16 9a26f90:sdf/1.0..1.12/{}.sdf"


def _plain(el: etree._Element) -> str | None:
    """The element's name, or None for comments and namespaced (custom) elements."""
    if not isinstance(el.tag, str) or el.tag.startswith("{") or ":" in el.tag:
        return None
    return local(el) or None


def _blocks(s: Sensor) -> Iterator[tuple[str, etree._Element, CameraSpec | None]]:
    """``(element name, element, its camera)`` for the sensor and its settings blocks."""
    yield "sensor", s.element, None
    for cam in s.cameras:
        yield "camera", cam.element, cam
    for tag in ("ray", "lidar", "imu"):
        el = child(s.element, tag)
        if el is not None:
            yield tag, el, None


def _simulator(target: str) -> str:
    return "Gazebo Sim" if is_gz(target) else "Gazebo Classic"


@rule(
    "SK415",
    "error/warning/info",
    "an element in no SDF version's schema inside <sensor>, <camera>, <ray>/<lidar> or <imu> "
    "(e.g. <vertical_fov>): sdformat keeps it as unknown and the simulator never reads it. "
    "Severity from what it meant against what applies: <vertical_fov> against the vertical "
    "field of view the renderer derives from horizontal_fov and the aspect (error when the "
    "image's edge moves by more than 1 px), <imu><orientation> noise against none "
    "(warning); an element whose meaning sensorkit cannot tell: info",
    "sdformat (a warning, or nothing on sdformat9)",
    formats=("urdf", "sdf"),
)
def unknown_elements(ctx: Context) -> Iterator[Finding]:
    if ctx.target not in SDFORMAT_OF_TARGET:
        return
    settings = frozenset().union(*(EVER_DEFINED[h] for h in _HOMES))
    for s in ctx.robot.sensors:
        for block, el, cam in _blocks(s):
            for c in el:
                name = _plain(c)
                if name is None or name in EVER_DEFINED[block] or name in READ_ANYWAY:
                    continue
                if (block == "sensor" and name in settings) or (
                    block != "sensor" and name in EVER_DEFINED["sensor"]
                ):
                    continue  # a misplaced setting: SK410's
                yield _unknown(ctx, s, block, c, name, cam)


def _unknown(
    ctx: Context, s: Sensor, block: str, el: etree._Element, name: str, cam: CameraSpec | None
) -> Finding:
    sim = _simulator(ctx.target)
    branch = SDFORMAT_OF_TARGET[ctx.target]
    head = (
        f"sensor {s.name!r}: <{name}> inside <{block}> is in no SDF schema "
        f"({_SCHEMA.format(block)}): sdformat {branch} keeps it as an unknown element and "
        f"{sim} never reads it"
    )
    role = MEANT.get((block, name))
    if role == "geometry" and cam is not None:
        judged = _vertical_fov(ctx, s, el, name, cam, head)
        if judged is not None:
            return judged
    if role == "noise":
        written = _numbers(el)
        return ctx.judged(
            "SK415",
            Consequence(
                Role.NOISE,
                f"noise {list(written)}",
                "no noise",
                equal=all(v == 0.0 for v in written),
            ),
            f"{head}; no SDF version gives the <{block}>'s {name} a noise, so it is noise-free",
            el,
            sensor=s.name,
            fix=f"remove <{name}>",
        )
    text = (el.text or "").strip()
    return ctx.judged(
        "SK415",
        Consequence(Role.FLAG, text or f"<{name}>", UNKNOWN),
        f"{head}; what it was meant to set sensorkit cannot tell (a plugin reading the "
        "sensor's SDF could still read it)",
        el,
        sensor=s.name,
        fix=f"remove <{name}>, or move it where its setting is defined",
    )


def _numbers(el: etree._Element) -> tuple[float, ...]:
    out: list[float] = []
    for leaf in el.iter():
        if leaf is el or len(leaf) or not isinstance(leaf.tag, str):
            continue
        value, _ = parse_float(leaf.text)
        if value is not None:
            out.append(value)
    return tuple(out)


def _vertical_fov(
    ctx: Context, s: Sensor, el: etree._Element, name: str, cam: CameraSpec, head: str
) -> Finding | None:
    """<vertical_fov> against the one the renderer derives (None: not computable)."""
    written, _ = parse_float(el.text)
    width = cam.width if cam.width and cam.width > 0 else 320
    height = cam.height if cam.height and cam.height > 0 else 240
    hfov = cam.hfov if cam.hfov is not None else 1.047
    if (
        written is None
        or not 0.0 < written < math.pi
        or not 0.0 < hfov < math.pi
        or cam.lens_intrinsics is not None
        or cam.lens_projection
    ):
        return None  # an unreadable value, or a lens that sets the projection itself
    effective = 2.0 * math.atan(math.tan(hfov / 2.0) * height / width)
    if not math.tan(effective / 2.0) > 0.0 or not math.tan(written / 2.0) > 0.0:
        return None  # a field of view too small to hold a row: not judged
    # The focal length each field of view gives the rows, and where the image's top edge
    # lands: half the height times their relative difference.
    fy_written = (height / 2.0) / math.tan(written / 2.0)
    fy_used = (height / 2.0) / math.tan(effective / 2.0)
    shift = height / 2.0 * abs(fy_written - fy_used) / fy_used
    return ctx.judged(
        "SK415",
        Consequence(Role.GEOMETRY, round(written, 6), round(effective, 6), equal=shift <= EDGE_PX),
        f"{head}; the vertical field of view follows from horizontal_fov {hfov:g} and the "
        f"{width}x{height} image ({VFOV_SOURCE}): {effective:.4f} rad, not {written:g}, which "
        f"moves the image's top edge by {shift:.3g} px",
        el,
        sensor=s.name,
        fix=f"remove <{name}>; for a {written:g} rad vertical field of view set the image height "
        f"to {round(width * math.tan(written / 2.0) / math.tan(hfov / 2.0))}",
    )


# ----------------------------------------------------------------------------- SK416


def _angle(rpy: tuple[float, float, float]) -> float:
    """The rotation angle of roll-pitch-yaw ``rpy`` (radians)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    trace = cy * cp + (sy * sp * sr + cy * cr) + cp * cr
    return math.acos(max(-1.0, min(1.0, (trace - 1.0) / 2.0)))


@rule(
    "SK416",
    "error/info",
    "a <pose> inside <camera> on Gazebo Sim, which renders the camera from the sensor's "
    "<pose> only (gz-sensors CameraSensor::CreateCamera): an error when it moves or turns "
    "the camera (more than 1 mm or 0.5 degree), info when it is the identity",
    "none",
    formats=("urdf", "sdf"),
)
def camera_pose_ignored(ctx: Context) -> Iterator[Finding]:
    if CAMERA_POSE_READ.get(ctx.target, True):
        return
    for s in ctx.robot.sensors:
        for cam in s.cameras:
            el = child(cam.element, "pose")
            if el is None or cam.pose is None or cam.pose.problems:
                continue
            xyz, rpy = cam.pose.xyz, cam.pose.rpy
            moved = math.hypot(*xyz)
            turned = _angle(rpy)
            yield ctx.judged(
                "SK416",
                Consequence(
                    Role.GEOMETRY,
                    tuple(round(v, 6) for v in (*xyz, *rpy)),
                    (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
                    equal=moved <= POSITION_TOL and turned <= ANGLE_TOL,
                ),
                f"sensor {s.name!r}: <camera><pose> is never read on {ctx.target} "
                f"({CAMERA_POSE_SOURCE}): the image is rendered from the sensor's <pose>, "
                f"{moved:.4g} m and {math.degrees(turned):.3g} degrees from where this pose puts it",
                el,
                sensor=s.name,
                fix="compose it into the sensor's <pose> and remove it from <camera>",
            )
