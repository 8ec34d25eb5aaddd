"""``sensorkit new``: generated packages expand with plain xacro, pass check_urdf, validate
clean and bridge every topic their sensors publish; YAML mistakes name their line."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree
from typer.testing import CliRunner

from sensorkit.base.errors import InputError, UsageError
from sensorkit.base.findings import Severity
from sensorkit.cli import app
from sensorkit.generate import base_templates, new_package, parse_spec, sensor_macros
from sensorkit.lint.engine import Options, validate_file

ROOT = Path(__file__).resolve().parent.parent
HARMONIC_YAML = ROOT / "examples" / "harmonic_robot" / "robot.yaml"

ALL_SENSORS = """\
sensors:
  - {type: camera, name: front_camera, parent: base_link, xyz: [0.25, 0, 0.1],
     options: {width: 320, height: 240}}
  - {type: depth_camera, name: rgbd, xyz: [0.2, 0, 0.15], rpy: [0, 0.2, 0]}
  - {type: stereo_camera, name: stereo, parent: lidar_link, xyz: [0, 0, 0.08],
     options: {baseline: 0.1}}
  - {type: lidar_2d, name: laser, xyz: [0.15, 0, 0.2]}
  - {type: lidar_3d, name: lidar, xyz: [0, 0, 0.3], options: {samples: 360, vertical_samples: 8}}
  - {type: imu, name: imu, xyz: [0, 0, 0.02], options: {gyro_noise_stddev: 2e-4}}
