"""What the language server keeps of included files' expansions, as plain data.

The replay itself, which reaches into xacro, is ``sensorkit.loading.xacro_fast``
(:func:`~sensorkit.loading.xacro_fast.reuse_includes`); here are the kept results, their
store, and how the values of xacro's property tables are compared (by their type and
``repr``, XML nodes by their XML): nothing here imports or touches xacro.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass
from typing import Any

MAX_KEPT = 20_000  # node texts kept at most; the store starts over past it

MAX_INCLUDES = 512  # results kept at most (oldest first out)
PER_PLACE = 4  # results kept for one include in one place (one file stack)


class Unkept(Exception):
    """This include's result cannot be kept (a value that cannot be compared)."""


@dataclass
class Kept:
    start: tuple[Any, ...]
    reads: list[tuple[str, str, Any, str]]  # (table, key, value, what) as ExpandDeps.saw
    cwd: str | None  # the working folder, if the include's reads made it matter
    files: list[str]
    includes: list[str]
    roots: list[tuple[Any, list[Any]]]  # each file's root element and its children
    slot: tuple[Any, int] | None  # (parent, index) of xacro's shared text node
    symbols: list[tuple[str, Any]]
    unevaluated: set[str]
    macros: list[tuple[str, Any]]  # macros new or changed, in table order
    args: dict[str, Any]


class IncludeMemo:
    """Included files' results kept across expansions (see above)."""

    def __init__(self) -> None:
        self.kept: OrderedDict[tuple[Any, ...], list[Kept]] = OrderedDict()
        self.replayed = 0  # counters, for tests and benchmarks
        self.expanded = 0

    def candidates(self, place: tuple[Any, ...]) -> list[Kept]:
        found = self.kept.get(place)
        if found is None:
            return []
        self.kept.move_to_end(place)
        return found

    def put(self, place: tuple[Any, ...], kept: Kept) -> None:
        found = self.kept.setdefault(place, [])
        found.insert(0, kept)
        del found[PER_PLACE:]
        self.kept.move_to_end(place)
        while len(self.kept) > MAX_INCLUDES:
            self.kept.popitem(last=False)


@dataclass
class Space:
    """A namespace's content as it was kept: rebuilt, never shared, on each replay."""

    items: list[tuple[str, Any]]
    unevaluated: set[str]


_FP: dict[int, tuple[Any, str]] = {}  # id(node) -> (node, its XML): macro bodies, blocks
_PLAIN = (str, int, float, bool, type(None))


def plain(value: Any, depth: int = 0) -> bool:
    if type(value) in _PLAIN:
        return True
    if depth > 8:
        return False
    if isinstance(value, (list, tuple)):
        return all(plain(v, depth + 1) for v in value)
    if isinstance(value, dict):
        return all(plain(k, depth + 1) and plain(v, depth + 1) for k, v in value.items())
    return False


def node_fp(node: Any) -> str:
    known = _FP.get(id(node))
    if known is not None and known[0] is node:
        return known[1]
    text: str = node.toxml()
    if len(_FP) >= MAX_KEPT:
        _FP.clear()
    _FP[id(node)] = (node, text)
    return text


def value_fp(value: Any) -> Any:
    """What ``value`` (a property's) is compared by; Unkept for what cannot be."""
    import xml.dom.minidom

    kind = type(value)
    if kind in _PLAIN:
        return (kind.__name__, repr(value))
    if isinstance(value, (list, tuple, dict)) and plain(value):  # xacro's YAML wrappers too
        return (kind.__name__, repr(value))
    if isinstance(value, xml.dom.minidom.Node):  # a block property
        return ("node", node_fp(value))
    raise Unkept


def path_in(node: Any, roots: list[Any]) -> tuple[int, list[int]] | None:
    """(which root, child indices from it) of ``node`` inside one of ``roots``, or None."""
    path: list[int] = []
    while node is not None:
        for i, root in enumerate(roots):
            if node is root:
                return i, path[::-1]
        up = node.parentNode
        if up is None:
            return None
        path.append(up.childNodes.index(node))
        node = up
    return None
