"""SK301: a placeholder ``<inertial>`` for a link Gazebo would drop (unsafe)."""

from __future__ import annotations

from sensorkit.base.findings import Finding
from sensorkit.fix.registry import Fix, FixContext, fixer
from sensorkit.fix.source import NotFixable

__all__ = ["placeholder_inertial"]

_PLACEHOLDER = [
    (0, "<inertial>"),
    (
        1,
        "<!-- sensorkit fix: a placeholder so Gazebo keeps this link (10 g, inertia of a 3 cm cube); put in the real mass and inertia -->",
    ),
    (1, '<mass value="0.01"/>'),
    (1, '<inertia ixx="1.5e-06" ixy="0" ixz="0" iyy="1.5e-06" iyz="0" izz="1.5e-06"/>'),
    (0, "</inertial>"),
]


@fixer(
    "SK301",
    "unsafe",
    "give a link without `<inertial>` a small documented placeholder (10 g, a 3 cm cube's inertia)",
)
def placeholder_inertial(fx: FixContext, f: Finding) -> Fix:
    link = fx.robot.link_map.get(f.link or "")
    if link is None:
        raise NotFixable(f"link {f.link!r} not found")
    if link.inertial is not None:
        raise NotFixable(
            f"link {link.name!r} has an <inertial> with zero mass: put in its real mass"
        )
    w = fx.written(link.element)
    return Fix(
        f,
        (w.file.insert_child(w.tag, _PLACEHOLDER),),
        f"add a placeholder <inertial> (10 g) to {link.name!r}",
        safe=False,
    )
