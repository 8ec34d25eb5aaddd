"""Strict reading of composed YAML nodes: every failure is one ``FILE:LINE:COLUMN`` line.

:func:`compose` parses the text into nodes without building Python values, so each
value keeps its place; :class:`Reader` turns nodes into checked strings, numbers
(written as xacro attribute text) and mappings, and raises
:class:`~sensorkit.base.errors.InputError` with the place of the first mistake.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NoReturn

import yaml

from sensorkit.base import yamlguard
from sensorkit.base.errors import InputError
from sensorkit.generate.catalog import NUMBER

__all__ = ["SAFE_TEXT", "Mark", "Reader", "compose", "kind_name", "suggest"]

_EXPRESSION = re.compile(r"^\$\{[^{}]+\}$")
SAFE_TEXT = re.compile(r"^[^<>&\"'\x00-\x1f]*$")
"""Text an XML attribute holds as it is (no markup, quotes or control characters)."""


@dataclass(frozen=True)
class Mark:
    """A place in the robot YAML (1-based line and column)."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


def kind_name(node: yaml.Node, value: Any = None) -> str:
    """What a node holds, for a message: ``a mapping``, ``a number (3)``, ..."""
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


def suggest(word: str, choices: Sequence[str]) -> str:
    """``; did you mean 'x'?`` for the choice closest to ``word``, or nothing."""
    close = difflib.get_close_matches(word, list(choices), n=1)
    return f"; did you mean {close[0]!r}?" if close else ""


def _fmt_number(value: float | int) -> str:
    if isinstance(value, int):
        return str(value)
    if value == int(value) and abs(value) < 1e15:
        return f"{value:.1f}" if abs(value) < 1e6 else repr(value)
    return repr(value)


class Reader:
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
            self.fail(node, where, f"expected a single value, got {kind_name(node)}")
        try:
            return self._ctor.construct_object(node, deep=True)
        except yaml.YAMLError as exc:
            self.fail(node, where, f"cannot read this value ({exc})")

    def mapping(
        self, node: yaml.Node, where: str, known: Sequence[str] | None, what: str = "key"
    ) -> dict[str, tuple[yaml.Node, yaml.Node]]:
        if not isinstance(node, yaml.MappingNode):
            value = self.value(node, where) if isinstance(node, yaml.ScalarNode) else None
            self.fail(node, where, f"expected a mapping, got {kind_name(node, value)}")
        out: dict[str, tuple[yaml.Node, yaml.Node]] = {}
        for key_node, value_node in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                self.fail(key_node, where, "merge keys (<<) are not supported here")
            key = self.value(key_node, where)
            if not isinstance(key, str):
                self.fail(key_node, where, f"keys must be strings, got {kind_name(key_node, key)}")
            here = f"{where}.{key}" if where else key
            if key in out:
                first = self.mark(out[key][0])
                self.fail(key_node, here, f"duplicate {what} (first given at line {first.line})")
            if known is not None and key not in known:
                self.fail(
                    key_node,
                    here,
                    f"unknown {what} {key!r} (known: {', '.join(known)}){suggest(key, known)}",
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
            self.fail(node, where, f"expected a string, got {kind_name(node, value)}")
        if choices is not None and value not in choices:
            self.fail(
                node,
                where,
                f"unknown value {value!r} (expected one of: {', '.join(choices)})"
                + suggest(value, choices),
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
        if isinstance(value, str) and NUMBER.match(value.strip()):
            value = float(value) if not re.match(r"^[-+]?\d+$", value.strip()) else int(value)
        if isinstance(value, str) and _EXPRESSION.match(value.strip()) and not whole:
            if not SAFE_TEXT.match(value):
                self.fail(node, where, "the expression contains characters XML cannot hold")
            return value.strip()
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            expected = "a whole number" if whole else "a number (or a ${...} xacro expression)"
            self.fail(node, where, f"expected {expected}, got {kind_name(node, value)}")
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
            if len(parts) == size and all(NUMBER.match(p) for p in parts):
                return " ".join(_fmt_number(float(p)) for p in parts)
        self.fail(node, where, f"expected a list of {size} numbers, got {kind_name(node, value)}")


def compose(path: Path, text: str, file: str) -> yaml.Node | None:
    """The YAML ``text`` as one node tree (None for an empty document); ``file`` names it
    in the message of a malformed document."""
    try:
        yamlguard.check(text)
    except yamlguard.TooDeep as exc:
        raise InputError(f"{file}: malformed YAML: {exc}") from None
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
    except RecursionError:  # block nesting (- - - ...) past the composer's recursion
        msg = f"{file}: malformed YAML: nests too deeply for a robot YAML"
        raise InputError(msg) from None
    finally:
        loader.dispose()
