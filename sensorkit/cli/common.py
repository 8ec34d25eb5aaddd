"""Shared CLI pieces: the settings a command runs with, argument parsing, stdin as the
robot file, colour, and the one error path. The shared options are in ``options``."""

from __future__ import annotations

import inspect
import os
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from functools import wraps
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import typer

from sensorkit.base.errors import SensorkitError
from sensorkit.cli.options import READING, ROBOT_FLAGS, with_parameters

if TYPE_CHECKING:
    from sensorkit.lint.engine import Report

F = TypeVar("F", bound=Callable[..., Any])


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
class RobotFlags:
    """The flags that say how to read the robot (--config, --arg, --package-path,
    --untrusted, --env), as given: ``settings`` merges them over the settings file."""

    config: Path | None = None
    arg: list[str] | None = None
    package_path: list[str] | None = None
    untrusted: bool = False
    env: list[str] | None = None
    no_cache: bool = False
    max_elements: int | None = None


@dataclass
class Settings:
    """What a command runs with: its flags, else the settings file, else the defaults."""

    target: str
    package_paths: tuple[str, ...]
    args: dict[str, str]
    untrusted: Any  # sensorkit.loading.untrusted.Untrusted | None
    config: Any  # sensorkit.lint.config.Config
    used: list[str] = field(default_factory=list)
    # the expansion cache (sensorkit.loading.cache): on disk, unless --no-cache or --untrusted
    cache: Any = None

    def origin(self, key: str) -> str:
        """``--target`` or ``sensorkit.toml``: where the value of ``key`` came from."""
        if key in self.used and self.config.path is not None:
            from sensorkit.loading.document import display_path

            return display_path(self.config.path)
        return f"--{key}"

    def describe(self, file: Path, overlay: dict[str, bytes], convention: Any = None) -> Any:
        """Load ``file`` with these settings and describe its sensors under the target
        (a ``sensorkit.describe.sensorinfo.RobotInfo`` saying where a chosen target came
        from): its robot, the first model of an SDF world."""
        return self.describe_all(file, overlay, convention)[0]

    def describe_all(
        self, file: Path, overlay: dict[str, bytes], convention: Any = None
    ) -> list[Any]:
        """As :meth:`describe`, for every model of an SDF world (one for other files)."""
        from sensorkit.describe.sensorinfo import describe, load_models
        from sensorkit.loading.input_findings import KEEP_ONE

        said: list[Any] = []
        robots = load_models(
            file,
            args=self.args,
            package_paths=self.package_paths,
            untrusted=self.untrusted,
            overlay=overlay,
            cache=self.cache,
            said=said,
        )
        for finding in said:  # e.g. a misspelt xacro arg: said here, as validate reports it
            where = f"{finding.source}: " if finding.source.line is not None else ""
            what = f"; {finding.fix}" if finding.rule == "SK102" and finding.fix else ""
            whole = finding.rule == "SK102" or (finding.fix or "").startswith(KEEP_ONE)
            missing = "" if whole else " (what it holds is not listed)"
            level = "note" if finding.severity.label == "info" else "warning"
            typer.echo(
                f"sensorkit: {level}: {where}{finding.rule}: {finding.message}{what}{missing}",
                err=True,
            )
        infos = []
        for robot in robots:
            info = describe(robot, self.target, convention=convention)
            if self.target != "auto":
                info.target_reason = f"chosen with {self.origin('target')}"
            infos.append(info)
        return infos

    def say_where(self, extra: tuple[str, ...] = (), *, quiet: bool = False) -> None:
        """One stderr line naming the settings taken from the file, if any (not with -q)."""
        said = self.config.describe([*self.used, *extra])
        if said and not quiet:
            typer.echo(f"sensorkit: {said}", err=True)


def settings(
    near: Path | None,
    flags: RobotFlags,
    *,
    target: str | None,
    default_target: str = "auto",
) -> Settings:
    """Merge flags over the settings file found from ``near`` (``--config`` wins)."""
    from sensorkit.lint.config import load_config, package_folder

    cfg = load_config(near, explicit=flags.config)
    trust = make_untrusted(flags.untrusted, flags.env)
    used: list[str] = []
    if target is None:
        target = cfg.target or default_target
        if cfg.target:
            used.append("target")
    for item in flags.package_path or ():
        if not Path(package_folder(item)).expanduser().is_dir():
            die(f"--package-path {item}: no such folder")
    for item in cfg.package_paths:
        if not Path(package_folder(item)).is_dir():
            die(f"{cfg.path}: package-path {item}: no such folder")
    paths = tuple(flags.package_path or ())
    if not paths and cfg.package_paths:
        paths = cfg.confined_package_paths() if trust is not None else tuple(cfg.package_paths)
        used.append("package-path")
    args = dict(cfg.args)
    if cfg.args:
        used.append("args")
    args.update(parse_xacro_args(flags.arg))
    _element_bound(flags, cfg, trust, used)
    return Settings(target, paths, args, trust, cfg, used, expansion_cache(flags, trust))


