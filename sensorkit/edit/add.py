"""Add a sensor to a robot file: plan in memory, check, then publish atomically.

``plan_add`` reads everything and writes nothing: it works out the new bytes of the
robot file (the original bytes with new text spliced in before the closing root tag,
and for xacro a namespace declaration when the root lacks one), the macro file to copy
beside it, the diff, and it refuses (``EditRefused``) when a name is taken, the parent
link is missing, or the result would carry a validator error the original does not.
``apply_add`` publishes a plan; ``add_sensor`` does both.
"""

from __future__ import annotations

import contextlib
import copy
import dataclasses
import difflib
import functools
import os
import posixpath
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from sensorkit.base.atomic import check_editable, editing, write_bytes
from sensorkit.base.errors import EditRefused, InputError, UsageError, WriteFailed
from sensorkit.base.findings import Finding
from sensorkit.edit.check import (
    Verdict,
    check_names,
    check_parent,
    compare_added,
    describe,
    names_in_use,
)
from sensorkit.edit.fragment import Fragment, expand_fragment
from sensorkit.edit.kinds import KINDS, XACRO_NS, MacroInfo, SensorKind, read_macro, shipped_macro
from sensorkit.edit.layout import Layout, read_layout
from sensorkit.edit.package import (
    SPEC_WHY,
    NewSensor,
    PackageContext,
    PackagePlan,
    find_package,
    lock_paths,
    plan_generated,
    plan_package,
    read_package,
)
from sensorkit.edit.render import (
    Lines,
    format_number,
    fragment_lines,
    macro_call_lines,
    render_block,
)
from sensorkit.edit.simchoice import choose_simulator
from sensorkit.loading.document import (
    Document,
    display_path,
    drop_default_namespace,
    looks_like_xacro,
    plain_document,
    read_input,
    strict_parser,
)
from sensorkit.loading.xacro_expand import forbid_entities

if TYPE_CHECKING:
    from sensorkit.lint.engine import Options
    from sensorkit.loading.bridge import BridgeTopic
    from sensorkit.model import Robot

NAME_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")
SENSORS_DIR = "sensors"
_RESERVED = ("name", "parent")


@dataclass(frozen=True)
class AddRequest:
    """What to add, where. ``params`` are macro parameters as text (``width="640"``)."""

    path: Path
    kind: str
    name: str
    parent: str
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    params: Mapping[str, str] = field(default_factory=dict)
    output: Path | None = None
    args: Mapping[str, str] = field(default_factory=dict)
    package_paths: tuple[str, ...] = ()
    validation: Options | None = None  # how to validate; default: every rule, target auto


@dataclass(frozen=True)
class PlannedWrite:
    """One file an add writes: ``role`` is ``"robot"``, ``"macro"`` (a new copy of a
    shipped macro) or ``"package"`` (another file of the robot's package, or its robot
    YAML: ``original`` holds its bytes as planned, None for a new file)."""

    path: Path
    data: bytes
    role: str
    mode: int | None = None
    original: bytes | None = None
    why: str = ""


@dataclass
class AddResult:
    """A planned (and, once ``written``, published) add."""

    kind: SensorKind
    name: str
    source: Path
    target: Path
    style: str  # "xacro" (macro call) or "urdf" (expanded elements)
    macro: MacroInfo
    original: bytes
    new: bytes
    writes: list[PlannedWrite]
    # (old text, new text, old label, new label) of each file the add writes
    changes: list[tuple[str, str, str, str]] = field(default_factory=list, repr=False)
    notes: list[str] = field(default_factory=list)
    links: list[str] = field(default_factory=list)
    joints: list[str] = field(default_factory=list)
    sensors: list[str] = field(default_factory=list)
    written: bool = False
    simulator: str = ""  # where sim came from, when --sim did not say (one line)

    @property
    def package_files(self) -> list[PlannedWrite]:
        """The package files the add writes besides the robot file and macro copy."""
        return [w for w in self.writes if w.role == "package"]

    @functools.cached_property
    def diff(self) -> str:
        """The unified diff of every write, worked out when first asked for (``--diff``):
        on a large file comparing the lines costs as much as the rest of the add."""
        return "".join(unified_diff(*change) for change in self.changes)


