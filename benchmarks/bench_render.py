"""How much does ``sensorkit render preview`` cost over pybullet doing the same work?

Both sides run as whole processes (interpreter start, imports, everything), several
times each; the medians are compared:

* sensorkit: ``sensorkit render preview`` of a robot with two 640x480 cameras and a
  360-beam lidar, in the default scene (all files, all checks, validate's findings).
* raw pybullet: a script that builds the same world by hand (ground, four textured
  walls, four textured crates, 72 marker spheres, the robot's URDF), renders the two
  640x480 frames with TinyRenderer and casts the 360 beams in one rayTestBatch, and
  writes nothing.

The library call alone (``render_preview`` in a bare ``python -c``) is timed as well, to
separate the command line's start-up (typer, which imports pydantic, and rich) from the
preview's own cost.

It also times one 16 x 1800 3D lidar scan (28,800 rays) inside one process, as the
preview casts it, and pybullet's raw rayTestBatch for the same rays.

Run: ``.venv/bin/python benchmarks/bench_render.py [--runs N]``. Target: ratio <= 1.5.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROBOT = """<?xml version="1.0"?>
<robot name="bench_bot">
  <link name="base_link">
    <inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0 0 0.15"/><geometry><box size="0.5 0.4 0.3"/></geometry></visual>
    <collision><origin xyz="0 0 0.15"/><geometry><box size="0.5 0.4 0.3"/></geometry></collision>
  </link>
  <link name="front_cam"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="front_cam_joint" type="fixed"><parent link="base_link"/><child link="front_cam"/><origin xyz="0.25 0 0.5"/></joint>
  <link name="front_cam_optical"/>
  <joint name="front_cam_optical_joint" type="fixed"><parent link="front_cam"/><child link="front_cam_optical"/>
    <origin rpy="-1.5707963267948966 0 -1.5707963267948966"/></joint>
  <link name="rear_cam"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="rear_cam_joint" type="fixed"><parent link="base_link"/><child link="rear_cam"/><origin xyz="-0.25 0 0.5" rpy="0 0.2 3.141592653589793"/></joint>
  <link name="rear_cam_optical"/>
  <joint name="rear_cam_optical_joint" type="fixed"><parent link="rear_cam"/><child link="rear_cam_optical"/>
    <origin rpy="-1.5707963267948966 0 -1.5707963267948966"/></joint>
  <link name="laser"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="laser_joint" type="fixed"><parent link="base_link"/><child link="laser"/><origin xyz="0 0 0.4"/></joint>
  <gazebo reference="front_cam">
    <sensor name="front" type="camera"><camera><horizontal_fov>1.2</horizontal_fov>
      <image><width>640</width><height>480</height></image><clip><near>0.05</near><far>50</far></clip></camera>
      <plugin name="front_driver" filename="libgazebo_ros_camera.so"><frame_name>front_cam_optical</frame_name></plugin>
    </sensor>
  </gazebo>
  <gazebo reference="rear_cam">
    <sensor name="rear" type="camera"><camera><horizontal_fov>1.5</horizontal_fov>
      <image><width>640</width><height>480</height></image><clip><near>0.05</near><far>50</far></clip></camera>
      <plugin name="rear_driver" filename="libgazebo_ros_camera.so"><frame_name>rear_cam_optical</frame_name></plugin>
    </sensor>
  </gazebo>
  <gazebo reference="laser">
    <sensor name="scan" type="ray"><ray>
      <scan><horizontal><samples>360</samples><resolution>1</resolution>
        <min_angle>-3.141592653589793</min_angle><max_angle>3.141592653589793</max_angle></horizontal></scan>
      <range><min>0.12</min><max>12</max></range></ray>
      <plugin name="scan_driver" filename="libgazebo_ros_ray_sensor.so">
        <ros><remapping>~/out:=scan</remapping></ros><frame_name>laser</frame_name></plugin>
    </sensor>
  </gazebo>
</robot>
"""

# The same world built by hand with pybullet alone: what any pybullet preview must do.
RAW = r"""
import math, sys
import numpy as np
import pybullet as p

robot, textures = sys.argv[1], sys.argv[2]
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
    p.changeVisualShape(body, -1, textureUniqueId=p.loadTexture(f"{textures}/{tex}.png"), rgbaColor=[1, 1, 1, 1])

L = 3.0
v, i, uv, n = box_mesh([L + 0.2, L + 0.2, 0.01], 1.0)
floor = p.createMultiBody(0, p.createCollisionShape(p.GEOM_PLANE),
    p.createVisualShape(p.GEOM_MESH, vertices=v, indices=i, uvs=uv, normals=n, visualFramePosition=[0, 0, -0.01]))
p.changeVisualShape(floor, -1, textureUniqueId=p.loadTexture(f"{textures}/floor.png"), rgbaColor=[1, 1, 1, 1])
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

def frame(eye, target, hfov):
    vfov = math.degrees(2 * math.atan(math.tan(hfov / 2) * 480 / 640))
    view = p.computeViewMatrix(eye, target, [0, 0, 1])
    proj = p.computeProjectionMatrixFOV(vfov, 640 / 480, 0.05, 50)
    return p.getCameraImage(640, 480, view, proj, renderer=p.ER_TINY_RENDERER,
                            flags=p.ER_SEGMENTATION_MASK_OBJECT_AND_LINKINDEX, shadow=0)

