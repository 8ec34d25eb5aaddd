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

import contextlib
import operator
import os
import time
from collections.abc import Callable
from typing import Any

from sensorkit.loading.kept_includes import (
    MAX_NODES,
    IncludeMemo,
    Keeper,
    Kept,
    Recorder,
    Space,
    Unkept,
    node_fp,
    plain,
    splice,
    value_fp,
)

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


# -- the language server: included files' and macro calls' results kept ---------------
#
# A ``<xacro:include>`` or a macro call evaluated in the document's own tables (at any
# depth of elements, but not inside a macro's body) is a function of what it starts from
# and what it reads: the tables (every property, its value and whether it is still
# unevaluated, namespaces within; every macro, its parameters, defaults and body), the
# args, the files read so far (their order numbers the line stamps), xacro's file stack,
# the working folder, the include's attributes or the call's XML (its blocks), and what it
# reads from the machine (each file's bytes, each ``$(find)``, ``$(env)``, glob, as
# ``reads`` records them). Its result is the tables and args after it, the elements it
# puts in its place, the namespaces it lifts to its parent, the files it added, its
# reads. One kept with the same start whose every read still gives what it gave is
# replayed: the tables set to what they were after it, its elements (kept privately, moved
# into the new document) put in place by xacro's own tail of ``process_include`` or
# ``handle_macro_call`` (``remove_previous_comments``, ``import_xml_namespaces``,
# ``replace_node``). Anything else is expanded by xacro and kept. xacro's one shared text
# node (``_empty_text_node``, which ``remove_previous_comments`` moves about) is put back
# where xacro had left it. tests/test_xacro_fast.py compares every result with a cold
# expansion over random edits.

_MEMO: IncludeMemo | None = None


def keep_includes(on: bool = True) -> IncludeMemo | None:
    """Keep included files' results from expansion to expansion in this process (the
    language server; see above); ``on=False`` forgets them. Returns the memo."""
    global _MEMO  # noqa: PLW0603 (one per process)
    _MEMO = IncludeMemo() if on and supported() else None
    return _MEMO


_MACRO_FP: dict[int, tuple[Any, ...]] = {}  # id(macro) -> (macro, body, params, defaults, fp)


def _macro_fp(xacro: Any, macro: Any) -> Any:
    if type(macro) is xacro.NameSpace:  # the macros of an include with ``ns``
        if isinstance(macro.parent, xacro.Table):
            raise Unkept
        return ("ns", tuple((k, _macro_fp(xacro, m)) for k, m in dict.items(macro)))
    if type(macro) is not xacro.Macro:
        raise Unkept
    # grab_macro gives a macro defined again a new body, params and defaults
    known = _MACRO_FP.get(id(macro))
    parts = (macro, macro.body, macro.params, macro.defaultmap)
    if known is not None and all(a is b for a, b in zip(known, parts, strict=False)):
        return known[4]
    if not plain(macro.defaultmap):
        raise Unkept
    body = node_fp(macro.body) if macro.body is not None else None
    fp = (tuple(macro.params), repr(macro.defaultmap), body)
    if len(_MACRO_FP) >= MAX_NODES:
        _MACRO_FP.clear()
    _MACRO_FP[id(macro)] = (*parts, fp)
    return fp


_SCALARS = frozenset({str, int, float, bool, type(None)})


def _table_fp(xacro: Any, table: Any, known: dict[int, tuple[Any, ...]] | None = None) -> Any:
    """What a property table is compared by (a namespace in it: its own, recursively).
    A table of scalars only, the usual case, by its keys and values' ``repr`` (which
    tells their types apart), in C loops; ``known`` gives the same answer, the same
    object, for the same table holding the very same values as when last asked."""
    values = list(dict.values(table))
    if set(map(type, values)) <= _SCALARS:
        keys = list(dict.keys(table))
        unevaluated = frozenset(table.unevaluated)
        last = known.get(id(table)) if known is not None else None
        if (
            last is not None
            and last[0] is table
            and last[1] == keys
            and len(last[2]) == len(values)
            and all(map(operator.is_, last[2], values))
            and last[3] == unevaluated
        ):
            return last[4]
        scalars = (tuple(keys), tuple(map(repr, values)), unevaluated)
        if known is not None:
            known[id(table)] = (table, keys, values, unevaluated, scalars)
        return scalars
    out = []
    for k, v in dict.items(table):
        if type(v) is xacro.NameSpace:
            if v.parent is not table:
                raise Unkept
            fp: Any = ("ns", _table_fp(xacro, v))
        else:
            fp = value_fp(v)
        out.append((k, fp, k in table.unevaluated))
    return tuple(out)


