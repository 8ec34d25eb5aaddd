"""``sensorkit frames``: the TF tree as check_urdf prints it, with the link each sensor is on,
the frame_id it stamps, optical frames and the links Gazebo lumps away; text, json and dot.

Every test runs the command as a user would, in a fresh process.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT, run_check_urdf, run_cli

ACCEPTANCE = ROOT / "tests" / "robots" / "acceptance"
HARMONIC = (
    ROOT / "examples/harmonic_robot/harmonic_robot_description/urdf/harmonic_robot.urdf.xacro"
)
OPTICAL_RPY = "-1.5707963267948966 0 -1.5707963267948966"
INERTIAL = (
    '<inertial><mass value="0.1"/>'
    '<inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>'
)


def rover(
    sensor: str, *, joint: str = "fixed", optical_rpy: str = OPTICAL_RPY, extra: str = ""
) -> str:
    """base_link -> camera_link (``joint``; the sensor's link) -> camera_optical_frame."""
    limits = '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
    return (
        '<?xml version="1.0"?>\n<robot name="rover">\n'
        f'<link name="base_link">{INERTIAL}</link>\n'
        f'<link name="camera_link">{INERTIAL}</link>\n'
        f'<joint name="camera_joint" type="{joint}"><parent link="base_link"/>'
        '<child link="camera_link"/><origin xyz="0.2 0 0.3" rpy="0 0 0"/>'
        f"{limits if joint != 'fixed' else ''}</joint>\n"
        '<link name="camera_optical_frame"/>\n'
        '<joint name="camera_optical_joint" type="fixed"><parent link="camera_link"/>'
        '<child link="camera_optical_frame"/>'
        f'<origin xyz="0 0 0" rpy="{optical_rpy}"/></joint>\n'
        f'<gazebo reference="camera_link">{sensor}</gazebo>\n{extra}\n</robot>\n'
    )


CAMERA = (
    "<camera><horizontal_fov>1.047</horizontal_fov>"
    "<image><width>640</width><height>480</height></image>"
    "<clip><near>0.05</near><far>8</far></clip></camera>"
)


def classic_camera(frame: str | None = "camera_optical_frame") -> str:
    tag = f"<frame_name>{frame}</frame_name>" if frame else ""
    return (
        f'<sensor name="cam" type="camera"><update_rate>30</update_rate>{CAMERA}'
        f'<plugin name="c" filename="libgazebo_ros_camera.so">{tag}</plugin></sensor>'
    )


def frames(tmp_path: Path, text: str, *args: str) -> subprocess.CompletedProcess[str]:
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    return run_cli("frames", str(path), *args)


def line_of(out: str, frame: str) -> str:
    """The tree line of ``frame``."""
    (line,) = [
        ln
        for ln in out.splitlines()
        if re.match(rf"^\s*(root link: |child\(\d+\):  ){frame}\b", ln.strip())
    ]
    return line


def tree_shape(lines: list[str]) -> list[tuple[int, int, str]]:
    """``(depth, index, name)`` of each tree line, by check_urdf's layout: the root line
    (``root Link: NAME ...``), then ``child(I):  NAME`` four spaces deeper per level."""
    out = []
    for ln in lines:
        root = re.match(r"^root [Ll]ink: (\S+)", ln)
        if root:
            out.append((0, 1, root.group(1)))
            continue
        child = re.match(r"^((?:    )+)child\((\d+)\):  (\S+)", ln)
        if child:
            out.append((len(child.group(1)) // 4, int(child.group(2)), child.group(3)))
    return out


# --------------------------------------------------------------------------- text: the tree


@pytest.mark.parametrize("path", sorted(ACCEPTANCE.glob("*.urdf")), ids=lambda p: p.name)
def test_tree_has_check_urdfs_shape(path: Path) -> None:
    ours = run_cli("frames", str(path), "-q")
    theirs = run_check_urdf(path)
    assert ours.returncode == 0 and theirs.returncode == 0, ours.stderr + theirs.stderr
    shape = tree_shape(ours.stdout.splitlines())
    assert shape == tree_shape(theirs.stdout.splitlines())
    assert len(shape) >= 4


def test_root_line_counts_children_with_the_right_plural(tmp_path: Path) -> None:
    out = frames(tmp_path, rover(classic_camera()), "-q").stdout
    assert out.splitlines()[:2] == ["robot name is: rover", "root link: base_link has 1 child"]
    one = frames(tmp_path, '<robot name="r"><link name="a"/></robot>', "-q").stdout
    assert "root link: a has 0 children" in one


def test_sk605_tree_marks_sensor_links_stamps_optical_and_lumping() -> None:
    res = run_cli("frames", str(ACCEPTANCE / "sk605_fixed.urdf"))
    assert res.returncode == 0, res.stderr
    out = res.stdout
    assert line_of(out, "camera_link").endswith(
        "[sensor front_camera on it; lumped into base_footprint by Gazebo Classic]"
    )
    assert line_of(out, "rear_camera_optical_frame").endswith(
        "[frame_id of rear_camera; optical frame of rear_camera; "
        "lumped into base_footprint by Gazebo Classic]"
    )
    assert line_of(out, "base_footprint") == "root link: base_footprint has 1 child"
    assert (
        "sensor front_camera (camera) on camera_link: frame_id camera_optical_frame "
        "(<frame_name> of libgazebo_ros_camera.so)\n" in out
    )
    assert "5 lumped by Gazebo Classic, 2 optical" in res.stderr
    assert "lumped frames stay in TF" in res.stderr


# --------------------------------------------------------------------------- optical


def test_optical_link_at_the_camera_is_marked_and_a_camera_stamping_its_body_is_told(
    tmp_path: Path,
) -> None:
    out = frames(tmp_path, rover(classic_camera("camera_link")), "-q").stdout
    assert "optical frame of cam" in line_of(out, "camera_optical_frame")
    assert "frame_id of cam" in line_of(out, "camera_link")
    assert out.rstrip().endswith(
        "frame_id camera_link (<frame_name> of libgazebo_ros_camera.so); "
        "optical frame at the camera: camera_optical_frame"
    )


def test_near_miss_a_link_named_optical_but_rotated_wrong_is_not_marked(tmp_path: Path) -> None:
    res = frames(tmp_path, rover(classic_camera(), optical_rpy="0 0 0"))
    assert res.returncode == 0, res.stderr
    assert "optical frame of" not in res.stdout
    assert "no link is placed as the camera's optical frame" in res.stdout
    assert ", 0 optical)" in res.stderr


# --------------------------------------------------------------------------- lumping


def test_classic_default_frame_is_the_link_lumping_keeps(tmp_path: Path) -> None:
    out = frames(tmp_path, rover(classic_camera(None)), "-q").stdout
    assert "lumped into base_link by Gazebo Classic" in line_of(out, "camera_link")
    assert "frame_id of cam" in line_of(out, "base_link")
    assert "frame_id base_link (the default of libgazebo_ros_camera.so)" in out


def test_near_miss_nothing_lumped_with_preserve_fixed_joint_or_a_moving_joint(
    tmp_path: Path,
) -> None:
    keep = '<gazebo reference="camera_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
    res = frames(tmp_path, rover(classic_camera(None), extra=keep))
    assert "lumped into" not in line_of(res.stdout, "camera_link")
    assert "fixed joint camera_joint kept by Gazebo Classic (lumping disabled)" in line_of(
        res.stdout, "camera_link"
    )
    assert "frame_id camera_link (the default" in res.stdout
    revolute = frames(tmp_path, rover(classic_camera(None), joint="revolute"))
    assert "lumped into" not in line_of(revolute.stdout, "camera_link")
    assert "lumped into camera_link" in line_of(revolute.stdout, "camera_optical_frame")
    bare = frames(tmp_path, '<robot name="r"><link name="a"/></robot>')
    assert "0 lumped by Gazebo Classic" in bare.stderr
    assert "lumped frames stay in TF" not in bare.stderr


def test_lumping_is_named_per_target(tmp_path: Path) -> None:
    out = frames(tmp_path, rover(classic_camera()), "--target", "harmonic", "-q").stdout
    assert "lumped into base_link by Gazebo Harmonic" in line_of(out, "camera_link")


# --------------------------------------------------------------------------- plugin frames


def test_gz_default_frame_is_the_scoped_name_and_no_frame_of_the_tree(tmp_path: Path) -> None:
    sensor = f'<sensor name="cam" type="camera">{CAMERA}</sensor>'
    out = frames(tmp_path, rover(sensor), "--target", "harmonic", "-q").stdout
    assert (
        "sensor cam (camera) on camera_link: frame_id rover::base_link::cam "
        "(Gazebo Harmonic's default, the scoped name), which is no frame of the tree"
    ) in out
    assert "frame_id of" not in out


def test_gz_optical_frame_id_stamps_the_images(tmp_path: Path) -> None:
    cam = CAMERA.replace(
        "</camera>", "<optical_frame_id>camera_optical_frame</optical_frame_id></camera>"
    )
    sensor = (
        f'<sensor name="cam" type="camera"><gz_frame_id>camera_link</gz_frame_id>{cam}</sensor>'
    )
    out = frames(tmp_path, rover(sensor), "--target", "harmonic", "-q").stdout
    assert (
        "frame_id camera_link (<gz_frame_id>), images camera_optical_frame (<optical_frame_id>)"
        in out
    )
    assert "frame_id of cam" in line_of(out, "camera_optical_frame")


def test_sensor_without_plugin_stamps_nothing(tmp_path: Path) -> None:
    out = frames(tmp_path, rover('<sensor name="imu" type="imu"/>'), "-q").stdout
    assert "sensor imu (imu) on camera_link: stamps nothing (no plugin publishes it to ROS)" in out


def test_example_robot_frames_match_what_topics_lists() -> None:
    res = run_cli("frames", str(HARMONIC), "-f", "json", "-q")
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)
    topics = json.loads(run_cli("topics", str(HARMONIC), "-f", "json", "-q").stdout)
    by_sensor: dict[str, set[str]] = {}
    for t in topics["topics"]:
        by_sensor.setdefault(t["sensor"], set()).add(t["frame_id"])
    ours = {s["name"]: {f["frame"] for f in s["frame_ids"]} for s in doc["sensors"]}
    assert ours == by_sensor


# --------------------------------------------------------------------------- json


def test_json_document(tmp_path: Path) -> None:
    res = frames(tmp_path, rover(classic_camera()), "--format", "json")
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)
    assert set(doc) == {
        "robot",
        "target",
        "target_reason",
        "simulator",
        "roots",
        "frames",
        "unreached",
        "sensors",
    }
    assert doc["roots"] == ["base_link"] and doc["simulator"] == "Gazebo Classic"
    assert [f["name"] for f in doc["frames"]] == [
        "base_link",
        "camera_link",
        "camera_optical_frame",
    ]
    optical = doc["frames"][2]
    assert optical == {
        "name": "camera_optical_frame",
        "parent": "camera_link",
        "joint": "camera_optical_joint",
        "joint_type": "fixed",
        "children": [],
        "sensors": [],
        "stamped_by": ["cam"],
        "optical_for": ["cam"],
        "lumped_into": "base_link",
        "lumping_disabled": False,
        "dropped_by": None,
        "missing": False,
    }
    assert doc["sensors"] == [
        {
            "name": "cam",
            "type": "camera",
            "reference": "camera_link",
            "link": "camera_link",
            "plugin": "libgazebo_ros_camera.so",
            "frame_ids": [
                {
                    "frame": "camera_optical_frame",
                    "data": "all",
                    "from": "frame_name",
                    "in_tree": True,
                }
            ],
            "note": None,
            "stamps_nothing": False,  # added (issue 35 item 9): only true when nothing publishes it
            "optical_frame": "camera_optical_frame",
        }
    ]


def test_json_keeps_a_missing_parent_and_a_cycle(tmp_path: Path) -> None:
    text = (
        '<robot name="r"><link name="a"/><link name="b"/><link name="c"/>'
        '<joint name="j" type="fixed"><parent link="ghost"/><child link="a"/></joint>'
        '<joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint>'
        '<joint name="cb" type="fixed"><parent link="c"/><child link="b"/></joint></robot>'
    )
    res = frames(tmp_path, text, "-f", "json")
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)
    assert doc["roots"] == ["ghost"]
    assert doc["frames"][0]["missing"] is True
    assert [f["name"] for f in doc["unreached"]] == ["b", "c"]
    text_out = frames(tmp_path, text, "-q").stdout
    assert (
        "root link: ghost has 1 child  [no <link> of this name: a joint names it as parent]"
        in text_out
    )
    assert "on a cycle of joints, under no root: b, c" in text_out


