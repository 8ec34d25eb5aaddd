"""The preview's parts: PNG files, the TinyRenderer projection, exact shapes, kinematics at
given joints, the URDF handed to pybullet, and keeping pybullet quiet."""

from __future__ import annotations

import io
import math
import os
import subprocess
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from sensorkit.base.errors import UsageError
from sensorkit.loading import PackageResolver
from sensorkit.model import load_robot
from sensorkit.model.sensors import LidarSpec
from sensorkit.model.transforms import transform
from sensorkit.render.camera import RenderCamera, depth_from_buffer
from sensorkit.render.lidar import (
    SAMPLE_BEAMS,
    LidarScan,
    _first_hits,
    cast,
    check_sample,
    lidar_beams,
    range_check,
)
from sensorkit.render.png import encode_png, read_png
from sensorkit.render.poses import joint_positions, link_poses
from sensorkit.render.raster import Canvas
from sensorkit.render.result import SensorPreview
from sensorkit.render.scene import GROUND, Scene, Shape, default_scene
from sensorkit.render.urdf_out import prepare_urdf

HERE = Path(__file__).parent / "render_robots"


# ---- PNG -------------------------------------------------------------------------------
@settings(max_examples=30, deadline=None)
@given(
    st.integers(1, 17),
    st.integers(1, 17),
    st.sampled_from([1, 3, 4]),
    st.integers(0, 2**32 - 1),
)
def test_png_round_trip(height: int, width: int, channels: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    image = rng.integers(0, 256, (height, width, channels), dtype=np.uint8)
    data = encode_png(image[:, :, 0] if channels == 1 else image)
    assert data.startswith(b"\x89PNG\r\n\x1a\n")
    assert np.array_equal(read_png(data), image)


def test_png_of_a_strided_view_is_its_pixels() -> None:
    """A view that is not one block of memory (every other column, three of four
    channels; the preview hands in such slices) is written pixel for pixel."""
    image = np.random.default_rng(3).integers(0, 256, (7, 10, 4), dtype=np.uint8)
    view = image[:, ::2, :3]
    assert np.array_equal(read_png(encode_png(view)), view)


def test_png_chunks_carry_valid_crcs() -> None:
    data = encode_png(np.zeros((2, 3, 3), dtype=np.uint8))
    pos = 8
    while pos < len(data):
        length = int.from_bytes(data[pos : pos + 4], "big")
        body = data[pos + 4 : pos + 8 + length]
        assert int.from_bytes(data[pos + 8 + length : pos + 12 + length], "big") == zlib.crc32(body)
        pos += 12 + length


def _hand_built_png(rows: list[bytes], width: int, height: int, colour: int) -> bytes:
    """A PNG assembled from zlib and struct, each row led by its own filter byte."""
    import struct

    def chunk(kind: bytes, data: bytes) -> bytes:
        return (
            struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
        )

    header = struct.pack(">IIBBBBB", width, height, 8, colour, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(b"".join(rows)))
        + chunk(b"IEND", b"")
    )


def test_read_png_decodes_every_filter_of_a_file_it_did_not_write() -> None:
    """A 3 x 2 RGB file built by hand: row 0 with Sub (1), row 1 with Up (2); a grey
    2 x 2 one with Average (3) and Paeth (4). The pixels are worked out here."""
    sub = bytes([1, 10, 20, 30, 5, 5, 5, 1, 2, 3])  # 10,20,30 then +5 then +1,2,3
    up = bytes([2, 1, 1, 1, 0, 0, 0, 250, 0, 0])  # the row above, plus these
    rgb = read_png(_hand_built_png([sub, up], 3, 2, 2))
    assert rgb.tolist() == [
        [[10, 20, 30], [15, 25, 35], [16, 27, 38]],
        [[11, 21, 31], [15, 25, 35], [10, 27, 38]],  # 16 + 250 wraps to 10
    ]
    avg = bytes([3, 100, 10])  # left 100, then 10 + (100 + 0) // 2
    paeth = bytes([4, 1, 1])  # above 100 -> 101; then Paeth(101, 60, 100) = 60 -> 61
    grey = read_png(_hand_built_png([avg, paeth], 2, 2, 0))
    assert grey[:, :, 0].tolist() == [[100, 60], [101, 61]]


def test_png_refuses_what_it_cannot_write() -> None:
    with pytest.raises(ValueError, match="uint8"):
        encode_png(np.zeros((2, 2), dtype=np.float32))
    with pytest.raises(ValueError, match="H, W"):
        encode_png(np.zeros((2, 2, 2), dtype=np.uint8))


# ---- drawing -------------------------------------------------------------------------------
def _dots_one_by_one(
    canvas: Canvas, pts: np.ndarray, colours: np.ndarray | tuple[int, int, int], radius: float
) -> None:
    """Canvas dots as the first version drew them: offset by offset, dot by dot (a
    square of them for dots of their own colour, a disc for dots of one colour)."""
    r = max(0, math.ceil(radius - 0.5))
    offsets = [
        (dx, dy)
        for dx in range(-r, r + 1)
        for dy in range(-r, r + 1)
        if isinstance(colours, np.ndarray) or dx * dx + dy * dy <= radius * radius + 0.25
    ]
    for dx, dy in offsets:
        for k, (x, y) in enumerate(pts):
            if not np.isfinite([x, y]).all():
                continue
            px, py = int(np.rint(x)) + dx, int(np.rint(y)) + dy
            if 0 <= px < canvas.width and 0 <= py < canvas.height:
                canvas.image[py, px] = colours[k] if isinstance(colours, np.ndarray) else colours


