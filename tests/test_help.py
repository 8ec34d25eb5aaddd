"""Issue 27, item 4: ``--help`` that teaches. Every command's help, read as a user reads it
(a real ``python -m sensorkit CMD --help`` at 100 columns, without colour): options grouped
into panels, every default shown, two examples that run as written, ``[tool.sensorkit]``
printed rather than taken as Rich markup, and a plain usage line."""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from functools import cache
from pathlib import Path

import pytest
from conftest import ROOT

ADD = ["add-camera", "add-depth-camera", "add-lidar", "add-stereo", "add-imu"]
COMMANDS = [
    "validate", "rules", "new", "intrinsics", "export", "topics", "frames", "lsp", "render",
    "render preview", "check-recording", *ADD,
]  # fmt: skip
# the argument part of each usage line
USAGE = {
    "validate": "[OPTIONS] FILES...",
    "rules": "[OPTIONS] [IDS]...",
    "new": "[OPTIONS] ROBOT.yaml",
    "lsp": "[OPTIONS]",
    "render": "[OPTIONS] COMMAND [ARGS]...",
    "check-recording": "[OPTIONS] BAG FILE",
    **{
        c: "[OPTIONS] FILE"
        for c in ["intrinsics", "export", "topics", "frames", "render preview", *ADD]
    },
}
BOX = re.compile(r"[│╭╮╰╯─]")


@cache
def _help(command: str, columns: int = 100) -> str:
    env = {k: v for k, v in os.environ.items() if k not in ("FORCE_COLOR",)}
    env.update(COLUMNS=str(columns), NO_COLOR="1", TERM="dumb")
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", *command.split(), "--help"],
        capture_output=True,
        text=True,
        env=env,
        timeout=60,
        check=False,
    )
    assert res.returncode == 0 and res.stderr == "", (command, res.stderr)
    return res.stdout


def _panels(text: str) -> dict[str, str]:
    """Each panel's title and its text, boxes drawn out."""
    panels: dict[str, str] = {}
    title = None
    for line in text.splitlines():
        top = re.match(r"\s*╭─ (.+?) ─", line)
        if top:
            title = top[1]
            panels[title] = ""
        elif line.lstrip().startswith("╰"):
            title = None
        elif title is not None:
            panels[title] += BOX.sub(" ", line) + "\n"
    return panels


def _entry(panel: str, option: str) -> str:
    """The whole entry of ``option`` in a panel's text, on one line."""
    lines = panel.splitlines()
    start = re.compile(rf"^\s+(\*\s+)?{re.escape(option)}[\s,]")
    for i, line in enumerate(lines):
        if start.match(line):
            entry = [line]
            for more in lines[i + 1 :]:
                if re.match(r"^ {1,5}\S", more):  # the next entry (wrapped text is indented)
                    break
                entry.append(more)
            return " ".join(" ".join(entry).split())
    raise AssertionError(f"{option} not in panel")


def _examples(text: str) -> list[str]:
    """The example command lines at the end of a help text, continuations joined."""
    assert "Examples:" in text
    tail = text[text.index("Examples:") :].splitlines()[1:]
    commands: list[str] = []
    joined = ""
    for line in (line.strip() for line in tail):
        if joined:
            joined += " " + line
        elif line.startswith("sensorkit "):
            joined = line
        if joined.endswith("\\"):
            joined = joined[:-1].rstrip()
        elif joined:
            commands.append(joined)
            joined = ""
    return commands


def test_every_command_is_here() -> None:
    """A command added later gets its examples and defaults checked too."""
    import typer

    from sensorkit.cli import app

    group = typer.main.get_command(app)
    assert set(group.commands) == {c.split()[0] for c in COMMANDS}  # type: ignore[attr-defined]


@pytest.mark.parametrize("command", COMMANDS)
def test_usage_line_is_plain(command: str) -> None:
    usage = next(line for line in _help(command).splitlines() if "Usage:" in line)
    assert usage.rstrip().endswith(f"sensorkit {command} {USAGE[command]}"), usage
    assert "{" not in usage and "}" not in usage


@pytest.mark.parametrize("command", [c for c in COMMANDS if c not in ("rules", "lsp", "render")])
def test_settings_file_is_named_as_written(command: str) -> None:
    """Rich took ``[tool.sensorkit]`` for a markup tag and printed nothing in its place."""
    text = " ".join(BOX.sub(" ", _help(command)).split())
    assert "pyproject.toml with [tool.sensorkit])" in text
    assert "[default: the nearest one above the robot file]" in text


@pytest.mark.parametrize(
    ("command", "panels"),
    [
        ("validate", {"Rules", "Fixing", "Output", "xacro & packages", "Trust"}),
        ("render preview", {"Rules", "Rendering", "Output", "xacro & packages", "Trust"}),
        ("export", {"Output", "xacro & packages", "Trust"}),
        ("add-camera", {"Mount", "Sensor", "Output", "xacro & packages", "Trust"}),
    ],
)
def test_options_are_grouped(command: str, panels: set[str]) -> None:
    found = _panels(_help(command))
    assert panels <= set(found), found.keys()
    shared = [t for t in found if t in ("Rules", "Fixing", "Output", "xacro & packages", "Trust")]
    order = ["Rules", "Fixing", "Output", "xacro & packages", "Trust"]
    assert shared == [t for t in order if t in shared]  # in one order on every command
    assert list(found)[-len(shared) :] == shared  # after the command's own
    where = {
        "--select": "Rules", "--fail-on": "Rules", "--fix": "Fixing", "--unsafe-fixes": "Fixing",
        "--format": "Output", "--quiet": "Output", "--arg": "xacro & packages",
        "--no-cache": "xacro & packages", "--untrusted": "Trust", "--env": "Trust",
        "--scene": "Rendering", "--out,--output": "Output", "--name": "Mount",
        "--update-rate": "Sensor", "--diff": "Output",
    }  # fmt: skip
    if command == "validate":
        where["--diff"] = "Fixing"  # the fixes as a diff; add-*'s --diff is the add's
    if command.startswith("add-"):
        where["--format"] = "Sensor"  # the camera's pixel format
    placed = 0
    for option, panel in where.items():
        in_panels = [t for t, body in found.items() if re.search(rf"\s{option}[\s,]", body)]
        assert in_panels in ([], [panel]), (option, in_panels)
        placed += len(in_panels)
    assert placed >= 6


