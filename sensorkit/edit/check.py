"""Checks an add must pass before anything is written.

Names: the new sensor's name and every link, joint and sensor its macro creates must be
unused, and the parent link must exist (the refusal names the closest links).

Validation: the validator runs on the robot before and after the add, and any
error-level finding the add introduces refuses it. The "after" robot is built in memory
at the original's path (nothing is written), so meshes, packages and inline
suppressions resolve exactly as they do for the original.
"""

from __future__ import annotations

import dataclasses
from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from sensorkit.base.errors import EditRefused
from sensorkit.base.findings import Finding, Severity
from sensorkit.loading.document import Document, display_path
from sensorkit.model import Robot
from sensorkit.model.parts import Joint, Link
from sensorkit.model.sensors import Sensor

if TYPE_CHECKING:
    from sensorkit.lint.engine import Options
    from sensorkit.model.sdf import Conversion


def closest(name: str, candidates: Iterable[str], n: int = 3) -> list[str]:
    """Up to ``n`` of ``candidates`` that look most like ``name`` (never empty if any exist)."""
    from sensorkit.base.suggest import closest as ranked

    pool = sorted(set(candidates))
    hits = ranked(name, pool, n=n)
    if not hits:
        lowered = name.lower()
        hits = [c for c in pool if lowered in c.lower() or c.lower() in lowered][:n]
    return hits or pool[:n]


def names_in_use(robot: Robot) -> dict[str, tuple[str, Link | Joint | Sensor]]:
    """Every name in use, mapped to what it names (first kind wins)."""
    used: dict[str, tuple[str, Link | Joint | Sensor]] = {}
    for link in robot.links:
        used.setdefault(link.name, ("link", link))
    for joint in robot.joints:
        used.setdefault(joint.name, ("joint", joint))
    for sensor in robot.sensors:
        used.setdefault(sensor.name, ("sensor", sensor))
    return used


def _free_name(name: str, used: dict[str, tuple[str, Link | Joint | Sensor]]) -> str:
    """``NAME_2`` (or the next free number) as a suggestion for another ``--name``."""
    n = 2
    while any(u.startswith(f"{name}_{n}") for u in used):
        n += 1
    return f"{name}_{n}"


def check_parent(robot: Robot, parent: str, where: str) -> None:
    """EditRefused naming the closest links when ``parent`` is not a link of the robot."""
    if parent in robot.link_map:
        return
    near = closest(parent, robot.link_map)
    if near:
        hint = f"; closest: {', '.join(near)}: pass --parent {near[0]}"
    elif robot.link_map:
        some = ", ".join(sorted(robot.link_map)[:5])
        hint = f"; pass --parent with one of its links ({some}{', ...' if len(robot.link_map) > 5 else ''})"
    else:
        hint = "; the robot has no links: add the link to mount on first"
    msg = f"parent link '{parent}' not found in {where}{hint}"
    raise EditRefused(msg)


def check_names(
    robot: Robot,
    name: str,
    created: Sequence[str],
    where: str,
    used: dict[str, tuple[str, Link | Joint | Sensor]] | None = None,
) -> None:
    """EditRefused when ``name`` or any name the macro creates is already used
    (``used``: ``names_in_use(robot)``, when the caller has it already)."""
    used = names_in_use(robot) if used is None else used
    for candidate in [name, *created]:
        if candidate in used:
            kind, item = used[candidate]
            what = f"{kind} '{item.name}' ({item.source})"
            via = "" if candidate == name else f" (the macro would create '{candidate}')"
            msg = (
                f"name '{name}' is already used in {where}: {what}{via}; pass another "
                f"--name (e.g. {_free_name(name, used)})"
            )
            raise EditRefused(msg)


@dataclass
class Verdict:
    """What the add changes in the validator's findings."""

    new_errors: list[Finding] = field(default_factory=list)
    new_warnings: list[Finding] = field(default_factory=list)
    internal_errors: list[str] = field(default_factory=list)