@pytest.mark.parametrize("per_dot", [True, False])
@pytest.mark.parametrize("radius", [0.5, 1.0, 2.0])
def test_many_dots_draw_the_picture_few_dots_draw(per_dot: bool, radius: float) -> None:
    """Past a few thousand dots the canvas paints by pixel; the picture must not change,
    down to which of two dots on one pixel shows (the later)."""
    rng = np.random.default_rng(int(radius * 10) + per_dot)
    pts = rng.uniform(-5, 45, (6000, 2)).round(1)  # many share a pixel, some off the canvas
    pts[::97] = np.nan
    colours = rng.integers(0, 256, (len(pts), 3)).astype(np.uint8)
    fast, slow = Canvas(40, 30, (9, 9, 9)), Canvas(40, 30, (9, 9, 9))
    if per_dot:
        fast.points(pts, colours, radius=radius)
        _dots_one_by_one(slow, pts, colours, radius)
    else:
        fast.points(pts, (200, 10, 50), radius=radius)
        _dots_one_by_one(slow, pts, (200, 10, 50), radius)
    np.testing.assert_array_equal(fast.image, slow.image)


# ---- projection --------------------------------------------------------------------------
def _camera(**kw: float) -> RenderCamera:
    base = {
        "width": 160,
        "height": 120,
        "fx": 100.0,
        "fy": 90.0,
        "cx": 79.5,
        "cy": 59.5,
        "skew": 0.0,
        "near": 0.1,
        "far": 50.0,
    }
    base.update(kw)
    return RenderCamera(T_world_render=np.eye(4), **base)  # type: ignore[arg-type]


@pytest.mark.parametrize("kw", [{}, {"cx": 70.0, "cy": 52.0}, {"skew": 3.0}])
def test_projection_sends_each_pixel_ray_to_the_point_tinyrenderer_samples(
    kw: dict[str, float],
) -> None:
    """TinyRenderer fills pixel (i, r) from NDC (2i/W - 1, 1 - 2(r+1)/H)."""
    cam = _camera(**kw)
    P = np.array(cam.projection_matrix()).reshape(4, 4).T  # column-major
    origin, dirs, cos = cam.pixel_rays()
    assert np.allclose(origin, 0.0)
    for i, r in ((0, 0), (159, 119), (80, 60), (17, 101)):
        d = dirs[r, i]
        # render pose = identity: eye x = -world y (right), eye y = world z, eye z = -world x
        eye = np.array([-d[1], d[2], -d[0], 1.0])
        clip = P @ eye
        ndc = clip[:3] / clip[3]
        assert ndc[0] == pytest.approx(2 * i / 160 - 1, abs=1e-9)
        assert ndc[1] == pytest.approx(1 - 2 * (r + 1) / 120, abs=1e-9)
        assert cos[r, i] == pytest.approx(d[0])


def test_view_matrix_maps_the_render_pose_to_the_eye_frame() -> None:
    T = transform((1.0, 2.0, 0.5), (0.0, 0.3, 1.0))
    cam = _camera()
    cam.T_world_render = T
    V = np.array(cam.view_matrix()).reshape(4, 4).T
    ahead = T @ np.array([2.0, 0.0, 0.0, 1.0])  # 2 m along the render x axis
    left = T @ np.array([0.0, 1.0, 0.0, 1.0])
    up = T @ np.array([0.0, 0.0, 1.0, 1.0])
    assert V @ ahead == pytest.approx([0, 0, -2, 1])
    assert V @ left == pytest.approx([-1, 0, 0, 1])
    assert V @ up == pytest.approx([0, 1, 0, 1])


def test_depth_buffer_to_metres() -> None:
    near, far = 0.1, 100.0
    z = np.array([0.1, 1.0, 3.0, 99.0])
    d = (1 / near - 1 / z) / (1 / near - 1 / far)  # OpenGL depth of those distances
    out = depth_from_buffer(np.append(d, 1.0).astype(np.float32), near, far)
    assert out[:4] == pytest.approx(z, rel=1e-4)
    assert np.isposinf(out[4])


def _plate_centroid(
    projection: list[float], width: int = 160, height: int = 120
) -> tuple[float, float]:
    """Centroid of a square plate centred on the optical axis, 5 m ahead."""
    from sensorkit.render.sim import World

    with World() as world:
        p = world.p
        vis = world._call("createVisualShape", p.GEOM_BOX, halfExtents=[0.01, 0.6, 0.6])
        body = world._call("createMultiBody", 0, -1, vis, [5.0, 0.0, 0.0])
        cam = _camera()
        image = world.render(width, height, cam.view_matrix(), projection)
    ys, xs = np.nonzero(image.body == body)
    return float(xs.mean()), float(ys.mean())


def test_tinyrenderer_puts_its_own_axis_half_a_pixel_off_and_ours_on_the_pixel_grid_centre() -> (
    None
):
    """pybullet's own symmetric projection lands the axis on (W/2, H/2 - 1); the preview's
    lands it on ((W-1)/2, (H-1)/2), where Gazebo's rasteriser puts it."""
    from sensorkit.render.sim import _pybullet

    p = _pybullet()
    vfov = math.degrees(2 * math.atan(60 / 90.0))
    own = p.computeProjectionMatrixFOV(vfov, 160 / 120, 0.1, 50.0)
    assert _plate_centroid(list(own)) == pytest.approx((80.0, 59.0), abs=0.05)
    assert _plate_centroid(_camera(fx=90.0, fy=90.0).projection_matrix()) == pytest.approx(
        (79.5, 59.5), abs=0.05
    )