def _element_bound(flags: RobotFlags, cfg: Any, trust: Any, used: list[str]) -> None:
    """``--max-elements``, else the settings file's ``max-elements`` (which comes with the
    input: under --untrusted it may only lower the bound), for the whole process."""
    from sensorkit.loading.document import MAX_ELEMENTS_UNTRUSTED, set_max_elements

    limit = flags.max_elements
    if limit is None and cfg.max_elements is not None:
        limit = cfg.max_elements if trust is None else min(cfg.max_elements, MAX_ELEMENTS_UNTRUSTED)
        used.append("max-elements")
    set_max_elements(limit)


def expansion_cache(flags: RobotFlags, trust: Any) -> Any:
    """The disk expansion cache a command reads robots through, or None with
    ``--no-cache`` or ``--untrusted`` (an untrusted robot is never cached)."""
    if flags.no_cache or trust is not None:
        return None
    from sensorkit.loading.cache import DiskCache

    cache = DiskCache()
    if not cache.usable() and cache.problem is not None:  # said once, here
        typer.echo(f"sensorkit: expansion cache not used: {cache.problem}", err=True)
    return cache


def robot_flags(values: dict[str, Any]) -> RobotFlags:
    """The values of ``options.ROBOT_FLAGS`` taken out of a command's ``values``."""
    return RobotFlags(**{p.name: values.pop(p.name) for p in ROBOT_FLAGS})


@dataclass
class Reading:
    """The options intrinsics, export and topics end with (``options.READING``), as
    given: how to read the robot, -q, --color and --stdin-filename."""

    flags: RobotFlags
    quiet: bool
    color: str
    stdin_filename: Path | None


def reads_robot(func: Callable[..., None]) -> Callable[..., None]:
    """A command that ends with the options of ``options.READING``: typer sees those in
    place of the function's parameter ``reading``, which gets them as one ``Reading``."""
    signature = inspect.signature(func, eval_str=True)
    own = [p for name, p in signature.parameters.items() if name != "reading"]

    @wraps(func)
    def command(**values: Any) -> None:
        flags = robot_flags(values)
        flags.no_cache = values.pop("no_cache")
        quiet, color, stdin = values.pop("quiet"), values.pop("color"), values.pop("stdin_filename")
        func(**values, reading=Reading(flags, quiet, color, stdin))

    return with_parameters(command, [*own, *READING])


def described_robot(
    file: Path, reading: Reading, *, target: str | None, convention: str | None = None
) -> tuple[Path, Any]:
    """The robot of ``file`` described under its target, as intrinsics, export and topics
    read it: ``-`` is stdin; the settings file found upward from the robot (``--config``
    wins) fills what the flags leave out, and one stderr line names what it gave (not
    with -q). Returns the robot's path and its ``RobotInfo``. ``--color`` is checked;
    nothing these commands print is coloured."""
    use_color(reading.color)
    file, overlay = stdin_robot(file, reading.stdin_filename)
    st = settings(file, reading.flags, target=target)
    st.say_where(quiet=reading.quiet)
    return file, st.describe(file, overlay, convention)


def target_simulator(target: str) -> dict[str, str]:
    """The macro ``sim`` (and ``gz_version``) a settings file's target stands for."""
    from sensorkit.model.targets import is_gz

    if is_gz(target):
        return {"sim": "gz", "gz_version": target}
    return {"sim": "classic"}


def launch_files(given: list[Path] | None, cfg: Any) -> tuple[str, ...]:
    """``--launch`` files, else the settings file's ``launch`` (each must exist)."""
    for item in given or ():
        if not item.is_file():
            die(f"--launch {item}: no such file")
    if given:
        return tuple(str(p) for p in given)
    for item in cfg.launch:
        if not Path(item).is_file():
            die(f"{cfg.path}: launch {item}: no such file")
    return tuple(cfg.launch)


def fail_on_threshold(flag: str | None, cfg: Any) -> Any:
    """``--fail-on``, else the settings file's ``fail-on``, else error, as a Severity;
    ``never`` (no finding fails; a file that cannot be checked still does) is None. The
    settings file is shared by validate and render preview, so both take every value.
    A bad value is a usage error naming where it came from."""
    from sensorkit.base.errors import UsageError
    from sensorkit.base.findings import Severity

    text = flag or cfg.fail_on or "error"
    where = "--fail-on" if flag else f"{cfg.path}: fail-on"
    if text.strip().lower() == "never":
        return None
    try:
        return Severity.parse(text)
    except ValueError as exc:
        msg = f"{where}: {exc} (or never)"
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