# ----------------------------------------------------------------------------- helpers


def _diff_lines(text: str) -> list[str]:
    """Lines with their own terminators (\\n or \\r\\n kept), for difflib."""
    return re.findall(r"[^\n]*\n|[^\n]+\Z", text)


def unified_diff(old: str, new: str, old_label: str, new_label: str) -> str:
    """A unified diff that ``patch``/``git apply`` accept (marks a missing final newline)."""
    out: list[str] = []
    for line in difflib.unified_diff(_diff_lines(old), _diff_lines(new), old_label, new_label):
        if line.endswith("\n"):
            out.append(line)
        else:
            out.append(line + "\n\\ No newline at end of file\n")
    return "".join(out)


def _parse(data: bytes, where: str) -> etree._Element:
    reason = forbid_entities(data)
    if reason:
        msg = f"{where}: {reason}"
        raise EditRefused(msg)
    try:
        return etree.fromstring(data, strict_parser())
    except etree.XMLSyntaxError as exc:
        line, col = exc.position if exc.position else (exc.lineno, exc.offset)
        msg = f"{where}:{line}:{col}: not well-formed XML ({exc.msg}); fix it before adding sensors"
        raise EditRefused(msg) from None


def _node_key(node: etree._Element) -> str:
    """``link|name`` for an element (namespace ignored), ``#comment`` for a comment."""
    if isinstance(node, etree._Comment):
        return "#comment"
    return f"{etree.QName(node).localname}|{node.get('name', '')}"


def _resolve_kind(kind: str) -> SensorKind:
    try:
        return KINDS[kind]
    except KeyError:
        msg = f"unknown sensor kind {kind!r} (known: {', '.join(KINDS)})"
        raise UsageError(msg) from None


def _top_level_includes(root: etree._Element) -> list[str]:
    """``filename`` of every ``<xacro:include>`` directly under the root."""
    out: list[str] = []
    for el in root:
        if (
            isinstance(el.tag, str)
            and etree.QName(el).localname == "include"
            and el.prefix == "xacro"
        ):
            out.append(el.get("filename", ""))
    return out


def _relative_include_warnings(root: etree._Element, source: Path, target: Path) -> list[str]:
    """Notes for relative includes that stop resolving when the output moves folder."""
    notes: list[str] = []
    if source.resolve().parent == target.resolve().parent:
        return notes
    for filename in _top_level_includes(root):
        if not filename or filename.startswith(("$", "/", "package://", "file://")):
            continue
        if not (target.parent / filename).exists():
            notes.append(
                f"{display_path(target)} is in another folder than {display_path(source)}: "
                f"its include '{filename}' does not resolve from there"
            )
    return notes


# ----------------------------------------------------------------------------- planning


@dataclass
class _MacroChoice:
    path: Path  # the macro file the call will use
    info: MacroInfo
    copy_to: Path | None  # where the shipped file must be copied (xacro only), or None
    copy_data: bytes = b""
    notes: list[str] = field(default_factory=list)
    # the file holds sensorkit's own macro, byte for byte (not a user's modified copy)
    ours: bool = True


def _choose_macro(kind: SensorKind, xacro_style: bool, target: Path) -> _MacroChoice:
    shipped = shipped_macro(kind)
    if not xacro_style:
        info = read_macro(shipped, kind.macro_name)
        if info is None:
            msg = f"sensorkit's {shipped} defines no macro {kind.macro_name}"
            raise InputError(msg)
        return _MacroChoice(path=shipped, info=info, copy_to=None)
    local = target.parent / SENSORS_DIR / kind.macro_file
    shipped_data = shipped.read_bytes()
    if local.exists() or local.is_symlink():
        if not local.is_file():
            msg = f"{display_path(local)} is not a file; move it away to add a {kind.label}"
            raise EditRefused(msg)
        if local.read_bytes() == shipped_data:
            info = read_macro(local, kind.macro_name)
            if info is None:
                msg = f"sensorkit's {shipped} defines no macro {kind.macro_name}"
                raise InputError(msg)
            return _MacroChoice(path=local, info=info, copy_to=None)
        info = read_macro(local, kind.macro_name)
        if info is None:
            msg = (
                f"{display_path(local)} differs from sensorkit's and defines no macro "
                f"{kind.macro_name}; rename it or remove it so sensorkit can copy its own"
            )
            raise EditRefused(msg)
        note = (
            f"{display_path(local)} differs from sensorkit's {kind.macro_file}: "
            "left as it is and used (your modified copy)"
        )
        return _MacroChoice(path=local, info=info, copy_to=None, notes=[note], ours=False)
    info = read_macro(shipped, kind.macro_name)
    if info is None:
        msg = f"sensorkit's {shipped} defines no macro {kind.macro_name}"
        raise InputError(msg)
    return _MacroChoice(path=shipped, info=info, copy_to=local, copy_data=shipped_data)


