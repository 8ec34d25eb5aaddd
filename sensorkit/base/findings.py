"""Findings are data: what a rule saw, where, and how to fix it."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

from sensorkit.base.consequence import SEVERITY_CONTRACT, Consequence, Severity
from sensorkit.base.quote import shorten

__all__ = ["SEVERITY_CONTRACT", "Finding", "Severity", "SourceRef"]


@dataclass(frozen=True)
class SourceRef:
    """Where an element came from: a file and a 1-based line (None when unknown)."""

    file: str | None
    line: int | None = None

    def __str__(self) -> str:
        if self.file is None:
            return "<unknown>"
        return f"{self.file}:{self.line}" if self.line else self.file


@dataclass(frozen=True)
class Finding:
    """One problem found in a robot description.

    ``rule`` is the public id (``SK502``); ``fix`` is a sentence or a replacement the
    user can apply. ``link``, ``joint``, ``sensor`` and ``frame`` name what it is about.
    """

    rule: str
    severity: Severity
    message: str
    source: SourceRef = field(default_factory=lambda: SourceRef(None))
    link: str | None = None
    joint: str | None = None
    sensor: str | None = None
    frame: str | None = None
    fix: str | None = None
    column: int | None = None
    # What was written against what the simulator uses, where the rule knows both
    # (sensorkit.base.consequence): the severity of such a finding is computed from it.
    consequence: Consequence | None = None

    def __post_init__(self) -> None:
        # What a finding quotes of the input stays short in every format (issue 25): a
        # name of millions of characters is clipped here, once, for all of them. ``link``,
        # ``sensor``... stay whole: they are keys (the loader caps names, MAX_NAME_CHARS).
        for key in ("message", "fix"):
            value = getattr(self, key)
            if isinstance(value, str) and len(value) > 200:
                object.__setattr__(self, key, shorten(value))

    @property
    def file(self) -> str | None:
        return self.source.file

    @property
    def line(self) -> int | None:
        return self.source.line

    def to_dict(self) -> dict[str, Any]:
        """The JSON form of the output contract: fields are only ever added."""
        data = asdict(self)
        data.pop("source")
        data.pop("consequence")
        out: dict[str, Any] = {
            "rule": self.rule,
            "severity": self.severity.label,
            "message": self.message,
            "file": self.file,
            "line": self.line,
        }
        for key in ("column", "link", "joint", "sensor", "frame", "fix"):
            if data.get(key) is not None:
                out[key] = data[key]
        if self.consequence is not None:
            out["consequence"] = self.consequence.to_dict()
        return out

    def sort_key(self) -> tuple[str, int, str, str]:
        return (self.file or "", self.line or 0, self.rule, self.message)
