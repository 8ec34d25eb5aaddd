"""``sensorkit new``: assemble a robot base and sensor macros into an ament package.

Library API (the CLI in :mod:`sensorkit.cli.new` is a thin layer over it):

- :func:`load_spec` / :func:`parse_spec`: read and check a robot YAML
  (:class:`RobotSpec`, :class:`SensorSpec`); mistakes raise ``InputError`` with
  ``FILE:LINE:COLUMN``.
- :func:`new_package`: write the package (:class:`GeneratedPackage`).
- :func:`sensor_macros` / :func:`base_templates`: what the shipped xacro files offer.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from sensorkit.generate.catalog import MacroInfo, Param, base_templates, sensor_macros
    from sensorkit.generate.package import GeneratedPackage, build_package, new_package
    from sensorkit.generate.reader import Mark
    from sensorkit.generate.spec import RobotSpec, SensorSpec, load_spec, parse_spec

# Loaded on first use: the package writer with its YAML parser costs some 60 ms to import,
# which a command that needs one module of the package does without.
_HOME = {
    "MacroInfo": "catalog",
    "Param": "catalog",
    "base_templates": "catalog",
    "sensor_macros": "catalog",
    "GeneratedPackage": "package",
    "build_package": "package",
    "new_package": "package",
    "Mark": "reader",
    "RobotSpec": "spec",
    "SensorSpec": "spec",
    "load_spec": "spec",
    "parse_spec": "spec",
}


def __getattr__(name: str) -> Any:
    if name in _HOME:
        value = getattr(importlib.import_module(f"sensorkit.generate.{_HOME[name]}"), name)
        globals()[name] = value
        return value
    msg = f"module 'sensorkit.generate' has no attribute {name!r}"
    raise AttributeError(msg)


__all__ = [
    "GeneratedPackage",
    "MacroInfo",
    "Mark",
    "Param",
    "RobotSpec",
    "SensorSpec",
    "base_templates",
    "build_package",
    "load_spec",
    "new_package",
    "parse_spec",
    "sensor_macros",
]
