"""``sensorkit new`` writes what a ROS 2 user opens first: ``launch/display.launch.py``
(robot_state_publisher, joint_state_publisher(_gui), rviz2) and ``rviz/<robot>.rviz`` with a
display for every sensor topic ``sensorkit topics`` lists."""

from __future__ import annotations

import ast
import json
from pathlib import Path
from typing import Any

import pytest
import yaml
from lxml import etree
from typer.testing import CliRunner

from sensorkit.cli import app
from sensorkit.generate import new_package

# The display class of each message type, read from ros2/rviz
# rviz_default_plugins/plugins_description.xml (humble 9b35482: each <class> names its
# <message_type>). sensorkit's own table (sensorkit.knowledge.rviz) must agree.
DISPLAY_OF = {
    "sensor_msgs/msg/Image": "rviz_default_plugins/Image",
    "sensor_msgs/msg/LaserScan": "rviz_default_plugins/LaserScan",
    "sensor_msgs/msg/PointCloud2": "rviz_default_plugins/PointCloud2",
}
# Message types RViz2 has no display for in rviz_default_plugins on every release the
# targets pair with: no Imu display anywhere; CameraInfo only from Jazzy (ros2/rviz#1166).
NO_DISPLAY = {"sensor_msgs/msg/Imu", "sensor_msgs/msg/CameraInfo"}

SENSORS = """\
sensors:
  - {type: camera, name: front_camera, xyz: [0.25, 0, 0.1]}
  - {type: depth_camera, name: rgbd, xyz: [0.2, 0, 0.15], rpy: [0, 0.2, 0]}
  - {type: stereo_camera, name: stereo, xyz: [0.2, 0, 0.3]}
  - {type: lidar_2d, name: laser, xyz: [0.15, 0, 0.2]}
  - {type: lidar_3d, name: lidar, xyz: [0, 0, 0.35]}
  - {type: imu, name: imu, xyz: [0, 0, 0.02]}
"""
CASES = {
    "classic": "name: classic_bot\nsim: classic\n" + SENSORS,
    "harmonic": "name: gz_bot\nbase: skid_steer\nsim: gz\ngz_version: harmonic\n" + SENSORS,
    "fortress-ns": "name: ns_bot\nsim: gz\ngz_version: fortress\nnamespace: robot1\n" + SENSORS,
    "classic-ns": "name: cns_bot\nsim: classic\nnamespace: team/robot2\n" + SENSORS,
    "none": "name: bare_bot\nsim: none\n" + SENSORS,
}


def generate(tmp_path: Path, text: str) -> tuple[Path, str, list[str]]:
    spec = tmp_path / "robot.yaml"
    spec.write_text(text)
    out = tmp_path / "pkg"
    result = new_package(spec, out)
    return out, result.spec.name, result.files


def sensorkit_topics(xacro: Path) -> list[dict[str, Any]]:
    """What ``sensorkit topics FILE`` lists (JSON), the one source for topic names."""
    result = CliRunner().invoke(app, ["topics", str(xacro), "--format", "json"])
    assert result.exit_code == 0, result.stderr
    topics: list[dict[str, Any]] = json.loads(result.stdout)["topics"]
    return topics


def calls(tree: ast.AST, name: str) -> list[ast.Call]:
    return [
        node
        for node in ast.walk(tree)
        if isinstance(node, ast.Call)
        and (
            (isinstance(node.func, ast.Name) and node.func.id == name)
            or (isinstance(node.func, ast.Attribute) and node.func.attr == name)
        )
    ]


def keyword(call: ast.Call, name: str) -> ast.expr | None:
    return next((k.value for k in call.keywords if k.arg == name), None)


def constants(tree: ast.AST) -> dict[str, str]:
    """Module-level ``NAME = "text"`` assignments."""
    out: dict[str, str] = {}
    for node in ast.iter_child_nodes(tree):
        if (
            isinstance(node, ast.Assign)
            and len(node.targets) == 1
            and isinstance(node.targets[0], ast.Name)
            and isinstance(node.value, ast.Constant)
            and isinstance(node.value.value, str)
        ):
            out[node.targets[0].id] = node.value.value
    return out


def launch_config_name(expr: ast.expr | None) -> str | None:
    """``X`` of ``IfCondition(LaunchConfiguration("X"))`` and the like."""
    if not isinstance(expr, ast.Call) or not expr.args:
        return None
    inner = expr.args[0]
    if isinstance(inner, ast.Call) and calls(inner, "LaunchConfiguration"):
        arg = inner.args[0]
        return arg.value if isinstance(arg, ast.Constant) else None
    return None


