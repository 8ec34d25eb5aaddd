"""The robot model: the :class:`Robot` record, holding the links, joints, gazebo blocks
and sensors read from a URDF, with the tree questions and the poses it answers.

Its parts' records (Link, Joint, ...) are in :mod:`sensorkit.model.parts`, the reader in
:mod:`sensorkit.model.urdf`, the answers in its bases :class:`~sensorkit.model.tree.Tree`
and :class:`~sensorkit.model.poses.Poses`. A model read from SDF
(:mod:`sensorkit.model.sdf_build`) fills the same records, and keeps what only SDF says
(its frames, joints' own poses, nested models, includes) in ``sdf``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from sensorkit.loading.document import Document
from sensorkit.model.parts import GazeboBlock, Joint, Link, Stray
from sensorkit.model.poses import Poses
from sensorkit.model.tree import Tree

if TYPE_CHECKING:
    from sensorkit.model.sdf_read import SdfModel
    from sensorkit.model.sensors import Plugin, Sensor
    from sensorkit.model.transforms import Pose


@dataclass
class Robot(Tree, Poses):
    """The whole description, with lazy forward kinematics at zero joint positions."""

    name: str
    document: Document
    links: list[Link] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)
    gazebo: list[GazeboBlock] = field(default_factory=list)
    sensors: list[Sensor] = field(default_factory=list)
    model_plugins: list[Plugin] = field(default_factory=list)
    strays: list[Stray] = field(default_factory=list)
    link_map: dict[str, Link] = field(default_factory=dict)
    joint_map: dict[str, Joint] = field(default_factory=dict)
    parent_joint: dict[str, Joint] = field(default_factory=dict)
    child_joints: dict[str, list[Joint]] = field(default_factory=dict)
    _T_world: dict[str, Pose | None] = field(default_factory=dict, repr=False)
    # (tree top, number of ancestors) of links whose way up has no cycle
    _up: dict[str, tuple[str, int]] = field(default_factory=dict, repr=False)
    _roots: list[str] | None = field(default=None, repr=False)
    cache: dict[Any, Any] = field(default_factory=dict, repr=False)  # derived data, by user
    # read from SDF: the model's frames, joints' own poses, nested models, includes
    sdf: SdfModel | None = field(default=None, repr=False)

    @property
    def macros_only(self) -> bool:
        """A xacro that expands to no link, joint or sensor: it only defines macros or
        properties for robots to include (a partial given explicitly)."""
        if self.sdf is not None:
            return False
        return self.document.expanded and not self.links and not self.joints and not self.sensors


def all_plugins(robot: Robot) -> list[Plugin]:
    """Every plugin: model-level first, then each sensor's, in document order."""
    out = list(robot.model_plugins)
    for s in robot.sensors:
        out.extend(s.plugins)
    return out
