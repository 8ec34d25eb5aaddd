"""Scalar formatting shared by the exporters: exact reals, strict ints, safe strings.

Readers disagree on what a number is. OpenCV's FileStorage and ORB-SLAM3 tell ints
from reals by the literal (``500`` is an int, ``500.0`` a real); PyYAML only resolves
a float when the literal has a dot (``1e-05`` stays a string). So every real is
written with ``repr`` (shortest text that round-trips exactly) and forced to contain
a dot, and every int is written without one.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterable

import numpy as np

from sensorkit.describe.intrinsics import (
    InvalidValue,
    _finite,  # one definition of "a finite number"
    _positive,  # and of "greater than zero"
)

_PLAIN = re.compile(r"^[A-Za-z_/~][A-Za-z0-9_/.~-]*$")
_YAML_WORDS = frozenset(
    {"true", "false", "yes", "no", "on", "off", "null", "y", "n", "nan", "inf"},
)


def real(value: object, name: str = "value") -> str:
    """A finite float as an exact YAML/OpenCV real literal (always has a dot).

    ``-0.0`` is written as ``0.0``; ``1e-05`` as ``1.0e-05``.

    Raises:
        InvalidValue: ``value`` is not a finite number.
    """
    number = _finite(name, value)
    text = repr(number + 0.0)
    if "." not in text:
        mantissa, _, exponent = text.partition("e")
        text = f"{mantissa}.0e{exponent}" if exponent else f"{mantissa}.0"
    return text


def integer(value: object, name: str = "value") -> str:
    """An int literal; bools, floats and other types are refused.

    Raises:
        InvalidValue: ``value`` is not an int.
    """
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        msg = f"{name} must be an integer, got {value!r}"
        raise InvalidValue(msg)
    return str(int(value))


def boolean(value: bool) -> str:
    """A YAML boolean literal (``true``/``false``), as ROS 2 parameter files use."""
    return "true" if value else "false"


def string(value: object, name: str = "value") -> str:
    """A YAML string: plain when unambiguous, double-quoted (JSON escaping) otherwise.

    Raises:
        InvalidValue: ``value`` is not a string or is empty.
    """
    if not isinstance(value, str) or not value:
        msg = f"{name} must be a non-empty string, got {value!r}"
        raise InvalidValue(msg)
    if _PLAIN.match(value) and value.lower() not in _YAML_WORDS and value != "~":
        return value
    return quoted(value)


def quoted(value: str) -> str:
    """A double-quoted YAML string (JSON escaping is valid YAML)."""
    return json.dumps(value, ensure_ascii=True)


def real_list(values: Iterable[object], name: str = "value") -> str:
    """A flow sequence of exact reals: ``[1.0, 0.0, 2.5]``."""
    return "[" + ", ".join(real(v, name) for v in values) + "]"


def int_list(values: Iterable[object], name: str = "value") -> str:
    """A flow sequence of ints: ``[640, 480]``."""
    return "[" + ", ".join(integer(v, name) for v in values) + "]"


def fps_int(value: object, name: str = "fps") -> int:
    """A frame rate as a positive int (ORB-SLAM3 refuses ``30.0`` for ``Camera.fps``).

    Raises:
        InvalidValue: not a positive whole number.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        msg = f"{name} must be a positive whole number, got {value!r}"
        raise InvalidValue(msg)
    number = float(value)
    if not math.isfinite(number) or number <= 0 or not number.is_integer():
        msg = f"{name} must be a positive whole number, got {value!r}"
        raise InvalidValue(msg)
    return int(number)


def finite(value: object, name: str) -> float:
    """Return ``value`` as a float if finite (not a bool), else raise InvalidValue."""
    return _finite(name, value)


def positive(value: object, name: str) -> float:
    """Return ``value`` as a float if finite (not a bool) and greater than zero, else raise
    InvalidValue."""
    return _positive(name, value)


def matrix_rows(matrix: Iterable[Iterable[float]]) -> list[float]:
    """Flatten a 2-D matrix row-major into Python floats."""
    return [float(v) for row in matrix for v in row]
