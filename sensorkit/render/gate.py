"""The preview as a gate: one verdict from validate's findings and the preview's checks.

Findings are data; this module is the policy. ``--fail-on`` is a severity (as for
``sensorkit validate``) or None (``never``). A check's ``fail`` counts as an error and its
``warn`` as a warning, so one threshold decides both: at the default ``error``, a
robot fails on any validate error or failed check, and ``warning`` fails it on warned
checks too. A preview whose validate could not run fails (nothing vouches for the
robot) unless the gate is off.

The verdict's text is what a CI log and the page's header show first, e.g.
``FAIL: 1 error (SK502 front_camera), 1 failed check (bad_cx_cam reprojection)``, and
its reasons say each in full, one a line.

One rule gives a status (``ok``, ``warn``, ``fail``, ``skipped``) to a sensor and to the
whole preview, from checks and findings alike (``status_of``): an error finding counts
as a failed check, a warning as a warned one. A sensor shown "ok" never carries an error.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from sensorkit.base.findings import Finding, Severity

if TYPE_CHECKING:
    from sensorkit.render.checks import Check

__all__ = [
    "CHECK_SEVERITY",
    "Verdict",
    "fail_on_label",
    "found_text",
    "sensor_findings",
    "status_of",
    "verdict",
]

CHECK_SEVERITY = {"fail": Severity.ERROR, "warn": Severity.WARNING}
FINDING_STATUS = {Severity.ERROR: "fail", Severity.WARNING: "warn"}  # and the reverse
STATUS_ORDER = {"skipped": 0, "ok": 1, "warn": 2, "fail": 3}
NAMED = 3  # findings or checks named in the verdict's one line
MESSAGE_CHARS = 300  # of a finding's message in the reasons


def fail_on_label(fail_on: Severity | None) -> str:
    """``error``, ``warning``, ``info`` or ``never``."""
    return "never" if fail_on is None else fail_on.label


def _plural(n: int, word: str) -> str:
    if word == "info":
        return f"{n} info"
    return f"{n} {word}" + ("" if n == 1 else "s")


def _short(text: str, limit: int = MESSAGE_CHARS) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 3].rstrip() + "..."


def _about(f: Finding) -> str:
    """``SK502 front_camera``: the rule and what it is about."""
    about = f.sensor or f.link or f.joint or f.frame
    return f"{f.rule} {about}" if about else f.rule


def _finding_line(f: Finding) -> str:
    return f"{_about(f)}: {_short(f.message)}"


@dataclass
class Verdict:
    """Does the preview pass the gate, and why (most severe first)."""

    failed: bool
    fail_on: str  # error | warning | info | never
    findings: dict[str, int]  # validate's findings by severity: error, warning, info
    checks: dict[str, int]  # the preview's checks by status: ok, warn, fail, skipped
    reasons: list[str] = field(default_factory=list)  # what fails it, one line each
    validate_error: str | None = None  # validate could not run
    text: str = ""

    @property
    def counts_text(self) -> str:
        """``validate: 1 error, 0 warnings, 0 info; checks: 5 ok, 1 warn, 0 fail``."""
        f, c = self.findings, self.checks
        found = (
            f"validate could not run ({_short(self.validate_error)})"
            if self.validate_error is not None
            else "validate: " + ", ".join(_plural(f[k], k) for k in ("error", "warning", "info"))
        )
        return f"{found}; checks: {c['ok']} ok, {c['warn']} warn, {c['fail']} fail"

    def to_dict(self) -> dict[str, Any]:
        return {
            "status": "fail" if self.failed else "pass",
            "fail_on": self.fail_on,
            "text": self.text,
            "findings": dict(self.findings),
            "checks": dict(self.checks),
            "reasons": list(self.reasons),
            "validate_error": self.validate_error,
        }


def verdict(
    findings: Sequence[Finding] | None,
    findings_error: str | None,
    checks: Sequence[tuple[str, Check]],
    fail_on: Severity | None,
) -> Verdict:
    """The gate's verdict on validate's ``findings`` (None: validate did not run, with
    ``findings_error``) and the preview's ``checks`` (sensor name, check)."""
    counts = {"error": 0, "warning": 0, "info": 0}
    for f in findings or ():
        counts[f.severity.label] += 1
    statuses = {"ok": 0, "warn": 0, "fail": 0, "skipped": 0}
    for _, c in checks:
        statuses[c.status] = statuses.get(c.status, 0) + 1
    out = Verdict(False, fail_on_label(fail_on), counts, statuses)
    if findings is None:
        out.validate_error = findings_error or "validate is not available"
    at = fail_on if fail_on is not None else Severity.INFO
    over = sorted(
        (f for f in findings or () if f.severity >= at),
        key=lambda f: (-int(f.severity), f.sort_key()),
    )
    bad = sorted(
        (
            (name, c)
            for name, c in checks
            if c.status in CHECK_SEVERITY and CHECK_SEVERITY[c.status] >= at
        ),
        key=lambda nc: -int(CHECK_SEVERITY[nc[1].status]),
    )
    out.reasons = [f"{f.severity.label}: {_finding_line(f)}" for f in over] + [
        f"check {c.status}: {name} {c.name}: {_short(c.message)}" for name, c in bad
    ]
    if out.validate_error is not None:
        out.reasons.insert(0, f"validate could not run: {_short(out.validate_error)}")

    parts: list[str] = []
    if out.validate_error is not None:
        parts.append("validate could not run")
    for severity in (Severity.ERROR, Severity.WARNING, Severity.INFO):
        these = [f for f in over if f.severity == severity]
        if these:
            named = ", ".join(_about(f) for f in these[:NAMED])
            more = f" and {len(these) - NAMED} more" if len(these) > NAMED else ""
            parts.append(f"{_plural(len(these), severity.label)} ({named}{more})")
    for status, word in (("fail", "failed check"), ("warn", "warned check")):
        these_c = [(name, c) for name, c in bad if c.status == status]
        if these_c:
            named = ", ".join(f"{name} {c.name}" for name, c in these_c[:NAMED])
            more = f" and {len(these_c) - NAMED} more" if len(these_c) > NAMED else ""
            parts.append(f"{_plural(len(these_c), word)} ({named}{more})")
    if fail_on is None:
        out.text = f"NOT GATED (--fail-on never): {out.counts_text}"
        return out
    out.failed = bool(parts)
    if out.failed:
        out.text = "FAIL: " + ", ".join(parts)
    else:
        out.text = f"PASS: no finding or check at or above {fail_on.label} ({out.counts_text})"
    return out


def status_of(checks: Sequence[Check], findings: Sequence[Finding] = ()) -> str:
    """The status of a sensor (or the preview) with these ``checks`` and validate's
    ``findings``: the most severe of the checks' statuses and the findings' (an error is
    ``fail``, a warning ``warn``, an info nothing); ``skipped`` with neither."""
    statuses = [c.status for c in checks]
    statuses += [FINDING_STATUS[f.severity] for f in findings if f.severity in FINDING_STATUS]
    return max(statuses, key=STATUS_ORDER.__getitem__, default="skipped")


def found_text(findings: Sequence[Finding]) -> str:
    """``1 error, 2 warnings``: the severities present among ``findings``."""
    return ", ".join(
        _plural(n, label)
        for label in ("error", "warning", "info")
        if (n := sum(1 for f in findings if f.severity.label == label))
    )


def sensor_findings(findings: Sequence[Finding] | None, sensor: str) -> list[Finding]:
    """validate's findings about ``sensor``, most severe first."""
    return sorted(
        (f for f in findings or () if f.sensor == sensor),
        key=lambda f: (-int(f.severity), f.sort_key()),
    )