def _snapshot(xacro: Any, table: Any, macros: bool) -> list[tuple[str, Any]]:
    """A table's items to keep: macros copied, namespaces as Space."""
    out: list[tuple[str, Any]] = []
    for k, v in dict.items(table):
        if type(v) is xacro.NameSpace:
            out.append((k, Space(_snapshot(xacro, v, macros), set(v.unevaluated))))
        else:
            out.append((k, _copy_macro(v) if macros else v))
    return out


def _rebuild(xacro: Any, items: list[tuple[str, Any]], table: Any, macros: bool) -> None:
    """Put kept items into ``table`` (namespaces made anew under it, macros copied)."""
    for k, kept in items:
        value = kept
        if isinstance(kept, Space):
            value = xacro.NameSpace() if macros else xacro.NameSpace(parent=table)
            _rebuild(xacro, kept.items, value, macros)
            value.unevaluated.update(kept.unevaluated)
        elif macros:
            value = _copy_macro(kept)
        dict.__setitem__(table, k, value)


def _copy_macro(macro: Any) -> Any:
    """A macro to put in a table: its own lists (``grab_macro`` of a redefinition changes
    the macro it finds in place), the same body (xacro only ever clones it)."""
    import copy

    out = copy.copy(macro)
    out.history = list(macro.history)
    out.params = list(macro.params)
    out.defaultmap = dict(macro.defaultmap)
    return out


def _top_tables(xacro: Any, macros: Any, symbols: Any) -> bool:
    """Whether the include is evaluated in the document's own tables (not in a macro's)."""
    return (
        type(symbols) is xacro.Table
        and type(macros) is xacro.Table
        and symbols.parent is symbols.root
        and not isinstance(macros.parent, xacro.Table)
    )