# --------------------------------------------------------------------------- dot

DOT_ID = r'"(?:[^"\\]|\\.)*"'
DOT_ATTRS = rf"\[(?:\w+=(?:{DOT_ID}|\w+)(?:, )?)+\]"
DOT_LINE = re.compile(
    rf"^  (?:{DOT_ID} {DOT_ATTRS};|{DOT_ID} -> {DOT_ID} {DOT_ATTRS};|label={DOT_ID};"
    r"|node \[shape=\w+\];)$"
)


def strict_dot(text: str) -> tuple[set[str], set[tuple[str, str, str]]]:
    """Nodes and ``(parent, child, label)`` edges of the digraph, each line checked against
    the DOT grammar for the statements ``frames_dot`` writes."""
    lines = text.splitlines()
    assert re.fullmatch(rf"digraph {DOT_ID} \{{", lines[0]) and lines[-1] == "}"
    nodes, edges = set(), set()
    for ln in lines[1:-1]:
        assert DOT_LINE.match(ln), ln
        ids = re.findall(DOT_ID, ln)
        if " -> " in ln:
            edges.add((ids[0][1:-1], ids[1][1:-1], ids[2][1:-1]))
        elif ln.startswith('  "'):
            nodes.add(ids[0][1:-1])
    return nodes, edges


