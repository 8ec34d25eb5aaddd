"""SK505: rotations written exactly, and the numbers and angles fixers write.

An angle within half a degree of a multiple of pi/2 (as SK502/SK505 judge it) is written
exactly: ``${-pi/2}`` in xacro, full precision in URDF. Only literal numbers change;
text a xacro expression produces stays as it is.
"""

from __future__ import annotations

import math
import re

from sensorkit.base.findings import Finding
from sensorkit.fix.registry import EXPR, Fix, FixContext, fixer, is_expr
from sensorkit.fix.source import NotFixable
from sensorkit.knowledge.limits import ANGLE_TOL  # as SK502/SK505
from sensorkit.model.parse import child

__all__ = [
    "ANGLE_TOL",
    "HALF_PI",
    "OPTICAL_RPY_URDF",
    "OPTICAL_RPY_XACRO",
    "exact_angles",
    "exact_optical",
    "urdf_number",
]

HALF_PI = math.pi / 2
OPTICAL_RPY_XACRO = "${-pi/2} 0 ${-pi/2}"
OPTICAL_RPY_URDF = f"{-HALF_PI!r} 0 {-HALF_PI!r}"


def urdf_number(v: float) -> str:
    """A number as URDF text: full precision, no trailing ``.0``, no ``-0``."""
    if v == 0:
        return "0"
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


_NUMBER = re.compile(r"(?<!\S)[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?!\S)")


def _mask_expressions(raw: str) -> str:
    """``raw`` with every ``${...}``/``$(...)`` replaced by as many ``x`` (not numbers)."""
    out = list(raw)
    i = 0
    while True:
        m = EXPR.search(raw, i)
        if m is None:
            break
        close = "}" if m.group(0) == "${" else ")"
        depth, j = 0, m.end() - 1
        while j < len(raw):
            if raw[j] == m.group(0)[1]:
                depth += 1
            elif raw[j] == close:
                depth -= 1
                if depth == 0:
                    break
            j += 1
        for k in range(m.start(), min(j + 1, len(raw))):
            out[k] = "x"
        i = j + 1
    return "".join(out)


def exact_angles(raw: str, *, xacro: bool) -> str:
    """``raw`` with every literal angle within half a degree of a multiple of pi/2 written
    exactly (xacro: ``${-pi/2}``; URDF: full precision); expressions stay as they are."""
    masked = _mask_expressions(raw)
    parts: list[str] = []
    last = 0
    for m in _NUMBER.finditer(masked):
        v = float(m.group(0))
        for k in (0, -1, 1, -2, 2):
            exact = k * HALF_PI
            if v != exact and abs(v - exact) <= ANGLE_TOL:
                if k == 0:
                    text = "0"
                elif xacro:
                    text = {-1: "${-pi/2}", 1: "${pi/2}", -2: "${-pi}", 2: "${pi}"}[k]
                else:
                    text = urdf_number(exact)
                parts += [raw[last : m.start()], text]
                last = m.end()
                break
    parts.append(raw[last:])
    return "".join(parts)


@fixer(
    "SK505",
    "safe",
    "write the optical rotation exactly (`${-pi/2}` in xacro, `-1.5707963267948966` in URDF); "
    "only the approximate numbers change",
)
def exact_optical(fx: FixContext, f: Finding) -> Fix:
    joint = fx.robot.joint_map.get(f.joint or "")
    origin = child(joint.element, "origin") if joint is not None else None
    if origin is None:
        raise NotFixable(f"joint {f.joint!r} has no <origin> to edit")
    w = fx.written(origin)
    a = w.tag.attr("rpy")
    if a is None:
        raise NotFixable(f"<origin> at {w.where} has no rpy as written")
    new = exact_angles(a.raw, xacro=fx.xacro)
    if new == a.raw:
        raise NotFixable(
            f'rpy="{a.raw}" at {w.where} is computed by xacro: write the exact angle where its value comes from'
            if is_expr(a.raw)
            else f'rpy="{a.raw}" at {w.where} holds no approximate angle'
        )
    return Fix(f, (w.file.set_attr(a, new),), f'rpy "{a.raw}" -> "{new}"')
