"""The rule registry and the context every rule reads.

A rule is a pure function ``(ctx) -> Iterable[Finding]``: it reads the model and never
prints, raises for a finding, touches files or exits. Register with ``@rule``; the ids
are a public contract (never renumber or reuse one).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from sensorkit.base.consequence import Consequence
from sensorkit.base.findings import Finding, Severity, SourceRef

if TYPE_CHECKING:
    from lxml import etree

    from sensorkit.loading.bridge import BridgeTopic
    from sensorkit.loading.launch_facts import LaunchFacts
    from sensorkit.model.frames import SensorFrames
    from sensorkit.model.robot import Robot
    from sensorkit.model.sdf import Conversion
    from sensorkit.model.sensors import Sensor

RuleFunc = Callable[["Context"], Iterable[Finding]]


@dataclass(frozen=True)
class RuleInfo:
    """A rule in the registry: id, severity, title, the existing tool it mirrors, its check."""

    id: str
    severity: str  # as in the catalogue: "error", "warning", "info", "error/warning"
    title: str
    existing: str
    func: RuleFunc | None = None
    # The inputs the rule runs on: "urdf" (URDF/xacro), "sdf" (SDF models and worlds). A
    # rule is URDF-only until it is shown to hold on SDF (a trigger and a near miss of its
    # own in SDF): what URDF's conversion does (lumping, massless links dropped, `<gazebo
    # reference>`) does not happen to an SDF model, and a rule that assumed it would be
    # wrong there.
    formats: tuple[str, ...] = ("urdf",)

    def runs_on(self, robot: Robot) -> bool:
        """Whether the rule checks ``robot`` (an SDF model only if it knows SDF)."""
        return ("sdf" if robot.sdf is not None else "urdf") in self.formats

    @property
    def family(self) -> str:
        return self.id[:3] + "xx"


RULES: dict[str, RuleInfo] = {}


def rule(
    id: str,
    severity: str,
    title: str,
    existing: str = "none",
    formats: tuple[str, ...] = ("urdf",),
) -> Callable[[RuleFunc], RuleFunc]:
    """Register a rule function under its public id; ``formats``: see :class:`RuleInfo`."""

    def deco(func: RuleFunc) -> RuleFunc:
        if id in RULES and RULES[id].func is not None:
            msg = f"rule {id} registered twice"
            raise RuntimeError(msg)
        RULES[id] = RuleInfo(id, severity, title, existing, func, formats)
        return func

    return deco


def declare(
    id: str,
    severity: str,
    title: str,
    existing: str = "none",
    formats: tuple[str, ...] = ("urdf",),
) -> None:
    """Register a rule whose findings come from loading (SK101..SK103), not a function."""
    RULES[id] = RuleInfo(id, severity, title, existing, None, formats)


def put_in_order(ids: Sequence[str]) -> None:
    """Reorder ``RULES`` as ``ids`` lists them: every registered rule, each once."""
    if sorted(ids) != sorted(RULES):
        msg = f"the rule order lists {sorted(set(ids) ^ set(RULES))} wrongly"
        raise RuntimeError(msg)
    ordered = {rid: RULES[rid] for rid in ids}
    RULES.clear()
    RULES.update(ordered)


@dataclass
class MissingFile:
    """A file reference (mesh, texture) that does not resolve; found before rules run."""

    uri: str
    source: SourceRef
    reason: str
    link: str | None = None


@dataclass
class Bridge:
    """The ros_gz_bridge configuration known for a Gazebo Sim robot (files may be none)."""

    files: list[str] = field(default_factory=list)
    topics: list[BridgeTopic] = field(default_factory=list)


@dataclass
class Context:
    """Everything a rule may read. Computed once per robot by the engine."""

    robot: Robot
    target: str
    conversion: Conversion
    frames: dict[int, SensorFrames] = field(default_factory=dict)
    missing_files: list[MissingFile] = field(default_factory=list)
    auto: bool = False  # the target was picked by --target auto
    bridge: Bridge | None = None  # gz targets: what the bridge carries to ROS (launch's too)
    launch: LaunchFacts | None = None  # what the robot's launch files say (issue 24)

    def frames_of(self, sensor: Sensor) -> SensorFrames:
        return self.frames[id(sensor)]

    def locate(self, el: etree._Element | None) -> SourceRef:
        return self.robot.document.locate(el)

    def finding(
        self,
        rule_id: str,
        severity: Severity,
        message: str,
        where: etree._Element | SourceRef | None = None,
        **extra: Any,
    ) -> Finding:
        source = where if isinstance(where, SourceRef) else self.locate(where)
        return Finding(rule_id, severity, message, source, **extra)

    def judged(
        self,
        rule_id: str,
        consequence: Consequence,
        message: str,
        where: etree._Element | SourceRef | None = None,
        **extra: Any,
    ) -> Finding:
        """A finding whose severity is computed from ``consequence`` (what was written
        against what the simulator uses: sensorkit.base.consequence), its message followed
        by the two values."""
        text = f"{message} ({consequence.says()})"
        return self.finding(
            rule_id, consequence.severity, text, where, consequence=consequence, **extra
        )
