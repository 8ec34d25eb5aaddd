"""``--untrusted``: expand a xacro file from a pull request without leaking the machine.

A robot description reaches CI from people the CI does not trust. Standard xacro lets it
read the whole environment (``$(env NAME)``, ``$(optenv NAME)``), any file
(``<xacro:include>``, ``xacro.load_yaml``), and evaluates ``${...}`` and ``$(eval ...)``
as Python: ``$(eval ...)`` runs with Python's full builtins (xacro
substitution_args.py ``_eval``: ``eval(s, {}, ...)``, so ``open`` is reachable) and
``${...}`` only refuses names that start with ``__`` at the top level of the expression
(xacro ``safe_eval``). Whatever it reads can end up in a link name, and link names are
echoed into findings, SARIF and GitHub annotations.

Under ``--untrusted`` (see ``xacro_expand``):

- the expansion runs in a forked child whose environment holds only the names allowed
  with ``--env NAME``; ``$(env OTHER)`` is an SK102 error naming the variable (never a
  value), ``$(optenv OTHER default)`` gives its default;
- includes and ``load_yaml`` may only read files inside the file's workspace and the
  packages ``$(find)`` resolved (real paths: a symlink out of the workspace is refused);
- every ``${...}`` and ``$(eval ...)`` expression is evaluated by
  :class:`XacroEvaluator`, never by Python's ``eval``: an allow-list of constructs, of
  callable functions (Python's pure builtins, math, xacro's documented helpers) and of
  str/list/dict methods, with bounded sizes (``sensorkit.loading.safe_eval``); anything
  else is an SK102 error naming the construct. The trusted path keeps xacro's own
  evaluation.

The CI recipe in the README runs sensorkit in a job that holds no secrets as well.
"""

from __future__ import annotations

import ast
import builtins
import math
import os
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sensorkit.loading.safe_eval import (
    MAX_INT_BITS,
    MAX_TOTAL_STEPS,
    Evaluator,
    Functions,
    UnsafeExpression,
    evaluate,
    parse,
    refuse,
)

__all__ = ["UnsafeExpression", "XacroEvaluator", "check_expression"]

# ``${...}`` sees only xacro's symbol table, whose ``python`` namespace holds these: removed
# while untrusted (nothing calls them anyway: see ``XacroEvaluator``).
HIDDEN_PYTHON_NAMES = ("type", "vars", "issubclass")
# xacro's own helpers (xacro/__init__.py create_global_symbols: ``expose(load_yaml=...,
# abs_filename=..., dotify=..., ns='xacro')``, ``arg``, the message functions, ``fatal``
# and ``tokenize``): callable under --untrusted (``load_yaml`` reads through the confined
# ``open``).
XACRO_HELPERS = frozenset(
    "load_yaml abs_filename dotify arg message warning error print_location fatal tokenize".split()  # noqa: SIM905
)
@dataclass(frozen=True)
class Untrusted:
    """How to expand untrusted input: which environment names xacro may read."""

    env: frozenset[str] = frozenset()


@dataclass
class Confinement:
    """The folders an untrusted expansion may read files from (real paths)."""

    roots: list[str] = field(default_factory=list)

    def add(self, folder: str | os.PathLike[str]) -> None:
        real = os.path.realpath(folder)
        if real not in self.roots:
            self.roots.append(real)

    def allows(self, file: str | os.PathLike[str]) -> bool:
        from sensorkit.loading.packages import inside

        return inside(os.path.realpath(file), self.roots)

    def refuse(self, file: str) -> str:
        return (
            f"--untrusted: {file} is outside the workspace and the resolved packages; "
            "not read (the repository is the limit: pass --package-path for a package "
            "that lives elsewhere)"
        )


def confinement_for(path: Path, explicit: Iterable[Path], scan_dirs: Iterable[Path]) -> Confinement:
    """The readable area of ``path`` (``packages.readable_area``: its repository, the
    ``--package-path`` folders, AMENT_PREFIX_PATH's share folders)."""
    from sensorkit.loading.packages import readable_area

    conf = Confinement()
    for folder in readable_area(path, [*explicit, *scan_dirs]):
        conf.add(folder)
    return conf


# -- guards for the registered builtins ---------------------------------------------------
def _range(ev: Evaluator, fn: Any, args: list[Any], kwargs: dict[str, Any]) -> Any:
    return ev.bound(fn(*args, **kwargs))


def _pow(ev: Evaluator, fn: Any, args: list[Any], kwargs: dict[str, Any]) -> Any:
    if len(args) == 2:
        ev.power(*args)
    return fn(*args, **kwargs)


