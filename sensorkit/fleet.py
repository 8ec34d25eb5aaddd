"""Many files in one ``sensorkit validate``: folder arguments and a pool of worker processes.

Folders: ``find_robots`` walks a folder the way colcon does (no hidden folders, none that
hold a ``COLCON_IGNORE``, no ``build``/``install``/``log``) and keeps the top-level robot
descriptions: every ``*.urdf``, and every ``*.xacro`` (``*.urdf.xacro`` included) that is
more than a partial. A partial's root holds nothing but ``<xacro:macro>``,
``<xacro:property>``, ``<xacro:include>`` and ``<xacro:arg>``: it is included by robots,
never validated on its own.

Pool: ``run_pool`` hands one file at a time to each of N worker processes and gathers the
reports in input order. A worker validates, keeps only the findings (plain data) and
sends them back; a worker that dies (a crash, the kernel's OOM killer) costs only the file
it held, which becomes that file's error, and a new worker takes its place. Workers run
in their own process group, so xacro's forked children (``loading.xacro_expand``) die with
them when sensorkit stops early (Ctrl-C); they ignore SIGINT, which the parent handles.
"""

from __future__ import annotations

import contextlib
import os
import signal
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from lxml import etree

if TYPE_CHECKING:
    from multiprocessing.connection import Connection
    from multiprocessing.process import BaseProcess

    from sensorkit.engine import FileReport, Options

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
    return name.endswith((".urdf", ".xacro"))


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
        hits.extend(Path(here, f) for f in files if is_description_name(f))
    for path in sorted(hits):
        (found.partials if is_partial(path) else found.files).append(path)
    return found


# ----------------------------------------------------------------------------- pool


def cpu_count() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def _worker(conn: Connection, options: Options) -> None:  # pragma: no cover (a child)
    """Validate what the parent sends, one file at a time, until it sends None."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    with contextlib.suppress(OSError):  # stopping the group stops xacro's children too
        os.setpgid(0, 0)
    from sensorkit.engine import validate_one

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
    parent_end, child_end = ctx.Pipe()
    proc = ctx.Process(target=_worker, args=(child_end, options), daemon=False)
    proc.start()
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
    from sensorkit.engine import FileReport
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
    from sensorkit.loading.xacro_expand import warm

    if any(not p.name.endswith(".urdf") for p in paths):  # .xacro, or anything else
        warm()


def run_pool(
    paths: Sequence[Path],
    options: Options,
    jobs: int,
    on_done: Callable[[int, FileReport], None] | None = None,
) -> list[FileReport]:
    """Validate ``paths`` in ``jobs`` worker processes; reports in input order."""
    import multiprocessing as mp
    from multiprocessing.connection import wait

    method = "fork" if "fork" in mp.get_all_start_methods() else "spawn"
    ctx = mp.get_context(method)
    if method == "fork":
        _preload(paths)
    results: list[FileReport | None] = [None] * len(paths)
    next_task = 0
    busy: dict[Any, tuple[BaseProcess, int]] = {}  # connection -> (its worker, file index)
    raised: dict[int, Exception] = {}  # file index -> what validating it raised
    workers: list[tuple[BaseProcess, Connection]] = []

    def done(index: int, report: FileReport) -> None:
        results[index] = report
        if on_done is not None:
            on_done(index, report)

    def feed(proc: BaseProcess, conn: Connection) -> None:
        """The next file to an idle worker, or None (stop) when there is none left."""
        nonlocal next_task
        if next_task >= len(paths):
            with contextlib.suppress(OSError):
                conn.send(None)
            return
        try:
            conn.send((next_task, paths[next_task]))
        except OSError:  # it died after its last answer: the file goes to a new worker
            _stop(proc)
            start()
            return
        busy[conn] = (proc, next_task)
        next_task += 1

    def start() -> None:
        proc, conn = _start(ctx, options)
        workers.append((proc, conn))
        feed(proc, conn)

    try:
        for _ in range(max(1, min(jobs, len(paths)))):
            start()
        while busy:
            by_sentinel: dict[Any, Any] = {p.sentinel: c for c, (p, _) in busy.items()}
            for item in wait([*busy, *by_sentinel]):
                conn = by_sentinel.get(item, item)
                if conn not in busy:
                    continue  # already handled through its other handle
                proc, index = busy.pop(conn)
                report: FileReport | None = None
                try:
                    if conn.poll():
                        got, answer = conn.recv()
                        if got != index:
                            answer = None
                        elif isinstance(answer, Exception):
                            # validate_file raised (a usage error, a bug): --jobs 1 stops
                            # at the first such file, so raise the earliest one once the
                            # files before it are done, and start no new one meanwhile.
                            raised[index] = answer
                            next_task = len(paths)
                            feed(proc, conn)
                            continue
                        report = answer
                except (EOFError, OSError):
                    report = None
                if report is not None:
                    done(index, report)
                    feed(proc, conn)
                    continue
                # The worker died holding this file: say so, and replace the worker.
                _stop(proc)
                done(index, _crashed(paths[index], proc))
                if next_task < len(paths):
                    start()
        if raised:
            raise raised[min(raised)]
        for proc, _conn in workers:
            proc.join(10)
    finally:
        for proc, conn in workers:
            _stop(proc)
            conn.close()
    out = [r for r in results if r is not None]
    assert len(out) == len(paths)
    return out
