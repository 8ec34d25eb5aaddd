"""``sensorkit validate`` and ``sensorkit rules``."""

from __future__ import annotations

import dataclasses
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, NoReturn

import typer

from sensorkit.cli.common import (
    STDIN,
    RobotFlags,
    collector_off,
    exit_status,
    fail_on_threshold,
    handle_errors,
    launch_files,
    note,
    say_file_errors,
    settings,
    stdin_robots,
    use_color,
)
from sensorkit.cli.options import (
    BRIDGE_DEFAULT,
    BRIDGE_HELP,
    FIXING,
    LAUNCH_DEFAULT,
    LAUNCH_HELP,
    OUTPUT,
    RULES,
    XACRO,
    ArgOpt,
    ColorOpt,
    Command,
    ConfigOpt,
    EnvOpt,
    MaxElementsOpt,
    NoCacheOpt,
    PackagePathOpt,
    QuietOpt,
    StdinFilenameOpt,
    UntrustedOpt,
    examples,
)

if TYPE_CHECKING:
    from sensorkit.lint.engine import Options

_KEPT: list[object] = []  # see validate(): models left for the process exit to drop

FORMAT_HELP = "text (for people), json, sarif (2.1.0) or github (workflow annotations)"

# The rules ``sensorkit.fix`` has a fixer for (a test holds this to its registry): a report
# with none of them never imports the fix layer.
FIXABLE_RULES = frozenset({"SK301", "SK303", "SK502", "SK503", "SK505", "SK601", "SK602"})


def fixability(report: Any, options: Options) -> dict[int, str]:
    """``Options.fixability`` for validate's text and JSON: which findings ``--fix`` would
    fix (``sensorkit.fix.marks``), asked only of a report holding a fixable rule's finding.
    Module level, so ``--jobs`` workers receive it by name."""
    if not any(f.rule in FIXABLE_RULES for f in report.findings):
        return {}
    from sensorkit.fix.marks import fixability as marks

    return marks(report, options)


CAR = "examples/orbslam3_car/urdf/orbslam3_car.urdf.xacro"
VALIDATE_EXAMPLES = examples(
    ("Check a robot", f"sensorkit validate {CAR}"),
    (
        "Show the safe fixes for every robot below a folder, as a diff",
        "sensorkit validate --diff tests/robots/acceptance",
    ),
)
RULES_EXAMPLES = examples(
    ("List every rule", "sensorkit rules"),
    ("Explain one, with a bad and a good example", "sensorkit rules SK502"),
)


def register(app: typer.Typer) -> None:
    app.command("validate", cls=Command, epilog=VALIDATE_EXAMPLES)(validate)
    app.command("rules", cls=Command, epilog=RULES_EXAMPLES)(rules)