def _value_options(command: str) -> list[str]:
    """The options of ``command`` that take a value (flags show no default), but --help."""
    import typer

    from sensorkit.cli import app

    group = typer.main.get_command(app)
    cmd = group
    for word in command.split():
        cmd = cmd.commands[word]  # type: ignore[attr-defined]
    return [
        next(o for o in p.opts if o.startswith("--"))
        for p in cmd.params
        if p.param_type_name == "option" and not p.is_flag and "--help" not in p.opts
    ]


@pytest.mark.parametrize("command", [c for c in COMMANDS if c not in ("lsp", "render")])
def test_every_default_is_shown(command: str) -> None:
    text = _help(command)
    panels = _panels(text)
    for option in _value_options(command):
        owner = [body for body in panels.values() if re.search(rf"\s{option}[\s,]", body)]
        assert owner, option
        entry = _entry(owner[0], option)
        assert "[default: " in entry or "[required]" in entry, entry
        assert "[default: (" not in entry, entry  # typer's (TEXT) for a default given as text


def test_target_auto_is_the_default_said() -> None:
    for command in ("validate", "render preview", "topics"):
        entry = _entry(next(iter(_panels_with(command, "--target"))), "--target")
        assert "[default: the settings file's, else auto]" in entry, entry


def _panels_with(command: str, option: str) -> list[str]:
    return [b for b in _panels(_help(command)).values() if re.search(rf"\s{option}\s", b)]


def test_add_commands_show_the_shipped_macros_defaults() -> None:
    from sensorkit.cli.edit_options import COMMAND_KINDS, MACRO_DEFAULTS
    from sensorkit.edit.kinds import KINDS, read_macro, shipped_macro

    for kind, shown in MACRO_DEFAULTS.items():
        macro = read_macro(shipped_macro(KINDS[kind]), KINDS[kind].macro_name)
        assert macro is not None
        written = {
            p.name: p.default for p in macro.params if p.name not in ("name", "parent", "sim")
        }
        assert shown == written, kind
    assert {k for kinds in COMMAND_KINDS.values() for k in kinds} == set(MACRO_DEFAULTS)
    sensor = _panels(_help("add-camera"))["Sensor"]
    assert "[default: 30]" in _entry(sensor, "--update-rate")
    assert "[default: 0.025 0.09 0.025]" in _entry(sensor, "--size")
    assert "[default: the robot's:" in _entry(sensor, "--sim")  # was swallowed as markup
    lidar = _panels(_help("add-lidar"))["Sensor"]
    assert "[default: 360; with --3d 1800]" in _entry(lidar, "--samples")
    assert "[default: -pi]" in _entry(lidar, "--min-angle")
    imu = _panels(_help("add-imu"))["Sensor"]
    assert "[default: 100]" in _entry(imu, "--update-rate")


def test_every_command_ends_with_two_examples_that_fit_100_columns() -> None:
    for command in COMMANDS:
        narrow, wide = _examples(_help(command)), _examples(_help(command, columns=200))
        assert len(wide) == 2 and narrow == wide, (command, narrow, wide)
        assert all(c.startswith(f"sensorkit {command}") for c in wide), wide


@pytest.fixture(scope="module")
def example_commands() -> list[str]:
    seen: list[str] = []
    for command in COMMANDS:
        seen += [c for c in _examples(_help(command, columns=200)) if c not in seen]
    return seen


def test_examples_run_as_written(example_commands: list[str], tmp_path: Path) -> None:
    """Each example, run from a copy of the project's examples/, macros/ and tests/robots/,
    is a command that runs: it may find something (exit 1), never a usage error (exit 2),
    and reads only files that are there."""
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    shutil.copytree(ROOT / "macros", tmp_path / "macros")
    shutil.copytree(ROOT / "tests" / "robots", tmp_path / "tests" / "robots")
    env = {k: v for k, v in os.environ.items() if k not in ("FORCE_COLOR",)}
    env.update(NO_COLOR="1", XDG_CACHE_HOME=str(tmp_path / "cache"))
    assert len(example_commands) >= 2 * (len(COMMANDS) - 1)  # render and render preview share
    for line in example_commands:
        argv = shlex.split(line)
        res = subprocess.run(
            [sys.executable, "-m", "sensorkit", *argv[1:]],
            cwd=tmp_path,
            env=env,
            stdin=subprocess.DEVNULL,
            capture_output=True,
            text=True,
            timeout=300,
            check=False,
        )
        assert res.returncode in (0, 1), (line, res.returncode, res.stderr[-2000:])
        said = res.stdout + res.stderr
        assert "Traceback" not in said and "no such file" not in said.lower(), (line, said[-2000:])
