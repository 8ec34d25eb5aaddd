"""Validation rules, one module per family, all registered in ``RULES`` by id."""

from sensorkit.lint.rules import frames, input, mass, plugins, sensors, tree  # noqa: F401  (registration)
from sensorkit.lint.rules.base import RULES, Context, MissingFile, RuleInfo

__all__ = ["RULES", "Context", "MissingFile", "RuleInfo"]