"""

SKID_GZ = f"""\
name: skid_bot
base: skid_steer
base_params: {{chassis_length: 0.7, wheel_base: 0.45, drive_plugin: true}}
sim: gz
gz_version: harmonic
namespace: ""
{ALL_SENSORS}"""

SKID_FORTRESS_NS = SKID_GZ.replace("gz_version: harmonic", "gz_version: fortress").replace(
    'namespace: ""', "namespace: robot1"
)
DIFF_CLASSIC = f"""\
name: classic_bot
base: diff_drive
sim: classic
{ALL_SENSORS}"""
DIFF_NONE = "name: bare_bot\nsim: none\n" + ALL_SENSORS

# What each gz sensor type publishes for its <topic> T (gz-sensors), and which of those
# a generated bridge must carry. A 3D lidar's LaserScan is left out on purpose, and so is an
# RGB-D cloud: gz-sensors computes it x-forward but stamps it with the optical frame
# (https://github.com/gazebosim/gz-sensors/issues/488), so the bridge must not carry it.
GZ_OUTPUTS = {
    "camera": [""],
    "rgbd_camera": ["/image", "/depth_image", "/camera_info"],
    "gpu_lidar": ["", "/points"],
    "imu": [""],
}
# The ROS topics each sensorkit macro publishes on Gazebo Classic; the bridge must give
# the same names on Gazebo Sim (one camera_info serves both rgbd images there).
CLASSIC_TOPICS = {
    "camera": ["image_raw", "camera_info"],
    "depth_camera": ["image_raw", "camera_info", "depth/image_raw", "points"],
    "stereo_camera": ["left/image_raw", "left/camera_info", "right/image_raw", "right/camera_info"],
    "lidar_2d": ["scan"],
    "lidar_3d": ["points"],
    "imu": ["imu"],
}


def xacro_exe() -> list[str]:
    venv = Path(sys.executable).with_name("xacro")
    if venv.exists():
        return [str(venv)]
    found = shutil.which("xacro")
    if found:
        return [found]
    return [sys.executable, "-m", "xacro"]


def expand_plain(path: Path, *args: str) -> str:
    """Expand with the real xacro command, as ros2 launch would."""
    proc = subprocess.run(
        [*xacro_exe(), str(path), *args], capture_output=True, text=True, timeout=60, check=False
    )
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def check_urdf(urdf_text: str, tmp_path: Path) -> None:
    exe = shutil.which("check_urdf") or "/usr/bin/check_urdf"
    if not Path(exe).exists():
        pytest.fail("check_urdf is missing: apt-get install liburdfdom-tools")
    out = tmp_path / "expanded.urdf"
    out.write_text(urdf_text)
    proc = subprocess.run([exe, str(out)], capture_output=True, text=True, timeout=20, check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "Successfully Parsed XML" in proc.stdout


def assert_validates_clean(path: Path) -> None:
    report = validate_file(path, Options())
    assert report.error is None, report.error
    assert not report.internal_errors, report.internal_errors
    bad = [f for f in report.findings if f.severity >= Severity.WARNING]
    assert not bad, [(f.rule, f.message) for f in bad]


def generate(tmp_path: Path, text: str, name: str = "robot.yaml") -> tuple[Path, Path]:
    spec = tmp_path / name
    spec.write_text(text)
    out = tmp_path / "pkg"
    new_package(spec, out)
    return spec, out


def gz_sensor_topics(urdf_text: str) -> list[tuple[str, str, str]]:
    """(sensor name, type, gz topic) for every gz sensor the expanded robot declares."""
    root = etree.fromstring(urdf_text.encode())
    out = []
    for sensor in root.iter("sensor"):
        topic = sensor.findtext("topic")
        if topic is not None:
            out.append((sensor.get("name"), sensor.get("type"), topic.strip().strip("/")))
        info = sensor.findtext("camera/camera_info_topic")
        if info is not None:
            out.append((sensor.get("name"), "camera_info", info.strip().strip("/")))
    return out


@pytest.mark.parametrize(
    ("text", "robot", "sim"),
    [
        (HARMONIC_YAML.read_text(), "harmonic_robot", "gz"),
        (SKID_GZ, "skid_bot", "gz"),
        (SKID_FORTRESS_NS, "skid_bot", "gz"),
        (DIFF_CLASSIC, "classic_bot", "classic"),
        (DIFF_NONE, "bare_bot", "none"),
    ],
    ids=["harmonic-example", "skid-harmonic", "skid-fortress-ns", "diff-classic", "diff-none"],
)
def test_generated_package_expands_checks_and_validates(
    tmp_path: Path, text: str, robot: str, sim: str
) -> None:
    _, out = generate(tmp_path, text)
    xacro_file = out / "urdf" / f"{robot}.urdf.xacro"
    urdf = expand_plain(xacro_file)
    check_urdf(urdf, tmp_path)
    assert_validates_clean(xacro_file)

    # The package skeleton colcon needs.
    pkg = etree.parse(str(out / "package.xml")).getroot()
    assert pkg.get("format") == "3"
    assert pkg.findtext("buildtool_depend") == "ament_cmake"
    deps = {d.text for d in pkg.findall("exec_depend")}
    assert {"xacro", "robot_state_publisher"} <= deps
    assert pkg.findtext("export/build_type") == "ament_cmake"
    cmake = (out / "CMakeLists.txt").read_text()
    assert f"project({pkg.findtext('name')})" in cmake
    assert "DESTINATION share/${PROJECT_NAME}" in cmake
    assert "urdf" in cmake.split("DIRECTORY", 1)[1].split("DESTINATION", 1)[0]

    # The macros used are copies of the shipped ones, next to the robot file.
    spec = parse_spec(text, tmp_path / "robot.yaml")
    for s in spec.sensors:
        copy = out / "urdf" / "sensors" / s.macro.file.name
        assert copy.read_bytes() == s.macro.file.read_bytes()
        assert f'<xacro:include filename="sensors/{s.macro.file.name}"/>' in xacro_file.read_text()
    assert (out / "urdf" / spec.base_macro.file.name).read_bytes() == (
        spec.base_macro.file.read_bytes()
    )

    bridge = out / "config" / "bridge.yaml"
    if sim != "gz":
        assert not bridge.exists()
        assert "config" not in cmake
        return
    assert "config" in cmake
    assert {"ros_gz_bridge", "ros_gz_sim"} <= deps
    entries = yaml.safe_load(bridge.read_text())
    assert entries, "bridge.yaml must never be empty"
    for e in entries:
        assert set(e) == {
            "ros_topic_name",
            "gz_topic_name",
            "ros_type_name",
            "gz_type_name",
            "direction",
        }
        prefix = "ignition.msgs." if spec.gz_version == "fortress" else "gz.msgs."
        assert e["gz_type_name"].startswith(prefix), e
        assert e["direction"] in ("GZ_TO_ROS", "ROS_TO_GZ")
    gz_names = {e["gz_topic_name"].strip("/") for e in entries}
    ros_names = {e["ros_topic_name"] for e in entries}
    assert "/clock" in ros_names

    # Every topic the expanded sensors declare is bridged (gz side) ...
    declared = gz_sensor_topics(urdf)
    assert declared
    for sensor, stype, topic in declared:
        if stype == "camera_info":
            assert topic in gz_names, (sensor, topic)
            continue
        vertical = etree.fromstring(urdf.encode()).xpath(
            f"//sensor[@name='{sensor}']/lidar/scan/vertical/samples/text()"
        )
        for suffix in GZ_OUTPUTS[stype]:
            if stype == "gpu_lidar" and suffix == "" and vertical and int(vertical[0]) > 1:
                continue  # a multi-layer LaserScan is not a LaserScan ROS can read
            assert f"{topic}{suffix}" in gz_names, (sensor, f"{topic}{suffix}", gz_names)
        if stype == "rgbd_camera":
            assert f"{topic}/points" not in gz_names, (sensor, "x-forward cloud bridged (gz-sensors#488)")
    # ... under the ROS names the same macros give on Gazebo Classic.
    ns = f"{spec.namespace}/" if spec.namespace else ""
    for s in spec.sensors:
        for t in CLASSIC_TOPICS[s.type]:
            if s.type == "depth_camera" and t == "points":  # not bridged: gz-sensors#488
                assert f"{ns}{s.name}/{t}" not in ros_names, (s.name, t)
                continue
            assert f"{ns}{s.name}/{t}" in ros_names, (s.name, t, sorted(ros_names))


def test_harmonic_example_bridge_names_every_sensor_topic(tmp_path: Path) -> None:
    _, out = generate(tmp_path, HARMONIC_YAML.read_text())
    entries = yaml.safe_load((out / "config" / "bridge.yaml").read_text())
    pairs = {(e["ros_topic_name"], e["ros_type_name"]) for e in entries}
    assert pairs >= {
        ("/clock", "rosgraph_msgs/msg/Clock"),
        ("front_camera/image_raw", "sensor_msgs/msg/Image"),
        ("front_camera/camera_info", "sensor_msgs/msg/CameraInfo"),
        ("rgbd_camera/image_raw", "sensor_msgs/msg/Image"),
        ("rgbd_camera/depth/image_raw", "sensor_msgs/msg/Image"),
        ("rgbd_camera/camera_info", "sensor_msgs/msg/CameraInfo"),
        ("lidar/points", "sensor_msgs/msg/PointCloud2"),
        ("imu/imu", "sensor_msgs/msg/Imu"),
        ("cmd_vel", "geometry_msgs/msg/Twist"),
        ("odom", "nav_msgs/msg/Odometry"),
    }
    # The RGB-D cloud is x-forward but stamped optical on Gazebo Sim
    # (https://github.com/gazebosim/gz-sensors/issues/488): left out, and the file says why.
    assert ("rgbd_camera/points", "sensor_msgs/msg/PointCloud2") not in pairs
    assert "gz-sensors#488" in (out / "config" / "bridge.yaml").read_text()
    by_ros = {e["ros_topic_name"]: e for e in entries}
    assert by_ros["rgbd_camera/depth/image_raw"]["gz_topic_name"] == "rgbd_camera/depth_image"
    assert by_ros["lidar/points"]["gz_topic_name"] == "lidar/scan/points"
    assert by_ros["cmd_vel"]["direction"] == "ROS_TO_GZ"


def test_sim_none_variant_of_a_gz_package_has_no_plugins(tmp_path: Path) -> None:
    _, out = generate(tmp_path, SKID_GZ)
    urdf = expand_plain(out / "urdf" / "skid_bot.urdf.xacro", "sim:=none")
    root = etree.fromstring(urdf.encode())
    assert not root.findall(".//sensor")
    assert not root.findall(".//plugin")
    check_urdf(urdf, tmp_path)


def test_generation_is_deterministic(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(SKID_GZ)
    a, b = tmp_path / "a", tmp_path / "b"
    ra = new_package(spec, a)
    rb = new_package(spec, b)
    assert ra.files == rb.files
    for rel in ra.files:
        assert (a / rel).read_bytes() == (b / rel).read_bytes(), rel


def test_launch_files_are_python(tmp_path: Path) -> None:
    for text in (SKID_GZ, DIFF_CLASSIC, DIFF_NONE):
        root = tmp_path / text.split("\n", 1)[0].split(": ")[1]
        root.mkdir()
        _, out = generate(root, text)
        for launch in (out / "launch").glob("*.py"):
            compile(launch.read_text(), str(launch), "exec")


def test_catalog_comes_from_the_shipped_files() -> None:
    assert set(sensor_macros()) >= {
        "camera",
        "depth_camera",
        "stereo_camera",
        "lidar_2d",
        "lidar_3d",
        "imu",
    }
    assert set(base_templates()) >= {"diff_drive", "skid_steer"}
    for info in base_templates().values():
        assert {"chassis_length", "chassis_width", "chassis_height", "wheel_radius"} <= set(
            info.params
        )
        assert {"wheel_width", "wheel_separation", "chassis_mass", "wheel_mass"} <= set(info.params)


@pytest.mark.parametrize("base", ["diff_drive", "skid_steer"])
def test_base_templates_have_inertials_and_continuous_wheels(tmp_path: Path, base: str) -> None:
    (tmp_path / "r.xacro").write_text(
        f'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        f'<xacro:include filename="{ROOT / "templates" / f"{base}.urdf.xacro"}"/>'
        f'<xacro:sensorkit_{base}_base sim="none"/></robot>'
    )
    urdf = expand_plain(tmp_path / "r.xacro")
    check_urdf(urdf, tmp_path)
    root = etree.fromstring(urdf.encode())
    links = {link.get("name"): link for link in root.findall("link")}
    assert "base_footprint" in links
    assert links["base_footprint"].find("inertial") is None  # root: KDL ignores it
    for name, link in links.items():
        if name == "base_footprint":
            continue
        inertial = link.find("inertial")
        assert inertial is not None, name
        assert float(inertial.find("mass").get("value")) > 0
        inertia = inertial.find("inertia")
        ixx, iyy, izz = (float(inertia.get(k)) for k in ("ixx", "iyy", "izz"))
        assert min(ixx, iyy, izz) > 0
        assert ixx + iyy >= izz and iyy + izz >= ixx and ixx + izz >= iyy, name
    joint = root.find("joint[@name='base_joint']")
    assert joint.find("parent").get("link") == "base_footprint"
    assert joint.find("child").get("link") == "base_link"
    wheels = [j for j in root.findall("joint") if j.get("type") == "continuous"]
    assert len(wheels) == (2 if base == "diff_drive" else 4)
    for j in wheels:
        assert j.find("axis").get("xyz") == "0 1 0"


# ---------------------------------------------------------------- YAML mistakes

GOOD = """\
name: my_robot
base: diff_drive
sim: gz
sensors:
  - type: camera
    name: front_camera
    parent: base_link
    xyz: [0.25, 0, 0.1]
    options: {width: 640}
