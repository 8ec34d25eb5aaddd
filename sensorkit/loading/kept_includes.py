"""What the language server keeps of xacro's work from edit to edit: the results of
included files and of macro calls evaluated in the document's own tables.

The part that reaches into xacro is ``sensorkit.loading.xacro_fast``
(:func:`~sensorkit.loading.xacro_fast.reuse_includes`, which says what is kept and when
it is replayed); here, with nothing of xacro imported or touched, are the kept results
and their store, how property values are compared (by their type and ``repr``, XML nodes
by their XML), and :class:`Keeper`: what an expansion read (checked again before a
replay) and the elements put in place (private copies, moved into the new document).
"""

from __future__ import annotations

import glob
import os
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from sensorkit.base.regular import MAX_READ, read_regular
from sensorkit.loading.reads import digest

# Macro bodies and blocks whose XML is kept (each holds its DOM alive: a few KiB to some
# tens), and macros whose fingerprint is; either starts over past it.
MAX_NODES = 2048

MAX_INCLUDES = 4096  # places kept at most (the least recently used go first)
PER_PLACE = 4  # results kept for one include in one place (one file stack)
# What is kept and compared is bounded in table entries (each result keeps the tables
# after it, each include or call compares the tables before it): a robot of thousands of
# properties and calls expands as without the memo past these, never slower by much.
MAX_WEIGHT = 200_000  # table entries and DOM nodes kept over all results (~1 KiB a node)
RUN_BUDGET = 2_000_000  # table entries compared in one expansion


class Unkept(Exception):
    """This include's result cannot be kept (a value that cannot be compared)."""


@dataclass
class Kept:
    kind: str  # "include" or "macro"
    start: tuple[Any, ...]
    reads: list[tuple[str, str, Any, str]]  # (table, key, value, what) as ExpandDeps.saw
    cwd: str | None  # the working folder, if the include's reads made it matter
    files: list[str]
    includes: list[str]
    roots: list[tuple[Any, list[Any]]]  # each file's root element and its children
    slot: tuple[Any, int] | None  # (parent, index) of xacro's shared text node
    symbols: list[tuple[str, Any]] | None  # None: the table as it was before
    unevaluated: set[str]
    macros: list[tuple[str, Any]]  # macros new or changed, in table order
    args: dict[str, Any]
    nodes: int = 0  # the nodes its elements hold

    @property
    def weight(self) -> int:
        return len(self.symbols or ()) + self.nodes + 1


class IncludeMemo:
    """Included files' results kept across expansions (see above)."""

    def __init__(self) -> None:
        self.kept: OrderedDict[tuple[Any, ...], list[Kept]] = OrderedDict()
        self.replayed = 0  # counters, for tests and benchmarks
        self.expanded = 0
        self.weight = 0
        self.runs = 0  # expansions so far; a place remembers the last that used it
        self.used_in: dict[tuple[Any, ...], int] = {}

    def candidates(self, place: tuple[Any, ...]) -> list[Kept]:
        found = self.kept.get(place)
        if found is None:
            return []
        self.kept.move_to_end(place)
        self.used_in[place] = self.runs
        return found

    def put(self, place: tuple[Any, ...], kept: Kept) -> None:
        """Keep ``kept``; when full, the least recently used place goes, unless this
        expansion used it too (a robot larger than the store keeps what it has instead
        of pushing out, call after call, the results it is about to need)."""
        if place not in self.kept:
            while len(self.kept) >= MAX_INCLUDES or self.weight + kept.weight > MAX_WEIGHT:
                if not self.kept or self.used_in.get(next(iter(self.kept))) == self.runs:
                    return
                gone_place, gone = self.kept.popitem(last=False)
                self.used_in.pop(gone_place, None)
                self.weight -= sum(k.weight for k in gone)
        found = self.kept.setdefault(place, [])
        found.insert(0, kept)
        self.weight += kept.weight
        for old in found[PER_PLACE:]:
            self.weight -= old.weight
        del found[PER_PLACE:]
        self.kept.move_to_end(place)
        self.used_in[place] = self.runs


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
    if len(_FP) >= MAX_NODES:
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


@dataclass
class Recorder:
    """One include or macro call being expanded by xacro, to be kept."""

    place: tuple[Any, ...]
    start: tuple[Any, ...]
    macros_before: dict[str, Any]
    files_at: int
    includes_at: int
    single_at: tuple[Any, Any, Any]  # the shared text node's parent and siblings
    cwd_before: str | None
    reads: list[tuple[str, str, Any, str]] = field(default_factory=list)
    ok: bool = True
    single_seen: tuple[Any, int, Any, Any] | None = None  # (parent, index, siblings)
    roots: list[tuple[Any, list[Any]]] | None = None
    slot: tuple[Any, int] | None = None
    nodes: int = 0


