"""Findings are data: what a rule saw, where, and how to fix it."""

from __future__ import annotations

import enum
from dataclasses import asdict, dataclass, field
from typing import Any

from sensorkit.base.quote import shorten


class Severity(enum.IntEnum):
    """Ordered so that ``severity >= fail_on`` reads naturally."""

    INFO = 0
    WARNING = 1
    ERROR = 2

    @property
    def label(self) -> str:
        return self.name.lower()

    @classmethod
    def parse(cls, text: str) -> Severity:
        try:
            return cls[text.strip().upper()]
        except KeyError:
            msg = f"unknown severity {text!r}: use error, warning or info"
            raise ValueError(msg) from None


# What each severity promises the user (issue 23). Every rule's severity is judged by it;
# `sensorkit rules` and the README print it.
SEVERITY_CONTRACT: dict[Severity, str] = {
    Severity.ERROR: "the sensor will not work as written: no data, data in a frame TF cannot "
    "place, or geometry or calibration that is wrong",
    Severity.WARNING: "it works, but something a user would fix",
    Severity.INFO: "true and harmless, or a limit of what sensorkit knows",
}


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
        return out

    def sort_key(self) -> tuple[str, int, str, str]:
        return (self.file or "", self.line or 0, self.rule, self.message)