def _macro_label(info: MacroInfo) -> str:
    from sensorkit.base.resources import macros_dir

    if info.path.resolve().parent == macros_dir().resolve():
        return f"sensorkit's {info.name} macro"
    return f"the {info.name} macro in {display_path(info.path)}"


def _call_attributes(
    req: AddRequest, info: MacroInfo, params: Mapping[str, str]
) -> list[tuple[str, str]]:
    known = info.names()
    label = _macro_label(info)
    for key in params:
        if key in _RESERVED or key not in known:
            offered = ", ".join(n for n in known if n not in _RESERVED)
            msg = f"{label} has no parameter {key!r} (it takes: {offered})"
            raise UsageError(msg)
    for needed in _RESERVED:
        if needed not in known:
            msg = f"{label} takes no {needed!r} parameter"
            raise EditRefused(msg)
    if "origin" not in info.blocks:
        msg = f"{label} takes no *origin block"
        raise EditRefused(msg)
    attrs = [("name", req.name), ("parent", req.parent)]
    attrs += [(n, params[n]) for n in known if n in params]
    missing = [p.name for p in info.params if p.default is None and p.name not in dict(attrs)]
    if missing:
        msg = f"{label} needs {', '.join(missing)} (no default)"
        raise UsageError(msg)
    return attrs


def _splice(data: bytes, layout: Layout, block: str, at: int, ns_decl: str | None) -> bytes:
    """Insert ``block`` at character ``at`` and ``ns_decl`` into the root start tag."""
    edits: list[tuple[int, str]] = [(at, block)]
    if ns_decl is not None:
        end = layout.root_start_end - 1  # the '>'
        while end > layout.root_start_at and layout.text[end - 1] in " \t\r\n":
            end -= 1
        edits.append((end, ns_decl))
    out = data
    for char_at, text in sorted(edits, key=lambda e: e[0], reverse=True):
        off = layout.byte_offset(char_at)
        out = out[:off] + layout.encode(text) + out[off:]
    return out


# rcl's namespace rules: "/"-separated tokens of letters, digits and "_", not starting
# with a digit; an optional leading "/" (a trailing one is tolerated by the macros).
ROS_NAMESPACE_RE = re.compile(r"^/?[A-Za-z_][A-Za-z0-9_]*(/[A-Za-z_][A-Za-z0-9_]*)*/?$")


