"""Many files in one ``sensorkit validate``: folder arguments and a pool of worker processes.

``validate_paths`` validates a list of files, in this process or (``jobs`` > 1) in the pool.

Folders: ``find_robots`` walks a folder the way colcon does (no hidden folders, none that
hold a ``COLCON_IGNORE``, no ``build``/``install``/``log``) and keeps the top-level robot
descriptions: every ``*.urdf``, and every ``*.xacro`` (``*.urdf.xacro`` included) that is
more than a partial. A partial's root holds nothing but ``<xacro:macro>``,
``<xacro:property>``, ``<xacro:include>`` and ``<xacro:arg>``: it is included by robots,
never validated on its own. SDF too: every ``*.sdf`` and ``*.world`` (and ``*.sdf.xacro``),
except that a Gazebo model folder (one holding a ``model.config``) gives only the SDF file
its ``model.config`` names (``loading.sdf_files.model_file``: the newest ``<sdf>``), not
each older version of the model beside it.

Pool: ``run_pool`` hands files to N worker processes, each holding the one it validates
and the next, and gathers the reports in input order. A worker validates, keeps only the
findings (plain data) and sends them back; a worker that dies (a crash, the kernel's OOM
killer) costs only the file it was validating, which becomes that file's error: a new
worker takes its place and the file queued behind. Workers run in their own process
group, so xacro's forked children (``loading.xacro_expand``) die with them when sensorkit
stops early (Ctrl-C); they ignore SIGINT, which the parent handles. A worker dies with
sensorkit even when sensorkit is killed outright (SIGKILL: ``base.confine.die_with_parent``),
and xacro's children die with the worker the same way.
"""

from __future__ import annotations

import contextlib
import os
import signal
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from lxml import etree

from sensorkit.lint.engine import FileReport, Options, Report, validate_one

if TYPE_CHECKING:
    from multiprocessing.connection import Connection
    from multiprocessing.process import BaseProcess

SKIP_DIRS = frozenset({"build", "install", "log"})
IGNORE_MARKER = "COLCON_IGNORE"
PARTIAL_TAGS = frozenset({"macro", "property", "include", "arg"})
XACRO_NAMESPACES = frozenset(
    {"http://www.ros.org/wiki/xacro", "http://ros.org/wiki/xacro", "http://wiki.ros.org/xacro"}
)


# ----------------------------------------------------------------------------- folders


@dataclass
class Found:
    """What a folder holds: robot descriptions to validate, and partials skipped."""

    files: list[Path] = field(default_factory=list)
    partials: list[Path] = field(default_factory=list)


def is_description_name(name: str) -> bool:
    return name.endswith((".urdf", ".xacro", ".sdf", ".world"))


def _model_versions(here: str, files: list[str]) -> set[str]:
    """The SDF files of a model folder ``here`` other than the one its model.config names
    (gz-sim and libsdformat read that one: gazebosim/sdformat@sdformat12_12.8.0:
    src/parser.cc:1204-1257, getModelFilePath)."""
    if "model.config" not in files:
        return set()
    from sensorkit.loading.sdf_files import model_file

    chosen = model_file(Path(here))
    if chosen is None:
        return set()
    return {f for f in files if f.endswith(".sdf") and f != chosen.name}


def is_partial(path: Path) -> bool:
    """A xacro whose root holds only macros, properties, includes and args.

    A file that does not parse is not a partial: validating it says what is wrong.
    """
    if not path.name.endswith(".xacro"):
        return False
    try:
        parser = etree.XMLParser(
            resolve_entities=False, no_network=True, load_dtd=False, huge_tree=True
        )
        root = etree.parse(str(path), parser).getroot()
    except (etree.XMLSyntaxError, OSError, ValueError):
        return False
    children = [c for c in root if isinstance(c.tag, str)]
    if not children:
        return False
    for child in children:
        qname = etree.QName(child)
        if qname.localname not in PARTIAL_TAGS:
            return False
        if qname.namespace not in XACRO_NAMESPACES and child.prefix != "xacro":
            return False
    return True


def find_robots(folder: Path) -> Found:
    """Top-level robot descriptions below ``folder``, sorted by path (see the module doc)."""
    found = Found()
    hits: list[Path] = []
    for here, dirs, files in os.walk(folder):
        if IGNORE_MARKER in files:
            dirs[:] = []
            continue
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in SKIP_DIRS)
        other = _model_versions(here, files)
        hits.extend(Path(here, f) for f in files if is_description_name(f) and f not in other)
    for path in sorted(hits):
        (found.partials if is_partial(path) else found.files).append(path)
    return found


# ----------------------------------------------------------------------------- pool


