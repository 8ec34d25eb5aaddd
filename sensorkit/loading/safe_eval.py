"""An allow-list evaluator for untrusted ``${...}`` and ``$(eval ...)`` expressions.

Python's ``eval`` is no sandbox: from almost any object an expression walks to frames,
globals and ``open`` (``().__class__.__bases__``, a generator's ``gi_frame``, a format
spec's ``{0:{1.__globals__}}``); a deny-list lost to the way not thought of (issue 25).
This module never calls ``eval``: it walks the parsed tree and knows only these:

- literals (str, numbers, booleans, None) and list, tuple, set and dict displays;
- arithmetic, comparison and boolean operators, and ``a if c else b``;
- names, looked up in the namespace the caller gives (xacro's properties and args and the
  symbols xacro's own evaluation offers), and comprehension variables;
- subscripts of str, list, tuple, dict and range values (xacro's YAML and namespace
  wrappers are dicts and lists);
- attributes only as xacro's namespaces and YAML dictionaries define them (an item
  lookup) or one of the str/list/dict methods in :data:`METHODS`;
- calls only of the functions the caller registers (:class:`Functions`), matched by
  identity, so a property that holds ``type`` cannot be called;
- list, set and dict comprehensions and generator expressions, f-strings, ``%`` and
  ``str.format`` with plain fields (no attribute, item or nested field).

Everything else (lambda, ``:=``, attributes such as ``__class__`` or ``gi_frame``, calls of
anything unregistered) raises :class:`UnsafeExpression` naming the construct. Sizes are
bounded before they are computed where the operands tell: no int over
:data:`MAX_INT_BITS` bits (about 10**4 digits), no str, list, dict, set or range over
:data:`MAX_ITEMS` elements (nor the text of a value rendered with ``str``), and at most
:data:`MAX_STEPS` evaluation steps (tree nodes and comprehension rounds) per expression.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable, Iterator
from typing import Any

from sensorkit.loading.safe_values import (
    BINOPS,
    COMPARE,
    DIGITS,
    FIELD,
    ITERATORS,
    MAX_CHARS,
    MAX_INT_BITS,
    MAX_ITEMS,
    MAX_STEPS,
    MAX_TOTAL_STEPS,
    format_fields,
    not_data,
    percent_fields,
    text_size,
)

__all__ = ["MAX_INT_BITS", "MAX_ITEMS", "MAX_TOTAL_STEPS", "Evaluator", "Functions", "evaluate"]

QUOTE = 200

_SEQUENCES = (str, list, tuple, dict, set, frozenset, range)
_NUMBERS = (int, float, complex)
_CONSTANTS = (str, int, float, complex, bool, type(None))

METHODS: dict[type, frozenset[str]] = {
    str: frozenset(
        """capitalize casefold center count endswith find format index isalnum isalpha
        isdecimal isdigit islower isnumeric isspace istitle isupper join ljust lower lstrip
        partition removeprefix removesuffix replace rfind rindex rjust rpartition rsplit
        rstrip split splitlines startswith strip swapcase title upper zfill""".split()  # noqa: SIM905
    ),
    list: frozenset({"count", "index", "copy"}),
    tuple: frozenset({"count", "index"}),
    dict: frozenset({"get", "keys", "values", "items", "copy"}),
}

_NODES: tuple[type, ...] = (
    ast.Expression, ast.Constant, ast.Name, ast.Load, ast.Store, ast.BinOp, ast.UnaryOp,
    ast.BoolOp, ast.Compare, ast.IfExp, ast.Call, ast.keyword, ast.Attribute, ast.Subscript,
    ast.Slice, ast.List, ast.Tuple, ast.Set, ast.Dict, ast.Starred, ast.ListComp,
    ast.SetComp, ast.DictComp, ast.GeneratorExp, ast.comprehension, ast.JoinedStr,
    ast.FormattedValue, ast.operator, ast.unaryop, ast.boolop, ast.cmpop,
)  # fmt: skip
_NAMED = {
    ast.Lambda: "lambda", ast.NamedExpr: "':=' (assignment)", ast.MatMult: "'@'",
    ast.Await: "await", ast.Yield: "yield", ast.YieldFrom: "yield",
}  # fmt: skip


class UnsafeExpression(Exception):
    """An expression ``--untrusted`` refuses to evaluate."""


def quote(expr: str) -> str:
    """``expr`` on one line, at most :data:`QUOTE` characters."""
    line = " ".join(expr.split())
    return line if len(line) <= QUOTE else line[: QUOTE - 3] + "..."


def refuse(what: str, expr: str) -> UnsafeExpression:
    return UnsafeExpression(f"--untrusted: {what} is not allowed in an expression: {quote(expr)}")


def parse(expr: str) -> ast.Expression:
    """Parse and check that every node is one :func:`evaluate` knows (SyntaxError passes)."""
    try:
        tree = ast.parse(expr.strip(), mode="eval")
    except (RecursionError, MemoryError):
        raise refuse("an expression nested this deeply", expr) from None
    for node in ast.walk(tree):
        if not isinstance(node, _NODES) or isinstance(node, ast.MatMult):
            raise refuse(_NAMED.get(type(node), type(node).__name__), expr)
        if isinstance(node, ast.Attribute) and node.attr.startswith("_"):
            raise refuse(f"attribute .{node.attr}", expr)
        if isinstance(node, ast.Name) and node.id.startswith("__"):
            raise refuse(f"name {node.id}", expr)
        if isinstance(node, ast.Constant) and not isinstance(node.value, _CONSTANTS):
            raise refuse(f"a {type(node.value).__name__} literal", expr)
        if isinstance(node, ast.comprehension) and node.is_async:
            raise refuse("async for", expr)
    return tree


class Functions:
    """The callables an expression may call, by identity, each with an optional guard.

    A guard gets the arguments and raises :class:`UnsafeExpression` (through ``fail``) or
    returns the result itself; without one the function is called and its result bounded.
    """

    def __init__(self, parent: Functions | None = None) -> None:
        self._by_id: dict[int, tuple[str, Any, Callable[..., Any] | None]] = {}
        self.parent = parent

    def add(self, name: str, fn: Any, guard: Callable[..., Any] | None = None) -> None:
        if callable(fn):
            self._by_id[id(fn)] = (name, fn, guard)

    def get(self, fn: Any) -> tuple[str, Any, Callable[..., Any] | None] | None:
        hit = self._by_id.get(id(fn))
        if hit is not None and hit[1] is fn:
            return hit
        return None if self.parent is None else self.parent.get(fn)


class _Method:
    """``obj.name`` for an allowed str/list/dict method; calling it goes through checks."""

    def __init__(self, ev: Evaluator, base: type, name: str, obj: Any) -> None:
        self.ev, self.base, self.name, self.obj = ev, base, name, obj

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.ev.call_method(self, list(args), kwargs)

    def __repr__(self) -> str:
        return f"<method {self.base.__name__}.{self.name}>"


_OVER = {int: "an integer over 10,000 digits", str: f"a str over {MAX_ITEMS:,} characters"}


class Evaluator:
    def __init__(
        self,
        expr: str,
        lookup: Callable[[str], Any],
        functions: Functions,
        budget: int = MAX_STEPS,
    ) -> None:
        self.expr = expr
        self.limit = min(MAX_STEPS, budget)
        self.lookup = lookup
        self.functions = functions
        self.steps = 0
        self.scopes: list[dict[str, Any]] = []
        # nodes whose value may be other than data: a call's function, an attribute's
        # object (a namespace), a call's argument (a registered function: callable_arg)
        self.free: set[int] = set()

    # -- bounds -----------------------------------------------------------------------
    def fail(self, what: str) -> UnsafeExpression:
        return refuse(what, self.expr)

    def step(self, n: int = 1) -> None:
        """Count ``n`` steps (a node, a comprehension round, or the items a builtin walks:
        :meth:`charge`); refused past MAX_STEPS, or past what is left of ``budget``."""
        self.steps += n
        if self.steps > self.limit:
            if self.limit < MAX_STEPS:
                raise self.fail(
                    f"expressions that take over {MAX_TOTAL_STEPS:,} steps in one expansion"
                )
            raise self.fail(f"an expression that takes over {MAX_STEPS:,} steps")

    def charge(self, *values: Any) -> None:
        """Steps for the items a builtin or method walks in C (a sort, a count, ``in``):
        one per element or per 8 characters, so a loop of them stops early too."""
        n = 0
        for v in values:
            if isinstance(v, str):
                n += len(v) // 8
            elif isinstance(v, (list, tuple, dict, set, frozenset, range)):
                n += len(v)
        if n:
            self.step(n)

    def bound(self, value: Any) -> Any:
        if isinstance(value, int):
            self.size(value.bit_length() > MAX_INT_BITS, int)
        if isinstance(value, _SEQUENCES):
            try:
                n = len(value)
            except OverflowError:
                n = MAX_ITEMS + 1
            self.size(n > MAX_ITEMS, type(value))
        return value

    def text(self, value: Any, extra: int = 0) -> None:
        if text_size(value) + extra > MAX_ITEMS:
            raise self.fail(f"text over {MAX_ITEMS:,} characters")

    def spec(self, spec: str) -> int:
        """The width a format spec asks for; refused past the size bound."""
        if "{" in spec or "}" in spec:
            raise self.fail("a nested format field")
        width = sum(int(d) for d in DIGITS.findall(spec)) if len(spec) < 64 else MAX_ITEMS + 1
        if width > MAX_ITEMS:
            raise self.fail(f"a format width over {MAX_ITEMS:,}")
        return width

    # -- nodes --------------------------------------------------------------------------
    def ev(self, node: ast.AST) -> Any:
        self.step()
        method = getattr(self, "ev_" + type(node).__name__, None)
        if method is None:  # parse() lets no other node through
            raise self.fail(type(node).__name__)
        return method(node)

    def ev_Expression(self, node: ast.Expression) -> Any:
        return self.ev(node.body)

    def ev_Constant(self, node: ast.Constant) -> Any:
        return node.value

    def ev_Name(self, node: ast.Name) -> Any:
        for scope in reversed(self.scopes):
            if node.id in scope:
                return scope[node.id]
        return self.data(node, self.lookup(node.id))

    def data(self, node: ast.AST, value: Any) -> Any:
        """``value``, when it is data or ``node`` may be other (:attr:`free`); else refused
        naming the construct and what it is, never its repr."""
        if id(node) not in self.free:
            what = not_data(value)
            if what is not None:
                shown = ast.unparse(node)
                shown = shown if len(shown) <= 60 else shown[:57] + "..."
                raise self.fail(f"{shown} ({what}) as a value")
        return value

    def ev_List(self, node: ast.List) -> Any:
        return self.bound(self.items(node.elts))

    def ev_Tuple(self, node: ast.Tuple) -> Any:
        return self.bound(tuple(self.items(node.elts)))

    def ev_Set(self, node: ast.Set) -> Any:
        return self.bound(set(self.items(node.elts)))

    def ev_Dict(self, node: ast.Dict) -> Any:
        out: dict[Any, Any] = {}
        for k, v in zip(node.keys, node.values, strict=True):
            if k is None:
                out.update(self.mapping(self.ev(v)))
            else:
                out[self.ev(k)] = self.ev(v)
        return self.bound(out)

    def items(self, elts: list[ast.expr]) -> list[Any]:
        out: list[Any] = []
        for e in elts:
            if isinstance(e, ast.Starred):
                out.extend(self.sequence(self.ev(e.value)))
            else:
                out.append(self.ev(e))
            self.bound(out)
        return out

    def sequence(self, value: Any) -> list[Any]:
        """``value``'s items, at most :data:`MAX_ITEMS` (nothing reachable is endless)."""
        out: list[Any] = []
        for item in value:
            out.append(item)
            if len(out) > MAX_ITEMS:
                raise self.fail(f"a sequence over {MAX_ITEMS:,} elements")
        return out

    def mapping(self, value: Any) -> dict[str, Any]:
        if not isinstance(value, dict):
            raise TypeError(f"argument after ** must be a mapping, not {type(value).__name__}")
        return dict(value)

    def ev_IfExp(self, node: ast.IfExp) -> Any:
        return self.ev(node.body) if self.ev(node.test) else self.ev(node.orelse)

    def ev_BoolOp(self, node: ast.BoolOp) -> Any:
        value: Any = None
        for v in node.values:
            value = self.ev(v)
            if isinstance(node.op, ast.And) != bool(value):
                return value
        return value

    def ev_UnaryOp(self, node: ast.UnaryOp) -> Any:
        v = self.ev(node.operand)
        if isinstance(node.op, ast.Not):
            return not v
        if not isinstance(v, _NUMBERS):
            raise self.fail(f"a unary operator on {type(v).__name__}")
        ops: dict[type, Callable[[Any], Any]] = {
            ast.USub: lambda x: -x, ast.UAdd: lambda x: +x, ast.Invert: lambda x: ~x,
        }  # fmt: skip
        return ops[type(node.op)](v)

    def ev_Compare(self, node: ast.Compare) -> Any:
        left = self.ev(node.left)
        for op, comp in zip(node.ops, node.comparators, strict=True):
            right = self.ev(comp)
            self.charge(right if isinstance(op, (ast.In, ast.NotIn)) else None)
            if not COMPARE[type(op)](left, right):
                return False
            left = right
        return True

    def ev_BinOp(self, node: ast.BinOp) -> Any:
        a, b = self.ev(node.left), self.ev(node.right)
        return self.binop(node.op, a, b)

    def binop(self, op: ast.operator, a: Any, b: Any) -> Any:
        for v in (a, b):
            if not isinstance(v, (*_NUMBERS, str, list, tuple, set, frozenset, dict)):
                raise self.fail(f"an operator on {type(v).__name__}")
        seqs = (str, list, tuple)
        if isinstance(op, ast.Pow):
            self.power(a, b)
        elif isinstance(op, ast.LShift) and isinstance(a, int) and isinstance(b, int):
            self.size(b > 0 and a != 0 and a.bit_length() + b > MAX_INT_BITS, int)
        elif isinstance(op, ast.Mult) and isinstance(a, seqs) and isinstance(b, int):
            self.size(len(a) * b > MAX_ITEMS, type(a))
        elif isinstance(op, ast.Mult) and isinstance(b, seqs) and isinstance(a, int):
            self.size(len(b) * a > MAX_ITEMS, type(b))
        elif isinstance(op, ast.Add) and isinstance(a, seqs) and isinstance(b, seqs):
            self.size(len(a) + len(b) > MAX_ITEMS, type(a))
        elif isinstance(op, ast.Mod) and isinstance(a, str):
            return self.percent(a, b)
        return self.bound(BINOPS[type(op)](a, b))

    def power(self, a: Any, b: Any) -> None:
        big = isinstance(a, int) and isinstance(b, int) and b > 0 and abs(a) > 1
        self.size(big and b * math.log2(abs(a)) > MAX_INT_BITS, int)

    def size(self, over: bool, kind: type) -> None:
        """Refuse a result the operands show is over the bounds, before computing it."""
        if over:
            raise self.fail(_OVER.get(kind, f"a {kind.__name__} over {MAX_ITEMS:,} elements"))

    def percent(self, fmt: str, args: Any) -> str:
        """``fmt % args``, its size counted first: each field's width and the text of the
        value it takes (a field repeated counts each time: ``'%(a)s' * n % d``)."""
        total = len(fmt)
        for width, value in percent_fields(fmt, args):
            if width < 0:
                raise self.fail("a '*' width in % formatting")
            total += width + text_size(value, MAX_ITEMS - total)
            if total > MAX_ITEMS:
                raise self.fail(f"text over {MAX_ITEMS:,} characters")
        return str(self.bound(fmt % args))

    def ev_Subscript(self, node: ast.Subscript) -> Any:
        self.free.add(id(node.value))  # a namespace's item (its data is checked below)
        obj = self.ev(node.value)
        key = self.ev(node.slice)
        if not isinstance(obj, (str, list, tuple, dict, range)):
            raise self.fail(f"a subscript of {type(obj).__name__}")
        return self.data(node, self.bound(obj[key]))

    def ev_Slice(self, node: ast.Slice) -> Any:
        parts = [None if p is None else self.ev(p) for p in (node.lower, node.upper, node.step)]
        return slice(*parts)

    def ev_Attribute(self, node: ast.Attribute) -> Any:
        self.free.add(id(node.value))  # ``xacro.load_yaml``: the namespace as the object
        obj = self.ev(node.value)
        return self.data(node, self.attribute(obj, node.attr))

    def attribute(self, obj: Any, name: str) -> Any:
        for base, names in METHODS.items():
            if isinstance(obj, base) and name in names:
                return _Method(self, base, name, obj)
        # xacro's namespaces (NameSpace) and YAML dictionaries (YamlDictWrapper) read
        # ``a.b`` as ``a['b']`` through their own __getattr__
        if isinstance(obj, dict) and getattr(type(obj), "__getattr__", None) is not None:
            try:
                return obj[name]
            except KeyError:
                raise NameError(f"name '{name}' is not defined") from None
        raise self.fail(f"attribute .{name} of a {type(obj).__name__}")

    # -- comprehensions -------------------------------------------------------------------
    def ev_ListComp(self, node: ast.ListComp | ast.GeneratorExp) -> Any:
        chars = [0]
        return self.bound([self.counted(chars, node.elt) for _ in self.rounds(node.generators)])

    ev_GeneratorExp = ev_ListComp  # noqa: N815 (a list: whatever takes one takes a list)

    def ev_SetComp(self, node: ast.SetComp) -> Any:
        chars = [0]
        return self.bound({self.counted(chars, node.elt) for _ in self.rounds(node.generators)})

    def ev_DictComp(self, node: ast.DictComp) -> Any:
        chars = [0]
        return self.bound(
            {
                self.counted(chars, node.key): self.counted(chars, node.value)
                for _ in self.rounds(node.generators)
            }
        )

    def counted(self, chars: list[int], node: ast.expr) -> Any:
        """One item of a comprehension, its text added to ``chars`` (the comprehension's
        total, bounded by MAX_CHARS: a million rounds of a big string are refused before
        they are built, not only a million items)."""
        value = self.ev(node)
        chars[0] += text_size(value, MAX_CHARS)
        if chars[0] > MAX_CHARS:
            raise self.fail(f"a comprehension over {MAX_CHARS:,} characters")
        return value

    def rounds(self, gens: list[ast.comprehension], i: int = 0) -> Iterator[None]:
        if i == len(gens):
            yield None
            return
        gen = gens[i]
        self.scopes.append({})
        try:
            for item in self.sequence(self.ev(gen.iter)):
                self.step()
                self.assign(gen.target, item)
                if all(self.ev(cond) for cond in gen.ifs):
                    yield from self.rounds(gens, i + 1)
        finally:
            self.scopes.pop()

    def assign(self, target: ast.expr, value: Any) -> None:
        if isinstance(target, ast.Name):
            self.scopes[-1][target.id] = value
        elif isinstance(target, (ast.Tuple, ast.List)):
            values = self.sequence(value)
            if len(values) != len(target.elts):
                raise ValueError(f"cannot unpack {len(values)} values into {len(target.elts)}")
            for t, v in zip(target.elts, values, strict=True):
                self.assign(t, v)
        else:
            raise self.fail(f"a comprehension target {type(target).__name__}")

    # -- strings ---------------------------------------------------------------------------
    def ev_JoinedStr(self, node: ast.JoinedStr) -> Any:
        parts = [str(self.ev(v)) for v in node.values]
        self.text(parts)
        return "".join(parts)

    def ev_FormattedValue(self, node: ast.FormattedValue) -> Any:
        value = self.ev(node.value)
        spec = "" if node.format_spec is None else self.ev(node.format_spec)
        width = self.spec(spec)
        self.text(value, width)
        if node.conversion in (ord("r"), ord("a")):
            value = repr(value) if node.conversion == ord("r") else ascii(value)
        elif node.conversion == ord("s"):
            value = str(value)
        return format(value, spec)

    def check_format(self, fmt: str, args: list[Any], kwargs: dict[str, Any]) -> None:
        """``fmt.format(*args, **kwargs)``'s size, counted first: each field's width and
        the text of the value it takes, a field repeated each time (``'{0}' * n``)."""
        width = len(fmt)
        for name, spec, value in format_fields(fmt, args, kwargs):
            if not FIELD.fullmatch(name):
                raise self.fail(f"a format field that reads an attribute or an item ('{{{name[:40]}}}')")
            width += self.spec(spec) + text_size(value, MAX_ITEMS - width)
            if width > MAX_ITEMS:
                raise self.fail(f"text over {MAX_ITEMS:,} characters")

    # -- calls -----------------------------------------------------------------------------
    def ev_Call(self, node: ast.Call) -> Any:
        self.free.add(id(node.func))
        self.free.update(id(a.value if isinstance(a, ast.Starred) else a) for a in node.args)
        self.free.update(id(kw.value) for kw in node.keywords if kw.arg is not None)
        fn = self.ev(node.func)
        args = self.items(node.args)
        kwargs: dict[str, Any] = {}
        for kw in node.keywords:
            if kw.arg is None:
                kwargs.update(self.mapping(self.ev(kw.value)))
            else:
                kwargs[kw.arg] = self.ev(kw.value)
        if isinstance(fn, _Method) and fn.ev is self:
            return self.data(node, self.call_method(fn, args, kwargs))
        what = ast.unparse(node.func)
        return self.data(node, self.call(fn, args, kwargs, what))

    def call(self, fn: Any, args: list[Any], kwargs: dict[str, Any], what: str) -> Any:
        entry = self.functions.get(fn)
        if entry is None:
            raise self.fail(f"calling {what[:60]}")
        self.step()
        name, real, guard = entry
        if name not in ("len", "isinstance", "bool"):  # these never walk their argument
            self.charge(*args, *kwargs.values())
        if name != "isinstance":
            args = [self.callable_arg(a) for a in args]
            kwargs = {k: self.callable_arg(v) for k, v in kwargs.items()}
        if guard is not None:
            return self.bound(guard(self, real, args, kwargs))
        return self.bound(real(*args, **kwargs))

    def callable_arg(self, value: Any) -> Any:
        """A function passed to ``map``, ``sorted(key=...)``: registered, and checked when
        called; anything else passed must be data (``str(xacro)``, ``min([], default=math)``
        would hand out a namespace)."""
        if isinstance(value, _Method) and value.ev is self:
            return value
        if isinstance(value, ITERATORS):  # ``list(map(float, xs))``: yields data only
            return value
        if not callable(value) or isinstance(value, (dict, list)):
            what = not_data(value)
            if what is not None:
                raise self.fail(f"passing {what} as an argument")
            return value
        entry = self.functions.get(value)
        if entry is None:
            raise self.fail(f"passing {type(value).__name__} {getattr(value, '__name__', '')} as an argument")

        def checked(*a: Any, **k: Any) -> Any:
            return self.call(value, list(a), k, entry[0])

        return checked

    def call_method(self, m: _Method, args: list[Any], kwargs: dict[str, Any]) -> Any:
        self.step()
        self.charge(m.obj, *args)
        obj, name = m.obj, m.name
        if name == "format":
            self.check_format(obj, args, kwargs)
        elif name == "join":
            parts = self.sequence(args[0]) if args else []
            total = sum(len(p) if isinstance(p, str) else 0 for p in parts) + len(obj) * len(parts)
            self.size(total > MAX_ITEMS, str)
            args = [parts, *args[1:]]
        elif name == "replace" and len(args) >= 2 and isinstance(args[0], str) and isinstance(args[1], str):
            count = obj.count(args[0]) if args[0] else len(obj) + 1
            self.size(len(obj) + count * (len(args[1]) - len(args[0])) > MAX_ITEMS, str)
        elif name in ("center", "ljust", "rjust", "zfill") and args and isinstance(args[0], int):
            self.size(args[0] > MAX_ITEMS, str)
        args = [self.callable_arg(a) for a in args]
        return self.bound(getattr(m.base, name)(obj, *args, **kwargs))


def evaluate(
    expr: str,
    lookup: Callable[[str], Any],
    functions: Functions,
    budget: list[int] | None = None,
) -> Any:
    """Evaluate ``expr`` by the allow-list above; ``lookup(name)`` resolves a free name
    (raising NameError when unbound). The result is bounded like every step, and must be
    data (see :func:`not_data`). ``budget``: the steps left to a whole expansion (one
    item, lowered by what this expression takes)."""
    tree = parse(expr)
    ev = Evaluator(expr, lookup, functions, budget[0] if budget is not None else MAX_STEPS)
    try:
        return _evaluate(ev, tree)
    finally:
        if budget is not None:
            budget[0] -= ev.steps


def _evaluate(ev: Evaluator, tree: ast.Expression) -> Any:
    try:
        value = ev.ev(tree)
        ev.bound(value)
        what = not_data(value)
        if what is not None:  # e.g. a method named and not called: ``'a'.upper``
            raise ev.fail(f"a result that is {what}")
        if isinstance(value, (list, tuple, dict, set, frozenset)):
            ev.text(value)
        return value
    except (RecursionError, MemoryError):
        raise ev.fail("an expression nested or sized like this") from None
