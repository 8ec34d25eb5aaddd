"""The fixers, one per rule (see :mod:`sensorkit.fix.registry` for the contract).

Each finds the element its finding is about in the model, locates it where it is
written, and edits only that element (an attribute value, a tag name, a child). Text a
xacro expression or a macro parameter produces is never rewritten: the fix would have to
be made where the value comes from.

One module per family: :mod:`.angles` (SK505), :mod:`.plugins` (SK601),
:mod:`.ros1_tags` (SK602), :mod:`.frames` (SK502, SK503, SK303) and :mod:`.inertial`
(SK301). Importing them registers their fixers, in the order imported here.
"""

from __future__ import annotations

# In the registration order, which FIXERS keeps: not sorted.
# isort: off
from sensorkit.fix.fixers import angles
from sensorkit.fix.fixers import plugins
from sensorkit.fix.fixers import ros1_tags
from sensorkit.fix.fixers import frames
from sensorkit.fix.fixers import inertial

# isort: on

__all__ = ["angles", "frames", "inertial", "plugins", "ros1_tags"]