def plan_add(req: AddRequest) -> AddResult:
    """Work out an add without writing anything (see the module doc)."""
    from sensorkit.model import Loaded, build_robot, load_robot

    kind = _resolve_kind(req.kind)
    if not NAME_RE.match(req.name):
        msg = (
            f"--name {req.name!r}: use letters, digits and '_', starting with a letter "
            "(it becomes link, frame and topic names)"
        )
        raise UsageError(msg)
    for key, value in req.params.items():
        # Values are written into xacro: ${...} or $(...) would be evaluated there.
        if "${" in str(value) or "$(" in str(value):
            msg = f"--{key.replace('_', '-')} {value!r}: '${{' and '$(' are not allowed (xacro would evaluate them)"
            raise UsageError(msg)
    namespace = str(req.params.get("namespace") or "")
    if namespace and not ROS_NAMESPACE_RE.match(namespace):
        msg = (
            f"--namespace {namespace!r}: not a ROS namespace (letters, digits and '_', "
            "segments separated by '/', each starting with a letter or '_')"
        )
        raise UsageError(msg)
    if not req.parent or req.parent != req.parent.strip():
        msg = f"--parent {req.parent!r}: give the name of an existing link"
        raise UsageError(msg)
    source = req.path
    target = req.output if req.output is not None else source
    if target.is_dir():
        msg = f"{display_path(target)}: is a folder; -o takes a file name"
        raise UsageError(msg)
    if not target.parent.is_dir():
        msg = f"{display_path(target.parent)}: no such folder"
        raise UsageError(msg)
    where = display_path(source)
    data = read_input(source)
    root = _parse(data, where)
    layout = read_layout(data, where, root)
    xacro_style = looks_like_xacro(source, data)

    if xacro_style:
        untrusted = req.validation.untrusted if req.validation is not None else None
        loaded = load_robot(
            source, args=dict(req.args), package_paths=req.package_paths, untrusted=untrusted
        )
    else:  # plain URDF: the model reads the tree parsed above (as load_robot would)
        loaded = Loaded(build_robot(plain_document(source, root)))
    robot = loaded.robot
    if robot is None:
        first = loaded.findings[0] if loaded.findings else None
        why = f"{first.rule} {first.message}" if first else "it could not be read"
        msg = f"{where} does not load, so sensorkit cannot add to it: {why}"
        raise EditRefused(msg)

    used = names_in_use(robot)
    check_names(robot, req.name, (), where, used)
    check_parent(robot, req.parent, where)

    notes: list[str] = []
    pkg: PackageContext | None = None
    if source.resolve() == target.resolve():
        guarded = req.validation is not None and req.validation.untrusted is not None
        pkg = read_package(source, data, untrusted=guarded)
        notes += pkg.notes if pkg is not None else []
    elif find_package(source) is not None:
        notes.append(
            "-o: the package's other files (bridge, README, robot YAML) are left as they are"
        )
    params = dict(req.params)
    if pkg is not None and pkg.spec is not None:
        _follow_spec(pkg, params)

    choice = _choose_macro(kind, xacro_style, target)
    known = set(choice.info.names())
    sim = choose_simulator(params, robot, root if xacro_style else None, req.args)
    params.update({k: v for k, v in sim.values.items() if k in known and k not in params})
    expressions = {k: v for k, v in sim.expressions.items() if k in known}
    if pkg is not None and pkg.spec is not None and "sim" not in expressions:
        _refuse_literal_sim(pkg, params)
    notes += sim.notes
    attrs = _call_attributes(req, choice.info, params)
    call = macro_call_lines(kind.macro_name, attrs, req.xyz, req.rpy, include=None)
    # sensorkit's own macro, called with values checked above (no ${ or $( in them):
    # nothing in it can hang or exhaust the machine, so it expands here, without forking
    # a process that holds the whole robot (~80 ms of copy-on-write on 10k links)
    frag = expand_fragment(choice.path, kind.macro_name, call, in_process=choice.ours)
    check_names(robot, req.name, frag.created(), where, used)
    written_attrs = [(k, expressions.get(k, v)) for k, v in attrs]

    notes += choice.notes
    ns_decl: str | None = None
    inserted_keys: list[str]
    if xacro_style:
        rel = posixpath.join(SENSORS_DIR, kind.macro_file)
        local = (target.parent / SENSORS_DIR / kind.macro_file).resolve()
        present = any(
            f and "$" not in f and (target.parent / f).resolve() == local
            for f in _top_level_includes(root)
        )
        if not present and source.resolve().parent == target.resolve().parent:
            present = str(local) in {os.path.abspath(p) for p in robot.document.includes}
        include = None if present else rel
        lines: Lines = macro_call_lines(
            kind.macro_name, written_attrs, req.xyz, req.rpy, include, expressions
        )
        inserted_keys = ([] if include is None else ["include"]) + [kind.macro_name]
        if "xacro" not in root.nsmap:
            ns_decl = f' xmlns:xacro="{XACRO_NS}"'
        notes += _relative_include_warnings(root, source, target)
    else:
        header = f"{req.name}: {kind.label} from sensorkit's {kind.macro_name} macro"
        lines = fragment_lines(frag.nodes, header)
        inserted_keys = ["#comment", *[_node_key(n) for n in frag.nodes]]

    line_start = layout.line_start_before(layout.root_end_at)
    at = line_start if line_start is not None else layout.root_end_at
    block = render_block(
        lines,
        layout,
        at_line_start=line_start is not None,
        blank_before=line_start is not None and not layout.previous_line_blank(line_start),
    )
    new = _splice(data, layout, block, at, ns_decl)
    tail = _check_splice(layout, new, at, ns_decl, inserted_keys, xacro_style, where)

    regenerated: bytes | None = None
    package = PackagePlan()
    if pkg is not None:
        sensor = _new_sensor(req, kind, frag, params, choice.info)
        if pkg.spec is not None:
            package = plan_generated(pkg, source, new, sensor)
        else:
            package = plan_package(pkg, sensor)
        notes += package.notes
        if package.robot is not None:
            regenerated = package.robot

    verdict = _validate(
        req,
        robot=robot,
        load_findings=list(loaded.findings),
        tail=tail,
        frag=frag,
        xacro_style=xacro_style,
        bridge_added=package.bridged,
    )
    if regenerated is not None:
        new = regenerated  # the same robot (plan_generated checked), as `new` writes it
    if verdict.new_errors:
        first = verdict.new_errors[0]
        more = len(verdict.new_errors) - 1
        tail = f" (and {more} more)" if more else ""
        msg = f"adding '{req.name}' would introduce an error: {describe(first)}{tail}"
        raise EditRefused(msg)
    notes += [f"new warning: {describe(f)}" for f in verdict.new_warnings]
    notes += [f"validator internal error: {e}" for e in verdict.internal_errors]

    writes: list[PlannedWrite] = []
    changes: list[tuple[str, str, str, str]] = []
    if choice.copy_to is not None:
        writes.append(PlannedWrite(choice.copy_to, choice.copy_data, "macro"))
        rel_copy = display_path(choice.copy_to)
        notes.append(f"copied sensorkit's {kind.macro_file} to {rel_copy}")
    for change in package.changes:
        if choice.copy_to is not None and change.path.resolve() == choice.copy_to.resolve():
            if change.new != choice.copy_data:
                msg = f"internal error: two different copies of {kind.macro_file} planned"
                raise EditRefused(msg)
            continue
        if change.old is not None:
            check_editable(change.path)
        writes.append(
            PlannedWrite(change.path, change.new, "package", change.mode, change.old, change.why)
        )
    mode = (target if target.exists() else source).stat().st_mode
    writes.append(PlannedWrite(target, new, "robot", mode))
    new_text = new[len(layout.bom) :].decode(layout.encoding)
    changes.append(
        (layout.text, new_text, f"a/{display_path(source)}", f"b/{display_path(target)}")
    )
    if choice.copy_to is not None:
        macro_text = choice.copy_data.decode("utf-8", "replace")
        changes.append(("", macro_text, "/dev/null", f"b/{display_path(choice.copy_to)}"))
    for w in writes:
        if w.role == "package":
            shown = display_path(w.path)
            old_text = "" if w.original is None else w.original.decode("utf-8", "replace")
            old_label = "/dev/null" if w.original is None else f"a/{shown}"
            changes.append((old_text, w.data.decode("utf-8", "replace"), old_label, f"b/{shown}"))
    return AddResult(
        kind=kind,
        name=req.name,
        source=source,
        target=target,
        style="xacro" if xacro_style else "urdf",
        macro=choice.info,
        original=data,
        new=new,
        writes=writes,
        changes=changes,
        notes=notes,
        links=list(frag.links),
        joints=list(frag.joints),
        sensors=list(frag.sensors),
        simulator=sim.origin,
    )


