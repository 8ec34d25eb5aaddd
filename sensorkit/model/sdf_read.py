"""Reading an SDF file (1.5 to 1.11) into :class:`SdfModel` records: each model's frame
graph (:mod:`sensorkit.model.sdf_frames`), with its nested and ``<include>``d models, and
the elements :mod:`sensorkit.model.sdf_build` turns into a
:class:`~sensorkit.model.robot.Robot`.

A file holding a ``<model>`` gives one model; a ``<world>`` gives each model it holds or
includes, in document order, each placed in the world's frame. Nested models are not
models of their own: their links, joints and frames join the top model's, named with
``::`` scopes as sdformat names them (``outer::inner::link``).

Versions: SDF before 1.7 has no ``relative_to``. libsdformat converts such a file before
reading it, and the conversion renames ``//pose/@frame`` to ``//pose/@relative_to`` and
``use_parent_model_frame`` to ``xyz/@expressed_in="__model__"``
(gazebosim/sdformat@sdformat12_12.8.0:sdf/1.7/1_6.convert:3-42): so do we. Every model
keeps the version of the file it was read from (an included file may be of another).
A merged include (``//include/@merge``, SDF 1.9) is no nested model: its links, joints,
frames, nested models and plugins join the including model unscoped, beside a frame
``_merged__NAME__model__`` that stands for the merged model's ``__model__``, as
libsdformat inserts them (gazebosim/sdformat@sdformat12_12.8.0:src/parser.cc:236-364).
Not read: a merged include directly in a ``<world>`` (an error in libsdformat 12,
parser.cc:221-229; merged into the world from sdformat 14) is read as a model of its own.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from sensorkit.base.findings import Finding, Severity
from sensorkit.loading.document import Document
from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.sdf_files import add_file, parse_sdf, resolve_model_uri
from sensorkit.loading.uris import OUTSIDE
from sensorkit.model.parse import child, parse_vec, text_of
from sensorkit.model.sdf_frames import TOP, FrameGraph, Vertex, inverse, scoped
from sensorkit.model.transforms import IDENTITY, Pose, compose, pose

MAX_INCLUDE_DEPTH = 32


@dataclass
class Include:
    """An ``<include>``: its URI and the file it led to, or why none."""

    uri: str
    element: etree._Element
    path: Path | None
    why: str = ""
    searched: tuple[str, ...] = ()
    via: str = ""  # "GAZEBO_MODEL_PATH": found only through Gazebo Classic's model path
    # the URIs of the includes that brought the file this include is written in, outermost
    # first (empty: written in the file given): a nested include's chain, said with it
    within: tuple[str, ...] = ()


@dataclass
class Element:
    """A link, joint or sensor element to model, with its scope and its file's version."""

    name: str  # scoped (a sensor: its link's scoped name)
    element: etree._Element
    scope: str
    version: tuple[int, ...]
    frame: str | None = None  # the vertex its ``__model__`` names (None: ``scope``)

    @property
    def model_frame(self) -> str:
        return self.scope if self.frame is None else self.frame


@dataclass
class SdfModel:
    """What SDF says of one model beyond the Robot's records: its frames (links, joints,
    frames, nested models) and their poses, its nested models, includes and plugins."""

    name: str
    element: etree._Element
    version: tuple[int, ...]
    graph: FrameGraph = field(default_factory=FrameGraph)
    world_pose: Pose | None = None  # the model's frame in the world (world files)
    world: etree._Element | None = None
    models: dict[str, etree._Element] = field(default_factory=dict)  # nested, by scope
    includes: list[Include] = field(default_factory=list)
    # the world's own includes, on the world's first model only: SK107 says them with the
    # target's search path (a world with no model says them when it is read)
    world_includes: list[Include] = field(default_factory=list)
    links: list[Element] = field(default_factory=list)
    joints: list[Element] = field(default_factory=list)
    sensors: list[Element] = field(default_factory=list)
    plugins: list[tuple[str, etree._Element]] = field(default_factory=list)  # (owner, el)
    pose_problems: list[tuple[str, etree._Element]] = field(default_factory=list)
    # a world's own frames and its models' placements (the world graph): on the world's
    # first model only, so that what they hold is said once (SK208, SK209)
    world_graph: FrameGraph | None = None
    # a world's systems (every model of the world): its own <plugin>s, and every plugin
    # of the world and its models (SK620: is the Sensors system among them)
    world_systems: list[etree._Element] = field(default_factory=list)
    world_plugins: list[etree._Element] = field(default_factory=list)

    def pose_of(self, name: str) -> Pose | None:
        """Pose of a frame (link, joint, frame, nested model) in the model's frame."""
        return self.graph.pose(name)