def _numbers(ev: Evaluator, fn: Any, args: list[Any], kwargs: dict[str, Any]) -> Any:
    """``sum``, ``math.prod``, ``math.lcm``: numbers only (``sum`` of lists or strings
    concatenates), and ints whose digits together stay inside the bound."""
    items = ev.sequence(args[0]) if fn in (sum, math.prod) and args else list(args)
    rest = list(args[1:]) if fn in (sum, math.prod) else []
    values = [*items, *rest, *kwargs.values()]
    if not all(isinstance(v, (int, float, complex)) for v in values):
        raise ev.fail(f"{fn.__name__} of anything but numbers")
    ev.size(sum(v.bit_length() for v in values if isinstance(v, int)) > MAX_INT_BITS, int)
    return fn(items, *rest, **kwargs) if fn in (sum, math.prod) else fn(*items)


def _small_ints(ev: Evaluator, fn: Any, args: list[Any], kwargs: dict[str, Any]) -> Any:
    """``math.factorial``, ``comb``, ``perm``: arguments up to 10,000."""
    if any(isinstance(a, int) and a > 10_000 for a in [*args, *kwargs.values()]):
        raise ev.fail(f"{fn.__name__} of a number over 10,000")
    return fn(*args, **kwargs)


def _round(ev: Evaluator, fn: Any, args: list[Any], kwargs: dict[str, Any]) -> Any:
    """``round(x, n)``: ``n`` within 10,000 digits either way (``round(7, -10**8)``
    computes ``10**(10**8)`` before it answers)."""
    digits = args[1] if len(args) > 1 else kwargs.get("ndigits")
    if isinstance(digits, int) and abs(digits) > 10_000:
        raise ev.fail("round to more than 10,000 digits")
    return fn(*args, **kwargs)


def _rendered(ev: Evaluator, fn: Any, args: list[Any], kwargs: dict[str, Any]) -> Any:
    """``str``, ``repr``, ``ascii``, ``format``: the text stays inside the bound."""
    if fn is format and len(args) > 1 and isinstance(args[1], str):
        ev.text(args[0], ev.spec(args[1]))
    else:
        ev.text(args[:1])
    return fn(*args, **kwargs)


SAFE_BUILTINS: dict[str, Callable[..., Any] | None] = {
    **dict.fromkeys(
        """abs all any bin bool chr complex dict divmod enumerate filter float frozenset
        hash hex int isinstance len list map max min oct ord reversed set slice sorted
        tuple zip""".split()  # noqa: SIM905
    ),
    "range": _range, "round": _round, "pow": _pow, "sum": _numbers,
    "str": _rendered, "repr": _rendered, "ascii": _rendered, "format": _rendered,
}  # fmt: skip
MATH_GUARDS: dict[str, Callable[..., Any]] = {
    "prod": _numbers, "lcm": _numbers, "factorial": _small_ints, "comb": _small_ints,
    "perm": _small_ints, "pow": _pow,
}  # fmt: skip


def builtin_functions() -> Functions:
    """Python's pure builtins (:data:`SAFE_BUILTINS`) and every public function of math."""
    import builtins

    funcs = Functions()
    for name, guard in SAFE_BUILTINS.items():
        funcs.add(name, getattr(builtins, name), guard)
    for name, value in vars(math).items():
        if not name.startswith("_"):
            funcs.add(name, value, MATH_GUARDS.get(name))
    return funcs


def safe_names(names: Iterable[str]) -> Mapping[str, Any]:
    """The builtins among ``names`` that :data:`SAFE_BUILTINS` allows, by name."""
    import builtins

    allowed = {*SAFE_BUILTINS, "True", "False", "None"}
    return {n: getattr(builtins, n) for n in names if n in allowed}


