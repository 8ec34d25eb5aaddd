"""What stops a preview before pybullet starts, each with the one line a user reads.

An unknown sensor, target or rule, a camera or a lidar over the render budget, a sensor
or a robot too far from its root to be a finite place, a kinematic tree that is broken
or is not one tree: each raises UsageError or InputError (exit 2) before anything is
allocated, so that pybullet is never handed what would exhaust the machine or crash it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from sensorkit.base.errors import InputError, UsageError
from sensorkit.knowledge.limits import PLAUSIBLE_CAMERA_PIXELS, PLAUSIBLE_LIDAR_RAYS
from sensorkit.render.plan import lidar_rays, wanted

if TYPE_CHECKING:
    from sensorkit.model.robot import Robot

__all__ = [
    "MAX_CAMERA_PIXELS",
    "MAX_LIDAR_RAYS",
    "MAX_POSE_M",
    "check_budget",
    "check_reach",
    "check_rules",
    "check_sensor_names",
    "check_structure",
    "check_tree",
    "chosen_target",
]

# Budgets checked before anything is allocated: the plausibility limits validate warns of
# (SK403/SK406), with their reasons, in sensorkit/knowledge/limits.py.
MAX_CAMERA_PIXELS = PLAUSIBLE_CAMERA_PIXELS
MAX_LIDAR_RAYS = PLAUSIBLE_LIDAR_RAYS
# Sensors further than this from the robot's root are not on a robot (1e308 m overflows).
MAX_POSE_M = 1e4


def check_sensor_names(robot: Robot, names: Sequence[str]) -> None:
    """Refuse a ``--sensor`` the robot does not have, listing those it has."""
    known = [s.name for s in robot.sensors]
    for name in names:
        if name not in known:
            listing = ", ".join(known) if known else "the robot has no <sensor>"
            msg = f"--sensor {name}: no sensor called {name!r} (sensors: {listing})"
            raise UsageError(msg)


def chosen_target(robot: Robot, target: str, origin: str) -> tuple[str, str]:
    """The target and why: detected for ``auto``, else as chosen with ``origin``."""
    from sensorkit.model.targets import TARGETS, detect_target

    if target == "auto":
        return detect_target(robot)
    if target in TARGETS:
        return target, f"chosen with {origin}"
    msg = f"unknown target {target!r}: use auto, " + ", ".join(TARGETS)
    raise UsageError(msg)


def check_rules(target: str, select: Sequence[str], ignore: Sequence[str]) -> None:
    """Refuse validate's rules that do not exist (exit 2), as ``sensorkit validate`` does."""
    from sensorkit.lint.engine import Options

    Options(target=target, select=tuple(select), ignore=tuple(ignore))


def check_budget(
    robot: Robot, only: Sequence[str], target: str, *, max_pixels: int, max_rays: int
) -> None:
    """Refuse (UsageError, exit 2) a sensor whose render would exhaust the machine, or whose
    pose is not a finite place near the robot, naming the sensor and the option to raise."""
    from sensorkit.describe.published import camera_size
    from sensorkit.model.frames_np import render_pose_np

    for s in robot.sensors:
        if not wanted(s, only):
            continue
        for cam in s.cameras:
            w, h, _ = camera_size(cam, [])
            if w * h > max_pixels:
                msg = (
                    f"sensor {s.name!r}: a {w}x{h} camera is {w * h:,} pixels, over the render "
                    f"budget of {max_pixels:,}; pass --max-pixels {w * h} to render it anyway"
                )
                raise UsageError(msg)
        if s.lidar is not None:
            rays = lidar_rays(s)
            if rays > max_rays:
                raise_it = (
                    f"; pass --max-rays {rays:.0f} to cast it anyway" if rays < math.inf else ""
                )
                msg = (
                    f"sensor {s.name!r}: a lidar of {rays:,.0f} rays per scan (samples x "
                    f"resolution) is over the render budget of {max_rays:,}{raise_it}"
                )
                raise UsageError(msg)
        T = render_pose_np(robot, s, target)
        if T is not None:
            import numpy as np

            if not np.all(np.isfinite(T)) or float(np.abs(T[:3, 3]).max()) > MAX_POSE_M:
                msg = (
                    f"sensor {s.name!r} sits at {T[:3, 3].tolist()} m from the robot's root: not a "
                    f"finite place within {MAX_POSE_M:g} m, so it cannot be rendered (check its joint origins)"
                )
                raise UsageError(msg)


def check_structure(robot: Robot, target: str) -> None:
    """Never hand pybullet a structurally broken robot (a typeless joint segfaults it):
    validate's SK2xx errors stop the render with one line (exit 2)."""
    from sensorkit.base.findings import Severity
    from sensorkit.lint.engine import Options, check_robot

    report = check_robot(robot, Options(target=target, select=("SK2",)))
    errors = [f for f in report.findings if f.severity == Severity.ERROR]
    if errors:
        first = errors[0]
        more = f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
        msg = (
            f"{first.file}:{first.line}: {first.rule} {first.message}{more}: the kinematic tree is "
            "broken, so nothing is rendered; run sensorkit validate"
        )
        raise InputError(msg)


def check_reach(robot: Robot, reach: float) -> None:
    """Refuse a robot whose shapes or links reach ``reach`` m from its root, past
    ``MAX_POSE_M`` (or nan: 1e308 origins or sizes overflow the scene)."""
    if not reach <= MAX_POSE_M:
        msg = (
            f"{robot.document.display}: the robot reaches {reach:g} m from its root: not a finite "
            f"size within {MAX_POSE_M:g} m, so it cannot be rendered (check its joint origins and "
            "geometry sizes)"
        )
        raise UsageError(msg)


def check_tree(robot: Robot) -> None:
    """Refuse a robot that is not one tree of links: pybullet loads nothing else."""
    roots = robot.roots()
    if len(roots) != 1:
        where = robot.document.display
        if not robot.links:
            msg = f"{where}: defines no links, so there is nothing to render (a file of macros to include?)"
        elif not roots:
            msg = f"{where}: its joints form a cycle, and pybullet needs a tree"
        else:
            msg = f"{where}: the robot has {len(roots)} root links ({', '.join(roots)}); pybullet needs one tree"
        raise InputError(msg)
