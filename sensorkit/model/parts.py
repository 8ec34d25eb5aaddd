"""The records a URDF's elements are read into: Link (with its Inertial), Joint, the
``<gazebo>`` blocks, and Strays, what urdfdom would ignore.

:class:`~sensorkit.model.robot.Robot` holds them; :mod:`sensorkit.model.urdf` reads them.
"""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree

from sensorkit.base.findings import SourceRef
from sensorkit.loading.document import Document
from sensorkit.model.parse import Origin, Vec3


class _Located:
    """Mixin: ``source`` is computed on first use (most elements never need it)."""

    __slots__ = ()
    element: etree._Element
    doc: Document

    @property
    def source(self) -> SourceRef:
        return self.doc.locate(self.element)


@dataclass(slots=True)
class Inertial(_Located):
    """A link's ``<inertial>``: mass, inertia and origin (None where unreadable; see problems).

    ``inertia`` and ``origin`` are shared by every inertial whose text reads the same: read
    them, never change them.
    """

    mass: float | None
    inertia: dict[str, float | None]
    origin: Origin
    element: etree._Element
    doc: Document
    problems: tuple[str, ...] = ()
    # Numbers the simulator reads from text that is more than a number: (element, text
    # written, value read). sdformat's std::stod reads "0.0074Source Control" as 0.0074
    # (sensorkit.model.parse.stod_prefix); the value is in mass/inertia, not a problem.
    lenient: tuple[tuple[str, str, float], ...] = ()


@dataclass(slots=True)
class Link(_Located):
    """A ``<link>``: its first inertial and the mesh files its visuals and collisions name."""

    name: str
    element: etree._Element
    doc: Document
    inertial: Inertial | None = None
    meshes: tuple[tuple[str, SourceRef], ...] = ()

    @property
    def mass(self) -> float:
        """Mass Gazebo sees (0 when missing or unreadable)."""
        if self.inertial is None or self.inertial.mass is None:
            return 0.0
        return self.inertial.mass


@dataclass(slots=True)
class Joint(_Located):
    """A ``<joint>`` as urdfdom reads it (the first of each child element counts)."""

    name: str
    type: str
    parent: str | None
    child: str | None
    origin: Origin
    element: etree._Element
    doc: Document
    axis: Vec3 | None = None
    axis_problem: str | None = None
    limit: dict[str, float | None] | None = None
    limit_problems: tuple[str, ...] = ()
    mimic: str | None = None
    has_mimic: bool = False


@dataclass(slots=True)
class Stray:
    """Something urdfdom silently ignores: an unknown child element, or attribute if ``attr``."""

    element: etree._Element
    parent_tag: str
    attr: str | None
    link: str | None


@dataclass
class GazeboBlock:
    """A ``<gazebo>`` extension; ``reference`` is None for model-level blocks."""

    reference: str | None
    element: etree._Element
    source: SourceRef