"""


@pytest.mark.parametrize(
    ("text", "line", "needle"),
    [
        (GOOD.replace("sim: gz", "sim: gz\ncolour: red"), 4, "unknown key 'colour'"),
        (GOOD.replace("base: diff_drive", "base: tank"), 2, "unknown value 'tank'"),
        (GOOD.replace("sim: gz", "sim: gazebo"), 3, "unknown value 'gazebo'"),
        (GOOD.replace("type: camera", "type: kamera"), 5, "did you mean 'camera'"),
        (GOOD.replace("width: 640", "width: wide"), 9, "expected a whole number"),
        (GOOD.replace("width: 640", "width: 640.5"), 9, "expected a whole number"),
        (GOOD.replace("width: 640", "widht: 640"), 9, "did you mean 'width'"),
        (GOOD.replace("width: 640", "sim: gz"), 9, "top level"),
        (GOOD.replace("xyz: [0.25, 0, 0.1]", "xyz: [0.25, 0]"), 8, "list of 3 numbers"),
        (GOOD.replace("xyz: [0.25, 0, 0.1]", "xyz: [0.25, true, 0]"), 8, "expected a number"),
        (GOOD.replace("parent: base_link", "parent: roof_link"), 7, "no link 'roof_link'"),
        (GOOD.replace("parent: base_link", "parent: front_camera_link"), 7, "itself"),
        (GOOD.replace("name: my_robot", "name: My Robot"), 1, "not a valid name"),
        (GOOD.replace("name: my_robot\n", ""), 1, "missing key 'name'"),
        (GOOD.replace("    name: front_camera\n", ""), 5, "missing key 'name'"),
        (GOOD + "  - {type: imu, name: front_camera}\n", 10, "duplicate sensor name"),
        (GOOD + "  - {type: imu, name: base}\n", 10, "would create link 'base_link'"),
        ("name: my_robot\nsensors: 3\n", 2, "expected a list of sensors"),
        (GOOD.replace("options: {width: 640}", "options: {width: 640"), 10, "malformed YAML"),
        (GOOD.replace("sim: gz", "sim: gz\nsim: classic"), 4, "duplicate key"),
        (GOOD.replace("sim: gz", "base_params: {wheel_radius: -}"), 3, "expected a number"),
        (GOOD.replace("sim: gz", "base_params: {drive_plugin: 1}"), 3, "true or false"),
        ("- just\n- a list\n", 1, "expected a mapping"),
        ("", 1, "empty"),
    ],
    ids=[
        "unknown-key",
        "unknown-base",
        "unknown-sim",
        "unknown-sensor-type",
        "option-wrong-type",
        "option-not-whole",
        "unknown-option",
        "shared-option",
        "short-xyz",
        "bool-in-xyz",
        "missing-parent",
        "self-parent",
        "bad-robot-name",
        "no-robot-name",
        "no-sensor-name",
        "duplicate-sensor",
        "link-clash",
        "sensors-not-list",
        "malformed",
        "duplicate-key",
        "base-param-type",
        "bool-param",
        "not-a-mapping",
        "empty",
    ],
)
def test_yaml_mistakes_exit_2_with_the_line(
    tmp_path: Path, text: str, line: int, needle: str
) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(text)
    out = tmp_path / "pkg"
    result = CliRunner().invoke(app, ["new", str(spec), "-o", str(out)])
    assert result.exit_code == 2, result.output
    message = result.stderr.strip()
    assert "\n" not in message, message
    assert f"{spec}:{line}:" in message, message
    assert needle in message, message
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == ["robot.yaml"]  # no temp folder left


def test_mistake_column_points_at_the_value() -> None:
    # "    options: {width: -x}": the value starts in column 22.
    with pytest.raises(InputError, match=r"^robot\.yaml:9:22: sensors\[0\]\.options\.width: "):
        parse_spec(GOOD.replace("width: 640", "width: -x"), Path("robot.yaml"))


def test_macro_check_failure_points_at_the_sensor(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(GOOD.replace("width: 640", "mass: 0"))
    with pytest.raises(InputError) as err:
        new_package(spec, tmp_path / "pkg")
    assert f"{spec}:5:" in str(err.value)  # the sensor entry
    assert "mass must be > 0" in str(err.value)
    assert not (tmp_path / "pkg").exists()
    assert [p.name for p in tmp_path.iterdir()] == ["robot.yaml"]


def test_missing_yaml_file_is_exit_2(tmp_path: Path) -> None:
    result = CliRunner().invoke(
        app, ["new", str(tmp_path / "nope.yaml"), "-o", str(tmp_path / "o")]
    )
    assert result.exit_code == 2
    assert "nope.yaml" in result.stderr


# ---------------------------------------------------------------- the output folder


def test_non_empty_output_is_refused_unless_force(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(GOOD)
    out = tmp_path / "pkg"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    result = CliRunner().invoke(app, ["new", str(spec), "-o", str(out)])
    assert result.exit_code == 2
    assert "not empty" in result.stderr and "--force" in result.stderr
    assert [p.name for p in out.iterdir()] == ["keep.txt"]

    result = CliRunner().invoke(app, ["new", str(spec), "-o", str(out), "--force"])
    assert result.exit_code == 0, result.output
    assert not (out / "keep.txt").exists()
    assert (out / "urdf" / "my_robot.urdf.xacro").is_file()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pkg", "robot.yaml"]
    assert str(out / "package.xml") in result.stdout


def test_empty_output_folder_is_used(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(GOOD)
    out = tmp_path / "pkg"
    out.mkdir()
    new_package(spec, out)
    assert (out / "package.xml").is_file()
    umask = os.umask(0o022)
    os.umask(umask)
    assert os.stat(out).st_mode & 0o777 == 0o777 & ~umask  # not mkdtemp's 0o700


def test_force_never_replaces_the_folder_holding_the_yaml(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(GOOD)
    with pytest.raises(UsageError, match=r"robot\.yaml"):
        new_package(spec, tmp_path, force=True)
    assert spec.read_text() == GOOD


def test_output_that_is_a_file_is_refused(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(GOOD)
    with pytest.raises(UsageError, match="not a folder"):
        new_package(spec, spec)


def test_dry_run_writes_nothing(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(GOOD)
    result = CliRunner().invoke(app, ["new", str(spec), "-o", str(tmp_path / "pkg"), "--dry-run"])
    assert result.exit_code == 0, result.output
    assert "config/bridge.yaml" in result.stdout
    assert [p.name for p in tmp_path.iterdir()] == ["robot.yaml"]


finite = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e9, max_value=1e9)
# Angles within one turn: `new` refuses an rpy past 2*pi as degrees written for radians
# (issue 38), as add-camera does; the refusal has its own test in test_newcomer_answers.
angle = st.floats(allow_nan=False, allow_infinity=False, min_value=-6.283, max_value=6.283)


@settings(max_examples=200, deadline=None)
@given(xyz=st.lists(finite, min_size=3, max_size=3), rpy=st.lists(angle, min_size=3, max_size=3))
def test_numbers_reach_the_xacro_exactly(xyz: list[float], rpy: list[float]) -> None:
    text = GOOD.replace("xyz: [0.25, 0, 0.1]", f"xyz: {xyz!r}\n    rpy: {rpy!r}")
    sensor = parse_spec(text, Path("robot.yaml")).sensors[0]
    assert [float(v) for v in sensor.xyz.split()] == xyz
    assert [float(v) for v in sensor.rpy.split()] == rpy


def test_force_through_a_symlinked_output_edits_the_target(tmp_path: Path) -> None:
    # Issue 10: `new -o LINK --force` used to rename the link away and put a folder in its
    # place, leaving the target with the old package and a stray link beside it.
    spec = tmp_path / "robot.yaml"
    spec.write_text(GOOD)
    target = tmp_path / "real" / "pkg"
    target.mkdir(parents=True)
    (target / "stale.txt").write_text("old")
    link = tmp_path / "pkg"
    link.symlink_to(target, target_is_directory=True)
    result = CliRunner().invoke(app, ["new", str(spec), "-o", str(link), "--force"])
    assert result.exit_code == 0, result.output
    assert link.is_symlink() and link.resolve() == target.resolve()
    assert (target / "urdf" / "my_robot.urdf.xacro").is_file()
    assert not (target / "stale.txt").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pkg", "real", "robot.yaml"]
    assert [p.name for p in (tmp_path / "real").iterdir()] == ["pkg"]  # no staging left


def test_the_header_names_the_yaml_the_user_has(tmp_path: Path) -> None:
    """Issue 38: the generated header said "Change robot.yaml", which is not in the
    package. `new` never writes its input into its output (a copy would be a second source
    of truth that add-* and the user's own YAML would part on, and `new --force` refuses
    an -o that holds its input), so the header and README name the YAML by its path from
    the package folder, and the command that generates again; add-* finds the YAML beside
    the package through the same path."""
    one = "name: classic_bot\nbase: diff_drive\nsim: none\nsensors:\n  - {type: imu, name: imu, parent: base_link}\n"
    (tmp_path / "robot.yaml").write_text(one)
    pkg = tmp_path / "classic_bot_description"
    result = new_package(tmp_path / "robot.yaml", pkg)
    assert result.spec.package == pkg.name
    xacro = pkg / "urdf" / f"{result.spec.name}.urdf.xacro"
    head = xacro.read_text().split("-->")[0]
    etree.parse(str(xacro))  # the comment stays XML ("--force" could not be in it)
    assert "Change ../robot.yaml (the path is from the package folder)" in head
    assert "`sensorkit new robot.yaml -o classic_bot_description`" in head
    assert "--" not in head.split("<!--", 1)[1]
    assert (pkg / "../robot.yaml").resolve() == (tmp_path / "robot.yaml").resolve()
    readme = (pkg / "README.md").read_text()
    assert "`../robot.yaml` from" in readme
    assert "`sensorkit new robot.yaml -o classic_bot_description --force`" in readme
    # a YAML kept elsewhere: its path from the package, which leads to it
    designs = tmp_path / "designs"
    designs.mkdir()
    shutil.copy(tmp_path / "robot.yaml", designs / "bot.yaml")
    far = tmp_path / "ws" / "src" / "classic_bot_description"
    new_package(designs / "bot.yaml", far)
    head = (far / "urdf" / xacro.name).read_text().split("-->")[0]
    assert "Change ../../../designs/bot.yaml " in head
    assert "`sensorkit new ../../designs/bot.yaml -o classic_bot_description`" in head
    assert (far / "../../../designs/bot.yaml").resolve() == (designs / "bot.yaml").resolve()