@dataclass
class SdfRead:
    """The models of an SDF file, or the findings that say why there are none."""

    document: Document | None
    models: list[SdfModel] = field(default_factory=list)
    findings: list[Finding] = field(default_factory=list)


@dataclass
class _Ctx:
    doc: Document
    resolver: PackageResolver
    overlay: Mapping[str, bytes] | None
    stack: list[str] = field(default_factory=list)  # files being included, for loops
    brought: dict[str, str] = field(default_factory=dict)  # included file -> its URI
    world_includes: list[Include] = field(default_factory=list)  # a world's own (SK107)


def version_of(root: etree._Element) -> tuple[int, ...]:
    """The ``<sdf version>`` as numbers (1.9 when absent or unreadable)."""
    text = root.get("version", "")
    try:
        return tuple(int(p) for p in text.strip().split("."))
    except ValueError:
        return (1, 9)


def read_pose(
    owner: etree._Element, version: tuple[int, ...]
) -> tuple[Pose, str | None, etree._Element | None, str | None]:
    """``owner``'s ``<pose>``: (raw pose, the frame it is written relative to or None,
    the element, a problem). SDF >= 1.9 ``rotation_format`` and ``degrees`` are read
    (gazebosim/sdformat@sdformat12_12.8.0:sdf/1.9/pose.sdf)."""
    el = child(owner, "pose")
    if el is None:
        return IDENTITY, None, None, None
    attr = "frame" if version < (1, 7) else "relative_to"  # 1_6.convert:3-9
    rel = el.get(attr) or None
    quat = version >= (1, 9) and el.get("rotation_format", "euler_rpy") == "quat_xyzw"
    text = (el.text or "").strip() or ("0 0 0 0 0 0 1" if quat else "0 0 0 0 0 0")
    values, why = parse_vec(text, 7 if quat else 6)
    if values is None:
        return IDENTITY, rel, el, f"pose {why}"
    xyz = values[:3]
    if quat:
        return _quat_pose(xyz, values[3:]), rel, el, None
    rpy = values[3:]
    if version >= (1, 9) and el.get("degrees", "false").strip().lower() in ("true", "1"):
        rpy = tuple(math.radians(a) for a in rpy)
    return pose(xyz, rpy), rel, el, None


def _quat_pose(xyz: tuple[float, ...], q: tuple[float, ...]) -> Pose:
    x, y, z, w = q
    n = math.sqrt(x * x + y * y + z * z + w * w) or 1.0
    x, y, z, w = x / n, y / n, z / n, w / n
    return (
        1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
        2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
        2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y),
        xyz[0], xyz[1], xyz[2],
    )  # fmt: skip


def _vertex(
    sm: SdfModel,
    el: etree._Element,
    kind: str,
    name: str,
    scope: str,
    default: str,
    version: tuple[int, ...],
    attached_to: str | None = None,
    frame: str | None = None,
) -> Vertex:
    """The vertex of ``el``, its pose relative to what it names in ``scope`` (``__model__``
    being ``frame``, the scope's own unless merged), else to ``default`` (a vertex name,
    already scoped)."""
    raw, rel, pose_el, problem = read_pose(el, version)
    if problem is not None and pose_el is not None:
        sm.pose_problems.append((problem, pose_el))
    relative_to = ref(scope, frame, rel) if rel is not None else default
    vertex = Vertex(name, kind, relative_to, raw, el, rel, attached_to, pose_el)
    sm.graph.add(vertex)
    return vertex


def ref(scope: str, frame: str | None, name: str) -> str:
    """The vertex ``name`` written in the model ``scope`` names, ``__model__`` being
    ``frame``: a merged include's elements name its proxy frame by ``__model__``
    (gazebosim/sdformat@sdformat12_12.8.0:src/parser.cc:294-352)."""
    if name == "__model__" and frame is not None:
        return frame
    return scoped(scope, name)


def merges(inc: etree._Element) -> bool:
    """Whether an ``<include>`` is merged: ``@merge`` read as tinyxml2's BoolAttribute
    (gazebosim/sdformat@sdformat12_12.8.0:src/parser.cc:1820)."""
    text = (inc.get("merge") or "").strip()
    if text.lstrip("-").isdigit():
        return int(text) != 0
    return text in ("true", "True", "TRUE")


