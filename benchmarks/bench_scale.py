"""How `sensorkit validate` scales: deep chains and wide 8-ary trees of 10k and 100k links.

Run by hand (never in the test suite)::

    .venv/bin/python benchmarks/bench_scale.py            # everything, 5 runs each
    .venv/bin/python benchmarks/bench_scale.py --sizes 10000 --shapes wide --runs 7

Each robot carries ~100 cameras (half publishing in their optical frame, a quarter in the
body link next to an optical frame, a quarter in the body link with no optical frame at
all) and 10 lidars (some stamped with an optical frame). Per robot, the commands run in
paired, interleaved rounds (validate, floor, check_urdf; the order rotates each round) and
the medians of their CPU times (user + sys of the child) are compared:

- the floor: a Python process that imports lxml, parses the file with sensorkit's parser
  options and walks every element once, reading its tag and attributes: what any Python
  validator pays at the least;
- ``check_urdf`` (Debian liburdfdom-tools): urdfdom's own reader (not on deep chains over
  10k links, where printing the tree indented by depth takes minutes).

The growth exponent is log(t(100k) / t(10k)) / log(10): 1.0 is linear. Start-up is a
100-link robot with sensors against ``python -c "import typer, lxml.etree"``.

Targets (issue 11): exponent <= 1.1; validate <= 1.3x the floor at 10k and 100k; <= 1.0x
check_urdf on the wide 10k tree; the 100-link validate <= 1.25x the typer+lxml start-up.
The code under test is the checkout this script lives in (PYTHONPATH points at it).
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_validate import INERTIAL, timed

ROOT = Path(__file__).resolve().parent.parent

FLOOR = """
import sys
from lxml import etree
parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                         dtd_validation=False, huge_tree=True, remove_blank_text=False,
                         recover=False)
with open(sys.argv[1], "rb") as f:
    root = etree.fromstring(f.read(), parser)
n = 0
for el in root.iter():
    if isinstance(el.tag, str):
        n += len(el.items())
