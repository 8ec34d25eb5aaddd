"""What a preview gives back: one record per sensor rendered, and the whole preview's.

Below both the preview that fills these records and the report that writes them out
(summary.json, index.html), so that neither imports the other for them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sensorkit.base.findings import Severity
from sensorkit.render.checks import Check

if TYPE_CHECKING:
    from sensorkit.base.findings import Finding
    from sensorkit.model.sensors import Sensor
    from sensorkit.render.gate import Verdict
    from sensorkit.render.svg import Figure

__all__ = ["PreviewResult", "SensorPreview"]


@dataclass
class SensorPreview:
    """What was rendered for one sensor (one camera of a multicamera), and how it checked."""

    name: str  # the sensor name; "sensor/camera" for a camera of a multicamera
    sensor: str
    type: str
    kind: str
    link: str | None
    directory: Path | None = None
    files: dict[str, Path] = field(default_factory=dict)
    findings: list[Finding] = field(default_factory=list)  # validate's, about this sensor
    checks: list[Check] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    skipped: str | None = None  # why nothing was rendered
    info: dict[str, Any] = field(default_factory=dict)  # frames, intrinsics, scan, topics
    figures: dict[str, Figure] = field(default_factory=dict)  # labelled pictures, by key

    @classmethod
    def of(cls, sensor: Sensor, name: str | None = None) -> SensorPreview:
        """An empty record for ``sensor`` (``name``: a multicamera's camera's label)."""
        return cls(name or sensor.name, sensor.name, sensor.type, sensor.kind, sensor.reference)

    @property
    def status(self) -> str:
        """``status_of`` its checks and findings (``skipped`` when not rendered and no
        finding is a warning or an error)."""
        from sensorkit.render.gate import status_of

        return status_of([] if self.skipped else self.checks, self.findings)

    def add_figure(self, figure: Figure) -> None:
        """Show ``figure`` on the sensor's part of index.html; its numbers go to summary.json."""
        self.figures[figure.key] = figure
        self.info.setdefault("pictures", {})[figure.key] = figure.facts


@dataclass
class PreviewResult:
    out_dir: Path
    robot: str
    source: Path
    target: str
    target_reason: str
    scene: str
    joints: dict[str, float]
    sensors: list[SensorPreview]
    files: dict[str, Path] = field(default_factory=dict)  # summary, overview, index
    findings: list[Finding] | None = None  # validate's; None when it could not run
    fail_on: Severity | None = Severity.ERROR  # the gate's threshold; None: never fail
    findings_error: str | None = None
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0
    figures: list[Figure] = field(default_factory=list)  # the robot close up, stereo pairs
    placement: str | None = None  # a line when parts of the robot are below the ground

    @property
    def status(self) -> str:
        """``status_of`` every check and every finding (pass or fail: see ``verdict``)."""
        from sensorkit.render.gate import status_of

        checks = [c for s in self.sensors for c in s.checks]
        return status_of(checks, self.findings or [])

    @property
    def verdict(self) -> Verdict:
        """Pass or fail at ``fail_on``, from validate's findings and the checks."""
        from sensorkit.render.gate import verdict

        checks = [(s.name, c) for s in self.sensors for c in s.checks]
        return verdict(self.findings, self.findings_error, checks, self.fail_on)

    @property
    def failed(self) -> bool:
        return self.verdict.failed
