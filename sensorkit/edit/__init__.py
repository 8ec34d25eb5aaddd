"""Editing robot files: add sensors without disturbing a byte of what is there.

Rooms: ``layout`` reads how a file is written (encoding, newlines, indentation, where
the root closes) from its raw bytes; ``render`` makes the new text; ``fragment``
expands one macro call on its own; ``check`` refuses taken names, missing parents and
new validator errors; ``atomic`` publishes; ``add`` puts them together.
"""

from sensorkit.edit.add import AddRequest, AddResult, PlannedWrite, add_sensor, apply_add, plan_add
from sensorkit.edit.kinds import KINDS, SensorKind

__all__ = [
    "KINDS",
    "AddRequest",
    "AddResult",
    "PlannedWrite",
    "SensorKind",
    "add_sensor",
    "apply_add",
    "plan_add",
]
