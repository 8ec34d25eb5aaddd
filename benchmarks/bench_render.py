"""How much does ``sensorkit render preview`` cost over pybullet doing the same work?

For each sensor kind a one-sensor robot is previewed, and a raw pybullet script does the
same work by hand and writes nothing: that script is the floor any pybullet preview
stands on. The robots:

* ``camera``: one 640x480 camera (classic, with a ROS plugin).
* ``scan``: a 360-beam 2D lidar (classic ``ray``, with a ROS plugin).
* ``velo``: a 128 x 2048 3D lidar (gz ``gpu_lidar``; 262,144 rays, 17 rayTestBatch calls).
* ``mixed`` (with ``--mixed``): two 640x480 cameras and the 360-beam lidar, the robot of
  the first version of this benchmark, where the preview spreads sensors over processes.

The raw script builds the same world (ground, four textured walls, four textured crates,
72 marker spheres, the robot's URDF), loading the very texture files the preview loads (the
default room's, walls 512 px, as sensorkit.render.textures keeps them), then renders the frames with TinyRenderer and casts
the beams with rayTestBatch in batches of 16,383 rays, as the preview does. Textures are
loaded only when a camera renders: rays never see them, and the preview skips them too.

Both sides run as whole processes (interpreter start, imports, everything), paired and
interleaved: run k previews every robot and runs its raw script back to back, the order
of the pair alternating from one run to the next, so a machine that gets busier or
quieter weighs on both sides alike. Each run's CPU time is what
``resource.getrusage(RUSAGE_CHILDREN)`` adds up over the process and every process it
forked (pybullet's ray threads included); wall time is printed beside it. The ratios are
of the medians; the median of the per-pair ratios is printed too.

CPU time is the figure to read on a shared machine: wall time counts whatever else is
running, and a preview that renders in parallel spends more CPU than wall time. The raw
script runs with numpy's default OpenBLAS thread pool (sensorkit sets
OPENBLAS_NUM_THREADS=1): starting the pool costs it 0.10-0.13 s of CPU (9 pairs each,
2026-11-29), most of why its CPU time exceeds its wall time for the camera and the 2D
lidar. Left so: it is what a script importing numpy pays.

``--baseline DIR`` adds a third side to every round: the preview of another sensorkit
source tree (a git worktree of the commit to compare, e.g. ``git worktree add --detach
../base main``), run from that folder so that its code, not this one, is imported. Its
ratios print beside this tree's, with the paired CPU difference: before and after in the
same rounds.

Run by hand, never from the tests:
``PYTHONPATH=. .venv/bin/python benchmarks/bench_render.py [--runs N] [--only KIND ...]
[--baseline DIR]``.
Target (issue 37): each kind <= 1.3 (CPU time).
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

INERTIAL = '<inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>'
BASE = """
  <link name="base_link">
    <inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0 0 0.15"/><geometry><box size="0.5 0.4 0.3"/></geometry></visual>
    <collision><origin xyz="0 0 0.15"/><geometry><box size="0.5 0.4 0.3"/></geometry></collision>
  </link>"""


def _camera(name: str, xyz: str, rpy: str, hfov: float) -> str:
    return f"""
  <link name="{name}_cam">{INERTIAL}</link>
  <joint name="{name}_cam_joint" type="fixed"><parent link="base_link"/><child link="{name}_cam"/><origin xyz="{xyz}" rpy="{rpy}"/></joint>
  <link name="{name}_cam_optical"/>
  <joint name="{name}_cam_optical_joint" type="fixed"><parent link="{name}_cam"/><child link="{name}_cam_optical"/>
    <origin rpy="-1.5707963267948966 0 -1.5707963267948966"/></joint>
  <gazebo reference="{name}_cam">
    <sensor name="{name}" type="camera"><camera><horizontal_fov>{hfov}</horizontal_fov>
      <image><width>640</width><height>480</height></image><clip><near>0.05</near><far>50</far></clip></camera>
      <plugin name="{name}_driver" filename="libgazebo_ros_camera.so"><frame_name>{name}_cam_optical</frame_name></plugin>
    </sensor>
  </gazebo>"""


SCAN = f"""
  <link name="laser">{INERTIAL}</link>
  <joint name="laser_joint" type="fixed"><parent link="base_link"/><child link="laser"/><origin xyz="0 0 0.4"/></joint>
  <gazebo reference="laser">
    <sensor name="scan" type="ray"><ray>
      <scan><horizontal><samples>360</samples><resolution>1</resolution>
        <min_angle>-3.141592653589793</min_angle><max_angle>3.141592653589793</max_angle></horizontal></scan>
      <range><min>0.12</min><max>12</max></range></ray>
      <plugin name="scan_driver" filename="libgazebo_ros_ray_sensor.so">
        <ros><remapping>~/out:=scan</remapping></ros><frame_name>laser</frame_name></plugin>
    </sensor>
  </gazebo>"""

VELO = f"""
  <link name="lidar_link">{INERTIAL}</link>
  <joint name="lidar_joint" type="fixed"><parent link="base_link"/><child link="lidar_link"/><origin xyz="0 0 0.8"/></joint>
  <gazebo reference="lidar_link">
    <sensor name="velo" type="gpu_lidar">
      <gz_frame_id>lidar_link</gz_frame_id>
      <topic>velo/scan</topic>
      <lidar>
        <scan>
          <horizontal><samples>2048</samples><resolution>1</resolution><min_angle>-3.141592653589793</min_angle><max_angle>3.141592653589793</max_angle></horizontal>
          <vertical><samples>128</samples><resolution>1</resolution><min_angle>-0.39269908169872414</min_angle><max_angle>0.39269908169872414</max_angle></vertical>
        </scan>
        <range><min>0.3</min><max>30</max></range>
      </lidar>
    </sensor>
  </gazebo>"""

FRONT = _camera("front", "0.25 0 0.5", "0 0 0", 1.2)
REAR = _camera("rear", "-0.25 0 0.5", "0 0.2 3.141592653589793", 1.5)


def _robot(name: str, *parts: str) -> str:
    return f'<?xml version="1.0"?>\n<robot name="{name}">{BASE}{"".join(parts)}\n</robot>\n'


# kind -> (robot, the raw script's work: "cam:x,y,z,tx,ty,tz,hfov" / "rays:z,rows,vlo,vhi,cols,min,max")
CASES: dict[str, tuple[str, list[str]]] = {
    "camera": (_robot("cam_bot", FRONT), ["cam:0.25,0,0.5,1.25,0,0.5,1.2"]),
    "scan": (_robot("scan_bot", SCAN), ["rays:0.4,1,0,0,360,0.12,12"]),
    "velo": (
        _robot("velo_bot", VELO),
        ["rays:0.8,128,-0.39269908169872414,0.39269908169872414,2048,0.3,30"],
    ),
    "mixed": (
        _robot("mixed_bot", FRONT, REAR, SCAN),
        [
            "cam:0.25,0,0.5,1.25,0,0.5,1.2",
            "cam:-0.25,0,0.5,-1.25,0,0.2973,1.5",
            "rays:0.4,1,0,0,360,0.12,12",
        ],
    ),
}

# The same world built by hand with pybullet alone: what any pybullet preview must do.
RAW = r"""
import math, sys
import numpy as np
import pybullet as p

