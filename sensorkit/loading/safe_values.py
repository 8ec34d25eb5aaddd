"""The data an untrusted expression may hold, and the sizes it may reach (issue 36).

:func:`not_data` says whether a value is only data (str, numbers, booleans, None and
lists, tuples, sets and dicts of those), :func:`text_size` estimates the text of a value
before it is rendered, and :func:`percent_fields` / :func:`format_fields` list the value
each field of a format takes, so a repeated field counts each time. Used by
:mod:`sensorkit.loading.safe_eval`.
"""

from __future__ import annotations

import ast
import operator
import re
import string
from collections.abc import Callable, Iterator
from typing import Any

MAX_ITEMS = 10**6
MAX_INT_BITS = 33_220  # 2**33220 has 10,001 decimal digits
MAX_STEPS = 10**6
# What one expression may build in all, in characters of its text (a comprehension's items
# together, a container's walk): 16 MB of text.
MAX_CHARS = 16 * 10**6
# Steps of every expression of one expansion together (XacroEvaluator): a macro that
# evaluates a heavy expression in a loop stops at this, long before the 60 s timeout.
MAX_TOTAL_STEPS = 2 * 10**7

def text_size(value: Any, limit: int = MAX_ITEMS) -> int:
    """An upper estimate of ``len(str(value))``, walked until it passes ``limit``."""
    total, stack = 0, [value]
    while stack and total <= limit:
        v = stack.pop()
        if isinstance(v, str):
            total += len(v) + 2
        elif isinstance(v, bool) or v is None:
            total += 5
        elif isinstance(v, int):
            total += v.bit_length() // 3 + 2
        elif isinstance(v, (float, complex)):
            total += 48
        elif isinstance(v, dict):
            total += 2 + 4 * len(v)
            stack.extend(v.keys())
            stack.extend(dict.values(v))
        elif isinstance(v, (list, tuple, set, frozenset)):
            total += 2 + 2 * len(v)
            stack.extend(v)
        else:
            total += 80  # a function's or an object's repr
    return total


_SCALARS = (str, int, float, complex, bool, type(None))
_VIEWS: tuple[type, ...] = (type({}.keys()), type({}.values()), type({}.items()))
# What the registered builtins return to be passed on (their items are checked as made).
ITERATORS: tuple[type, ...] = (map, filter, zip, enumerate, reversed, type(reversed([])), type(iter(range(0))))
# Containers already found to hold only data, kept (so their ids stay theirs) until the
# table is full: a YAML dict named in every expression is walked once.
_DATA_SEEN: dict[int, Any] = {}


def not_data(value: Any) -> str | None:
    """What in ``value`` is not data (issue 36: values are only str, numbers, booleans,
    None, and lists, tuples, sets and dicts of those), in words; None when all is data.
    xacro's symbol tables and namespaces (dict subclasses with a ``parent``) are not."""
    stack, count = [value], 0
    while stack:
        v = stack.pop()
        if isinstance(v, _SCALARS):
            continue
        count += 1
        if count > 4 * MAX_ITEMS:
            return "a value this large"
        if id(v) in _DATA_SEEN and _DATA_SEEN[id(v)] is v:
            continue
        if isinstance(v, dict) and "parent" not in getattr(v, "__dict__", ()):
            stack.extend(v.keys())
            stack.extend(dict.values(v))
        elif isinstance(v, list):
            stack.extend(list.__iter__(v))  # the items themselves (a YAML list wraps them)
        elif isinstance(v, (tuple, set, frozenset, *_VIEWS)):
            stack.extend(iter(v))  # type: ignore[call-overload]
        elif isinstance(v, range):
            continue
        else:
            return kind_of(v)
    if isinstance(value, (dict, list)) and len(_DATA_SEEN) < 4096:
        _DATA_SEEN[id(value)] = value
    return None


def kind_of(value: Any) -> str:
    """A value that is not data, in words (never its repr)."""
    import types

    if isinstance(value, types.ModuleType):
        return "a module"
    if isinstance(value, dict):
        return "a namespace"
    if isinstance(value, type):
        return "a class"
    if callable(value):
        return "a function"
    return f"a {type(value).__name__} object"


PERCENT = re.compile(r"%(?:\([^)]*\))?[#0\- +]*(\*|\d+)?(?:\.(\*|\d+))?[hlL]?(.?)")
DIGITS = re.compile(r"\d+")
FIELD = re.compile(r"\d*|[A-Za-z_]\w*")


def percent_fields(fmt: str, args: Any) -> Iterator[tuple[int, Any]]:
    """(width, value) of each field of ``fmt % args`` (``%%`` takes none); a width of -1
    for a ``*`` width or precision, which formatting must refuse."""
    items = args if isinstance(args, tuple) else (args,)
    i = 0
    for m in PERCENT.finditer(fmt):
        if "*" in (m.group(1), m.group(2)):
            yield -1, None
            return
        width = sum(int(g) for g in m.groups()[:2] if g and g.isdigit())
        if m.group(3) == "%" or not m.group(3):
            yield width, None
            continue
        key = re.match(r"%\(([^)]*)\)", m.group(0))
        if key is not None and isinstance(args, dict):
            yield width, args.get(key.group(1))
        else:
            yield width, items[i] if i < len(items) else None
            i += 1


def format_fields(fmt: str, args: list[Any], kwargs: dict[str, Any]) -> Iterator[tuple[str, str, Any]]:
    """(name, spec, value) of each field of ``fmt.format(*args, **kwargs)``, in order,
    automatic numbering resolved (a ValueError for a broken format string)."""
    try:
        fields = list(string.Formatter().parse(fmt))
    except ValueError as exc:
        raise ValueError(f"bad format string: {exc}") from None
    auto = 0
    for _, name, spec, _ in fields:
        if name is None:
            continue
        key = name
        if key == "":
            key, auto = str(auto), auto + 1
        value = args[int(key)] if key.isdigit() and int(key) < len(args) else kwargs.get(key)
        yield name, spec or "", value


COMPARE: dict[type, Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le,
    ast.Gt: operator.gt, ast.GtE: operator.ge, ast.Is: operator.is_, ast.IsNot: operator.is_not,
    ast.In: lambda a, b: a in b, ast.NotIn: lambda a, b: a not in b,
}  # fmt: skip
BINOPS: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
    ast.Div: operator.truediv, ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod,
    ast.Pow: operator.pow, ast.LShift: operator.lshift, ast.RShift: operator.rshift,
    ast.BitOr: operator.or_, ast.BitXor: operator.xor, ast.BitAnd: operator.and_,
}  # fmt: skip