print(n)
"""

OPTICAL_RPY = "-1.5707963267948966 0 -1.5707963267948966"


def _camera(i: int, link: str, frame: str) -> str:
    return (
        f'<gazebo reference="{link}"><sensor name="cam{i}" type="camera"><update_rate>30</update_rate>'
        "<camera><horizontal_fov>1.2</horizontal_fov><image><width>640</width><height>480</height>"
        "</image><clip><near>0.05</near><far>50</far></clip></camera>"
        f'<plugin name="cam{i}_controller" filename="libgazebo_ros_camera.so">'
        f"<ros><namespace>/cam{i}</namespace></ros><camera_name>cam{i}</camera_name>"
        f"<frame_name>{frame}</frame_name></plugin></sensor></gazebo>"
    )


def _lidar(i: int, link: str, frame: str) -> str:
    return (
        f'<gazebo reference="{link}"><sensor name="lidar{i}" type="ray"><update_rate>10</update_rate>'
        "<ray><scan><horizontal><samples>360</samples><resolution>1</resolution>"
        "<min_angle>-3.14159</min_angle><max_angle>3.14159</max_angle></horizontal></scan>"
        "<range><min>0.12</min><max>12.0</max></range></ray>"
        f'<plugin name="lidar{i}_controller" filename="libgazebo_ros_ray_sensor.so">'
        f"<ros><namespace>/lidar{i}</namespace><remapping>~/out:=scan</remapping></ros>"
        "<output_type>sensor_msgs/LaserScan</output_type>"
        f"<frame_name>{frame}</frame_name></plugin></sensor></gazebo>"
    )


def scale_urdf(n: int, shape: str, cameras: int = 100, lidars: int = 10) -> str:
    """``n`` links in a deep chain or a wide 8-ary tree, with cameras and lidars on them."""
    parts = ['<?xml version="1.0"?>', '<robot name="scale">', '<link name="link0"/>']
    for i in range(1, n):
        if shape == "deep":
            parent, xyz = i - 1, "0.1 0 0.01"  # a helix: no two links in one place
        else:
            parent, k = (i - 1) // 8, (i - 1) % 8
            xyz = f"0.1 {0.02 * k - 0.07:.2f} 0.01"
        parts.append(
            f'<link name="link{i}">{INERTIAL}<visual><geometry><box size="0.1 0.1 0.1"/>'
            "</geometry></visual></link>"
        )
        parts.append(
            f'<joint name="joint{i}" type="revolute"><parent link="link{parent}"/>'
            f'<child link="link{i}"/><origin xyz="{xyz}" rpy="0 0 0.1"/><axis xyz="0 0 1"/>'
            '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
        )
    step = max(1, n // (cameras + lidars + 1))
    for c in range(cameras):
        link = f"link{step * (c + 1)}"
        optical = f"cam{c}_optical_frame"
        if c % 4 != 3:  # three in four have an optical frame beside them
            parts.append(
                f'<link name="{optical}"/><joint name="{optical}_joint" type="fixed">'
                f'<parent link="{link}"/><child link="{optical}"/>'
                f'<origin xyz="0 0 0" rpy="{OPTICAL_RPY}"/></joint>'
            )
        parts.append(_camera(c, link, optical if c % 2 == 0 else link))
    for k in range(lidars):
        link = f"link{step * (cameras + k + 1)}"
        frame = link if k % 3 else "cam0_optical_frame"
        parts.append(_lidar(k, link, frame))
    parts.append("</robot>")
    return "\n".join(parts) + "\n"


def median_cpu(cmd: list[str], env: dict[str, str]) -> float:
    return timed(cmd, 1, env)[1][0]


def paired(cmds: dict[str, list[str]], runs: int, env: dict[str, str]) -> dict[str, float]:
    """Median CPU seconds of each command over ``runs`` interleaved rounds; and, as
    ``"<name>/<first>"``, the median over rounds of each command's ratio to the first
    command of the same round (steadier than a ratio of medians when the machine's speed
    drifts between rounds)."""
    names = list(cmds)
    times: dict[str, list[float]] = {name: [] for name in names}
    for r in range(runs):
        order = names[r % len(names) :] + names[: r % len(names)]
        for name in order:
            times[name].append(median_cpu(cmds[name], env))
    out = {name: statistics.median(t) for name, t in times.items()}
    first = names[0]
    for name in names[1:]:
        out[f"{first}/{name}"] = statistics.median(
            a / b for a, b in zip(times[first], times[name], strict=True)
        )
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[10_000, 100_000])
    ap.add_argument("--shapes", nargs="+", default=["deep", "wide"], choices=["deep", "wide"])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--no-check-urdf", action="store_true", help="skip check_urdf")
    ap.add_argument("--no-startup", action="store_true", help="skip the start-up comparison")
    a = ap.parse_args()
    check_urdf = None if a.no_check_urdf else shutil.which("check_urdf")
    if not a.no_check_urdf and check_urdf is None:
        print("check_urdf is missing (apt-get install liburdfdom-tools): not compared")
    py = sys.executable
    results: dict[tuple[str, int], dict[str, float]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, PYTHONPYCACHEPREFIX=str(Path(tmp) / "pycache"))
        env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        floor = Path(tmp) / "floor.py"
        floor.write_text(FLOOR)
        for shape in a.shapes:
            for n in a.sizes:
                path = Path(tmp) / f"{shape}{n}.urdf"
                path.write_text(scale_urdf(n, shape))
                validate = [py, "-m", "sensorkit", "validate", str(path)]
                rc = subprocess.run(validate, capture_output=True, text=True, env=env, check=False)
                last = (rc.stdout.strip().splitlines() or ["(no output)"])[-1]
                print(f"{shape} {n}: exit {rc.returncode}: {last}", flush=True)
                cmds = {"validate": validate, "floor": [py, str(floor), str(path)]}
                # check_urdf prints the tree indented by depth: quadratic on a deep chain
                # (minutes at 100k), so it is compared on the wide trees and deep 10k only.
                if check_urdf is not None and (shape == "wide" or n <= 10_000):
                    cmds["check_urdf"] = [check_urdf, str(path)]
                results[(shape, n)] = paired(cmds, a.runs, env)
                print(
                    "  "
                    + ", ".join(
                        f"{k} {v:.3f}" + ("" if "/" in k else " s")
                        for k, v in results[(shape, n)].items()
                    ),
                    flush=True,
                )
        startup = None
        if not a.no_startup:
            path = Path(tmp) / "small.urdf"
            path.write_text(scale_urdf(100, "wide", cameras=4, lidars=2))
            startup = paired(
                {
                    "validate": [py, "-m", "sensorkit", "validate", str(path)],
                    "typer+lxml": [py, "-c", "import typer, lxml.etree"],
                },
                max(a.runs, 11),
                env,
            )
    print()
    print(f"median CPU seconds of {a.runs} paired runs")
    print("(v/floor, v/check: ratio of the medians; per run: median of each round's ratio)")
    head = (
        f"{'robot':<12}{'validate':>10}{'floor':>9}{'check_urdf':>12}{'v/floor':>9}"
        f"{'per run':>9}{'v/check':>9}{'per run':>9}"
    )
    print(head)
    nan = float("nan")
    for (shape, n), r in results.items():
        cu = r.get("check_urdf")
        print(
            f"{shape + ' ' + str(n):<12}{r['validate']:>10.3f}{r['floor']:>9.3f}"
            f"{cu if cu is not None else nan:>12.3f}{r['validate'] / r['floor']:>9.2f}"
            f"{r['validate/floor']:>9.2f}{r['validate'] / cu if cu else nan:>9.2f}"
            f"{r.get('validate/check_urdf', nan):>9.2f}"
        )
    if len(a.sizes) >= 2:
        lo, hi = min(a.sizes), max(a.sizes)
        for shape in a.shapes:
            for what in ("validate", "floor"):
                t_lo, t_hi = results[(shape, lo)][what], results[(shape, hi)][what]
                k = math.log(t_hi / t_lo) / math.log(hi / lo)
                print(f"growth exponent {shape} {what} {lo}->{hi}: {k:.2f}")
    if startup is not None:
        print(
            f"start-up, 100 links with sensors: validate {startup['validate'] * 1000:.0f} ms, "
            f"typer+lxml {startup['typer+lxml'] * 1000:.0f} ms, "
            f"ratio {startup['validate'] / startup['typer+lxml']:.2f} "
            f"(per run {startup['validate/typer+lxml']:.2f})"
        )


if __name__ == "__main__":
    main()