def _key(f: Finding) -> tuple[str, int, str]:
    return (f.rule, int(f.severity), f.message)


def introduced(before: Sequence[Finding], after: Sequence[Finding]) -> list[Finding]:
    """Findings of ``after`` that ``before`` lacks (as a multiset of rule, severity, message)."""
    budget = Counter(_key(f) for f in before)
    out: list[Finding] = []
    for f in after:
        k = _key(f)
        if budget[k] > 0:
            budget[k] -= 1
        else:
            out.append(f)
    return out


def findings(
    robot: Robot, load_findings: Sequence[Finding], options: Options
) -> tuple[list[Finding], list[str]]:
    """What ``sensorkit validate`` reports for ``robot`` (selection and inline suppressions
    applied), and the validator's internal errors."""
    from sensorkit.lint.engine import check_robot
    from sensorkit.lint.suppress import collect

    report = check_robot(robot, options)
    found = [f for f in [*load_findings, *report.findings] if options.wants(f.rule)]
    files = [(display_path(f), Path(f)) for f in robot.document.source_files()]
    sup = collect(files)
    return [f for f in found if not sup.suppressed(f)], list(report.internal_errors)


def compare(
    before: Robot,
    before_load: Sequence[Finding],
    after: Document,
    options: Options,
) -> Verdict:
    """Validate the robot before and after the add, both read from memory.

    ``after`` is a document at the same path as ``before`` (so meshes, packages and
    inline suppressions resolve alike); only the validator's verdict on the difference
    matters.
    """
    from sensorkit.model import build_robot

    old, _ = findings(before, before_load, options)
    new, internal = findings(build_robot(after), before_load, options)
    fresh = introduced(old, new)
    return Verdict(
        new_errors=[f for f in fresh if f.severity >= Severity.ERROR],
        new_warnings=[f for f in fresh if f.severity == Severity.WARNING],
        internal_errors=internal,
    )


def describe(finding: Finding) -> str:
    """``RULE message`` on one line. No file:line: a new finding is about text that is
    not in the user's file yet (the message names the sensor, link or joint)."""
    text = " ".join(finding.message.split())
    return f"{finding.rule} {text}"


# ----------------------------------------------------------------------------- re-check

# Rules whose findings on an element depend on that element alone (and on maps that an
# added leaf only extends): after an add they are the old findings plus those of the new
# elements, in the same order a full run gives. SK203 (roots, cut-off trees) cannot change
# when the robot had none and the addition hangs from an existing link.
_ADDITIVE = frozenset({"SK105", "SK201", "SK202", "SK204", "SK205", "SK206", "SK302", "SK507"})
# The model's element lists, and the maps that place their elements in the tree.
_ELEMENTS = ("links", "joints", "gazebo", "sensors", "model_plugins", "strays")
_TREE = ("link_map", "joint_map", "parent_joint", "child_joints")
_ROBOT_FIELDS = frozenset(
    {"name", "document", *_ELEMENTS, *_TREE, "_T_world", "_up", "_roots", "cache", "sdf"}
)


def _leaf_subtree(before: Robot, part: Robot) -> bool:
    """The part's links hang, joint by joint, below existing links as a tree of their own,
    and nothing in the robot already refers to them (so no old link, joint or pose moves)."""
    new_links = {lk.name for lk in part.links}
    if len(new_links) != len(part.links) or "" in new_links:
        return False
    if any(
        n in before.link_map or n in before.parent_joint or n in before.child_joints
        for n in new_links
    ):
        return False
    if any(j.name in before.joint_map for j in part.joints):
        return False
    parent_of: dict[str, str] = {}
    for j in part.joints:
        if j.child not in new_links or j.child in parent_of or j.parent is None:
            return False
        if j.parent not in new_links and j.parent not in before.link_map:
            return False
        parent_of[j.child] = j.parent
    if set(parent_of) != new_links:
        return False
    for name in new_links:  # every chain leaves the new links: no cycle among them
        cur, steps = name, 0
        while cur in new_links:
            cur, steps = parent_of[cur], steps + 1
            if steps > len(new_links):
                return False
    return True


