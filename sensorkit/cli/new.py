"""``sensorkit new ROBOT.yaml -o DIR``: generate an ament package from a robot YAML."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from sensorkit.base.quote import plural
from sensorkit.cli.common import RobotFlags, handle_errors, settings, target_simulator, use_color
from sensorkit.cli.common import note as say
from sensorkit.cli.options import OUTPUT, ColorOpt, Command, ConfigOpt, QuietOpt, examples

EXAMPLES = examples(
    (
        "List the files a package would have, writing nothing",
        "sensorkit new examples/harmonic_robot/robot.yaml -o my_robot_description --dry-run",
    ),
    (
        "Generate it into a colcon workspace",
        "sensorkit new examples/harmonic_robot/robot.yaml -o ws/src/harmonic_robot_description",
    ),
)


@handle_errors
def new(
    spec: Annotated[
        Path,
        typer.Argument(
            help="the robot YAML (name, base, sim, sensors)",
            metavar="ROBOT.yaml",
            show_default=False,
        ),
    ],
    output: Annotated[
        Path,
        typer.Option(
            "--out",
            "-o",
            "--output",
            help="the package folder to create",
            show_default=False,
            rich_help_panel=OUTPUT,
        ),
    ],
    force: Annotated[
        bool,
        typer.Option("--force", help="replace OUTPUT if it is not empty", rich_help_panel=OUTPUT),
    ] = False,
    dry_run: Annotated[
        bool,
        typer.Option(
            "--dry-run", help="check and list the files, write nothing", rich_help_panel=OUTPUT
        ),
    ] = False,
    config: ConfigOpt = None,
    quiet: QuietOpt = False,
    color: ColorOpt = "auto",
) -> None:
    """Generate a colcon-ready ament package: package.xml, CMakeLists.txt, the robot
    xacro with the base and sensor macros, launch files and, for Gazebo Sim, the
    ros_gz_bridge config and a world."""
    from sensorkit.generate import new_package

    use_color(color)  # checked; nothing printed is coloured
    st = settings(spec, RobotFlags(config), target=None)
    defaults: dict[str, str] = {}
    if st.config.target:  # the simulator a robot.yaml without `sim:` is generated for
        defaults.update(target_simulator(st.config.target))
        note = st.config.describe(["target"])
        say(f"sensorkit: {note} (for a robot.yaml that names no sim)", quiet)
    result = new_package(spec, output, force=force, dry_run=dry_run, defaults=defaults)
    for rel in result.files:
        typer.echo((output / rel).as_posix())
    verb = "would write" if dry_run else "wrote"
    say(
        f"sensorkit: {verb} package {result.spec.package} ({plural(len(result.files), 'file')}) in {output}",
        quiet,
    )
    if not dry_run:
        say(f"sensorkit: next: sensorkit validate {result.robot_xacro.as_posix()}", quiet)


def register(app: typer.Typer) -> None:
    """Add the ``new`` command to ``app``."""
    app.command(name="new", cls=Command, no_args_is_help=True, epilog=EXAMPLES)(new)
