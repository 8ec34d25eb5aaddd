"""Property tests for ``sensorkit add-*``: random names, mounts, parameters and file styles.

- an accepted add keeps every original byte and line in order, the result validates
  without errors, and the new joint carries exactly the requested mount;
- a dry run (``--diff``) and a refused add (taken name, missing parent) leave every
  file byte-identical and create none.
"""

from __future__ import annotations

import math
import shutil
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from sensorkit.base.errors import EditRefused
from sensorkit.base.findings import Severity
from sensorkit.edit import AddRequest, add_sensor, apply_add
from sensorkit.lint.engine import Options, validate_file
from sensorkit.model import load_robot

ROBOTS = Path(__file__).resolve().parent / "edit_robots"
EXISTING = {
    "base_footprint", "base_link", "left_wheel", "right_wheel",
    "base_joint", "left_wheel_joint", "right_wheel_joint",
}  # fmt: skip
LINKS = ["base_footprint", "base_link", "left_wheel", "right_wheel"]

SETTINGS = settings(
    max_examples=25,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)

names = st.from_regex(r"[a-z][a-z0-9_]{0,14}", fullmatch=True)
coords = st.floats(-2.0, 2.0, allow_nan=False, allow_infinity=False)
angles = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
rates = st.floats(1.0, 60.0).map(lambda v: round(v, 3))


@st.composite
def sensor(draw: st.DrawFn) -> tuple[str, dict[str, str]]:
    kind = draw(
        st.sampled_from(["camera", "depth_camera", "lidar_2d", "lidar_3d", "stereo_camera", "imu"])
    )
    params: dict[str, str] = {}
    if draw(st.booleans()):
        params["update_rate"] = repr(draw(rates))
    if kind in ("camera", "depth_camera", "stereo_camera"):
        if draw(st.booleans()):
            params["width"] = str(draw(st.integers(16, 1920)))
            params["height"] = str(draw(st.integers(16, 1080)))
        if draw(st.booleans()):
            params["hfov"] = repr(round(draw(st.floats(0.3, 2.5)), 4))
    if kind.startswith("lidar") and draw(st.booleans()):
        params["samples"] = str(draw(st.integers(8, 2000)))
        params["range_min"] = repr(round(draw(st.floats(0.05, 0.5)), 3))
        params["range_max"] = repr(round(draw(st.floats(2.0, 80.0)), 2))
    if draw(st.booleans()):
        params["sim"] = draw(st.sampled_from(["classic", "gz", "none"]))
        if params["sim"] == "gz":
            params["gz_version"] = draw(st.sampled_from(["fortress", "harmonic", "jetty"]))
    return kind, params


@st.composite
def robot_file(draw: st.DrawFn) -> tuple[str, str, str]:
    """(style, newline, indent) of the robot the add edits."""
    return (
        draw(st.sampled_from(["urdf", "xacro"])),
        draw(st.sampled_from(["\n", "\r\n"])),
        draw(st.sampled_from(["  ", "    ", "\t"])),
    )


def restyle(data: bytes, newline: str, indent: str) -> bytes:
    out: list[str] = []
    for line in data.decode().splitlines():
        stripped = line.lstrip(" ")
        out.append(indent * ((len(line) - len(stripped)) // 2) + stripped)
    return (newline.join(out) + newline).encode()


def make_robot(folder: Path, style: str, newline: str, indent: str) -> Path:
    if style == "urdf":
        path = folder / "rover.urdf"
        path.write_bytes(restyle((ROBOTS / "rover.urdf").read_bytes(), newline, indent))
        return path
    shutil.copytree(ROBOTS / "xacro_robot", folder / "xrover")
    path = folder / "xrover" / "robot.urdf.xacro"
    path.write_bytes(restyle(path.read_bytes(), newline, indent))
    return path


def snapshot(folder: Path) -> dict[str, bytes]:
    return {
        str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()
    }


def lines_in_order(old: bytes, new: bytes) -> bool:
    it = iter(new.splitlines(keepends=True))
    return all(any(a == b for b in it) for a in old.splitlines(keepends=True))


def free(name: str) -> bool:
    return not any(e == name or e.startswith(name + "_") for e in EXISTING)


@SETTINGS
@given(
    robot_file(),
    sensor(),
    names,
    st.sampled_from(LINKS),
    st.tuples(coords, coords, coords),
    st.tuples(angles, angles, angles),
)
def test_accepted_add_keeps_bytes_and_validates(
    style: tuple[str, str, str],
    spec: tuple[str, dict[str, str]],
    name: str,
    parent: str,
    xyz: tuple[float, float, float],
    rpy: tuple[float, float, float],
) -> None:
    assume(free(name))
    kind, params = spec
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        path = make_robot(folder, *style)
        original = path.read_bytes()
        before = snapshot(folder)

        req = AddRequest(path, kind, name, parent, xyz=xyz, rpy=rpy, params=params)
        result = add_sensor(req, dry_run=True)
        assert snapshot(folder) == before  # --diff: nothing written
        apply_add(result)
        new = path.read_bytes()

        assert new == result.new
        it = iter(new)
        assert all(any(c == d for d in it) for c in original)  # every byte, in order
        assert lines_in_order(original, new)  # every line whole
        if style[1] == "\r\n":
            assert new.count(b"\n") == new.count(b"\r\n")
        else:
            assert b"\r" not in new

        report = validate_file(path, Options())
        assert report.error is None, report.error
        errors = [(f.rule, f.message) for f in report.findings if f.severity >= Severity.ERROR]
        assert not errors

        robot = load_robot(path).robot
        assert robot is not None
        joint = robot.joint_map[f"{name}_joint"]
        assert joint.parent == parent
        assert joint.origin.xyz == xyz and joint.origin.rpy == rpy  # exact: shortest repr


@SETTINGS
@given(
    robot_file(),
    st.sampled_from(["camera", "lidar_2d", "imu"]),
    st.one_of(
        st.tuples(st.sampled_from(sorted(EXISTING)), st.sampled_from(LINKS)),  # taken name
        st.tuples(st.just("base"), st.sampled_from(LINKS)),  # the macro would make base_link
        st.tuples(names.filter(free), names.filter(lambda n: n not in LINKS)),  # no such parent
    ),
)
def test_refused_add_changes_nothing(
    style: tuple[str, str, str], kind: str, name_parent: tuple[str, str]
) -> None:
    name, parent = name_parent
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        path = make_robot(folder, *style)
        before = snapshot(folder)
        try:
            add_sensor(AddRequest(path, kind, name, parent))
        except EditRefused as exc:
            assert name in str(exc) or parent in str(exc)
        else:
            raise AssertionError(f"add of {name!r} on {parent!r} was not refused")
        assert snapshot(folder) == before
