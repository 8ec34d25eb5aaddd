"""The xacro args a robot is given but never declares or reads, and arg values with white
space: xacro ignores an undeclared ``name:=value`` without a word (xacro 2.0.8: the
command line's args go into ``substitution_args_context['arg']`` whether a file declares
them or not), so a misspelt ``gazebo:=`` leaves the robot on its default. sensorkit does
the same, as ROS's own tool does, and says so in one SK102 warning with the closest name.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from pathlib import Path

from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.base.suggest import closest

_DECLARED = re.compile(rb"<\s*[\w.-]+:arg\b[^>]*?\bname\s*=\s*[\"']([^\"']+)[\"']")
_READ = re.compile(rb"\$\(\s*arg\s+([^\s)]+)\s*\)")


def robot_args(texts: Iterable[bytes]) -> set[str]:
    """The arg names the texts declare (``<xacro:arg name=...>``) or read (``$(arg X)``)."""
    names: set[str] = set()
    for text in texts:
        names.update(m.decode(errors="replace") for m in _DECLARED.findall(text))
        names.update(m.decode(errors="replace") for m in _READ.findall(text))
    return names


def file_texts(
    first: bytes, files: Iterable[str], overlay: Mapping[str, bytes] | None
) -> list[bytes]:
    """The top file's bytes and those of every file the expansion read (as the editor
    holds them when ``overlay`` has them); a file gone since is left out."""
    texts = [first]
    for name in files:
        if overlay and name in overlay:
            texts.append(overlay[name])
            continue
        try:
            texts.append(Path(name).read_bytes())
        except OSError:
            continue
    return texts


def arg_findings(where: str, args: Mapping[str, str], known: set[str]) -> list[Finding]:
    """SK102 warnings: each given arg no file declares or reads, with the closest name."""
    found = []
    for name, value in args.items():
        if name in known:
            continue
        best = closest(name, sorted(known))
        hint = f" (did you mean '{best[0]}'?)" if best else ""
        args_list = ", ".join(sorted(known)[:12]) or "none"
        found.append(
            Finding(
                "SK102",
                Severity.WARNING,
                f"arg {name}:={value} is given, but no file of the robot declares or reads "
                f"'{name}'{hint}: xacro ignores it, and so the robot is checked without it",
                SourceRef(where, None),
                fix=(f"pass {best[0]}:={value}" if best else "check the spelling")
                + f" (the robot's args: {args_list})",
            )
        )
    return found


def _joined(value: str) -> str:
    return re.sub(r"\s+", "_", value.strip())


def space_findings(where: str, args: Mapping[str, str], link_names: Iterable[str]) -> list[Finding]:
    """SK102 warnings: an arg value holding white space that ends up in link names (a
    quoted ``namespace:='my robot'``): no ROS name or TF frame_id tool expects one."""
    spaced = {n: v for n, v in args.items() if v.strip() and re.search(r"\s", v.strip())}
    if not spaced:
        return []
    names = list(link_names)
    found = []
    for name, value in spaced.items():
        hit = [link for link in names if value.strip() in link]
        if not hit:
            continue
        found.append(
            Finding(
                "SK102",
                Severity.WARNING,
                f"arg {name}:={value!r} holds white space, which ends up in link names "
                f"({', '.join(repr(h) for h in hit[:3])}): frame_ids and the topic names built "
                "from them are not valid ROS names with white space in them",
                SourceRef(where, None),
                fix=f"pass {name}:={_joined(value)} (no white space)",
            )
        )
    return found
