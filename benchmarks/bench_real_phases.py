"""Where one `sensorkit validate` run's CPU time goes (``bench_real.py --profile ROBOT``).

A driver process runs the CLI in-process as the console script does (same argv, same
``main()``), with CPU clocks (user + sys of the process, and of the children it waited for:
the forked xacro expansion) around its phases:

- interpreter start: the CPU the process had used when the driver's first line ran;
- imports: ``import sensorkit.cli`` (typer and the validate command), then the modules the
  command loads on first use (engine, rules, model, loading, xacro_expand, report);
- xacro imports (``xacro_expand.warm``), the expansion (this process: fork, pipe, unpickle;
  children: xacro in the forked child), the rest of loading (reading, parsing, line stamps),
  the model (``build_robot``), the rules' context (target, conversion, frames, missing
  files: ``check_robot`` less the rules), each rule,
  suppression comments, the report's rendering;
- the CLI's rest: typer, options, settings, output: ``main()``'s time less the phases above.

Each phase is counted once (a phase inside another is taken out of the outer one). The
phases' medians over the runs are printed, then, from ``python -X importtime`` runs of the
console script (wall time, by the interpreter's own clock), the 15 imports with the largest
cumulative time, indented by depth.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
from pathlib import Path
from typing import Any

DRIVER = r"""
import resource
import sys


def _cpu():
    s = resource.getrusage(resource.RUSAGE_SELF)
    c = resource.getrusage(resource.RUSAGE_CHILDREN)
    return s.ru_utime + s.ru_stime, c.ru_utime + c.ru_stime


START = _cpu()
OUT = sys.argv[1]
sys.argv = sys.argv[2:]  # as the console script sees it: [.../sensorkit, "validate", FILE, ...]
phases = {"interpreter start": [START[0], START[1]]}
rules = {}
stack = []


def add(label, own, child):
    p = phases.setdefault(label, [0.0, 0.0])
    p[0] += own
    p[1] += child


def measured(label, func, rule=False):
    phases.setdefault(label, [0.0, 0.0])  # printed in this order

    def wrapper(*a, **k):
        s0, c0 = _cpu()
        stack.append([0.0, 0.0])
        try:
            return func(*a, **k)
        finally:
            s1, c1 = _cpu()
            inner = stack.pop()
            own, child = s1 - s0, c1 - c0
            if rule:  # run_rule(ctx, info, errors)
                rules[a[1].id] = rules.get(a[1].id, 0.0) + own + child
            add(label, own - inner[0], child - inner[1])
            if stack:
                stack[-1][0] += own
                stack[-1][1] += child
    return wrapper


def step(label, before):
    s, c = _cpu()
    add(label, s - before[0], c - before[1])
    return (s, c)


t = _cpu()
import sensorkit.cli as cli
t = step("imports: sensorkit.cli (typer, the validate command)", t)
import sensorkit.lint.engine as engine
import sensorkit.lint.report as report
import sensorkit.loading.xacro_expand as xe
import sensorkit.model as model
step("imports: engine, rules, model, loading, report", t)

xe.warm = measured("xacro imports (warm)", xe.warm)
xe.expand = measured("xacro expansion (children: the forked xacro)", xe.expand)
model.load_description = measured("loading less expansion: read, parse, line stamps", model.load_description)
model.build_robot = measured("model (build_robot)", model.build_robot)
engine.check_robot = measured("rules' context: target, conversion, frames, missing files", engine.check_robot)
engine.run_rule = measured("rules", engine.run_rule, rule=True)
engine._suppress = measured("suppression comments", engine._suppress)
report.render = measured("report rendering", report.render)


class Quit(Exception):
    pass


def _exit(code):
    raise Quit(code)


import os
os._exit = _exit  # main() ends the process without teardown: come back here instead
def totals():
    return sum(p[0] for p in phases.values()), sum(p[1] for p in phases.values())


before = totals()
t = _cpu()
try:
    cli.main()
except (SystemExit, Quit):
    pass
