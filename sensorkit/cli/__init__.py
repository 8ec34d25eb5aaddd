"""The ``sensorkit`` command. Thin: each command parses options, calls one library
function and formats its result. Command groups live in their own modules, each with a
``register(app)``; heavy imports (pybullet, ...) stay inside the command functions so
``sensorkit validate`` starts fast."""

from __future__ import annotations

import os
import sys

from sensorkit import __version__

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (``--version``)
if TYPE_CHECKING:
    from typing import Any

# sensorkit's numpy work is small (4x4 transforms, one image at a time): OpenBLAS's thread
# pool only burns CPU at start-up. Set before anything imports numpy; the user's value wins.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def __getattr__(name: str) -> Any:
    """``app``, the typer application, built on first use (``sensorkit.cli.root``)."""
    if name == "app":
        from sensorkit.cli.root import app

        globals()["app"] = app
        return app
    msg = f"module {__name__!r} has no attribute {name!r}"
    raise AttributeError(msg)


def _app() -> Any:
    """The typer application (``app``, as a caller may have replaced it)."""
    return globals().get("app") or __getattr__("app")


_XACRO_ARG = r"^[A-Za-z_][A-Za-z0-9_]*:="  # compiled on first use: only for NAME:=VALUE


def _xacro_arg(token: str) -> bool:
    import re  # loaded by the console script already; not by ``python -m sensorkit``

    return re.match(_XACRO_ARG, token) is not None


def xacro_args_as_options(argv: list[str]) -> list[str]:
    """``robot.xacro name:=value`` as ``xacro`` and ``ros2 launch`` take it: each bare
    ``NAME:=VALUE`` becomes ``--arg NAME:=VALUE`` (a value already after ``--arg`` stays)."""
    out: list[str] = []
    for i, token in enumerate(argv):
        if ":=" in token and _xacro_arg(token) and (i == 0 or argv[i - 1] != "--arg"):
            out += ["--arg", token]
        else:
            out.append(token)
    return out


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _is_option(token: str) -> bool:
    """``--x``/``-x``: not ``-`` (stdin) and not a negative number."""
    return token.startswith("-") and len(token) > 1 and not _is_number(token)


def _value_counts(argv: list[str]) -> dict[str, int]:
    """The options of the command ``argv`` names that take values, with how many."""
    import typer.main

    cmd: object = typer.main.get_command(_app())
    for token in argv:
        sub = getattr(cmd, "commands", {}).get(token)
        if sub is None:
            break
        cmd = sub
    counts: dict[str, int] = {}
    for p in getattr(cmd, "params", []):
        if p.param_type_name == "option" and not p.is_flag and not p.count:
            counts.update(dict.fromkeys(p.opts, p.nargs))
    return counts


def _suspect(argv: list[str]) -> bool:
    """An option followed by another, with nothing or only numbers between (the values of
    ``--xyz``, ``--rpy``, ``--size``): what needs the command's options looked up."""
    last = None
    for i, token in enumerate(argv):
        if _is_option(token):
            if last is not None and all(_is_number(t) for t in argv[last + 1 : i]):
                return True
            last = i
        elif not _is_number(token):
            last = None
    return False


def option_eats_option(argv: list[str]) -> str | None:
    """The one-line error for an option whose value is the next option (``--target --fix``,
    ``--xyz 0.2 0 --diff``): click would take ``--fix`` as the value and call it an unknown
    target, or "not a valid float"; the user left a value out. None when every value is a
    value (``-0.5`` is a number, ``-`` is stdin). The command's options are looked up only
    when an option is followed by one."""
    if "--" in argv:
        argv = argv[: argv.index("--")]
    if not _suspect(argv):
        return None
    counts = _value_counts(argv)
    for i, token in enumerate(argv):
        n = counts.get(token)
        if not n:
            continue
        for got in argv[i + 1 : i + 1 + n]:
            if _is_option(got):
                need = "a value" if n == 1 else f"{n} values"
                return f"{token} needs {need}; got {got!r}, an option"
    return None


