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

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

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
from sensorkit.generate.reader import SAFE_TEXT, Mark, Reader, compose, kind_name, suggest
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

_Top = dict[str, tuple[yaml.Node, yaml.Node]]


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


def _param_text(reader: Reader, node: yaml.Node, where: str, param: Param) -> str:
    if param.kind == "vector":
        return reader.vector(node, where, param.size)
    if param.kind == "bool":
        value = reader.value(node, where)
        if not isinstance(value, bool):
            reader.fail(node, where, f"expected true or false, got {kind_name(node, value)}")
        return "true" if value else "false"
    if param.kind in ("int", "float"):
        whole = param.name in ("width", "height") or param.name.endswith("samples")
        return reader.number_text(node, where, whole=whole)
    value = reader.value(node, where)
    if isinstance(value, bool) or value is None or isinstance(value, (list, dict)):
        reader.fail(node, where, f"expected a string, got {kind_name(node, value)}")
    text = str(value)
    if not SAFE_TEXT.match(text):
        reader.fail(node, where, "the value contains characters XML cannot hold (< > & quotes)")
    return text


def _params(
    reader: Reader,
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
                + suggest(key, settable),
            )
        out[key] = _param_text(reader, value_node, here, macro.params[key])
        marks[here] = reader.mark(value_node)
    return out


_PLAIN_TEXT = "plain text (no < > & or quotes)"


def _get(top: _Top, key: str) -> yaml.Node | None:
    return top[key][1] if key in top else None


def _package_fields(r: Reader, top: _Top, name: str) -> tuple[str, str, str, str, str, str]:
    """The package.xml fields (package, version, description, maintainer name and e-mail,
    license), each the default the YAML does not override."""
    node = _get(top, "package")
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
    node = _get(top, "version")
    version = "0.1.0"
    if node is not None:
        raw = r.value(node, "version")
        if not isinstance(raw, str) or not _VERSION.match(raw):
            r.fail(node, "version", f"expected a version like 0.1.0, got {kind_name(node, raw)}")
        version = raw
    node = _get(top, "description")
    description = (
        r.string(node, "description", pattern=SAFE_TEXT, rule=_PLAIN_TEXT)
        if node is not None
        else f"Description of {name} with its sensors, generated by sensorkit."
    )
    maintainer_name, maintainer_email = "Your Name", "you@example.com"
    node = _get(top, "maintainer")
    if node is not None:
        m = r.mapping(node, "maintainer", MAINTAINER_KEYS)
        if "name" in m:
            maintainer_name = r.string(
                m["name"][1], "maintainer.name", pattern=SAFE_TEXT, rule=_PLAIN_TEXT
            )
        if "email" in m:
            maintainer_email = r.string(
                m["email"][1], "maintainer.email", pattern=_EMAIL, rule="an e-mail address"
            )
    node = _get(top, "license")
    license_ = (
        r.string(node, "license", pattern=SAFE_TEXT, rule=_PLAIN_TEXT)
        if node is not None
        else "Apache-2.0"
    )
    return package, version, description, maintainer_name, maintainer_email, license_


def _simulation(r: Reader, top: _Top, defaults: Mapping[str, str]) -> tuple[str, str, str]:
    """``(sim, gz_version, namespace)``: the YAML's, else ``defaults`` (from the settings
    file's target), else gz, harmonic and the root namespace."""
    node = _get(top, "sim")
    sim = r.string(node, "sim", choices=SIMS) if node is not None else defaults.get("sim", "gz")
    node = _get(top, "gz_version")
    gz_version = defaults.get("gz_version", "harmonic")
    if node is not None:
        gz_version = r.string(node, "gz_version", choices=GZ_VERSIONS)
    node = _get(top, "namespace")
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
    return sim, gz_version, namespace.strip("/")


def _refuse_robot_description(text: str, path: Path, file: str) -> None:
    """A URDF/xacro given where a robot YAML belongs (named ``.urdf``/``.xacro``, or text
    that opens with ``<`` as XML does and YAML never starts a mapping): one line naming
    the command that takes it."""
    if path.name.endswith((".urdf", ".xacro")) or text.lstrip("\ufeff \t\r\n").startswith("<"):
        msg = (
            f"{file}: not a robot YAML: `sensorkit new` takes a robot YAML; "
            "URDF/xacro go to `sensorkit validate` (and `sensorkit add-*` to add a sensor)"
        )
        raise InputError(msg)


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
    _refuse_robot_description(text, path, file)
    root = compose(path, text, file)
    if root is None:
        msg = f"{file}:1:1: the file is empty; expected a mapping with name, base and sensors"
        raise InputError(msg)
    r = Reader(file)
    top = r.mapping(root, "", TOP_KEYS)
    marks: dict[str, Mark] = {k: r.mark(v) for k, (_, v) in top.items()}
    if "name" not in top:
        r.fail(root, "", "missing key 'name' (the robot's name, e.g. name: my_robot)")
    name = r.string(
        top["name"][1],
        "name",
        pattern=_PACKAGE,
        rule="a valid name (lowercase letters, digits and underscores, starting with a letter)",
    )
    package, version, description, maintainer_name, maintainer_email, license_ = _package_fields(
        r, top, name
    )
    bases = base_templates()
    node = _get(top, "base")
    base = r.string(node, "base", choices=sorted(bases)) if node is not None else "diff_drive"
    base_params = _params(
        r, _get(top, "base_params"), "base_params", bases[base], what="base parameter", marks=marks
    )
    sim, gz_version, namespace = _simulation(r, top, defaults or {})
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
        sensors=_sensors(r, _get(top, "sensors"), bases[base], marks),
        marks=marks,
    )