def _canonical(el: etree._Element, name: str) -> str | None:
    """A model's canonical link, scoped: ``@canonical_link``, else its first link, else
    its first nested model's (gazebosim/sdformat@sdformat12_12.8.0:src/Model.cc:713-763)."""
    given = el.get("canonical_link")
    if given:
        return scoped(name, given)
    for c in el:
        if c.tag == "link" and c.get("name"):
            return scoped(name, c.get("name", ""))
    for c in el:
        if c.tag == "model" and c.get("name"):
            return scoped(name, c.get("name", ""))
    return None


def _walk_model(
    ctx: _Ctx,
    sm: SdfModel,
    el: etree._Element,
    scope: str,
    version: tuple[int, ...],
    frame: str | None = None,
) -> None:
    """Every frame, link, joint, sensor and plugin of the model ``el`` whose elements are
    named in ``scope`` and whose frame is the vertex ``frame`` (``scope`` itself unless the
    model is merged), nested models and includes too.

    Defaults when a pose names no frame (gazebosim/sdformat@sdformat12_12.8.0:
    src/FrameSemantics.cc): a link's and a nested model's pose is in the model frame
    (:293-298, :428-432, :686 the scope vertex); a joint's in its child (:383-387); a
    frame's in what it is attached to, the model frame when nothing (:335-339, :797-802).
    """
    mf = scope if frame is None else frame
    for c in el:
        tag, name = c.tag, c.get("name", "")
        if tag == "link":
            full = scoped(scope, name)
            _vertex(sm, c, "link", full, scope, mf, version, frame=mf)
            sm.links.append(Element(full, c, scope, version, frame))
            for s in c:
                if s.tag == "sensor":
                    sm.sensors.append(Element(full, s, scope, version))
                elif s.tag == "plugin":
                    sm.plugins.append((full, s))
        elif tag == "joint":
            kid = ref(scope, mf, text_of(c, "child") or "")
            _vertex(sm, c, "joint", scoped(scope, name), scope, kid, version, kid, mf)
            sm.joints.append(Element(scoped(scope, name), c, scope, version, frame))
        elif tag == "frame":
            att = ref(scope, mf, c.get("attached_to") or "__model__")
            _vertex(sm, c, "frame", scoped(scope, name), scope, att, version, att, mf)
        elif tag == "model":
            full = scoped(scope, name)
            _vertex(sm, c, "model", full, scope, mf, version, _canonical(c, full), mf)
            sm.models[full] = c
            _walk_model(ctx, sm, c, full, version)
            _place(sm, full, _placement(c, None, version), c)
        elif tag == "include":
            _include(ctx, sm, c, scope, version, mf)
        elif tag == "plugin":
            sm.plugins.append((mf, c))


def _load_include(
    ctx: _Ctx, inc: etree._Element, owner: SdfModel
) -> tuple[etree._Element, tuple[int, ...]] | None:
    """The ``<model>`` an ``<include>`` brings and its file's version, or None (the
    include is kept in ``owner.includes`` with why)."""
    uri = text_of(inc, "uri") or ""
    including = Path(ctx.stack[-1])
    within = tuple(ctx.brought.get(f, f) for f in ctx.stack[1:])
    if not uri:
        owner.includes.append(Include(uri, inc, None, "the <include> has no <uri>", within=within))
        return None
    got = resolve_model_uri(uri, including, ctx.resolver)
    record = Include(uri, inc, got.path, got.why, got.searched, got.via, within)
    owner.includes.append(record)
    if got.path is None:
        return None
    ctx.brought.setdefault(str(got.path), uri)
    if not ctx.resolver.allows(got.path):  # a model folder's file named elsewhere
        record.path, record.why = None, OUTSIDE
        return None
    key = str(got.path.resolve())
    if key in ctx.stack or len(ctx.stack) > MAX_INCLUDE_DEPTH:
        record.why = "the include comes back to a file that includes it"
        return None
    root, findings = parse_sdf(got.path, ctx.overlay, ctx.resolver.confined is not None)
    if root is None:
        record.why = findings[0].message if findings else "unreadable"
        return None
    model = child(root, "model")
    if model is None:
        record.why = "the file holds no <model>"
        return None
    add_file(ctx.doc, root, got.path)
    return model, version_of(root)


