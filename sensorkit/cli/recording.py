"""``sensorkit check-recording BAG FILE``: a recording checked against the description.

Thin: parse options, describe the robot and its topics as ``sensorkit topics`` does, call
:func:`sensorkit.recording.check.check_recording`, print its findings in validate's
formats. rosbags (the extra ````sensorkit-ros[recording]````) is imported only when the command
runs. Findings go to stdout; notes, the summary and the progress bar to stderr.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, TextIO

import typer

from sensorkit.cli.common import (
    Reading,
    exit_status,
    fail_on_threshold,
    handle_errors,
    reads_robot,
    use_color,
)
from sensorkit.cli.options import OUTPUT, Command, FileArg, TargetOpt, examples
from sensorkit.cli.topics import BridgeOpt, LaunchOpt, topic_lists
from sensorkit.cli.validate import FORMAT_HELP, ExitZeroOpt, FailOnOpt
from sensorkit.cli.world_models import described_models

if TYPE_CHECKING:
    from sensorkit.recording.check import RecordingReport

FORMATS = ("text", "json", "sarif", "github")
PROGRESS_AFTER = 2.0  # seconds: a shorter read shows no progress bar

BagArg = Annotated[
    Path,
    typer.Argument(
        help="the recording: a ROS 1 .bag, a rosbag2 folder (sqlite3 or MCAP), or an .mcap "
        "or .db3 file",
        show_default=False,
    ),
]
FormatOpt = Annotated[str, typer.Option("--format", "-f", help=FORMAT_HELP, rich_help_panel=OUTPUT)]

CAR = "examples/orbslam3_car"
EXAMPLES = examples(
    (
        "Check a recording of the example car against its description",
        f"sensorkit check-recording {CAR}/recordings/car_sim.mcap "
        f"{CAR}/urdf/orbslam3_car.urdf.xacro",
    ),
    (
        "The same as annotations for a GitHub workflow",
        f"sensorkit check-recording {CAR}/recordings/car_sim.mcap "
        f"{CAR}/urdf/orbslam3_car.urdf.xacro -f github",
    ),
)


class ProgressBar:
    """A one-line bar on stderr for a read that takes longer than ``PROGRESS_AFTER``
    seconds, on a terminal only; nothing otherwise."""

    def __init__(self, label: str, stream: TextIO | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.label = label
        self.started = time.monotonic()
        self.shown = False
        try:
            self.tty = bool(self.stream.isatty())
        except (AttributeError, ValueError):
            self.tty = False

    def __call__(self, done: int, total: int, what: str) -> None:
        if not self.tty:
            return
        if done >= total:
            if self.shown:
                self.stream.write("\r\x1b[K")
                self.stream.flush()
            return
        if time.monotonic() - self.started < PROGRESS_AFTER:
            return
        width = 24
        filled = width * done // max(total, 1)
        line = f"sensorkit: reading {self.label} [{'#' * filled}{'.' * (width - filled)}] {done}/{total} {what}"
        self.stream.write("\r\x1b[K" + line[:200])
        self.stream.flush()
        self.shown = True


@handle_errors
@reads_robot
def check_recording(
    bag: BagArg,
    file: FileArg,
    fmt: FormatOpt = "text",
    target: TargetOpt = None,
    bridge: BridgeOpt = None,
    launch: LaunchOpt = None,
    fail_on: FailOnOpt = None,
    exit_zero: ExitZeroOpt = False,
    *,
    reading: Reading,
) -> None:
    """Check a recording (BAG) against the robot description (FILE): every topic the
    description predicts is there with its type and frame_id, TF agrees with the joints,
    camera_info, images, scans and clouds are what the sensors publish, and the rates
    are their update_rate.

    Only the index and the first messages of each topic are read, never the whole bag.
    Exit status: 0 no finding at or above --fail-on; 1 there are; 2 it could not run.
    """
    from sensorkit.base.errors import UsageError
    from sensorkit.lint.config import load_config
    from sensorkit.lint.engine import FileReport, Report
    from sensorkit.lint.report import render
    from sensorkit.recording.check import check_recording as check

    if fmt not in FORMATS:
        raise UsageError(f"--format {fmt!r}: use " + ", ".join(FORMATS))
    if str(bag) == "-":
        raise UsageError("BAG: - (stdin) is not a recording; give the path of the bag")
    colored = fmt == "text" and use_color(reading.color)
    file, infos = described_models(file, reading, target=target)
    threshold = fail_on_threshold(fail_on, load_config(file, explicit=reading.flags.config))
    topics = topic_lists(file, infos, bridge, launch, reading)
    bar = ProgressBar(str(bag)) if not reading.quiet else None
    result = check(infos, topics, bag, progress=bar)
    info = infos[0]
    fr = FileReport(
        path=bag,
        findings=result.findings,
        target=info.target,
        target_reason=info.target_reason,
        sensors_checked=sum(len(i.sensors) for i in infos),
    )
    report = Report([fr])
    sys.stdout.write(render(report, fmt, color=colored, quiet=reading.quiet))
    if not reading.quiet:
        _say(result)
    raise typer.Exit(exit_status(report.exit_code(threshold), exit_zero=exit_zero))


def _say(result: RecordingReport) -> None:
    """On stderr: the notes, and what was read of how much."""
    for text in dict.fromkeys(result.notes):
        typer.echo(f"sensorkit: note: {text}", err=True)
    rec = result.recording
    total = sum(rec.counts.values())
    read = sum(s.read for s in rec.samples.values())
    typer.echo(
        f"sensorkit: {rec.path} ({rec.storage}, {rec.duration_ns / 1e9:.1f} s, "
        f"{len(rec.types)} topics, {total} messages): {result.expected} topics predicted; "
        f"read {read} messages and TF ({rec.bytes_read / 1e6:.1f} MB) in {rec.seconds:.2f} s",
        err=True,
    )


def register(app: typer.Typer) -> None:
    """Add ``check-recording`` to ``app``."""
    app.command("check-recording", cls=Command, no_args_is_help=True, epilog=EXAMPLES)(
        check_recording
    )
