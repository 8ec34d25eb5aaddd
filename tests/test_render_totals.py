"""Issue 36, item 6 (cause 8): one budget for the whole render preview.

``render preview`` of 1,000 small cameras ran past 150 s: the pixel and ray budgets were
per sensor and nothing bounded the total. Now pixels, rays and wall time have one budget
across sensors (``--max-total-pixels``, ``--max-total-rays``, ``--max-seconds``); past it
what fits is rendered and the sensors left out are named, in the result's notes, in each
left-out sensor's record and on the HTML page.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from sensorkit.render.plan import LEFT_OUT, Totals

INERTIAL = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'


def _cameras(folder: Path, n: int, lidar: bool = False) -> Path:
    parts = [f'<robot name="r"><link name="base_link">{INERTIAL}</link>']
    for i in range(n):
        parts.append(
            f'<link name="c{i}"/><joint name="j{i}" type="fixed"><parent link="base_link"/>'
            f'<child link="c{i}"/><origin xyz="0 {i * 0.01} 0.5"/></joint>'
            f'<gazebo reference="c{i}"><sensor name="cam{i}" type="camera"><camera>'
            "<horizontal_fov>1.2</horizontal_fov><image><width>64</width><height>48</height>"
            "</image><clip><near>0.05</near><far>20</far></clip></camera>"
            f'<plugin name="p{i}" filename="libgazebo_ros_camera.so"/></sensor></gazebo>'
        )
    if lidar:
        parts.append(
            '<link name="l"/><joint name="jl" type="fixed"><parent link="base_link"/><child link="l"/>'
            '<origin xyz="0 0 0.8"/></joint><gazebo reference="l"><sensor name="lidar" type="ray">'
            "<ray><scan><horizontal><samples>360</samples><min_angle>-3.14</min_angle>"
            "<max_angle>3.14</max_angle></horizontal></scan><range><min>0.1</min><max>10</max>"
            '</range></ray><plugin name="pl" filename="libgazebo_ros_ray_sensor.so"/></sensor></gazebo>'
        )
    parts.append("</robot>\n")
    path = folder / "r.urdf"
    folder.mkdir(parents=True, exist_ok=True)
    path.write_text("".join(parts))
    return path


def _left_out(result: object) -> list[str]:
    return [s.name for s in getattr(result, "sensors", []) if (s.skipped or "").startswith(LEFT_OUT)]


def test_past_the_total_pixels_what_fits_is_rendered_and_the_rest_named(tmp_path: Path) -> None:
    pytest.importorskip("pybullet")
    from sensorkit.render import render_preview

    robot = _cameras(tmp_path / "ws", 5)
    # each camera is 64 x 48 = 3,072 pixels: 2 fit in 7,000 (just over 6,144), the third not
    result = render_preview(robot, tmp_path / "out", totals=Totals(pixels=7_000))
    assert _left_out(result) == ["cam2", "cam3", "cam4"], [s.skipped for s in result.sensors]
    assert any("cam2, cam3, cam4" in n and "--max-total-pixels" in n for n in result.notes), result.notes
    html = (tmp_path / "out" / "index.html").read_text()
    assert "--max-total-pixels" in html and "cam4" in html
    rendered = [s.name for s in result.sensors if not s.skipped]
    assert rendered == ["cam0", "cam1"]
    near = render_preview(robot, tmp_path / "out2", totals=Totals(pixels=5 * 3072))
    assert _left_out(near) == []  # the near miss: exactly the total fits


def test_past_the_total_rays_a_lidar_is_left_out(tmp_path: Path) -> None:
    pytest.importorskip("pybullet")
    from sensorkit.render import render_preview

    robot = _cameras(tmp_path / "ws", 1, lidar=True)
    result = render_preview(robot, tmp_path / "out", totals=Totals(rays=359))
    assert _left_out(result) == ["lidar"], [s.skipped for s in result.sensors]
    assert any("--max-total-rays" in n for n in result.notes)
    ok = render_preview(robot, tmp_path / "out2", totals=Totals(rays=360))
    assert _left_out(ok) == []


def test_past_the_seconds_the_rest_is_left_out(tmp_path: Path) -> None:
    """200 small cameras with 2 s of rendering: some are rendered, the rest named; the
    preview ends soon after the budget (time printed, not asserted: -s)."""
    pytest.importorskip("pybullet")
    from sensorkit.render import render_preview

    robot = _cameras(tmp_path / "ws", 200)
    start = time.monotonic()
    result = render_preview(robot, tmp_path / "out", totals=Totals(seconds=2.0))
    print(f"200 cameras, --max-seconds 2: {time.monotonic() - start:.1f} s in all")
    left = _left_out(result)
    assert left and len(left) < 200, len(left)
    assert any("--max-seconds" in (s.skipped or "") for s in result.sensors)
    assert any(f"{len(left)} sensor(s) left out" in n for n in result.notes), result.notes