def _follow_spec(pkg: PackageContext, params: dict[str, str]) -> None:
    """In a package its robot YAML generates, ``namespace`` and ``gz_version`` are the
    YAML's (set once for every sensor there): fill them in, refuse another value."""
    spec = pkg.spec
    assert spec is not None and pkg.spec_path is not None
    for key, value in (("namespace", spec.namespace), ("gz_version", spec.gz_version)):
        given = params.get(key)
        if given is None:
            params[key] = value
        elif (given.strip("/") if key == "namespace" else given) != value:
            msg = (
                f"--{key.replace('_', '-')} {given}: {display_path(pkg.spec_path)}, which "
                f"generates this package, sets {key} {value!r} for every sensor; change it "
                "there and run sensorkit new --force, or leave the option out"
            )
            raise EditRefused(msg)


def _refuse_literal_sim(pkg: PackageContext, params: Mapping[str, str]) -> None:
    """A sensor fixed to one simulator has no place in a generated package, whose sensors
    all follow its ``sim`` argument (the robot YAML has one ``sim`` for all)."""
    assert pkg.spec is not None and pkg.spec_path is not None
    msg = (
        f"--sim {params.get('sim')}: every sensor of this package follows its sim argument "
        f"(default {pkg.spec.sim}, from {display_path(pkg.spec_path)}); leave --sim out, or "
        f"change sim there and run sensorkit new --force"
    )
    raise EditRefused(msg)


