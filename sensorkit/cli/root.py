"""The typer application behind ``sensorkit``: built when a command runs (``sensorkit
--version`` never imports typer; see ``sensorkit.cli.main``)."""

from __future__ import annotations

import sys

import typer

from sensorkit import __version__

app = typer.Typer(
    name="sensorkit",
    help="Correct-by-construction sensors for URDF/xacro robots on ROS 2 and Gazebo.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"sensorkit {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", "-V", callback=_version, is_eager=True, help="print the version"
    ),
) -> None:
    """sensorkit: validate, generate and preview robot sensors."""


# Commands whose module alone serves a ``sensorkit COMMAND ...`` process. Typer builds the
# click command of every registered function when the app runs (reading its signature's
# type hints): for ``sensorkit validate`` the other nine cost a fifth of its start-up, and
# for ``sensorkit render preview`` a tenth of a one-camera preview's CPU time.
_ALONE = {"validate": "validate", "rules": "validate", "render": "render", "lsp": "lsp"}


def _alone() -> str | None:
    """The one command module this process needs: ``sensorkit validate ...`` (or
    ``render ...``) run as the sensorkit program (console script or ``python -m sensorkit``); else None (all)."""
    argv = sys.argv
    if len(argv) < 2 or argv[1] not in _ALONE:
        return None
    prog = argv[0].replace("\\", "/")
    name = prog.rsplit("/", 1)[-1]
    if name in ("sensorkit", "sensorkit.exe") or prog.endswith("sensorkit/__main__.py"):
        return _ALONE[argv[1]]
    return None


def _register() -> None:
    import importlib

    alone = _alone()
    for name in (
        (alone,)
        if alone
        else ("validate", "edit", "new", "render", "export", "topics", "frames", "recording", "lsp")
    ):
        try:
            module = importlib.import_module(f"sensorkit.cli.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"sensorkit.cli.{name}":
                raise
            continue
        module.register(app)


_register()
