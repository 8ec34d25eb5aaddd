"""Add a sensor to a robot YAML without touching a byte of what is there.

The new entry is spliced in after the last item of ``sensors:`` (or inside a flow list
``sensors: [...]``, or as a new ``sensors:`` key at the end), in the style of the items
already there (block mapping or one-line flow mapping), in the file's newline style.
The caller checks the result with :func:`sensorkit.generate.spec.parse_spec`.
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import yaml

from sensorkit.base import yamlguard
from sensorkit.base.errors import EditRefused
from sensorkit.generate.catalog import NUMBER, SHARED_PARAMS, sensor_macros

_PLAIN = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_YAML_WORDS = frozenset(
    {"y", "n", "yes", "no", "on", "off", "true", "false", "null", "none", "~"}
)  # YAML 1.1 reads these bare words as booleans or null


@dataclass(frozen=True)
class SensorEntry:
    """A ``sensors:`` item: values as the add-* request holds them (macro parameter text)."""

    type: str
    name: str
    parent: str
    xyz: Sequence[str]
    rpy: Sequence[str]
    options: Mapping[str, str] = field(default_factory=dict)


def _scalar(text: str) -> str:
    if _PLAIN.match(text) and text.lower() not in _YAML_WORDS:
        return text
    return json.dumps(text)  # a JSON string is a YAML double-quoted scalar


def _option(sensor_type: str, key: str, text: str) -> str:
    param = sensor_macros()[sensor_type].params.get(key)
    kind = param.kind if param is not None else "str"
    if kind == "vector":
        return "[" + ", ".join(text.split()) + "]"
    if kind in ("int", "float") and NUMBER.match(text.strip()):
        return text.strip()
    if kind == "bool" and text.strip().lower() in ("true", "false"):
        return text.strip().lower()
    return _scalar(text)


def entry_fields(entry: SensorEntry) -> list[tuple[str, str]]:
    """``(key, YAML value)`` of the entry, in the order ``sensorkit new`` documents."""
    fields = [
        ("type", entry.type),
        ("name", entry.name),
        ("parent", _scalar(entry.parent)),
        ("xyz", "[" + ", ".join(entry.xyz) + "]"),
    ]
    if any(float(v) != 0.0 for v in entry.rpy):
        fields.append(("rpy", "[" + ", ".join(entry.rpy) + "]"))
    options = [
        f"{k}: {_option(entry.type, k, v)}"
        for k, v in entry.options.items()
        if k not in SHARED_PARAMS
    ]
    if options:
        fields.append(("options", "{" + ", ".join(options) + "}"))
    return fields


def _flow(entry: SensorEntry) -> str:
    return "{" + ", ".join(f"{k}: {v}" for k, v in entry_fields(entry)) + "}"


def _line_end(text: str, index: int) -> int:
    """The index just after the newline of the line holding ``index`` (or the end)."""
    nl = text.find("\n", index)
    return len(text) if nl < 0 else nl + 1


def append_sensor(text: str, entry: SensorEntry, where: str) -> str:
    """``text`` (a robot YAML) with ``entry`` added as its last sensor.

    Raises:
        EditRefused: the file is not a mapping, or its ``sensors:`` is of a shape this
            cannot extend (an explicit null, an anchor, a scalar).
    """
    newline = "\r\n" if "\r\n" in text else "\n"
    try:
        root = yamlguard.compose(text)
    except yaml.YAMLError as exc:
        msg = f"{where}: not YAML ({str(exc).splitlines()[0]})"
        raise EditRefused(msg) from None
    if not isinstance(root, yaml.MappingNode):
        msg = f"{where}: not a robot YAML (a mapping with name, base and sensors)"
        raise EditRefused(msg)
    sensors = next(
        (v for k, v in root.value if isinstance(k, yaml.ScalarNode) and k.value == "sensors"),
        None,
    )
    if sensors is None:
        if root.flow_style:
            msg = f"{where}: a flow-style mapping; add the sensor to its sensors by hand"
            raise EditRefused(msg)
        lead = "" if text.endswith(("\n", "\r")) or not text else newline
        body = f"  - {_flow(entry)}"
        return f"{text}{lead}sensors:{newline}{body}{newline}"
    if isinstance(sensors, yaml.SequenceNode) and sensors.flow_style:
        close = sensors.end_mark.index - 1  # the ']'
        if text[close] != "]":
            msg = f"{where}: cannot find the end of its sensors: [...] list"
            raise EditRefused(msg)
        sep = ", " if sensors.value else ""
        return text[:close] + sep + _flow(entry) + text[close:]
    if not isinstance(sensors, yaml.SequenceNode) or not sensors.value:
        line = sensors.start_mark.line + 1
        msg = f"{where}:{line}: sensors is not a list sensorkit can extend; write it as a list"
        raise EditRefused(msg)
    last = sensors.value[-1]
    line_start = text.rfind("\n", 0, last.start_mark.index) + 1
    prefix = text[line_start : last.start_mark.index]
    dash = prefix.rfind("-")
    if dash < 0 or prefix[:dash].strip():
        msg = f"{where}:{last.start_mark.line + 1}: cannot tell the indentation of its sensors"
        raise EditRefused(msg)
    at = _line_end(text, _content_end(last))
    if isinstance(last, yaml.MappingNode) and not last.flow_style:
        column = last.start_mark.column  # where the item's keys start, after "- "
        first = prefix[:dash] + "-" + " " * (column - dash - 1)
        lines = [
            (first if i == 0 else " " * column) + f"{k}: {v}"
            for i, (k, v) in enumerate(entry_fields(entry))
        ]
    else:
        lines = [f"{prefix[:dash]}- {_flow(entry)}"]
    block = newline.join(lines) + newline
    lead = "" if at == 0 or text[at - 1] == "\n" else newline
    return text[:at] + lead + block + text[at:]


def _content_end(node: yaml.Node) -> int:
    """Where the last value written in ``node`` ends (a block collection's own end mark
    lies at the next token, past any comment lines that follow it)."""
    if isinstance(node, yaml.MappingNode) and not node.flow_style and node.value:
        return _content_end(node.value[-1][1])
    if isinstance(node, yaml.SequenceNode) and not node.flow_style and node.value:
        return _content_end(node.value[-1])
    return int(node.end_mark.index)