def extend_robot(before: Robot, part: Robot) -> Robot | None:
    """``before`` with ``part``'s elements appended (what ``build_robot`` gives for the
    document holding both), without reading the old elements again; None when the part
    is not a leaf subtree (see ``_leaf_subtree``) or the model has grown fields unknown here.
    """
    if {f.name for f in dataclasses.fields(Robot)} != _ROBOT_FIELDS:
        return None
    if before.sdf is not None or part.sdf is not None:  # add-* edits URDF/xacro only
        return None
    if not _leaf_subtree(before, part):
        return None
    after = Robot(
        name=before.name,
        document=before.document,
        links=[*before.links, *part.links],
        joints=[*before.joints, *part.joints],
        gazebo=[*before.gazebo, *part.gazebo],
        sensors=[*before.sensors, *part.sensors],
        model_plugins=[*before.model_plugins, *part.model_plugins],
        strays=[*before.strays, *part.strays],
        link_map=dict(before.link_map),
        joint_map=dict(before.joint_map),
        parent_joint=dict(before.parent_joint),
        child_joints=dict(before.child_joints),
        _T_world=dict(before._T_world),  # old links keep their poses
        _up=dict(before._up),  # and their tree tops and depths (the part is a leaf subtree)
    )
    for lk in part.links:
        after.link_map.setdefault(lk.name, lk)
    for j in part.joints:
        after.joint_map.setdefault(j.name, j)
        if j.child is not None and j.child not in after.parent_joint:
            after.parent_joint[j.child] = j
        if j.parent is not None:
            after.child_joints[j.parent] = [*after.child_joints.get(j.parent, []), j]
    return after


def extend_conversion(
    conv: Conversion, before: Robot, after: Robot, added: Robot
) -> Conversion | None:
    """What ``convert(after)`` gives, from ``convert(before)`` and the added leaf subtree,
    when the addition drops nothing and lumps or keeps nothing it did not; else None.

    The new links are lumped (or kept) in the order Gazebo's conversion walks them; a
    surviving link that receives their mass keeps its place when its mass stays clear of
    zero (its ``mass_of`` is then the old sum plus theirs, which may differ from a full
    walk in the last bits; only the drop test reads it, and that is kept far from the
    edge). Anything else (a new drop, a changed preserveFixedJoint, a part hanging from
    more than one link, or from a link the walk never reaches) returns None.
    """
    from sensorkit.model.sdf import MASS_EPSILON, Conversion, preserved_fixed_joints

    preserved = preserved_fixed_joints(after)
    if preserved != conv.preserved_joints:
        return None
    new = {lk.name for lk in added.links}
    attach = {j.parent for j in added.joints if j.parent not in new}
    top = attach.pop() if len(attach) == 1 else None
    if top is None:
        return None
    chain = [top, *before.ancestors(top)]
    if chain[-1] in before.parent_joint:  # a cycle or a cut-off tree: the walk never gets here
        return None
    out = Conversion(
        target_of=dict(conv.target_of),
        mass_of=dict(conv.mass_of),
        dropped=dict(conv.dropped),
        preserved_joints=preserved,
    )
    order: list[str] = []
    stack = [top]
    while stack:  # as convert walks: children in joint order, the new ones come last
        cur = stack.pop()
        if cur != top:
            order.append(cur)
        for j in reversed(after.child_joints.get(cur, [])):
            child = j.child
            if child is not None and child in new and after.parent_joint.get(child) is j:
                stack.append(child)
    if len(order) != len(new):
        return None
    masses: dict[str, float] = {}
    for name in order:
        joint = after.parent_joint[name]
        parent_target = out.target_of[joint.parent or ""]
        lumped = joint.type == "fixed" and joint.name not in preserved and parent_target != "world"
        out.target_of[name] = parent_target if lumped else name
        target = out.target_of[name]
        masses[target] = masses.get(target, 0.0) + after.link_map[name].mass
    edge = 2 * MASS_EPSILON
    for target, extra in masses.items():
        if target in new:  # a new surviving link: it must carry mass and hang from one kept
            joint = after.parent_joint[target]
            parent_target = out.target_of[joint.parent or ""]
            if parent_target in out.dropped or abs(extra) <= edge:
                return None
            out.mass_of[target] = extra
        else:
            old = out.mass_of.get(target, 0.0)
            if target in out.dropped or abs(old) <= edge or abs(old + extra) <= edge:
                return None
            out.mass_of[target] = old + extra
    return out


