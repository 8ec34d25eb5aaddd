"""`sensorkit check-recording` on a generated ~2 GB recording of images and scans.

Run by hand (never in the test suite):

    .venv/bin/python benchmarks/bench_recording.py [--scratch DIR] [--rounds 5] [--keep]

The recording is the example car (tests/bags.py: its values from the simulators'
formulas) at 30 Hz with 640x480 rgb8 and 32FC1 images, camera_info, clouds and a 10 Hz
scan, about 2 GB, written in each format asked for (default: an MCAP rosbag2 and a ROS 1
bag) into the scratch folder, which must not be in the repository; it is deleted after
unless --keep.

Paired and interleaved rounds (the order rotated every round) of whole processes:

- `sensorkit check-recording BAG CAR -q`;
- `sensorkit topics CAR -q`: the same start-up and description, without the bag (what
  check-recording adds is the difference);
- peers: reading every message of the bag with rosbags' AnyReader, raw (the least a check
  that reads the whole recording costs), and decoded (what checking every message costs).

Each at two sizes (--frames, default 93 and 930: about 0.2 and 2 GB), to show that time
and memory do not grow with the bag. Per process, from os.wait4: CPU time (user + sys),
wall time, peak RSS. Medians are printed with the load average before and after; the page
cache is warm (the bag was just written), as it is when a user checks the bag they
recorded.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
CAR = ROOT / "examples" / "orbslam3_car" / "urdf" / "orbslam3_car.urdf.xacro"

PEER = """
import sys
from pathlib import Path
from rosbags.highlevel import AnyReader
from rosbags.typesys import Stores, get_typestore
decode = sys.argv[2] == "decode"
n = size = 0
with AnyReader([Path(sys.argv[1])], default_typestore=get_typestore(Stores.LATEST)) as r:
    for c, _t, raw in r.messages():
        n += 1
        size += len(raw)
        if decode:
            r.deserialize(raw, c.msgtype)
print(n, size)
"""


def make_bag(scratch: Path, fmt: str, frames: int) -> Path:
    from bags import car_scene, write_bag

    scene = car_scene()
    for topic, stream in scene.streams.items():
        scene = scene.with_stream(topic, count=frames if stream.rate == 30.0 else frames // 3)
    name = scratch / f"car_{frames}_{fmt}"
    out = name.with_suffix(".bag") if fmt == "ros1" else name
    if out.exists():
        return out
    t0 = time.perf_counter()
    path = write_bag(scene, name, fmt)
    print(
        f"wrote {path} ({size_of(path) / 1e9:.2f} GB) in {time.perf_counter() - t0:.0f} s",
        flush=True,
    )
    return path


def size_of(path: Path) -> int:
    return sum(p.stat().st_size for p in ([path] if path.is_file() else path.iterdir()))


def run(cmd: list[str]) -> tuple[float, float, float, int]:
    """(cpu s, wall s, peak RSS MB, exit status) of one process."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _pid, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    if proc.stderr is not None:
        proc.stderr.read()
        proc.stderr.close()
    cpu = usage.ru_utime + usage.ru_stime
    return cpu, wall, usage.ru_maxrss / 1024, os.waitstatus_to_exitcode(status)


def bench(bag: Path, rounds: int) -> None:
    sk = [sys.executable, "-m", "sensorkit"]
    commands = {
        "check-recording": [*sk, "check-recording", str(bag), str(CAR), "-q"],
        "topics (start-up)": [*sk, "topics", str(CAR), "-q"],
        "peer: read all": [sys.executable, "-c", PEER, str(bag), "raw"],
        "peer: decode all": [sys.executable, "-c", PEER, str(bag), "decode"],
    }
    results: dict[str, list[tuple[float, float, float, int]]] = {k: [] for k in commands}
    names = list(commands)
    load0 = os.getloadavg()[0]
    for i in range(rounds):
        for name in names[i % len(names) :] + names[: i % len(names)]:
            results[name].append(run(commands[name]))
    load1 = os.getloadavg()[0]
    print(
        f"\n{bag.name} ({size_of(bag) / 1e9:.2f} GB): {rounds} rounds, load {load0:.1f} -> {load1:.1f}"
    )
    med: dict[str, float] = {}
    for name, rows in results.items():
        cpu = statistics.median(r[0] for r in rows)
        wall = statistics.median(r[1] for r in rows)
        rss = max(r[2] for r in rows)
        med[name] = cpu
        codes = sorted({r[3] for r in rows})
        print(
            f"  {name:<18} cpu {cpu:7.2f} s  wall {wall:7.2f} s  peak RSS {rss:7.1f} MB  exit {codes}"
        )
    own = med["check-recording"] - med["topics (start-up)"]
    print(
        f"  check-recording's own CPU (less start-up) {own:.2f} s; check-recording / read all "
        f"{med['check-recording'] / med['peer: read all']:.2f}x, / decode all "
        f"{med['check-recording'] / med['peer: decode all']:.2f}x",
        flush=True,
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scratch", type=Path, default=Path("/work/scratch/recording/bench"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--frames", default="93,930", help="30 Hz frames per size (930: about 2 GB)")
    ap.add_argument("--formats", default="mcap,sqlite3,ros1")
    ap.add_argument("--keep", action="store_true", help="keep the generated recordings")
    args = ap.parse_args()
    scratch = args.scratch.resolve()
    if scratch.is_relative_to(ROOT):
        ap.error("--scratch must be outside the repository")
    scratch.mkdir(parents=True, exist_ok=True)
    try:
        for fmt in args.formats.split(","):
            for frames in (int(f) for f in args.frames.split(",")):
                bag = make_bag(scratch, fmt, frames)
                bench(bag, args.rounds)
                if not args.keep:
                    shutil.rmtree(bag) if bag.is_dir() else bag.unlink()
    finally:
        if not args.keep:
            shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