def _include(
    ctx: _Ctx,
    sm: SdfModel,
    inc: etree._Element,
    scope: str,
    version: tuple[int, ...],
    frame: str | None = None,
) -> None:
    """A nested model from an ``<include>``: its ``<name>`` and ``<pose>`` (with its
    attributes) replace the included model's (gazebosim/sdformat@sdformat12_12.8.0:
    src/parser.cc:1676-1700). The included file keeps its own version: libsdformat reads
    and converts each file on its own. A merged include joins ``scope`` instead."""
    loaded = _load_include(ctx, inc, sm)
    if loaded is None:
        return
    model, inner = loaded
    mf = scope if frame is None else frame
    if merges(inc):
        _merge(ctx, sm, inc, model, inner, (scope, version, mf))
        return
    full = scoped(scope, text_of(inc, "name") or model.get("name", ""))
    owner = inc if child(inc, "pose") is not None else model
    _vertex(sm, owner, "model", full, scope, mf, version if owner is inc else inner, frame=mf)
    sm.graph.vertices[full].attached_to = _canonical(model, full)
    sm.graph.vertices[full].element = model
    sm.models[full] = model
    # an include's own <plugin>s join the included model's (sdf/1.9/model.sdf:53-66)
    sm.plugins.extend((full, p) for p in inc if p.tag == "plugin")
    ctx.stack.append(str(sm.includes[-1].path))
    try:
        _walk_model(ctx, sm, model, full, inner)
    finally:
        ctx.stack.pop()
    _place(sm, full, _placement(model, inc, inner), inc)


def _merge(
    ctx: _Ctx,
    sm: SdfModel,
    inc: etree._Element,
    model: etree._Element,
    inner: tuple[int, ...],
    at: tuple[str, tuple[int, ...], str],
) -> None:
    """A merged include (gazebosim/sdformat@sdformat12_12.8.0:src/parser.cc:236-364): a
    frame ``_merged__NAME__model__`` (:2613-2616) attached to the merged model's canonical
    link, posed as the model would be (the include's pose, else the file's, relative to
    what it names, else the including model's frame; with a placement frame, the model
    frame that puts it there: :262-281), stands for the merged model's ``__model__``; its
    links, joints, frames, nested models and plugins join the including model's scope,
    their defaults and ``__model__`` naming that frame (:283-352)."""
    scope, version, mf = at
    name = text_of(inc, "name") or model.get("name", "")
    proxy = scoped(scope, f"_merged__{name}__model__")
    owner = inc if child(inc, "pose") is not None else model
    v = _vertex(sm, owner, "frame", proxy, scope, mf, version if owner is inc else inner, None, mf)
    v.attached_to = _canonical(model, scope)
    ctx.stack.append(str(sm.includes[-1].path))
    try:
        _walk_model(ctx, sm, model, scope, inner, proxy)
    finally:
        ctx.stack.pop()
    # the include's <plugin>s were added after the model's (parser.cc:1767-1773)
    sm.plugins.extend((mf, p) for p in inc if p.tag == "plugin")
    placement = _placement(model, inc, inner)
    if placement and sm.graph.vertices.get(proxy) is v:
        X_MPf = sm.graph.pose_in_scope(ref(scope, proxy, placement), proxy)
        if X_MPf is None:
            sm.pose_problems.append((f"placement_frame {placement!r} names no frame", inc))
        else:
            v.raw = compose(v.raw, inverse(X_MPf))


def _placement(
    model: etree._Element, inc: etree._Element | None, version: tuple[int, ...]
) -> str | None:
    """A model's placement frame (SDF >= 1.8): an include's ``<placement_frame>`` sets
    the model's ``@placement_frame`` (gazebosim/sdformat@sdformat12_12.8.0:
    src/parser.cc:1726-1761)."""
    if inc is not None and text_of(inc, "placement_frame"):
        return text_of(inc, "placement_frame")
    return model.get("placement_frame") if version >= (1, 8) else None


def _place(sm: SdfModel, vertex: str, frame: str | None, el: etree._Element) -> None:
    if not sm.graph.place(vertex, frame):
        sm.pose_problems.append((f"placement_frame {frame!r} names no frame of the model", el))