frame([0.25, 0, 0.5], [1.25, 0, 0.5], 1.2)
frame([-0.25, 0, 0.5], [-1.25, 0, 0.5 - 0.2027], 1.5)
a = np.linspace(-math.pi, math.pi, 360)
d = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=1)
o = np.array([0.0, 0.0, 0.4])
p.rayTestBatch(o + 0.12 * d, o + 12.0 * d, numThreads=0)
"""


def _median(command: list[str], runs: int, env: dict[str, str]) -> tuple[float, list[float]]:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        proc = subprocess.run(command, capture_output=True, text=True, check=False, env=env)
        times.append(time.perf_counter() - start)
        if proc.returncode not in (0, 1):
            sys.exit(f"failed ({proc.returncode}): {' '.join(command)}\n{proc.stderr}")
    return statistics.median(times), times


def _lidar_3d() -> tuple[float, float, int]:
    """(preview cast seconds, raw rayTestBatch seconds, calls) for a 16 x 1800 scan."""
    import numpy as np

    from sensorkit.model.sensors import LidarSpec
    from sensorkit.model.transforms import transform
    from sensorkit.render.lidar import cast, lidar_beams
    from sensorkit.render.scene import default_scene
    from sensorkit.render.sim import MAX_RAYS, World

    spec = LidarSpec(element=None, source=None)  # type: ignore[arg-type]
    spec.samples, spec.resolution, spec.min_angle, spec.max_angle = 1800, 1.0, -np.pi, np.pi
    spec.has_vertical, spec.v_samples, spec.v_resolution = True, 16, 1.0
    spec.v_min_angle, spec.v_max_angle = -0.26, 0.26
    spec.range_min, spec.range_max = 0.3, 30.0
    beams = lidar_beams(spec)
    scene = default_scene(0.5)
    with World() as world:
        world.add_default_shapes(scene, scene.half_extent)
        T = transform((0.0, 0.0, 0.8))
        cast(world, T, beams)  # warm up
        runs = []
        for _ in range(5):
            start = time.perf_counter()
            scan = cast(world, T, beams)
            runs.append(time.perf_counter() - start)
        dirs = beams.directions().reshape(-1, 3)
        starts, ends = T[:3, 3] + 0.3 * dirs, T[:3, 3] + 30.0 * dirs
        raw = []
        for _ in range(5):
            start = time.perf_counter()
            for lo in range(0, len(dirs), MAX_RAYS):
                world.p.rayTestBatch(
                    starts[lo : lo + MAX_RAYS],
                    ends[lo : lo + MAX_RAYS],
                    numThreads=0,
                    physicsClientId=world.client,
                )
            raw.append(time.perf_counter() - start)
    return statistics.median(runs), statistics.median(raw), scan.hits.calls


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--runs", type=int, default=7)
    options = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench-render-") as tmp:
        folder = Path(tmp)
        robot = folder / "bench_bot.urdf"
        robot.write_text(ROBOT)
        textures = folder / "textures"
        textures.mkdir()
        from sensorkit.render.png import write_png
        from sensorkit.render.textures import feature_texture, floor_texture

        write_png(textures / "floor.png", floor_texture(7))
        for k in range(4):
            write_png(textures / f"wall{k}.png", feature_texture(100 + k))
            write_png(textures / f"crate{k}.png", feature_texture(200 + k, 128))
        raw_script = folder / "raw.py"
        raw_script.write_text(RAW)
        sk = [
            sys.executable,
            "-c",
            "from sensorkit.cli import main; main()",
            "render",
            "preview",
            str(robot),
            "--out",
            str(folder / "out"),
        ]
        raw = [sys.executable, str(raw_script), str(robot), str(textures)]
        lib = [
            sys.executable,
            "-c",
            "import os, sys; from pathlib import Path; from sensorkit.render import render_preview; "
            "render_preview(Path(sys.argv[1]), Path(sys.argv[2]), workers=min(4, os.cpu_count() or 1))",
            str(robot),
            str(folder / "out-lib"),
        ]
        # Both sides run as installed code does: with bytecode cached (kept in a temporary
        # folder, so the source tree stays clean, whatever PYTHONDONTWRITEBYTECODE says).
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        env["PYTHONPYCACHEPREFIX"] = str(folder / "pycache")
        _median(sk, 1, env)  # warm the bytecode and file caches on both sides
        _median(raw, 1, env)
        _median(lib, 1, env)
        sk_median, sk_times = _median(sk, options.runs, env)
        raw_median, raw_times = _median(raw, options.runs, env)
        lib_median, lib_times = _median(lib, options.runs, env)
    print(f"runs: {options.runs} each (whole processes)")
    print(
        f"sensorkit render preview: median {sk_median:.3f} s  ({', '.join(f'{t:.3f}' for t in sk_times)})"
    )
    print(
        f"raw pybullet, same work:  median {raw_median:.3f} s  ({', '.join(f'{t:.3f}' for t in raw_times)})"
    )
    print(f"ratio: {sk_median / raw_median:.2f}  (target <= 1.5)")
    print(
        f"render_preview() without the CLI: median {lib_median:.3f} s  ({', '.join(f'{t:.3f}' for t in lib_times)})"
    )
    print(
        f"ratio without the CLI: {lib_median / raw_median:.2f}; the CLI's own start-up costs {sk_median - lib_median:.3f} s"
    )
    print(f"cores: {os.cpu_count()}, load average before: {os.getloadavg()[0]:.2f}")
    cast_s, raw_s, calls = _lidar_3d()
    print(
        f"16 x 1800 3D lidar (28,800 rays): preview cast {cast_s * 1000:.1f} ms in {calls} rayTestBatch calls; raw rayTestBatch {raw_s * 1000:.1f} ms"
    )


if __name__ == "__main__":
    main()