# ---- shapes --------------------------------------------------------------------------------
def test_shape_intersections() -> None:
    o = np.array([[0.0, 0.0, 1.0]] * 4)
    d = np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])
    box = Shape("b", "box", transform((3.0, 0.0, 1.0), (0, 0, math.pi / 4)), (0.5, 0.5, 0.5))
    t, n = box.hit(o, d)
    assert t[0] == pytest.approx(3.0 - 0.5 * math.sqrt(2)) and np.isnan(t[1:]).all()
    assert n[0] == pytest.approx([-math.sqrt(0.5), -math.sqrt(0.5), 0.0]) or n[0] == pytest.approx(
        [-math.sqrt(0.5), math.sqrt(0.5), 0.0]
    )
    sphere = Shape("s", "sphere", transform((-2.0, 0.0, 1.0)), (0.5,))
    assert sphere.intersect(o, d)[1] == pytest.approx(1.5) and np.isnan(sphere.intersect(o, d)[0])
    ground = Shape("g", GROUND, np.eye(4))
    assert ground.intersect(o, d)[2] == pytest.approx(1.0) and np.isnan(ground.intersect(o, d)[3])
    cyl = Shape("c", "cylinder", transform((0.0, 0.0, 3.0)), (0.2, 0.5))
    assert cyl.intersect(o, d)[3] == pytest.approx(1.5)  # bottom cap at z = 2.5
    side = cyl.hit(np.array([[-2.0, 0.0, 3.0]]), np.array([[1.0, 0.0, 0.0]]))
    assert side[0][0] == pytest.approx(1.8) and side[1][0] == pytest.approx([-1, 0, 0])
    inside = np.array([[3.0, 0.0, 1.0]])
    assert np.isnan(box.intersect(inside, np.array([[1.0, 0.0, 0.0]])))[0]
    # a ray parallel to a face, beside the box, never enters it (nor one along an edge's
    # slab but off to the side)
    level = Shape("l", "box", transform((3.0, 0.0, 0.4)), (0.3, 0.3, 0.4))
    over = level.intersect(
        np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.4]]), np.array([[1.0, 0, 0]] * 2)
    )
    assert np.isnan(over).all()
    assert level.intersect(np.array([[0.0, 0.0, 0.5]]), np.array([[1.0, 0, 0]]))[0] == 2.7


def test_default_scene_keeps_the_axes_clear_and_grows_with_the_robot() -> None:
    scene = default_scene(0.4)
    walls = [s for s in scene.shapes if s.role == "wall"]
    assert len(walls) == 4 and len(scene.markers) == 72
    faces = sorted(abs(s.centre[0]) - s.size[0] for s in walls if abs(s.centre[0]) > 1)
    assert faces == pytest.approx([3.0, 3.0])
    axis = np.array([[0.0, 0.0, h] for h in (0.3, 0.5, 1.0, 1.5)])
    for direction in ([1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]):
        d = np.tile(direction, (len(axis), 1)).astype(float)
        firsts = np.fmin.reduce([s.intersect(axis, d) for s in scene.shapes if s.kind != GROUND])
        assert firsts == pytest.approx([3.0] * len(axis))  # nothing before the wall
    assert default_scene(4.0).half_extent > 5.5


# ---- the lidar range check ---------------------------------------------------------------------
def _lidar_spec(rows: int, cols: int, v_half: float = 0.2618) -> LidarSpec:
    spec = LidarSpec(element=None, source=None)  # type: ignore[arg-type]
    spec.samples, spec.resolution, spec.min_angle, spec.max_angle = cols, 1.0, -math.pi, math.pi
    if rows > 1:
        spec.has_vertical, spec.v_samples, spec.v_resolution = True, rows, 1.0
        spec.v_min_angle, spec.v_max_angle = -v_half, v_half
    spec.range_min, spec.range_max = 0.3, 30.0
    return spec