def cpu_count() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def _worker(
    conn: Connection, options: Options, parent: int | None = None
) -> None:  # pragma: no cover (a child)
    """Validate what the parent sends, one file at a time, until it sends None.

    It dies with ``parent`` (the sensorkit process), and xacro's children with it."""
    if parent is not None:
        from sensorkit.base.confine import die_with_parent

        die_with_parent(parent)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    with contextlib.suppress(OSError):  # stopping the group stops xacro's children too
        os.setpgid(0, 0)
    try:
        while True:
            task = conn.recv()
            if task is None:
                break
            index, path = task
            try:
                answer: FileReport | Exception = validate_one(path, options)
            except Exception as exc:  # raised by the parent, as --jobs 1 would raise it
                answer = exc
            try:
                conn.send((index, answer))
            except Exception as exc:  # an exception that does not pickle
                conn.send((index, RuntimeError(f"{type(answer).__name__}: {answer}: {exc}")))
    except (EOFError, OSError, KeyboardInterrupt):
        pass
    finally:
        conn.close()
        os._exit(0)


def _start(ctx: Any, options: Options) -> tuple[BaseProcess, Connection]:
    """A worker, forked with every object of this process in the collector's permanent
    generation: its collections (a young one after each file, see ``validate_one``) then
    never walk what it inherited. ``sensorkit validate`` disables automatic collection
    before its last imports (about 9,000 objects): the worker's first collection walked
    them all, writing to each one's header and so copying the pages holding them, 5 ms
    of its first file."""
    import gc

    parent_end, child_end = ctx.Pipe()
    proc = ctx.Process(target=_worker, args=(child_end, options, os.getpid()), daemon=False)
    # A caller that froze objects itself keeps exactly its freeze: freezing more now
    # could not be undone for its objects alone, so its workers go without.
    ours = not gc.get_freeze_count()
    if ours:
        gc.freeze()
    try:
        proc.start()
    finally:
        if ours:
            gc.unfreeze()
    child_end.close()
    with contextlib.suppress(OSError):  # its own process group (see _worker)
        os.setpgid(proc.pid, proc.pid)
    return proc, parent_end


def _stop(proc: BaseProcess) -> None:
    pid = proc.pid
    if pid is not None and proc.exitcode is None:
        try:
            os.killpg(pid, signal.SIGKILL)
        except OSError:
            proc.kill()
    proc.join(5)


def _crashed(path: Path, proc: BaseProcess) -> FileReport:
    from sensorkit.loading.document import display_path

    code = proc.exitcode
    how = f"signal {-code}" if code is not None and code < 0 else f"exit status {code}"
    return FileReport(
        path=path,
        error=f"{display_path(path)}: the worker validating it stopped ({how}); nothing was checked",
    )


def _preload(paths: Sequence[Path]) -> None:
    """Import here what validating imports on first use (xacro, when a file may need it),
    so that every forked worker starts with it instead of importing it again.

    Only that: everything imported here is imported before any worker starts, one module
    after the other, so it lengthens every run by its import time. Validating imports no
    numpy (a test checks it), so neither does this."""
    from sensorkit.base.confine import preload
    from sensorkit.loading.xacro_expand import warm

    preload()  # each worker sets its parent-death signal with it
    if any(not p.name.endswith(".urdf") for p in paths):  # .xacro, or anything else
        warm()


QUEUED = 2  # files a worker holds at most: the one it validates and the next


def run_pool(
    paths: Sequence[Path],
    options: Options,
    jobs: int,
    on_done: Callable[[int, FileReport], None] | None = None,
) -> list[FileReport]:
    """Validate ``paths`` in ``jobs`` worker processes; reports in input order.

    Each worker holds up to ``QUEUED`` files: when it has answered one, the next already
    waits in its pipe, so it never waits for this process to be scheduled and send one
    (with the workers keeping every core busy, that wait came after each file). While
    there are no more files left to hand out than workers, a worker gets one at a time,
    so that none holds a file another could validate now.
    """
    import multiprocessing as mp

    method = "fork" if "fork" in mp.get_all_start_methods() else "spawn"
    ctx = mp.get_context(method)
    if method == "fork":
        _preload(paths)
    return _Pool(paths, options, ctx, on_done).run(jobs)


