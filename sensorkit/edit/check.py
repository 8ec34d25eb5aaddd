"""Checks an add must pass before anything is written.

Names: the new sensor's name and every link, joint and sensor its macro creates must be
unused, and the parent link must exist (the refusal names the closest links).

Validation: the validator runs on the robot before and after the add, and any
error-level finding the add introduces refuses it. The "after" robot is built in memory
at the original's path (nothing is written), so meshes, packages and inline
suppressions resolve exactly as they do for the original.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from sensorkit.errors import EditRefused
from sensorkit.findings import Finding, Severity
from sensorkit.loading.document import Document, display_path
from sensorkit.model import Robot

if TYPE_CHECKING:
    from sensorkit.engine import Options


def closest(name: str, candidates: Iterable[str], n: int = 3) -> list[str]:
    """Up to ``n`` of ``candidates`` that look most like ``name`` (never empty if any exist)."""
    from sensorkit.suggest import closest as ranked

    pool = sorted(set(candidates))
    hits = ranked(name, pool, n=n)
    if not hits:
        lowered = name.lower()
        hits = [c for c in pool if lowered in c.lower() or c.lower() in lowered][:n]
    return hits or pool[:n]


def _existing(robot: Robot) -> dict[str, str]:
    """Every name in use, mapped to what it names (first kind wins)."""
    used: dict[str, str] = {}
    for link in robot.links:
        used.setdefault(link.name, f"link '{link.name}' ({link.source})")
    for joint in robot.joints:
        used.setdefault(joint.name, f"joint '{joint.name}' ({joint.source})")
    for sensor in robot.sensors:
        used.setdefault(sensor.name, f"sensor '{sensor.name}' ({sensor.source})")
    return used


def check_parent(robot: Robot, parent: str, where: str) -> None:
    """EditRefused naming the closest links when ``parent`` is not a link of the robot."""
    if parent in robot.link_map:
        return
    near = closest(parent, robot.link_map)
    hint = f"; closest: {', '.join(near)}" if near else "; the robot has no links"
    msg = f"parent link '{parent}' not found in {where}{hint}"
    raise EditRefused(msg)


def check_names(robot: Robot, name: str, created: Sequence[str], where: str) -> None:
    """EditRefused when ``name`` or any name the macro creates is already used."""
    used = _existing(robot)
    for candidate in [name, *created]:
        if candidate in used:
            what = used[candidate]
            via = "" if candidate == name else f" (the macro would create '{candidate}')"
            msg = f"name '{name}' is already used in {where}: {what}{via}"
            raise EditRefused(msg)


@dataclass
class Verdict:
    """What the add changes in the validator's findings."""

    new_errors: list[Finding] = field(default_factory=list)
    new_warnings: list[Finding] = field(default_factory=list)
    internal_errors: list[str] = field(default_factory=list)


def _key(f: Finding) -> tuple[str, int, str]:
    return (f.rule, int(f.severity), f.message)


def introduced(before: Sequence[Finding], after: Sequence[Finding]) -> list[Finding]:
    """Findings of ``after`` that ``before`` lacks (as a multiset of rule, severity, message)."""
    budget = Counter(_key(f) for f in before)
    out: list[Finding] = []
    for f in after:
        k = _key(f)
        if budget[k] > 0:
            budget[k] -= 1
        else:
            out.append(f)
    return out


def findings(
    robot: Robot, load_findings: Sequence[Finding], options: Options
) -> tuple[list[Finding], list[str]]:
    """What ``sensorkit validate`` reports for ``robot`` (selection and inline suppressions
    applied), and the validator's internal errors."""
    from sensorkit.engine import check_robot
    from sensorkit.suppress import collect

    report = check_robot(robot, options)
    found = [f for f in [*load_findings, *report.findings] if options.wants(f.rule)]
    files = [(display_path(f), Path(f)) for f in robot.document.source_files()]
    sup = collect(files)
    return [f for f in found if not sup.suppressed(f)], list(report.internal_errors)


def compare(
    before: Robot,
    before_load: Sequence[Finding],
    after: Document,
    options: Options,
) -> Verdict:
    """Validate the robot before and after the add, both read from memory.

    ``after`` is a document at the same path as ``before`` (so meshes, packages and
    inline suppressions resolve alike); only the validator's verdict on the difference
    matters.
    """
    from sensorkit.model import build_robot

    old, _ = findings(before, before_load, options)
    new, internal = findings(build_robot(after), before_load, options)
    fresh = introduced(old, new)
    return Verdict(
        new_errors=[f for f in fresh if f.severity >= Severity.ERROR],
        new_warnings=[f for f in fresh if f.severity == Severity.WARNING],
        internal_errors=internal,
    )


def describe(finding: Finding) -> str:
    """``RULE message`` on one line. No file:line: a new finding is about text that is
    not in the user's file yet (the message names the sensor, link or joint)."""
    text = " ".join(finding.message.split())
    return f"{finding.rule} {text}"
