"""The options several commands share, each declared once as a typer ``Annotated`` alias:
a parameter ``arg: ArgOpt = None`` is the whole of ``--arg`` for the command that has it.

An option only one command takes is declared beside that command. Options that
several commands end with alike are also listed as parameters (``ROBOT_FLAGS``,
``PRINTING``, ``READING``), for the commands whose signature is put together from them
(``common.reads_robot``, the add-* table).
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Annotated, Any, TypeVar

import typer
from typer.core import TyperCommand

# the --help panels, printed in this order after the command's own (no panel: "Options";
# add-*'s Mount and Sensor, render preview's Rendering)
RULES = "Rules"
FIXING = "Fixing"
OUTPUT = "Output"
XACRO = "xacro & packages"
TRUST = "Trust"
_LAST = (RULES, FIXING, OUTPUT, XACRO, TRUST)

# What Rich takes for a markup tag ([bold], [tool.sensorkit], [default: x]), as
# rich.markup.escape finds it: --help text is plain text, never markup. (rich itself is
# imported only to print --help, not by a command that runs.)
_MARKUP_TAG = r"(\\*)(\[[a-z#/@][^[]*?])"


def _plain(text: str | None) -> str | None:
    """``text`` with each Rich markup tag escaped, so that --help prints it as written."""
    if not text or "[" not in text:
        return text
    return re.sub(_MARKUP_TAG, lambda m: f"{m[1]}{m[1]}\\{m[2]}", text)


class Command(TyperCommand):
    """Every sensorkit command (``app.command(cls=Command)``), for --help:

    - the usage line names arguments plainly: ``FILES...``, ``[IDS]...``, ``FILE``
      (typer writes ``{files}...``);
    - a ``show_default`` given as text (a default that is not a value: "the settings
      file's, else auto") reads ``[default: TEXT]`` as a value's does, not ``(TEXT)``;
    - help texts, the docstring and the examples print as written: ``[tool.sensorkit]``
      is text, not a Rich markup tag.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        rich = self.rich_markup_mode == "rich"
        for param in self.params:
            shown = getattr(param, "show_default", None)
            text = getattr(param, "help", None)
            if isinstance(shown, str) and text is not None:
                text = f"{text} [default: {shown}]"
                param.show_default = False  # type: ignore[attr-defined]
            if rich:
                text = _plain(text)
            if text is not None:
                param.help = text  # type: ignore[attr-defined]
        if rich:
            self.help, self.epilog = _plain(self.help), _plain(self.epilog)
            self.short_help = _plain(self.short_help)
        # typer prints the panels in the order their first option comes: the shared ones
        # last, in one order for every command (a stable sort: options keep theirs)
        self.params.sort(key=_panel_rank)

    def collect_usage_pieces(self, ctx: Any) -> list[str]:
        pieces = [self.options_metavar] if self.options_metavar else []
        for param in self.get_params(ctx):
            if param.param_type_name != "argument":
                continue  # options are [OPTIONS]
            name = param.metavar or (param.name or "").upper()
            name = name if param.required else f"[{name}]"
            pieces.append(name + ("..." if param.nargs != 1 else ""))
        return pieces


def _panel_rank(param: Any) -> int:
    panel = getattr(param, "rich_help_panel", None)
    return 1 + _LAST.index(panel) if panel in _LAST else 0


def examples(*pairs: tuple[str, str]) -> str:
    """A command's --help epilog: each example is (what it does, the command line). Each
    command line must run as written from the project's root (tests/test_help.py runs
    them). A long one is continued shell-style (`` \\``) so 100 columns do not wrap it."""
    lines = ["Examples:"]
    for said, command in pairs:
        lines.append(f"{said}:")
        line = " "
        for word in command.split(" "):
            if len(line) + len(word) > 94 and line.strip():
                lines.append(line + " \\")
                line = "   "
            line += " " + word
        lines.append(line)
    return "\n".join(lines)


FileArg = Annotated[Path, typer.Argument(help="a URDF or xacro file", show_default=False)]
ArgOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--arg",
        help="xacro argument NAME:=VALUE (repeatable; a bare NAME:=VALUE after FILE is one too)",
        metavar="NAME:=VALUE",
        show_default="the xacro's own",
        rich_help_panel=XACRO,
    ),
]
PackagePathOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--package-path",
        help="where ROS packages live: DIR (scanned for package.xml) or NAME=DIR (repeatable)",
        metavar="DIR|NAME=DIR",
        show_default="AMENT_PREFIX_PATH, ROS_PACKAGE_PATH, the workspace around the file",
        rich_help_panel=XACRO,
    ),
]
UntrustedOpt = Annotated[
    bool,
    typer.Option(
        "--untrusted",
        help="input from people you do not trust (pull-request CI): xacro sees no environment "
        "but --env names and reads no file outside the workspace and resolved packages",
        rich_help_panel=TRUST,
    ),
]
EnvOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--env",
        help="with --untrusted: an environment variable xacro may read (repeatable)",
        metavar="NAME",
        show_default="none",
        rich_help_panel=TRUST,
    ),
]
MaxElementsOpt = Annotated[
    int | None,
    typer.Option(
        "--max-elements",
        min=1,
        help="read descriptions of up to this many XML elements (settings key max-elements)",
        show_default="the settings file's, else 500,000 (60,000 with --untrusted)",
        rich_help_panel=XACRO,
    ),
]
NoCacheOpt = Annotated[
    bool,
    typer.Option(
        "--no-cache",
        help="expand xacro again even when nothing it read has changed (the cache is in "
        "$XDG_CACHE_HOME/sensorkit; never used with --untrusted)",
        rich_help_panel=XACRO,
    ),
]
ConfigOpt = Annotated[
    Path | None,
    typer.Option(
        "--config",
        help="settings file (sensorkit.toml, or pyproject.toml with [tool.sensorkit])",
        metavar="FILE",
        show_default="the nearest one above the robot file",
    ),
]
ColorOpt = Annotated[
    str,
    typer.Option(
        "--color",
        help="auto (on a terminal, unless NO_COLOR is set), always or never",
        metavar="auto|always|never",
        rich_help_panel=OUTPUT,
    ),
]
QuietOpt = Annotated[
    bool,
    typer.Option(
        "--quiet",
        "-q",
        help="print only results and errors: no summary, notes or progress",
        rich_help_panel=OUTPUT,
    ),
]
StdinFilenameOpt = Annotated[
    Path | None,
    typer.Option(
        "--stdin-filename",
        help="with - as the file: the path the text on stdin stands for (messages, relative "
        "includes, packages and the settings file are found from it)",
        metavar="PATH",
        show_default="-",
        rich_help_panel=XACRO,
    ),
]
# intrinsics, export and topics: validate's and render preview's say it their own way
TargetOpt = Annotated[
    str | None,
    typer.Option(
        "--target",
        help="auto, classic, ros1, fortress, harmonic or jetty (auto: detected as validate does)",
        show_default="the settings file's, else auto",
    ),
]
# validate's --bridge and --launch; topics' say "Gazebo Sim: " first
LAUNCH_HELP = (
    "a launch file to read for ros_gz_bridge entries, static transforms, frame_prefix and the "
    "spawned model name (repeatable)"
)
LAUNCH_DEFAULT = "the settings file's launch, else the launch files beside the robot's package"
BRIDGE_HELP = "ros_gz_bridge YAML that carries the robot's gz topics to ROS (repeatable)"
BRIDGE_DEFAULT = "the parameter_bridge YAMLs in the robot package's config/"


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
    parameter("max_elements", MaxElementsOpt),
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
