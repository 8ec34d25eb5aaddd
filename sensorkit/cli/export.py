"""``sensorkit intrinsics`` and ``sensorkit export``: what the sensors publish, as the
files their consumers read.

Thin: parse options, call :mod:`sensorkit.exporters.robot`, print. Data goes to stdout (the
intrinsics document; the paths written), notes and the summary to stderr.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from sensorkit.base.quote import plural
from sensorkit.cli.common import Reading, handle_errors, note, reads_robot
from sensorkit.cli.options import OUTPUT, Command, FileArg, TargetOpt, examples
from sensorkit.cli.world_models import described_models, export_prefix, intrinsics_of_models

ImuOpt = Annotated[
    str | None,
    typer.Option(
        "--imu",
        help="the IMU for Kalibr's T_cam_imu and the stereo-inertial files",
        metavar="NAME",
        show_default="the first (a note names it when there are several)",
    ),
]


@handle_errors
@reads_robot
def intrinsics(
    file: FileArg,
    sensor: Annotated[
        str | None,
        typer.Option(
            "--sensor",
            help="only this camera (a sensor name, or SENSOR/CAMERA inside a multicamera) "
            "or stereo pair (kalibr and orbslam3 formats print the pair's document)",
            metavar="NAME",
            show_default="every camera",
        ),
    ] = None,
    convention: Annotated[
        str | None,
        typer.Option(
            "--convention",
            help="classic (Gazebo Classic), gz (Gazebo Sim) or ideal (the pixel-centre "
            "pinhole): where cx, cy and the focal length come from",
            show_default="the target's (classic for classic and ros1, else gz)",
        ),
    ] = None,
    fmt: Annotated[
        str,
        typer.Option(
            "--format",
            "-f",
            help="json (every camera), camera-info, orbslam3, orbslam3-v1 (monocular; "
            "stereo for a pair, stereo-inertial with --imu), kalibr or opencv (one camera "
            "or pair each)",
            rich_help_panel=OUTPUT,
        ),
    ] = "json",
    imu: ImuOpt = None,
    target: TargetOpt = None,
    *,
    reading: Reading,
) -> None:
    """Print the camera_info each camera of FILE publishes, for a tool to read.

    Exit status: 0, or 2 when it could not run (unknown camera, no camera, ...).
    """
    from sensorkit.base.errors import UsageError
    from sensorkit.exporters.documents import FORMATS, intrinsics_output

    if fmt not in FORMATS:
        raise UsageError(f"--format {fmt!r}: use " + ", ".join(FORMATS))
    if convention is not None and convention not in ("classic", "gz", "ideal"):
        raise UsageError(f"--convention {convention!r}: use classic, gz or ideal")
    file, infos = described_models(file, reading, target=target, convention=convention)
    if len(infos) == 1:
        text, notes = intrinsics_output(infos[0], sensor, fmt, imu=imu)
    else:  # the models of a world
        text, notes = intrinsics_of_models(infos, sensor, fmt, imu)
    sys.stdout.write(text)
    for said in notes:
        note(f"sensorkit: note: {said}", reading.quiet)


@handle_errors
@reads_robot
def export(
    file: FileArg,
    out: Annotated[
        Path,
        typer.Option(
            "--out",
            "-o",
            "--output",
            help="the folder to create (must be missing or empty)",
            rich_help_panel=OUTPUT,
        ),
    ] = Path("sensorkit-export"),
    force: Annotated[
        bool,
        typer.Option("--force", help="replace --out if it is not empty", rich_help_panel=OUTPUT),
    ] = False,
    imu: ImuOpt = None,
    target: TargetOpt = None,
    *,
    reading: Reading,
) -> None:
    """Write each sensor's config files into one folder per sensor.

    Cameras: camera_info, ORB-SLAM3 (old, v1.0), Kalibr, OpenCV, JSON.
    Stereo pairs (stereo_LEFT_RIGHT/): camera_info left/right, Kalibr camchain,
    ORB-SLAM3 stereo and, with an IMU, stereo-inertial.
    Depth cameras: depthimage_to_laserscan, ORB-SLAM3 RGB-D.
    Lidars: LaserScan, slam_toolbox, Nav2 obstacle layer, AMCL.
    Gazebo Sim: bridge.yaml for ros_gz_bridge.

    Exit status: 0 all written; 1 some files could not be produced
    (why is on stderr, the rest is written); 2 it could not run.
    """
    from sensorkit.exporters.robot import export_files, publish_export

    file, infos = described_models(file, reading, target=target)
    info = infos[0]
    plan = export_files(info, imu=imu)
    several = len(infos) > 1  # a world: each model's files in a folder of its name
    if several:
        plans = [(i, export_files(i, imu=imu)) for i in infos]
        plan.files = {
            f"{export_prefix(i, several)}{k}": v for i, p in plans for k, v in p.files.items()
        }
        plan.notes = [f"{i.robot.name}: {n}" for i, p in plans for n in p.notes]
        plan.skipped = [f"{export_prefix(i, several)}{s}" for i, p in plans for s in p.skipped]
    inputs = [file, *(Path(f) for f in info.robot.document.files)]  # --force must spare them
    written = publish_export(plan.files, out, force=force, inputs=inputs)
    for path in written:
        typer.echo(path.as_posix())
    for said in plan.notes:
        note(f"sensorkit: note: {said}", reading.quiet)
    for skipped in plan.skipped:  # why the exit status is 1: said with -q too
        typer.echo(f"sensorkit: not written: {skipped}", err=True)
    note(
        f"sensorkit: wrote {plural(len(written), 'file')} for "
        f"{plural(sum(len(i.sensors) for i in infos), 'sensor')} of "
        + (
            f"{len(infos)} models ({', '.join(i.robot.name for i in infos)})"
            if several
            else info.robot.name
        )
        + f" into {out} (target {info.target}, {info.target_reason})",
        reading.quiet,
    )
    if plan.skipped:
        raise typer.Exit(1)


CAR = "examples/orbslam3_car/urdf/orbslam3_car.urdf.xacro"
INTRINSICS_EXAMPLES = examples(
    ("Every camera's camera_info, as JSON", f"sensorkit intrinsics {CAR}"),
    ("The ORB-SLAM3 settings of one camera", f"sensorkit intrinsics {CAR} -f orbslam3"),
)
EXPORT_EXAMPLES = examples(
    ("Every sensor's files, one folder per sensor", f"sensorkit export {CAR} -o car-config"),
    (
        "A Gazebo Sim robot's, with its bridge.yaml",
        "sensorkit export -o harmonic-config examples/harmonic_robot/"
        "harmonic_robot_description/urdf/harmonic_robot.urdf.xacro",
    ),
)


def register(app: typer.Typer) -> None:
    """Add ``intrinsics`` and ``export`` to ``app``."""
    app.command("intrinsics", cls=Command, no_args_is_help=True, epilog=INTRINSICS_EXAMPLES)(
        intrinsics
    )
    app.command("export", cls=Command, no_args_is_help=True, epilog=EXPORT_EXAMPLES)(export)
