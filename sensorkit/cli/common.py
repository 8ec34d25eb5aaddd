"""Shared CLI pieces: option aliases, argument parsing, and the one error path."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
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
        "--env",
        help="with --untrusted: an environment variable xacro may read (repeatable)",
        metavar="NAME",
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
FailOnOpt = Annotated[
    str | None,
    typer.Option(
        "--fail-on",
        help="lowest severity that fails: error | warning | info (default: the settings "
        "file's, else error)",
        show_default=False,
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
        die(
            "--env only means something with --untrusted (trusted input sees the whole environment)"
        )
    if not untrusted:
        return None
    from sensorkit.loading.untrusted import Untrusted

    return Untrusted(env=frozenset(env or ()))


@dataclass
class Settings:
    """What a command runs with: its flags, else the settings file, else the defaults."""

    target: str
    package_paths: tuple[str, ...]
    args: dict[str, str]
    untrusted: Any  # sensorkit.loading.untrusted.Untrusted | None
    config: Any  # sensorkit.config.Config
    used: list[str] = field(default_factory=list)

    def origin(self, key: str) -> str:
        """``--target`` or ``sensorkit.toml``: where the value of ``key`` came from."""
        if key in self.used and self.config.path is not None:
            from sensorkit.loading.document import display_path

            return display_path(self.config.path)
        return f"--{key}"

    def say_where(self, extra: tuple[str, ...] = ()) -> None:
        """One stderr line naming the settings taken from the file, if any."""
        note = self.config.describe([*self.used, *extra])
        if note:
            typer.echo(f"sensorkit: {note}", err=True)


def settings(
    near: Path | None,
    *,
    config: Path | None,
    target: str | None,
    package_path: list[str] | None,
    arg: list[str] | None,
    untrusted: bool = False,
    env: list[str] | None = None,
    default_target: str = "auto",
) -> Settings:
    """Merge flags over the settings file found from ``near`` (``--config`` wins)."""
    from sensorkit.config import load_config

    cfg = load_config(near, explicit=config)
    trust = make_untrusted(untrusted, env)
    used: list[str] = []
    if target is None:
        target = cfg.target or default_target
        if cfg.target:
            used.append("target")
    for item in package_path or ():
        name, sep, folder = item.partition("=")
        folder = folder if sep and name and "/" not in name else item
        if not Path(folder).expanduser().is_dir():
            die(f"--package-path {item}: no such folder")
    for item in cfg.package_paths:
        name, sep, folder = item.partition("=")
        folder = folder if sep and name and "/" not in name else item
        if not Path(folder).is_dir():
            die(f"{cfg.path}: package-path {item}: no such folder")
    paths = tuple(package_path or ())
    if not paths and cfg.package_paths:
        paths = cfg.confined_package_paths() if trust is not None else tuple(cfg.package_paths)
        used.append("package-path")
    args = dict(cfg.args)
    if cfg.args:
        used.append("args")
    args.update(parse_xacro_args(arg))
    return Settings(target, paths, args, trust, cfg, used)


def fail_on_threshold(flag: str | None, cfg: Any, *, never: bool = False) -> Any:
    """``--fail-on``, else the settings file's ``fail-on``, else error, as a Severity;
    with ``never`` allowed (render preview), ``never`` is None. A bad value is a usage
    error naming where it came from."""
    from sensorkit.errors import UsageError
    from sensorkit.findings import Severity

    text = flag or cfg.fail_on or "error"
    where = "--fail-on" if flag else f"{cfg.path}: fail-on"
    if never and text.strip().lower() == "never":
        return None
    try:
        return Severity.parse(text)
    except ValueError as exc:
        msg = f"{where}: {exc}" + (" (or never)" if never else "")
        raise UsageError(msg) from None


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
