"""Where sensorkit reaches into xacro's internals to expand faster (issue 37), in one place.

Three things, each only for the xacro versions in :data:`TESTED` (any other version runs
xacro untouched, in the forked child of ``xacro_expand``):

- **Lexing once.** xacro lexes every attribute and text holding ``$`` each time it is
  evaluated (``eval_text`` builds a ``QuickLexer`` and lexes), although robots evaluate
  the same few strings again and again (turtlebot4: 1,302 evaluations of 206 strings).
  :func:`lexer_class` is xacro's own lexer whose ``lex`` keeps the tokens of each text it
  lexed; later texts replay them. A text that does not lex is lexed by xacro every time,
  so its error comes as xacro raises it.
- **Compiling once.** xacro's ``safe_eval`` compiles each expression with the builtin
  ``compile``; :func:`cached_compile`, set as ``compile`` in xacro's module namespace,
  keeps each compiled expression. xacro's checks and ``eval`` run as before. In this
  process (below) the allow-list evaluator's parse of each expression is kept likewise.
- **Expanding trusted input in this process, bounded.** :func:`bound` makes every
  ``${...}`` and ``$(eval ...)`` go through the allow-list evaluator of ``--untrusted``
  (sensorkit.loading.untrusted, which bounds integer and sequence sizes and the steps of
  one expression), checks a deadline and the process's memory while xacro walks the
  document (each element it evaluates), and stops with :class:`NotHere` where the forked
  child must decide instead: an expression the evaluator does not take, memory grown past
  the child's limit. ``xacro_expand.expand`` then runs the forked child, whose answer is
  what sensorkit gave before; so does any failed in-process expansion, so that a finding's
  words never depend on which evaluator ran. A runaway ``${10**10**10}`` is refused by the
  evaluator's bound and times out in the child, as before.

Nothing of xacro's code is copied: xacro's own functions run, with these names of its
module replaced for one expansion and put back after (``xacro_expand.expand_in_process``).
tests/test_xacro_fast.py compares the result with xacro's own command line, byte for byte,
on every robot of the corpus.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from typing import Any

# xacro releases this module was checked against (tests/test_xacro_fast.py): the version
# of the xacro distribution installed beside the module.
TESTED = ("2.1.1",)
MAX_KEPT = 20_000  # texts (and expressions) kept at most; the cache starts over past it
MAX_TEXT = 4096  # longer texts are lexed each time (a whole text node, rarely repeated)
CHECK_EVERY = 64  # elements between two looks at the clock and the memory


class NotHere(BaseException):
    """This expansion must run in the forked child (see the module doc). A BaseException,
    so that xacro's ``except Exception`` handlers do not wrap it into an error of theirs."""


class OverTime(BaseException):
    """The in-process expansion ran past its deadline."""


_supported: bool | None = None


def supported() -> bool:
    """Whether the installed xacro is one of :data:`TESTED` (a ``xacro-VERSION.dist-info``
    folder beside the imported module)."""
    global _supported  # noqa: PLW0603 (asked once a process)
    if _supported is None:
        import xacro

        site = os.path.dirname(os.path.dirname(os.path.abspath(xacro.__file__ or "")))
        _supported = any(
            os.path.isdir(os.path.join(site, f"xacro-{v}.dist-info")) for v in TESTED
        ) and all(
            callable(getattr(xacro, name, None))
            for name in ("QuickLexer", "eval_text", "safe_eval", "eval_all")
        )
    return _supported


# -- lexing and compiling once -------------------------------------------------------------
_TOKENS: dict[str, tuple[Any, ...]] = {}
_lexers: dict[Any, Any] = {}


def _tokens(lexer: Any, text: str) -> tuple[Any, ...] | None:
    """Every token xacro's lexer gives for ``text``, or None when lexing fails."""
    try:
        lexer.lex(text)
        out = []
        while lexer.peek():
            out.append(lexer.next())
    except Exception:
        return None
    return tuple(out)


