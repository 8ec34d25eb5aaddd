"""``sensorkit render preview``: look through every sensor in pybullet.

Thin: parse options, call ``sensorkit.render.render_preview``, print. pybullet (and
numpy-heavy rendering code) is imported inside the command, so ``sensorkit validate``
never loads it. Progress goes to stderr; the per-sensor result and the paths written
go to stdout, the verdict last. Exit status: 0; 1 when validate's findings at or above
--fail-on or a failed check say so (the page's header says which); 2 when it could not
run.
"""

from __future__ import annotations

import math
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer
from typer.core import TyperGroup

# typer 0.2x vendors click; older ones depend on it. The type checker reads the installed
# typer's; at run time whichever of the two is there serves.
if TYPE_CHECKING:
    from typer._click.exceptions import UsageError as ClickUsageError
else:
    try:
        from typer._click.exceptions import UsageError as ClickUsageError
    except ImportError:  # pragma: no cover - depends on the installed typer
        from click.exceptions import UsageError as ClickUsageError

from sensorkit.cli.common import (
    RobotFlags,
    collector_off,
    die,
    exit_status,
    fail_on_threshold,
    handle_errors,
    note,
    refuse_stdin,
    settings,
    use_color,
)
from sensorkit.cli.options import (
    OUTPUT,
    RULES,
    ArgOpt,
    ColorOpt,
    Command,
    ConfigOpt,
    EnvOpt,
    FileArg,
    NoCacheOpt,
    PackagePathOpt,
    QuietOpt,
    UntrustedOpt,
    examples,
)

if TYPE_CHECKING:
    from collections.abc import Callable

    from sensorkit.render import PreviewResult


class _RenderGroup(TyperGroup):
    """``sensorkit render robot.urdf`` is a common slip: name the subcommand it needs."""

    def resolve_command(self, ctx: Any, args: list[str]) -> Any:
        try:
            return super().resolve_command(ctx, args)
        except ClickUsageError:
            if args and not args[0].startswith("-"):
                raise ClickUsageError(
                    f"render has no subcommand {args[0]!r}; did you mean: "
                    f"sensorkit render preview {' '.join(args)}",
                    ctx,
                ) from None
            raise


CAR = "examples/orbslam3_car/urdf/orbslam3_car.urdf.xacro"
PREVIEW_EXAMPLES = examples(
    (
        "Look through every sensor; then open car-preview/index.html",
        f"sensorkit render preview -o car-preview {CAR}",
    ),
    (
        "Only the lidar, failing on warnings too (for CI)",
        f"sensorkit render preview -o lidar-preview --sensor lidar --fail-on warning {CAR}",
    ),
)
RENDERING = "Rendering"

render_app = typer.Typer(
    name="render",
    cls=_RenderGroup,
    help="Render the robot's sensors in pybullet (no display needed).",
    epilog=PREVIEW_EXAMPLES,
    no_args_is_help=True,
    add_completion=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)


def parse_joints(items: list[str] | None) -> dict[str, float]:
    """``NAME=VALUE`` items (radians or metres) into a dict; a malformed one is a usage error."""
    out: dict[str, float] = {}
    for item in items or []:
        name, sep, text = item.partition("=")
        name = name.strip()
        if not sep or not name:
            die(f"--joint {item!r}: expected NAME=VALUE (radians or metres)")
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not math.isfinite(value):
            die(f"--joint {item!r}: {text.strip()!r} is not a finite number")
        out[name] = value
    return out