robot, textures, suffix, work = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
# Rays meet collision shapes, never a texture: without a camera to render, none is loaded
# (as the preview does).
cams = any(job.startswith("cam:") for job in work)
p.connect(p.DIRECT)

def box_mesh(h, k):
    v, uv, n, idx = [], [], [], []
    for a in range(3):
        b, c = (a + 1) % 3, (a + 2) % 3
        for s in (1.0, -1.0):
            corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
            corners = corners if s > 0 else corners[::-1]
            start = len(v)
            for u, w in corners:
                q = [0.0, 0.0, 0.0]; q[a] = s * h[a]; q[b] = u * h[b]; q[c] = w * h[c]
                v.append(q); uv.append([u * h[b] * k, w * h[c] * k])
                m = [0.0, 0.0, 0.0]; m[a] = s; n.append(m)
            idx += [start, start + 1, start + 2, start, start + 2, start + 3]
    return v, idx, uv, n

def textured_box(h, pos, yaw, tex, k):
    v, i, uv, n = box_mesh(h, k)
    vis = p.createVisualShape(p.GEOM_MESH, vertices=v, indices=i, uvs=uv, normals=n)
    col = p.createCollisionShape(p.GEOM_BOX, halfExtents=h)
    body = p.createMultiBody(0, col, vis, pos, p.getQuaternionFromEuler([0, 0, yaw]))
    if cams:
        p.changeVisualShape(body, -1, textureUniqueId=p.loadTexture(f"{textures}/{tex}{suffix}"), rgbaColor=[1, 1, 1, 1])

