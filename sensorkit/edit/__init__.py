"""Editing robot files: add sensors without disturbing a byte of what is there.

Rooms: ``request`` says what an add is asked and what it plans; ``layout`` reads how a
file is written (encoding, newlines, indentation, where the root closes) from its raw
bytes; ``macrocall`` picks the macro file and the call's attributes; ``render`` makes
the new text; ``fragment`` expands one macro call on its own; ``splice`` puts the text
in and checks it landed; ``check`` refuses taken names, missing parents and new
validator errors; ``package`` plans the robot package's other files; ``diff`` shows
the change; ``add`` puts them together and publishes atomically.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sensorkit.base.lazy import lazy_exports

if TYPE_CHECKING:
    from sensorkit.edit.add import add_sensor, apply_add, plan_add
    from sensorkit.edit.kinds import KINDS, SensorKind
    from sensorkit.edit.request import AddRequest, AddResult, PlannedWrite

# Loaded on first use (PEP 562): ``sensorkit.fix`` reads files with ``edit.layout`` alone,
# and validate's [*] marks import it; the whole add machinery is not needed for that.
_HOME = {
    "add_sensor": "add",
    "apply_add": "add",
    "plan_add": "add",
    "KINDS": "kinds",
    "SensorKind": "kinds",
    "AddRequest": "request",
    "AddResult": "request",
    "PlannedWrite": "request",
}


__getattr__ = lazy_exports(__name__, _HOME, globals())


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