PathsArg = Annotated[
    list[Path],
    typer.Argument(
        help="URDF or xacro files, or folders to search for top-level robot descriptions",
        show_default=False,
    ),
]
TargetOpt = Annotated[
    str | None,
    typer.Option(
        "--target",
        help="auto | classic | ros1 | fortress | harmonic | jetty (auto: Gazebo Sim or Classic "
        "from the plugins, ROS 1 for a description written wholly for it)",
        show_default="the settings file's, else auto",
        rich_help_panel=RULES,
    ),
]
FormatOpt = Annotated[str, typer.Option("--format", "-f", help=FORMAT_HELP, rich_help_panel=OUTPUT)]
FailOnOpt = Annotated[
    str | None,
    typer.Option(
        "--fail-on",
        help="lowest severity that fails: error | warning | info | never",
        show_default="the settings file's, else error",
        rich_help_panel=RULES,
    ),
]
SelectOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--select",
        help="only these rules (ids or prefixes, repeatable)",
        show_default="the settings file's, else every rule",
        rich_help_panel=RULES,
    ),
]
IgnoreOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--ignore",
        help="skip these rules (ids or prefixes, repeatable)",
        show_default="the settings file's, else none",
        rich_help_panel=RULES,
    ),
]
TimeoutOpt = Annotated[
    float,
    typer.Option("--timeout", help="seconds one xacro expansion may take", rich_help_panel=XACRO),
]
BridgeOpt = Annotated[
    list[Path] | None,
    typer.Option("--bridge", help=BRIDGE_HELP, show_default=BRIDGE_DEFAULT, rich_help_panel=RULES),
]
LaunchOpt = Annotated[
    list[Path] | None,
    typer.Option("--launch", help=LAUNCH_HELP, show_default=LAUNCH_DEFAULT, rich_help_panel=RULES),
]
FixOpt = Annotated[
    bool,
    typer.Option(
        "--fix", help="apply the safe fixes, then report what remains", rich_help_panel=FIXING
    ),
]
DiffOpt = Annotated[
    bool,
    typer.Option(
        "--diff", help="print the fixes as a unified diff; write nothing", rich_help_panel=FIXING
    ),
]
UnsafeFixesOpt = Annotated[
    bool,
    typer.Option(
        "--unsafe-fixes",
        help="with --fix or --diff: also fixes that change behaviour beyond the finding",
        rich_help_panel=FIXING,
    ),
]
JobsOpt = Annotated[
    int,
    typer.Option(
        "--jobs",
        "-j",
        help="files validated at once, each in a worker process (0: one per CPU core)",
        min=0,
    ),
]
ExitZeroOpt = Annotated[
    bool,
    typer.Option(
        "--exit-zero",
        help="exit 0 even with findings (still 2 when sensorkit cannot run)",
        rich_help_panel=RULES,
    ),
]


@handle_errors
def validate(
    files: PathsArg,
    target: TargetOpt = None,
    fmt: FormatOpt = "text",
    fail_on: FailOnOpt = None,
    select: SelectOpt = None,
    ignore: IgnoreOpt = None,
    arg: ArgOpt = None,
    package_path: PackagePathOpt = None,
    timeout: TimeoutOpt = 60.0,
    bridge: BridgeOpt = None,
    launch: LaunchOpt = None,
    untrusted: UntrustedOpt = False,
    env: EnvOpt = None,
    config: ConfigOpt = None,
    no_cache: NoCacheOpt = False,
    max_elements: MaxElementsOpt = None,
    fix: FixOpt = False,
    diff: DiffOpt = False,
    unsafe_fixes: UnsafeFixesOpt = False,
    jobs: JobsOpt = 1,
    exit_zero: ExitZeroOpt = False,
    quiet: QuietOpt = False,
    color: ColorOpt = "auto",
    stdin_filename: StdinFilenameOpt = None,
) -> None:
    """Check URDF/xacro robots: frames, optical rotations, plugins, topics, masses.

    A folder stands for the robot descriptions below it: *.urdf, *.urdf.xacro and
    *.xacro files that are more than macros, skipping build/, install/, log/, hidden
    folders and folders holding COLCON_IGNORE, in sorted order.

    FILE - reads the robot from stdin (--stdin-filename names it).

    Exit status: 0 nothing at or above --fail-on (or --exit-zero), 1 findings, 2 could
    not run.
    """
    with collector_off():
        from sensorkit.base.errors import UsageError
        from sensorkit.lint.report import FORMATS

        if fmt not in FORMATS:
            raise UsageError(f"--format {fmt!r}: use " + ", ".join(FORMATS))
        colored = fmt == "text" and use_color(color)
        if (fix or diff or unsafe_fixes) and any(str(f) == STDIN for f in files):
            raise UsageError("--fix and --diff edit files: they cannot take - (stdin)")
        files, overlay = stdin_robots(files, stdin_filename)
        flags = RobotFlags(config, arg, package_path, untrusted, env, no_cache, max_elements)
        rules = _Rules(select, ignore, fail_on, launch)
        options = _options(
            files, flags, rules, overlay, target=target, timeout=timeout, bridge=bridge, quiet=quiet
        )
        inputs = _expand_folders(files, quiet=quiet)
        if fmt in ("text", "json"):  # the [*] marks and the JSON "fixable" field
            options = dataclasses.replace(options, fixability=fixability)
        if fix or diff or unsafe_fixes:
            from sensorkit.cli.fixing import run_fix

            run_fix(
                inputs,
                options,
                fmt,
                options.fail_on,
                diff=diff,
                fix=fix,
                unsafe=unsafe_fixes,
                quiet=quiet,
                color=colored,
                exit_zero=exit_zero,
            )
        _check(inputs, options, fmt, jobs=jobs, color=colored, quiet=quiet, exit_zero=exit_zero)


