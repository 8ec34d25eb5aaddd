"""The last step of a preview: validate's findings, the overview, the files.

Once every sensor is rendered: ``run_validate`` runs validate on the robot the preview
loaded (read once, for both), ``share_findings`` gives each sensor's record the findings
about it, and ``write_preview`` draws overview.png and the robot's own pictures (close
up, stereo pairs) and writes summary.json and index.html (``sensorkit.render.report``).
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np

from sensorkit.render.result import PreviewResult, SensorPreview
from sensorkit.render.session import Progress, Session, say

if TYPE_CHECKING:
    from pathlib import Path

    from sensorkit.base.findings import Finding
    from sensorkit.model import Loaded
    from sensorkit.render.overview import SensorDrawing
    from sensorkit.render.overview_figure import FrameLabel
    from sensorkit.render.scene import Shape
    from sensorkit.render.svg import Figure

__all__ = ["frame_labels", "run_validate", "share_findings", "write_preview"]


def run_validate(
    path: Path,
    loaded: Loaded,
    target: str,
    args: Mapping[str, str],
    package_paths: Sequence[str],
    select: Sequence[str] = (),
    ignore: Sequence[str] = (),
) -> tuple[list[Finding] | None, str | None]:
    """validate's findings on the robot the preview loaded from ``path`` (``loaded``:
    read once, for both)."""
    try:
        from sensorkit.lint.engine import Options, validate_loaded
    except ImportError as exc:
        return None, f"validate is not available ({exc})"
    options = Options(
        target=target,
        args=dict(args),
        package_paths=tuple(package_paths),
        select=tuple(select),
        ignore=tuple(ignore),
    )
    report = validate_loaded(path, loaded, options)
    if report.error:
        return None, report.error
    return list(report.findings), None


def share_findings(findings: list[Finding] | None, previews: list[SensorPreview]) -> None:
    """Give each sensor's record validate's findings about it."""
    from sensorkit.render.gate import sensor_findings

    for p in previews:
        p.findings = sensor_findings(findings, p.sensor)


def write_preview(
    result: PreviewResult,
    run: Session,
    robot_shapes: list[Shape],
    robot_boxes: list[tuple[np.ndarray, np.ndarray]],
    drawings: list[SensorDrawing],
    reach: float,
    started: float,
    progress: Progress | None,
) -> None:
    """overview.png (the scene, ``reach``: how far the robot reaches from its root), the
    robot's pictures, summary.json and index.html, into ``result.out_dir``; the seconds
    taken since ``started``."""
    from sensorkit.render.overview import draw_overview
    from sensorkit.render.overview_figure import overview_figure
    from sensorkit.render.png import write_png
    from sensorkit.render.report import write_index, write_summary

    stage = result.out_dir
    say(progress, "writing overview, summary and index")
    half = max(run.scene.half_extent, reach + 0.5) + 0.3
    overview = draw_overview(run.scene.shapes, robot_shapes, robot_boxes, drawings, half)
    result.files["overview"] = stage / "overview.png"
    png = write_png(result.files["overview"], overview)
    result.figures.append(
        overview_figure(
            png, overview.shape[1], half, frame_labels(result.sensors), run.scene.markers, drawings
        )
    )
    result.figures += _robot_figures(run, result.sensors, robot_boxes, robot_shapes, result.notes)
    result.seconds = time.perf_counter() - started
    result.files["summary"] = stage / "summary.json"
    result.files["index"] = stage / "index.html"
    write_summary(result)
    write_index(result)


def frame_labels(previews: list[SensorPreview]) -> list[FrameLabel]:
    """Each placed sensor's name, the frame its data is stamped with (its link when it
    publishes nothing), its colour and where it is, for the overview."""
    from sensorkit.render.overview_figure import FrameLabel

    out = []
    for p in previews:
        frames = p.info.get("frames", {})
        pose = frames.get("render_pose")
        if pose is None:
            continue
        frame = frames.get("published_frame") or p.link or "?"
        origin = np.array(pose["matrix"], dtype=np.float64)[:3, 3]
        out.append(FrameLabel(p.name, str(frame), p.info.get("colour", "#555555"), origin))
    return out


def _robot_figures(
    run: Session,
    previews: list[SensorPreview],
    boxes: list[tuple[np.ndarray, np.ndarray]],
    robot_shapes: list[Shape],
    notes: list[str],
) -> list[Figure]:
    """The robot close up with every sensor's mount, and each stereo pair side by side."""
    from sensorkit.base.errors import SensorkitError
    from sensorkit.describe.sensorinfo import describe
    from sensorkit.render.mount_pictures import Mount, closeup_figure, stereo_figure
    from sensorkit.render.png import read_png

    mounts = []
    for p in previews:
        pose = p.info.get("frames", {}).get("render_pose")
        if pose is not None:
            mounts.append(
                Mount(p.name, p.info.get("colour", "#000000"), np.array(pose["matrix"]), p.link)
            )
    figures = [
        closeup_figure(
            boxes,
            [s.outline() for s in robot_shapes],
            [T[:3, 3] for T in run.poses.values()],
            mounts,
        )
    ]
    try:
        pairs = describe(run.robot, run.target).stereo_pairs
    except (SensorkitError, ValueError, ArithmeticError) as exc:  # a picture never stops a render
        notes.append(f"stereo pairs: not drawn ({exc})")
        return figures
    by_name = {p.name: p for p in previews}
    for pair in pairs:
        left, right = by_name.get(pair.left.id), by_name.get(pair.right.id)
        if left is None or right is None or "rgb" not in left.files or "rgb" not in right.files:
            continue
        left_png = left.files["rgb"].read_bytes()
        h, w = read_png(left_png).shape[:2]
        figures.append(
            stereo_figure(
                pair.name,
                left.name,
                right.name,
                left_png,
                right.files["rgb"].read_bytes(),
                (w, h),
                pair.baseline,
                pair.T_left_right[:3, 3],
                pair.rectified,
                pair.how,
            )
        )
    return figures
