"""Whole-process `sensorkit validate` vs `check_urdf` on a generated 10,000-link URDF.

Run by hand (never in the test suite): `.venv/bin/python benchmarks/bench_validate.py`.
Target: sensorkit's median at most check_urdf's (aim for half).
"""

from __future__ import annotations

import argparse
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>'


def big_urdf(n: int, seed: int = 1, *, camera: bool = True) -> str:
    """A random tree of ``n`` links (revolute joints), with a camera on it unless told not."""
    rnd = random.Random(seed)
    parts = ['<?xml version="1.0"?>', '<robot name="big">', '<link name="link0"/>']
    for i in range(1, n):
        parent = rnd.randrange(max(0, i - 50), i)
        parts.append(f'<link name="link{i}">{INERTIAL}<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>')
        parts.append(
            f'<joint name="joint{i}" type="revolute"><parent link="link{parent}"/><child link="link{i}"/>'
            '<origin xyz="0.1 0 0" rpy="0 0 0.1"/><axis xyz="0 0 1"/>'
            '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
        )
    if not camera:
        parts.append("</robot>")
        return "\n".join(parts) + "\n"
    parts.append('<link name="cam_optical"/><joint name="cam_optical_joint" type="fixed"><parent link="link5"/>'
                 '<child link="cam_optical"/><origin xyz="0 0 0" rpy="-1.5707963267948966 0 -1.5707963267948966"/></joint>')
    parts.append(
        '<gazebo reference="link5"><sensor name="cam" type="camera"><update_rate>30</update_rate><camera>'
        '<horizontal_fov>1.2</horizontal_fov><image><width>640</width><height>480</height></image>'
        '<clip><near>0.05</near><far>50</far></clip></camera><plugin name="cam_controller" filename="libgazebo_ros_camera.so">'
        '<frame_name>cam_optical</frame_name></plugin></sensor></gazebo>'
    )
    parts.append('</robot>')
    return "\n".join(parts) + "\n"


def timed(cmd: list[str], runs: int, env: dict[str, str] | None = None) -> tuple[list[float], list[float]]:
    """Wall-clock and CPU (user + sys of the child) seconds per run.

    CPU time is the steadier figure on a shared machine; both are reported.
    """
    import resource

    wall, cpu = [], []
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False, env=env)
        wall.append(time.perf_counter() - t0)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return wall, cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--links", type=int, default=10_000)
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument(
        "--no-camera",
        action="store_true",
        help="links and joints only, like what check_urdf reads (no numpy import needed)",
    )
    a = ap.parse_args()
    check_urdf = shutil.which("check_urdf")
    sensorkit = shutil.which("sensorkit") or str(Path(sys.executable).with_name("sensorkit"))
    if check_urdf is None:
        sys.exit("check_urdf is missing: apt-get install liburdfdom-tools")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "big.urdf"
        path.write_text(big_urdf(a.links, camera=not a.no_camera))
        # An installed package has its bytecode compiled; some shells set PYTHONDONTWRITEBYTECODE,
        # which would make every run recompile sensorkit. Cache bytecode in the temp folder.
        env = dict(os.environ, PYTHONPYCACHEPREFIX=str(Path(tmp) / "pycache"))
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        rc = subprocess.run([sensorkit, "validate", str(path)], capture_output=True, text=True, env=env, check=False)
        print(f"sensorkit exit {rc.returncode}: {rc.stdout.strip().splitlines()[-1]}")
        size = path.stat().st_size
        cu_wall, cu_cpu = timed([check_urdf, str(path)], a.runs)
        sk_wall, sk_cpu = timed([sensorkit, "validate", str(path)], a.runs, env)
    med = statistics.median
    print(f"{a.links} links, {size} bytes, {a.runs} runs each (median wall / median CPU)")
    print(f"check_urdf          {med(cu_wall) * 1000:8.1f} ms  {med(cu_cpu) * 1000:8.1f} ms")
    print(f"sensorkit validate  {med(sk_wall) * 1000:8.1f} ms  {med(sk_cpu) * 1000:8.1f} ms")
    print(
        f"ratio sensorkit/check_urdf: wall {med(sk_wall) / med(cu_wall):.2f}, CPU {med(sk_cpu) / med(cu_cpu):.2f}"
        " (target <= 1.0, aim 0.5)"
    )


if __name__ == "__main__":
    main()
