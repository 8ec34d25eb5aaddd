"""The long fuzz run: the targets of ``tests/test_fuzz.py`` on 100,000+ generated inputs.

Run by hand (never in the test suite), from the repository root::

    .venv/bin/python benchmarks/fuzz_long.py                 # 100,000 inputs, 2 workers
    .venv/bin/python benchmarks/fuzz_long.py --total 2000    # a quick look

Inputs come from ``tests/fuzz_strategies.py`` (Hypothesis, one seed per chunk) and run
through ``tests/fuzz_targets.py`` in worker processes. The parent is a watchdog: a worker
that spends longer than a target's bound on one input is killed with its whole process
group (xacro children, render forks) and the input is counted as a hang. Every failing
or hanging input is written to ``tests/regressions/fuzz/`` (``--save`` elsewhere), where
``tests/test_fuzz.py`` replays it. The summary gives inputs, failures and hangs per
target, the distinct problems, the wall time and the slowest input (kept in ``--out``).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import re
import shutil
import signal
import sys
import tempfile
import time
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from multiprocessing import connection
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), str(ROOT / "tests")]

# Shares of the total per target: cheap in-process targets carry the volume; render and
# fresh processes are slow, so they get a small share (still hundreds of inputs).
SHARES = {
    "validate": 0.52,
    "validate_paths": 0.05,
    "cli_validate": 0.08,
    "add": 0.10,
    "cli_add": 0.04,
    "intrinsics": 0.095,
    "export": 0.095,
    "render": 0.015,
    "cli_subprocess": 0.005,
}
CHUNK = {"render": 40, "cli_subprocess": 20}
DEFAULT_CHUNK = 250


@dataclass
class Chunk:
    target: str
    seed: int
    n: int


@dataclass
class Worker:
    proc: Any
    conn: Any
    chunk: Chunk
    scratch: Path
    done: int = 0
    started: float | None = None  # when the current input started
    current: str | None = None  # its JSON


@dataclass
class Stats:
    inputs: Counter[str] = field(default_factory=Counter)
    notes: dict[str, Counter[str]] = field(default_factory=lambda: defaultdict(Counter))
    failures: Counter[str] = field(default_factory=Counter)
    hangs: Counter[str] = field(default_factory=Counter)
    seconds: Counter[str] = field(default_factory=Counter)
    labels: Counter[str] = field(default_factory=Counter)
    problems: Counter[str] = field(default_factory=Counter)
    examples: dict[str, str] = field(default_factory=dict)  # problem -> a saved file
    slowest: list[tuple[float, str, str]] = field(default_factory=list)  # (s, target, label)


def problem_key(target: str, problem: str) -> str:
    """A problem without the scratch paths in it, so one bug counts once."""
    text = re.sub(r"\S*skfuzz-[^\s:'\"]*", "<file>", problem)
    text = re.sub(r"0x[0-9a-f]+", "0x..", text)
    return f"{target}: {text[:200]}"


# ------------------------------------------------------------------------------- worker


def _worker(conn: Any, chunk: Chunk, scratch: str, log: str) -> None:
    os.setsid()  # its own process group: the watchdog kills xacro and render children too
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    fd = os.open(log, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
    os.dup2(fd, 1)
    os.dup2(fd, 2)  # pybullet and xacro print; keep the console for the summary
    import warnings

    warnings.simplefilter("ignore")
    import fuzz_strategies
    import fuzz_targets
    import xacro  # noqa: F401 (imported once here, the forked expansions start warm)
    from hypothesis import HealthCheck, Phase, given, seed, settings

    @seed(chunk.seed)
    @settings(
        max_examples=chunk.n,
        deadline=None,
        database=None,
        phases=[Phase.generate],
        suppress_health_check=list(HealthCheck),
    )
    @given(fuzz_strategies.fuzz_inputs(chunk.target))
    def drive(inp: fuzz_strategies.FuzzInput) -> None:
        conn.send(("start", inp.dumps()))
        t0 = time.perf_counter()
        out = fuzz_targets.run(inp, Path(scratch))
        took = time.perf_counter() - t0
        conn.send(("done", out.problem, out.detail[-4000:], out.note, took, inp.case.label))

    try:
        drive()
    except BaseException as exc:  # the harness itself failed: say so, do not hide it
        import traceback

        conn.send(("harness", "".join(traceback.format_exception(exc))))
    conn.send(("end",))
    conn.close()
    os._exit(0)


# ------------------------------------------------------------------------------- parent


def _spawn(ctx: Any, chunk: Chunk, base: Path, log: Path) -> Worker:
    recv, send = ctx.Pipe(duplex=False)
    scratch = Path(tempfile.mkdtemp(prefix="w-", dir=base))
    proc = ctx.Process(target=_worker, args=(send, chunk, str(scratch), str(log)), daemon=False)
    proc.start()
    send.close()
    return Worker(proc, recv, chunk, scratch)


def _kill(w: Worker) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(w.proc.pid, signal.SIGKILL)
    if w.proc.is_alive():  # killed before it had its own group
        w.proc.kill()
    w.proc.join(10)
    w.conn.close()
    shutil.rmtree(w.scratch, ignore_errors=True)


def _save(text: str, problem: str, folder: Path) -> Path:
    import fuzz_targets
    from fuzz_strategies import FuzzInput

    inp = FuzzInput.loads(text)
    return fuzz_targets.save_regression(inp, fuzz_targets.Outcome(inp.target, problem), folder)


def plan(total: int, seed: int, only: list[str] | None) -> list[Chunk]:
    shares = {t: s for t, s in SHARES.items() if not only or t in only}
    scale = sum(shares.values())
    chunks: list[Chunk] = []
    for i, (target, share) in enumerate(shares.items()):
        n = round(total * share / scale)
        size = CHUNK.get(target, DEFAULT_CHUNK)
        k = 0
        while n > 0:
            m = min(size, n)
            chunks.append(Chunk(target, seed * 1_000_000 + i * 10_000 + k, m))
            n -= m
            k += 1
    # interleave targets so a partial run still covers all of them
    by: dict[str, list[Chunk]] = defaultdict(list)
    for c in chunks:
        by[c.target].append(c)
    out: list[Chunk] = []
    while any(by.values()):
        for t in list(by):
            if by[t]:
                out.append(by[t].pop(0))
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--total", type=int, default=100_000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--targets", nargs="*", help="only these targets")
    ap.add_argument("--out", type=Path, default=Path(tempfile.gettempdir()) / "sensorkit-fuzz-long")
    ap.add_argument("--save", type=Path, default=ROOT / "tests" / "regressions" / "fuzz")
    ap.add_argument(
        "--max-saved-per-problem", type=int, default=0, help="0: save every failing input"
    )
    args = ap.parse_args()

    import multiprocessing as mp

    import fuzz_strategies  # noqa: F401 (import before forking: workers start warm)
    import fuzz_targets
    import hypothesis  # noqa: F401

    def stop(signum: int, frame: object) -> None:
        raise KeyboardInterrupt  # then the summary of what ran

    # A run started in the background ignores SIGINT unless told: both stop it cleanly.
    signal.signal(signal.SIGINT, stop)
    signal.signal(signal.SIGTERM, stop)
    for var in ("SENSORKIT_DEBUG", "AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH"):
        os.environ.pop(var, None)
    os.environ["OPENBLAS_NUM_THREADS"] = "1"
    args.out.mkdir(parents=True, exist_ok=True)
    base = Path(tempfile.mkdtemp(prefix="scratch-", dir=args.out))
    log = args.out / "workers.log"
    ctx = mp.get_context("fork")
    queue = plan(args.total, args.seed, args.targets)
    planned = sum(c.n for c in queue)
    stats = Stats()
    saved_per: Counter[str] = Counter()
    slowest_input: tuple[float, str | None] = (0.0, None)
    harness_errors: list[str] = []
    workers: list[Worker] = []
    start = time.monotonic()
    last_report = start
    print(
        f"fuzz_long: {planned} inputs over {args.workers} workers, seed {args.seed}, out {args.out}",
        flush=True,
    )

    def record_failure(target: str, problem: str, text: str | None, hang: bool) -> None:
        key = problem_key(target, problem)
        stats.problems[key] += 1
        (stats.hangs if hang else stats.failures)[target] += 1
        if text is None:
            return
        if args.max_saved_per_problem and saved_per[key] >= args.max_saved_per_problem:
            return
        saved_per[key] += 1
        path = _save(text, problem, args.save)
        stats.examples.setdefault(
            key, str(path.relative_to(ROOT) if path.is_relative_to(ROOT) else path)
        )

    try:
        while queue or workers:
            while queue and len(workers) < args.workers:
                workers.append(_spawn(ctx, queue.pop(0), base, log))
            connection.wait([w.conn for w in workers], timeout=1.0)
            now = time.monotonic()
            for w in list(workers):
                gone = False
                while not gone and w.conn.poll():
                    try:
                        msg = w.conn.recv()
                    except (EOFError, OSError):
                        msg = ("died",)
                    kind = msg[0]
                    if kind == "start":
                        w.started, w.current = time.monotonic(), msg[1]
                    elif kind == "done":
                        _, problem, detail, note, took, label = msg
                        t = w.chunk.target
                        stats.inputs[t] += 1
                        stats.seconds[t] += took
                        stats.labels[label] += 1
                        stats.notes[t][note or "FAILED"] += 1
                        w.done += 1
                        if took > slowest_input[0]:
                            slowest_input = (took, w.current)
                        stats.slowest = sorted([*stats.slowest, (took, t, label)])[-5:]
                        if problem:
                            record_failure(t, problem, w.current, hang=False)
                            with (args.out / "details.log").open("a") as fh:
                                fh.write(f"== {t}: {problem}\n{detail}\n")
                        w.started, w.current = None, None
                    elif kind == "harness":
                        harness_errors.append(msg[1])
                    elif kind in ("end", "died"):
                        died_on = kind == "died" and w.current is not None
                        if died_on:
                            # the worker itself died on an input (a segfault?): a crash
                            stats.inputs[w.chunk.target] += 1
                            stats.notes[w.chunk.target]["DIED"] += 1
                            problem = f"worker died (exit {w.proc.exitcode}) on an input"
                            record_failure(w.chunk.target, problem, w.current, hang=False)
                        left = w.chunk.n - w.done - (1 if died_on else 0)
                        _kill(w)
                        workers.remove(w)
                        gone = True
                        if kind == "died" and left > 0:
                            queue.insert(0, Chunk(w.chunk.target, w.chunk.seed + 7_777_777, left))
                if gone:
                    continue
                if w.started is not None and now - w.started > fuzz_targets.bound(w.chunk.target):
                    t = w.chunk.target
                    stats.inputs[t] += 1
                    stats.notes[t]["HANG"] += 1
                    stats.seconds[t] += now - w.started
                    record_failure(
                        t,
                        f"hang: no answer within {fuzz_targets.bound(t):g} s",
                        w.current,
                        hang=True,
                    )
                    left = w.chunk.n - w.done - 1
                    _kill(w)
                    workers.remove(w)
                    if left > 0:
                        queue.insert(0, Chunk(t, w.chunk.seed + 9_999_999, left))
            if now - last_report > 60:
                last_report = now
                done = sum(stats.inputs.values())
                rate = done / (now - start)
                print(
                    f"  {done}/{planned} inputs, {rate:.1f}/s, {sum(stats.failures.values())} failures, "
                    f"{sum(stats.hangs.values())} hangs, {now - start:.0f} s",
                    flush=True,
                )
    except KeyboardInterrupt:
        print("interrupted: the summary is of what ran", flush=True)
        for w in workers:
            _kill(w)
    wall = time.monotonic() - start
    shutil.rmtree(base, ignore_errors=True)
    if slowest_input[1] is not None:
        (args.out / "slowest_input.json").write_text(slowest_input[1])
    summary = report(stats, wall, slowest_input[0], harness_errors, args)
    (args.out / "summary.json").write_text(json.dumps(summary, indent=1))
    return 1 if summary["uncaught_exceptions"] or summary["hangs"] or harness_errors else 0


def report(
    stats: Stats, wall: float, slowest: float, harness: list[str], args: argparse.Namespace
) -> dict[str, Any]:
    total = sum(stats.inputs.values())
    print()
    print(f"{'target':<16}{'inputs':>9}{'failures':>10}{'hangs':>7}{'mean ms':>9}  outcomes")
    for t in SHARES:
        if not stats.inputs[t]:
            continue
        mean = 1000 * stats.seconds[t] / stats.inputs[t]
        outcomes = ", ".join(f"{k} {v}" for k, v in stats.notes[t].most_common())
        print(
            f"{t:<16}{stats.inputs[t]:>9}{stats.failures[t]:>10}{stats.hangs[t]:>7}{mean:>9.0f}  {outcomes}"
        )
    print(
        f"{'total':<16}{total:>9}{sum(stats.failures.values()):>10}{sum(stats.hangs.values()):>7}"
    )
    print(f"inputs by kind: {dict(stats.labels)}")
    print(
        f"wall time {wall:.0f} s ({total / max(wall, 1e-9):.1f} inputs/s with {args.workers} workers)"
    )
    print(
        "slowest inputs: "
        + "; ".join(f"{s:.2f} s {t} ({lab})" for s, t, lab in reversed(stats.slowest))
    )
    print(f"the slowest ({slowest:.2f} s) is kept in {args.out / 'slowest_input.json'}")
    if stats.problems:
        print("distinct problems:")
        for key, n in stats.problems.most_common():
            print(f"  {n:>6} x {key}  [{stats.examples.get(key, '-')}]")
    else:
        print("no uncaught exception, no hang")
    for h in harness:
        print("HARNESS ERROR:\n" + h)
    return {
        "inputs": dict(stats.inputs),
        "total": total,
        "uncaught_exceptions": sum(stats.failures.values()),
        "hangs": sum(stats.hangs.values()),
        "failures_per_target": dict(stats.failures),
        "hangs_per_target": dict(stats.hangs),
        "outcomes": {t: dict(c) for t, c in stats.notes.items()},
        "mean_ms": {t: 1000 * stats.seconds[t] / stats.inputs[t] for t in stats.inputs},
        "labels": dict(stats.labels),
        "wall_s": wall,
        "slowest": [list(s) for s in reversed(stats.slowest)],
        "problems": dict(stats.problems),
        "examples": stats.examples,
        "harness_errors": harness,
    }


if __name__ == "__main__":
    sys.exit(main())
