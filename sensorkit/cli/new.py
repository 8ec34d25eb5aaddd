"""``sensorkit new ROBOT.yaml -o DIR``: generate an ament package from a robot YAML."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from sensorkit.cli.common import ConfigOpt, handle_errors, settings


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
        typer.Option("--out", "-o", "--output", help="the package folder to create", show_default=False),
    ],
    force: Annotated[
        bool, typer.Option("--force", help="replace OUTPUT if it is not empty")
    ] = False,
    dry_run: Annotated[
        bool, typer.Option("--dry-run", help="check and list the files, write nothing")
    ] = False,
    config: ConfigOpt = None,
) -> None:
    """Generate a colcon-ready ament package: package.xml, CMakeLists.txt, the robot
    xacro with the base and sensor macros, launch files and, for Gazebo Sim, the
    ros_gz_bridge config and a world."""
    from sensorkit.generate import new_package
    from sensorkit.model.targets import is_gz

    st = settings(spec, config=config, target=None, package_path=None, arg=None)
    defaults: dict[str, str] = {}
    if st.config.target:  # the simulator a robot.yaml without `sim:` is generated for
        defaults["sim"] = "gz" if is_gz(st.config.target) else "classic"
        if is_gz(st.config.target):
            defaults["gz_version"] = st.config.target
        note = st.config.describe(["target"])
        typer.echo(f"sensorkit: {note} (for a robot.yaml that names no sim)", err=True)
    result = new_package(spec, output, force=force, dry_run=dry_run, defaults=defaults)
    for rel in result.files:
        typer.echo((output / rel).as_posix())
    verb = "would write" if dry_run else "wrote"
    typer.echo(
        f"sensorkit: {verb} package {result.spec.package} ({len(result.files)} files) in {output}",
        err=True,
    )
    if not dry_run:
        typer.echo(f"sensorkit: next: sensorkit validate {result.robot_xacro.as_posix()}", err=True)


def register(app: typer.Typer) -> None:
    """Add the ``new`` command to ``app``."""
    app.command(name="new", no_args_is_help=True)(new)
