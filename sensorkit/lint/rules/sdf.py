"""SK107, SK208, SK209, SK510: mistakes only SDF can make, checked on SDF models only.

Each is what libsdformat itself reports (tests/tools/sdf_errors.cc prints its errors on
the tests' trigger files; tests/test_sdf_rules.py pins each code):

- SK107, an ``<include>`` that leads to no file: URI_LOOKUP (see
  :mod:`sensorkit.model.sdf_includes`, which also says it of a world's own includes).
- SK208, a name that names no frame: a pose's ``relative_to`` (POSE_RELATIVE_TO_INVALID),
  a frame's ``attached_to`` (FRAME_ATTACHED_TO_INVALID) and a model's ``placement_frame``
  (POSE_RELATIVE_TO_INVALID), reported by ``sdf::Root::Load``
  (gazebosim/sdformat@sdformat12_12.8.0:src/FrameSemantics.cc:688-719, :804-821; the
  placement frame resolved at :261-265, reported at :1709-1713); an
  axis ``<xyz expressed_in>``, which Load accepts but ``JointAxis::ResolveXyz`` does not
  (POSE_RELATIVE_TO_INVALID).
- SK209, a cycle: FRAME_ATTACHED_TO_CYCLE and POSE_RELATIVE_TO_CYCLE
  (src/FrameSemantics.cc:116, :190, :724-731, :827-835).
- SK510, a sensor's ``<pose relative_to>`` naming no frame of the sensor's model. A
  sensor is no vertex of the frame graphs Load checks (nor in sdformat14_14.9.0's
  src/FrameSemantics.cc): only resolving its pose fails
  (POSE_RELATIVE_TO_INVALID, src/FrameSemantics.cc:1801-1804). A frame of another
  model, of the world or of an enclosing model is such a name too: a model's graph holds
  its own frames and its nested models' only (libsdformat says "unable to find unique
  frame", nothing about other models).

Severity, from what Gazebo Sim does: ``sdf::Root::Load`` errors make the server load
nothing of the world (gazebosim/gz-sim@gz-sim8_8.14.0:src/Server.cc:83-91, by default:
src/ServerConfig.cc:298-299; gazebosim/gz-sim@ignition-gazebo6_6.16.0:src/Server.cc:
136-141) and the create service spawn nothing (gazebosim/gz-sim@gz-sim8_8.14.0:
src/systems/user_commands/UserCommands.cc:925-930): SK107, SK208 and SK209 are errors.
An axis that does not resolve makes gz-sim drop its joint
(gazebosim/gz-sim@gz-sim8_8.14.0:src/SdfEntityCreator.cc:144-153, :803-811): an error.
A sensor pose that does not resolve is replaced by its raw pose in its link, relative_to
ignored (src/SdfEntityCreator.cc:131-141, :1078;
gazebosim/gz-sim@ignition-gazebo6_6.16.0:src/SdfEntityCreator.cc:111-121, :891): the
sensor is not where it is written, an error as a camera frame that is not optical is.
SK208, SK209 and SK510 say nothing on Gazebo classic targets, whose handling of these
errors is not established here; SK107 holds for both.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import TYPE_CHECKING

from lxml import etree

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.limits import ANGLE_TOL, POSITION_TOL
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.parse import child, text_of
from sensorkit.model.targets import is_gz

if TYPE_CHECKING:  # the SDF reader loads only when an SDF robot is checked
    from sensorkit.model.sdf_frames import FrameGraph, Vertex
    from sensorkit.model.sdf_read import SdfModel
    from sensorkit.model.transforms import Pose

REFUSED = "Gazebo Sim loads no part of a world that holds it, nor spawns the model"
SDF = ("sdf",)


@rule(
    "SK107",
    "error/info",
    "an SDF `<include>` whose URI does not resolve (model://, package:// and paths through "
    "the target's model path, GZ_SIM_RESOURCE_PATH or Classic's GAZEBO_MODEL_PATH, the "
    "packages and the models beside it; every place searched); info when sensorkit "
    "cannot read it (a Fuel URL, another scheme, outside the workspace with --untrusted) "
    "or on Classic for a model Gazebo 11 installs (sun, ground_plane)",
    "libsdformat",
    formats=SDF,
)
def unresolved_includes(ctx: Context) -> Iterator[Finding]:
    from sensorkit.model.sdf_includes import include_finding

    sm = ctx.robot.sdf
    if sm is None:
        return
    said: set[str] = set()  # an info (a Fuel URI not read) once, however often included
    for inc in [*sm.includes, *sm.world_includes]:
        found = include_finding(inc, ctx.robot.document, ctx.target)
        if found is not None and (found.severity > Severity.INFO or found.message not in said):
            said.add(found.message)
            yield found


def _model_label(sm: SdfModel, scope: str) -> str:
    return f"{sm.name}::{scope}" if scope else sm.name


def _graphs(sm: SdfModel) -> Iterator[tuple[FrameGraph, str]]:
    """The model's frame graph, and the world's when this model holds it."""
    yield sm.graph, f"model {sm.name!r}"
    if sm.world_graph is not None and sm.world is not None:
        yield sm.world_graph, f"world {sm.world.get('name', '')!r}"


def _scope_of(v: Vertex) -> str:
    return v.name.rpartition("::")[0]


def _blind(sm: SdfModel) -> list[str]:
    """The scopes an include that brought nothing was written in: the names it would have
    brought (a merged include's into that scope, others' below it) are unknown."""
    out: list[str] = []
    for inc in sm.includes:
        if inc.path is not None and not inc.why:
            continue
        parent = inc.element.getparent()
        scope = next((k for k, el in sm.models.items() if el is parent), "")
        out.append(scope)
    return out


def _unknowable(blind: list[str], scope: str) -> bool:
    """Whether a name written in ``scope`` may name what an include in ``blind`` brings."""
    return any(not scope or t == scope or t.startswith(scope + "::") for t in blind)


@rule(
    "SK208",
    "error",
    "an SDF name that names no frame in its scope: a pose's `relative_to`, a frame's "
    "`attached_to`, a model's `placement_frame`, an axis's `expressed_in` (gz targets)",
    "libsdformat",
    formats=SDF,
)
def unknown_frame_names(ctx: Context) -> Iterator[Finding]:
    sm = ctx.robot.sdf
    if sm is None or not is_gz(ctx.target):  # Gazebo classic: not known
        return
    blind = _blind(sm)
    for graph, label in _graphs(sm):
        for v in graph.vertices.values():
            if graph is not sm.graph:
                yield from _vertex_names(ctx, graph, v, label)
            elif not _unknowable(blind, _scope_of(v)):  # the model the name is written in
                yield from _vertex_names(ctx, graph, v, f"model {_model_label(sm, _scope_of(v))!r}")
    for problem, el in sm.pose_problems:
        if problem.startswith("placement_frame ") and not blind:
            yield ctx.finding(
                "SK208",
                Severity.ERROR,
                f"{problem}: libsdformat reports POSE_RELATIVE_TO_INVALID and {REFUSED}",
                el,
                fix="name a link, joint, frame or nested model of the placed model",
            )
    yield from _axis_names(ctx, sm, blind)


def _vertex_names(ctx: Context, graph: FrameGraph, v: Vertex, where: str) -> Iterator[Finding]:
    if v.kind == "inner":  # a world graph's copy of a model's frame
        return
    what = f"{v.kind} {v.name!r}" if v.name else where
    written_att = v.element.get("attached_to") if v.kind == "frame" else None
    if written_att and v.attached_to is not None and not graph.knows(v.attached_to):
        yield ctx.finding(
            "SK208",
            Severity.ERROR,
            f"{what}: attached_to={written_att!r} names no frame in {where} "
            f"(libsdformat: FRAME_ATTACHED_TO_INVALID), so {REFUSED}",
            v.element,
            frame=v.name or None,
            fix="name a link, joint, frame or nested model of the same model",
        )
        return
    if v.written is not None and not graph.knows(v.relative_to):
        yield ctx.finding(
            "SK208",
            Severity.ERROR,
            f"{what}: <pose relative_to={v.written!r}> names no frame in {where} "
            f"(libsdformat: POSE_RELATIVE_TO_INVALID), so {REFUSED}",
            v.pose_element if v.pose_element is not None else v.element,
            frame=v.name or None,
            fix="name a link, joint, frame or nested model of the same model (a name "
            "inside a nested model as NESTED::NAME)",
        )


def _axis_names(ctx: Context, sm: SdfModel, blind: list[str]) -> Iterator[Finding]:
    from sensorkit.model.sdf_frames import scoped

    for item in sm.joints:
        if item.version < (1, 7) or _unknowable(blind, item.scope):  # 1.6: no expressed_in
            continue
        for tag in ("axis", "axis2"):
            xyz = child(child(item.element, tag), "xyz")
            frame = xyz.get("expressed_in") if xyz is not None else None
            if not frame or sm.graph.knows(scoped(item.scope, frame)):
                continue
            yield ctx.finding(
                "SK208",
                Severity.ERROR,
                f"joint {item.name!r}: <{tag}><xyz expressed_in={frame!r}> names no frame "
                f"in model {_model_label(sm, item.scope)!r}: libsdformat loads it but cannot "
                "resolve the axis (POSE_RELATIVE_TO_INVALID), and gz-sim then does not "
                "create the joint: its child falls off",
                xyz,
                joint=item.name,
                fix="name a link, joint, frame or nested model of the joint's model",
            )


def _cycle(graph: FrameGraph, start: str, edge: str) -> list[str] | None:
    """The cycle ``start`` lies on following ``edge`` (relative_to or attached_to)."""
    from sensorkit.model.sdf_frames import TOP

    order: list[str] = []
    cur: str | None = start
    while cur is not None and cur != TOP:
        if cur in order:
            return order[order.index(cur) :] if cur == start else None
        v = graph.vertices.get(cur)
        if v is None or v.kind == "inner" or (edge == "attached_to" and v.kind == "link"):
            return None
        order.append(cur)
        cur = v.relative_to if edge == "relative_to" else v.attached_to
    return None


@rule(
    "SK209",
    "error",
    "an SDF frame cycle: frames `attached_to` each other, or poses `relative_to` each "
    "other (or to themselves), so no frame on the cycle has a pose (gz targets)",
    "libsdformat",
    formats=SDF,
)
def frame_cycles(ctx: Context) -> Iterator[Finding]:
    sm = ctx.robot.sdf
    if sm is None or not is_gz(ctx.target):  # Gazebo classic: not known
        return
    for graph, where in _graphs(sm):
        said: set[frozenset[str]] = set()
        for edge, code in (
            ("attached_to", "FRAME_ATTACHED_TO_CYCLE"),
            ("relative_to", "POSE_RELATIVE_TO_CYCLE"),
        ):
            for name, v in graph.vertices.items():
                found = _cycle(graph, name, edge)
                if found is None or frozenset(found) in said:
                    continue
                said.add(frozenset(found))
                label = f"model {_model_label(sm, _scope_of(v))!r}" if graph is sm.graph else where
                yield _cycle_finding(ctx, v, found, edge, code, label)


def _cycle_finding(
    ctx: Context, v: Vertex, cycle: list[str], edge: str, code: str, where: str
) -> Finding:
    loop = " -> ".join(repr(n) for n in [*cycle, cycle[0]])
    el: etree._Element | None = v.element
    if edge == "relative_to" and v.pose_element is not None:
        el = v.pose_element
    return ctx.finding(
        "SK209",
        Severity.ERROR,
        f"{where}: {edge} goes round in a cycle, {loop}: no frame on it has a pose "
        f"(libsdformat: {code}), so {REFUSED}",
        el,
        frame=v.name or None,
        fix=f"make one frame of the cycle {edge.replace('_', ' ')} a link or the model",
    )


def _elsewhere(sm: SdfModel, scope: str, name: str) -> str:
    """Where ``name`` (not a frame of model ``scope``) is a frame after all: an enclosing
    model's, or, in a world, another model's or the world's; "" when nowhere known."""
    from sensorkit.model.sdf_frames import scoped

    parts = scope.split("::") if scope else []
    for i in range(len(parts) - 1, -1, -1):
        outer = "::".join(parts[:i])
        if sm.graph.knows(scoped(outer, name)):
            label = _model_label(sm, outer)
            return f" ({name!r} is a frame of the enclosing model {label!r}, out of its scope)"
    if sm.world is None:
        return ""
    first = name.partition("::")[0]
    for c in sm.world:
        own = text_of(c, "name") if c.tag == "include" else c.get("name")
        if own != first or own == sm.name or c.tag not in ("model", "include", "frame"):
            continue
        if c.tag == "frame":
            return f" ({own!r} is a frame of the world, which a sensor's pose cannot name)"
        return f" ({own!r} is another model of the world, which a sensor's pose cannot name)"
    return ""