def test_dot_is_a_digraph_of_frames_with_joint_labelled_edges(tmp_path: Path) -> None:
    res = frames(tmp_path, rover(classic_camera()), "-f", "dot")
    assert res.returncode == 0, res.stderr
    nodes, edges = strict_dot(res.stdout)
    assert nodes == {"base_link", "camera_link", "camera_optical_frame"}
    assert edges == {
        ("base_link", "camera_link", "camera_joint (fixed)"),
        ("camera_link", "camera_optical_frame", "camera_optical_joint (fixed)"),
    }
    assert re.search(
        r'"camera_optical_frame" \[label="camera_optical_frame\\n.*optical frame of cam', res.stdout
    )


def test_dot_escapes_quotes_and_backslashes_in_names(tmp_path: Path) -> None:
    text = (
        '<robot name="q&quot;r"><link name="a&quot;b"/><link name="c\\d"/>'
        '<joint name="j" type="fixed"><parent link="a&quot;b"/><child link="c\\d"/></joint></robot>'
    )
    res = frames(tmp_path, text, "-f", "dot")
    assert res.returncode == 0, res.stderr
    nodes, edges = strict_dot(res.stdout)
    assert nodes == {'a\\"b', "c\\\\d"}
    assert edges == {('a\\"b', "c\\\\d", "j (fixed)")}


