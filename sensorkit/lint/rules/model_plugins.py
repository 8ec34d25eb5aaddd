"""SK616: a model-level plugin looks up a link or joint that fixed-joint lumping removed.

Plugins such as ROS 1's ``gazebo_ros_imu`` find their body by the name in ``<bodyName>``
and return without publishing when Gazebo has no link of that name; a link that hangs on a
fixed joint is merged into its parent when the URDF is converted, so the name is gone. The
table of such lookups, with sources, is sensorkit.knowledge.link_lookups.
"""

from __future__ import annotations

from collections.abc import Iterator

from sensorkit.base.consequence import Consequence, Role
from sensorkit.base.findings import Finding
from sensorkit.knowledge.link_lookups import lookups_of
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.frames import ros_generation
from sensorkit.model.parse import local
from sensorkit.model.targets import is_gz

# p3d's frameName: these report in the world and look up no link (gazebo_ros_p3d.cpp:171-176,
# noetic-devel f9e1a46).
_WORLD_NAMES = frozenset({"/world", "world", "/map", "map"})


def _removed(ctx: Context, kind: str, name: str) -> str | None:
    """Why Gazebo has no link/joint ``name`` after lumping (None: it has one, or the name is
    not one of the URDF's, which sensorkit then cannot judge)."""
    robot, conv = ctx.robot, ctx.conversion
    if kind == "link":
        if name not in robot.link_map:
            return None
        if name in conv.dropped:
            return f"link {name!r} is dropped when the URDF is converted (with massless link {conv.dropped[name]!r})"
        if conv.is_lumped(name):
            joint = robot.parent_joint.get(name)
            via = f" by fixed joint {joint.name!r}" if joint is not None else ""
            return f"link {name!r} is merged into {conv.survivor(name)!r}{via} (fixed-joint lumping)"
        return None
    joint = robot.joint_map.get(name)
    if joint is None or joint.type != "fixed" or joint.child is None:
        return None
    if conv.is_lumped(joint.child):
        return (
            f"fixed joint {name!r} is removed when lumping merges {joint.child!r} into "
            f"{conv.survivor(joint.child)!r}"
        )
    return None


@rule(
    "SK616",
    "error",
    "a model-level plugin sensorkit knows looks up a link or joint by name (ROS 1 gazebo_ros_imu "
    "<bodyName>, p3d, f3d, ft_sensor) that fixed-joint lumping removes: it finds none and "
    "publishes nothing",
)
def lumped_lookup(ctx: Context) -> Iterator[Finding]:
    if is_gz(ctx.target):
        return
    ros = ros_generation(ctx.target)
    for p in ctx.robot.model_plugins:
        for lk in lookups_of(p.filename, ros):
            if lk.unless is not None and p.param(lk.unless) is not None:
                continue
            el = next((c for c in p.element if local(c) == lk.param), None)
            name = (el.text or "").strip() if el is not None else ""
            if not name or (lk.param == "frameName" and name in _WORLD_NAMES):
                continue
            why = _removed(ctx, lk.kind, name)
            if why is None:
                continue
            joint = name if lk.kind == "joint" else getattr(ctx.robot.parent_joint.get(name), "name", "JOINT")
            keep = f'<gazebo reference="{joint}"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
            fix = (
                f"keep the joint: add {keep}"
                if lk.kind == "joint"
                else f"name the link it is merged into ({ctx.conversion.survivor(name)!r}), or keep it: add {keep}"
            )
            yield ctx.judged(
                "SK616",
                Consequence(Role.OUTPUT, f"{lk.kind} {name}", None),
                f"plugin {p.name!r} ({p.filename}) looks up {lk.kind} <{lk.param}>{name}</{lk.param}>, "
                f"but {why}: Gazebo has none of that name, so the plugin stops at load and publishes "
                f"no {lk.publishes} ({lk.source})",
                el,
                fix=fix,
            )
