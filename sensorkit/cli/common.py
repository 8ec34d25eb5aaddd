"""Shared CLI pieces: option aliases, argument parsing, and the one error path."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from functools import wraps
from pathlib import Path
from typing import Annotated, Any, TypeVar

import typer

from sensorkit.errors import SensorkitError

F = TypeVar("F", bound=Callable[..., Any])

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
        "--env", help="with --untrusted: an environment variable xacro may read (repeatable)",
        metavar="NAME",
    ),
]
FilesArg = Annotated[list[Path], typer.Argument(help="URDF or xacro files", show_default=False)]
FileArg = Annotated[Path, typer.Argument(help="a URDF or xacro file", show_default=False)]


def parse_xacro_args(items: list[str] | None) -> dict[str, str]:
    """``NAME:=VALUE`` items into a dict; a malformed one is a usage error."""
    out: dict[str, str] = {}
    for item in items or []:
        name, sep, value = item.partition(":=")
        if not sep or not name:
            die(f"--arg {item!r}: expected NAME:=VALUE")
        out[name] = value
    return out


def make_untrusted(untrusted: bool, env: list[str] | None) -> Any:
    """The ``Untrusted`` setting for ``--untrusted``/``--env``, or None (trusted input)."""
    if env and not untrusted:
        die("--env only means something with --untrusted (trusted input sees the whole environment)")
    if not untrusted:
        return None
    from sensorkit.loading.untrusted import Untrusted

    return Untrusted(env=frozenset(env or ()))


def die(message: str, code: int = 2) -> None:
    """One line on stderr, then exit (the only way sensorkit reports that it cannot run)."""
    typer.echo(f"sensorkit: {message}", err=True)
    raise typer.Exit(code)


def handle_errors(func: F) -> F:
    """Turn SensorkitError (and OSError) into one line and exit status 2."""

    @wraps(func)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return func(*args, **kwargs)
        except (typer.Exit, typer.Abort, SystemExit):
            raise
        except (SensorkitError, OSError) as exc:
            if os.environ.get("SENSORKIT_DEBUG"):
                raise
            typer.echo(f"sensorkit: {exc}", err=True)
            raise typer.Exit(2) from None
        except KeyboardInterrupt:
            typer.echo("sensorkit: interrupted", err=True)
            raise typer.Exit(130) from None

    return wrapper  # type: ignore[return-value]


def stderr_is_tty() -> bool:
    return sys.stderr.isatty()