def _check(
    inputs: list[Path],
    options: Options,
    fmt: str,
    *,
    jobs: int,
    color: bool,
    quiet: bool,
    exit_zero: bool,
) -> NoReturn:
    """Validate the robots, print the report (then, on stderr, why a file could not be
    checked) and exit with validate's status."""
    from sensorkit.lint.fleet import validate_paths
    from sensorkit.lint.report import render

    if not jobs:
        from sensorkit.lint.fleet import cpu_count

        jobs = cpu_count()
    # The last model stays referenced until the process ends without teardown: freeing
    # it would only cost time.
    _KEPT.clear()  # one model at most (in-process callers run validate more than once)
    report = validate_paths(inputs, options, jobs=jobs, keep=_KEPT)
    from sensorkit.cli import leave_quickly

    leave_quickly()  # only reading was done: nothing to clean up
    sys.stdout.write(render(report, fmt, color=color, quiet=quiet))
    say_file_errors(report)
    raise typer.Exit(exit_status(report.exit_code(options.fail_on), exit_zero=exit_zero))


@dataclass
class _Rules:
    """--select, --ignore and --fail-on as given: which findings count, and which fail
    (the settings file's, for each one left out)."""

    select: list[str] | None
    ignore: list[str] | None
    fail_on: str | None
    launch: list[Path] | None = None  # --launch (not a rule flag, but taken from the file alike)


def _options(
    files: list[Path],
    flags: RobotFlags,
    rules: _Rules,
    overlay: dict[str, bytes],
    *,
    target: str | None,
    timeout: float,
    bridge: list[Path] | None,
    quiet: bool,
) -> Options:
    """What to check and how: the flags over the settings file found from the first
    robot; one stderr line names what the file gave (not with -q)."""
    from sensorkit.lint.engine import Options

    st = settings(files[0] if files else None, flags, target=target)
    cfg = st.config
    sep = [s for item in (rules.select or []) for s in item.split(",") if s] or cfg.select
    ign = [s for item in (rules.ignore or []) for s in item.split(",") if s] or cfg.ignore
    _refuse_select_all_ignored(sep, ign)
    threshold = fail_on_threshold(rules.fail_on, cfg)
    launch = launch_files(rules.launch, cfg)
    given = (
        ("select", rules.select),
        ("ignore", rules.ignore),
        ("fail-on", rules.fail_on),
        ("launch", rules.launch),
    )
    st.say_where(tuple(k for k, flag in given if not flag), quiet=quiet)
    return Options(
        target=st.target,
        select=tuple(sep),
        ignore=tuple(ign),
        fail_on=threshold,
        args=st.args,
        package_paths=st.package_paths,
        timeout=timeout,
        bridges=tuple(str(b) for b in bridge or ()),
        launch=launch,
        untrusted=st.untrusted,
        target_origin=st.origin("target"),
        overlay=overlay,
        cache=st.cache,
    )


def _refuse_select_all_ignored(select: list[str], ignore: list[str]) -> None:
    """--select whose every rule an --ignore prefix takes away checks nothing, and would
    print "ok: no findings" over any error: refused, naming both."""
    if not select or not ignore:
        return
    covered = [s for s in select if any(s.upper().startswith(i.upper()) for i in ignore)]
    if len(covered) == len(select):
        from sensorkit.cli.common import die

        die(
            f"--ignore {','.join(ignore)} takes away every rule --select {','.join(select)} "
            "chose, so nothing would be checked: drop the --ignore, or --select other rules"
        )