L = 3.0
v, i, uv, n = box_mesh([L + 0.2, L + 0.2, 0.01], 1.0)
floor = p.createMultiBody(0, p.createCollisionShape(p.GEOM_PLANE),
    p.createVisualShape(p.GEOM_MESH, vertices=v, indices=i, uvs=uv, normals=n, visualFramePosition=[0, 0, -0.01]))
if cams:
    p.changeVisualShape(floor, -1, textureUniqueId=p.loadTexture(f"{textures}/floor{suffix}"), rgbaColor=[1, 1, 1, 1])
for k, (x, y, h) in enumerate([(L + 0.1, 0, (0.1, L + 0.2, 1.25)), (-L - 0.1, 0, (0.1, L + 0.2, 1.25)),
                               (0, L + 0.1, (L + 0.2, 0.1, 1.25)), (0, -L - 0.1, (L + 0.2, 0.1, 1.25))]):
    textured_box(list(h), [x, y, 1.25], 0.0, f"wall{k}", 0.5)
for k, (sx, sy) in enumerate([(1, 1), (-1, 1), (-1, -1), (1, -1)]):
    textured_box([0.3, 0.3, 0.4], [sx * 0.62 * L, sy * 0.62 * L, 0.4], 0.45 + 0.3 * k, f"crate{k}", 1.2)
markers = []
for axis, sign in ((0, 1), (0, -1), (1, 1), (1, -1)):
    for lat in (-0.75, -0.45, -0.15, 0.15, 0.45, 0.75):
        for z in (0.3, 0.9, 1.6):
            q = [0.0, 0.0, z]; q[axis] = sign * (L - 0.25); q[1 - axis] = lat * L
            markers.append(q)
p.createMultiBody(0, p.createCollisionShape(p.GEOM_SPHERE, radius=0.05),
                  p.createVisualShape(p.GEOM_SPHERE, radius=0.05, rgbaColor=[1, 0.1, 0.9, 1]), batchPositions=markers)
body = p.loadURDF(robot, useFixedBase=True)
p.performCollisionDetection()

for job in work:
    what, _, numbers = job.partition(":")
    a = [float(x) for x in numbers.split(",")]
    if what == "cam":
        eye, target, hfov = a[0:3], a[3:6], a[6]
        vfov = math.degrees(2 * math.atan(math.tan(hfov / 2) * 480 / 640))
        view = p.computeViewMatrix(eye, target, [0, 0, 1])
        proj = p.computeProjectionMatrixFOV(vfov, 640 / 480, 0.05, 50)
        p.getCameraImage(640, 480, view, proj, renderer=p.ER_TINY_RENDERER,
                         flags=p.ER_SEGMENTATION_MASK_OBJECT_AND_LINKINDEX, shadow=0)
    else:
        z, rows, vlo, vhi, cols, rmin, rmax = a
        az = np.linspace(-math.pi, math.pi, int(cols))[None, :]
        el = (np.linspace(vlo, vhi, int(rows)) if rows > 1 else np.zeros(1))[:, None]
        d = np.stack(np.broadcast_arrays(np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)), axis=-1).reshape(-1, 3)
        o = np.array([0.0, 0.0, z])
        starts, ends = o + rmin * d, o + rmax * d
        for lo in range(0, len(d), 16383):
            p.rayTestBatch(starts[lo:lo + 16383], ends[lo:lo + 16383], numThreads=0)
"""


Side = tuple[list[str], dict[str, str], "str | None"]  # command, environment, folder


def _run(command: list[str], env: dict[str, str], cwd: str | None = None) -> tuple[float, float]:
    """(CPU seconds of the process and its children, wall seconds) of one run."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    proc = subprocess.run(command, capture_output=True, text=True, check=False, env=env, cwd=cwd)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode not in (0, 1):
        sys.exit(f"failed ({proc.returncode}): {' '.join(command)}\n{proc.stderr}")
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    return cpu, wall


def _fmt(values: list[float]) -> str:
    return ", ".join(f"{v:.2f}" for v in values)