@rule(
    "SK510",
    "error/warning",
    "an SDF sensor's `<pose relative_to>` names no frame of its model (a frame of another "
    "model, of the world or of an enclosing model included): gz-sim places the sensor at "
    "its raw pose in its link (gz targets). An error when the frame meant can be told (a "
    "frame of an enclosing model, or a one- or two-letter typo of a frame of its own) and "
    "the sensor then sits elsewhere than it would there; a warning otherwise (the sensor "
    "works at the raw pose, what was meant is not known)",
    "libsdformat",
    formats=SDF,
)
def sensor_pose_frames(ctx: Context) -> Iterator[Finding]:
    # libsdformat reports nothing when it loads the file: a sensor is no vertex of the
    # model's pose graph (gazebosim/sdformat@sdf14 8512585c:src/FrameSemantics.cc:296-519
    # adds links, frames, joints and models), so the name is looked up only when the pose
    # is resolved, which returns POSE_RELATIVE_TO_INVALID (:1830-1844). gz-sim
    # (gazebosim/gz-sim@gz-sim8 b81e26dab:src/SdfEntityCreator.cc:131-141, :1078), the
    # renderer (src/rendering/RenderUtil.cc:1333-1338) and gz-sensors
    # (gazebosim/gz-sensors@gz-sensors8 c8159af:src/Sensor.cc:198-204) then take the raw
    # pose, in the sensor's link, and say nothing.
    from sensorkit.model.sdf_frames import scoped
    from sensorkit.model.sdf_read import read_pose

    sm = ctx.robot.sdf
    if sm is None or not is_gz(ctx.target):  # Gazebo classic: not known
        return
    blind = _blind(sm)
    for item in sm.sensors:
        raw, rel, pose_el, _problem = read_pose(item.element, item.version)
        if rel is None or sm.graph.knows(scoped(item.scope, rel)):
            continue
        if _unknowable(blind, item.scope):  # the frame may come with what was not read
            continue
        sensor = item.element.get("name", "")
        meant = _meant_frame(sm, item.scope, rel)
        moved = None if meant is None else _offset(sm, item.name, meant[0], raw)
        sev = Severity.WARNING
        if meant is None or moved is None:
            what = "which frame was meant is not known, so it works there as written"
        elif moved == (0.0, 0.0):
            what = (
                f"placed in {meant[0]!r} ({meant[1]}) it would sit at the same place and "
                "rotation, so the sensor works where it was meant"
            )
        else:
            sev = Severity.ERROR
            what = (
                f"placed in {meant[0]!r} ({meant[1]}) it would sit {moved[0] * 1000:.1f} mm "
                f"and {math.degrees(moved[1]):.1f} degrees from where it does"
            )
        yield ctx.finding(
            "SK510",
            sev,
            f"sensor {sensor!r}: <pose relative_to={rel!r}> names no "
            f"frame of model {_model_label(sm, item.scope)!r}"
            f"{_elsewhere(sm, item.scope, rel)}: libsdformat reports nothing at load, but "
            "resolving the pose fails (POSE_RELATIVE_TO_INVALID), and gz-sim then places the "
            f"sensor at the raw pose in its link {item.name!r}, relative_to ignored; {what}",
            pose_el,
            sensor=sensor,
            link=item.name,
            fix="name a frame of the sensor's own model or of a model nested in it (add "
            "a <frame attached_to=...> there if needed)",
        )


