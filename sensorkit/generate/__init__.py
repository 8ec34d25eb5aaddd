"""``sensorkit new``: assemble a robot base and sensor macros into an ament package.

Library API (the CLI in :mod:`sensorkit.cli.new` is a thin layer over it):

- :func:`load_spec` / :func:`parse_spec`: read and check a robot YAML
  (:class:`RobotSpec`, :class:`SensorSpec`); mistakes raise ``InputError`` with
  ``FILE:LINE:COLUMN``.
- :func:`new_package`: write the package (:class:`GeneratedPackage`).
- :func:`bridge_entries`: the ros_gz_bridge entries of an expanded description.
- :func:`sensor_macros` / :func:`base_templates`: what the shipped xacro files offer.
"""

from __future__ import annotations

from sensorkit.generate.bridge import bridge_entries, bridge_file_text
from sensorkit.generate.catalog import MacroInfo, Param, base_templates, sensor_macros
from sensorkit.generate.package import GeneratedPackage, build_package, new_package
from sensorkit.generate.spec import Mark, RobotSpec, SensorSpec, load_spec, parse_spec

__all__ = [
    "GeneratedPackage",
    "MacroInfo",
    "Mark",
    "Param",
    "RobotSpec",
    "SensorSpec",
    "base_templates",
    "bridge_entries",
    "bridge_file_text",
    "build_package",
    "load_spec",
    "new_package",
    "parse_spec",
    "sensor_macros",
]
