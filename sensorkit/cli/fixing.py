"""``sensorkit validate --fix | --diff [--unsafe-fixes]``: apply fixes, say what happened.

stdout carries what validate prints after fixing (or, with ``--diff``, only the patch);
stderr says, per finding, what was fixed and, for every finding left, why: no fixer for
its rule, an unsafe fix that needs ``--unsafe-fixes``, or the fixer's own reason for
refusing; then ``fixed N findings (M remain)``. The exit status of ``--fix`` is
validate's on the fixed files; ``--diff`` exits 1 when it would change a file, 0 when it
would change nothing (2 when a file could not be checked), as ``ruff check --diff`` does.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NoReturn

import typer

from sensorkit.base.findings import Finding, Severity
from sensorkit.lint.engine import Options


def _where(f: Finding) -> str:
    return f"{f.file}:{f.line}" if f.line else str(f.file)


def _plural(n: int) -> str:
    return f"{n} finding" if n == 1 else f"{n} findings"


def _say_left(ff: Any, quiet: bool) -> None:
    """One stderr line per finding the fix left, saying why: the fixer's note (unsafe,
    waiting, refused with its reason), else that its rule has no fixer."""
    from sensorkit.cli.common import note
    from sensorkit.fix import FIXERS

    said: set[tuple[object, ...]] = set()
    for n in ff.notes:
        f = n.finding
        if n.kind == "unsafe":
            why = f"an unsafe fix ({n.text}) needs --unsafe-fixes"
        elif n.kind == "deferred":
            why = f"waits: {n.text}"
        else:
            why = n.text
        said.add((f.rule, f.file, f.line, f.message))
        note(f"sensorkit: not fixed {_where(f)} {f.rule}: {why}", quiet)
    revealed = {(f.rule, f.file, f.line, f.message) for f in ff.revealed}
    for f in ff.after:
        key = (f.rule, f.file, f.line, f.message)
        if key in said or key in revealed:
            continue
        said.add(key)
        why = (
            "the fixer found nothing it may change"
            if f.rule in FIXERS
            else "no automatic fix for this rule (its fix: line says what to change)"
        )
        note(f"sensorkit: not fixed {_where(f)} {f.rule}: {why}", quiet)


def run_fix(
    files: Sequence[Path],
    options: Options,
    fmt: str,
    threshold: Severity | None,
    *,
    diff: bool,
    fix: bool,
    unsafe: bool,
    quiet: bool = False,
    color: bool = False,
    exit_zero: bool = False,
) -> NoReturn:
    from sensorkit.base.errors import UsageError

    if unsafe and not (fix or diff):
        raise UsageError("--unsafe-fixes only means something with --fix or --diff")
    from sensorkit.cli.common import exit_status, note, say_file_errors
    from sensorkit.fix.apply import fix_paths

    run = fix_paths(files, options, unsafe=unsafe, write=not diff)
    verb = "would fix" if diff else "fixed"
    for ff in run.files:
        for fx in ff.applied:
            f = fx.finding
            note(f"sensorkit: {verb} {_where(f)} {f.rule}: {fx.title}", quiet)
        for f in ff.revealed:
            note(
                f"sensorkit: {_where(f)} {f.rule} shows now that the plugin loads "
                f"(it was folded into SK601): {' '.join(f.message.split())}",
                quiet,
            )
        _say_left(ff, quiet)
        if ff.more:
            note(f"sensorkit: {ff.path}: more fixes remain; run --fix again", quiet)
    if diff:
        sys.stdout.write(run.diff())
        for ff in run.files:
            if ff.error:
                typer.echo(f"sensorkit: {ff.error}", err=True)
        note(f"would fix {_plural(run.fixed)} ({run.remaining} would remain)", quiet)
        failed = any(ff.error or ff.internal_errors for ff in run.files)
        would_change = bool(run.changed())
        raise typer.Exit(
            exit_status(2 if failed else 1 if would_change else 0, exit_zero=exit_zero)
        )
    from sensorkit.lint.fleet import validate_paths
    from sensorkit.lint.report import render

    report = validate_paths(files, options)
    sys.stdout.write(render(report, fmt, color=color, quiet=quiet))
    say_file_errors(report)
    note(f"fixed {_plural(run.fixed)} ({len(report.findings)} remain)", quiet)
    raise typer.Exit(exit_status(report.exit_code(threshold), exit_zero=exit_zero))
