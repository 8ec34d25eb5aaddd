"""The labelled pictures of ``sensorkit render preview`` (issue 13) against geometry.

Each expected number comes from the test robots' own values (``tests/render_robots/``)
with plain trigonometry: the wall the depth camera sees, the beam that first meets the
ground, the mast that hides beams, the IMU mount's rpy, the stereo eyes' poses. The
labels are read back from index.html's inline SVG, the pictures from the PNGs.
"""

from __future__ import annotations

import base64
import json
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from sensorkit.render import render_preview
from sensorkit.render.pictures import (
    GROUND_HIT,
    depth_colour_range,
    draw_side,
    occluded_sectors,
    side_figure,
)
from sensorkit.render.png import encode_png, read_png
from sensorkit.render.raster import colourise_depth
from sensorkit.render.svg import nice_step

HERE = Path(__file__).parent / "render_robots"
WALL_SCENE = HERE / "wall_scene.urdf"
SVG = "{http://www.w3.org/2000/svg}"


def render(
    factory: pytest.TempPathFactory, robot: str, *, scene: bool = False, only: tuple[str, ...] = ()
) -> Path:
    out = factory.mktemp(robot)
    render_preview(HERE / f"{robot}.urdf", out, scene=WALL_SCENE if scene else None, sensors=only)
    return out


