"""SK2xx: the kinematic tree.

URDF only (``RuleInfo.formats``): SDF's kinematics are not URDF's, and libsdformat reports
what these rules would, in its own words (gazebosim/sdformat@sdformat12_12.8.0):
- SK201: names are unique per scope across links, joints, frames and models, and a second
  one is DUPLICATE_NAME (src/FrameSemantics.cc:636-645);
- SK202: a joint's missing child is JOINT_CHILD_LINK_INVALID (src/FrameSemantics.cc:
  767-775); a parent that names no frame is a frame-graph error;
- SK203: a link no joint holds is a free body, not a second root: libsdformat loads it
  without a word (tests/robots/sdf/frames/urdf_only.sdf, tests/test_sdf_frame_rules.py);
- SK204: a joint whose parent is its child is JOINT_PARENT_SAME_AS_CHILD (src/Joint.cc:
  159-166); closed chains are SDF;
- SK205: ball, universal, screw, gearbox and revolute2 are joint types (sdf/1.9/joint.sdf:
  9-21), an unknown one ATTRIBUTE_INVALID (src/Joint.cc:207-214), and <limit> has defaults
  (sdf/1.9/joint.sdf:75-89: no effort or velocity limit when absent);
- SK206: a zero axis is "The norm of the xyz vector cannot be zero" (src/JointAxis.cc:
  171-177); poses are the reader's (SdfModel.pose_problems);
- SK207: SDF 1.11's <mimic> sits in <axis>, which sensorkit does not read.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator

from sensorkit.base.findings import Finding, Severity
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.robot import Robot
from sensorkit.model.urdf import JOINT_TYPES


@rule("SK201", "error", "link, joint and sensor-link names unique", "urdfdom")
def unique_names(ctx: Context) -> Iterator[Finding]:
    # An error: urdfdom refuses the whole robot ("link '%s' is not unique.", "joint '%s' is not
    # unique.": ros/urdfdom@rolling (9a1f5b4):urdf_parser/src/model.cpp:177-181, :220-224), so
    # robot_state_publisher has no model and publishes no TF.
    robot = ctx.robot
    for kind, items, by_name in (
        ("link", robot.links, robot.link_map),
        ("joint", robot.joints, robot.joint_map),
    ):
        if len(by_name) == len(items) and "" not in by_name:
            continue  # the map holds one entry per name: every name is there once
        counts = Counter(x.name for x in items)
        seen: set[str] = set()
        for item in items:
            if not item.name:
                yield ctx.finding(
                    "SK201",
                    Severity.ERROR,
                    f"a <{kind}> has no name",
                    item.source,
                    fix=f'give the <{kind}> a unique name="..."',
                )
                continue
            if counts[item.name] > 1:
                if item.name in seen:
                    yield ctx.finding(
                        "SK201",
                        Severity.ERROR,
                        f"{kind} name {item.name!r} is used {counts[item.name]} times",
                        item.source,
                        **{kind: item.name},
                        fix=f"rename one of the {kind}s called {item.name!r}",
                    )
                seen.add(item.name)


@rule("SK202", "error", "every joint has parent and child, and both links exist", "urdfdom")
def joint_links(ctx: Context) -> Iterator[Finding]:
    # An error: urdfdom's initTree throws for a joint whose parent or child link is missing and
    # the parse fails, "Failed to build tree" (ros/urdfdom@rolling (9a1f5b4):urdf_parser/src/model.cpp:249-256).
    links = ctx.robot.link_map
    for j in ctx.robot.joints:
        if j.parent in links and j.child in links:
            continue  # the usual case: both exist (None is never a link name)
        for role, name in (("parent", j.parent), ("child", j.child)):
            if name is None:
                yield ctx.finding(
                    "SK202",
                    Severity.ERROR,
                    f'joint {j.name!r} has no <{role} link="..."/>',
                    j.source,
                    joint=j.name,
                    fix=f'add <{role} link="LINK"/> to the joint',
                )
            elif name not in links:
                from sensorkit.base.suggest import closest

                close = closest(name, links)
                yield ctx.finding(
                    "SK202",
                    Severity.ERROR,
                    f"joint {j.name!r} names {role} link {name!r}, which does not exist",
                    j.source,
                    joint=j.name,
                    link=name,
                    fix=f"did you mean {close[0]!r}?" if close else f'define <link name="{name}"/>',
                )


@rule("SK203", "error", "exactly one root link; name every disconnected link", "urdfdom")
def single_root(ctx: Context) -> Iterator[Finding]:
    # An error: urdfdom's initRoot throws for more than one root and the parse fails, "Failed to
    # find root link" (ros/urdfdom@rolling (9a1f5b4):urdf_parser/src/model.cpp:258-267).
    robot = ctx.robot
    if not robot.links:
        if robot.macros_only:  # a partial: no finding (the report counts it as skipped)
            return
        yield ctx.finding(
            "SK203",
            Severity.ERROR,
            "the robot has no links",
            robot.document.root,
            fix="add at least one <link>",
        )
        return
    for top in robot.cut_off():
        j = robot.parent_joint[top]
        sub = robot.subtree(top)
        below = (
            f" and the {len(sub) - 1} links below it ({', '.join(sub[1:4])}{', ...' if len(sub) > 4 else ''})"
            if len(sub) > 1
            else ""
        )
        yield ctx.finding(
            "SK203",
            Severity.ERROR,
            f"link {top!r}{below} is cut off from the robot: its joint {j.name!r} hangs it from "
            f"{j.parent!r}, which does not exist",
            robot.link_map[top].source,
            link=top,
            joint=j.name,
            fix=f"fix the parent of joint {j.name!r} (see SK202); until then TF cannot place these links",
        )
    roots = robot.roots()
    if len(roots) > 1:
        main = max(roots, key=lambda r: len(robot.subtree(r)))
        for r in roots:
            if r == main:
                continue
            sub = robot.subtree(r)
            extra = f" (with {len(sub) - 1} links below it)" if len(sub) > 1 else ""
            yield ctx.finding(
                "SK203",
                Severity.ERROR,
                f"link {r!r}{extra} is not connected to the tree rooted at {main!r}",
                robot.link_map[r].source,
                link=r,
                fix=f'add a joint with <child link="{r}"/> from a link of the main tree',
            )


@rule(
    "SK204",
    "error",
    "no link with two parent joints, no self-joint, no cycle (must terminate: check_urdf hangs)",
)
def tree_shape(ctx: Context) -> Iterator[Finding]:
    robot = ctx.robot
    children: set[str] = set()  # every child of a joint that is not a self-joint
    twice = False
    for j in robot.joints:
        c = j.child
        if c is not None and j.parent == c:
            yield ctx.finding(
                "SK204",
                Severity.ERROR,
                f"joint {j.name!r} joins link {j.parent!r} to itself",
                j.source,
                joint=j.name,
                link=j.parent,
                fix="a joint's parent and child must differ",
            )
        elif c is not None:
            if c in children:
                twice = True
            else:
                children.add(c)
    # Cycles over every joint (a second parent can close a loop too).
    if twice:
        yield from _second_parents(ctx)
    elif _reaches_every_child(robot, children):
        return
    yield from _cycles(ctx)


def _second_parents(ctx: Context) -> Iterator[Finding]:
    """SK204 for each link that more than one joint (not a self-joint) hangs."""
    robot = ctx.robot
    parents: dict[str, list[str]] = {}  # the parent joints of each child
    for j in robot.joints:
        if j.child is not None and j.parent != j.child:
            parents.setdefault(j.child, []).append(j.name)
    for child, joints in parents.items():
        if len(joints) > 1:
            yield ctx.finding(
                "SK204",
                Severity.ERROR,
                f"link {child!r} has {len(joints)} parent joints: {', '.join(joints)}",
                robot.joint_map[joints[1]].source,
                link=child,
                joint=joints[1],
                fix="a URDF is a tree: keep one parent joint (model closed chains with a plugin)",
            )


def _reaches_every_child(robot: Robot, children: set[str]) -> bool:
    """The fast path with one parent per link: a walk from the roots that reaches every
    child proves there is no cycle."""
    stack = robot.roots()
    reached = set(stack)
    child_joints = robot.child_joints
    while stack:
        kids = child_joints.get(stack.pop())
        if kids:
            for j in kids:
                c = j.child
                if c is not None and c not in reached and j.parent != c:
                    reached.add(c)
                    stack.append(c)
    return reached.issuperset(children)


def _cycles(ctx: Context) -> Iterator[Finding]:
    """SK204 for each kinematic cycle, once: an iterative depth-first search (it must
    terminate where check_urdf hangs)."""
    robot = ctx.robot
    edges: dict[str, list[tuple[str, str]]] = {}
    for j in robot.joints:
        if j.parent is not None and j.child is not None and j.parent != j.child:
            edges.setdefault(j.parent, []).append((j.child, j.name))
    color: dict[str, int] = {}
    reported: set[frozenset[str]] = set()
    for start in [lk.name for lk in robot.links] + list(edges):
        if color.get(start):
            continue
        color[start] = 1
        path: list[tuple[str, str | None]] = [(start, None)]
        iters = [iter(edges.get(start, []))]
        while iters:
            nxt = next(iters[-1], None)
            if nxt is None:
                color[path[-1][0]] = 2
                path.pop()
                iters.pop()
                continue
            child, jname = nxt
            state = color.get(child, 0)
            if state == 0:
                color[child] = 1
                path.append((child, jname))
                iters.append(iter(edges.get(child, [])))
            elif state == 1:
                names = [n for n, _ in path]
                loop = path[names.index(child) :]
                key = frozenset(n for n, _ in loop)
                if key in reported:
                    continue
                reported.add(key)
                joints = [jn or "" for _, jn in loop[1:]] + [jname]
                first = robot.joint_map.get(jname)
                yield ctx.finding(
                    "SK204",
                    Severity.ERROR,
                    "kinematic cycle: "
                    + " -> ".join([*(n for n, _ in loop), child])
                    + f" (joints {', '.join(joints)}); check_urdf loops forever on this",
                    first.source if first else robot.document.locate(None),
                    link=child,
                    joint=jname,
                    fix="break the loop: one of these joints must hang from a link outside it",
                )


@rule(
    "SK205",
    "error",
    "joint type valid; revolute/prismatic have `<limit>` with effort and velocity; lower <= upper",
    "urdfdom (partly)",
)
def joint_types(ctx: Context) -> Iterator[Finding]:
    # Errors urdfdom refuses the robot for (ros/urdfdom@rolling (9a1f5b4):urdf_parser/src/joint.cpp): "Joint [%s] has no known
    # type" :420-421; a revolute / prismatic joint without <limit> :461-467; a <limit> without
    # effort :136-137 or velocity :152-153. lower > upper is not checked by urdfdom and was not
    # verified against a simulator in the issue 23 audit.
    for j in ctx.robot.joints:
        if j.type not in JOINT_TYPES:
            yield ctx.finding(
                "SK205",
                Severity.ERROR,
                f"joint {j.name!r} has type {j.type!r}",
                j.source,
                joint=j.name,
                fix="use one of: " + ", ".join(sorted(JOINT_TYPES)),
            )
            continue
        for problem in j.limit_problems:
            yield ctx.finding(
                "SK205",
                Severity.ERROR,
                f"joint {j.name!r} <limit>: {problem}",
                j.source,
                joint=j.name,
                fix="write finite numbers",
            )
        if j.type in ("revolute", "prismatic"):
            if j.limit is None:
                yield ctx.finding(
                    "SK205",
                    Severity.ERROR,
                    f"{j.type} joint {j.name!r} has no <limit>",
                    j.source,
                    joint=j.name,
                    fix='add <limit lower="..." upper="..." effort="..." velocity="..."/> (or use type="continuous")',
                )
                continue
            for key in ("effort", "velocity"):
                if j.limit.get(key) is None and not any(key in p for p in j.limit_problems):
                    yield ctx.finding(
                        "SK205",
                        Severity.ERROR,
                        f"{j.type} joint {j.name!r}: <limit> has no {key}",
                        j.source,
                        joint=j.name,
                        fix=f'add {key}="..." to <limit>',
                    )
            lo, hi = j.limit.get("lower"), j.limit.get("upper")
            if lo is not None and hi is not None and lo > hi:
                yield ctx.finding(
                    "SK205",
                    Severity.ERROR,
                    f"joint {j.name!r}: lower {lo:g} > upper {hi:g}",
                    j.source,
                    joint=j.name,
                    fix="swap lower and upper",
                )


@rule(
    "SK206",
    "error",
    "origin xyz/rpy and axis are three finite numbers; axis non-zero",
    "urdfdom (partly)",
)
def numbers(ctx: Context) -> Iterator[Finding]:
    robot = ctx.robot
    for j in robot.joints:
        for problem in j.origin.problems:
            yield ctx.finding(
                "SK206",
                Severity.ERROR,
                f"joint {j.name!r} <origin>: {problem}",
                j.source,
                joint=j.name,
                fix="write three finite numbers separated by spaces",
            )
        # urdfdom reads <axis> only for moving joints (ros/urdfdom@9a1f5b4:
        # urdf_parser/src/joint.cpp:425): a fixed or floating joint's axis is never used.
        if j.axis_problem and j.type not in ("fixed", "floating"):
            yield ctx.finding(
                "SK206",
                Severity.ERROR,
                f"joint {j.name!r} <axis>: {j.axis_problem}",
                j.source,
                joint=j.name,
                fix='write a non-zero direction, e.g. <axis xyz="0 0 1"/>',
            )
    for lk in robot.links:
        if lk.inertial is not None:
            for problem in lk.inertial.origin.problems:
                yield ctx.finding(
                    "SK206",
                    Severity.ERROR,
                    f"link {lk.name!r} inertial <origin>: {problem}",
                    lk.inertial.source,
                    link=lk.name,
                    fix="write three finite numbers",
                )


@rule("SK207", "error", "mimic joint names an existing, non-fixed joint")
def mimic(ctx: Context) -> Iterator[Finding]:
    joints = ctx.robot.joint_map
    for j in ctx.robot.joints:
        # A fixed joint never moves, so nothing reads its <mimic> (robot_state_publisher and
        # Gazebo only mimic joints that have a position): only a moving mimic can break.
        if not j.has_mimic or j.type == "fixed":
            continue
        target = joints.get(j.mimic or "")
        if not j.mimic or target is None:
            yield ctx.finding(
                "SK207",
                Severity.ERROR,
                f"joint {j.name!r} mimics {j.mimic!r}, which does not exist",
                j.source,
                joint=j.name,
                fix='name an existing joint in <mimic joint="..."/>',
            )
        elif target.type == "fixed":
            yield ctx.finding(
                "SK207",
                Severity.ERROR,
                f"joint {j.name!r} mimics fixed joint {j.mimic!r}",
                j.source,
                joint=j.name,
                fix="mimic a joint that moves",
            )
        elif target.name == j.name:
            yield ctx.finding(
                "SK207",
                Severity.ERROR,
                f"joint {j.name!r} mimics itself",
                j.source,
                joint=j.name,
                fix="mimic another joint",
            )