@pytest.mark.parametrize("path", [HARMONIC, ACCEPTANCE / "sk605_fixed.urdf"], ids=lambda p: p.name)
def test_graphviz_reads_the_dot(path: Path, tmp_path: Path) -> None:
    dot = shutil.which("dot")
    if dot is None:
        pytest.skip("graphviz's dot is not installed")
    res = run_cli("frames", str(path), "-f", "dot", "-q")
    assert res.returncode == 0, res.stderr
    strict_dot(res.stdout)
    # -Tcanon: graphviz parses and prints the graph back; each frame is a node of it
    canon = subprocess.run(
        [dot, "-Tcanon"], input=res.stdout, capture_output=True, text=True, check=False, timeout=60
    )
    assert canon.returncode == 0 and not canon.stderr, canon.stderr
    edges = re.findall(r"^\s*(\w+) -> (\w+)", canon.stdout, re.MULTILINE)
    assert len(edges) == res.stdout.count(" -> ") >= 4


# --------------------------------------------------------------------------- errors and README


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (["nope.urdf"], "sensorkit: nope.urdf: no such file"),
        (["ROBOT", "--format", "svg"], "sensorkit: --format 'svg': use text, json, dot"),
        (["ROBOT", "--target", "gazebo"], "sensorkit: unknown target 'gazebo'"),
        (["ROBOT", "--arg", "x"], "sensorkit: --arg 'x': expected NAME:=VALUE"),
        (["BROKEN"], "sensorkit: "),
    ],
)
def test_bad_input_is_one_line_and_exit_2(tmp_path: Path, args: list[str], said: str) -> None:
    (tmp_path / "robot.urdf").write_text(rover(classic_camera()))
    (tmp_path / "broken.urdf").write_text("<robot name='r'><link name='a'></robot>")
    named = {"ROBOT": "robot.urdf", "BROKEN": "broken.urdf"}
    res = run_cli("frames", *[named.get(a, a) for a in args], cwd=tmp_path)
    assert res.returncode == 2
    assert res.stdout == ""
    assert res.stderr.startswith(said) and res.stderr.count("\n") == 1, res.stderr


def test_docs_example_is_what_frames_prints() -> None:
    readme = (ROOT / "docs" / "topics-frames.md").read_text()  # moved from the README (issue 38)
    cmd = "$ sensorkit frames tests/robots/acceptance/sk605_fixed.urdf\n"
    assert cmd in readme
    shown = readme.split(cmd, 1)[1].split("```", 1)[0]
    res = run_cli("frames", "tests/robots/acceptance/sk605_fixed.urdf", cwd=ROOT)
    assert res.stdout + res.stderr == shown


def test_loading_options_are_topics_own(tmp_path: Path) -> None:
    """-q, --color, - (stdin) with --stdin-filename, and the settings file's target."""
    path = tmp_path / "robot.urdf"
    path.write_text(rover(classic_camera()))
    quiet = run_cli("frames", str(path), "-q", "--color", "never")
    assert quiet.returncode == 0 and quiet.stderr == "" and "root link: base_link" in quiet.stdout
    (tmp_path / "sensorkit.toml").write_text('target = "jetty"\n')
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", "frames", "-", "--stdin-filename", "robot.urdf"],
        input=path.read_text(),
        capture_output=True,
        text=True,
        check=False,
        cwd=tmp_path,
        timeout=120,
    )
    assert res.returncode == 0, res.stderr
    assert "lumped into base_link by Gazebo Jetty" in line_of(res.stdout, "camera_link")
    assert "(target jetty, chosen with sensorkit.toml)" in res.stderr
    assert run_cli("frames", str(path), "--color", "sometimes").returncode == 2