@pytest.fixture(scope="module")
def wall(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return render(tmp_path_factory, "wall_bot", scene=True)


@pytest.fixture(scope="module")
def imu(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return render(tmp_path_factory, "imu_bot", scene=True)


def summary(out: Path) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((out / "summary.json").read_text())
    return data


def pictures(out: Path, name: str) -> dict[str, Any]:
    s = next(s for s in summary(out)["sensors"] if s["name"] == name)
    found: dict[str, Any] = s["pictures"]
    return found


def figure(out: Path, key: str, sensor: str | None = None) -> ET.Element:
    """The ``<svg>`` of the figure ``key``, within the sensor's part of index.html."""
    page = (out / "index.html").read_text()
    if sensor is not None:
        page = page[page.index(f'<h3 id="{sensor}">') :]
        page = page[: page.find("<h3 ", 5) if "<h3 " in page[5:] else len(page)]
    start = page.index(f'data-figure="{key}">')
    svg = page[page.index("<svg", start) : page.index("</svg>", start) + len("</svg>")]
    return ET.fromstring(svg)


def texts(svg: ET.Element, cls: str) -> list[ET.Element]:
    return [t for t in svg.iter(f"{SVG}text") if cls in (t.get("class") or "").split()]


def metres(label: str | None) -> float:
    assert label is not None
    m = re.fullmatch(r"(-?[0-9.]+) m", label)
    assert m, label
    return float(m.group(1))


# ---- depth -------------------------------------------------------------------------------------
def test_depth_colour_bar_spans_the_scene_in_metres(wall: Path) -> None:
    facts = pictures(wall, "depth_cam")["depth"]
    lo, hi = facts["colour_min_m"], facts["colour_max_m"]
    depth = np.load(wall / "depth_cam" / "depth.npy")
    valid = depth[np.isfinite(depth)]
    p2, p98 = np.percentile(valid, [2, 98])
    # the camera (0.5 m up, 0.25 m ahead of the base) sees the wall (x = 3) at 2.75 m and
    # the floor nearer: the colours span what is in view, not near..far (0.05..20 m)
    assert lo <= p2 and hi >= p98 and lo <= 2.75 <= hi
    assert lo >= 0.05 and hi <= 20.0
    assert hi - lo <= 1.3 * (p98 - p2)
    ticks = texts(figure(wall, "depth", "depth_cam"), "tick")
    ends = {t.get("data-end"): t for t in ticks if t.get("data-end")}
    assert (
        metres(ends["min"].text) == pytest.approx(lo)
        and float(ends["min"].get("data-value", "")) == lo
    )
    assert (
        metres(ends["max"].text) == pytest.approx(hi)
        and float(ends["max"].get("data-value", "")) == hi
    )
    values = [metres(t.text) for t in ticks]
    assert values == sorted(values) and all(lo <= v <= hi for v in values)
    # the wall's pixels decode (through the colour map over lo..hi) to 2.75 m
    png = read_png((wall / "depth_cam" / "depth.png").read_bytes()).astype(np.int64)
    lut_depths = np.linspace(lo, hi, 2001)
    lut = colourise_depth(lut_depths[None, :], lo=lo, hi=hi)[0].astype(np.int64)
    pixel = png[60, 80]
    decoded = lut_depths[int(np.argmin(np.abs(lut - pixel).sum(axis=1)))]
    assert decoded == pytest.approx(2.75, abs=(hi - lo) / 40)


def test_the_depth_caption_states_the_percentiles_it_used(wall: Path) -> None:
    """The caption's 2nd and 98th percentiles are those of depth.npy's valid depths (numpy
    computes them here), and lie within the colour range they were widened to."""
    facts = pictures(wall, "depth_cam")["depth"]
    depth = np.load(wall / "depth_cam" / "depth.npy").astype(np.float64)
    p2, p98 = np.percentile(depth[np.isfinite(depth)], [2, 98])
    assert facts["p2_m"] == pytest.approx(p2, abs=1e-4)
    assert facts["p98_m"] == pytest.approx(p98, abs=1e-4)
    assert facts["colour_min_m"] <= facts["p2_m"] <= facts["p98_m"] <= facts["colour_max_m"]
    page = (wall / "index.html").read_text()
    start = page.index('data-figure="depth">')
    caption = page[page.index("<figcaption>", start) : page.index("</figcaption>", start)]
    said = f"2nd and 98th percentiles, {p2:.3f}\u00a0m and {p98:.3f}\u00a0m"  # units kept on
    assert said in caption, caption


def test_depth_colour_range_stays_within_near_and_far() -> None:
    rng = np.random.default_rng(4)
    depth = rng.uniform(0.3, 9.0, size=(40, 50))
    depth[:2] = np.inf
    depth[-1] = -np.inf
    lo, hi = depth_colour_range(depth, 0.5, 4.0)
    assert (lo, hi) == (0.5, 4.0)  # the percentiles reach past both clips
    lo, hi = depth_colour_range(np.full((4, 4), 1.234), 0.1, 10.0)
    assert (lo, hi) == pytest.approx((1.2, 1.4))  # one depth: one round step around it
    assert depth_colour_range(np.full((3, 3), np.inf), 0.1, 10.0) == (0.1, 10.0)
    # sky: the renderer leaves it on the far clip plane, which is no surface to scale for
    scene = np.concatenate([np.full(300, 9.99995), np.linspace(0.5, 2.9, 700)])
    lo, hi = depth_colour_range(scene, 0.1, 10.0)
    assert lo <= 0.6 and 2.8 <= hi <= 3.0
    assert [nice_step(s) for s in (1.0, 7.0, 0.33)] == [0.2, 2.0, 0.1]


# ---- lidar from above --------------------------------------------------------------------------
def test_ring_labels_sit_on_their_rings_at_their_radii(wall: Path) -> None:
    facts = pictures(wall, "laser")["scan"]
    # the furthest return is a wall corner: (2.9, 3) m from the laser, plus 10 %
    assert facts["half_width_m"] == pytest.approx(math.hypot(2.9, 3.0) * 1.1, abs=0.05)
    assert facts["ring_step_m"] == 1.0 and facts["rings_m"] == [1.0, 2.0, 3.0, 4.0]
    svg = figure(wall, "scan", "laser")
    image = next(svg.iter(f"{SVG}image"))
    display = float(image.get("width", ""))
    png = read_png((wall / "laser" / "scan.png").read_bytes()).astype(np.int64)
    k = display / png.shape[1]
    c = png.shape[1] / 2.0
    scale = facts["pixels_per_m"]
    labels = texts(svg, "ring")
    assert [metres(t.text) for t in labels] == [1.0, 2.0, 3.0, 4.0]
    for t in labels:
        radius = metres(t.text)
        assert float(t.get("data-radius", "")) == radius
        x, y = float(t.get("x", "")) - 2, float(t.get("y", "")) + 2  # the label's corner
        assert math.hypot(x / k - c, y / k - c) == pytest.approx(radius * scale, abs=0.5)
        # the ring itself: grey pixels at that radius, down-left of the sensor (no returns)
        d = radius * scale / math.sqrt(2)
        near = png[int(c + d) - 2 : int(c + d) + 3, int(c - d) - 2 : int(c - d) + 3]
        assert (np.abs(near - 215).sum(axis=2) == 0).any()
    # the return straight ahead: the wall, 2.9 m in front of the laser
    column = png[:, int(c)]
    blue = np.flatnonzero(np.abs(column - [31, 119, 180]).sum(axis=1) == 0)
    assert (c - blue.mean()) / scale == pytest.approx(2.9, abs=2 / scale)


def _labels_over_returns(svg: ET.Element, view: Any, returns: np.ndarray, k: float) -> list[str]:
    """The ring labels whose box (10 px text, 6.5 px a character) covers a return."""
    px = view.px(returns) * k
    covered = []
    for t in texts(svg, "ring"):
        x, y = float(t.get("x", "")), float(t.get("y", ""))
        w = len(t.text or "") * 6.5
        under = (px[:, 0] >= x - 1) & (px[:, 0] <= x + w + 1) & (px[:, 1] >= y - 12)
        if (under & (px[:, 1] <= y + 3)).any():
            covered.append(t.text or "")
    return covered


def test_ring_labels_do_not_cover_the_returns() -> None:
    """A wall crossing the forward-right diagonal, where the 2 m label would sit: the
    label moves along its ring to where no return lies under it (and stays on the ring)."""
    from sensorkit.render.overview import scan_view
    from sensorkit.render.pictures import scan_figure

    t = np.linspace(-3.0, 3.0, 600)
    wall = np.stack([np.full_like(t, 1.6), t], axis=1)  # 1.6 m ahead: crosses ring 2 at 37 deg
    diagonal = np.stack([np.linspace(0.3, 3.0, 300), -np.linspace(0.3, 3.0, 300)], axis=1)
    returns = np.vstack([wall, diagonal])  # and a row of returns along the diagonal itself
    points = np.hstack([returns, np.zeros((len(returns), 1))])
    view = scan_view(points, 10.0)
    png = encode_png(np.full((view.size, view.size, 3), 250, dtype=np.uint8))
    k = 480 / view.size
    bare = ET.fromstring(scan_figure(png, view, [], 1, 0).svg)
    assert _labels_over_returns(bare, view, returns, k)  # where they were: on the returns
    svg = ET.fromstring(scan_figure(png, view, [], 1, 0, returns=returns).svg)
    labels = texts(svg, "ring")
    assert len(labels) >= 3 and _labels_over_returns(svg, view, returns, k) == []
    c = view.centre * k
    for label in labels:  # each still on its own ring
        x, y = float(label.get("x", "")) - 2, float(label.get("y", "")) + 2
        assert math.hypot(x - c, y - c) == pytest.approx(
            metres(label.text) * view.scale * k, abs=0.05
        )


def test_the_pixels_a_label_avoids_are_those_within_two_of_a_return() -> None:
    """_return_pixels marks every pixel within two (rows and columns) of a return's,
    returns off the picture included when their neighbours are on it: the same as
    marking the 25 neighbours of each return one by one."""
    from sensorkit.render.overview import ScanView
    from sensorkit.render.pictures import _return_pixels

    rng = np.random.default_rng(7)
    view, display = ScanView(480, 5.0, 1.0), 60
    k = display / view.size
    returns = rng.uniform(-5.4, 5.4, (400, 2))  # some a pixel or two off the picture
    returns[::37] = np.nan
    want = np.zeros((display + 1, display + 1), dtype=bool)
    for col, row in np.rint(view.px(returns[np.isfinite(returns[:, 0])]) * k).astype(int):
        for dc in range(-2, 3):
            for dr in range(-2, 3):
                if 0 <= col + dc <= display and 0 <= row + dr <= display:
                    want[row + dr, col + dc] = True
    assert want.any() and not want.all()
    assert np.array_equal(_return_pixels(view, returns, k, display), want)


def test_beams_hidden_by_the_mast_are_a_shaded_sector(
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    out = render(tmp_path_factory, "occluded_bot", only=("mast_laser",))
    facts = pictures(out, "mast_laser")["scan"]
    # laser at x = -0.1, z = 0.6; the mast's near face at x = 0.25, |y| <= 0.05
    edge = math.degrees(math.atan2(0.05, 0.35))
    step = 360 / 359
    [(a, b)] = facts["self_occluded_deg"]
    assert abs(a + edge) <= step and abs(b - edge) <= step
    legend = texts(figure(out, "scan", "mast_laser"), "sectors")
    assert len(legend) == 1 and f"{a:+.0f}..{b:+.0f} deg" in (legend[0].text or "")
    png = read_png((out / "mast_laser" / "scan.png").read_bytes()).astype(np.int64)
    c = png.shape[1] // 2  # the sector is 16 degrees wide: 8 px across, 30 px ahead
    assert (png[c - 60 : c - 30, c + 2] == [255, 222, 222]).all(axis=1).sum() > 20  # ahead
    assert not (png[c + 30 : c + 60, c + 2] == [255, 222, 222]).all(axis=1).any()  # behind


def test_occluded_sectors_join_across_the_back_of_a_full_circle() -> None:
    az = np.linspace(-math.pi, math.pi, 9)  # 45 degree steps, first and last the same way
    blocked = np.array([1, 0, 0, 0, 1, 0, 0, 0, 1], dtype=bool)
    [ahead, behind] = occluded_sectors(az, blocked, full_circle=True)
    assert ahead == pytest.approx((-math.pi / 8, math.pi / 8))
    assert behind == pytest.approx((math.pi - math.pi / 8, math.pi + math.pi / 8))
    assert len(occluded_sectors(az, blocked, full_circle=False)) == 3
    assert occluded_sectors(az, np.zeros(9, dtype=bool), full_circle=True) == []


# ---- lidar from the side -----------------------------------------------------------------------
def _ground_pixels(png_path: Path, view: dict[str, float]) -> tuple[np.ndarray, np.ndarray]:
    png = read_png(png_path.read_bytes()).astype(np.int64)
    rows, cols = np.nonzero(np.abs(png - GROUND_HIT).sum(axis=2) == 0)
    d = (cols - view["x0"]) / view["pixels_per_m_horizontal"]
    z = (view["z0"] - rows) / view["pixels_per_m_vertical"]
    return d, z


@pytest.mark.parametrize(
    ("robot", "sensor", "height", "down"),
    [
        ("gz_bot", "velo", 0.8, math.radians(20)),  # lowest of 16 rows at -20 deg
        ("imu_bot", "tilt_laser", 0.5, 0.35),  # a 2D lidar pitched 0.35 rad down
    ],
)
def test_side_view_puts_ground_hits_on_the_ground_below_the_sensor(
    tmp_path_factory: pytest.TempPathFactory, robot: str, sensor: str, height: float, down: float
) -> None:
    out = render(tmp_path_factory, robot, scene=True, only=(sensor,))
    facts = pictures(out, sensor)["side"]
    assert facts["sensor_height_m"] == pytest.approx(height)
    ahead = height / math.tan(down)  # where the steepest beam ahead meets the floor
    assert facts["nearest_ground_ahead_m"] == pytest.approx(ahead, abs=0.01)
    assert facts["ground_hits"] > 100
    d, z = _ground_pixels(out / sensor / "side.png", facts["view"])
    assert len(d) > 50
    pixel = 1.6 / facts["view"]["pixels_per_m_vertical"]
    assert np.abs(z).max() <= pixel  # on the ground line, a sensor height below the sensor
    assert d[d > 0].min() == pytest.approx(
        ahead, abs=1.6 / facts["view"]["pixels_per_m_horizontal"]
    )
    labels = texts(figure(out, "side", sensor), "ground")
    assert any(
        metres((t.text or "").removeprefix("ground from ")) == pytest.approx(ahead, abs=0.001)
        for t in labels
    )
    sensor_label = texts(figure(out, "side", sensor), "sensor")
    assert sensor_label[0].text == f"sensor {height:g} m above the ground"


def test_side_view_of_a_scan_with_no_returns_is_the_ground_and_the_sensor() -> None:
    points = np.full((64 * 3, 3), np.nan)
    rows = np.repeat(np.arange(3), 64)
    none = np.zeros(len(points), dtype=bool)
    image, view, facts = draw_side(
        points, np.array([0.0, 0.0, 1.5]), np.array([1.0, 0, 0]), rows, 3, none, none
    )
    assert image.shape == (view.height, view.width, 3) and facts["ground_hits"] == 0
    assert facts["nearest_ground_ahead_m"] is None and view.z_lo < 0 and view.z_hi > 1.5
    svg = ET.fromstring(side_figure(encode_png(image), view, facts).svg)
    assert texts(svg, "sensor")[0].text == "sensor 1.5 m above the ground"
    assert not texts(svg, "ground")


def test_a_level_2d_lidar_has_no_side_view(wall: Path) -> None:
    assert "side" not in pictures(wall, "laser") and not (wall / "laser" / "side.png").exists()


# ---- IMU ---------------------------------------------------------------------------------------
def _rpy(r: float, p: float, y: float) -> np.ndarray:
    cr, sr, cp, sp, cy, sy = (f(a) for a in (r, p, y) for f in (math.cos, math.sin))
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def _screen(v: np.ndarray) -> np.ndarray:
    """A world vector on screen (right, down) seen from yaw 45, pitch 30 deg, as RViz's orbit."""
    yaw, pitch = math.radians(45), math.radians(30)
    eye = np.array(
        [math.cos(yaw) * math.cos(pitch), math.sin(yaw) * math.cos(pitch), math.sin(pitch)]
    )
    right = np.array([-math.sin(yaw), math.cos(yaw), 0.0])
    up = np.cross(right, -eye)
    return np.array([v @ right, -(v @ up)])


def _direction(line: ET.Element) -> np.ndarray:
    x1, y1, x2, y2 = (float(line.get(k, "")) for k in ("x1", "y1", "x2", "y2"))
    return np.array([x2 - x1, y2 - y1])


def test_imu_triad_points_along_the_imu_axes_and_shows_the_stamped_frame(imu: Path) -> None:
    R = _rpy(0.3, -0.2, 0.9)  # imu_joint's rpy; base_link is the world
    svg = figure(imu, "imu", "imu")
    lines = {(ln.get("class") or ""): ln for ln in svg.iter(f"{SVG}line")}
    lengths = []
    for i, axis in enumerate("xyz"):
        drawn = _direction(lines[f"axis axis-{axis}"])
        expected = _screen(R[:, i])
        assert np.allclose(
            drawn / np.linalg.norm(drawn), expected / np.linalg.norm(expected), atol=1e-3
        )
        lengths.append(np.linalg.norm(drawn) / np.linalg.norm(expected))
        # data stamped base_link: the dashed axes are the world's
        stamped = _direction(lines[f"stamped stamped-{axis}"])
        world = _screen(np.eye(3)[i])
        assert np.allclose(
            stamped / np.linalg.norm(stamped), world / np.linalg.norm(world), atol=1e-3
        )
    assert np.ptp(lengths) < 1e-3 * min(lengths)  # one scale: foreshortening is the projection's
    check = texts(svg, "frame-check")
    assert check[0].text == "frame check: warn"
    data = next(s for s in summary(imu)["sensors"] if s["name"] == "imu")
    # its checks warn and validate finds an error (SK504): one rule, the worse of the two
    assert data["status"] == "fail" and not data["skipped"]
    assert [f["rule"] for f in data["findings"]] == ["SK504"]
    assert {c["name"]: c["status"] for c in data["checks"]} == {
        "render_pose": "ok",
        "published_frame": "warn",
    }


def test_an_unrendered_sensor_says_so_once(imu: Path) -> None:
    page = (imu / "index.html").read_text()
    assert "Not rendered: only cameras and lidars are" in page
    assert "not rendered: not rendered" not in page.lower()
    # the overview's table gives the IMU the status of its checks and findings (a warned
    # check and an SK504 error: fail), not "skipped"
    assert "<a href='#imu'>imu</a></td><td>imu</td><td><span class=\"fail\">" in page


# ---- the robot close up ------------------------------------------------------------------------
def test_close_up_frames_the_robot_and_names_every_mount(
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    out = render(tmp_path_factory, "mounts_bot")
    facts = summary(out)["pictures"]["closeup"]
    lo, hi = (np.array(v) for v in facts["bbox_m"])
    # the sensors' links, from mounts_bot's joints (pan at zero): all inside, and the box
    # is the robot's (0.4 x 0.4 x 1 m), not the room's
    links = {
        "pitch_cam": [0.2, 0.0, 1.0],
        "yaw_cam": [0.1, 0.0, 0.5],
        "body_cam": [-0.2, 0.0, 0.6],
    }
    for xyz in links.values():
        assert (lo - 1e-9 <= xyz).all() and (np.array(xyz) <= hi + 1e-9).all()
    assert np.allclose(lo, [-0.2, -0.2, 0.0], atol=0.02) and np.allclose(
        hi, [0.2, 0.2, 1.0], atol=0.02
    )
    svg = figure(out, "closeup")
    vlo, vhi = (np.array(v) for v in facts["view_bbox_m"])
    s = facts["pixels_per_m"]
    assert s > 150  # the overview has about 60 px a metre
    side_x0 = next(
        float(t.get("x", ""))
        for t in svg.iter(f"{SVG}text")
        if (t.text or "").startswith("from the right")
    )
    for name, xyz in links.items():
        x, y, z = xyz
        expected = {
            "top": ((x - vlo[0]) * s, 20 + (vhi[1] - y) * s),
            "side": (side_x0 + (x - vlo[0]) * s, 20 + (vhi[2] - z) * s),
        }
        for view, (px, py) in expected.items():
            [label] = [
                t
                for t in texts(svg, "mount")
                if t.get("data-sensor") == name and t.get("data-view") == view
            ]
            assert label.text == name
            [leader] = [
                ln
                for ln in svg.iter(f"{SVG}line")
                if ln.get("data-sensor") == name and ln.get("data-view") == view
            ]
            assert float(leader.get("x1", "")) == pytest.approx(px, abs=0.01)
            assert float(leader.get("y1", "")) == pytest.approx(py, abs=0.01)


# ---- stereo ------------------------------------------------------------------------------------
def test_stereo_pair_side_by_side_with_its_baseline(
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    out = render(tmp_path_factory, "stereo_bot")
    baseline = 0.06 - (-0.06)  # the two <camera><pose> y offsets
    facts = summary(out)["pictures"]["stereo:stereo"]
    assert facts["baseline_m"] == pytest.approx(baseline, abs=1e-12)
    assert facts["left"] == "stereo/left" and facts["right"] == "stereo/right"
    svg = figure(out, "stereo:stereo")
    [label] = texts(svg, "baseline")
    assert float(label.get("data-baseline", "")) == pytest.approx(baseline, abs=1e-12)
    assert label.text == "baseline 0.12 m (120.0 mm)"
    left, right = svg.iter(f"{SVG}image")
    assert float(left.get("x", "")) < float(right.get("x", ""))
    for image, eye in ((left, "left"), (right, "right")):
        data = base64.b64decode(image.get("href", "").split(",", 1)[1])
        assert data == (out / "stereo" / eye / "rgb.png").read_bytes()


def test_values_read_in_mm_and_degrees_with_fixed_decimals() -> None:
    """No ``2.34773e-06 m``: lengths in mm, angles in degrees, a fixed number of decimals,
    and a non-breaking space between number and unit so the unit never wraps alone."""
    from sensorkit.render.svg import quantity, vector

    nbsp = "\u00a0"
    assert quantity(2.34773e-06, "m") == f"0.0{nbsp}mm"
    assert quantity(0.25, "m") == f"250.0{nbsp}mm"
    assert quantity(-1e-9, "m") == f"0.0{nbsp}mm"  # never "-0.0"
    assert quantity(math.radians(11.5), "rad") == "11.50\u00b0"
    assert quantity(0.123456, "px") == f"0.12{nbsp}px"
    assert quantity(0.5, "deg") == "0.50\u00b0"
    assert quantity(0.00436, "rad", 3) == "0.250\u00b0"
    assert vector([0.25, 0, 0.1], "m") == f"(250.0, 0.0, 100.0){nbsp}mm"
    assert vector([0, math.pi / 2, 0], "rad") == "(0.00, 90.00, 0.00)\u00b0"


def _text_boxes(svg: ET.Element) -> list[tuple[str, tuple[float, float, float, float]]]:
    from sensorkit.render.svg import label_box

    out = []
    for t in svg.iter(f"{SVG}text"):
        size = float(t.get("font-size", "11"))
        anchor = t.get("text-anchor", "start")
        bold = t.get("font-weight") == "bold"
        box = label_box(
            float(t.get("x", "")), float(t.get("y", "")), t.text or "", size, anchor, bold=bold
        )
        out.append((t.text or "", box))
    return out


def _overlapping(svg: ET.Element) -> list[tuple[str, str]]:
    boxes = _text_boxes(svg)
    return [
        (a, b)
        for i, (a, p) in enumerate(boxes)
        for b, q in boxes[i + 1 :]
        if min(p[2], q[2]) > max(p[0], q[0]) and min(p[3], q[3]) > max(p[1], q[1])
    ]


@pytest.mark.parametrize("stamped", [None, "same", "turned"])
def test_imu_axis_labels_never_overlap(stamped: str | None) -> None:
    """The IMU's x, y, z, the world's and the stamped frame's names: where axes point the
    same way (an IMU aligned with the world, a stamped frame equal to its own) the labels
    move apart instead of printing over one another."""
    from sensorkit.render.mount_pictures import imu_figure

    R = np.eye(3)
    turned = _rpy(0.0, 0.0, 0.1)
    R_stamped = None if stamped is None else R if stamped == "same" else turned
    fig = imu_figure(R, R_stamped, "base_link", "warn", "turned")
    svg = ET.fromstring(fig.svg)
    names = [text for text, _ in _text_boxes(svg)]
    assert {"x", "y", "z", "world x", "world y", "world z"} <= set(names)
    assert _overlapping(svg) == []