class XacroEvaluator:
    """xacro's ``safe_eval`` (``${...}``) and ``$(eval ...)`` by allow-list (see safe_eval).

    Built after ``xacro_expand`` has patched ``env``, ``optenv`` and ``find``: those are
    read from xacro's table when each ``$(eval)`` runs.
    """

    def __init__(self, xacro: Any, sa: Any) -> None:
        self.xacro, self.sa = xacro, sa
        self.functions = _xacro_functions(xacro)
        self.budget = [MAX_TOTAL_STEPS]  # the steps every expression of the expansion shares

    def expression(self, expr: str, symbols: Any, local: Any = None) -> Any:
        """``${expr}``: names are xacro's symbols (properties, namespaces, helpers)."""

        def lookup(name: str) -> Any:
            if local is not None and name in local:
                return local[name]
            try:
                return symbols[name]
            except KeyError:
                raise NameError(f"name '{name}' is not defined") from None

        return evaluate(expr, lookup, self.functions, self.budget)

    def substitution(self, s: str, context: dict[str, Any]) -> str:
        """``$(eval s)``: names as in xacro substitution_args ``_eval``: ``arg``,
        ``dirname``, ``env``, ``optenv``, ``find``, math, the args themselves; then the
        builtins of :data:`SAFE_BUILTINS` (xacro's ``eval`` would offer all of them)."""
        sa = self.sa
        if "__" in s:  # xacro's own refusal, kept word for word
            msg = "$(eval ...) may not contain double underscore expressions"
            raise sa.SubstitutionException(msg)
        args = context.setdefault("arg", {})

        def arg(name: str) -> Any:
            return sa.convert_value(sa._eval_arg(name, args=args), "auto")

        def dirname() -> Any:
            return sa._eval_dirname(context["filename"])

        names: dict[str, Any] = {"arg": arg, "dirname": dirname, **sa._eval_dict}
        local = Functions(self.functions)
        for name in ("arg", "dirname", "env", "optenv", "find"):
            local.add(name, names.get(name))
        fallback = safe_names(dir(builtins))

        def lookup(name: str) -> Any:
            if name in names:
                return names[name]
            if name in args:
                return sa.convert_value(args[name], "auto")
            if name in fallback:
                return fallback[name]
            if hasattr(builtins, name):  # xacro's eval would find it: say it is refused
                raise refuse(f"name {name}", s)
            raise NameError(f"name '{name}' is not defined")

        return str(evaluate(s, lookup, local, self.budget))


def _xacro_functions(xacro: Any) -> Functions:
    """Python's safe builtins and math, plus whatever xacro's symbol table holds under the
    names of those and of :data:`XACRO_HELPERS` (its deprecated direct names are wrappers,
    distinct objects)."""
    funcs = Functions(builtin_functions())
    root = xacro._global_symbols
    tables = [(root, None), *((dict(root.get(ns, {})), ns) for ns in ("python", "math", "xacro"))]
    math_names = {n for n in dir(__import__("math")) if not n.startswith("_")}
    for table, ns in tables:
        for name, value in dict.items(table) if isinstance(table, dict) else ():
            if ns in (None, "python") and name in SAFE_BUILTINS:
                funcs.add(name, value, SAFE_BUILTINS[name])
            elif ns in (None, "math") and name in math_names:
                funcs.add(name, value, MATH_GUARDS.get(name))
            elif ns in (None, "xacro") and name in XACRO_HELPERS:
                funcs.add(name, value)
    return funcs


def check_expression(expr: str, *, builtins_reachable: bool = False) -> None:
    """Refuse what can be refused before evaluating: constructs outside the allow-list,
    ``_`` attributes, ``__`` names, a literal format string with attribute, item or
    nested fields; with ``builtins_reachable`` (``$(eval)``), builtins other than
    :data:`SAFE_BUILTINS`. The evaluation itself (:class:`XacroEvaluator`) checks the rest.
    """
    import string

    try:
        tree = parse(expr)
    except SyntaxError:
        return  # xacro reports the syntax error itself
    unsafe = set(dir(builtins)) - set(SAFE_BUILTINS) - {"True", "False", "None"}
    for node in ast.walk(tree):
        if builtins_reachable and isinstance(node, ast.Name) and node.id in unsafe:
            raise refuse(f"name {node.id}", expr)
        if (
            isinstance(node, ast.Attribute)
            and node.attr == "format"
            and isinstance(node.value, ast.Constant)
            and isinstance(node.value.value, str)
        ):
            for _, name, spec, _ in string.Formatter().parse(node.value.value):
                if name and ("." in name or "[" in name or "{" in (spec or "")):
                    raise refuse("a format field with an attribute, item or nested field", expr)


def keep_only_environment(allowed: Iterable[str]) -> None:
    """Drop every environment variable but ``allowed`` from this (child) process.

    Clears ``os.environ`` (and with it ``os.environb``) and the start-up copy
    ``posix.environ`` that ``os`` was built from, so no value stays in reachable memory.
    """
    keep = set(allowed)
    for name in list(os.environ):
        if name not in keep:
            del os.environ[name]
    try:
        import posix

        for key in list(posix.environ):
            name = key.decode("utf-8", "replace") if isinstance(key, bytes) else key
            if name not in keep:
                del posix.environ[key]
    except ImportError:  # not POSIX
        pass