def rviz_displays(doc: dict[str, Any]) -> list[dict[str, Any]]:
    displays: list[dict[str, Any]] = doc["Visualization Manager"]["Displays"]
    return displays


def links_of(out: Path, robot: str) -> set[str]:
    from sensorkit.loading.packages import PackageResolver
    from sensorkit.loading.xacro_expand import expand

    outcome = expand(
        out / "urdf" / f"{robot}.urdf.xacro", {}, PackageResolver(use_environment=False)
    )
    assert outcome.xml is not None, outcome.message
    root = etree.fromstring(outcome.xml.encode())
    return {link.get("name") for link in root.findall("link")}


@pytest.mark.parametrize("case", list(CASES))
def test_display_launch_starts_the_three_nodes_with_the_package_config(
    tmp_path: Path, case: str
) -> None:
    out, robot, files = generate(tmp_path, CASES[case])
    assert "launch/display.launch.py" in files
    assert f"rviz/{robot}.rviz" in files
    launch = out / "launch" / "display.launch.py"
    tree = ast.parse(launch.read_text(), str(launch))
    consts = constants(tree)
    assert consts["ROBOT"] == robot

    nodes = {}
    for call in calls(tree, "Node"):
        package = keyword(call, "package")
        assert isinstance(package, ast.Constant), ast.dump(call)
        nodes[package.value] = call
    assert set(nodes) == {
        "robot_state_publisher",
        "joint_state_publisher",
        "joint_state_publisher_gui",
        "rviz2",
    }
    # gui:=true runs the slider window, gui:=false the plain publisher; never both.
    gui = nodes["joint_state_publisher_gui"]
    plain = nodes["joint_state_publisher"]
    assert calls(keyword(gui, "condition"), "IfCondition")  # type: ignore[arg-type]
    assert calls(keyword(plain, "condition"), "UnlessCondition")  # type: ignore[arg-type]
    assert launch_config_name(keyword(gui, "condition")) == "gui"
    assert launch_config_name(keyword(plain, "condition")) == "gui"

    declared = {}
    for call in calls(tree, "DeclareLaunchArgument"):
        first = call.args[0]
        assert isinstance(first, ast.Constant)
        declared[first.value] = call
    assert {"sim", "gui", "use_sim_time", "rviz_config"} <= set(declared)
    default = keyword(declared["sim"], "default_value")
    assert isinstance(default, ast.Constant) and default.value == "none"  # as description.launch

    # rviz2 -d the package's rviz/<robot>.rviz (the rviz_config argument's default).
    rviz_args = keyword(nodes["rviz2"], "arguments")
    assert isinstance(rviz_args, ast.List)
    assert isinstance(rviz_args.elts[0], ast.Constant) and rviz_args.elts[0].value == "-d"
    config = rviz_args.elts[1]
    assert isinstance(config, ast.Call) and calls(config, "LaunchConfiguration")
    assert isinstance(config.args[0], ast.Constant) and config.args[0].value == "rviz_config"
    path = keyword(declared["rviz_config"], "default_value")
    assert isinstance(path, ast.Call) and calls(path, "join")
    parts = path.args[1:]
    assert isinstance(parts[0], ast.Constant) and parts[0].value == "rviz"
    assert isinstance(parts[1], ast.BinOp) and isinstance(parts[1].left, ast.Name)
    assert isinstance(parts[1].right, ast.Constant)
    rel = f"{parts[0].value}/{consts[parts[1].left.id]}{parts[1].right.value}"
    assert rel == f"rviz/{robot}.rviz"
    assert (out / rel).is_file()

    # robot_state_publisher gets the xacro of the package's robot with sim:=<sim>.
    text = launch.read_text()
    assert '"urdf", ROBOT + ".urdf.xacro"' in text
    assert 'Command(["xacro ", xacro_file, " sim:=", LaunchConfiguration("sim")])' in text


