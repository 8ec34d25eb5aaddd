"""The model against an independent implementation (yourdfpy) and the simulator's conversion rules."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from builders import inertial, joint, link
from conftest import CORPUS, NO_CORPUS, ROOT
from lxml import etree

from sensorkit.loading.xacro_expand import LOC_ATTR
from sensorkit.model import load_robot
from sensorkit.model.sdf import convert
from sensorkit.model.transforms import matrix_to_rpy, rpy_to_matrix, transform
from sensorkit.model.urdf import build_robot

ROBOTS = [
    pytest.param(p, marks=pytest.mark.skipif(not p.exists(), reason=NO_CORPUS), id=p.name)
    for p in (
        CORPUS / "ros-navigation__navigation2_tutorials/sam_bot_description/src/description/sam_bot_description.urdf",
        CORPUS / "ROBOTIS-GIT__turtlebot3/turtlebot3_description/urdf/turtlebot3_waffle.urdf",
        CORPUS / "linorobot__linorobot2/linorobot2_description/urdf/robots/2wd.urdf.xacro",
        CORPUS / "IntelRealSense__realsense-ros/realsense2_description/urdf/test_d435_multiple_cameras.urdf.xacro",
        ROOT / "tests/robots/workspace/src/rover_description/urdf/rover.urdf.xacro",
    )
]


@pytest.mark.parametrize("path", ROBOTS)
def test_forward_kinematics_matches_yourdfpy(path: Path, tmp_path: Path) -> None:
    yourdfpy = pytest.importorskip("yourdfpy", reason="yourdfpy is in the test extra")
    robot = load_robot(path).robot
    assert robot is not None
    root = etree.fromstring(etree.tostring(robot.document.root))
    for el in root.iter():
        if isinstance(el.tag, str):
            el.attrib.pop(LOC_ATTR, None)
    for mesh in root.iter("mesh"):  # yourdfpy need not find meshes to do kinematics
        mesh.set("filename", "missing.stl")
    out = tmp_path / "r.urdf"
    out.write_bytes(etree.tostring(root))
    ref = yourdfpy.URDF.load(str(out), load_meshes=False, build_collision_scene_graph=False, load_collision_meshes=False)
    base = robot.root()
    assert base is not None
    for lk in robot.links:
        ours = robot.T_world_link(lk.name)
        theirs = ref.get_transform(lk.name, base)
        np.testing.assert_allclose(ours, theirs, atol=1e-9, err_msg=lk.name)


def test_rpy_round_trip() -> None:
    rng = np.random.default_rng(1)
    for _ in range(200):
        rpy = rng.uniform([-np.pi, -np.pi / 2 + 1e-3, -np.pi], [np.pi, np.pi / 2 - 1e-3, np.pi])
        np.testing.assert_allclose(rpy_to_matrix(matrix_to_rpy(rpy_to_matrix(rpy))), rpy_to_matrix(rpy), atol=1e-12)
    T = transform((1, 2, 3), (0, 0, np.pi / 2))
    np.testing.assert_allclose(T @ [1, 0, 0, 1], [1, 3, 3, 1], atol=1e-12)


def _robot(text: str):  # type: ignore[no-untyped-def]
    from sensorkit.loading.document import Document

    return build_robot(Document(path=Path("mem.urdf"), root=etree.fromstring(text)))


def test_lumping_and_dropping() -> None:
    text = (
        '<robot name="r"><link name="base_footprint"/>' + link("base_link", inertial(5, 0.1))
        + joint("bj", "base_footprint", "base_link")
        + '<link name="arm"/>' + joint("aj", "base_link", "arm", type="continuous", extra='<axis xyz="0 0 1"/>')
        + link("hand") + joint("hj", "arm", "hand")
        + '<link name="opt"/>' + joint("oj", "base_link", "opt")
        + '<link name="kept"/>' + joint("kj", "base_link", "kept")
        + '<gazebo reference="kj"><preserveFixedJoint>true</preserveFixedJoint></gazebo></robot>'
    )
    conv = convert(_robot(text))
    assert conv.survivor("base_link") == "base_footprint" and conv.survivor("opt") == "base_footprint"
    assert conv.mass_of["base_footprint"] == 5
    # arm is massless but hand's mass is lumped into it: kept. 'kept' has a preserved joint and no mass: dropped.
    assert "arm" not in conv.dropped and conv.survivor("hand") == "arm"
    assert conv.dropped == {"kept": "kept"}


@pytest.mark.parametrize(
    ("value", "kept"),
    [("true", True), ("yes", True), ("YES", True), ("1", True), ("no", False), ("false", False)],
)
def test_preserve_fixed_joint_takes_what_sdformat_takes_as_true(value: str, kept: bool) -> None:
    """sdformat keeps a fixed joint for "true", "yes" (any case) and "1"
    (gazebosim/sdformat@sdformat14_14.9.0:src/parser_urdf.cc:1540-1549; the same in
    sdformat9 and sdformat12)."""
    for tag in ("preserveFixedJoint", "disableFixedJointLumping"):
        text = (
            '<robot name="r">' + link("base", inertial(1, 0.1)) + link("cam", inertial(0.1, 0.01))
            + joint("cj", "base", "cam")
            + f'<gazebo reference="cj"><{tag}>{value}</{tag}></gazebo></robot>'
        )
        assert convert(_robot(text)).is_lumped("cam") is not kept, (tag, value)


def test_massless_revolute_link_drops_its_subtree() -> None:
    text = (
        '<robot name="r">' + link("base", inertial(1, 0.1)) + '<link name="pan"/>'
        + joint("pj", "base", "pan", type="revolute", extra='<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>')
        + link("cam") + joint("cj", "pan", "cam", type="continuous", extra='<axis xyz="0 1 0"/>') + "</robot>"
    )
    conv = convert(_robot(text))
    assert conv.dropped == {"pan": "pan", "cam": "pan"}


def _tangle() -> str:
    """Leaves before their parents, a cycle, a cut-off branch, a duplicate name, a leaf of a
    leaf's sibling and rotated origins: every way world_positions can take."""
    return (
        '<robot name="r">'
        + '<link name="late_leaf"/>' + joint("lj", "mid", "late_leaf", xyz="0.3 -0.2 0.1", rpy="0.4 0.2 -0.3")
        + link("base", inertial(1, 0.1)) + '<link name="mid"/>'
        + joint("mj", "base", "mid", xyz="1 2 3", rpy="0.1 -0.7 1.3")
        + '<link name="leaf"/>' + joint("fj", "mid", "leaf", xyz="-0.5 0.25 2", rpy="1 2 3")
        + '<link name="leaf"/>'
        + '<link name="c1"/><link name="c2"/>' + joint("c1j", "c2", "c1") + joint("c2j", "c1", "c2")
        + '<link name="cut"/>' + joint("xj", "nowhere", "cut", xyz="5 5 5", rpy="0 0 1")
        + '<link name="cut_leaf"/>' + joint("xlj", "cut", "cut_leaf", xyz="0.1 0.2 0.3", rpy="0.3 0 0")
        + '<link name="cycle_leaf"/>' + joint("clj", "c1", "cycle_leaf")
        + "</robot>"
    )


@pytest.mark.parametrize("path", [pytest.param(None, id="tangle"), *ROBOTS])
def test_world_positions_are_the_world_poses_translations_bit_for_bit(path: Path | None) -> None:
    def fresh():  # type: ignore[no-untyped-def]
        if path is None:
            return _robot(_tangle())
        loaded = load_robot(path).robot
        assert loaded is not None
        return loaded

    positions = fresh().world_positions()
    poses = fresh()  # its own caches: each pose composed the long way
    names = [lk.name for lk in poses.links]
    assert set(positions) == set(names)
    for name in names:
        P = poses.world_pose(name)
        assert positions[name] == (None if P is None else P[9:12]), name
    if path is None:
        assert positions["c1"] is None and positions["cycle_leaf"] is None
        assert positions["cut_leaf"] is not None and positions["late_leaf"] is not None