OutOpt = Annotated[
    Path,
    typer.Option(
        "--out",
        "-o",
        "--output",
        help="folder to write; replaced whole at the end (an earlier preview is replaced)",
        rich_help_panel=OUTPUT,
    ),
]
SceneOpt = Annotated[
    Path | None,
    typer.Option(
        "--scene",
        help="a URDF of static objects to use instead of the default room (the ground stays)",
        show_default="a room with textured walls",
        rich_help_panel=RENDERING,
    ),
]
SensorOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--sensor",
        help="only this sensor (repeatable)",
        metavar="NAME",
        show_default="every camera and lidar",
        rich_help_panel=RENDERING,
    ),
]
JointOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--joint",
        help="joint position NAME=VALUE in radians or metres (repeatable)",
        metavar="NAME=VALUE",
        show_default="0 for every joint",
        rich_help_panel=RENDERING,
    ),
]
TargetOpt = Annotated[
    str | None,
    typer.Option(
        "--target",
        help="auto, classic, ros1, fortress, harmonic or jetty (camera_info convention, "
        "frames; auto: detected as validate does)",
        show_default="the settings file's, else auto",
        rich_help_panel=RULES,
    ),
]
MaxPixelsOpt = Annotated[
    int,
    typer.Option(
        "--max-pixels",
        help="most pixels one camera may have",
        show_default="16777216 (4096x4096)",
        rich_help_panel=RENDERING,
    ),
]
MaxRaysOpt = Annotated[
    int,
    typer.Option(
        "--max-rays", help="most rays one lidar may cast per scan", rich_help_panel=RENDERING
    ),
]
MaxTotalPixelsOpt = Annotated[
    int,
    typer.Option(
        "--max-total-pixels",
        help="most pixels of all cameras together; past it the rest are left out, named",
        rich_help_panel=RENDERING,
    ),
]
MaxTotalRaysOpt = Annotated[
    int,
    typer.Option(
        "--max-total-rays",
        help="most rays of all lidars together; past it the rest are left out, named",
        rich_help_panel=RENDERING,
    ),
]
MaxSecondsOpt = Annotated[
    float,
    typer.Option(
        "--max-seconds",
        help="seconds of rendering in all; sensors not started by then are left out, named",
        rich_help_panel=RENDERING,
    ),
]
ForceOpt = Annotated[
    bool,
    typer.Option(
        "--force",
        help="replace a non-empty --out that is not an earlier sensorkit preview",
        rich_help_panel=OUTPUT,
    ),
]
FailOnOpt = Annotated[
    str | None,
    typer.Option(
        "--fail-on",
        help="lowest severity of validate's findings that fails, and of checks (a failed "
        "check is an error, a warned one a warning): error | warning | info | never",
        show_default="the settings file's, else error",
        rich_help_panel=RULES,
    ),
]
ExitZeroOpt = Annotated[
    bool,
    typer.Option(
        "--exit-zero",
        help="exit 0 even when the verdict fails (still 2 when the preview cannot run)",
        rich_help_panel=RULES,
    ),
]


def _check_scene(scene: Path | None) -> None:
    """``--scene`` must name a file (exit 2 otherwise)."""
    if scene is not None and not scene.is_file():
        die(f"--scene {scene}: no such file" if not scene.exists() else f"--scene {scene}: not a file")


