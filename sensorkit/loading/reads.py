"""What a xacro expansion read from the machine, recorded so a cached result can be checked.

An expansion's output depends on its input files and on what xacro looks up while it
runs. ``record_reads`` patches xacro (in the process that expands, for the duration of
one ``expand_in_process``) so that each such read is written down in an ``ExpandDeps``:

- every file read, with the hash of the bytes read: the top file and each include (read
  through the overlay mapping handed to ``_loc_parser``), and each file xacro's
  ``load_yaml`` opens (xacro calls the module-level name ``open``);
- each glob pattern of an include and the sorted list it matched;
- each ``$(env X)`` / ``$(optenv X ...)`` name and the value seen (None: not set);
- each ``$(find pkg)`` name and the folder it resolved to (None: not found);
- the working folder, when a relative path or ``$(cwd)`` made it matter.

What cannot be replayed makes the record ``cacheable=False``: an expression that could
reach outside xacro's symbols (an attribute starting with ``_``; ``type``, ``vars``) or
give another value in another process (``hash``, sets, whose order follows string
hashes), a ``$(eval ...)`` using anything but arithmetic and the args, a read of
something that is not a regular file, or a file that changed while it was read twice.
The record is plain data (it is pickled back from the expansion child).
"""

from __future__ import annotations

import functools
import hashlib
import io
import os
import re
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

from sensorkit.base.regular import MAX_READ, read_regular

# Names that make an expression unrepeatable or let it reach beyond xacro's symbols.
_UNSAFE_NAMES = frozenset(
    {
        "hash", "set", "frozenset", "id", "type", "vars", "dir", "globals", "locals",
        "open", "eval", "exec", "compile", "input", "breakpoint", "getattr", "setattr",
        "delattr", "object", "memoryview", "help", "exit", "quit", "print",
    }
)  # fmt: skip
# What an expression must contain for _unsafe to parse it (a cheap pre-filter): a name or
# attribute starting with "_", a brace (a set), or one of the names above.
_SUSPECT = re.compile(r"(?<![\w.])_|\.\s*_|\{|\b(?:" + "|".join(sorted(_UNSAFE_NAMES)) + r")\b")
# What a ``$(eval ...)`` may name besides the args: its own functions and math's.
_EVAL_NAMES = frozenset({"arg", "dirname", "env", "optenv", "find", "true", "false", "True",
                         "False", "list", "dict", "map", "str", "float", "int"})  # fmt: skip


def digest(data: bytes) -> str:
    """The hash a file's bytes are recorded by."""
    return hashlib.blake2b(data, digest_size=20).hexdigest()


@dataclass
class ExpandDeps:
    """Everything one expansion read (see the module doc); plain, picklable data."""

    files: dict[str, str | None] = field(default_factory=dict)  # path -> digest, None: unreadable
    globs: dict[str, list[str]] = field(default_factory=dict)
    env: dict[str, str | None] = field(default_factory=dict)
    packages: dict[str, str | None] = field(default_factory=dict)
    cwd: str | None = None
    cacheable: bool = True
    why: str = ""  # why not cacheable

    def refuse(self, why: str) -> None:
        if self.cacheable:
            self.cacheable, self.why = False, why

    def saw(self, table: dict[str, Any], key: str, value: Any, what: str) -> None:
        """Record ``key`` -> ``value``; a second, different value is not replayable."""
        if key in table and table[key] != value:
            self.refuse(f"{what} {key} changed during the expansion")
        table.setdefault(key, value)

    def absolute(self, path: str) -> str:
        if not os.path.isabs(path):
            self.cwd = os.getcwd()
        return os.path.abspath(path)


@functools.lru_cache(maxsize=4096)
def _unsafe(expr: str, allowed: frozenset[str] = frozenset()) -> str | None:
    """Why ``expr`` (a Python expression) cannot be replayed from its inputs, or None.
    Kept for each expression: robots evaluate the same few again and again."""
    if not allowed and not _SUSPECT.search(expr):
        return None
    import ast

    try:
        tree = ast.parse(expr.strip(), mode="eval")
    except SyntaxError:
        return None  # xacro reports it; a failed expansion is never stored
    for node in ast.walk(tree):
        if isinstance(node, (ast.Set, ast.SetComp)):
            return "a set (its order follows string hashes)"
        if isinstance(node, ast.Attribute) and (
            node.attr.startswith("_") or node.attr in _UNSAFE_NAMES  # python.hash
        ):
            return f"the attribute {node.attr}"
        if isinstance(node, ast.Name):
            if node.id in _UNSAFE_NAMES or node.id.startswith("_"):
                return f"the name {node.id}"
            if allowed and node.id not in allowed and not _is_math(node.id):
                return f"the name {node.id} in $(eval)"
    return None


def _is_math(name: str) -> bool:
    import math

    return not name.startswith("_") and hasattr(math, name)


class _ReadingOverlay(Mapping[str, bytes]):
    """The overlay ``_loc_parser`` reads every file through: the caller's overlay where it
    holds the file, else the disk; each read is recorded with the hash of its bytes."""

    def __init__(self, deps: ExpandDeps, overlay: Mapping[str, bytes] | None) -> None:
        self.deps = deps
        self.base = overlay or {}

    def __bool__(self) -> bool:
        return True

    def __contains__(self, key: object) -> bool:
        return isinstance(key, str)

    def __getitem__(self, key: str) -> bytes:
        path = self.deps.absolute(key)
        if path in self.base:
            data = self.base[path]
        else:
            try:
                data = _read_regular(path, self.deps)
            except OSError:
                self.deps.saw(self.deps.files, path, None, "file")
                raise
        self.deps.saw(self.deps.files, path, digest(data), "file")
        return data

    def __iter__(self) -> Iterator[str]:
        return iter(self.base)

    def __len__(self) -> int:
        return len(self.base)


