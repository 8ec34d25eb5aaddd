"""``sensorkit frames``: a robot's TF tree as ``check_urdf`` prints it, with its sensors' frames.

Thin: parse options, call :func:`sensorkit.describe.frames_tree.frame_tree`, format it as
text (``check_urdf``'s tree, then one line per sensor), JSON or a graphviz digraph (the
nodes and ``parent -> child`` edges ``tf2_tools view_frames`` draws). The tree goes to
stdout, notes and the summary to stderr.
"""

from __future__ import annotations

import json
import sys
from typing import TYPE_CHECKING, Annotated, Any

import typer

from sensorkit.cli.common import Reading, handle_errors, note, reads_robot
from sensorkit.cli.options import OUTPUT, Command, FileArg, TargetOpt, examples
from sensorkit.cli.topics import LaunchOpt, read_launch_facts
from sensorkit.cli.world_models import described_models, models_json

if TYPE_CHECKING:
    from pathlib import Path

    from sensorkit.describe.frames_tree import Frame, FrameTree, SensorFrame, Stamp
    from sensorkit.describe.sensorinfo import RobotInfo

FORMATS = ("text", "json", "dot")

FormatOpt = Annotated[
    str,
    typer.Option(
        "--format",
        "-f",
        help="text (the tree as check_urdf prints it, then the frame each sensor stamps), "
        "json, or dot (a graphviz digraph as tf2_tools view_frames draws: "
        "`sensorkit frames robot.urdf -f dot | dot -Tpdf -o frames.pdf`)",
        rich_help_panel=OUTPUT,
    ),
]

EXAMPLES = examples(
    (
        "The TF tree, each sensor's frames, and what Gazebo lumps",
        "sensorkit frames examples/orbslam3_car/urdf/orbslam3_car.urdf.xacro",
    ),
    (
        "The same as a graphviz digraph, for dot -Tpdf",
        "sensorkit frames examples/orbslam3_car/urdf/orbslam3_car.urdf.xacro -f dot",
    ),
)

LUMPING_NOTE = (
    "lumped frames stay in TF (robot_state_publisher publishes every joint); Gazebo merges "
    "them into the link named, which its sensors then hang from: a plugin's default frame "
    "and a gz scoped name use that link"
)


@handle_errors
@reads_robot
def frames(
    file: FileArg,
    fmt: FormatOpt = "text",
    target: TargetOpt = None,
    launch: LaunchOpt = None,
    *,
    reading: Reading,
) -> None:
    """Print the TF tree of FILE as check_urdf does, marking the link each sensor is on,
    the frame each sensor's data is stamped with, optical frames, and the links Gazebo
    lumps away (fixed joints) or drops (no mass).

    Exit status: 0, or 2 when it could not run.
    """
    from sensorkit.base.errors import UsageError
    from sensorkit.describe.frames_tree import frame_tree
    from sensorkit.describe.sensorinfo import spawned_as
    from sensorkit.model.targets import is_gz

    if fmt not in FORMATS:
        raise UsageError(f"--format {fmt!r}: use " + ", ".join(FORMATS))
    file, infos = described_models(file, reading, target=target)
    if launch and not any(is_gz(info.target) for info in infos):
        note(
            f"sensorkit: note: --launch ignored: target {infos[0].target} is not Gazebo Sim",
            reading.quiet,
        )
    # On Gazebo Sim a sensor without a frame tag is stamped MODEL::LINK::SENSOR, MODEL the
    # name its launch file spawns the robot under: the launch files validate reads say it.
    infos = [
        spawned_as(info, _spawn_name(file, info, launch, reading))
        if is_gz(info.target)
        else info
        for info in infos
    ]
    trees = [frame_tree(info) for info in infos]  # a world: one tree per model
    writer = {"text": frames_text, "json": frames_json, "dot": frames_dot}[fmt]
    if fmt == "json" and len(trees) > 1:
        sys.stdout.write(models_json(infos, [frames_json(t) for t in trees]))
    else:
        sys.stdout.write("\n".join(writer(t) for t in trees))
    if any(t.lumped for t in trees):
        note(f"sensorkit: note: {LUMPING_NOTE}", reading.quiet)
    for tree in trees:
        note(f"sensorkit: {_summary(tree)}", reading.quiet)


def _spawn_name(
    file: Path, info: RobotInfo, launch: list[Path] | None, reading: Reading
) -> str | None:
    """The name the launch files validate reads spawn the robot under, or None."""
    facts = read_launch_facts(file, info, launch, reading)
    return facts.spawn_name() if facts is not None else None