s, c = _cpu()
after = totals()
add("CLI rest: typer, options, settings, output", s - t[0] - (after[0] - before[0]), c - t[1] - (after[1] - before[1]))
import json
with open(OUT, "w") as f:
    json.dump({"phases": phases, "rules": rules, "total": s + c}, f)
"""


def driver_runs(cmd: list[str], env: dict[str, str], tmp: Path, runs: int) -> list[dict[str, Any]]:
    driver = tmp / "phases_driver.py"
    driver.write_text(DRIVER)
    out = tmp / "phases.json"
    results = []
    for _ in range(runs):
        subprocess.run(
            [sys.executable, str(driver), str(out), *cmd],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            env=env,
            cwd=tmp,
            check=True,
        )
        results.append(json.loads(out.read_text()))
    return results


def importtime(
    cmd: list[str], env: dict[str, str], tmp: Path, runs: int = 3
) -> list[tuple[float, float, str]]:
    """(cumulative ms, self ms, indented module) of the 15 slowest imports, medians of runs."""
    cum: dict[str, list[float]] = {}
    own: dict[str, list[float]] = {}
    for _ in range(runs):
        err = subprocess.run(
            [sys.executable, "-X", "importtime", *cmd],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
            env=env,
            cwd=tmp,
            check=False,
        ).stderr
        for line in err.splitlines():
            if not line.startswith("import time:") or "cumulative" in line:
                continue
            s, c, name = line[len("import time:") :].split("|", 2)
            cum.setdefault(name.rstrip(), []).append(int(c) / 1000)
            own.setdefault(name.rstrip(), []).append(int(s) / 1000)
    med = statistics.median
    rows = [(med(cum[n]), med(own[n]), n) for n in cum]
    return sorted(rows, reverse=True)[:15]


def profile(robot: Any, env: dict[str, str], tmp: Path, runs: int) -> None:
    """Print where ``sensorkit validate`` spends its CPU on ``robot`` (a bench_real.Robot)."""
    from bench_real import cpu_of  # the benchmark's own clock, for the whole console script

    cmd = robot.sensorkit_cmd(no_cache=False)
    help_text = subprocess.run(
        [cmd[0], "validate", "--help"],
        capture_output=True,
        text=True,
        env=dict(env, COLUMNS="200"),
        check=False,
    ).stdout
    if "--no-cache" in help_text:
        cmd.append("--no-cache")
    whole = [cpu_of(cmd, env, tmp)[0] for _ in range(runs + 1)][1:]  # the first compiles bytecode
    results = driver_runs(cmd, env, tmp, runs)
    med = statistics.median
    labels = list(results[0]["phases"])
    print(f"`sensorkit validate {robot.file}` ({robot.label}): median CPU ms of {runs} runs")
    print(
        f"  console script {med(whole) * 1e3:.1f} ms; in-process driver total {med(r['total'] for r in results) * 1e3:.1f} ms"
    )
    print(f"  {'phase':58} {'process':>8} {'children':>8}")
    for label in labels:
        own = med(r["phases"].get(label, [0, 0])[0] for r in results) * 1e3
        child = med(r["phases"].get(label, [0, 0])[1] for r in results) * 1e3
        print(f"  {label:58} {own:8.1f} {child:8.1f}")
    rule_ids = sorted({k for r in results for k in r["rules"]})
    per_rule = sorted(
        ((med(r["rules"].get(k, 0.0) for r in results) * 1e3, k) for k in rule_ids), reverse=True
    )
    print(
        f"  rules: {len(rule_ids)} ran; the slowest: "
        + ", ".join(f"{k} {t:.1f}" for t, k in per_rule[:6])
    )
    print(
        "  python -X importtime of the console script (wall ms, median of 3), top 15 by cumulative:"
    )
    print(f"  {'cumul':>7} {'self':>6}  module")
    for c, s, name in importtime(cmd, env, tmp):
        print(f"  {c:7.1f} {s:6.1f}  {name}")
    print(f"  (load average {' '.join(f'{v:.1f}' for v in os.getloadavg())})")
