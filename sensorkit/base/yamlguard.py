"""YAML read within bounds: nesting no file sensorkit reads ever needs is refused first.

PyYAML keeps one possible simple key per open flow collection and walks them all on every
token (yaml/scanner.py ``stale_possible_simple_keys``), so ``[[[[...`` costs time growing
with the square of its depth until the composer's recursion ends it: ~1.5 s of CPU for
10,000 brackets (PyYAML 6.0, measured), paid on every read of the file. Deep block nesting
(``- - - - ...``) ends in a RecursionError. Bridge configurations, launch files, parameter
files and robot YAMLs nest a few levels; :data:`MAX_DEPTH` is far above any of them.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import TYPE_CHECKING, TypeVar

import yaml

if TYPE_CHECKING:
    from yaml import Node

__all__ = ["MAX_DEPTH", "TooDeep", "check", "compose", "flow_depth", "safe_load"]

T = TypeVar("T")

MAX_DEPTH = 64

# The tokens that matter for flow nesting: brackets, and what hides brackets (quoted
# scalars, comments). Everything else is skipped by the regex engine, not by Python.
_TOKENS = re.compile(r"""[\[\]{}]|'(?:[^']|'')*'|"(?:[^"\\]|\\.)*"|(?:^|(?<=\s))\#[^\n]*""", re.M)


class TooDeep(yaml.YAMLError):  # type: ignore[misc]  # PyYAML ships no type hints
    """YAML nested past MAX_DEPTH: a YAMLError, so every reader's own handler says it."""


def flow_depth(text: str) -> int:
    """The deepest nesting of flow collections (``[`` and ``{``) in ``text``."""
    depth = deepest = 0
    for m in _TOKENS.finditer(text):
        c = m.group()
        if c in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif c in "]}":
            depth = max(0, depth - 1)
    return deepest


def _refuse_deep(text: str) -> None:
    depth = flow_depth(text)
    if depth > MAX_DEPTH:
        msg = f"nests {depth} levels of [ or {{, more than the {MAX_DEPTH} any configuration needs"
        raise TooDeep(msg)


def _read(load: Callable[[str], T], text: str) -> T:
    _refuse_deep(text)
    try:
        return load(text)
    except RecursionError:
        msg = "nests too deeply for a configuration"
        raise TooDeep(msg) from None


def compose(text: str) -> Node | None:
    """``yaml.compose`` with the safe loader, within the bounds above (raises TooDeep)."""
    return _read(lambda t: yaml.compose(t, Loader=yaml.SafeLoader), text)


def safe_load(text: str) -> object:
    """``yaml.safe_load`` within the bounds above (raises TooDeep)."""
    return _read(yaml.safe_load, text)


def check(text: str) -> None:
    """Raise TooDeep for flow nesting past MAX_DEPTH (for readers that drive a loader
    themselves and catch RecursionError on their own)."""
    _refuse_deep(text)