def _sensor(
    r: Reader,
    item: yaml.Node,
    where: str,
    taken: Mapping[str, SensorSpec],
    marks: dict[str, Mark],
) -> tuple[SensorSpec, yaml.Node | None]:
    """One ``sensors:`` entry, checked, and the node of its ``parent`` key (if given);
    ``taken`` holds the sensors before it, by name."""
    macros = sensor_macros()
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
    if sname in taken:
        first = taken[sname].mark
        r.fail(
            entry["name"][1],
            f"{where}.name",
            f"duplicate sensor name {sname!r} (first used at line {first.line})",
        )
    smarks = {"name": r.mark(entry["name"][1]), "type": r.mark(entry["type"][1])}
    parent, parent_node = "base_link", None
    if "parent" in entry:
        parent_node = entry["parent"][1]
        parent = r.string(parent_node, f"{where}.parent", pattern=_IDENT, rule="a link name")
        smarks["parent"] = r.mark(parent_node)
    xyz = rpy = "0 0 0"
    if "xyz" in entry:
        xyz = r.vector(entry["xyz"][1], f"{where}.xyz", 3)
    if "rpy" in entry:
        rpy = r.vector(entry["rpy"][1], f"{where}.rpy", 3)
        _check_radians(r, entry["rpy"][1], f"{where}.rpy", rpy)
    options = _params(
        r,
        entry["options"][1] if "options" in entry else None,
        f"{where}.options",
        macros[stype],
        what="option",
        marks=marks,
    )
    spec = SensorSpec(stype, sname, parent, xyz, rpy, options, r.mark(item), smarks)
    return spec, parent_node


def _check_radians(r: Reader, node: yaml.Node, where: str, rpy: str) -> None:
    """An angle over 2π is degrees by habit (90 for a quarter turn): refused as add-*'s
    --rpy refuses it, with the radians it likely meant."""
    for text in rpy.split():
        angle = float(text)
        if abs(angle) > 2 * math.pi:
            r.fail(
                node,
                where,
                f"{angle:g} is more than 2π; angles are in radians "
                f"(radians? {angle:g}° is {math.radians(angle):.6g})",
            )


def _sensors(
    r: Reader, node: yaml.Node | None, base: MacroInfo, marks: dict[str, Mark]
) -> list[SensorSpec]:
    if node is None or (isinstance(node, yaml.ScalarNode) and r.value(node, "sensors") is None):
        return []
    if not isinstance(node, yaml.SequenceNode):
        value = r.value(node, "sensors") if isinstance(node, yaml.ScalarNode) else None
        r.fail(node, "sensors", f"expected a list of sensors, got {kind_name(node, value)}")
    names: dict[str, SensorSpec] = {}
    parent_nodes: dict[str, yaml.Node] = {}
    for i, item in enumerate(node.value):
        spec, parent_node = _sensor(r, item, f"sensors[{i}]", names, marks)
        if parent_node is not None:
            parent_nodes[spec.name] = parent_node
        names[spec.name] = spec
    out = list(names.values())
    owner = _link_owners(r, node, out, base)
    _check_parents(r, node, out, owner, parent_nodes)
    return out


def _link_owners(
    r: Reader, node: yaml.SequenceNode, sensors: list[SensorSpec], base: MacroInfo
) -> dict[str, str]:
    """Links: the base's, and each sensor's; a name may be made only once. Link -> who
    makes it."""
    owner: dict[str, str] = {link: "the base" for link in base.link_patterns}
    for i, spec in enumerate(sensors):
        for link in spec.macro.links_for(spec.name):
            if link in owner:
                r.fail(
                    node.value[i],
                    f"sensors[{i}].name",
                    f"sensor {spec.name!r} would create link {link!r}, which {owner[link]} "
                    "already has; choose another name",
                )
            owner[link] = f"sensor {spec.name!r}"
    return owner


def _check_parents(
    r: Reader,
    node: yaml.SequenceNode,
    sensors: list[SensorSpec],
    owner: Mapping[str, str],
    parent_nodes: Mapping[str, yaml.Node],
) -> None:
    """Parents: an existing link, not the sensor's own, and no mounting loop."""
    for i, spec in enumerate(sensors):
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
                + suggest(spec.parent, known),
            )
    by_link = {link: s for s in sensors for link in s.macro.links_for(s.name)}
    for i, spec in enumerate(sensors):
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