def read_models(
    path: Path,
    resolver: PackageResolver,
    overlay: Mapping[str, bytes] | None = None,
    document: Document | None = None,
) -> SdfRead:
    """The models of the SDF file ``path``: its ``<model>``, or each model of its
    ``<world>``; from ``document`` when given (a ``.sdf.xacro``'s expansion, whose
    elements keep their files and lines). Raises InputError when the file is unreadable
    or holds neither."""
    from sensorkit.base.errors import InputError
    from sensorkit.loading.document import display_path

    if document is None:
        root, findings = parse_sdf(path, overlay, resolver.confined is not None)
        if root is None:
            return SdfRead(None, [], findings)
        doc = Document(path=path, root=root)
    else:
        doc, root = document, document.root
    ctx = _Ctx(doc, resolver.for_file(path), overlay, [str(path.resolve())])
    version = version_of(root)
    out = SdfRead(doc)
    for el in root:
        if el.tag == "model":
            sm = SdfModel(el.get("name", ""), el, version)
            _walk_model(ctx, sm, el, TOP, version)
            frame = _placement(el, None, version)  # places the model in its parent only
            if frame and sm.graph.pose(scoped(TOP, frame)) is None:
                sm.pose_problems.append((f"placement_frame {frame!r} names no frame", el))
            out.models.append(sm)
        elif el.tag == "world":
            out.models.extend(_read_world(ctx, el, version))
    if not any(el.tag in ("model", "world") for el in root):
        msg = f"{display_path(path)}: <sdf> holds no <model> or <world>: nothing to check"
        raise InputError(msg)
    from sensorkit.model.sdf_includes import include_finding

    if out.models:  # the first model's SK107 says them, with the target's search path
        owned = {id(inc) for sm in out.models for inc in sm.includes}  # a model's own
        out.models[0].world_includes.extend(i for i in ctx.world_includes if id(i) not in owned)
        return out
    said: set[str] = set()  # an info (a Fuel URI not read) once, however often included
    for inc in ctx.world_includes:  # a world's own includes belong to no model
        found = include_finding(inc, doc)
        if found is not None and (found.severity > Severity.INFO or found.message not in said):
            said.add(found.message)
            out.findings.append(found)
    return out


def _read_world(ctx: _Ctx, world: etree._Element, version: tuple[int, ...]) -> list[SdfModel]:
    """Each model of a world, with its pose in the world frame (models and world frames
    are the world graph's vertices: gazebosim/sdformat@sdformat12_12.8.0:
    src/FrameSemantics.cc:1144-1176)."""
    graph = FrameGraph()
    holder = SdfModel(world.get("name", ""), world, version, graph)
    models: list[SdfModel] = []
    for c in world:
        if c.tag == "model":
            sm = SdfModel(c.get("name", ""), c, version, world=world)
            _walk_model(ctx, sm, c, TOP, version)
        elif c.tag == "include":
            loaded = _load_include(ctx, c, holder)
            if loaded is None:
                continue
            model, inner = loaded
            name = text_of(c, "name") or model.get("name", "")
            sm = SdfModel(name, model, inner, world=world)
            sm.includes.append(holder.includes[-1])
            ctx.stack.append(str(holder.includes[-1].path))
            try:
                _walk_model(ctx, sm, model, TOP, inner)
            finally:
                ctx.stack.pop()
        elif c.tag == "frame":
            att = c.get("attached_to") or ""
            _vertex(holder, c, "frame", c.get("name", ""), TOP, att, version, att or None)
            continue
        else:
            continue
        owner = c if c.tag == "model" or child(c, "pose") is not None else sm.element
        _vertex(holder, owner, "model", sm.name, TOP, TOP, version if owner is c else sm.version)
        frame = _placement(sm.element, c if c.tag == "include" else None, sm.version)
        if frame:  # the model's frame is the world graph's vertex; X_MPf is in its graph
            X_MPf = sm.graph.pose(scoped(TOP, frame))
            vertex = graph.vertices.get(sm.name)
            if X_MPf is None or vertex is None:
                sm.pose_problems.append((f"placement_frame {frame!r} names no frame", c))
            else:
                vertex.raw = compose(vertex.raw, inverse(X_MPf))
        models.append(sm)
    for v in graph.vertices.values():  # "world" names the world frame, as __model__ a model's
        # (gazebosim/sdformat@sdformat12_12.8.0:src/FrameSemantics.cc:1149-1158)
        v.relative_to = TOP if v.relative_to == "world" else v.relative_to
        v.attached_to = TOP if v.attached_to == "world" else v.attached_to
    for sm in models:  # world poses may name a frame inside a model: "model::link"
        for name in list(sm.graph.vertices):
            p = sm.graph.pose(name)
            if p is not None:
                graph.add(Vertex(f"{sm.name}::{name}", "inner", sm.name, p, sm.element))
    for sm in models:
        sm.world_pose = graph.pose(sm.name)
        sm.pose_problems.extend(holder.pose_problems)
    if models and all(i.path is not None and not i.why for i in holder.includes):
        models[0].world_graph = graph  # not when an include brought nothing: names unknown
    systems = [c for c in world if c.tag == "plugin"]
    plugins = [*world.iter("plugin"), *(el for sm in models for _, el in sm.plugins)]
    for sm in models:
        sm.world_systems, sm.world_plugins = systems, plugins
    ctx.world_includes.extend(holder.includes)
    return models
