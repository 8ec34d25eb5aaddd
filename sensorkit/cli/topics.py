"""``sensorkit topics``: every topic a robot's sensors will publish, as ``ros2 topic list -t``.

Thin: parse options, call :mod:`sensorkit.describe.topics`, print. The list goes to stdout, notes
and the summary to stderr.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from sensorkit.cli.common import Reading, handle_errors, note, reads_robot
from sensorkit.cli.options import (
    BRIDGE_DEFAULT,
    BRIDGE_HELP,
    LAUNCH_DEFAULT,
    LAUNCH_HELP,
    OUTPUT,
    RULES,
    Command,
    FileArg,
    TargetOpt,
    examples,
)
from sensorkit.cli.world_models import described_models, models_json

if TYPE_CHECKING:
    from sensorkit.describe.sensorinfo import RobotInfo
    from sensorkit.describe.topics import RobotTopics
    from sensorkit.loading.launch_facts import LaunchFacts

FORMATS = ("text", "list", "json")

FormatOpt = Annotated[
    str,
    typer.Option(
        "--format",
        "-f",
        help="text (a row per topic: name, type, frame_id, encoding, rate, sensor), list "
        "(the lines `ros2 topic list -t` will print) or json",
        rich_help_panel=OUTPUT,
    ),
]
BridgeOpt = Annotated[
    list[Path] | None,
    typer.Option(
        "--bridge",
        help="Gazebo Sim: " + BRIDGE_HELP,
        show_default=BRIDGE_DEFAULT,
        rich_help_panel=RULES,
    ),
]
LaunchOpt = Annotated[
    list[Path] | None,
    typer.Option(
        "--launch",
        help="Gazebo Sim: " + LAUNCH_HELP,
        show_default=LAUNCH_DEFAULT,
        rich_help_panel=RULES,
    ),
]
HARMONIC = "examples/harmonic_robot/harmonic_robot_description/urdf/harmonic_robot.urdf.xacro"
EXAMPLES = examples(
    ("The topics of a Gazebo Sim robot, as its bridge names them", f"sensorkit topics {HARMONIC}"),
    (
        "Another robot's, as JSON for a script",
        "sensorkit topics examples/orbslam3_car/urdf/orbslam3_car.urdf.xacro -f json",
    ),
)


@handle_errors
@reads_robot
def topics(
    file: FileArg,
    fmt: FormatOpt = "text",
    target: TargetOpt = None,
    bridge: BridgeOpt = None,
    launch: LaunchOpt = None,
    *,
    reading: Reading,
) -> None:
    """List every topic the sensors of FILE will publish: resolved name, message type,
    frame_id, image encoding and rate; on Gazebo Sim with the gz topic and the ROS name
    the bridge gives it, or "not bridged".

    Exit status: 0, or 2 when it could not run.
    """
    from sensorkit.base.errors import UsageError
    from sensorkit.describe.topics import topics_json, topics_list, topics_text

    if fmt not in FORMATS:
        raise UsageError(f"--format {fmt!r}: use " + ", ".join(FORMATS))
    file, infos = described_models(file, reading, target=target)
    results = topic_lists(file, infos, bridge, launch, reading)
    show = topics_list if fmt == "list" else topics_text
    if len(results) == 1:
        sys.stdout.write(topics_json(results[0]) if fmt == "json" else show(results[0]))
    elif fmt == "json":
        sys.stdout.write(models_json(infos, [topics_json(r) for r in results]))
    else:  # a world: one table per model
        sys.stdout.write("\n".join(f"model {r.robot}:\n{show(r)}" for r in results))
    if not reading.quiet:
        for result in results:
            _say_notes_and_summary(result)


def topic_lists(
    file: Path,
    infos: list[RobotInfo],
    bridge: list[Path] | None,
    launch: list[Path] | None,
    reading: Reading,
) -> list[RobotTopics]:
    """The topics of each described model, with the bridge (``--bridge``, ``--launch``,
    the settings file's) on Gazebo Sim; a note (not with -q) when they are given for
    another target. ``check-recording`` predicts a recording's topics with it too."""
    from sensorkit.describe.topics import load_bridge, robot_topics
    from sensorkit.model.targets import is_gz

    files = [str(b) for b in bridge or ()]
    if (files or launch) and not any(is_gz(info.target) for info in infos):
        flag = "--bridge" if files else "--launch"
        note(
            f"sensorkit: note: {flag} ignored: target {infos[0].target} is not Gazebo Sim",
            reading.quiet,
        )
    results = []
    for info in infos:
        config_read = None
        if is_gz(info.target):
            from sensorkit.describe.sensorinfo import spawned_as

            facts = read_launch_facts(file, info, launch, reading)
            config_read = load_bridge(
                info.robot,
                info.target,
                files,
                facts=facts,
            )
            # the robot under the name its launch file spawns it, as validate sees it
            info = spawned_as(info, facts.spawn_name() if facts is not None else None)  # noqa: PLW2901
        results.append(robot_topics(info, config_read))
    return results


def read_launch_facts(
    file: Path, info: RobotInfo, launch: list[Path] | None, reading: Reading
) -> LaunchFacts | None:
    """The launch files validate reads for ``info``'s robot (``--launch``, else the
    settings file's, else those beside the robot); None when none was read."""
    from sensorkit.cli.common import launch_files
    from sensorkit.describe.topics import read_launch
    from sensorkit.lint.config import load_config

    cfg = load_config(file, explicit=reading.flags.config)
    return read_launch(
        info.robot,
        info.target,
        launch_files(launch, cfg),
        tuple(reading.flags.package_path or ()),
    )


def _say_notes_and_summary(result: RobotTopics) -> None:
    """On stderr: the notes (each once) and a line counting the topics (not with -q)."""
    for text in result.notes:
        typer.echo(f"sensorkit: note: {text}", err=True)
    said: set[str] = set()
    for t in result.topics:
        for text in t.notes:
            line = f"sensorkit: note: {t.gz_name or t.name}: {text}"
            if line not in said:
                said.add(line)
                typer.echo(line, err=True)
    shown = len(result.ros_topics)
    extra = len(result.topics) - shown
    typer.echo(
        f"sensorkit: {shown} ROS topic{'' if shown == 1 else 's'}"
        + (f" and {extra} gz topic{'' if extra == 1 else 's'} not bridged" if extra else "")
        + f" from {result.sensors} sensor{'' if result.sensors == 1 else 's'} of "
        f"{result.robot} (target {result.target}, {result.target_reason})"
        + (f"; bridge: {', '.join(result.bridge_files)}" if result.bridge_files else "")
        + (f"; launch: {', '.join(result.launch_files)}" if result.launch_files else ""),
        err=True,
    )


def register(app: typer.Typer) -> None:
    """Add ``topics`` to ``app``."""
    app.command("topics", cls=Command, no_args_is_help=True, epilog=EXAMPLES)(topics)
