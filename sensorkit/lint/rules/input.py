"""SK1xx: input and expansion. SK101..SK103 come from loading; SK104/SK105 read the model."""

from __future__ import annotations

import difflib
from collections.abc import Iterator

from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.lint.rules.base import Context, MissingFile, declare, rule
from sensorkit.model.parse import local
from sensorkit.model.urdf import ROBOT_CHILDREN, URDF_ATTRS, URDF_CHILDREN

# SDF: parse_sdf reports SK101 (sensorkit.loading.sdf_files); a .sdf.xacro expands first
declare(
    "SK101",
    "error",
    "XML is well-formed; report file:line:column; a UTF-16/32 file or a prefixed root "
    "(`<urdf:robot>`), which xacro and check_urdf refuse",
    "all parsers",
    ("urdf", "sdf"),
)
declare(
    "SK102",
    "error/warning",
    "xacro expands; report the include and macro stack, with line where possible (error); "
    "an arg given that no file declares or reads, which xacro ignores, with the closest name, "
    "and an arg value whose white space ends up in link names (warning)",
    "xacro (no line)",
    ("urdf", "sdf"),
)
declare(
    "SK103",
    "error/info",
    "`$(find pkg)` / `package://pkg/...` resolve; list every place searched; a package the "
    "robot uses found twice in a colcon `src/` or a `--package-path DIR`, which colcon "
    "refuses to build (error), or around a file in no workspace (info), naming both copies "
    "and the one read",
    "xacro at run time",
    ("urdf", "sdf"),  # SDF: package:// mesh URIs (an include's is SK107)
)

ALLOWED_CHILDREN = URDF_CHILDREN
ALLOWED_ATTRS = URDF_ATTRS
HINTS = {
    "gazebo": '<gazebo> inside <link> is ignored: put it at robot level as <gazebo reference="LINK">',
    "joint": "<joint> inside <link> is ignored: joints go directly under <robot>",
    "sensor": 'URDF <link> has no <sensor>: declare it in <gazebo reference="LINK"><sensor ...>',
}


@rule(
    "SK104",
    "warning",
    "files referenced (meshes, includes) exist",
    "yourdfpy (log only)",
    ("urdf", "sdf"),  # SDF: mesh URIs as gz-sim finds them (loading.sdf_files.resolve_mesh_uri)
)
def missing_files(ctx: Context) -> Iterator[Finding]:
    # One finding per cause: a macro called four times names one missing mesh at one line
    # four times (turtlebot4's standoffs); the finding says how many uses it stands for.
    uses: dict[tuple[str, SourceRef], list[MissingFile]] = {}
    for miss in ctx.missing_files:
        uses.setdefault((miss.uri, miss.source), []).append(miss)
    for group in uses.values():
        miss = group[0]
        more = f" ({len(group)} uses of it)" if len(group) > 1 else ""
        yield ctx.finding(
            "SK104",
            Severity.WARNING,
            f"{miss.uri!r} does not resolve{more}: {miss.reason}",
            miss.source,
            link=miss.link,
            fix="fix the path or the package name, or pass --package-path for the package",
        )


@rule(
    "SK105",
    "warning",
    "unknown or misplaced element/attribute that URDF parsers silently ignore "
    "(`<joint>` inside `<link>`, `<intertial>`, `<mass values=...>`, `<gazebo>` inside `<link>`, "
    "a tag directly under `<robot>` that nothing reads)",
)
def unknown_elements(ctx: Context) -> Iterator[Finding]:
    for stray in ctx.robot.strays:
        el, ptag = stray.element, stray.parent_tag
        if stray.attr is None:
            tag = local(el)
            allowed = sorted(ALLOWED_CHILDREN[ptag])
            hint = HINTS.get(tag)
            if hint is None:
                close = difflib.get_close_matches(tag, allowed, n=1, cutoff=0.7)
                hint = (
                    f"did you mean <{close[0]}>?"
                    if close
                    else f"<{ptag}> takes only " + ", ".join(f"<{c}>" for c in allowed)
                )
            if ptag == "robot":
                hint = (
                    f"URDF reads only {', '.join(f'<{c}>' for c in sorted(ROBOT_CHILDREN))} here: "
                    "if a macro or xacro:element produced this tag, make it produce the element you meant"
                )
            yield ctx.finding(
                "SK105",
                Severity.WARNING,
                f"<{tag}> directly under <robot> is read by no URDF parser or simulator: whatever it holds is lost"
                if ptag == "robot"
                else f"<{tag}> inside <{ptag}> is silently ignored by URDF parsers",
                el,
                link=stray.link,
                fix=hint,
            )
            continue
        allowed = sorted(ALLOWED_ATTRS[ptag])
        close = difflib.get_close_matches(stray.attr, allowed, n=1, cutoff=0.6)
        yield ctx.finding(
            "SK105",
            Severity.WARNING,
            f'attribute {stray.attr}="{el.get(stray.attr)}" on <{ptag}> is silently ignored',
            el,
            link=stray.link,
            fix=f'write {close[0]}="..."' if close else f"<{ptag}> takes " + ", ".join(allowed),
        )


@rule(
    "SK106",
    "info",
    "a launch file sensorkit could not read (it does not parse, is too large, includes itself, "
    "or names what cannot be resolved): what it starts is unknown, so no finding rests on it",
)
def unreadable_launch(ctx: Context) -> Iterator[Finding]:
    if ctx.launch is None:
        return
    for problem in ctx.launch.problems:
        yield ctx.finding(
            "SK106",
            Severity.INFO,
            f"{problem.file}: could not read: {problem.message}",
            SourceRef(problem.file, problem.line),
            fix="pass the launch files to read with --launch, or fix this one",
        )
