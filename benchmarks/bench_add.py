"""`sensorkit add-camera` against `sensorkit validate` on a generated 10,000-link URDF.

Run by hand (never in the test suite): `.venv/bin/python benchmarks/bench_add.py`.
Each run pairs one add (on a fresh copy of the file, written for real) with one validate
of the same robot, interleaved, so drift on a shared machine hits both alike. CPU is
user + sys of the command and its children (xacro runs in a child for the macro).
Target: median CPU of add-camera <= 1.5 x median CPU of validate.

`--baseline DIR` runs the add from another sensorkit source tree too (PYTHONPATH=DIR),
to compare a change with what it replaces.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_validate import INERTIAL, big_urdf, timed


def robot(links: int) -> str:
    """``big_urdf`` with an inertial on the root, so that the add is accepted and written."""
    return big_urdf(links).replace(
        '<link name="link0"/>', f'<link name="link0">{INERTIAL}</link>', 1
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--links", type=int, default=10_000)
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--baseline", type=Path, help="another sensorkit tree to time the add of")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        source = tmp / "big.urdf"
        source.write_text(robot(a.links))
        size = source.stat().st_size
        env = dict(os.environ, PYTHONPYCACHEPREFIX=str(tmp / "pycache"))
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        trees = {"add-camera": env}
        if a.baseline is not None:
            trees["add-camera (baseline)"] = dict(env, PYTHONPATH=str(a.baseline.resolve()))
        os.chdir(tmp)  # `python -m` puts the working folder first on sys.path: not a tree
        sk = [sys.executable, "-m", "sensorkit"]
        work = tmp / "robot.urdf"
        shutil.copyfile(source, work)
        check = subprocess.run(
            [*sk, "add-camera", str(work), "--name", "cam2", "--parent", "link7"],
            capture_output=True, text=True, env=env, check=False,
        )  # fmt: skip
        print(f"add-camera exit {check.returncode}: {check.stderr.strip() or check.stdout.strip()}")
        cpu: dict[str, list[float]] = {"validate": [], **{k: [] for k in trees}}
        wall: dict[str, list[float]] = {k: [] for k in cpu}
        for _ in range(a.runs):
            w, c = timed([*sk, "validate", str(source)], 1, env)
            wall["validate"] += w
            cpu["validate"] += c
            for label, tree_env in trees.items():
                shutil.copyfile(source, work)
                cmd = [*sk, "add-camera", str(work), "--name", "cam2", "--parent", "link7"]
                w, c = timed(cmd, 1, tree_env)
                wall[label] += w
                cpu[label] += c
    med = statistics.median
    print(f"{a.links} links ({size} bytes), {a.runs} paired runs (median wall / median CPU)")
    for label, spent in cpu.items():
        ratio = med(spent) / med(cpu["validate"])
        print(
            f"{label:<24} {med(wall[label]) * 1000:8.0f} ms {med(spent) * 1000:8.0f} ms"
            f"   CPU x{ratio:.2f} of validate"
        )
    print("target: add-camera CPU <= 1.5 x validate CPU")


if __name__ == "__main__":
    main()
