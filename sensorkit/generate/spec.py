"""The robot YAML that ``sensorkit new`` reads, checked strictly, with line numbers.

::

    name: my_robot                 # required; lowercase letters, digits, underscores
    package: my_robot_description  # default <name>_description
    version: 0.1.0                 # package.xml fields, all optional
    description: "..."
    maintainer: {name: "...", email: "..."}
    license: Apache-2.0
    base: diff_drive               # a template in templates/ (diff_drive, skid_steer)
    base_params: {chassis_length: 0.5}
    sim: gz                        # classic | gz | none (default gz)
    gz_version: harmonic           # fortress | harmonic | jetty (default harmonic)
    namespace: ""                  # ROS namespace (and gz topic prefix) of every sensor
    sensors:
      - type: camera               # a macro in macros/ (camera, depth_camera, ...)
        name: front_camera         # required, unique
        parent: base_link          # default base_link; a base link or another sensor's link
        xyz: [0.25, 0, 0.1]        # default [0, 0, 0]
        rpy: [0, 0, 0]             # default [0, 0, 0]
        options: {width: 640}      # the macro's parameters

The file is read with ``yaml.compose`` so every mistake (unknown key, wrong type,
unknown sensor type, duplicate name, missing parent, malformed YAML) is reported as
one ``FILE:LINE:COLUMN: where: what`` line and no partial robot is ever produced.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NoReturn

import yaml

from sensorkit.base.errors import InputError
from sensorkit.generate.catalog import (
    SENSOR_KEY_PARAMS,
    SHARED_PARAMS,
    MacroInfo,
    Param,
    base_templates,
    sensor_macros,
)
from sensorkit.model.targets import GZ_TARGETS

SIMS = ("classic", "gz", "none")
GZ_VERSIONS = GZ_TARGETS

TOP_KEYS = (
    "name",
    "package",
    "version",
    "description",
    "maintainer",
    "license",
    "base",
    "base_params",
    "sim",
    "gz_version",
    "namespace",
    "sensors",
)
SENSOR_KEYS = ("type", "name", "parent", "xyz", "rpy", "options")
MAINTAINER_KEYS = ("name", "email")

_PACKAGE = re.compile(r"^[a-z][a-z0-9_]*$")  # REP 144
_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
_NAMESPACE = re.compile(r"^/?([A-Za-z][A-Za-z0-9_]*)(/[A-Za-z][A-Za-z0-9_]*)*/?$")
_VERSION = re.compile(r"^\d+\.\d+\.\d+$")
_EMAIL = re.compile(r"^[^@\s<>\"]+@[^@\s<>\"]+$")
_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")
_EXPRESSION = re.compile(r"^\$\{[^{}]+\}$")
_SAFE_TEXT = re.compile(r"^[^<>&\"'\x00-\x1f]*$")


@dataclass(frozen=True)
class Mark:
    """A place in the robot YAML (1-based line and column)."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


@dataclass
class SensorSpec:
    """One checked ``sensors:`` entry; values already in xacro attribute text."""

    type: str
    name: str
    parent: str
    xyz: str
    rpy: str
    options: dict[str, str]
    mark: Mark
    marks: dict[str, Mark] = field(default_factory=dict)

    @property
    def macro(self) -> MacroInfo:
        return sensor_macros()[self.type]


@dataclass
class RobotSpec:
    """A checked robot YAML."""

    path: Path
    name: str
    package: str
    version: str
    description: str
    maintainer_name: str
    maintainer_email: str
    license: str
    base: str
    base_params: dict[str, str]
    sim: str
    gz_version: str
    namespace: str
    sensors: list[SensorSpec]
    marks: dict[str, Mark] = field(default_factory=dict)

    @property
    def base_macro(self) -> MacroInfo:
        return base_templates()[self.base]

    def sensor_named(self, name: str) -> SensorSpec | None:
        return next((s for s in self.sensors if s.name == name), None)


def _kind_name(node: yaml.Node, value: Any = None) -> str:
    if isinstance(node, yaml.MappingNode):
        return "a mapping"
    if isinstance(node, yaml.SequenceNode):
        return "a list"
    if value is None:
        return "nothing (null)"
    if isinstance(value, bool):
        return f"a boolean ({value!r})"
    if isinstance(value, (int, float)):
        return f"a number ({value!r})"
    if isinstance(value, str):
        return f"a string ({value!r})"
    return f"a {type(value).__name__}"


