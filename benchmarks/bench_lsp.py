"""Edit-to-diagnostics latency of `sensorkit lsp` on turtlebot4 (issue 26: median at most
150 ms, goal 50 ms).

Run by hand (never in the test suite): `.venv/bin/python benchmarks/bench_lsp.py`.

Drives the server as tests/test_lsp.py does (JSON-RPC over its stdin/stdout): opens
turtlebot4's standard robot (``gazebo:=ignition`` and the corpus as package path, sent
as initializationOptions, as tests/realworld/robots.yaml reads it), then sends N
didChange edits, each toggling a comment at the end of the buffer, and times each from
the send to the publishDiagnostics of that version. The machine may be shared, so the
server's CPU time per edit is measured too: utime+stime of the server and of the
expansion children it reaped (``/proc/PID/stat`` fields 14-17), before and after.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from lsp_client import Client  # noqa: E402

REALWORLD = ROOT.parent / "shared" / "corpus" / "realworld"
ROBOT = "turtlebot__turtlebot4/turtlebot4_description/urdf/standard/turtlebot4.urdf.xacro"
TICK = os.sysconf("SC_CLK_TCK")


EDIT = "<!-- edit {} -->"  # the edit: this comment added at the end, then removed


def edited(text: str, i: int) -> str:
    """The buffer after edit ``i``: even edits add the comment line, odd ones remove it."""
    return text if i % 2 else text + EDIT.format(i) + "\n"


def robot_options(robot: Path, arg: list[str] | None) -> tuple[dict[str, str], dict[str, object]]:
    """The xacro args (``NAME:=VALUE``; turtlebot4 defaults to gazebo:=ignition) and the
    initializationOptions that send them with the corpus as package path."""
    if arg is None:
        arg = ["gazebo:=ignition"] if robot == REALWORLD / ROBOT else []
    args = dict(item.split(":=", 1) for item in arg)
    return args, {"args": args, "packagePaths": [str(REALWORLD)]}


def stat_cpu(stat: str) -> float:
    """utime + stime + cutime + cstime, in seconds, from the text of a /proc/PID/stat."""
    fields = stat.rsplit(")", 1)[1].split()
    # fields[0] is the state (field 3); utime..cstime are fields 14..17
    return sum(int(x) for x in fields[11:15]) / TICK


def cpu_seconds(pid: int) -> float:
    """utime + stime + cutime + cstime of ``pid``, in seconds."""
    return stat_cpu(Path(f"/proc/{pid}/stat").read_text())


def pct(values: list[float], q: float) -> float:
    s = sorted(values)
    return s[min(len(s) - 1, round(q * (len(s) - 1)))]


def cpu_now() -> float:
    """This process's CPU seconds and its reaped children's (the expansion children)."""
    import resource

    me, kids = (
        resource.getrusage(resource.RUSAGE_SELF),
        resource.getrusage(resource.RUSAGE_CHILDREN),
    )
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


def breakdown(robot: Path, args: dict[str, str], edits: int) -> None:
    """Where an edit's CPU goes, in this process: the load (xacro expansion, in its forked
    child, and the model) and the rules (validate_loaded: rules, suppression, sorting)."""
    import dataclasses

    from sensorkit.lint.engine import validate_loaded
    from sensorkit.lsp.analysis import load
    from sensorkit.lsp.settings import Overrides, settings_for

    options = settings_for(robot, Overrides(args=args, package_paths=(str(REALWORLD),))).options
    text = robot.read_text()
    loads: list[float] = []
    rules: list[float] = []
    for i in range(edits + 1):
        body = edited(text, i)
        opts = dataclasses.replace(options, overlay={str(robot): body.encode()})
        c0 = cpu_now()
        loaded = load(robot, opts)
        c1 = cpu_now()
        validate_loaded(robot, loaded, opts)
        c2 = cpu_now()
        if i:  # the first warms the imports
            loads.append((c1 - c0) * 1000)
            rules.append((c2 - c1) * 1000)
    print(
        f"  in-process CPU per edit: load (expansion + model) median "
        f"{statistics.median(loads):.0f} ms, rules median {statistics.median(rules):.0f} ms"
    )


def run_client(
    robot: Path, options: dict[str, object], edits: int, warmup: int = 0
) -> tuple[float, int, list[float], list[float], int]:
    """A cold server: open ``robot``, then ``warmup`` edits not counted and ``edits``
    counted. Seconds to the first diagnostics, how many, wall and server CPU seconds per
    counted edit, the server's exit status."""
    client = Client(cwd=ROOT)
    try:
        t0 = time.perf_counter()
        client.initialize(robot.parent, options)
        text = robot.read_text()
        client.open(robot, text, version=1)
        first = client.diagnostics(robot, 1, timeout=120)
        opened = time.perf_counter() - t0
        wall: list[float] = []
        cpu: list[float] = []
        for i in range(warmup + edits):
            version = i + 2
            before = cpu_seconds(client.proc.pid)
            t = time.perf_counter()
            client.change(robot, edited(text, i), version)
            client.diagnostics(robot, version, timeout=60)
            if i >= warmup:
                wall.append(time.perf_counter() - t)
                cpu.append(cpu_seconds(client.proc.pid) - before)
        code = client.close()
    finally:
        client.kill()
    return opened, len(first), wall, cpu, code


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--edits", type=int, default=30)
    ap.add_argument("--robot", type=Path, default=REALWORLD / ROBOT)
    ap.add_argument(
        "--arg", action="append", help="NAME:=VALUE (default for turtlebot4: gazebo:=ignition)"
    )
    ap.add_argument(
        "--breakdown", action="store_true", help="also time load and rules in this process"
    )
    a = ap.parse_args()
    if not a.robot.is_file():
        sys.exit(f"bench_lsp: no robot at {a.robot}")
    args, options = robot_options(a.robot, a.arg)
    opened, first, wall, cpu, code = run_client(a.robot, options, a.edits)
    print(
        f"open: {opened:.2f} s to the first diagnostics "
        f"({first} in the top file), server started cold"
    )
    ms = [w * 1000 for w in wall]
    cms = [c * 1000 for c in cpu]
    print(f"{a.edits} edits of {a.robot.name} (args {args}), edit -> publishDiagnostics:")
    print(
        f"  wall: median {statistics.median(ms):.0f} ms, p90 {pct(ms, 0.9):.0f} ms, min {min(ms):.0f} ms"
    )
    print(
        f"  server CPU per edit (with its expansion children): median "
        f"{statistics.median(cms):.0f} ms, p90 {pct(cms, 0.9):.0f} ms "
        f"(clock tick {1000 / TICK:.0f} ms)"
    )
    print(f"  server exit status {code}")
    if a.breakdown:
        breakdown(a.robot, args, a.edits)


if __name__ == "__main__":
    main()