@pytest.mark.parametrize(
    ("rows", "cols"), [(1, 360), (16, 256), (16, 1800), (128, 2048), (5000, 3), (1, 900_000)]
)
def test_range_check_sample_is_bounded_and_keeps_every_row(rows: int, cols: int) -> None:
    sample = check_sample(rows, cols)
    assert len(sample) == len(np.unique(sample)) and (np.diff(sample) > 0).all()
    assert sample.min() >= 0 and sample.max() < rows * cols
    if rows * cols <= SAMPLE_BEAMS:
        assert len(sample) == rows * cols  # a small scan is checked whole
    else:
        assert len(sample) <= max(SAMPLE_BEAMS, min(rows, SAMPLE_BEAMS))
    picked_rows = np.unique(sample // cols)
    if rows <= SAMPLE_BEAMS:
        assert len(picked_rows) == rows  # every row represented
        per_row = np.bincount(sample // cols, minlength=rows)
        assert per_row.max() - per_row.min() == 0
        # and the columns cover the whole azimuth range, not one slice of it
        assert np.ptp(sample % cols) >= 0.9 * (cols - 1) or len(sample) == rows
    np.testing.assert_array_equal(sample, check_sample(rows, cols))  # deterministic


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1))
@example(1503)  # once off in the last bit
def test_pruned_first_hits_equal_every_shape_tested(seed: int) -> None:
    """Skipping the shapes a ray cannot reach never changes its first hit."""
    rng = np.random.default_rng(seed)
    shapes = list(default_scene(0.5).shapes)
    for k in range(6):  # and shapes around and above the origin
        T = transform(tuple(rng.uniform(-2, 2, 3)), tuple(rng.uniform(-3, 3, 3)))
        kind = ("box", "sphere", "cylinder")[k % 3]
        size = {"box": tuple(rng.uniform(0.05, 1.0, 3)), "sphere": (rng.uniform(0.05, 1),)}
        shapes.append(Shape(f"s{k}", kind, T, size.get(kind, tuple(rng.uniform(0.05, 1, 2)))))
    origin = rng.uniform(-1, 1, 3) + np.array([0, 0, 1.0])
    dirs = rng.normal(size=(3000, 3))
    dirs[:5] = [[0, 0, 1], [0, 0, -1], [1, 0, 0], [-1, 0, 0], [-1, -1e-17, 0]]
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    t, i, _ = _first_hits(shapes, origin, dirs, 0.3)
    starts = origin + 0.3 * dirs
    every = np.array([s.intersect(starts, dirs) for s in shapes])
    exact = np.fmin.reduce(every, axis=0)
    hit = np.isfinite(t)
    np.testing.assert_array_equal(hit, np.isfinite(exact))
    # equal up to the last bit: a matrix product rounds differently on fewer rows
    np.testing.assert_allclose(t[hit], exact[hit], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(every[i[hit], np.flatnonzero(hit)], t[hit], rtol=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.integers(1, 700),
    st.sampled_from([np.float32, np.float64]),
    st.sampled_from(["normal", "small", "ties", "wide"]),
)
def test_stats_give_numpys_numbers_bit_for_bit(seed: int, n: int, dtype: type, kind: str) -> None:
    """median, percentile and unique (sensorkit.render._stats, which spare the preview
    numpy.ma) are np.median, np.percentile, np.nanmedian and np.unique, exactly."""
    from sensorkit.render._stats import median, percentile, unique

    rng = np.random.default_rng(seed)
    values = {
        "normal": lambda: rng.normal(size=n),
        "small": lambda: rng.exponential(size=n) * 1e-3,
        "ties": lambda: rng.integers(0, 4, size=n).astype(float),
        "wide": lambda: np.abs(rng.normal(size=n)) * 10.0 ** rng.integers(-9, 3, size=n),
    }[kind]().astype(dtype)
    assert median(values) == float(np.median(values)) == float(np.nanmedian(values))
    for q in (0.0, 1.0, 2.0, 37.3, 50.0, 98.0, 99.0, 100.0):
        assert percentile(values, q) == float(np.percentile(values, q)), q
    wide = values.astype(np.float64)  # as depth_colour_range passes them, with two q at once
    both = np.percentile(wide, [2.0, 98.0])
    assert (percentile(wide, 2.0), percentile(wide, 98.0)) == (float(both[0]), float(both[1]))
    with_nan = values.copy()
    with_nan[rng.integers(0, n)] = np.nan
    assert math.isnan(median(with_nan)) and math.isnan(percentile(with_nan, 99.0))
    ints = rng.integers(-5, 2**40, size=n) // rng.integers(1, 2**38)
    np.testing.assert_array_equal(unique(ints), np.unique(ints))
    assert unique(ints).dtype == np.unique(ints).dtype


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 400), st.integers(-3, 3))
def test_picture_helpers_equal_the_numpy_they_replace(seed: int, n: int, scale: int) -> None:
    """finite_rows, take_rows and the furthest return of scan_view are the plain numpy
    expressions they stand for, exactly."""
    from sensorkit.render.overview import _furthest
    from sensorkit.render.raster import finite_rows, take_rows

    rng = np.random.default_rng(seed)
    points = rng.normal(size=(n, 3)) * 10.0**scale
    if seed % 3 == 0:
        points[rng.random(n) < 0.3] = np.nan
    if seed % 5 == 0:
        points[rng.integers(0, n), rng.integers(0, 3)] = np.inf
    if seed % 7 == 0:
        points[:] = 0.0
    finite = np.isfinite(points).all(axis=1)
    np.testing.assert_array_equal(finite_rows(points), finite)
    np.testing.assert_array_equal(take_rows(points, finite), points[finite])
    if finite.any():
        exact = float(np.max(np.hypot(points[finite, 0], points[finite, 1])))
        assert _furthest(points, finite) == exact


def _scan_in(scene: Scene, spec: LidarSpec, z: float = 0.8) -> tuple[LidarScan, dict]:
    from sensorkit.render.sim import World

    with World() as world:
        world.add_default_shapes(scene, scene.half_extent)
        world.refresh_bounds()
        scan = cast(world, transform((0.0, 0.0, z)), lidar_beams(spec))
        return scan, dict(world.shape_of)