def _plural(n: int, word: str, words: str | None = None) -> str:
    return f"{n} {word if n == 1 else words or word + 's'}"


def _summary(tree: FrameTree) -> str:
    links = sum(1 for f in tree.frames.values() if not f.missing)
    said = [f"{len(tree.lumped)} lumped by {tree.simulator}", f"{len(tree.optical)} optical"]
    return (
        f"{_plural(links, 'frame')} ({', '.join(said)}) and "
        f"{_plural(len(tree.sensors), 'sensor')} of {tree.robot} "
        f"(target {tree.target}, {tree.target_reason})"
    )


# --------------------------------------------------------------------------- text


def _names(items: list[str]) -> str:
    return ", ".join(items)


def marks(f: Frame, simulator: str) -> list[str]:
    """What the tree says of frame ``f`` beyond its name, in a fixed order."""
    out: list[str] = []
    if f.missing:
        out.append("no <link> of this name: a joint names it as parent")
    if f.sensors:
        out.append(f"{'sensor' if len(f.sensors) == 1 else 'sensors'} {_names(f.sensors)} on it")
    if f.stamped_by:
        out.append(f"frame_id of {_names(f.stamped_by)}")
    if f.optical_for:
        out.append(f"optical frame of {_names(f.optical_for)}")
    if f.lumped_into is not None:
        out.append(f"lumped into {f.lumped_into} by {simulator}")
    if f.kept:
        out.append(f"fixed joint {f.joint} kept by {simulator} (lumping disabled)")
    if f.dropped_by is not None:
        why = "it has" if f.dropped_by == f.name else f"{f.dropped_by} has"
        out.append(f"dropped by {simulator}: {why} no mass")
    return out


def _tree_lines(tree: FrameTree) -> list[str]:
    """The tree in check_urdf's shape: ``root Link: X has N child(ren)``, then each child
    as ``child(i):  NAME``, four spaces deeper per level (urdfdom's check_urdf.cpp
    printTree); each line followed by its marks in brackets."""
    lines: list[str] = []
    index: dict[str, int] = {}
    for f in tree.frames.values():
        for i, child in enumerate(f.children, 1):
            index.setdefault(child, i)
    for name, depth in tree.order:
        f = tree.frames[name]
        said = marks(f, tree.simulator)
        tail = f"  [{'; '.join(said)}]" if said else ""
        if depth == 0:
            lines.append(
                f"root link: {name} has {_plural(len(f.children), 'child', 'children')}{tail}"
            )
        else:
            lines.append(f"{'    ' * depth}child({index.get(name, 1)}):  {name}{tail}")
    if tree.unreached:
        lines.append(f"on a cycle of joints, under no root: {_names(tree.unreached)}")
    return lines


def stamp_text(stamp: Stamp, sensor: SensorFrame, simulator: str) -> str:
    """One stamped frame of a sensor and where its name comes from."""
    if stamp.how == "default":
        source = (
            f"{simulator}'s default, the scoped name"
            if sensor.plugin is None
            else f"the default of {sensor.plugin}"
        )
    elif sensor.plugin is not None:
        source = f"<{stamp.how}> of {sensor.plugin}"
    else:
        source = f"<{stamp.how}>"
    what = "images " if stamp.data == "images" else ""
    out = f"{what}{stamp.frame} ({source})"
    return out if stamp.in_tree else out + ", which is no frame of the tree"


def _sensor_line(s: SensorFrame, simulator: str) -> str:
    where = f"on {s.link}" if s.link is not None else f"on {s.reference!r}, which is no link"
    head = f"sensor {s.name} ({s.type}) {where}: "
    if not s.stamps:
        if s.stamps_nothing:
            return head + f"stamps nothing ({s.note})"
        return head + f"frame_id not known ({s.note})"
    line = head + "frame_id " + ", ".join(stamp_text(t, s, simulator) for t in s.stamps)
    if s.camera and s.stamps[-1].frame != s.optical:
        line += "; " + (
            f"optical frame at the camera: {s.optical}"
            if s.optical
            else "no link is placed as the camera's optical frame"
        )
    return line


def frames_text(tree: FrameTree) -> str:
    """``robot name is: NAME``, the tree, then a line per sensor naming its frames."""
    lines = [f"robot name is: {tree.robot}", *_tree_lines(tree)]
    if tree.sensors:
        lines.append("")
        lines += [_sensor_line(s, tree.simulator) for s in tree.sensors]
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------- json