@dataclass
class _Pool:
    """One ``run_pool``: its workers, the files each holds, the files left to hand out."""

    paths: Sequence[Path]
    options: Options
    ctx: Any  # the multiprocessing context workers start in
    on_done: Callable[[int, FileReport], None] | None
    results: list[FileReport | None] = field(default_factory=list)  # by file index
    next_task: int = 0
    # files sent to a worker that died before it began them
    retry: list[int] = field(default_factory=list)
    # connection -> (its worker, the files sent to it and not answered yet, oldest first)
    live: dict[Any, tuple[BaseProcess, deque[int]]] = field(default_factory=dict)
    raised: dict[int, Exception] = field(default_factory=dict)  # file index -> what it raised
    workers: list[tuple[BaseProcess, Connection]] = field(default_factory=list)
    # connections a send failed on: their worker is gone
    broken: set[Any] = field(default_factory=set)

    def __post_init__(self) -> None:
        self.results = [None] * len(self.paths)

    def run(self, jobs: int) -> list[FileReport]:
        """Start the workers, keep them fed until every file is answered, stop them."""
        from multiprocessing.connection import wait

        live = self.live
        try:
            for _ in range(max(1, min(jobs, len(self.paths)))):
                self.start()
            for _ in range(QUEUED):  # one file each first, then the next ones
                for conn in list(live):
                    self.give(conn)
            for conn in list(live):
                self.feed(conn)
            while live:
                by_sentinel: dict[Any, Any] = {p.sentinel: c for c, (p, _) in live.items()}
                for item in wait([*live, *by_sentinel]):
                    conn = by_sentinel.get(item, item)
                    if conn not in live:
                        continue  # already handled through its other handle
                    if self.collect(conn):
                        self.feed(conn)
                    else:
                        self.bury(conn)
            if self.raised:
                raise self.raised[min(self.raised)]
            for proc, _conn in self.workers:
                proc.join(10)
        finally:
            for proc, conn in self.workers:
                _stop(proc)
                conn.close()
        out = [r for r in self.results if r is not None]
        assert len(out) == len(self.paths)
        return out

    def done(self, index: int, report: FileReport) -> None:
        self.results[index] = report
        if self.on_done is not None:
            self.on_done(index, report)

    def limit(self) -> int:
        # validate_file raised (a usage error, a bug): --jobs 1 stops at the first such
        # file, so no file after it is handed out; the earliest is raised at the end.
        return min(self.raised) if self.raised else len(self.paths)

    def left(self) -> int:
        """Files not handed out yet (and to be)."""
        end = self.limit()
        return sum(1 for i in self.retry if i < end) + max(0, end - self.next_task)

    def give(self, conn: Connection) -> bool:
        """Send ``conn``'s worker one more file; False when it should get none now."""
        _proc, queue = self.live[conn]
        if len(queue) >= QUEUED or (queue and self.left() <= len(self.live)):
            return False
        end = self.limit()
        if self.retry and self.retry[0] < end:
            index = self.retry.pop(0)
        elif self.next_task < end:
            index = self.next_task
            self.next_task += 1
        else:
            return False
        try:
            conn.send((index, self.paths[index]))
        except OSError:  # it died: collect() sees it, and bury() takes over
            self.broken.add(conn)
            self.retry.append(index)
            self.retry.sort()
            return False
        queue.append(index)
        return True

    def feed(self, conn: Connection) -> None:
        """Top up a worker's files; stop it (None) when it holds none and none is left."""
        while self.give(conn):
            pass
        if not self.live[conn][1] and conn not in self.broken:
            with contextlib.suppress(OSError):
                conn.send(None)
            del self.live[conn]

    def start(self) -> Connection:
        proc, conn = _start(self.ctx, self.options)
        self.workers.append((proc, conn))
        self.live[conn] = (proc, deque())
        return conn

    def collect(self, conn: Connection) -> bool:
        """Take every answer ``conn`` holds; False when its worker is gone."""
        proc, queue = self.live[conn]
        try:
            while conn.poll():  # a worker speaks only to answer: else it is gone (EOF)
                got, answer = conn.recv()
                if not queue or got != queue[0]:
                    return False
                index = queue.popleft()
                if isinstance(answer, Exception):
                    self.raised[index] = answer
                else:
                    self.done(index, answer)
        except (EOFError, OSError):
            return False
        return proc.exitcode is None

    def bury(self, conn: Connection) -> None:
        """A worker died: the file it held becomes that file's error, the files queued
        behind it go to other workers, and a new worker takes its place."""
        proc, queue = self.live.pop(conn)
        _stop(proc)
        if queue:
            index = queue.popleft()
            self.done(index, _crashed(self.paths[index], proc))
            self.retry.extend(queue)
            self.retry.sort()
        if self.left():
            self.feed(self.start())


def validate_paths(
    paths: Sequence[Path],
    options: Options | None = None,
    *,
    jobs: int = 1,
    keep: list[object] | None = None,
) -> Report:
    """Validate several files; reports in input order, each holding findings only.

    ``jobs`` > 1 validates one file per task in that many worker processes
    (:func:`run_pool`); the result is the same as with ``jobs=1``.
    ``keep`` takes the last file's model (see :func:`~sensorkit.lint.engine.validate_one`).
    """
    options = options or Options()
    if jobs > 1 and len(paths) > 1:
        return Report(run_pool(paths, options, jobs))
    last = len(paths) - 1
    return Report(
        [validate_one(p, options, keep=keep if i == last else None) for i, p in enumerate(paths)]
    )