@render_app.command("preview", cls=Command, epilog=PREVIEW_EXAMPLES)
@handle_errors
def preview(
    file: FileArg,
    out: OutOpt = Path("sensorkit-preview"),
    scene: SceneOpt = None,
    sensor: SensorOpt = None,
    joint: JointOpt = None,
    arg: ArgOpt = None,
    package_path: PackagePathOpt = None,
    target: TargetOpt = None,
    max_pixels: MaxPixelsOpt = 4096 * 4096,
    max_rays: MaxRaysOpt = 1_000_000,
    max_total_pixels: MaxTotalPixelsOpt = 64 * 1024 * 1024,
    max_total_rays: MaxTotalRaysOpt = 4_000_000,
    max_seconds: MaxSecondsOpt = 120.0,
    force: ForceOpt = False,
    untrusted: UntrustedOpt = False,
    env: EnvOpt = None,
    config: ConfigOpt = None,
    no_cache: NoCacheOpt = False,
    quiet: QuietOpt = False,
    color: ColorOpt = "auto",
    fail_on: FailOnOpt = None,
    exit_zero: ExitZeroOpt = False,
) -> None:
    """Render every camera and cast every lidar of FILE into --out, with checks: a gate.

    Writes images, depth, ranges and camera_info per sensor, plus summary.json,
    overview.png and a self-contained index.html whose header gives the verdict. The
    folder is filled beside --out and swapped in at the end: an interrupted render leaves
    the old one as it was. Exit status 0; 1 when validate finds something at or above
    --fail-on or a check fails; 2 when the preview cannot run.
    """
    refuse_stdin(file, "render preview renders a file")
    colored = use_color(color, sys.stderr)
    st = settings(
        file, RobotFlags(config, arg, package_path, untrusted, env, no_cache), target=target
    )
    threshold = fail_on_threshold(fail_on, st.config)
    st.say_where(() if fail_on else ("fail-on", "select", "ignore"), quiet=quiet)
    joints = parse_joints(joint)
    _check_scene(scene)
    from sensorkit.base.atomic import check_writable_out

    check_writable_out(out)  # before the render, not after it
    log = _progress(colored, quiet)
    # the model, the scene and a lidar's ray results: many small objects (collector_off)
    with collector_off():
        from sensorkit.render import render_preview
        from sensorkit.render.plan import Totals

        # No live spinner: it would run a thread, and cameras render in forked processes.
        result = render_preview(
            file,
            out,
            scene=scene,
            sensors=tuple(sensor or ()),
            joints=joints,
            args=st.args,
            package_paths=st.package_paths,
            target=st.target,
            progress=log,
            workers=min(4, os.cpu_count() or 1),
            max_pixels=max_pixels,
            max_rays=max_rays,
            totals=Totals(max_total_pixels, max_total_rays, max_seconds),
            force=force,
            untrusted=st.untrusted,
            target_origin=st.origin("target"),
            fail_on=threshold,
            select=tuple(st.config.select),
            ignore=tuple(st.config.ignore),
            cache=st.cache,
        )
    _print_result(result, quiet)
    from sensorkit.cli import leave_quickly

    leave_quickly()  # everything is written and pybullet disconnected: skip teardown
    if result.verdict.failed:
        raise typer.Exit(exit_status(1, exit_zero=exit_zero))


def _progress(colored: bool, quiet: bool) -> Callable[[str], None]:
    """Where the progress lines go: with -q nowhere; else stderr, with rich's timestamps
    and colour for people, plain lines for logs."""

    def say(message: str) -> None:
        note(message, quiet)

    if not colored or quiet:
        return say
    from rich.console import Console

    console = Console(
        stderr=True, highlight=False, log_path=False, force_terminal=True, no_color=False
    )

    def log(message: str) -> None:
        console.log(message, markup=False)

    return log


def _print_result(result: PreviewResult, quiet: bool) -> None:
    """Each sensor's status, findings and checks that did not pass, the notes (stderr),
    the index written and the verdict last."""
    from sensorkit.render.gate import found_text

    for s in result.sensors:
        found = found_text(s.findings)
        typer.echo(
            f"{s.name}: {s.status}"
            + (f" ({s.skipped})" if s.skipped else "")
            + (f"; validate: {found}" if found else "")
        )
        for f in s.findings:
            typer.echo(f"  {f.severity.label}: {f.rule} {f.message}")
        for c in s.checks:
            if c.status in ("warn", "fail"):
                typer.echo(f"  {c.status}: {c.name}: {c.message}")
    for said in result.notes:
        note(f"note: {said}", quiet)
    typer.echo(f"wrote {result.files['index']}")
    verdict = result.verdict
    typer.echo(verdict.text)
    for reason in verdict.reasons if verdict.failed else ():
        typer.echo(f"  {reason}")


def register(app: typer.Typer) -> None:
    """Add the ``render`` group to the ``sensorkit`` command."""
    app.add_typer(render_app, name="render")