def _expand_folders(items: list[Path], *, quiet: bool = False) -> list[Path]:
    """Files as given; each folder replaced by the robot descriptions found below it."""
    out: list[Path] = []
    for item in items:
        if not item.is_dir():
            out.append(item)
            continue
        from sensorkit.cli.common import die
        from sensorkit.lint.fleet import find_robots
        from sensorkit.loading.document import display_path

        found = find_robots(item)
        where = display_path(item)
        skipped = (
            f" (skipped {len(found.partials)} macro-only xacro file"
            f"{'' if len(found.partials) == 1 else 's'})"
            if found.partials
            else ""
        )
        if not found.files:
            die(
                f"{where}: no robot description (*.urdf, *.xacro, *.sdf, *.world) below it{skipped}"
            )
        n = len(found.files)
        note(
            f"sensorkit: {where}: found {n} robot description{'' if n == 1 else 's'}{skipped}",
            quiet,
        )
        out.extend(found.files)
    return out


@handle_errors
def rules(
    ids: Annotated[
        list[str] | None,
        typer.Argument(help="explain these rules (ids such as SK502)", show_default="all"),
    ] = None,
    fmt: Annotated[
        str, typer.Option("--format", "-f", help="text, json or markdown", rich_help_panel=OUTPUT)
    ] = "text",
    color: ColorOpt = "auto",
) -> None:
    """List every rule (id, severity, fixable, what it checks), or explain the ones named."""
    import json

    from sensorkit.base.errors import UsageError
    from sensorkit.fix import fixable
    from sensorkit.lint.report import rule_table
    from sensorkit.lint.rules import RULES

    if fmt not in ("text", "json", "markdown"):
        raise UsageError(f"--format {fmt!r}: use text, json or markdown")
    colored = fmt == "text" and use_color(color)
    wanted = [i.upper() for i in ids or []]
    unknown = [i for i in wanted if i not in RULES]
    if unknown:
        raise UsageError(
            f"no rule {unknown[0]} (rule ids look like SK502; `sensorkit rules` lists them)"
        )
    if fmt == "markdown" and not wanted:
        sys.stdout.write(rule_table(fixable))
        return
    if fmt == "json":
        from sensorkit.lint.explain import EXAMPLES

        rows = []
        for rid in wanted or sorted(RULES):
            info = RULES[rid]
            row: dict[str, object] = {
                "id": rid,
                "severity": info.severity,
                "title": info.title,
                "existing": info.existing,
                "fixable": fixable(rid),
                "formats": list(info.formats),
            }
            ex = EXAMPLES.get(rid)
            if wanted and ex is not None:
                row.update(why=ex.why, bad=ex.bad, good=ex.good)
            rows.append(row)
        sys.stdout.write(json.dumps(rows, indent=2) + "\n")
        return
    if wanted:
        from sensorkit.lint.explain import explain

        sys.stdout.write("\n".join(explain(rid, fixable(rid)) for rid in wanted))
        return
    styles = {"error": "31", "warning": "33", "info": "36"}
    for rid in sorted(RULES):
        info = RULES[rid]
        sev = f"{info.severity:<13}"
        if colored:  # the first severity's colour (error/warning: red)
            sev = f"\x1b[{styles[info.severity.split('/')[0]]}m{sev}\x1b[0m"
        typer.echo(f"{rid}  {sev} {fixable(rid) or '-':<11} {info.title}", color=colored)
    from sensorkit.base.findings import SEVERITY_CONTRACT

    typer.echo("\nseverity is a promise:")
    for level, promise in sorted(SEVERITY_CONTRACT.items(), reverse=True):
        typer.echo(f"  {level.label:<8} {promise}")
