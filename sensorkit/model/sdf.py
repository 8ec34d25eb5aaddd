"""What Gazebo's URDF-to-SDF conversion (sdformat ``parser_urdf.cc``) keeps.

- Fixed joints are lumped: the child link merges into its parent (mass added, visuals,
  collisions, ``<gazebo reference>`` blocks and sensors move with their poses composed)
  unless the joint carries ``<preserveFixedJoint>true</preserveFixedJoint>`` or
  ``<disableFixedJointLumping>true</disableFixedJointLumping>`` in its gazebo block.
- A surviving link with no inertial or zero (lumped) mass is not modelled, and neither are its
  joint and everything below it (``CreateSDF``). A root named ``world`` is exempt.
- Except a massless link whose fixed joint would be lumped but whose parent is ``world``:
  ``ReduceFixedJoints`` never lumps into ``world``, and ``CreateSDF`` returns early only
  when the parent joint is not one it reduces, so such a link is not created (its own
  visuals, collisions and sensors are lost) while the links below it are still converted.
  The same code on every target: gazebosim/sdformat@sdf9 (9ee2d4f3, Gazebo Classic):
  src/parser_urdf.cc:412 (no lumping into world), :2679-2683 (parentJointReduced: no
  return), :2765-2772 (no link created for zero mass), :2776-2780 (children converted);
  @sdf12 (b9417e5b, Fortress): :421, :2697-2701, :2780, :2791; @sdf14 (8512585c,
  Harmonic): :424, :2700-2704, :2783, :2794. With preserveFixedJoint or
  disableFixedJointLumping the joint is not one it reduces, so the early return drops the
  link and its subtree (sdf9 :2683-2760).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from sensorkit.model.parse import text_of

if TYPE_CHECKING:
    from sensorkit.model.robot import Robot

# What sdformat takes as true in preserveFixedJoint and disableFixedJointLumping:
# `lowerStr(valueStr) == "true" || lowerStr(valueStr) == "yes" || valueStr == "1"`
# (gazebosim/sdformat@sdformat9_9.10.2:src/parser_urdf.cc:1516-1535, Gazebo Classic;
# @sdformat12_12.8.0:src/parser_urdf.cc:1527-1546, Fortress;
# @sdformat14_14.9.0:src/parser_urdf.cc:1530-1549, Harmonic).
_TRUE = {"true", "yes", "1"}
MASS_EPSILON = 1e-6  # sdformat compares the (lumped) mass with 0 by math::equal


@dataclass
class Conversion:
    """Result of the conversion as far as frames and masses go."""

    target_of: dict[str, str] = field(default_factory=dict)  # link -> surviving link
    mass_of: dict[str, float] = field(default_factory=dict)  # surviving link -> lumped mass
    dropped: dict[str, str] = field(default_factory=dict)  # link -> massless link that drops it
    # massless links fixed to 'world' by a joint lumping would reduce: not created, but the
    # links below them are converted (a subset of dropped's causes; see the module doc)
    uncreated: set[str] = field(default_factory=set)
    preserved_joints: set[str] = field(default_factory=set)

    def survivor(self, link: str) -> str:
        return self.target_of.get(link, link)

    def is_lumped(self, link: str) -> bool:
        return self.survivor(link) != link


def preserved_fixed_joints(robot: Robot) -> set[str]:
    """Joints whose gazebo block disables fixed-joint lumping."""
    out: set[str] = set()
    for block in robot.gazebo:
        if block.reference is None:
            continue
        for tag in ("preserveFixedJoint", "disableFixedJointLumping"):
            value = text_of(block.element, tag)
            if value is not None and value.lower() in _TRUE:
                out.add(block.reference)
    return out


def convert(robot: Robot) -> Conversion:
    """Compute lumping and dropping for ``robot`` (cycle-safe).

    A model read from SDF is not converted: the simulator reads its links as written, so
    no link is lumped or dropped (lumping and dropping are parser_urdf.cc's, which only a
    URDF goes through: gazebosim/sdformat@sdformat12_12.8.0:src/parser.cc:753-772 reads
    an ``<sdf>`` document as it is and calls URDF2SDF only when that fails and the file is
    URDF).
    """
    if robot.sdf is not None:
        conv = Conversion()
        for part in robot.links:
            conv.target_of[part.name] = part.name
            inertial = part.inertial
            mass = inertial.mass if inertial is not None and inertial.mass is not None else 0.0
            conv.mass_of[part.name] = mass
        return conv
    conv = Conversion(preserved_joints=preserved_fixed_joints(robot))
    preserved = conv.preserved_joints
    target_of, mass_of = conv.target_of, conv.mass_of
    parent_joint, child_joints, link_map = robot.parent_joint, robot.child_joints, robot.link_map
    order: list[str] = []
    # Depth first from each root; a link's survivor is settled when it is reached, after
    # every link above it (lumping looks only at what was reached before).
    for root in robot.roots():
        stack = [root]
        while stack:
            cur = stack.pop()
            if cur in target_of:
                continue
            order.append(cur)
            joint = parent_joint.get(cur)
            target = cur
            if joint is not None and joint.type == "fixed" and joint.name not in preserved:
                up = target_of.get(joint.parent) if joint.parent is not None else None
                if up is not None and up != "world":
                    target = up
            target_of[cur] = target
            kids = child_joints.get(cur)
            if kids:
                for j in reversed(kids):
                    c = j.child
                    # a joint to a missing link (SK202) adds none
                    if c is not None and c in link_map and parent_joint.get(c) is j:
                        stack.append(c)
    for name in link_map:
        if name not in target_of:
            target_of[name] = name
    for name, target in target_of.items():
        link = link_map.get(name)
        mass = 0.0
        if link is not None:
            inertial = link.inertial
            if inertial is not None and inertial.mass is not None:
                mass = inertial.mass
        mass_of[target] = mass_of.get(target, 0.0) + mass
    _create_sdf(robot, conv, order)
    return conv


def _create_sdf(robot: Robot, conv: Conversion, order: list[str]) -> None:
    """CreateSDF: walk surviving links from each root; a massless one drops its subtree,
    except one fixed to 'world' (``uncreated``: see the module doc)."""
    target_of, mass_of, dropped = conv.target_of, conv.mass_of, conv.dropped
    parent_joint, preserved = robot.parent_joint, conv.preserved_joints
    for name in order:
        if target_of[name] != name or name in dropped:
            continue
        joint = parent_joint.get(name)
        if joint is not None and joint.parent is not None:
            parent_target = target_of.get(joint.parent, joint.parent)
            if parent_target in dropped and dropped[parent_target] not in conv.uncreated:
                dropped[name] = dropped[parent_target]
                continue
        if name == "world" and joint is None:
            continue
        if abs(mass_of.get(name, 0.0)) <= MASS_EPSILON:
            dropped[name] = name
            if (
                joint is not None
                and joint.type == "fixed"
                and joint.name not in preserved
                and joint.parent == "world"
            ):
                conv.uncreated.add(name)
    for name in order:  # lumped links follow their survivor
        target = target_of[name]
        if target != name and target in dropped:
            dropped[name] = dropped[target]
