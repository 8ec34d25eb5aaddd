"""``sensorkit validate --fix``: fixers per rule, and the step that applies them.

Findings stay data and rules stay pure; a fixer reads the model, a finding and the
files' bytes and returns byte edits (:mod:`sensorkit.fix.registry`). Elements are found
where they are written by a lexical scan of the original bytes
(:mod:`sensorkit.fix.source`); :mod:`sensorkit.fix.apply` checks, applies and publishes.
"""

from __future__ import annotations

from sensorkit.fix import fixers as _fixers  # noqa: F401  (registers the fixers)
from sensorkit.fix.registry import FIXERS, Fix, FixContext, FixerInfo, NotFixable, fixer

__all__ = ["FIXERS", "Fix", "FixContext", "FixerInfo", "NotFixable", "fixable", "fixer"]


def fixable(rule: str) -> str:
    """``safe``, ``unsafe`` or ``safe/unsafe`` for a rule with a fixer, else ``""``."""
    info = FIXERS.get(rule)
    return info.safety if info is not None else ""