def _meant_frame(sm: SdfModel, scope: str, name: str) -> tuple[str, str] | None:
    """The frame a name out of scope most likely means, with words for why: a frame of an
    enclosing model of that name, or a frame of the sensor's own model one or two letters
    away (and no other that close). None when it cannot be told."""
    from sensorkit.model.sdf_frames import scoped

    parts = scope.split("::") if scope else []
    for i in range(len(parts) - 1, -1, -1):
        outer = scoped("::".join(parts[:i]), name)
        if sm.graph.knows(outer):
            return outer, "the enclosing model's frame of that name"
    prefix = f"{scope}::" if scope else ""
    own = [
        v[len(prefix):] for v in sm.graph.vertices
        if v.startswith(prefix) and "::" not in v[len(prefix):]
    ]
    close = [n for n in own if _edits(name, n) <= 2]
    if len(close) == 1:
        return scoped(scope, close[0]), "the model's frame a letter or two away"
    return None


def _edits(a: str, b: str) -> int:
    """Levenshtein distance, stopping early past 2 (only 'one or two letters' matters)."""
    if abs(len(a) - len(b)) > 2:
        return 3
    prev = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        cur = [i]
        for j, cb in enumerate(b, 1):
            cur.append(min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (ca != cb)))
        if min(cur) > 2:
            return 3
        prev = cur
    return prev[-1]


def _offset(sm: SdfModel, link: str, frame: str, raw: Pose) -> tuple[float, float] | None:
    """How far the sensor placed at ``raw`` in ``frame`` sits from ``raw`` in ``link``:
    (metres, radians), each 0.0 within the frame rules' 1 mm and 0.5 degree; None when
    either frame has no pose."""
    from sensorkit.model.sdf_frames import between
    from sensorkit.model.transforms import compose

    X_LF = sm.graph.in_frame(frame, link)
    if X_LF is None:
        return None
    d = between(raw, compose(X_LF, raw))
    dist = math.sqrt(d[9] ** 2 + d[10] ** 2 + d[11] ** 2)
    angle = math.acos(max(-1.0, min(1.0, (d[0] + d[4] + d[8] - 1.0) / 2.0)))
    return (
        0.0 if dist <= POSITION_TOL else dist,  # SK503's 1 mm
        0.0 if angle <= ANGLE_TOL else angle,  # SK502's 0.5 degree
    )