def lexer_class(base: Any) -> Any:
    """xacro's ``QuickLexer`` (``base``) keeping the tokens of every text it lexed."""
    known = _lexers.get(base)
    if known is not None:
        return known

    class CachedLexer(base):  # type: ignore[misc]
        _replay: tuple[Any, ...] | None = None
        _at = 0

        def lex(self, text: str) -> None:
            tokens = _TOKENS.get(text) if type(text) is str else None
            if tokens is None and type(text) is str and len(text) <= MAX_TEXT:
                tokens = _tokens(base(self), text)
                if tokens is not None:
                    if len(_TOKENS) >= MAX_KEPT:
                        _TOKENS.clear()
                    _TOKENS[text] = tokens
            self._replay, self._at = tokens, 0
            if tokens is None:
                base.lex(self, text)

        def peek(self) -> Any:
            replay = self._replay
            if replay is None:
                return base.peek(self)
            return replay[self._at] if self._at < len(replay) else None

        def next(self) -> Any:
            replay = self._replay
            if replay is None:
                return base.next(self)
            if self._at >= len(replay):
                return None
            self._at += 1
            return replay[self._at - 1]

    _lexers[base] = CachedLexer
    return CachedLexer


_CODE: dict[tuple[Any, ...], Any] = {}


def cached_compile(source: Any, filename: str, mode: str, *args: Any, **kwargs: Any) -> Any:
    """The builtin ``compile``, keeping what it compiled from text (same arguments, same
    code object: code objects are immutable)."""
    if args or kwargs or type(source) is not str:
        return compile(source, filename, mode, *args, **kwargs)
    key = (source, filename, mode)
    code = _CODE.get(key)
    if code is None:
        code = compile(source, filename, mode)
        if len(_CODE) >= MAX_KEPT:
            _CODE.clear()
        _CODE[key] = code
    return code


def speed_up(xacro: Any, undo: list[Callable[[], None]]) -> None:
    """Lex and compile each text once (see the module doc); ``undo`` gets what puts xacro
    back. Nothing when the installed xacro is not one tested."""
    if not supported():
        return
    _set(xacro, "QuickLexer", lexer_class(xacro.QuickLexer), undo)
    _set(xacro, "compile", cached_compile, undo)


def _set(owner: Any, name: str, value: Any, undo: list[Callable[[], None]]) -> None:
    had, old = name in vars(owner), vars(owner).get(name)
    setattr(owner, name, value)
    undo.append(lambda: setattr(owner, name, old) if had else vars(owner).pop(name, None))


# -- trusted input in this process, bounded ---------------------------------------------
_TREES: dict[str, Any] = {}


def _parsed(parse: Callable[[str], Any]) -> Callable[[str], Any]:
    """The allow-list evaluator's ``parse`` (text to checked tree), keeping each tree: the
    evaluator only reads it. What it refuses raises each time, as before."""

    def cached(expr: str) -> Any:
        tree = _TREES.get(expr)
        if tree is None:
            tree = parse(expr)
            if len(_TREES) >= MAX_KEPT:
                _TREES.clear()
            _TREES[expr] = tree
        return tree

    return cached


def _resident() -> int | None:
    """This process's resident memory in bytes (Linux), else None."""
    try:
        with open("/proc/self/statm", "rb") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return None


def bound(xacro: Any, sa: Any, timeout: float, memory: int, undo: list[Callable[[], None]]) -> None:
    """Evaluate ``${...}`` and ``$(eval ...)`` by the allow-list evaluator and watch time
    and memory while xacro walks the document (see the module doc). Call after the
    expansion's other patches of ``sa``'s evaluator; ``undo`` gets what puts xacro back."""
    from sensorkit.loading import safe_eval as allow_list
    from sensorkit.loading.untrusted import UnsafeExpression, XacroEvaluator

    evaluator = XacroEvaluator(xacro, sa)
    _set(allow_list, "parse", _parsed(allow_list.parse), undo)
    deadline = time.monotonic() + timeout
    start = _resident()
    walked = [0]

    def safe_eval(expr: str, symbols: Any, local: Any = None) -> Any:
        try:
            return evaluator.expression(expr, symbols, local)
        except UnsafeExpression:
            raise NotHere from None

    def eval_sub(s: str, context: Any) -> Any:
        try:
            return evaluator.substitution(s, context)
        except UnsafeExpression:
            raise NotHere from None

    inner_all = xacro.eval_all

    def eval_all(node: Any, macros: Any, symbols: Any) -> Any:
        walked[0] += 1
        if walked[0] % CHECK_EVERY == 0:
            if time.monotonic() > deadline:
                raise OverTime
            now = _resident()
            if start is not None and now is not None and now - start > memory:
                raise NotHere
        return inner_all(node, macros, symbols)

    _set(xacro, "safe_eval", safe_eval, undo)
    _set(xacro, "eval_all", eval_all, undo)
    _set(sa, "_eval", eval_sub, undo)