def _suggest(word: str, choices: Sequence[str]) -> str:
    close = difflib.get_close_matches(word, list(choices), n=1)
    return f"; did you mean {close[0]!r}?" if close else ""


def _fmt_number(value: float | int) -> str:
    if isinstance(value, int):
        return str(value)
    if value == int(value) and abs(value) < 1e15:
        return f"{value:.1f}" if abs(value) < 1e6 else repr(value)
    return repr(value)


class _Reader:
    """Walks composed YAML nodes; every failure names the file, line and column."""

    def __init__(self, file: str) -> None:
        self.file = file
        self._ctor = yaml.SafeLoader("")

    def mark(self, node: yaml.Node) -> Mark:
        m = node.start_mark
        return Mark(self.file, m.line + 1, m.column + 1)

    def fail(self, node: yaml.Node, where: str, problem: str) -> NoReturn:
        msg = f"{self.mark(node)}: {where}: {problem}" if where else f"{self.mark(node)}: {problem}"
        raise InputError(msg)

    def value(self, node: yaml.Node, where: str) -> Any:
        if not isinstance(node, yaml.ScalarNode):
            self.fail(node, where, f"expected a single value, got {_kind_name(node)}")
        try:
            return self._ctor.construct_object(node, deep=True)
        except yaml.YAMLError as exc:
            self.fail(node, where, f"cannot read this value ({exc})")

    def mapping(
        self, node: yaml.Node, where: str, known: Sequence[str] | None, what: str = "key"
    ) -> dict[str, tuple[yaml.Node, yaml.Node]]:
        if not isinstance(node, yaml.MappingNode):
            value = self.value(node, where) if isinstance(node, yaml.ScalarNode) else None
            self.fail(node, where, f"expected a mapping, got {_kind_name(node, value)}")
        out: dict[str, tuple[yaml.Node, yaml.Node]] = {}
        for key_node, value_node in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                self.fail(key_node, where, "merge keys (<<) are not supported here")
            key = self.value(key_node, where)
            if not isinstance(key, str):
                self.fail(key_node, where, f"keys must be strings, got {_kind_name(key_node, key)}")
            here = f"{where}.{key}" if where else key
            if key in out:
                first = self.mark(out[key][0])
                self.fail(key_node, here, f"duplicate {what} (first given at line {first.line})")
            if known is not None and key not in known:
                self.fail(
                    key_node,
                    here,
                    f"unknown {what} {key!r} (known: {', '.join(known)}){_suggest(key, known)}",
                )
            out[key] = (key_node, value_node)
        return out

    def string(
        self,
        node: yaml.Node,
        where: str,
        *,
        pattern: re.Pattern[str] | None = None,
        rule: str = "",
        choices: Sequence[str] | None = None,
        allow_empty: bool = False,
    ) -> str:
        value = self.value(node, where)
        if not isinstance(value, str):
            self.fail(node, where, f"expected a string, got {_kind_name(node, value)}")
        if choices is not None and value not in choices:
            self.fail(
                node,
                where,
                f"unknown value {value!r} (expected one of: {', '.join(choices)})"
                + _suggest(value, choices),
            )
        if value == "" and allow_empty:
            return value
        if value == "" and not allow_empty:
            self.fail(node, where, "must not be empty")
        if pattern is not None and not pattern.match(value):
            self.fail(node, where, f"{value!r} is not {rule}")
        return value

    def number_text(self, node: yaml.Node, where: str, *, whole: bool = False) -> str:
        """A number (or a ``${...}`` xacro expression) as attribute text."""
        value = self.value(node, where)
        if isinstance(value, str) and _NUMBER.match(value.strip()):
            value = float(value) if not re.match(r"^[-+]?\d+$", value.strip()) else int(value)
        if isinstance(value, str) and _EXPRESSION.match(value.strip()) and not whole:
            if not _SAFE_TEXT.match(value):
                self.fail(node, where, "the expression contains characters XML cannot hold")
            return value.strip()
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            expected = "a whole number" if whole else "a number (or a ${...} xacro expression)"
            self.fail(node, where, f"expected {expected}, got {_kind_name(node, value)}")
        if not math.isfinite(value):
            self.fail(node, where, f"expected a finite number, got {value!r}")
        if whole:
            if isinstance(value, float) and not value.is_integer():
                self.fail(node, where, f"expected a whole number, got {value!r}")
            return str(int(value))
        return _fmt_number(value)

    def vector(self, node: yaml.Node, where: str, size: int) -> str:
        if isinstance(node, yaml.SequenceNode):
            if len(node.value) != size:
                self.fail(node, where, f"expected a list of {size} numbers, got {len(node.value)}")
            return " ".join(
                self.number_text(item, f"{where}[{i}]") for i, item in enumerate(node.value)
            )
        value = self.value(node, where)
        if isinstance(value, str):
            parts = value.split()
            if len(parts) == size and all(_NUMBER.match(p) for p in parts):
                return " ".join(_fmt_number(float(p)) for p in parts)
        self.fail(node, where, f"expected a list of {size} numbers, got {_kind_name(node, value)}")


