"""add-* checks the robot once and works out the rest (``check.compare_added``): its
verdict must be the one a full check of the robot before and after gives (``compare``)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

import sensorkit.edit.add
import sensorkit.edit.check
from sensorkit.base.errors import EditRefused
from sensorkit.base.findings import Finding
from sensorkit.edit import AddRequest, plan_add
from sensorkit.edit.check import Verdict, compare, copy_document_with
from sensorkit.loading.document import Document
from sensorkit.model import Robot
from sensorkit.model.sdf import Conversion, convert

ROBOTS = Path(__file__).resolve().parent / "edit_robots"

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
INERTIAL = (
    '<inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" '
    'izz="0.1"/></inertial>'
)


FAST: list[bool] = []


@pytest.fixture(autouse=True)
def conversion_checked(monkeypatch: pytest.MonkeyPatch) -> None:
    """Whenever the conversion is extended rather than redone, it is what convert gives."""
    real = sensorkit.edit.check.extend_conversion

    def checked(conv: Conversion, before: Robot, after: Robot, added: Robot) -> Conversion | None:
        out = real(conv, before, after, added)
        FAST.append(out is not None)
        if out is not None:
            whole = convert(after)
            assert out.target_of == whole.target_of
            assert list(out.dropped.items()) == list(whole.dropped.items())
            assert out.preserved_joints == whole.preserved_joints
            for name, mass in whole.mass_of.items():
                assert out.mass_of[name] == pytest.approx(mass, rel=1e-12, abs=1e-15)
        return out

    monkeypatch.setattr(sensorkit.edit.check, "extend_conversion", checked)


def test_the_rover_takes_the_short_way(rover: Path) -> None:
    FAST.clear()
    plan_add(AddRequest(rover, "camera", "s", "base_link"))
    assert FAST == [True]


def test_sensorkits_own_macro_expands_without_a_fork(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The fragment of sensorkit's own macro expands in process (forking a process that
    holds a large robot costs more than the expansion); a user's modified copy of the
    macro still goes to the isolated child, with its timeout."""
    from sensorkit.edit import add_sensor, fragment

    forked: list[Path] = []
    real = fragment.expand

    def spy(path: Path, *args: object, **kwargs: object) -> object:
        forked.append(path)
        return real(path, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(fragment, "expand", spy)
    monkeypatch.chdir(tmp_path)
    shutil.copyfile(ROBOTS / "rover.urdf", tmp_path / "rover.urdf")
    plan_add(AddRequest(tmp_path / "rover.urdf", "camera", "s", "base_link"))
    assert forked == []
    # a xacro robot: the add copies sensorkit's macro beside it, and uses it unchanged
    shutil.copytree(ROBOTS / "xacro_robot", tmp_path / "x")
    top = tmp_path / "x" / "robot.urdf.xacro"
    add_sensor(AddRequest(top, "camera", "s", "base_link"))
    assert forked == []
    (copy,) = (tmp_path / "x" / "sensors").glob("*.xacro")
    plan_add(AddRequest(top, "camera", "s2", "base_link"))  # the copy as shipped
    assert forked == []
    copy.write_text(copy.read_text() + "<!-- mine -->\n")  # now a user's modified copy
    plan_add(AddRequest(top, "camera", "s3", "base_link"))
    assert len(forked) == 1


def full(robot: Robot, load: list[Finding], part: Document, options: object) -> Verdict:
    return compare(robot, load, copy_document_with(robot.document, part), options)  # type: ignore[arg-type]


def outcome(req: AddRequest) -> tuple[str, list[str]]:
    try:
        result = plan_add(req)
    except EditRefused as exc:
        return f"refused: {exc}", []
    return "added", result.notes


def both(req: AddRequest, monkeypatch: pytest.MonkeyPatch) -> tuple[str, list[str]]:
    quick = outcome(req)
    with monkeypatch.context() as m:
        m.setattr(sensorkit.edit.add, "compare_added", full)
        slow = outcome(req)
    assert quick == slow
    return quick


def _robot(tmp_path: Path, body: str, name: str = "r.urdf") -> Path:
    path = tmp_path / name
    path.write_text(f'<?xml version="1.0"?>\n<robot name="r" {XACRO_NS}>\n{body}\n</robot>\n')
    return path


@pytest.fixture
def rover(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    shutil.copyfile(ROBOTS / "rover.urdf", tmp_path / "rover.urdf")
    return tmp_path / "rover.urdf"


@pytest.mark.parametrize(
    ("kind", "params"),
    [
        ("camera", {}),
        ("camera", {"near": "0"}),  # SK405: refused
        ("camera", {"sim": "gz", "gz_version": "harmonic"}),  # the target turns gz
        ("depth_camera", {}),
        ("lidar_2d", {"samples": "0"}),
        ("imu", {}),
        ("stereo_camera", {"sim": "none"}),
    ],
)
def test_same_verdict_on_the_rover(
    rover: Path, kind: str, params: dict[str, str], monkeypatch: pytest.MonkeyPatch
) -> None:
    both(AddRequest(rover, kind, "s", "base_link", params=params), monkeypatch)


def test_same_verdict_on_a_xacro_robot(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    shutil.copytree(ROBOTS / "xacro_robot", tmp_path / "x")
    path = tmp_path / "x" / "robot.urdf.xacro"
    assert both(AddRequest(path, "camera", "cam", "base_link"), monkeypatch)[0] == "added"
    both(AddRequest(path, "camera", "cam", "base_link", params={"near": "0"}), monkeypatch)


def test_node_name_clash_is_refused_alike(rover: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rover.write_text(
        rover.read_text().replace(
            "\n</robot>",
            '\n  <gazebo reference="base_link"><sensor name="o" type="camera">'
            '<plugin name="front_controller" filename="libgazebo_ros_camera.so">'
            "<camera_name>o</camera_name></plugin></sensor></gazebo>\n</robot>",
        )
    )
    verdict = both(AddRequest(rover, "camera", "front", "base_link"), monkeypatch)
    assert "SK604" in verdict[0]


@pytest.mark.parametrize(
    "body",
    [
        # SK301: a massless root drops everything, and its message lists the sensors
        '<link name="base"/><link name="a">{i}</link>'
        '<joint name="j" type="revolute"><parent link="base"/><child link="a"/>'
        '<limit effort="1" velocity="1"/></joint>',
        # SK203: the parent hangs in a second tree, whose message counts its links
        '<link name="base">{i}</link><link name="island">{i}</link>',
        # SK202/SK203: a joint already names the link the add creates
        '<link name="base">{i}</link><joint name="j" type="fixed"><parent link="s_link"/>'
        '<child link="base"/></joint>',
        # SK207: an old joint mimics the joint the add creates
        '<link name="base">{i}</link><link name="a">{i}</link>'
        '<joint name="j" type="revolute"><parent link="base"/><child link="a"/>'
        '<limit effort="1" velocity="1"/><mimic joint="s_joint"/></joint>',
        # SK105/SK201/SK205: old problems stay as they are
        '<link name="base">{i}<bogus/></link><link name="base"/>'
        '<joint name="k" type="hinge"><parent link="base"/><child link="base"/></joint>',
        # SK104: a missing mesh, and a package nobody has
        '<link name="base">{i}<visual><geometry><mesh filename="package://nopkg/m.stl"/>'
        '</geometry></visual><visual><geometry><mesh filename="gone.stl"/></geometry></visual>'
        "</link>",
    ],
)
def test_same_verdict_on_odd_robots(
    tmp_path: Path, body: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    path = _robot(tmp_path, body.format(i=INERTIAL))
    for parent in ("base", "island", "a"):  # each link the robot has
        if f'<link name="{parent}"' in path.read_text():
            both(AddRequest(path, "camera", "s", parent), monkeypatch)
            both(AddRequest(path, "lidar_2d", "s", parent, params={"sim": "gz"}), monkeypatch)
