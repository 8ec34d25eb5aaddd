"""Intrinsics and LaserScan math against the simulators' own formulas."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sensorkit.base.errors import UsageError
from sensorkit.describe.intrinsics import (
    Intrinsics,
    InvalidValue,
    camera_intrinsics,
    laser_scan,
)

# --------------------------------------------------------------------------- golden


def test_classic_golden_640x480_hfov2() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic")
    assert intr.fx == 205.46963709898583
    assert intr.fy == 205.46963709898583
    assert intr.cx == 320.5
    assert intr.cy == 240.5
    assert intr.skew == 0.0
    assert intr.distortion == (0.0, 0.0, 0.0, 0.0, 0.0)
    assert intr.convention == "classic"


def test_gz_golden_640x480_hfov2() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "gz")
    assert abs(intr.fx - 205.46963709898583) < 1e-4
    assert abs(intr.fy - 205.46963709898583) < 1e-4
    assert intr.cx == 320.0
    assert intr.cy == 240.0


def test_ideal_centres_on_pixel_centres() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "ideal")
    assert intr.fx == 205.46963709898583
    assert (intr.cx, intr.cy) == (319.5, 239.5)


def test_matrices_shapes_and_values() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic")
    f = 205.46963709898583
    np.testing.assert_array_equal(intr.K, [[f, 0, 320.5], [0, f, 240.5], [0, 0, 1]])
    np.testing.assert_array_equal(intr.R, np.eye(3))
    np.testing.assert_array_equal(intr.P, [[f, 0, 320.5, 0], [0, f, 240.5, 0], [0, 0, 1, 0]])
    assert intr.K.shape == (3, 3)
    assert intr.P.shape == (3, 4)


# --------------------------------------------------------------------------- fov


@pytest.mark.parametrize("convention", ["classic", "gz", "ideal"])
def test_hfov_round_trip(convention: str) -> None:
    intr = camera_intrinsics(1280, 720, 1.3962634, convention)  # type: ignore[arg-type]
    assert intr.hfov == pytest.approx(1.3962634, abs=1e-6)


def test_vfov_formula() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic")
    assert intr.vfov == 2 * math.atan(480 / (2 * intr.fy))
    assert intr.vfov < intr.hfov


# --------------------------------------------------------------------------- overrides


def test_focal_length_override() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic", focal_length=500.0)
    assert intr.fx == intr.fy == 500.0
    # hfov now follows the focal length, not the SDF angle.
    assert intr.hfov == pytest.approx(2 * math.atan(640 / 1000))


def test_focal_length_zero_means_computed() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic", focal_length=0.0)
    assert intr.fx == 205.46963709898583


def test_cx_cy_override() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic", cx=300.0, cy=200.0)
    assert (intr.cx, intr.cy) == (300.0, 200.0)
    assert intr.K[0, 2] == 300.0
    assert intr.P[1, 2] == 200.0


def test_hack_baseline_sets_p03() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic", hack_baseline=0.07)
    assert intr.P[0, 3] == -205.46963709898583 * 0.07
    assert intr.baseline_tx == intr.P[0, 3]
    assert intr.K[0, 2] == 320.5  # K is untouched


def test_hack_baseline_zero_is_positive_zero() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic")
    assert math.copysign(1.0, intr.baseline_tx) == 1.0


def test_lens_intrinsics_verbatim() -> None:
    intr = camera_intrinsics(
        640, 480, 2.0, "gz", lens_intrinsics=(277.0, 278.5, 160.0, 120.25, 0.5)
    )
    assert (intr.fx, intr.fy, intr.cx, intr.cy, intr.skew) == (277.0, 278.5, 160.0, 120.25, 0.5)
    assert intr.K[0, 1] == 0.5


def test_distortion_kept_in_plumb_bob_order() -> None:
    d = (-0.25, 0.12, -0.00028, -5e-05, 0.0)
    intr = camera_intrinsics(640, 480, 2.0, "classic", distortion=d)
    assert intr.distortion == d
    assert intr.has_distortion


@pytest.mark.parametrize(
    ("kwargs", "convention"),
    [
        ({"focal_length": 100.0}, "gz"),
        ({"cx": 1.0}, "ideal"),
        ({"lens_intrinsics": (1.0, 1.0, 1.0, 1.0, 0.0)}, "classic"),
    ],
)
def test_parameters_of_another_simulator_are_refused(
    kwargs: dict[str, object], convention: str
) -> None:
    with pytest.raises(InvalidValue):
        camera_intrinsics(640, 480, 2.0, convention, **kwargs)  # type: ignore[arg-type]


# --------------------------------------------------------------------------- project


@pytest.mark.parametrize("convention", ["classic", "gz", "ideal"])
def test_optical_axis_projects_to_principal_point(convention: str) -> None:
    intr = camera_intrinsics(640, 480, 2.0, convention)  # type: ignore[arg-type]
    uv = intr.project(np.array([[0.0, 0.0, 3.0]]))
    assert uv.shape == (1, 2)
    assert tuple(uv[0]) == (intr.cx, intr.cy)


def test_project_edge_of_fov_hits_image_border() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "ideal")
    x = math.tan(1.0)  # half of hfov = 1 rad
    uv = intr.project(np.array([[x, 0.0, 1.0], [-x, 0.0, 1.0]]))
    assert uv[0, 0] == pytest.approx(319.5 + 320.0)
    assert uv[1, 0] == pytest.approx(319.5 - 320.0)


def test_project_behind_camera_is_nan() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic")
    uv = intr.project(np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]))
    assert np.isnan(uv[:2]).all()
    assert np.isfinite(uv[2]).all()


def test_project_with_distortion_leaves_axis_alone() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic", distortion=(-0.3, 0.1, 0.001, 0.002, 0.01))
    uv = intr.project(np.array([[0.0, 0.0, 1.0], [0.2, 0.1, 1.0]]), apply_distortion=True)
    assert tuple(uv[0]) == (intr.cx, intr.cy)
    plain = intr.project(np.array([[0.2, 0.1, 1.0]]))
    assert not np.allclose(uv[1], plain[0])


def test_project_rejects_bad_shape() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic")
    with pytest.raises(InvalidValue, match="shape"):
        intr.project(np.zeros((4, 2)))


# --------------------------------------------------------------------------- bad values


@pytest.mark.parametrize(
    ("args", "name"),
    [
        ((0, 480, 2.0, "classic"), "width"),
        ((-640, 480, 2.0, "classic"), "width"),
        ((640.5, 480, 2.0, "classic"), "width"),
        ((True, 480, 2.0, "classic"), "width"),
        ((640, 0, 2.0, "classic"), "height"),
        ((640, 480, 0.0, "classic"), "hfov"),
        ((640, 480, -1.0, "classic"), "hfov"),
        ((640, 480, math.pi, "classic"), "hfov"),
        ((640, 480, 4.0, "classic"), "hfov"),
        ((640, 480, float("nan"), "classic"), "hfov"),
        ((640, 480, float("inf"), "classic"), "hfov"),
        ((640, 480, 2.0, "unity"), "convention"),
    ],
)
def test_bad_values_raise_value_error_naming_the_value(args: tuple[object, ...], name: str) -> None:
    with pytest.raises(ValueError, match=name):
        camera_intrinsics(*args)  # type: ignore[arg-type]


def test_invalid_value_is_a_usage_error() -> None:
    with pytest.raises(UsageError):
        camera_intrinsics(640, 480, 0.0, "classic")


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"focal_length": -1.0}, "focal_length"),
        ({"focal_length": float("nan")}, "focal_length"),
        ({"cx": float("nan")}, "cx"),
        ({"cy": float("inf")}, "cy"),
        ({"distortion": (0.0, 0.0, 0.0, 0.0)}, "distortion"),
        ({"distortion": (0.0, 0.0, float("nan"), 0.0, 0.0)}, "distortion"),
        ({"hack_baseline": float("nan")}, "hack_baseline"),
    ],
)
def test_bad_keyword_values(kwargs: dict[str, object], name: str) -> None:
    with pytest.raises(ValueError, match=name):
        camera_intrinsics(640, 480, 2.0, "classic", **kwargs)  # type: ignore[arg-type]


def test_bad_lens_intrinsics() -> None:
    with pytest.raises(ValueError, match="lens_intrinsics"):
        camera_intrinsics(640, 480, 2.0, "gz", lens_intrinsics=(0.0, 1.0, 1.0, 1.0, 0.0))
    with pytest.raises(ValueError, match="lens_intrinsics"):
        camera_intrinsics(640, 480, 2.0, "gz", lens_intrinsics=(1.0, 1.0, 1.0))  # type: ignore[arg-type]


def test_intrinsics_constructor_validates() -> None:
    with pytest.raises(ValueError, match="fx"):
        Intrinsics(640, 480, 0.0, 1.0, 1.0, 1.0)
    with pytest.raises(ValueError, match="cy"):
        Intrinsics(640, 480, 1.0, 1.0, 1.0, float("nan"))
    intr = Intrinsics(np.int64(640), 480, np.float32(1.5), 1, 2, 3)  # type: ignore[arg-type]
    assert type(intr.width) is int
    assert type(intr.fx) is float
    assert type(intr.fy) is float


def test_intrinsics_is_frozen() -> None:
    intr = camera_intrinsics(640, 480, 2.0, "classic")
    with pytest.raises(AttributeError):
        intr.fx = 1.0  # type: ignore[misc]


# --------------------------------------------------------------------------- LaserScan


def test_laser_scan_full_circle() -> None:
    scan = laser_scan(360, 1, -math.pi, math.pi, 0.12, 3.5)
    assert scan.samples == 360
    assert scan.angle_increment == 2 * math.pi / 359
    assert scan.angle_min == -math.pi
    assert scan.angle_max == math.pi
    assert (scan.range_min, scan.range_max) == (0.12, 3.5)
    assert scan.time_increment == 0.0
    assert scan.scan_time == 0.0
    angles = scan.beam_angles()
    assert angles.shape == (360,)
    assert angles[0] == -math.pi
    assert angles[-1] == pytest.approx(math.pi)


def test_laser_scan_resolution_halves_the_beams() -> None:
    scan = laser_scan(640, 0.5, -1.0, 1.0, 0.1, 30.0)
    assert scan.samples == 320
    assert scan.angle_increment == 2.0 / 319


def test_laser_scan_floor_not_round() -> None:
    assert laser_scan(7, 0.5, -1.0, 1.0, 0.1, 30.0).samples == 3


def test_laser_scan_single_beam() -> None:
    scan = laser_scan(1, 1, 0.0, 0.0, 0.1, 10.0)
    assert scan.samples == 1
    assert scan.angle_increment == 0.0
    assert list(scan.beam_angles()) == [0.0]


@pytest.mark.parametrize(
    ("args", "name"),
    [
        ((0, 1, -1.0, 1.0, 0.1, 10.0), "samples"),
        ((360, 0, -1.0, 1.0, 0.1, 10.0), "resolution"),
        ((360, float("nan"), -1.0, 1.0, 0.1, 10.0), "resolution"),
        ((1, 0.5, -1.0, 1.0, 0.1, 10.0), "resolution"),
        ((360, 1, 1.0, -1.0, 0.1, 10.0), "max_angle"),
        ((360, 1, float("nan"), 1.0, 0.1, 10.0), "min_angle"),
        ((360, 1, -1.0, 1.0, 10.0, 1.0), "range_min"),
        ((360, 1, -1.0, 1.0, -0.1, 1.0), "range_min"),
        ((360, 1, -1.0, 1.0, 0.1, float("inf")), "range_max"),
    ],
)
def test_laser_scan_bad_values(args: tuple[object, ...], name: str) -> None:
    with pytest.raises(ValueError, match=name):
        laser_scan(*args)  # type: ignore[arg-type]


# --------------------------------------------------------------------------- property


@settings(max_examples=300, deadline=None)
@given(
    width=st.integers(16, 4096),
    height=st.integers(16, 4096),
    hfov=st.floats(0.1, 3.0, allow_nan=False, allow_infinity=False),
)
def test_classic_round_trip_property(width: int, height: int, hfov: float) -> None:
    intr = camera_intrinsics(width, height, hfov, "classic")
    refit = width / (2.0 * math.tan(intr.hfov / 2.0))
    assert refit == pytest.approx(intr.fx, rel=1e-12)
    assert intr.hfov == pytest.approx(hfov, rel=1e-12)
    uv = intr.project(np.array([[0.0, 0.0, 1.0]]))
    assert tuple(uv[0]) == (intr.cx, intr.cy)
    assert (intr.cx, intr.cy) == ((width + 1) / 2, (height + 1) / 2)


@settings(max_examples=200, deadline=None)
@given(
    width=st.integers(16, 4096),
    height=st.integers(16, 4096),
    hfov=st.floats(0.1, 3.0, allow_nan=False, allow_infinity=False),
)
def test_gz_agrees_with_double_formula_property(width: int, height: int, hfov: float) -> None:
    gz = camera_intrinsics(width, height, hfov, "gz")
    exact = width / (2.0 * math.tan(hfov / 2.0))
    # Ogre keeps the frustum in float32; tan(vfov/2) is ill-conditioned as vfov nears pi
    # (very tall images), where Gazebo's own value drifts further from the double formula.
    vfov = 2.0 * math.atan(height / (2.0 * exact))
    rel = 1e-5 if vfov < 2.8 else 1e-2
    assert gz.fx == pytest.approx(exact, rel=rel)
    assert gz.fy == pytest.approx(exact, rel=rel)
    assert (gz.cx, gz.cy) == (width / 2, height / 2)