@pytest.mark.parametrize("case", list(CASES))
def test_rviz_config_shows_every_sensor_topic_sensorkit_topics_lists(
    tmp_path: Path, case: str
) -> None:
    out, robot, _ = generate(tmp_path, CASES[case])
    doc = yaml.safe_load((out / "rviz" / f"{robot}.rviz").read_text())
    displays = rviz_displays(doc)
    for d in displays:
        assert {"Class", "Name", "Enabled", "Value"} <= set(d), d
        assert d["Enabled"] is True and d["Value"] is True
    names = [d["Name"] for d in displays]
    assert len(names) == len(set(names)), names

    by_class = {d["Class"]: d for d in displays}
    assert "rviz_default_plugins/Grid" in by_class
    assert "rviz_default_plugins/TF" in by_class
    model = by_class["rviz_default_plugins/RobotModel"]
    assert model["Description Source"] == "Topic"
    ns = yaml.safe_load(CASES[case]).get("namespace", "")
    want = f"/{ns}/robot_description" if ns else "/robot_description"
    assert model["Description Topic"]["Value"] == want
    # robot_state_publisher publishes it transient local: a late RViz still gets it.
    assert model["Description Topic"]["Durability Policy"] == "Transient Local"

    frame = doc["Visualization Manager"]["Global Options"]["Fixed Frame"]
    assert frame in links_of(out, robot)
    assert frame == "base_footprint"  # both shipped bases have one

    sensor_displays = {d["Topic"]["Value"]: d for d in displays if "Topic" in d}
    if case == "none":
        assert sensor_displays == {}
        return
    listed = sensorkit_topics(out / "urdf" / f"{robot}.urdf.xacro")
    want_shown: dict[str, str] = {}
    for t in listed:
        if t["topic"] is None or t["direction"] != "publishes":
            continue  # not bridged to ROS
        if t["type"] in NO_DISPLAY:
            assert t["topic"] not in sensor_displays
            continue
        assert t["type"] in DISPLAY_OF, t
        want_shown[t["topic"]] = DISPLAY_OF[t["type"]]
    assert {k: d["Class"] for k, d in sensor_displays.items()} == want_shown
    assert set(want_shown.values()) == set(DISPLAY_OF.values())  # all three kinds exercised
    for topic, d in sensor_displays.items():
        assert d["Topic"] == {
            "Depth": 5,
            "Durability Policy": "Volatile",
            "History Policy": "Keep Last",
            "Reliability Policy": "Best Effort",  # receives from reliable publishers too
            "Value": topic,
        }
    if ns:
        assert all(t.startswith(f"/{ns}/") for t in sensor_displays)
    # The configuration says which topics it leaves out, and why.
    head = (out / "rviz" / f"{robot}.rviz").read_text().split("\nPanels:")[0]
    assert "sensor_msgs/msg/Imu" in head and "sensor_msgs/msg/CameraInfo" in head


def test_sensorkit_tables_agree_with_rviz() -> None:
    from sensorkit.knowledge.rviz import NO_RVIZ_DISPLAY, RVIZ_DISPLAYS

    assert {k: RVIZ_DISPLAYS[k] for k in DISPLAY_OF} == DISPLAY_OF
    assert set(NO_RVIZ_DISPLAY) == NO_DISPLAY
    assert not set(RVIZ_DISPLAYS) & NO_DISPLAY
    assert all(v.startswith("rviz_default_plugins/") for v in RVIZ_DISPLAYS.values())


@pytest.mark.parametrize("case", ["classic", "harmonic", "none"])
def test_package_installs_rviz_and_depends_on_what_display_runs(tmp_path: Path, case: str) -> None:
    out, robot, _ = generate(tmp_path, CASES[case])
    pkg = etree.parse(str(out / "package.xml")).getroot()
    deps = {d.text for d in pkg.findall("exec_depend")}
    assert {
        "robot_state_publisher",
        "joint_state_publisher",
        "joint_state_publisher_gui",
        "rviz2",
        "xacro",
    } <= deps
    cmake = (out / "CMakeLists.txt").read_text()
    installed = cmake.split("DIRECTORY", 1)[1].split("DESTINATION", 1)[0].split()
    assert "rviz" in installed and "launch" in installed
    readme = (out / "README.md").read_text()
    package = pkg.findtext("name")
    assert f"ros2 launch {package} display.launch.py" in readme
    assert f"rviz/{robot}.rviz" in readme
    if case != "none":
        assert f"rviz2 -d install/{package}/share/{package}/rviz/{robot}.rviz" in readme


def test_rviz_scalars_read_back_as_written() -> None:
    from sensorkit.generate.rviz import _scalar

    for text in ["", "yes", "no", "on", "true", "null", "1.5", "a: b", "#x", "- x", "x ", "~"]:
        assert yaml.safe_load(f"k: {_scalar(text)}") == {"k": text}, text
    assert _scalar("160; 160; 164") == "160; 160; 164"
    assert _scalar("<Fixed Frame>") == "<Fixed Frame>"
    assert _scalar("/robot1/laser/scan") == "/robot1/laser/scan"
