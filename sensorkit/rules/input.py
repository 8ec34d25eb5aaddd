"""SK1xx: input and expansion. SK101..SK103 come from loading; SK104/SK105 read the model."""

from __future__ import annotations

import difflib
from collections.abc import Iterator

from lxml import etree

from sensorkit.findings import Finding, Severity
from sensorkit.loading.xacro_expand import LOC_ATTR
from sensorkit.model.robot import local
from sensorkit.rules.base import Context, declare, rule

declare("SK101", "error", "XML is well-formed; report file:line:column", "all parsers")
declare(
    "SK102",
    "error",
    "xacro expands; report the include and macro stack, with line where possible",
    "xacro (no line)",
)
declare(
    "SK103",
    "error",
    "`$(find pkg)` / `package://pkg/...` resolve; list every place searched",
    "xacro at run time",
)

# What urdfdom reads inside each element; anything else is silently ignored by it.
ALLOWED_CHILDREN: dict[str, set[str]] = {
    "link": {"inertial", "visual", "collision"},
    "inertial": {"origin", "mass", "inertia"},
    "visual": {"origin", "geometry", "material"},
    "collision": {"origin", "geometry"},
    "joint": {
        "origin", "parent", "child", "axis", "calibration", "dynamics", "limit",
        "safety_controller", "mimic",
    },
}
ALLOWED_ATTRS: dict[str, set[str]] = {
    "mass": {"value"},
    "inertia": {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"},
    "origin": {"xyz", "rpy"},
    "limit": {"lower", "upper", "effort", "velocity"},
    "axis": {"xyz"},
    "parent": {"link"},
    "child": {"link"},
    "link": {"name", "type"},
    "joint": {"name", "type"},
    "dynamics": {"damping", "friction"},
    "mimic": {"joint", "multiplier", "offset"},
    "safety_controller": {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"},
    "calibration": {"rising", "falling", "reference_position"},
}
HINTS = {
    "gazebo": "<gazebo> inside <link> is ignored: put it at robot level as <gazebo reference=\"LINK\">",
    "joint": "<joint> inside <link> is ignored: joints go directly under <robot>",
    "sensor": "URDF <link> has no <sensor>: declare it in <gazebo reference=\"LINK\"><sensor ...>",
}


@rule("SK104", "warning", "files referenced (meshes, includes) exist", "yourdfpy (log only)")
def missing_files(ctx: Context) -> Iterator[Finding]:
    for miss in ctx.missing_files:
        yield ctx.finding(
            "SK104",
            Severity.WARNING,
            f"{miss.uri!r} does not resolve: {miss.reason}",
            miss.source,
            link=miss.link,
            fix="fix the path or the package name, or pass --package-path for the package",
        )


@rule(
    "SK105",
    "warning",
    "unknown or misplaced element/attribute that URDF parsers silently ignore "
    "(`<joint>` inside `<link>`, `<intertial>`, `<mass values=...>`, `<gazebo>` inside `<link>`)",
)
def unknown_elements(ctx: Context) -> Iterator[Finding]:
    for top in ctx.robot.document.root.iterchildren("link", "joint"):
        name = top.get("name")
        link = name if top.tag == "link" else None
        if not ALLOWED_ATTRS[top.tag].issuperset(top.keys()):  # type: ignore[index]
            yield from _attrs(ctx, top, link)
        yield from _children(ctx, top, link)


def _children(ctx: Context, parent: etree._Element, link: str | None) -> Iterator[Finding]:
    """Findings for the children of ``parent``, an element whose content urdfdom defines."""
    ptag = parent.tag
    allowed = ALLOWED_CHILDREN[ptag]  # type: ignore[index]
    for el in parent:
        tag = el.tag
        if not isinstance(tag, str):
            continue
        if tag not in allowed:
            tag = local(el)
            hint = HINTS.get(tag)
            if hint is None:
                close = difflib.get_close_matches(tag, sorted(allowed), n=1, cutoff=0.7)
                hint = (
                    f"did you mean <{close[0]}>?"
                    if close
                    else f"<{ptag}> takes only " + ", ".join(f"<{c}>" for c in sorted(allowed))
                )
            yield ctx.finding(
                "SK105",
                Severity.WARNING,
                f"<{tag}> inside <{ptag}> is silently ignored by URDF parsers",
                el,
                link=link,
                fix=hint,
            )
            continue
        allowed_attrs = ALLOWED_ATTRS.get(tag)
        if allowed_attrs is not None and not allowed_attrs.issuperset(el.keys()):
            yield from _attrs(ctx, el, link)
        if tag in ALLOWED_CHILDREN:
            yield from _children(ctx, el, link)


def _attrs(ctx: Context, el: etree._Element, link: str | None) -> Iterator[Finding]:
    tag = el.tag
    allowed = ALLOWED_ATTRS[tag]  # type: ignore[index]
    for attr in el.attrib:
        if attr in allowed or attr == LOC_ATTR or attr.startswith("{"):
            continue
        close = difflib.get_close_matches(attr, sorted(allowed), n=1, cutoff=0.6)
        yield ctx.finding(
            "SK105",
            Severity.WARNING,
            f"attribute {attr}=\"{el.get(attr)}\" on <{tag}> is silently ignored",
            el,
            link=link,
            fix=f"write {close[0]}=\"...\"" if close else f"<{tag}> takes " + ", ".join(sorted(allowed)),
        )