def _param_text(reader: _Reader, node: yaml.Node, where: str, param: Param) -> str:
    if param.kind == "vector":
        return reader.vector(node, where, param.size)
    if param.kind == "bool":
        value = reader.value(node, where)
        if not isinstance(value, bool):
            reader.fail(node, where, f"expected true or false, got {_kind_name(node, value)}")
        return "true" if value else "false"
    if param.kind in ("int", "float"):
        whole = param.name in ("width", "height") or param.name.endswith("samples")
        return reader.number_text(node, where, whole=whole)
    value = reader.value(node, where)
    if isinstance(value, bool) or value is None or isinstance(value, (list, dict)):
        reader.fail(node, where, f"expected a string, got {_kind_name(node, value)}")
    text = str(value)
    if not _SAFE_TEXT.match(text):
        reader.fail(node, where, "the value contains characters XML cannot hold (< > & quotes)")
    return text


def _params(
    reader: _Reader,
    node: yaml.Node | None,
    where: str,
    macro: MacroInfo,
    *,
    what: str,
    marks: dict[str, Mark],
) -> dict[str, str]:
    if node is None or (isinstance(node, yaml.ScalarNode) and reader.value(node, where) is None):
        return {}
    settable = macro.settable()
    entries = reader.mapping(node, where, None, what="option")
    out: dict[str, str] = {}
    for key, (key_node, value_node) in entries.items():
        here = f"{where}.{key}"
        if key in SHARED_PARAMS:
            reader.fail(key_node, here, f"{key} is set once for the whole robot, at the top level")
        if key in SENSOR_KEY_PARAMS:
            reader.fail(key_node, here, f"give {key} as the sensor's own key, not as an option")
        if key not in settable:
            reader.fail(
                key_node,
                here,
                f"unknown {what} {key!r} for {macro.kind} (known: {', '.join(settable)})"
                + _suggest(key, settable),
            )
        out[key] = _param_text(reader, value_node, here, macro.params[key])
        marks[here] = reader.mark(value_node)
    return out


def _compose(path: Path, text: str, file: str) -> yaml.Node | None:
    loader = yaml.SafeLoader(text)
    try:
        return loader.get_single_node()
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        problem = exc.problem or exc.context or "malformed YAML"
        if exc.context and exc.problem:
            problem = f"{exc.problem} ({exc.context})"
        where = f"{file}:{mark.line + 1}:{mark.column + 1}" if mark else file
        msg = f"{where}: malformed YAML: {problem}"
        raise InputError(msg) from None
    except yaml.YAMLError as exc:
        msg = f"{file}: malformed YAML: {exc}"
        raise InputError(msg) from None
    finally:
        loader.dispose()