def main() -> None:
    """Console entry point.

    A command that has finished all its writes may call ``leave_quickly()``: its exit then
    skips the interpreter's teardown (freeing a large model costs a tenth of a second for
    nothing). Output streams are flushed first; nothing else is pending by then.

    A reader that stops early (``sensorkit rules | head -1``) ends the process quietly as
    it ends ``cat`` or ``grep``: SIGPIPE keeps its default action (Python ignores it and
    raises BrokenPipeError instead, which would print "Broken pipe" and exit 2), so the
    shell reports status 141 and prints nothing.
    """
    global _program  # noqa: PLW0603 (one process-wide switch)
    _program = True
    if sys.argv[1:] in (["--version"], ["-V"]):  # typer and the engine never load
        sys.stdout.write(f"sensorkit {__version__}\n")
        sys.stdout.flush()
        raise SystemExit(0)
    import signal  # imported by the interpreter already: no start-up cost

    if hasattr(signal, "SIGPIPE"):  # not on Windows
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    sys.argv[1:] = xacro_args_as_options(sys.argv[1:])
    eaten = option_eats_option(sys.argv[1:])
    if eaten:
        sys.stderr.write(f"sensorkit: {eaten}\n")
        raise SystemExit(2)
    try:
        code = run_app()
    except SystemExit as exc:
        if not _quick_exit:
            raise
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    if _quick_exit:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    raise SystemExit(code)


def _click_exceptions() -> Any:
    """The click exceptions typer raises: its own copy of click (typer >= 0.16 vendors it
    as ``typer._click``), else click."""
    try:
        from typer._click import exceptions
    except ImportError:  # an older typer, on click itself
        from click import exceptions  # type: ignore[no-redef]
    return exceptions


def _abort_type() -> type[BaseException]:
    """click's Abort as typer raises it: typer >= 0.16 keeps it in ``typer.exceptions``
    (its vendored click has none in ``typer._click.exceptions``: looking it up there
    turned any other exception into an AttributeError traceback), else click's."""
    try:
        from typer.exceptions import Abort
    except ImportError:  # an older typer, on click itself
        from click.exceptions import Abort  # type: ignore[assignment]
    return Abort


def run_app() -> int:
    """Run the command; its exit status. A usage error (an unknown option or command, a
    bad or missing value) is one line on stderr, exit status 2, as every other error of
    sensorkit's is (click draws a usage line, a hint and a box around the message: five
    lines); running a group without a command still prints its help."""
    app = _app()
    exceptions = _click_exceptions()
    try:
        code = app(standalone_mode=False)
    except exceptions.NoArgsIsHelpError as exc:
        from typer import rich_utils

        rich_utils.rich_format_error(exc)
        return 2
    except exceptions.ClickException as exc:
        sys.stderr.write(usage_line(exc) + "\n")
        return int(exc.exit_code)
    except _abort_type():
        sys.stderr.write("sensorkit: aborted\n")
        return 1
    return code if isinstance(code, int) else 0


def usage_line(exc: Any) -> str:
    """``sensorkit: validate: Missing argument 'files' (see 'sensorkit validate -h')``"""
    message = " ".join(exc.format_message().split()).rstrip(".")
    ctx = getattr(exc, "ctx", None)
    if ctx is None:
        return f"sensorkit: {message}"
    names = []
    while ctx.parent is not None:  # the command's words below the program's
        names.append(ctx.info_name)
        ctx = ctx.parent
    where = " ".join(reversed(names))
    where = f"{where}: " if where else ""
    return f"sensorkit: {where}{message} (see '{exc.ctx.command_path} -h')"


_quick_exit = False
_program = False


def in_program() -> bool:
    """True when this process is the ``sensorkit`` program (``main()`` runs the command),
    which ends when the command does; False for a caller running a command in its own
    process (typer's CliRunner, a script), whose objects outlive the command."""
    return _program


def leave_quickly() -> None:
    """Let ``main()`` end the process without teardown (see its docstring)."""
    global _quick_exit  # noqa: PLW0603 (one process-wide switch)
    _quick_exit = True
