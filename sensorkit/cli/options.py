"""The options several commands share, each declared once as a typer ``Annotated`` alias:
a parameter ``arg: ArgOpt = None`` is the whole of ``--arg`` for the command that has it.

An option only one command takes is declared beside that command. Options that
several commands end with alike are also listed as parameters (``ROBOT_FLAGS``,
``PRINTING``, ``READING``), for the commands whose signature is put together from them
(``common.reads_robot``, the add-* table).
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Annotated, Any, TypeVar

import typer

FileArg = Annotated[Path, typer.Argument(help="a URDF or xacro file", show_default=False)]
ArgOpt = Annotated[
    list[str] | None,
    typer.Option("--arg", help="xacro argument NAME:=VALUE (repeatable)", metavar="NAME:=VALUE"),
]
PackagePathOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--package-path",
        help="where ROS packages live: DIR (scanned for package.xml) or NAME=DIR (repeatable)",
        metavar="DIR|NAME=DIR",
    ),
]
UntrustedOpt = Annotated[
    bool,
    typer.Option(
        "--untrusted",
        help="input from people you do not trust (pull-request CI): xacro sees no environment "
        "but --env names and reads no file outside the workspace and resolved packages",
    ),
]
EnvOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--env",
        help="with --untrusted: an environment variable xacro may read (repeatable)",
        metavar="NAME",
    ),
]
NoCacheOpt = Annotated[
    bool,
    typer.Option(
        "--no-cache",
        help="expand xacro again even when nothing it read has changed (the cache is in "
        "$XDG_CACHE_HOME/sensorkit; never used with --untrusted)",
    ),
]
ConfigOpt = Annotated[
    Path | None,
    typer.Option(
        "--config",
        help="settings file (sensorkit.toml, or pyproject.toml with [tool.sensorkit]); "
        "default: the nearest one above the robot file",
        metavar="FILE",
    ),
]
ColorOpt = Annotated[
    str,
    typer.Option(
        "--color",
        help="auto (on a terminal, unless NO_COLOR is set), always or never",
        metavar="auto|always|never",
    ),
]
QuietOpt = Annotated[
    bool,
    typer.Option(
        "--quiet", "-q", help="print only results and errors: no summary, notes or progress"
    ),
]
StdinFilenameOpt = Annotated[
    Path | None,
    typer.Option(
        "--stdin-filename",
        help="with - as the file: the path the text on stdin stands for (messages, relative "
        "includes, packages and the settings file are found from it)",
        metavar="PATH",
    ),
]
# intrinsics, export and topics: validate's and render preview's say it their own way
TargetOpt = Annotated[
    str | None,
    typer.Option(
        "--target",
        help="auto, classic, ros1, fortress, harmonic or jetty (default: the settings file's, "
        "else auto: detected as validate does)",
        show_default=False,
    ),
]
# validate's --bridge; topics' says "Gazebo Sim: " first
LAUNCH_HELP = (
    "a launch file to read for ros_gz_bridge entries, static transforms, frame_prefix and the "
    "spawned model name (repeatable; default: the settings file's launch, else the launch "
    "files beside the robot's package)"
)
BRIDGE_HELP = (
    "ros_gz_bridge YAML that carries the robot's gz topics to ROS (repeatable; default: "
    "parameter_bridge YAMLs in the robot package's config/)"
)


F = TypeVar("F", bound=Callable[..., Any])


def with_parameters(func: F, parameters: Sequence[inspect.Parameter]) -> F:
    """``func``, whose signature as typer reads it is ``parameters``."""
    func.__signature__ = inspect.Signature(parameters)  # type: ignore[attr-defined]
    return func


def parameter(name: str, annotation: object, default: object = None) -> inspect.Parameter:
    """Parameter ``name`` of a command whose signature is put together from parts:
    ``annotation`` says which option fills it (typer reads the signature)."""
    return inspect.Parameter(
        name, inspect.Parameter.KEYWORD_ONLY, annotation=annotation, default=default
    )


# how to read the robot (``common.RobotFlags``)
ROBOT_FLAGS = (
    parameter("arg", ArgOpt),
    parameter("package_path", PackagePathOpt),
    parameter("untrusted", UntrustedOpt, False),
    parameter("env", EnvOpt),
    parameter("config", ConfigOpt),
)
# what to print
PRINTING = (parameter("quiet", QuietOpt, False), parameter("color", ColorOpt, "auto"))
# what intrinsics, export and topics end with (``common.Reading``)
READING = (
    *ROBOT_FLAGS,
    parameter("no_cache", NoCacheOpt, False),
    *PRINTING,
    parameter("stdin_filename", StdinFilenameOpt),
)