def parse_spec(
    text: str,
    path: Path,
    *,
    display: str | None = None,
    defaults: Mapping[str, str] | None = None,
) -> RobotSpec:
    """Check robot YAML ``text`` (read from ``path``) and return the robot it describes.

    Raises:
        InputError: one line, ``FILE:LINE:COLUMN: where: what``.
    """
    file = display or str(path)
    root = _compose(path, text, file)
    if root is None:
        msg = f"{file}:1:1: the file is empty; expected a mapping with name, base and sensors"
        raise InputError(msg)
    r = _Reader(file)
    top = r.mapping(root, "", TOP_KEYS)
    marks: dict[str, Mark] = {k: r.mark(v) for k, (_, v) in top.items()}

    def get(key: str) -> yaml.Node | None:
        return top[key][1] if key in top else None

    if "name" not in top:
        r.fail(root, "", "missing key 'name' (the robot's name, e.g. name: my_robot)")
    name = r.string(
        top["name"][1],
        "name",
        pattern=_PACKAGE,
        rule="a valid name (lowercase letters, digits and underscores, starting with a letter)",
    )
    node = get("package")
    package = (
        r.string(
            node,
            "package",
            pattern=_PACKAGE,
            rule="a valid ROS package name (REP 144: "
            "lowercase letters, digits and underscores, starting with a letter)",
        )
        if node is not None
        else f"{name}_description"
    )
    node = get("version")
    version = "0.1.0"
    if node is not None:
        raw = r.value(node, "version")
        if not isinstance(raw, str) or not _VERSION.match(raw):
            r.fail(node, "version", f"expected a version like 0.1.0, got {_kind_name(node, raw)}")
        version = raw
    node = get("description")
    description = (
        r.string(node, "description", pattern=_SAFE_TEXT, rule="plain text (no < > & or quotes)")
        if node is not None
        else f"Description of {name} with its sensors, generated by sensorkit."
    )
    maintainer_name, maintainer_email = "Your Name", "you@example.com"
    node = get("maintainer")
    if node is not None:
        m = r.mapping(node, "maintainer", MAINTAINER_KEYS)
        if "name" in m:
            maintainer_name = r.string(
                m["name"][1],
                "maintainer.name",
                pattern=_SAFE_TEXT,
                rule="plain text (no < > & or quotes)",
            )
        if "email" in m:
            maintainer_email = r.string(
                m["email"][1], "maintainer.email", pattern=_EMAIL, rule="an e-mail address"
            )
    node = get("license")
    license_ = (
        r.string(node, "license", pattern=_SAFE_TEXT, rule="plain text (no < > & or quotes)")
        if node is not None
        else "Apache-2.0"
    )

    bases = base_templates()
    node = get("base")
    base = r.string(node, "base", choices=sorted(bases)) if node is not None else "diff_drive"
    base_params = _params(
        r, get("base_params"), "base_params", bases[base], what="base parameter", marks=marks
    )

    defaults = defaults or {}  # from the settings file's target, when the YAML says nothing
    node = get("sim")
    sim = r.string(node, "sim", choices=SIMS) if node is not None else defaults.get("sim", "gz")
    node = get("gz_version")
    gz_version = defaults.get("gz_version", "harmonic")
    if node is not None:
        gz_version = r.string(node, "gz_version", choices=GZ_VERSIONS)
    node = get("namespace")
    namespace = ""
    if node is not None:
        raw = r.value(node, "namespace")
        if raw is not None:
            namespace = r.string(
                node,
                "namespace",
                pattern=_NAMESPACE,
                allow_empty=True,
                rule="a ROS namespace (names of letters, digits and underscores separated by /)",
            )
    namespace = namespace.strip("/")

    sensors = _sensors(r, get("sensors"), bases[base], marks)
    return RobotSpec(
        path=path,
        name=name,
        package=package,
        version=version,
        description=description,
        maintainer_name=maintainer_name,
        maintainer_email=maintainer_email,
        license=license_,
        base=base,
        base_params=base_params,
        sim=sim,
        gz_version=gz_version,
        namespace=namespace,
        sensors=sensors,
        marks=marks,
    )