class _Run(Keeper):
    """One expansion's use of the kept results: the functions ``reuse_includes`` sets."""

    def __init__(self, memo: IncludeMemo, xacro: Any, find: Any, files: list[str], rec: Any):
        super().__init__(memo, rec, find, files, xacro._empty_text_node)
        self.xacro = xacro
        self.watch: dict[int, Recorder] = {}
        self.known: dict[int, tuple[Any, ...]] = {}  # _table_fp's last answers
        self.real_include = xacro.process_include
        self.real_call = xacro.handle_macro_call
        self.real_remove = xacro.remove_previous_comments
        self.real_replace = xacro.replace_node

    def start(self, kind: str, node: Any, macros: Any, symbols: Any) -> tuple[Any, ...]:
        """(where, what it starts from, the macros' fingerprints); Unkept if not known."""
        x = self.xacro
        what = tuple(sorted(node.attributes.items())) if kind == "include" else node.toxml()
        place = (kind, what, tuple(x.filestack or ()), tuple(self.files))
        macro_fps = {k: _macro_fp(x, m) for k, m in dict.items(macros)}
        args = x.substitution_args_context.get("arg")
        if not plain(args) or set(x.substitution_args_context) != {"arg"}:
            raise Unkept
        table = _table_fp(x, symbols, self.known)
        start = (what, table, tuple(macro_fps.items()), repr(args), os.getcwd())
        return place, start, macro_fps

    def kept_or_run(self, kind: str, node: Any, macros: Any, symbols: Any, run: Any) -> Any:
        """Replay a kept result for ``node``, else ``run()`` xacro's own and keep it."""
        if not _top_tables(self.xacro, macros, symbols):
            return run()
        self.budget -= len(symbols) + len(macros)
        if self.budget < 0:  # too large to compare at each call: as without the memo
            return run()
        try:
            place, start, macro_fps = self.start(kind, node, macros, symbols)
        except Unkept:
            return run()
        for kept in self.memo.candidates(place):
            if id(kept) not in self.used and kept.start == start and self.holds(kept):
                self.used.add(id(kept))
                self.replay(kept, node, macros, symbols)
                self.memo.replayed += 1
                return True
        rec = self.begin(place, start, macro_fps, len(self.xacro.all_includes))
        self.watch[id(node)] = rec
        try:
            result = run()
        finally:
            self.watch.pop(id(node), None)
            cwd = self.end(rec)
        self.memo.expanded += 1
        if rec.ok and rec.roots is not None:
            with contextlib.suppress(Unkept):
                self.memo.put(place, self.keep(kind, rec, cwd, macros, symbols))
        return result

    # -- the functions set in xacro's module ---------------------------------------------
    def process_include(self, elt: Any, macros: Any, symbols: Any, func: Any) -> None:
        def run() -> None:
            self.real_include(elt, macros, symbols, func)

        self.kept_or_run("include", elt, macros, symbols, run)

    def handle_macro_call(self, node: Any, macros: Any, symbols: Any) -> Any:
        if node.tagName == "xacro:call" or not node.tagName.startswith("xacro:"):
            return self.real_call(node, macros, symbols)
        return self.kept_or_run(
            "macro", node, macros, symbols, lambda: self.real_call(node, macros, symbols)
        )

    def remove_previous_comments(self, node: Any) -> Any:
        rec = self.watch.get(id(node))
        if rec is not None and rec.roots is None:
            self.seen_single(rec)
        return self.real_remove(node)

    def replace_node(self, node: Any, by: Any = None, content_only: bool = False) -> Any:
        rec = self.watch.get(id(node))
        if rec is not None and rec.roots is None and content_only and by is not None:
            self.capture(rec, by if isinstance(by, list) else [by])
        return self.real_replace(node, by, content_only)

    # -- keeping and replaying -----------------------------------------------------------
    def keep(self, kind: str, rec: Recorder, cwd: str | None, macros: Any, symbols: Any) -> Kept:
        x = self.xacro
        changed = {}
        for name, macro in dict.items(macros):
            if rec.macros_before.get(name) != _macro_fp(x, macro):
                changed[name] = macro
        after = _table_fp(x, symbols, self.known)  # every value one that can be compared
        same = after is rec.start[1]  # the very same table: nothing to set on a replay
        assert rec.roots is not None
        return Kept(
            kind=kind,
            start=rec.start,
            reads=rec.reads,
            cwd=cwd,
            files=self.files[rec.files_at :],
            includes=list(x.all_includes[rec.includes_at :]),
            roots=rec.roots,
            slot=rec.slot,
            symbols=None if same else _snapshot(x, symbols, False),
            unevaluated=set(symbols.unevaluated),
            macros=_snapshot(x, changed, True),
            args=dict(x.substitution_args_context["arg"]),
            nodes=rec.nodes,
        )

    def replay(self, kept: Kept, node: Any, macros: Any, symbols: Any) -> None:
        x = self.xacro
        kids = self.put_back(kept)
        x.all_includes.extend(kept.includes)
        if kept.symbols is not None:
            dict.clear(symbols)
            _rebuild(x, kept.symbols, symbols, False)
            symbols.unevaluated.clear()
            symbols.unevaluated.update(kept.unevaluated)
        _rebuild(x, kept.macros, macros, True)
        args = x.substitution_args_context["arg"]
        args.clear()
        args.update(kept.args)
        roots = [root for root, _children in kept.roots]
        if kept.kind == "include":  # as xacro's process_include ends
            for root in roots:
                x.import_xml_namespaces(node.parentNode, root.attributes)
            self.real_remove(node)
        else:  # as xacro's handle_macro_call ends
            self.real_remove(node)
            x.import_xml_namespaces(node.parentNode, roots[0].attributes)
        if self.single.parentNode is not None:  # remove_previous_comments moved it out
            kids = [kid for kid in kids if kid is not self.single]
        splice(node, kids)  # replace_node(node, roots, content_only=True)


def reuse_includes(
    xacro: Any,
    find: Callable[[str], Any],
    files: list[str],
    recording: Any,
    undo: list[Callable[[], None]],
) -> None:
    """Replay kept includes and macro calls and keep new ones in this expansion (when
    :func:`keep_includes` is on; see above). ``recording``: the expansion's ``reads.Recording``; ``files``: the
    list the line stamps number; ``find``: ``$(find)`` unrecorded. Call after every other
    patch of the expansion."""
    memo = _MEMO
    if memo is None or not supported():
        return
    run = _Run(memo, xacro, find, files, recording)
    _set(xacro, "process_include", run.process_include, undo)
    _set(xacro, "handle_macro_call", run.handle_macro_call, undo)
    _set(xacro, "remove_previous_comments", run.remove_previous_comments, undo)
    _set(xacro, "replace_node", run.replace_node, undo)
    undo.append(run.patch_deps())