def _sides(folder: Path, kinds: list[str], baseline: Path | None) -> dict[str, dict[str, Side]]:
    """Each robot's sides: ``sk`` (this sensorkit), ``base`` (the ``--baseline`` tree's)
    and ``raw`` (the raw script), written into ``folder`` with the textures they load."""
    from sensorkit.render.scene import default_scene
    from sensorkit.render.textures import texture_file

    textures = folder / "textures"
    textures.mkdir()
    # the files the preview loads: the default room's textures at their sizes (walls
    # 512 px), in the format the preview hands pybullet
    for key, texture in default_scene(3.0).textures.items():
        made = texture_file(texture, textures)
        (textures / f"{key}{made.suffix}").write_bytes(made.read_bytes())
    raw_script = folder / "raw.py"
    raw_script.write_text(RAW)
    # Every side runs as installed code does: with bytecode cached (kept in a temporary
    # folder, so the source tree stays clean, whatever PYTHONDONTWRITEBYTECODE says).
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPYCACHEPREFIX"] = str(folder / "pycache")
    sides: dict[str, dict[str, Side]] = {}
    for kind in kinds:
        text, work = CASES[kind]
        robot = folder / f"{kind}.urdf"
        robot.write_text(text)
        sk = [sys.executable, "-m", "sensorkit", "render", "preview", str(robot), "--out"]
        raw = [sys.executable, str(raw_script), str(robot), str(textures), made.suffix, *work]
        sides[kind] = {"sk": ([*sk, str(folder / f"out-{kind}")], env, None)}
        if baseline is not None:  # run from its folder: `-m` puts the working folder first
            base_env = {**env, "PYTHONPATH": str(baseline)}
            sides[kind]["base"] = ([*sk, str(folder / f"base-{kind}")], base_env, str(baseline))
        sides[kind]["raw"] = (raw, env, None)
    return sides


def _report(times: dict[str, dict[str, list[tuple[float, float]]]]) -> None:
    """Medians per robot and side, then each sensorkit's ratios to the raw script."""
    print(f"{'robot':8} {'side':5} {'CPU median':>10} {'wall median':>11}   CPU per run (s)")
    for kind, by_side in times.items():
        for side, runs in by_side.items():
            cpu, wall = [c for c, _ in runs], [w for _, w in runs]
            print(
                f"{kind:8} {side:5.5} {statistics.median(cpu):10.3f} "
                f"{statistics.median(wall):11.3f}   {_fmt(cpu)}"
            )
    print(f"\n{'robot':8} {'side':5} {'CPU ratio':>9} {'paired':>7} {'wall ratio':>10}")
    for kind, by_side in times.items():
        raw_cpu = [c for c, _ in by_side["raw"]]
        raw_wall = [w for _, w in by_side["raw"]]
        for side in [s for s in by_side if s != "raw"]:
            cpu = [c for c, _ in by_side[side]]
            wall = [w for _, w in by_side[side]]
            paired = statistics.median(a / b for a, b in zip(cpu, raw_cpu, strict=True))
            print(
                f"{kind:8} {side:5.5} {statistics.median(cpu) / statistics.median(raw_cpu):9.2f} "
                f"{paired:7.2f} {statistics.median(wall) / statistics.median(raw_wall):10.2f}"
            )
        if "base" in by_side:
            diff = statistics.median(
                a - b for (a, _), (b, _) in zip(by_side["sk"], by_side["base"], strict=True)
            )
            print(f"{kind:8} sk - base, paired CPU median: {diff * 1000:+.0f} ms")


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--only", nargs="*", choices=sorted(CASES), default=None)
    parser.add_argument("--mixed", action="store_true", help="add the two-camera + lidar robot")
    parser.add_argument(
        "--baseline",
        type=Path,
        default=None,
        help="another sensorkit source tree (a git worktree of the commit to compare): its "
        "preview runs in the same rounds, as side 'base'",
    )
    options = parser.parse_args()
    kinds = options.only or ["camera", "scan", "velo"] + (["mixed"] if options.mixed else [])
    baseline = options.baseline.resolve() if options.baseline is not None else None
    with tempfile.TemporaryDirectory(prefix="bench-render-") as tmp:
        sides = _sides(Path(tmp), kinds, baseline)
        for by_side in sides.values():  # warm the bytecode and file caches of every side
            for side in by_side.values():
                _run(*side)
        load = os.getloadavg()[0]
        times = {kind: {name: [] for name in by_side} for kind, by_side in sides.items()}
        for k in range(options.runs):
            for kind, by_side in sides.items():
                names = list(by_side) if k % 2 == 0 else list(reversed(by_side))
                for name in names:
                    times[kind][name].append(_run(*by_side[name]))
    print(
        f"runs: {options.runs} rounds per robot, interleaved; cores: {os.cpu_count()}; "
        f"load average before: {load:.2f}, after: {os.getloadavg()[0]:.2f}"
    )
    _report(times)


if __name__ == "__main__":
    main()
