"""Severity computed from consequence (issue 35): what the author wrote against what the
simulator will really use.

A rule that reports a difference between what is written and what runs states both values
and the role the value plays, and takes its severity from :func:`severity_of`, the one place
where consequence becomes severity:

- the effective value equals the intended one: info, however wrong the spelling;
- a frame, a topic, a calibration, a geometry, or whether the sensor publishes at all
  (``OUTPUT``) differs: error (ROS receives wrong data, or none);
- a rate, noise, a limit or a flag differs: warning (it works, not as tuned); so does a
  topic only the simulator's side sees (``SIM_TOPIC``: no bridge carries it to ROS);
- a cosmetic difference: info;
- sensorkit cannot tell the effective value (``UNKNOWN``): info, since a rule must know
  before it reports above info.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import Any, Final

__all__ = ["SEVERITY_CONTRACT", "UNKNOWN", "Consequence", "Role", "Severity", "same_value", "severity_of"]


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


class Role(str, enum.Enum):
    """What a value does for the data ROS receives."""

    FRAME = "frame"  # the frame_id stamped, or where TF places it
    TOPIC = "topic"  # the topic (or namespace) the data goes to
    CALIBRATION = "calibration"  # camera_info, intrinsics, distortion, baseline
    GEOMETRY = "geometry"  # field of view, image size, clip, scan angles and ranges
    OUTPUT = "output"  # whether the sensor publishes anything at all
    RATE = "rate"
    NOISE = "noise"
    LIMIT = "limit"
    FLAG = "flag"
    # a topic on the simulator's side that no bridge carries to ROS (two gz sensors on one
    # gz topic nothing bridges): ROS receives nothing wrong, the simulator's stream is
    SIM_TOPIC = "simulator topic"
    COSMETIC = "cosmetic"


class _Unknown:
    """The effective value sensorkit cannot tell (a plugin it does not know, say)."""

    _instance: _Unknown | None = None

    def __new__(cls) -> _Unknown:
        if cls._instance is None:
            cls._instance = super().__new__(cls)
        return cls._instance

    def __repr__(self) -> str:
        return "UNKNOWN"

    def __str__(self) -> str:
        return "not known to sensorkit"


UNKNOWN: Final = _Unknown()

# A difference in these roles means ROS receives wrong data, or none.
WRONG_DATA: Final = frozenset(
    {Role.FRAME, Role.TOPIC, Role.CALIBRATION, Role.GEOMETRY, Role.OUTPUT}
)
# A difference in these means the sensor works, not as tuned.
TUNING: Final = frozenset({Role.RATE, Role.NOISE, Role.LIMIT, Role.FLAG, Role.SIM_TOPIC})


def _number(value: Any) -> float | None:
    if isinstance(value, bool):
        return float(value)
    if isinstance(value, int | float):
        return float(value)
    if isinstance(value, str):
        try:
            return float(value.strip())
        except ValueError:
            return None
    return None


def same_value(a: Any, b: Any, *, rel: float = 1e-9, abs_tol: float = 1e-12) -> bool:
    """Whether two written or effective values are the same value: numbers (also numbers
    written as text) within ``rel``/``abs_tol``, sequences item by item, the rest by ``==``
    (text stripped)."""
    if a is UNKNOWN or b is UNKNOWN:
        return False
    if isinstance(a, list | tuple) and isinstance(b, list | tuple):
        return len(a) == len(b) and all(
            same_value(x, y, rel=rel, abs_tol=abs_tol) for x, y in zip(a, b, strict=True)
        )
    x, y = _number(a), _number(b)
    if x is not None and y is not None:
        if math.isnan(x) or math.isnan(y):
            return math.isnan(x) and math.isnan(y)
        return math.isclose(x, y, rel_tol=rel, abs_tol=abs_tol)
    if isinstance(a, str) and isinstance(b, str):
        return a.strip() == b.strip()
    return bool(a == b)


def severity_of(role: Role, intended: Any, effective: Any, *, equal: bool | None = None) -> Severity:
    """The severity of writing ``intended`` where the simulator uses ``effective``.
    ``equal`` overrides the comparison where the rule knows better (a tolerance of its own)."""
    if effective is UNKNOWN or intended is UNKNOWN:
        return Severity.INFO
    if equal is None:
        equal = same_value(intended, effective)
    if equal or role is Role.COSMETIC:
        return Severity.INFO
    if role in WRONG_DATA:
        return Severity.ERROR
    return Severity.WARNING


def _show(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_show(v) for v in value) + "]"
    if value is None:
        return "nothing"
    return str(value)


@dataclass(frozen=True)
class Consequence:
    """What the author meant (``intended``) and what the simulator uses (``effective``) for a
    value of ``role``; ``equal`` when the rule compared them with a tolerance of its own."""

    role: Role
    intended: Any
    effective: Any
    equal: bool | None = None

    def __post_init__(self) -> None:
        # Findings are frozen, comparable data: sequences are kept as tuples.
        for key in ("intended", "effective"):
            value = getattr(self, key)
            if isinstance(value, list):
                object.__setattr__(self, key, tuple(value))

    @property
    def severity(self) -> Severity:
        return severity_of(self.role, self.intended, self.effective, equal=self.equal)

    @property
    def changes_nothing(self) -> bool:
        return self.severity is Severity.INFO and self.effective is not UNKNOWN

    def says(self) -> str:
        """The two values in words, for the finding's message."""
        if self.effective is UNKNOWN:
            return f"written {_show(self.intended)}; what the simulator uses instead is not known to sensorkit"
        if self.severity is Severity.INFO and self.role is not Role.COSMETIC:
            return f"written {_show(self.intended)}; the simulator uses {_show(self.effective)}: nothing changes"
        return f"written {_show(self.intended)}; the simulator uses {_show(self.effective)}"

    def to_dict(self) -> dict[str, Any]:
        """The JSON form (a finding's ``consequence`` field)."""

        def plain(v: Any) -> Any:
            if v is UNKNOWN:
                return None
            if isinstance(v, list | tuple):
                return [plain(x) for x in v]
            if isinstance(v, str | int | float | bool) or v is None:
                return v
            return str(v)

        return {
            "role": self.role.value,
            "intended": plain(self.intended),
            "effective": plain(self.effective),
            "known": self.effective is not UNKNOWN,
        }