class Keeper:
    """What one expansion reads while results are recorded, and the DOM side of keeping
    and replaying them. ``single``: xacro's one shared text node, which its
    ``remove_previous_comments`` moves about; ``find``: ``$(find)``, unrecorded."""

    def __init__(
        self,
        memo: IncludeMemo,
        recording: Any,
        find: Callable[[str], Any],
        files: list[str],
        single: Any,
    ) -> None:
        self.memo, self.find, self.files, self.single = memo, find, files, single
        self.deps, self.overlay = recording.deps, recording.overlay
        self.active: list[Recorder] = []
        self.used: set[int] = set()  # a kept result is put in one place per expansion
        self.budget = RUN_BUDGET
        memo.runs += 1
        self.digests: dict[str, str | None] = {}

    def holds(self, kept: Kept) -> bool:
        """Whether every read of ``kept`` still gives what it gave (read unrecorded: only
        a replay adds its reads to the expansion's)."""
        for table, key, value, _what in kept.reads:
            if table == "files":
                now: Any = self.digest(key)
            elif table == "env":
                now = os.environ.get(key)
            elif table == "packages":
                try:
                    now = str(self.find(key))
                except Exception:
                    now = None
            else:
                now = sorted(glob.glob(key))
            if now != value:
                return False
        return True

    def digest(self, path: str) -> str | None:
        """The digest of ``path``'s bytes now (the overlay's), once per expansion."""
        if path not in self.digests:
            base = self.overlay.base
            try:
                data = base[path] if path in base else read_regular(path, MAX_READ)
                self.digests[path] = digest(data)
            except OSError:
                self.digests[path] = None
        return self.digests[path]

    def begin(self, place: Any, start: Any, macros: dict[str, Any], includes: int) -> Recorder:
        s = self.single
        rec = Recorder(
            place, start, macros, len(self.files), includes,
            (s.parentNode, s.previousSibling, s.nextSibling), self.deps.cwd,
        )  # fmt: skip
        self.deps.cwd = None  # whether this one's reads make the working folder matter
        self.active.append(rec)
        return rec

    def end(self, rec: Recorder) -> str | None:
        """Stop recording ``rec``; the working folder if its reads made it matter."""
        self.active.remove(rec)
        own: str | None = self.deps.cwd
        self.deps.cwd = rec.cwd_before if rec.cwd_before is not None else own
        return own

    def seen_single(self, rec: Recorder) -> None:
        """Where the shared text node is as xacro's tail of the include or call begins."""
        s = self.single
        parent = s.parentNode
        index = parent.childNodes.index(s) if parent is not None else -1
        rec.single_seen = (parent, index, s.previousSibling, s.nextSibling)

    def capture(self, rec: Recorder, roots: list[Any]) -> None:
        """Private copies of what the include or call puts in place, and where the shared
        text node was when xacro's tail began: inside those elements (its slot), or where
        it was before (else nothing is kept)."""
        seen = rec.single_seen
        if seen is None:
            rec.ok = False
            return
        parent, index, before, after = seen
        found = path_in(parent, roots)
        if found is None and (parent, before, after) != rec.single_at:
            rec.ok = False
            return
        copies = [r.cloneNode(True) for r in roots]
        if found is not None:
            which, path = found
            slot = copies[which]
            for i in path:
                slot = slot.childNodes[i]
            if self.single.parentNode is parent:  # still there: its copy is not the node
                slot.removeChild(slot.childNodes[index])
            rec.slot = (slot, index)
        rec.roots = [(c, list(c.childNodes)) for c in copies]
        rec.nodes = sum(_count(c) for c in copies)

    def put_back(self, kept: Kept) -> list[Any]:
        """Add ``kept``'s reads and files to this expansion; the nodes to put in its place
        (the shared text node back in its slot)."""
        deps = self.deps
        for table, key, value, what in kept.reads:
            deps.saw(getattr(deps, table), key, value, what)
        if kept.cwd is not None and deps.cwd is None:
            deps.cwd = kept.cwd
        self.files.extend(kept.files)
        single = self.single
        slot_parent, slot_index = kept.slot if kept.slot is not None else (None, 0)
        if slot_parent is not None and single.parentNode is not None:
            single.parentNode.removeChild(single)
        kids: list[Any] = []
        for root, children in kept.roots:
            if slot_parent is root:
                children = [*children[:slot_index], single, *children[slot_index:]]  # noqa: PLW2901
            kids += children
        if slot_parent is not None and all(slot_parent is not root for root, _c in kept.roots):
            after = slot_parent.childNodes
            slot_parent.insertBefore(single, after[slot_index] if slot_index < len(after) else None)
        return kids

    def patch_deps(self) -> Callable[[], None]:
        """Record every read and refusal of the expansion's ``ExpandDeps`` into the results
        being recorded; returns what undoes it."""
        deps = self.deps
        names = {id(deps.files): "files", id(deps.env): "env", id(deps.packages): "packages"}
        inner_saw, inner_refuse = deps.saw, deps.refuse

        def saw(table: dict[str, Any], key: str, value: Any, what: str) -> None:
            name = names.get(id(table), "globs")
            for rec in self.active:
                rec.reads.append((name, key, value, what))
            inner_saw(table, key, value, what)

        def refuse(why: str) -> None:
            for rec in self.active:
                rec.ok = False
            inner_refuse(why)

        deps.saw, deps.refuse = saw, refuse

        def unpatch() -> None:
            for name in ("saw", "refuse"):
                vars(deps).pop(name, None)

        return unpatch


def splice(node: Any, kids: list[Any]) -> None:
    """What xacro's ``replace_node(node, by=roots, content_only=True)`` makes of kept
    nodes: ``kids`` in ``node``'s place, in one step instead of one list search each. The
    documents ``kids`` were in before are let go (a kept result's nodes are its own and
    are in one document at a time), so they are not taken out of them."""
    from xml.dom.minidom import _clear_id_cache  # type: ignore[attr-defined]

    parent = node.parentNode
    at = parent.childNodes.index(node)
    prev = parent.childNodes[at - 1] if at else None
    for kid in kids:
        kid.parentNode = parent
        kid.previousSibling = prev
        if prev is not None:
            prev.nextSibling = kid
        prev = kid
    after = node.nextSibling
    if prev is not None:
        prev.nextSibling = after
    if after is not None:
        after.previousSibling = prev
    parent.childNodes[at : at + 1] = kids
    node.parentNode = node.previousSibling = node.nextSibling = None
    _clear_id_cache(parent)


def _count(node: Any) -> int:
    """The nodes of ``node``'s tree."""
    total, stack = 0, [node]
    while stack:
        n = stack.pop()
        total += 1
        stack.extend(n.childNodes)
    return total