COLOR_CHOICES = ("auto", "always", "never")


def use_color(choice: str, stream: Any = None) -> bool:
    """Whether to colour what goes to ``stream`` (default stdout) for ``--color CHOICE``.

    ``always`` and ``never`` win over the environment (as ruff and cargo do). ``auto``
    colours a terminal only: no colour when ``NO_COLOR`` is set to anything non-empty
    (https://no-color.org) or ``TERM=dumb``; ``FORCE_COLOR`` (non-empty) colours a pipe too.
    """
    if choice not in COLOR_CHOICES:
        die(f"--color {choice!r}: use auto, always or never")
    if choice != "auto":
        return choice == "always"
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    if os.environ.get("TERM") == "dumb":
        return False
    out = sys.stdout if stream is None else stream
    try:
        return bool(out.isatty())
    except (AttributeError, ValueError):  # a closed or replaced stream
        return False


def exit_status(code: int, *, exit_zero: bool) -> int:
    """``--exit-zero``: findings (1) become 0; could-not-run (2) stays."""
    return 0 if exit_zero and code == 1 else code


def say_file_errors(report: Report) -> None:
    """On stderr, why each file that could not be checked was not, and each internal error."""
    for fr in report.files:
        if fr.error:
            typer.echo(f"sensorkit: {fr.error}", err=True)
        for err in fr.internal_errors:
            typer.echo(f"sensorkit: internal error: {err}", err=True)


STDIN = "-"
STDIN_NAME = "<stdin>"


def stdin_robot(path: Path, stdin_filename: Path | None) -> tuple[Path, dict[str, bytes]]:
    """``-`` as the robot file: the path it stands for and ``{abspath: bytes}`` to read
    instead of that file (``sensorkit.loading`` takes it as ``overlay``).

    The path is ``--stdin-filename`` (messages name it; relative includes, packages and
    the settings file are found from it), else ``<stdin>`` in the working folder. At most
    ``MAX_FILE_BYTES`` are read, as from a file. Another path comes back as it is.
    """
    if str(path) != STDIN:
        if stdin_filename is not None:
            die("--stdin-filename only means something with - (stdin) as the robot file")
        return path, {}
    from sensorkit.loading.document import MAX_FILE_BYTES

    if stdin_filename is not None and stdin_filename.is_dir():
        die(f"--stdin-filename {stdin_filename}: is a folder; name the file the text stands for")
    if sys.stdin is None:
        die("-: there is no stdin to read the robot from")
    data = sys.stdin.buffer.read(MAX_FILE_BYTES + 1)
    if len(data) > MAX_FILE_BYTES:
        die(f"-: stdin holds more than the {MAX_FILE_BYTES} bytes sensorkit reads")
    name = stdin_filename if stdin_filename is not None else Path(STDIN_NAME)
    return name, {os.path.abspath(name): data}


def stdin_robots(
    paths: list[Path], stdin_filename: Path | None
) -> tuple[list[Path], dict[str, bytes]]:
    """``stdin_robot`` for a list of files, where ``-`` may appear once."""
    if sum(1 for p in paths if str(p) == STDIN) > 1:
        die("- (stdin) given twice: stdin holds one robot")
    if stdin_filename is not None and not any(str(p) == STDIN for p in paths):
        die("--stdin-filename only means something with - (stdin) as the robot file")
    out: list[Path] = []
    overlay: dict[str, bytes] = {}
    for p in paths:
        name, data = stdin_robot(p, stdin_filename)
        out.append(name)
        overlay.update(data)
    return out, overlay


def refuse_stdin(path: Path, why: str) -> None:
    """A usage error for ``-`` where the command needs a file on disk."""
    if str(path) == STDIN:
        die(f"- (stdin): {why}; give the path of the file")


def note(message: str, quiet: bool = False) -> None:
    """A line on stderr that ``--quiet`` drops (notes, progress, summaries)."""
    if not quiet:
        typer.echo(message, err=True)


@contextmanager
def collector_off() -> Iterator[None]:
    """The cyclic collector off while a command builds its model: tens of thousands of
    small objects, built once and acyclic or freed by reference counting, which the
    collector would only walk again and again.

    Afterwards, in the sensorkit program (which ends with the command) what was built is
    frozen before the collector comes back on, or the first allocation would start a
    collection that walks all of it (64 ms after an add on 10k links). A caller running
    the command in its own process (typer's CliRunner, a script) gets its collector back
    as it was, with nothing frozen: frozen objects would never be freed.
    """
    import gc

    from sensorkit.cli import in_program

    collecting = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if collecting:
            if in_program():
                gc.freeze()
            gc.enable()
