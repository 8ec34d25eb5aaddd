"""Every model of an SDF world for ``topics``, ``intrinsics``, ``export`` and ``frames``.

A URDF, xacro or SDF model file holds one robot, and these commands print what they
always did. An SDF ``<world>`` holds several models (``Loaded.robots``): each is
described under the target (``auto`` is detected per model), and the commands cover
each of them: one section, one JSON entry or one export folder per model.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

from sensorkit.cli.common import Reading, settings, stdin_robot, use_color

if TYPE_CHECKING:
    from sensorkit.describe.sensorinfo import RobotInfo

__all__ = [
    "described_models",
    "export_prefix",
    "intrinsics_of_models",
    "models_json",
    "world_name",
]


def described_models(
    file: Path, reading: Reading, *, target: str | None, convention: str | None = None
) -> tuple[Path, list[RobotInfo]]:
    """As ``described_robot``, with every model of a world (one entry for other files)."""
    use_color(reading.color)
    file, overlay = stdin_robot(file, reading.stdin_filename)
    st = settings(file, reading.flags, target=target)
    st.say_where(quiet=reading.quiet)
    return file, st.describe_all(file, overlay, convention)


def world_name(infos: list[RobotInfo]) -> str | None:
    """The world's name when the models come from an SDF world, else None."""
    sdf = infos[0].robot.sdf if infos else None
    if sdf is None or sdf.world is None:
        return None
    return str(sdf.world.get("name", ""))


def models_json(infos: list[RobotInfo], docs: list[str]) -> str:
    """One JSON document for several models: ``{"world": NAME, "models": [DOC, ...]}``,
    each DOC what the command prints for one robot."""
    out = {"world": world_name(infos), "models": [json.loads(d) for d in docs]}
    return json.dumps(out, indent=2, allow_nan=False) + "\n"


def intrinsics_of_models(
    infos: list[RobotInfo], sensor: str | None, fmt: str, imu: str | None
) -> tuple[str, list[str]]:
    """``sensorkit intrinsics`` over a world: each model with a camera that ``sensor``
    names (``MODEL::SENSOR`` picks the model). JSON holds every such model; the other
    formats hold one camera, so they need the choice to fall on one model.

    Raises:
        UsageError: no model has the camera, or several do and the format holds one.
    """
    from sensorkit.base.errors import UsageError
    from sensorkit.exporters.documents import intrinsics_output

    names = [i.robot.name for i in infos]
    chosen = infos
    if sensor is not None and "::" in sensor:
        model, _, sensor = sensor.partition("::")
        chosen = [i for i in infos if i.robot.name == model]
        if not chosen:
            msg = f"--sensor: the world has no model {model!r} (models: {', '.join(names)})"
            raise UsageError(msg)
    got: list[tuple[RobotInfo, str, list[str]]] = []
    first: UsageError | None = None
    for info in chosen:
        try:
            text, notes = intrinsics_output(info, sensor, fmt, imu=imu)
        except UsageError as exc:
            first = first or exc
            continue
        got.append((info, text, notes))
    if not got:
        assert first is not None
        msg = f"no model of the world ({', '.join(names)}) gives that: {first}"
        raise UsageError(msg)
    if len(got) == 1:
        return got[0][1], got[0][2]
    if fmt != "json":
        which = ", ".join(i.robot.name for i, _, _ in got)
        msg = (
            f"cameras in {len(got)} models of the world ({which}): -f {fmt} holds one; "
            "name it with --sensor MODEL::SENSOR, or use -f json"
        )
        raise UsageError(msg)
    notes = [f"{i.robot.name}: {n}" for i, _, ns in got for n in ns]
    return models_json([i for i, _, _ in got], [t for _, t, _ in got]), notes


def export_prefix(info: RobotInfo, several: bool) -> str:
    """The folder a model's export files go into: the model's name in a world of several
    models (names are unique in a world), else none."""
    return f"{info.robot.name}/" if several else ""