def _new_sensor(
    req: AddRequest,
    kind: SensorKind,
    frag: Fragment,
    params: Mapping[str, str],
    info: MacroInfo,
) -> NewSensor:
    def default(key: str) -> str:
        param = info.param(key)
        return params.get(key) or (param.default if param and param.default else "")

    return NewSensor(
        kind=kind.key,
        name=req.name,
        parent=req.parent,
        xyz=[format_number(v) for v in req.xyz],
        rpy=[format_number(v) for v in req.rpy],
        options=dict(req.params),
        sensors=[s for el in frag.elements() for s in el.iter("sensor")],
        sim=default("sim") or None,
        gz_version=default("gz_version") or "harmonic",
    )


def _check_splice(
    layout: Layout,
    new: bytes,
    at: int,
    ns_decl: str | None,
    inserted: list[str],
    xacro_style: bool,
    where: str,
) -> etree._Element:
    """A guard: the new file, from the new text on, parses under its root start tag and
    holds exactly the inserted nodes before the closing tag.

    The original parsed and the splice point is at its closing root tag, so this proves
    the whole new file parses, reading only the end of it. The lines before are kept as
    newlines, so the returned root's elements carry the lines they have in the new file.
    """
    text = new[len(layout.bom) :].decode(layout.encoding)
    shift = len(ns_decl) if ns_decl is not None else 0
    start_tag = text[layout.root_start_at : layout.root_start_end + shift]
    at_new = at + shift

    def breaks(t: str) -> int:
        return t.count("\n") + t.count("\r") - t.count("\r\n")

    pad = breaks(text[:at_new]) - breaks(start_tag)
    try:
        tail = etree.fromstring("\n" * pad + start_tag + text[at_new:], strict_parser())
    except etree.XMLSyntaxError as exc:
        msg = f"{where}: internal error, the edit would not parse ({exc.msg}); nothing was written"
        raise EditRefused(msg) from None
    added = [n for n in tail if isinstance(n.tag, str) or isinstance(n, etree._Comment)]
    if xacro_style:
        ok = [
            etree.QName(n).localname if isinstance(n.tag, str) else "#comment" for n in added
        ] == inserted
    else:
        ok = [_node_key(n) for n in added] == inserted
    if not ok:
        msg = f"{where}: internal error, the new text missed the closing tag; nothing was written"
        raise EditRefused(msg)
    return tail


def _validate(
    req: AddRequest,
    *,
    robot: Robot,
    load_findings: list[Finding],
    tail: etree._Element,
    frag: Fragment,
    xacro_style: bool,
    bridge_added: Sequence[BridgeTopic] = (),
) -> Verdict:
    """What the add changes in the validator's findings (``check.compare_added``).

    The new elements sit at the end of the robot: for xacro, the call is the last thing
    in the file and the macro is self-contained, so the expansion gains the macro's
    output at its end; for URDF they are the inserted text, parsed with its lines.
    """
    from sensorkit.lint.engine import Options

    options = req.validation or Options(args=dict(req.args), package_paths=req.package_paths)
    if bridge_added:
        options = dataclasses.replace(options, bridge_pending=tuple(bridge_added))
    doc = robot.document
    if xacro_style:
        root = etree.Element(doc.root.tag, dict(doc.root.attrib), nsmap=doc.root.nsmap)
        for node in frag.nodes:
            root.append(copy.deepcopy(node))
    else:
        root = drop_default_namespace(tail)
    part = Document(
        path=doc.path,
        root=root,
        files=list(doc.files),
        expanded=doc.expanded,
        includes=list(doc.includes),
    )
    return compare_added(robot, load_findings, part, options)