def _beam_on(scan: LidarScan, shapes_of: dict, name: str, among: np.ndarray) -> int:
    """The beam of ``among`` nearest the middle of the shape called ``name``."""
    (key,) = [k for k, shapes in shapes_of.items() if any(s.name == name for s in shapes)]
    on = among[(scan.hits.body[among] == key[0]) & (scan.hits.link[among] == key[1])]
    H = scan.beams.shape[1]
    off = np.abs(scan.beams.elevation[on // H]) + np.abs(scan.beams.azimuth[on % H])
    return int(on[np.argmin(off)])


@pytest.mark.parametrize(("rows", "cols"), [(1, 360), (16, 200), (128, 2048)])
def test_range_check_fails_a_wrong_range_on_a_sampled_beam(rows: int, cols: int) -> None:
    scan, shapes_of = _scan_in(default_scene(0.5), _lidar_spec(rows, cols))
    good = range_check(scan, shapes_of)
    assert good.status == "ok", good.message
    assert good.details["rays"] == rows * cols
    assert good.details["sampled"] == min(rows * cols, len(check_sample(rows, cols)))
    assert good.details["beams"] > 0.8 * good.details["sampled"]
    beam = _beam_on(scan, shapes_of, "wall_+x", check_sample(rows, cols))
    flat = scan.ranges.reshape(-1)
    right = float(flat[beam])
    flat[beam] = right + 0.02  # 2 cm long
    bad = range_check(scan, shapes_of)
    assert bad.status == "fail" and bad.value == pytest.approx(0.02, abs=1e-3), bad.message
    flat[beam] = right
    scan.hits.body[beam] = -1  # pybullet saw nothing where the wall is
    missed = range_check(scan, shapes_of)
    assert missed.status == "fail" and missed.details["missed"] == 1, missed.message


def test_a_2d_lidar_above_the_crates_passes_the_range_check() -> None:
    """Level beams over a crate's top face do not hit it (they once did, in the exact
    geometry, and the check failed 57 beams that pybullet rightly saw hit the wall)."""
    scan, shapes_of = _scan_in(default_scene(0.5), _lidar_spec(1, 360), z=1.0)
    check = range_check(scan, shapes_of)
    assert check.status == "ok" and check.details["wrong_shape"] == 0, check.message


@pytest.mark.parametrize(
    ("rows", "cols", "xyz", "pitch", "yaw"),
    [
        # pitched 2D lidars: a beam at the foot of a wall or a crate, where the floor meets
        # it, once failed as "1 beams hit a different known shape than the exact first hit"
        (1, 720, (-0.382, -0.46, 1.563), 0.229, 2.28),
        (1, 720, (0.791, -0.66, 1.275), -0.227, -2.199),
        (1, 1800, (-0.988, 0.442, 0.568), 0.094, 1.109),
        # a 3D beam on the top edge of a wall, which the exact geometry just misses
        (32, 720, (0.0, -0.15, 1.911), 0.0, 0.755),
        # a level beam clipping a crate's corner by 0.4 mm, under pybullet's tolerance:
        # pybullet sees the wall behind it
        (
            1,
            1800,
            (0.10011433703800576, -0.8482257974573126, 0.11871156739070256),
            0.0,
            -1.868417991343553,
        ),
    ],
)
def test_range_check_passes_beams_on_edges_within_their_footprint(
    rows: int, cols: int, xyz: tuple[float, float, float], pitch: float, yaw: float
) -> None:
    """A correct scan never fails: where a beam's footprint spans an edge, its range is
    compared with the exact ranges across the footprint, not with the shape it hit. A
    range outside the footprint still fails there."""
    from sensorkit.render.sim import World

    scene = default_scene(0.5)
    with World() as world:
        world.add_default_shapes(scene, scene.half_extent)
        world.refresh_bounds()
        scan = cast(world, transform(xyz, (0.0, pitch, yaw)), lidar_beams(_lidar_spec(rows, cols)))
        shapes_of = dict(world.shape_of)
    good = range_check(scan, shapes_of)
    assert good.status == "ok" and good.details["wrong_shape"] == 0, good.message
    # the beams where pybullet hit another shape than the exact first hit, made long
    sample = check_sample(rows, cols)
    known = [s for shapes in shapes_of.values() for s in shapes if s.collision]
    body_of = {id(s): key for key, shapes in shapes_of.items() for s in shapes}
    _, first, _ = _first_hits(known, scan.origin, scan.dirs_world[sample], 0.3)
    exact_body = np.array([body_of[id(known[i])][0] if i >= 0 else -1 for i in first])
    edges = sample[(scan.hits.body[sample] >= 0) & (scan.hits.body[sample] != exact_body)]
    assert len(edges) == good.details["other_shape_in_footprint"]
    flat = scan.ranges.reshape(-1)
    if not len(edges):  # pybullet agreed on every shape: any beams, then
        edges = sample[np.isfinite(flat[sample])][:5]
    flat[edges] += 0.5  # beyond their footprint (a grazing one may not be)
    bad = range_check(scan, shapes_of)
    assert bad.status == "fail" and 0.1 < bad.value < 0.51, bad.message


def test_range_check_compares_an_object_seen_by_a_single_row() -> None:
    """A 4 cm bar across the middle row of a 15-row scan (rows 2 degrees apart): the rows
    above and below miss it, yet its beams are compared, and a wrong range there fails."""
    bar = Shape("bar", "box", transform((3.0, 0.0, 0.8)), (0.05, 1.0, 0.02), rgba=(1, 0, 0, 1))
    ground = Shape("ground", GROUND, np.eye(4), (), GROUND)
    scene = Scene([ground, bar], "bar", 4.0)
    spec = _lidar_spec(15, 240, v_half=math.radians(14))
    scan, shapes_of = _scan_in(scene, spec)
    V, H = scan.beams.shape
    assert scan.beams.elevation[7] == pytest.approx(0.0, abs=1e-12)
    (key,) = [k for k, shapes in shapes_of.items() if shapes == [bar]]
    on_bar = (scan.hits.body == key[0]).reshape(V, H)
    assert on_bar.any(axis=1).tolist() == [r == 7 for r in range(V)]  # one row sees it
    good = range_check(scan, shapes_of)
    assert good.status == "ok", good.message
    scan.ranges[on_bar] += 0.05
    bad = range_check(scan, shapes_of)
    assert bad.status == "fail" and bad.value == pytest.approx(0.05, abs=1e-3), bad.message


# ---- what RViz will show -------------------------------------------------------------------
def test_rviz_places_data_by_the_stamped_frame() -> None:
    from sensorkit.render.rviz import MISMATCH, PANEL, Misplaced, camera_points, draw_rviz

    # a scan whose frame is turned 90 degrees left of where the lidar looks
    T_true = transform((0.0, 0.0, 1.0))
    T_stamped = transform((0.0, 0.0, 1.0), (0.0, 0.0, math.pi / 2))
    pts = np.array([[2.0, 0.0, 0.0], [3.0, 1.0, 0.0]])
    m = Misplaced("laser_mount", T_true, T_stamped, pts, 0, 1.0)
    np.testing.assert_allclose(m.true_world(pts), [[2, 0, 1], [3, 1, 1]], atol=1e-12)
    np.testing.assert_allclose(m.stamped_world(pts), [[0, 2, 1], [-1, 3, 1]], atol=1e-12)
    np.testing.assert_allclose(m.forward(), [[1, 0, 1], [0, 1, 1]], atol=1e-12)
    assert m.to_dict()["centre_moved_m"] == pytest.approx(math.hypot(3.0, 2.0))
    image, panels = draw_rviz(m, (31, 119, 180))
    assert image.shape == (PANEL[1], 2 * PANEL[0] + 6, 3)
    # each panel's scale, for the axes and scale bar index.html draws over it (issue 38):
    # the top view spans the 4 x 3 m of truth, sample and axes within its margins
    assert [p["view"] for p in panels] == ["top", "side"]
    assert [p["x0"] for p in panels] == [0, PANEL[0] + 6]
    assert panels[0]["px_per_m"] == pytest.approx(min((320 - 28) / 4.0, (240 - 28) / 3.0))
    assert panels[1]["heading"] == pytest.approx([1.0, 0.0])
    magenta = (image == MISMATCH).all(axis=2)
    assert magenta[:, : PANEL[0]].sum() > 20 and magenta[:, PANEL[0] + 6 :].sum() > 20
    # a camera's depth as points in its optical frame: a flat wall 2 m ahead
    depth = np.full((3, 4), 2.0, dtype=np.float32)
    depth[0, 0] = np.inf  # nothing there: no point
    points, corners = camera_points(depth, fx=2.0, fy=2.0, cx=1.5, cy=1.0, reach=4.0)
    assert len(points) == 11 and np.allclose(points[:, 2], 2.0)
    np.testing.assert_allclose(points[0], [(1 - 1.5) / 2 * 2, (0 - 1.0) / 2 * 2, 2.0])
    np.testing.assert_allclose(corners[2], [(3 - 1.5) / 2 * 4, (2 - 1.0) / 2 * 4, 4.0])


# ---- rendering in several processes --------------------------------------------------------
def test_sensors_are_split_over_processes_by_work() -> None:
    from sensorkit.render.plan import plan_jobs as _plan
    from sensorkit.render.workers import _cost, _groups

    robot = load_robot(HERE / "gz_bot.urdf").robot
    assert robot is not None
    jobs = [j for j in _plan(robot, (), Path("out")) if not isinstance(j, SensorPreview)]
    names = [j.name for j in jobs]
    assert names == ["gz_cam", "lens_cam", "velo"]
    assert _cost(jobs[2]) > _cost(jobs[0]) + _cost(jobs[1])  # 28,800 rays, 2 x 161x121
    assert [[j.name for j in g] for g in _groups(jobs, 1)] == [names]
    # the biggest to a forked process: this one has the overview and validate to do after
    assert [[j.name for j in g] for g in _groups(jobs, 2)] == [["gz_cam", "lens_cam"], ["velo"]]
    assert [[j.name for j in g] for g in _groups(jobs, 4)] == [["lens_cam"], ["gz_cam"], ["velo"]]


def test_a_lidar_cast_in_a_forked_process_gives_the_same_files(tmp_path: Path) -> None:
    from sensorkit.render import render_preview

    robot, scene = HERE / "gz_bot.urdf", HERE / "wall_scene.urdf"
    one = render_preview(robot, tmp_path / "one", scene=scene, workers=1)
    two = render_preview(robot, tmp_path / "two", scene=scene, workers=2)
    for a, b in zip(one.sensors, two.sensors, strict=True):
        assert [c.to_dict() for c in a.checks] == [c.to_dict() for c in b.checks]
        for key, path in a.files.items():
            assert path.read_bytes() == b.files[key].read_bytes(), (a.name, key)
    assert (tmp_path / "one" / "overview.png").read_bytes() == (
        tmp_path / "two" / "overview.png"
    ).read_bytes()


# ---- kinematics ------------------------------------------------------------------------------
def test_link_poses_follow_the_joints() -> None:
    robot = load_robot(HERE / "mounts_bot.urdf").robot
    assert robot is not None
    poses = link_poses(robot, joint_positions(robot, {"pan": 0.5}))
    T = poses["yaw_cam_link"]
    assert T[:3, 3] == pytest.approx([0.1 * math.cos(0.5), 0.1 * math.sin(0.5), 0.5])
    zero = link_poses(robot, {})
    for name, T0 in zero.items():
        assert pytest.approx(robot.T_world_link(name)) == T0
    with pytest.raises(UsageError, match="movable joints: pan"):
        joint_positions(robot, {"tilt": 1.0})
    with pytest.raises(UsageError, match="fixed"):
        joint_positions(robot, {"pitch_cam_joint": 1.0})


# ---- the URDF pybullet loads -------------------------------------------------------------------
ASCII_STL = """solid t
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 0.1 0 0
  vertex 0 0.1 0
 endloop
endfacet
endsolid t
"""


def test_prepared_urdf_drops_what_pybullet_cannot_load(tmp_path: Path) -> None:
    pkg = tmp_path / "src" / "my_robot"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>my_robot</name></package>")
    (pkg / "meshes" / "part.stl").write_text(ASCII_STL)
    (pkg / "urdf").mkdir()
    xacro = pkg / "urdf" / "r.urdf.xacro"
    xacro.write_text(
        """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="s" value="0.2"/>
  <link name="base">
    <visual><geometry><mesh filename="package://my_robot/meshes/part.stl"/></geometry></visual>
    <visual><geometry><mesh filename="package://my_robot/meshes/missing.dae"/></geometry></visual>
    <collision><geometry><mesh filename="package://nowhere/meshes/x.stl"/></geometry></collision>
    <collision><geometry><box size="${s} ${s} ${s}"/></geometry></collision>
  </link>
  <gazebo reference="base"><material>Gazebo/Red</material></gazebo>
</robot>"""
    )
    robot = load_robot(xacro).robot
    assert robot is not None
    prepared = prepare_urdf(robot, PackageResolver.from_options([], near=xacro))
    text = prepared.text.decode()
    assert "sk_loc_" not in text and "<gazebo" not in text
    assert str((pkg / "meshes" / "part.stl").resolve()) in text
    assert prepared.dropped == 2 and len(prepared.notes) == 2
    assert any("missing.dae" in n for n in prepared.notes)
    assert any("package 'nowhere' not found" in n for n in prepared.notes)

    from sensorkit.render.sim import World

    with World() as world:
        body = world.add_robot(prepared.text)
        assert world.robot_links == {(body, -1): "base"} and body >= 0


def test_pybullet_failure_is_an_input_error() -> None:
    from sensorkit.base.errors import InputError
    from sensorkit.render.sim import World

    with World() as world, pytest.raises(InputError, match="pybullet could not load"):
        world.add_robot(
            b"<robot name='x'><link name='a'/><joint name='j' type='fixed'><parent link='a'/><child link='zz'/></joint></robot>"
        )


def test_captured_output_keeps_c_level_writes_off_the_terminal() -> None:
    code = (
        "import os, ctypes\n"
        "from sensorkit.render.sim import captured_output\n"
        "log = []\n"
        "with captured_output(log):\n"
        "    os.write(1, b'fd one\\n'); os.write(2, b'fd two\\n')\n"
        "    ctypes.CDLL(None).printf(b'from C\\n')\n"
        "print('after', sorted(log))\n"
    )
    proc = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=60,
        env=dict(os.environ),
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert proc.stdout == "after ['fd one', 'fd two', 'from C']\n"


def test_textures_are_made_once_and_kept_in_the_cache(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The default room's textures come from the user's cache after the first preview;
    a cached file is used only when whole, and an unwritable cache falls back. They are
    BMP files (pybullet loads them three times faster than PNGs), read back here by
    Pillow, an independent parser."""
    from PIL import Image

    from sensorkit.render.textures import Texture, texture_file

    cache = tmp_path / "cache"
    monkeypatch.setenv("SENSORKIT_CACHE_DIR", str(cache))
    fallback = tmp_path / "tmp"
    fallback.mkdir()
    tex = Texture("feature", 101, 64)
    made = texture_file(tex, fallback)
    assert made.parent == cache / "textures" and list(fallback.iterdir()) == []
    with Image.open(made, formats=["BMP"]) as img:
        assert np.array_equal(np.asarray(img.convert("RGB")), tex.image())
    assert [p.name for p in made.parent.iterdir()] == [made.name]  # no temporary left

    def refuse(self: Texture) -> np.ndarray:
        raise AssertionError("made again")

    with monkeypatch.context() as m:
        m.setattr(Texture, "image", refuse)
        assert texture_file(tex, fallback) == made  # read from the cache, not made
    good = made.read_bytes()
    for broken in (good[: len(good) // 2], good[:-20] + bytes(20), b"", good[:40]):
        made.write_bytes(broken)
        assert texture_file(tex, fallback) == made
        assert made.read_bytes() == good  # made again, whole
    other = Texture("feature", 101, 32)  # the same seed at another size is another file
    assert texture_file(other, fallback) != made
    # a cache that cannot be written: the file goes to the caller's folder
    blocked = tmp_path / "blocked"
    blocked.write_text("a file where the cache folder would be")
    monkeypatch.setenv("SENSORKIT_CACHE_DIR", str(blocked))
    out = texture_file(tex, fallback)
    assert out.parent == fallback and out.read_bytes() == good


@pytest.mark.parametrize(("width", "height"), [(4, 6), (5, 3), (1, 1), (7, 2)])
def test_bmp_textures_read_back_as_written_and_damage_is_told(width: int, height: int) -> None:
    """Every row width (BMP pads rows to four bytes), read back by Pillow; a file cut
    short, with trailing bytes, of another size, or with a pixel changed is not intact."""
    from PIL import Image

    from sensorkit.render.bitmap import encode_bmp, intact_bmp

    rng = np.random.default_rng(width * 10 + height)
    image = rng.integers(0, 256, (height, width, 3), dtype=np.uint8)
    data = encode_bmp(image)
    with Image.open(io.BytesIO(data), formats=["BMP"]) as img:
        assert np.array_equal(np.asarray(img.convert("RGB")), image)
    assert intact_bmp(data, width, height)
    assert not intact_bmp(data, height, width) or width == height
    assert not intact_bmp(data + b"x", width, height)
    for cut in range(len(data)):
        assert not intact_bmp(data[:cut], width, height)
    changed = bytearray(data)
    changed[-1] ^= 1
    assert not intact_bmp(bytes(changed), width, height)


def test_intact_png_tells_a_whole_png_from_a_damaged_one() -> None:
    from sensorkit.render.png import encode_png, intact_png

    data = encode_png(np.full((6, 4, 3), 7, dtype=np.uint8), level=0)
    assert intact_png(data, 4, 6)
    assert not intact_png(data, 6, 4)  # another size
    assert not intact_png(data + b"x", 4, 6)  # trailing bytes
    for cut in range(len(data)):
        assert not intact_png(data[:cut], 4, 6)
    flipped = bytearray(data)
    flipped[40] ^= 1  # a pixel byte in IDAT: its CRC no longer holds
    assert not intact_png(bytes(flipped), 4, 6)


def test_a_wall_shows_one_copy_of_its_texture() -> None:
    """No seam and no repeat on a wall of the default room: every face's texture
    coordinates stay within one copy (0..1), so a camera facing a wall never sees two
    halves of one pattern; the floor's tiles still repeat every metre."""
    from sensorkit.render.scene import box_mesh, default_scene

    for reach in (0.5, 3.0, 9.0):
        scene = default_scene(reach, textured=False)
        walls = [s for s in scene.shapes if s.role in ("wall", "crate")]
        assert len(walls) == 8
        for wall in walls:
            _, _, uvs, _ = box_mesh(tuple(wall.size), wall.uv_per_m)  # type: ignore[arg-type]
            uv = np.array(uvs)
            assert uv.min() >= -1e-9 and uv.max() <= 1 + 1e-9, (
                reach,
                wall.name,
                uv.min(),
                uv.max(),
            )
        ground = next(s for s in scene.shapes if s.role == "ground")
        assert ground.uv_per_m == 1.0


def test_scene_markers_are_never_drawn_in_the_rviz_magenta() -> None:
    """Magenta is kept for where RViz will put data: the default room's marker spheres
    render amber, and the overview draws them amber, with no magenta pixel when no data
    is misplaced."""
    from sensorkit.render.overview import MARKER_COLOUR, MISMATCH, draw_overview, overview_px
    from sensorkit.render.scene import default_scene

    scene = default_scene(0.5, textured=False)
    assert scene.markers
    for marker in scene.markers:
        rgb = np.array(marker.rgba[:3]) * 255
        assert np.abs(rgb - np.array(MISMATCH)).max() > 100, marker.rgba
    half = scene.half_extent + 0.3
    image = draw_overview(scene.shapes, [], [], [], half).astype(np.int64)
    for marker in scene.markers:
        col, row = np.rint(overview_px(marker.centre[:2], half, image.shape[1])[0]).astype(int)
        assert image[row, col].tolist() == list(MARKER_COLOUR)
    near_magenta = np.abs(image - np.array(MISMATCH)).sum(axis=2) < 60
    assert not near_magenta.any()


def test_polygons_fill_what_they_enclose_and_clip_at_the_edges() -> None:
    """Canvas.polygon (Pillow's scan conversion): a square fills its inside and nothing
    beyond its edges; a concave shape leaves its notch empty; a polygon reaching far past
    the canvas is clipped, not refused."""
    c = Canvas(20, 20, (0, 0, 0))
    c.polygon(np.array([[2.0, 2.0], [8.0, 2.0], [8.0, 8.0], [2.0, 8.0]]), (255, 0, 0))
    red = c.image[:, :, 0] == 255
    assert red[3:8, 3:8].all() and not red[:2].any() and not red[9:].any()
    assert not red[:, :2].any() and not red[:, 9:].any()
    u = Canvas(20, 20, (0, 0, 0))  # a U: the notch between its arms stays empty
    u.polygon(
        np.array([[2.0, 2], [6, 2], [6, 12], [12, 12], [12, 2], [16, 2], [16, 17], [2, 17]]),
        (0, 255, 0),
    )
    green = u.image[:, :, 1] == 255
    assert green[14, 4] and green[5, 4] and green[5, 14] and not green[5, 9]
    far = Canvas(20, 20, (0, 0, 0))
    far.polygon(np.array([[10.0, 10.0], [-500.0, 2000.0], [2000.0, 2000.0]]), (0, 0, 255))
    blue = far.image[:, :, 2] == 255
    assert blue[19, 10] and blue[12, 10] and not blue[5, 10]