def _read_regular(path: str, deps: ExpandDeps) -> bytes:
    """The bytes of ``path``, a regular file (base.regular: a pipe, a device is refused)."""
    return read_regular(path, MAX_READ)


@dataclass
class Recording:
    """The patches ``record_reads`` made; ``restore`` undoes them (in a ``finally``)."""

    deps: ExpandDeps
    overlay: Mapping[str, bytes]
    undo: list[Callable[[], None]] = field(default_factory=list)

    def restore(self) -> None:
        for step in reversed(self.undo):
            step()
        self.undo.clear()


def _patch(rec: Recording, owner: Any, name: str, value: Any) -> None:
    """``owner.name = value`` (``owner`` a module or a dict), undone by ``rec.restore``."""
    if isinstance(owner, dict):
        had, old = name in owner, owner.get(name)
        owner[name] = value
        rec.undo.append(lambda: owner.__setitem__(name, old) if had else owner.pop(name, None))
        return
    had, old = name in vars(owner), vars(owner).get(name)
    setattr(owner, name, value)
    rec.undo.append(lambda: setattr(owner, name, old) if had else vars(owner).pop(name, None))


def record_reads(xacro: Any, sa: Any, overlay: Mapping[str, bytes] | None) -> Recording:
    """Patch ``xacro`` and its ``substitution_args`` (``sa``) to record what the expansion
    reads. Call after the expansion's own patches (it wraps them); pass
    ``Recording.overlay`` to ``_loc_parser`` as its overlay; ``restore`` in ``finally``."""
    deps = ExpandDeps()
    rec = Recording(deps, _ReadingOverlay(deps, overlay))
    base = overlay or {}
    _record_lookups(rec, sa)
    inner_open = vars(xacro).get("open", open)

    def recording_open(file: Any, mode: str = "r", *a: Any, **kw: Any) -> Any:
        # xacro.load_yaml: open(filename) in text mode. The bytes are read once, hashed,
        # and decoded as open() would (locale encoding, universal newlines).
        if mode not in ("r", "rt") or a or kw:
            deps.refuse(f"xacro opened {file} with mode {mode!r}")
            return inner_open(file, mode, *a, **kw)
        path = deps.absolute(str(file))
        # never a pipe or a device, trusted or not (base.regular)
        data = base[path] if path in base else read_regular(path, MAX_READ)
        deps.saw(deps.files, path, digest(data), "file")
        return io.TextIOWrapper(io.BytesIO(data), encoding=None)

    class _Glob:
        @staticmethod
        def glob(pattern: str, *a: Any, **kw: Any) -> list[str]:
            import glob as real

            found: list[str] = real.glob(pattern, *a, **kw)
            if a or kw:
                deps.refuse("a glob with options")
            deps.saw(deps.globs, deps.absolute(pattern), sorted(found), "glob")
            return found

    inner_eval = xacro.safe_eval
    inner_ext = xacro.eval_extension

    def safe_eval(expr: str, symbols: Any, local: Any = None) -> Any:
        why = _unsafe(expr) if isinstance(expr, str) else "an expression that is not text"
        if why:
            deps.refuse(f"${{{expr}}} uses {why}")
        return inner_eval(expr, symbols, local)

    def eval_extension(s: str) -> Any:
        if s == "$(cwd)":
            deps.cwd = os.getcwd()
        return inner_ext(s)

    _patch(rec, xacro, "open", recording_open)
    _patch(rec, xacro, "glob", _Glob)
    _patch(rec, xacro, "safe_eval", safe_eval)
    _patch(rec, xacro, "eval_extension", eval_extension)
    return rec


def _record_lookups(rec: Recording, sa: Any) -> None:
    """Wrap ``$(env)``, ``$(optenv)``, ``$(find)`` and ``$(eval)`` to record them."""
    deps = rec.deps
    inner_env, inner_optenv = sa._eval_env, sa._eval_optenv
    inner_find, inner_eval = sa._eval_find, sa._eval

    def env(name: str) -> str:
        deps.saw(deps.env, name, os.environ.get(name), "environment variable")
        value: str = inner_env(name)
        return value

    def optenv(name: str, default: str = "") -> str:
        deps.saw(deps.env, name, os.environ.get(name), "environment variable")
        value: str = inner_optenv(name, default)
        return value

    def find(pkg: str) -> str:
        try:
            folder: str = inner_find(pkg)
        except Exception:
            deps.saw(deps.packages, pkg, None, "package")
            raise
        deps.saw(deps.packages, pkg, str(folder), "package")
        return folder

    def eval_sub(s: str, context: Any) -> Any:
        names = frozenset(_EVAL_NAMES | set((context or {}).get("arg", {})))
        why = _unsafe(s, names) if isinstance(s, str) else "an expression that is not text"
        if why:
            deps.refuse(f"$(eval {s}) uses {why}")
        return inner_eval(s, context)

    for name, value in (("_eval_env", env), ("_eval_optenv", optenv), ("_eval_find", find)):
        _patch(rec, sa, name, value)
    _patch(rec, sa, "_eval", eval_sub)
    for name, value in (("env", env), ("optenv", optenv), ("find", find)):
        _patch(rec, sa._eval_dict, name, value)
