"""add-* inside a package keeps it consistent (issue 12): the simulator comes from the robot,
the call follows the package's ``sim`` argument, and the bridge, README and robot.yaml
gain the sensor, so ``sensorkit new --force`` afterwards regenerates the same package."""

from __future__ import annotations

import json
import os
import re
import shutil
from pathlib import Path

import pytest
import yaml
from lxml import etree
from typer.testing import CliRunner

import sensorkit.edit.add
from sensorkit.base.errors import WriteFailed
from sensorkit.cli import app
from sensorkit.edit import AddRequest, add_sensor
from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.xacro_expand import expand_in_process

GZ_YAML = """\
# a test robot
name: bot
base: diff_drive
sim: gz
gz_version: harmonic
sensors:
  - type: lidar_2d
    name: laser
    xyz: [0, 0, 0.2]
"""
CLASSIC_YAML = GZ_YAML.replace("sim: gz", "sim: classic")


def cli(*args: object) -> tuple[int, str, str]:
    result = CliRunner().invoke(app, [str(a) for a in args])
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


def snapshot(folder: Path) -> dict[str, bytes]:
    return {
        p.relative_to(folder).as_posix(): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


def make_package(tmp: Path, text: str) -> tuple[Path, Path]:
    spec = tmp / "robot.yaml"
    spec.write_text(text)
    pkg = tmp / "bot_description"
    code, _, err = cli("new", spec, "-o", pkg)
    assert code == 0, err
    return spec, pkg


@pytest.fixture(scope="module")
def gz_package(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    return make_package(tmp_path_factory.mktemp("gz"), GZ_YAML)


def copy_of(made: tuple[Path, Path], tmp: Path) -> tuple[Path, Path]:
    spec, pkg = made
    shutil.copy2(spec, tmp / spec.name)
    shutil.copytree(pkg, tmp / pkg.name)
    return tmp / spec.name, tmp / pkg.name


def xacro_robot(path: Path, **args: str) -> etree._Element:
    """``path`` expanded by the real xacro library."""
    outcome = expand_in_process(path, dict(args), PackageResolver(use_environment=False))
    assert outcome.xml is not None, outcome.message
    return etree.fromstring(outcome.xml.encode("utf-8"))


def bridge_of(path: Path) -> list[dict[str, str]]:
    loaded = yaml.safe_load(path.read_text())
    assert isinstance(loaded, list)
    return loaded


def test_camera_without_sim_in_a_gz_package(gz_package: tuple[Path, Path], tmp_path: Path) -> None:
    spec, pkg = copy_of(gz_package, tmp_path)
    xacro_file = pkg / "urdf" / "bot.urdf.xacro"
    before = snapshot(pkg)
    old_spec = spec.read_bytes()
    code, _, err = cli("add-camera", xacro_file, "--name", "cam", "--parent", "base_link",
                       "--xyz", 0.2, 0, 0.1, "--width", 320)  # fmt: skip
    assert code == 0, err
    assert 'sim="$(arg sim)" as the robot\'s other sensors (it gives gz here)' in err
    assert re.search(r"updated \S*robot\.yaml \(sensor appended\)", err), err
    after = snapshot(pkg)

    # the call follows the package's switch, as the other sensors' calls
    text = xacro_file.read_text()
    call = text[text.index("<xacro:sensorkit_camera") :]
    assert 'sim="$(arg sim)"' in call and 'sim="gz"' not in text

    # sim:=gz: the camera is there and bridged, as `sensorkit export` bridges it
    robot = xacro_robot(xacro_file, sim="gz")
    sensors = {s.get("name"): s for s in robot.iter("sensor")}
    assert sensors["cam"].get("type") == "camera"
    bridge = bridge_of(pkg / "config" / "bridge.yaml")
    cam_entries = [e for e in bridge if e["ros_topic_name"].startswith("cam/")]
    assert {e["ros_topic_name"] for e in cam_entries} == {"cam/image_raw", "cam/camera_info"}
    assert after["config/bridge.yaml"].startswith(before["config/bridge.yaml"])  # an append
    out = tmp_path / "export"
    code, _, err = cli("export", xacro_file, "--out", out)
    assert code == 0, err
    exported = [e for e in bridge_of(out / "bridge.yaml") if e["ros_topic_name"].startswith("cam/")]
    assert exported == cam_entries

    # sim:=none: the real robot's description carries no simulated sensor
    bare = xacro_robot(xacro_file, sim="none")
    assert not list(bare.iter("sensor")) and not list(bare.iter("plugin"))
    assert "cam_link" in {link.get("name") for link in bare.iter("link")}

    # validate reports nothing
    code, out_text, err = cli("validate", xacro_file, "--format", "json")
    assert code == 0, err
    report = json.loads(out_text)
    assert report["findings"] == [], report["findings"]

    # robot.yaml gained the sensor (an append) and README its row
    assert spec.read_bytes().startswith(old_spec)
    assert "| cam | camera | base_link | 0.2 0 0.1 | 0 0 0 |" in (pkg / "README.md").read_text()

    # sensorkit new --force from the updated robot.yaml: byte for byte the same package
    regenerated = tmp_path / "regenerated"
    code, _, err = cli("new", spec, "-o", regenerated)
    assert code == 0, err
    assert snapshot(regenerated) == after
    code, _, err = cli("new", spec, "-o", pkg, "--force")
    assert code == 0, err
    assert snapshot(pkg) == after
    assert os.access(pkg / "scripts" / "save_frames.py", os.X_OK)


def test_classic_package_picks_classic(tmp_path: Path) -> None:
    spec, pkg = make_package(tmp_path, CLASSIC_YAML)
    xacro_file = pkg / "urdf" / "bot.urdf.xacro"
    code, _, err = cli("add-camera", xacro_file, "--name", "cam", "--parent", "base_link")
    assert code == 0, err
    assert "it gives classic here" in err
    robot = xacro_robot(xacro_file)
    plugins = {p.get("filename") for p in robot.iter("plugin")}
    assert "libgazebo_ros_camera.so" in plugins
    assert not (pkg / "config").exists()  # no bridge on Gazebo Classic
    code, _, err = cli("validate", xacro_file, "--fail-on", "warning")
    assert code == 0, err
    after = snapshot(pkg)
    code, _, err = cli("new", spec, "-o", pkg, "--force")
    assert code == 0, err
    assert snapshot(pkg) == after


def test_diff_shows_every_file_and_writes_nothing(
    gz_package: tuple[Path, Path], tmp_path: Path
) -> None:
    spec, pkg = copy_of(gz_package, tmp_path)
    before, old_spec = snapshot(pkg), spec.read_bytes()
    code, out, err = cli("add-camera", pkg / "urdf" / "bot.urdf.xacro", "--name", "cam",
                         "--parent", "base_link", "--diff")  # fmt: skip
    assert code == 0, err
    assert snapshot(pkg) == before and spec.read_bytes() == old_spec
    changed = {line.split("/", 1)[1] for line in out.splitlines() if line.startswith("+++ b/")}
    rel = os.path.relpath(pkg)
    for name in ("urdf/bot.urdf.xacro", "config/bridge.yaml", "README.md", "rviz/bot.rviz",
                 "urdf/sensors/camera.urdf.xacro", "launch/save_frames.launch.py"):  # fmt: skip
        assert any(c.endswith(f"{Path(rel).name}/{name}") for c in changed), (name, changed)
    assert any(c.endswith("robot.yaml") for c in changed)


def test_literal_sim_in_a_generated_package_is_refused(
    gz_package: tuple[Path, Path], tmp_path: Path
) -> None:
    spec, pkg = copy_of(gz_package, tmp_path)
    before, old_spec = snapshot(pkg), spec.read_bytes()
    code, _, err = cli("add-camera", pkg / "urdf" / "bot.urdf.xacro", "--name", "cam",
                       "--parent", "base_link", "--sim", "classic")  # fmt: skip
    assert code == 2
    assert "--sim classic" in err and "sim argument" in err
    assert snapshot(pkg) == before and spec.read_bytes() == old_spec


def test_a_failed_write_puts_every_file_back(
    gz_package: tuple[Path, Path], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    spec, pkg = copy_of(gz_package, tmp_path)
    before, old_spec = snapshot(pkg), spec.read_bytes()
    real = sensorkit.edit.add.write_bytes

    def failing(path: Path, data: bytes, **kw: object) -> None:
        if path.name == "robot.yaml" and data != old_spec:  # the last write of the add
            msg = f"{path}: could not be written (No space left on device); it is unchanged"
            raise WriteFailed(msg)
        real(path, data, **kw)  # type: ignore[arg-type]

    monkeypatch.setattr(sensorkit.edit.add, "write_bytes", failing)
    req = AddRequest(pkg / "urdf" / "bot.urdf.xacro", "camera", "cam", "base_link")
    with pytest.raises(WriteFailed):
        add_sensor(req)
    assert snapshot(pkg) == before and spec.read_bytes() == old_spec
    assert not (pkg / "scripts").exists()


PLAIN = """\
<?xml version="1.0"?>
<robot name="plain" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>
"""


def test_plain_robot_keeps_todays_behaviour(tmp_path: Path) -> None:
    robot = tmp_path / "plain.urdf.xacro"
    robot.write_text(PLAIN)
    code, _, err = cli("add-camera", robot, "--name", "cam", "--parent", "base_link")
    assert code == 0, err
    assert "sim classic, the macro's default" in err and "--sim gz" in err
    assert sorted(
        p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*") if p.is_file()
    ) == [
        "plain.urdf.xacro",
        "sensors/camera.urdf.xacro",
    ]
    assert 'sim="' not in robot.read_text()  # the macro's default, as before
    plugins = {p.get("filename") for p in xacro_robot(robot).iter("plugin")}
    assert plugins == {"libgazebo_ros_camera.so"}
    # its second sensor follows the first: classic, from what --target auto sees
    code, _, err = cli("add-imu", robot, "--name", "imu", "--parent", "base_link")
    assert code == 0, err
    assert "sim classic from the robot's other plugins and sensors" in err


def test_gz_robot_outside_a_package_takes_gz(tmp_path: Path) -> None:
    robot = tmp_path / "plain.urdf.xacro"
    robot.write_text(PLAIN)
    code, _, err = cli("add-lidar", robot, "--name", "lidar", "--parent", "base_link",
                       "--sim", "gz", "--gz-version", "fortress")  # fmt: skip
    assert code == 0, err
    code, _, err = cli("add-camera", robot, "--name", "cam", "--parent", "base_link")
    assert code == 0, err
    assert "sim gz (fortress) from the robot's other plugins and sensors" in err
    tail = robot.read_text().split("<xacro:sensorkit_camera", 1)[1]
    assert 'sim="gz"' in tail and 'gz_version="fortress"' in tail
    assert {p.name for p in tmp_path.iterdir()} == {"plain.urdf.xacro", "sensors"}


HAND_PACKAGE_XACRO = """\
<?xml version="1.0"?>
<robot name="hand" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="sim" default="gz"/>
  <xacro:include filename="sensors/lidar_2d.urdf.xacro"/>
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <xacro:sensorkit_lidar_2d name="laser" parent="base_link" sim="$(arg sim)" gz_version="jetty">
    <origin xyz="0 0 0.2" rpy="0 0 0"/>
  </xacro:sensorkit_lidar_2d>
</robot>
"""
HAND_BRIDGE = """\
# my own bridge, CRLF and all\r
- ros_topic_name: laser/scan\r
  gz_topic_name: laser/scan\r
  ros_type_name: sensor_msgs/msg/LaserScan\r
  gz_type_name: gz.msgs.LaserScan\r
  direction: GZ_TO_ROS\r
"""


def test_hand_written_package_gets_bridge_entries_appended(tmp_path: Path) -> None:
    from sensorkit.base.resources import macros_dir

    pkg = tmp_path / "hand_description"
    (pkg / "urdf" / "sensors").mkdir(parents=True)
    (pkg / "config").mkdir()
    (pkg / "package.xml").write_text(
        "<package format='3'><name>hand_description</name></package>\n"
    )
    shutil.copy(macros_dir() / "lidar_2d.urdf.xacro", pkg / "urdf" / "sensors")
    robot = pkg / "urdf" / "hand.urdf.xacro"
    robot.write_text(HAND_PACKAGE_XACRO)
    bridge = pkg / "config" / "bridge.yaml"
    bridge.write_bytes(HAND_BRIDGE.encode())
    code, _, err = cli("add-camera", robot, "--name", "cam", "--parent", "base_link")
    assert code == 0, err
    assert "it gives gz here" in err
    call = robot.read_text().split("<xacro:sensorkit_camera", 1)[1]
    assert 'sim="$(arg sim)"' in call and 'gz_version="jetty"' in call
    data = bridge.read_bytes()
    assert data.startswith(HAND_BRIDGE.encode()) and b"\r\n" in data[len(HAND_BRIDGE) :]
    names = [e["ros_topic_name"] for e in bridge_of(bridge)]
    assert names == ["laser/scan", "cam/image_raw", "cam/camera_info"]
    assert not (pkg / "README.md").exists() and not (tmp_path / "robot.yaml").exists()
    code, _, err = cli("validate", robot, "--fail-on", "warning")
    assert code == 0, err
    # sim:=none: nothing simulated
    assert not list(xacro_robot(robot, sim="none").iter("sensor"))


ENTRY_ARGS = ("camera", "cam", "base_link", ["0.2", "0", "0.1"], ["0", "0", "0"], {"width": "320"})


@pytest.mark.parametrize(
    ("text", "added"),
    [
        (GZ_YAML, "  - type: camera\n    name: cam\n"),
        (GZ_YAML.replace("\n", "\r\n"), "  - type: camera\r\n    name: cam\r\n"),
        ("name: bot\nsensors: []\n", "sensors: [{type: camera, name: cam,"),
        ("name: bot\n", "sensors:\n  - {type: camera, name: cam,"),
        (
            "name: bot\nsensors:\n  - {type: imu, name: i}  # c\n# end\nbase: diff_drive\n",
            "  - {type: imu, name: i}  # c\n  - {type: camera, name: cam,",
        ),
    ],
)
def test_robot_yaml_append_keeps_every_byte(text: str, added: str) -> None:
    from sensorkit.generate.spec import parse_spec
    from sensorkit.generate.spec_edit import SensorEntry, append_sensor

    new = append_sensor(text, SensorEntry(*ENTRY_ARGS), "robot.yaml")
    assert added in new
    at = next((i for i, (a, b) in enumerate(zip(text, new, strict=False)) if a != b), len(text))
    # one contiguous insertion at ``at``, nothing else
    assert new[:at] + new[at + len(new) - len(text) :] == text
    spec = parse_spec(new, Path("robot.yaml"))
    cam = spec.sensors[-1]
    assert (cam.name, cam.type, cam.xyz, cam.options) == (
        "cam",
        "camera",
        "0.2 0 0.1",
        {"width": "320"},
    )


def test_commands_run_in_a_callers_process_leave_its_objects_collectable(tmp_path: Path) -> None:
    """The sensorkit program runs validate, add-* and render preview with the cyclic
    collector off and freezes what they built (it exits right after); a caller running
    them in its own process (CliRunner here) must get its collector back as it was, with
    nothing of the command's frozen for good."""
    import gc

    robot = tmp_path / "plain.urdf.xacro"
    robot.write_text(PLAIN)
    before = gc.get_freeze_count()
    assert gc.isenabled()  # as every test leaves it (validate in-process used not to)
    code, _, err = cli("validate", robot)
    assert code in (0, 1), err
    assert gc.isenabled() and gc.get_freeze_count() == before
    code, _, err = cli("add-camera", robot, "--name", "cam", "--parent", "base_link")
    assert code == 0, err
    assert gc.isenabled() and gc.get_freeze_count() == before
    wall_bot = Path(__file__).parent / "render_robots" / "wall_bot.urdf"
    code, out, err = cli(
        "render", "preview", wall_bot, "--out", tmp_path / "preview", "--sensor", "laser",
        "--fail-on", "never",
    )
    assert code == 0, out + err
    assert gc.isenabled() and gc.get_freeze_count() == before
