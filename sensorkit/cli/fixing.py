"""``sensorkit validate --fix | --diff [--unsafe-fixes]``: apply fixes, say what happened.

stdout carries what validate prints after fixing (or, with ``--diff``, only the patch);
stderr says, per finding, what was fixed and why the others were not, then
``fixed N findings (M remain)``. The exit status is validate's on the fixed files.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn

import typer

from sensorkit.base.findings import Finding, Severity
from sensorkit.lint.engine import Options


def _where(f: Finding) -> str:
    return f"{f.file}:{f.line}" if f.line else str(f.file)


def _plural(n: int) -> str:
    return f"{n} finding" if n == 1 else f"{n} findings"


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
        for said in ff.notes:
            f = said.finding
            if said.kind == "unsafe":
                why = f"an unsafe fix ({said.text}) needs --unsafe-fixes"
            elif said.kind == "deferred":
                why = f"waits: {said.text}"
            else:
                why = said.text
            note(f"sensorkit: not fixed {_where(f)} {f.rule}: {why}", quiet)
        if ff.more:
            note(f"sensorkit: {ff.path}: more fixes remain; run --fix again", quiet)
    if diff:
        sys.stdout.write(run.diff())
        for ff in run.files:
            if ff.error:
                typer.echo(f"sensorkit: {ff.error}", err=True)
        note(f"would fix {_plural(run.fixed)} ({run.remaining} would remain)", quiet)
        failed = any(ff.error or ff.internal_errors for ff in run.files)
        bad = threshold is not None and any(
            f.severity >= threshold for ff in run.files for f in ff.after
        )
        raise typer.Exit(exit_status(2 if failed else 1 if bad else 0, exit_zero=exit_zero))
    from sensorkit.lint.fleet import validate_paths
    from sensorkit.lint.report import render

    report = validate_paths(files, options)
    sys.stdout.write(render(report, fmt, color=color, quiet=quiet))
    say_file_errors(report)
    note(f"fixed {_plural(run.fixed)} ({len(report.findings)} remain)", quiet)
    raise typer.Exit(exit_status(report.exit_code(threshold), exit_zero=exit_zero))
