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


def _walk(root: etree._Element) -> Iterator[tuple[etree._Element, str | None]]:
    """(element, enclosing link name) for every element of links and joints."""
    for top in root:
        tag = local(top)
        if tag not in ("link", "joint"):
            continue
        name = top.get("name")
        for el in top.iter():
            if isinstance(el.tag, str):
                yield el, name if tag == "link" else None


@rule(
    "SK105",
    "warning",
    "unknown or misplaced element/attribute that URDF parsers silently ignore "
    "(`<joint>` inside `<link>`, `<intertial>`, `<mass values=...>`, `<gazebo>` inside `<link>`)",
)
def unknown_elements(ctx: Context) -> Iterator[Finding]:
    for el, link in _walk(ctx.robot.document.root):
        tag = local(el)
        parent = el.getparent()
        ptag = local(parent) if parent is not None else ""
        # Only check inside elements whose content urdfdom defines.
        if ptag in ALLOWED_CHILDREN and tag not in ALLOWED_CHILDREN[ptag]:
            hint = HINTS.get(tag)
            if hint is None:
                close = difflib.get_close_matches(tag, sorted(ALLOWED_CHILDREN[ptag]), n=1, cutoff=0.7)
                hint = (
                    f"did you mean <{close[0]}>?"
                    if close
                    else f"<{ptag}> takes only " + ", ".join(f"<{c}>" for c in sorted(ALLOWED_CHILDREN[ptag]))
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
        allowed = ALLOWED_ATTRS.get(tag)
        if allowed is None or (ptag not in ALLOWED_CHILDREN and tag not in ("link", "joint")):
            continue
        for attr in el.attrib:
            if attr == LOC_ATTR or attr.startswith("{"):
                continue
            if attr not in allowed:
                close = difflib.get_close_matches(attr, sorted(allowed), n=1, cutoff=0.6)
                yield ctx.finding(
                    "SK105",
                    Severity.WARNING,
                    f"attribute {attr}=\"{el.get(attr)}\" on <{tag}> is silently ignored",
                    el,
                    link=link,
                    fix=f"write {close[0]}=\"...\"" if close else f"<{tag}> takes " + ", ".join(sorted(allowed)),
                )
