"""Which simulator a sensor added without ``--sim`` is written for, and how.

Order: ``--sim`` (or the settings file's ``target``) > the expression the robot's other
macro calls pass (``sim="$(arg sim)"``: the new call passes the same, so the robot keeps
one switch) > what the robot's plugins and sensors say (what ``--target auto`` sees,
:func:`sensorkit.model.targets.robot_simulator`) > the macro's own default (``classic``),
with a note naming ``--sim``. ``gz_version`` follows the same order; the other calls'
value is taken when they all pass the same one.

The values returned are literals (what the expression gives with the file's default or
``--arg`` values): the fragment is expanded and validated with them.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from lxml import etree

from sensorkit.edit.kinds import XACRO_NS
from sensorkit.model.targets import GZ_TARGETS as GZ_VERSIONS

if TYPE_CHECKING:
    from sensorkit.model import Robot

SIMS = ("classic", "gz", "none")  # the macros' sim values (sensorkit.generate.spec.SIMS)
# xacro's own elements: never a call of a user's macro.
_XACRO_BUILTINS = frozenset(
    {"include", "arg", "property", "macro", "if", "unless", "insert_block", "element", "attribute"}
)
_ARG_EXPR = re.compile(r"^\$\(arg ([A-Za-z_][A-Za-z0-9_]*)\)$")


@dataclass
class SimChoice:
    """``values``: the literal ``sim``/``gz_version`` for the macro (absent: its default);
    ``expressions``: attribute -> the xacro expression to write instead of the literal."""

    values: dict[str, str] = field(default_factory=dict)
    expressions: dict[str, str] = field(default_factory=dict)
    origin: str = ""  # where the simulator came from, when --sim did not say (one line)
    notes: list[str] = field(default_factory=list)


def sibling_values(root: etree._Element | None, key: str) -> set[str]:
    """The values of attribute ``key`` on the macro calls directly under the root
    (not inside macro definitions, where ``${sim}`` means the macro's own parameter)."""
    if root is None:
        return set()
    out: set[str] = set()
    for el in root:
        if not isinstance(el.tag, str):
            continue
        qname = etree.QName(el)
        if qname.namespace != XACRO_NS or qname.localname in _XACRO_BUILTINS:
            continue
        value = el.get(key)
        if value is not None:
            out.add(value)
    return out


def _arg_default(root: etree._Element, name: str) -> str | None:
    for el in root:
        if (
            isinstance(el.tag, str)
            and etree.QName(el).namespace == XACRO_NS
            and etree.QName(el).localname == "arg"
            and el.get("name") == name
        ):
            default = el.get("default")
            return None if default is None else str(default)
    return None


def resolve_expression(
    expression: str, root: etree._Element | None, args: Mapping[str, str]
) -> str | None:
    """What ``$(arg NAME)`` gives: ``--arg NAME:=...``, else the file's ``<xacro:arg>``
    default (a literal one). None for any other expression."""
    match = _ARG_EXPR.match(expression.strip())
    if match is None or root is None:
        return None
    name = match.group(1)
    value = args.get(name)
    if value is None:
        value = _arg_default(root, name)
    if value is None or "$" in value:
        return None
    return value


def _shared(root: etree._Element | None, key: str) -> str | None:
    values = sibling_values(root, key)
    return next(iter(values)) if len(values) == 1 else None


def choose_simulator(
    params: Mapping[str, str],
    robot: Robot,
    root: etree._Element | None,
    args: Mapping[str, str],
) -> SimChoice:
    """Decide ``sim`` and ``gz_version`` for a new call (see the module doc).

    ``root`` is the parsed xacro file (None for plain URDF: no expressions there).
    """
    from sensorkit.model.targets import robot_simulator

    out = SimChoice()
    given = params.get("sim")
    shared = _shared(root, "sim")
    expr = shared if shared is not None and "$" in shared else None
    expr_value = resolve_expression(expr, root, args) if expr is not None else None
    if expr is not None and expr_value not in SIMS:
        expr = expr_value = None  # an expression sensorkit cannot evaluate: not copied
    evidence = robot_simulator(robot)
    sim: str | None
    if given is not None:
        sim = given
        if expr is not None and expr_value == given:
            out.expressions["sim"] = expr
            out.origin = f'sim="{expr}" as the robot\'s other sensors (it gives {given} here)'
        elif expr is not None:
            out.notes.append(
                f'the robot\'s other sensors pass sim="{expr}" ({expr_value} here); '
                f"this one is written for {given} whatever the argument says"
            )
    elif expr is not None and expr_value is not None:
        sim = expr_value
        out.expressions["sim"] = expr
        out.origin = f'sim="{expr}" as the robot\'s other sensors (it gives {expr_value} here)'
    elif evidence is not None:
        sim = evidence[0]
    else:
        sim = None
        out.origin = (
            "sim classic, the macro's default: the robot has no simulator plugin or sensor "
            "to take it from; pass --sim gz (and --gz-version) for Gazebo Sim, --sim none "
            "for links only"
        )
    if sim is not None:
        out.values["sim"] = sim
    _choose_gz_version(out, params, root, args, evidence)
    if given is None and expr is None and evidence is not None:
        version = params.get("gz_version") or out.values.get("gz_version")
        said = f" ({version})" if sim == "gz" and version else ""
        out.origin = (
            f"sim {sim}{said} from the robot's other plugins and sensors "
            f"(what --target auto sees: {evidence[2]}); --sim chooses another"
        )
    return out


def _choose_gz_version(
    out: SimChoice,
    params: Mapping[str, str],
    root: etree._Element | None,
    args: Mapping[str, str],
    evidence: tuple[str, str | None, str] | None,
) -> None:
    if "gz_version" in params or not (out.values.get("sim") == "gz" or "sim" in out.expressions):
        return
    shared = _shared(root, "gz_version")
    if shared is not None and "$" in shared:
        value = resolve_expression(shared, root, args)
        if value in GZ_VERSIONS:
            out.values["gz_version"] = value
            out.expressions["gz_version"] = shared
            return
    elif shared in GZ_VERSIONS:
        out.values["gz_version"] = shared
        return
    if out.values.get("sim") == "gz" and evidence is not None and evidence[1] is not None:
        out.values["gz_version"] = evidence[1]
