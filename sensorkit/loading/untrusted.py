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
- every ``${...}`` and ``$(eval ...)`` expression must pass :func:`check_expression`:
  no names or attributes that reach frames, code, globals or the import system, and no
  builtins beyond the arithmetic and container helpers xacro documents.

This narrows what an expression can reach; it does not make Python's ``eval`` a sandbox
against code written to escape it. The CI recipe in the README runs sensorkit in a job
that holds no secrets as well.
"""

from __future__ import annotations

import ast
import os
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

# Builtins a ``$(eval ...)`` expression may name. ``$(eval)`` runs with Python's full
# builtins (xacro substitution_args.py ``_eval``), so everything else is refused there:
# xacro's own exposed list (xacro/__init__.py create_global_symbols) without ``type``,
# ``vars`` and ``issubclass``, which reach class internals.
SAFE_BUILTINS = frozenset(
    """list dict map len str float int bool min max round abs all any complex divmod
    enumerate filter frozenset hash isinstance ord repr reversed slice set sum tuple zip
    sorted range format True False None""".split()  # noqa: SIM905 (a word list reads best)
)
# ``${...}`` sees only xacro's symbol table (``__builtins__`` is emptied by xacro
# safe_eval), but its ``python`` namespace exposes these: removed while untrusted.
HIDDEN_PYTHON_NAMES = ("type", "vars", "issubclass")
# Attributes that lead from any object to frames, code or globals: generators,
# coroutines, frames, tracebacks, functions, classes.
DENIED_ATTRIBUTES = frozenset(
    """gi_frame gi_code gi_yieldfrom gi_running cr_frame cr_code cr_await cr_origin
    ag_frame ag_code ag_await f_back f_globals f_locals f_builtins f_code f_trace
    tb_frame tb_next co_consts co_code func_globals func_code mro""".split()  # noqa: SIM905
)
# ``str.format`` walks attribute paths written in the format string
# (``'{0.__globals__}'.format(f)``): allowed only on a literal without such fields.
FORMAT_METHODS = frozenset({"format", "format_map"})


class UnsafeExpression(Exception):
    """An expression ``--untrusted`` refuses to evaluate."""


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
        real = os.path.realpath(file)
        return any(real == r or real.startswith(r.rstrip(os.sep) + os.sep) for r in self.roots)

    def refuse(self, file: str) -> str:
        return (
            f"--untrusted: {file} is outside the workspace and the resolved packages; "
            "not read (pass --package-path for a package that lives elsewhere)"
        )


def confinement_for(path: Path, explicit: Iterable[Path], scan_dirs: Iterable[Path]) -> Confinement:
    """The file's workspace (as ``$(find)`` searches it) plus any ``--package-path``."""
    from sensorkit.loading.packages import own_package, workspace_roots

    conf = Confinement()
    pkg = own_package(path)
    conf.add(pkg if pkg is not None else path.resolve().parent)
    for root in workspace_roots(path):
        conf.add(root)
    for folder in [*explicit, *scan_dirs]:
        conf.add(folder)
    return conf


def _plain_format_literal(node: ast.expr) -> bool:
    """``node`` is a string literal whose replacement fields name no attribute or item."""
    import string

    if not isinstance(node, ast.Constant) or not isinstance(node.value, str):
        return False
    try:
        fields = [f for _, f, _, _ in string.Formatter().parse(node.value) if f is not None]
    except ValueError:
        return False
    return not any("." in f or "[" in f for f in fields)


def check_expression(expr: str, *, builtins_reachable: bool = False) -> None:
    """Raise UnsafeExpression if ``expr`` reaches outside the safe subset.

    Refused: names starting with ``__``; attributes starting with ``_`` and
    :data:`DENIED_ATTRIBUTES`; ``.format``/``.format_map`` except on a plain literal;
    with ``builtins_reachable`` (``$(eval)``), builtins other than
    :data:`SAFE_BUILTINS`. Other names (xacro properties, ``math``, ``xacro``) are
    looked up by xacro as usual.
    """
    import builtins

    try:
        tree = ast.parse(expr.strip(), mode="eval")
    except SyntaxError:
        return  # xacro reports the syntax error itself
    unsafe_builtins = set(dir(builtins)) - SAFE_BUILTINS if builtins_reachable else set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute):
            attr = node.attr
            if attr.startswith("_") or attr in DENIED_ATTRIBUTES:
                raise UnsafeExpression(f"--untrusted: attribute .{attr} is not allowed")
            if attr in FORMAT_METHODS and not _plain_format_literal(node.value):
                raise UnsafeExpression(
                    f"--untrusted: .{attr} only on a string literal whose fields are plain"
                )
        elif isinstance(node, ast.Name):
            name = node.id
            if name.startswith("__") or name in unsafe_builtins:
                raise UnsafeExpression(f"--untrusted: {name!r} is not allowed in an expression")


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