# ----------------------------------------------------------------------------- publishing


def apply_add(result: AddResult) -> AddResult:
    """Publish a planned add, each file atomically: new files first (the macro copy, new
    package files), then the package files that change, the robot file, and the robot
    YAML last.

    Refuses (and writes nothing) when a file changed since it was planned. If a write
    fails, the files written before it are put back as they were (their planned bytes)
    and the new ones removed, so the package is left as it was; if even that fails, the
    error names the files that could not be put back.
    """
    if result.source.resolve() == result.target.resolve():
        try:
            current = result.target.read_bytes()
        except OSError as exc:
            msg = f"{display_path(result.target)}: cannot read it again ({exc.strerror})"
            raise InputError(msg) from None
        if current != result.original:
            msg = (
                f"{display_path(result.target)} changed while sensorkit worked; nothing was written"
            )
            raise EditRefused(msg)
    for w in result.writes:
        if w.role != "package":
            continue
        try:
            now: bytes | None = w.path.read_bytes()
        except FileNotFoundError:
            now = None
        except OSError as exc:
            msg = f"{display_path(w.path)}: cannot read it again ({exc.strerror})"
            raise InputError(msg) from None
        if now != w.original:
            what = "appeared" if w.original is None else "changed"
            msg = f"{display_path(w.path)} {what} while sensorkit worked; nothing was written"
            raise EditRefused(msg)

    def order(w: PlannedWrite) -> int:
        if w.role == "robot":
            return 2
        if w.role == "package" and w.original is not None:
            return 3 if w.why == SPEC_WHY else 1
        return 0

    writes = sorted(result.writes, key=order)  # stable: the planned order within a step
    made_dirs: list[Path] = []
    made_files: list[Path] = []
    replaced: list[tuple[Path, bytes]] = []
    try:
        for w in writes:
            if w.role == "macro" or (w.role == "package" and w.original is None):
                if w.path.exists():
                    msg = f"{display_path(w.path)} appeared meanwhile; nothing was written"
                    raise EditRefused(msg)
                missing = [p for p in [w.path.parent, *w.path.parent.parents] if not p.exists()]
                for folder in reversed(missing):
                    folder.mkdir()
                    made_dirs.append(folder)
                write_bytes(w.path, w.data, mode=w.mode)
                made_files.append(w.path)
            else:
                write_bytes(w.path, w.data, mode=w.mode)
                if w.role == "package" and w.original is not None:
                    replaced.append((w.path, w.original))
                elif w.role == "robot" and result.source.resolve() == w.path.resolve():
                    replaced.append((w.path, result.original))
    except BaseException:
        stuck: list[str] = []
        for path, old in reversed(replaced):
            try:
                write_bytes(path, old)
            except (OSError, WriteFailed):
                stuck.append(display_path(path))
        for f in made_files:
            f.unlink(missing_ok=True)
        for d in reversed(made_dirs):
            with contextlib.suppress(OSError):
                d.rmdir()
        if stuck:
            msg = (
                "the add failed part way and these files could not be put back as they "
                f"were (they hold the new text): {', '.join(stuck)}"
            )
            raise WriteFailed(msg) from None
        raise
    result.written = True
    return result


def add_sensor(req: AddRequest, *, dry_run: bool = False) -> AddResult:
    """Plan an add and, unless ``dry_run``, publish it. Raises EditRefused on refusal.

    A real add holds the folder lock from reading the file to the last rename, so two adds
    on one file take turns and both land (``sensorkit.base.atomic.editing``).
    """
    if dry_run:
        return plan_add(req)
    target = req.output if req.output is not None else req.path
    check_editable(target)
    # The folders of the robot's package too (bridge, README, robot YAML beside it).
    with editing(req.path, target, *lock_paths(req.path)):
        result = plan_add(req)
        apply_add(result)
    return result