def _sensors(
    r: _Reader, node: yaml.Node | None, base: MacroInfo, marks: dict[str, Mark]
) -> list[SensorSpec]:
    if node is None or (isinstance(node, yaml.ScalarNode) and r.value(node, "sensors") is None):
        return []
    if not isinstance(node, yaml.SequenceNode):
        value = r.value(node, "sensors") if isinstance(node, yaml.ScalarNode) else None
        r.fail(node, "sensors", f"expected a list of sensors, got {_kind_name(node, value)}")
    macros = sensor_macros()
    out: list[SensorSpec] = []
    names: dict[str, SensorSpec] = {}
    parent_nodes: dict[str, yaml.Node] = {}
    for i, item in enumerate(node.value):
        where = f"sensors[{i}]"
        entry = r.mapping(item, where, SENSOR_KEYS)
        if "type" not in entry:
            r.fail(item, where, f"missing key 'type' (one of: {', '.join(macros)})")
        stype = r.string(entry["type"][1], f"{where}.type", choices=list(macros))
        if "name" not in entry:
            r.fail(item, where, "missing key 'name' (e.g. name: front_camera)")
        sname = r.string(
            entry["name"][1],
            f"{where}.name",
            pattern=_IDENT,
            rule="a valid name (letters, digits and underscores, starting with a letter)",
        )
        if sname in names:
            first = names[sname].mark
            r.fail(
                entry["name"][1],
                f"{where}.name",
                f"duplicate sensor name {sname!r} (first used at line {first.line})",
            )
        smarks = {"name": r.mark(entry["name"][1]), "type": r.mark(entry["type"][1])}
        parent = "base_link"
        if "parent" in entry:
            parent = r.string(
                entry["parent"][1], f"{where}.parent", pattern=_IDENT, rule="a link name"
            )
            parent_nodes[sname] = entry["parent"][1]
            smarks["parent"] = r.mark(entry["parent"][1])
        xyz = rpy = "0 0 0"
        if "xyz" in entry:
            xyz = r.vector(entry["xyz"][1], f"{where}.xyz", 3)
        if "rpy" in entry:
            rpy = r.vector(entry["rpy"][1], f"{where}.rpy", 3)
        options = _params(
            r,
            entry["options"][1] if "options" in entry else None,
            f"{where}.options",
            macros[stype],
            what="option",
            marks=marks,
        )
        spec = SensorSpec(stype, sname, parent, xyz, rpy, options, r.mark(item), smarks)
        names[sname] = spec
        out.append(spec)

    # Links: the base's, and each sensor's; a name may be made only once.
    owner: dict[str, str] = {link: "the base" for link in base.link_patterns}
    for i, spec in enumerate(out):
        for link in spec.macro.links_for(spec.name):
            if link in owner:
                r.fail(
                    node.value[i],
                    f"sensors[{i}].name",
                    f"sensor {spec.name!r} would create link {link!r}, which {owner[link]} "
                    "already has; choose another name",
                )
            owner[link] = f"sensor {spec.name!r}"
    # Parents: an existing link, not the sensor's own, and no mounting loop.
    for i, spec in enumerate(out):
        pnode = parent_nodes.get(spec.name, node.value[i])
        own = spec.macro.links_for(spec.name)
        if spec.parent in own:
            r.fail(
                pnode,
                f"sensors[{i}].parent",
                f"{spec.parent!r} is a link of sensor {spec.name!r} itself",
            )
        if spec.parent not in owner:
            known = list(owner)
            r.fail(
                pnode,
                f"sensors[{i}].parent",
                f"no link {spec.parent!r} (links: {', '.join(known)})"
                + _suggest(spec.parent, known),
            )
    by_link = {link: s for s in out for link in s.macro.links_for(s.name)}
    for i, spec in enumerate(out):
        seen = {spec.name}
        cur = by_link.get(spec.parent)
        while cur is not None:
            if cur.name in seen:
                r.fail(
                    parent_nodes.get(spec.name, node.value[i]),
                    f"sensors[{i}].parent",
                    f"sensors are mounted on each other in a loop ({spec.name} -> ... -> "
                    f"{cur.name})",
                )
            seen.add(cur.name)
            cur = by_link.get(cur.parent)
    return out


def load_spec(path: Path, defaults: Mapping[str, str] | None = None) -> RobotSpec:
    """Read and check the robot YAML at ``path``.

    Raises:
        InputError: unreadable file or any mistake in it (one line with FILE:LINE:COLUMN).
    """
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        msg = f"{path}: no such file"
        raise InputError(msg) from None
    except IsADirectoryError:
        msg = f"{path}: is a folder, expected a robot YAML file"
        raise InputError(msg) from None
    except UnicodeDecodeError as exc:
        msg = f"{path}: not UTF-8 text ({exc.reason} at byte {exc.start})"
        raise InputError(msg) from None
    except OSError as exc:
        msg = f"{path}: cannot read ({exc.strerror})"
        raise InputError(msg) from None
    return parse_spec(text, path, defaults=defaults)