def _frame_json(f: Frame) -> dict[str, Any]:
    return {
        "name": f.name,
        "parent": f.parent,
        "joint": f.joint,
        "joint_type": f.joint_type,
        "children": f.children,
        "sensors": f.sensors,
        "stamped_by": f.stamped_by,
        "optical_for": f.optical_for,
        "lumped_into": f.lumped_into,
        "lumping_disabled": f.kept,
        "dropped_by": f.dropped_by,
        "missing": f.missing,
    }


def _sensor_json(s: SensorFrame) -> dict[str, Any]:
    return {
        "name": s.name,
        "type": s.type,
        "reference": s.reference,
        "link": s.link,
        "plugin": s.plugin,
        "frame_ids": [
            {"frame": t.frame, "data": t.data, "from": t.how, "in_tree": t.in_tree}
            for t in s.stamps
        ],
        "note": s.note,
        "stamps_nothing": s.stamps_nothing,
        "optical_frame": s.optical,
    }


def frames_json(tree: FrameTree) -> str:
    """The tree as one JSON document (frames in the order of the text's walk)."""
    doc = {
        "robot": tree.robot,
        "target": tree.target,
        "target_reason": tree.target_reason,
        "simulator": tree.simulator,
        "roots": tree.roots,
        "frames": [_frame_json(tree.frames[name]) for name, _depth in tree.order],
        "unreached": [_frame_json(tree.frames[name]) for name in tree.unreached],
        "sensors": [_sensor_json(s) for s in tree.sensors],
    }
    return json.dumps(doc, indent=2) + "\n"


# --------------------------------------------------------------------------- dot


def dot_id(text: str) -> str:
    """``text`` as a DOT double-quoted string: ``\\`` and ``"`` escaped, control
    characters as spaces (a quoted string may hold any other character)."""
    clean = "".join(" " if ord(c) < 32 or ord(c) == 127 else c for c in text)
    return '"' + clean.replace("\\", "\\\\").replace('"', '\\"') + '"'


def dot_label(parts: list[str]) -> str:
    """Lines as one DOT label: each escaped, joined by ``\\n`` (a centred line break)."""
    return '"' + "\\n".join(dot_id(x)[1:-1] for x in parts) + '"'


def _dot_node(f: Frame, simulator: str) -> str:
    attrs = [f"label={dot_label([f.name, *marks(f, simulator)])}"]
    style = []
    if f.optical_for or f.stamped_by or f.sensors:
        style.append("filled")
        attrs.append('fillcolor="#cfe8ff"' if f.optical_for else 'fillcolor="#e8e8e8"')
    if f.lumped_into is not None or f.dropped_by is not None or f.missing:
        style.append("dashed")
    if style:
        attrs.append(f'style="{",".join(style)}"')
    return f"  {dot_id(f.name)} [{', '.join(attrs)}];"


def frames_dot(tree: FrameTree) -> str:
    """A graphviz digraph: a node per frame (its label the name and its marks), an edge
    ``parent -> child`` per joint labelled with the joint's name and type, as
    tf2_tools' view_frames draws a TF tree; frames stamped that are no link of the tree
    as dotted nodes without edges."""
    lines = [
        f"digraph {dot_id(tree.robot)} {{",
        f"  label={dot_id(f'{tree.robot}: TF tree, target {tree.target}')};",
        "  node [shape=ellipse];",
    ]
    walked = [tree.frames[name] for name, _depth in tree.order]
    walked += [tree.frames[name] for name in tree.unreached]
    lines += [_dot_node(f, tree.simulator) for f in walked]
    for f in walked:
        if f.parent is not None and f.joint is not None:
            label = f"{f.joint} ({f.joint_type})" if f.joint_type else f.joint
            lines.append(f"  {dot_id(f.parent)} -> {dot_id(f.name)} [label={dot_id(label)}];")
    outside: dict[str, list[str]] = {}
    for s in tree.sensors:
        for t in s.stamps:
            if not t.in_tree:
                outside.setdefault(t.frame, []).append(s.name)
    for frame, who in outside.items():
        label = dot_label([frame, f"frame_id of {_names(who)}", "no frame of the tree"])
        lines.append(f"  {dot_id(frame)} [label={label}, style=dotted];")
    lines.append("}")
    return "\n".join(lines) + "\n"


def register(app: typer.Typer) -> None:
    """Add ``frames`` to ``app``."""
    app.command("frames", cls=Command, no_args_is_help=True, epilog=EXAMPLES)(frames)