def _selected(found: Iterable[Finding], robot: Robot, options: Options) -> list[Finding]:
    from sensorkit.lint.suppress import collect

    kept = [f for f in found if options.wants(f.rule)]
    files = [(display_path(f), Path(f)) for f in robot.document.source_files()]
    sup = collect(files)
    return [f for f in kept if not sup.suppressed(f)]


def compare_added(
    before: Robot,
    before_load: Sequence[Finding],
    part: Document,
    options: Options,
) -> Verdict:
    """``compare`` for a robot that only gains ``part``'s elements at its end.

    The robot is checked once; the result with the part is worked out from that run:
    the model is extended rather than rebuilt, rules that look at one element at a time
    (``_ADDITIVE``) check only the new elements, and the others run on the whole. The
    verdict is the one ``compare`` gives (tests/test_edit_incremental.py holds them
    side by side). A part that is not a leaf subtree falls back to ``compare``.
    """
    from sensorkit.lint.engine import find_missing_files, make_context, run_rule, run_rules
    from sensorkit.lint.rules import RULES
    from sensorkit.model import build_robot
    from sensorkit.model.targets import is_gz

    added = build_robot(part)
    after = extend_robot(before, added)
    if after is None:
        whole = copy_document_with(before.document, part)
        return compare(before, before_load, whole, options)
    run = run_rules(before, options)
    old = _selected([*before_load, *run.findings()], before, options)

    reuse = run.ctx.bridge if is_gz(run.ctx.target) else True
    conv = extend_conversion(run.ctx.conversion, before, after, added)
    ctx, _ = make_context(after, options, bridge=reuse, conversion=conv)
    package_findings = list(run.package_findings)
    if run.resolver is not None:
        missing, more = find_missing_files(
            after, run.resolver, links=added.links, seen_packages=set(run.seen_packages)
        )
        ctx.missing_files = [*run.ctx.missing_files, *missing]
        package_findings += more
    # the added elements, in the whole robot's tree
    view = Robot(
        after.name,
        after.document,
        **{k: getattr(added, k) for k in _ELEMENTS},
        **{k: getattr(after, k) for k in _TREE},
    )
    only_new = dataclasses.replace(ctx, robot=view, missing_files=[])
    failed = {e.split()[1] for e in run.internal_errors if e.startswith("rule ")}
    internal: list[str] = []
    found: list[Finding] = [*before_load, *package_findings]
    for rid, info in RULES.items():
        if info.func is None or not options.wants(rid):
            continue
        had = run.by_rule.get(rid, [])
        if rid in _ADDITIVE and rid not in failed:
            found += had + run_rule(only_new, info, internal)
        elif rid == "SK203" and not had and rid not in failed:
            continue
        else:
            found += run_rule(ctx, info, internal)
    fresh = introduced(old, _selected(found, after, options))
    return Verdict(
        new_errors=[f for f in fresh if f.severity >= Severity.ERROR],
        new_warnings=[f for f in fresh if f.severity == Severity.WARNING],
        internal_errors=internal,
    )


def copy_document_with(doc: Document, part: Document) -> Document:
    """A document holding ``doc``'s elements followed by ``part``'s (copies of both)."""
    import copy

    root = copy.deepcopy(doc.root)
    for node in part.root:
        root.append(copy.deepcopy(node))
    return Document(
        path=doc.path,
        root=root,
        files=list(doc.files),
        expanded=doc.expanded,
        includes=list(doc.includes),
    )
