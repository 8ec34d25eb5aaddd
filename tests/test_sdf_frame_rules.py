"""The tree, mass and frame rules on SDF models (issue 28): which run, and what they say.

A rule runs on SDF only where its meaning holds there (``RuleInfo.formats``). Each such
rule has a trigger and a near miss of its own here, in tests/robots/sdf/frames. The rules
left URDF-only are checked not to run on an SDF model that would trip them in URDF.

Where TF gets an SDF model's frames: robot_state_publisher fed the SDF through sdformat_urdf
puts each link at the frame of the joint it is the child of (ros/sdformat_urdf@9cec63e:
sdformat_urdf/src/sdformat_urdf.cpp:322-327); gz-sim's PosePublisher publishes the link's
own pose (gazebosim/gz-sim@gz-sim8_8.9.0:src/systems/pose_publisher/PosePublisher.cc:513).
A frame those two place apart is not judged (sensorkit.model.frames.sdf_tf_agrees).
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
from conftest import CORPUS, needs_corpus, sdformat_tool

from sensorkit.base.findings import Finding, Severity
from sensorkit.lint.engine import Options, validate_file
from sensorkit.lint.rules import RULES
from sensorkit.model import load_robot
from sensorkit.model.frames import sensor_frames
from sensorkit.model.sdf import convert

HERE = Path(__file__).resolve().parent
FRAMES = HERE / "robots" / "sdf" / "frames"
TOOL_SOURCE = HERE / "tools" / "sdf_poses.cc"

ON_SDF = ("SK302", "SK501", "SK502", "SK503", "SK504", "SK506", "SK507", "SK508", "SK509")
URDF_ONLY = (
    "SK201", "SK202", "SK203", "SK204", "SK205", "SK206", "SK207",
    "SK301", "SK303", "SK304", "SK505",
)  # fmt: skip


def _findings(name: str, rule: str, **options: object) -> list[Finding]:
    report = validate_file(FRAMES / name, Options(**options))  # type: ignore[arg-type]
    assert report.error is None and not report.internal_errors, report.error
    assert report.robot is not None and report.robot.sdf is not None
    return [f for f in report.findings if f.rule == rule]


def _sensors(found: list[Finding]) -> set[str | None]:
    return {f.sensor for f in found}


def test_rules_that_hold_on_sdf_run_on_it_and_the_others_do_not() -> None:
    assert [rid for rid in ON_SDF if "sdf" not in RULES[rid].formats] == []
    assert [rid for rid in URDF_ONLY if RULES[rid].formats != ("urdf",)] == []


def test_sk501_frame_tag_naming_no_frame() -> None:
    found = _findings("sk501.sdf", "SK501")
    assert _sensors(found) == {"bad_lidar"}
    (f,) = found
    # info, not error: TF may come from a URDF beside the SDF, which sensorkit does not see
    # (ros-navigation/nav2_minimal_turtlebot_simulation's gz_waffle.sdf.xacro stamps
    # 'camera_depth_frame', a link of the turtlebot3_waffle.urdf next to it, :284)
    assert f.severity == Severity.INFO and f.frame == "lidar_lnk"
    assert "no frame of this SDF model" in f.message and "URDF" in f.message
    assert f.fix == "did you mean 'lidar_link'?"


def test_sk501_near_misses_frames_tf_may_have() -> None:
    # "sk501/lidar_link": PosePublisher's scoped link, "::" bridged as "/"; imu_frame: a
    # <frame> (a URDF kept beside the SDF may have it); default_imu: no frame tag, whose
    # scoped default a spawner's PosePublisher may publish (osrf/subt@083c6a8:
    # submitted_models/costar_husky_sensor_config_1/launch/spawner.rb:29-32).
    found = _sensors(_findings("sk501.sdf", "SK501"))
    assert not found & {"posepublisher_lidar", "frame_imu", "default_imu"}


def test_sk501_says_nothing_of_a_nested_model() -> None:
    # sdformat_urdf refuses nested models (ros/sdformat_urdf@9cec63e:sdformat_urdf/README.md:22):
    # the names TF has for their links are not known.
    assert _findings("sk501_nested.sdf", "SK501") == []


def test_sk502_camera_stamped_with_a_body_frame() -> None:
    found = _findings("sk502.sdf", "SK502")
    assert _sensors(found) == {"body_cam"}  # good_cam and rgb_cam stamp optical frames
    (f,) = found
    assert f.severity == Severity.ERROR and f.frame == "camera_link"
    assert "off by 120.0 degrees" in f.message
    assert (
        f.fix
        == "publish in 'camera_optical_frame', which is already an optical frame at the camera"
    )


def test_sk506_optical_frame_named_without_optical() -> None:
    found = _findings("sk502.sdf", "SK506")
    assert _sensors(found) == {"rgb_cam"}  # good_cam's frame says optical
    assert found[0].severity == Severity.INFO


def test_sk503_frame_away_from_the_sensor() -> None:
    found = _findings("sk503.sdf", "SK503")
    assert _sensors(found) == {"offset_lidar"}
    (f,) = found
    assert "sits 50.0 mm away" in f.message
    assert f.fix is not None and '<pose relative_to="lidar_link">' in f.fix


def test_sk503_not_said_where_tf_publishers_disagree() -> None:
    # scan_link's joint has a <pose> in it: sdformat_urdf puts scan_link at 0.1 0 0.2,
    # PosePublisher at the model's origin; which one TF has is not known.
    assert "ambiguous_lidar" not in _sensors(_findings("sk503.sdf", "SK503"))


def test_rotation_rules_judge_a_frame_tf_only_moves() -> None:
    # moved_joint moves moved_link but does not turn it: its rotation is the same from
    # either publisher, so SK502 holds; its position is not (no SK503).
    assert _sensors(_findings("tf_disagree.sdf", "SK502")) == {"shifted_cam"}
    assert _findings("tf_disagree.sdf", "SK503") == []


def test_rotation_rules_skip_a_frame_tf_may_turn() -> None:
    # turned_joint turns turned_link: sdformat_urdf's link is optical, PosePublisher's not.
    assert "turned_cam" not in _sensors(_findings("tf_disagree.sdf", "SK502"))
    assert _findings("tf_disagree.sdf", "SK508") == []  # turned_optical_frame likewise


def test_sk504_imu_turned_from_its_frame() -> None:
    found = _findings("sk504.sdf", "SK504")
    assert _sensors(found) == {"flipped_imu"}
    assert "rotated 180.0 degrees" in found[0].message


def test_sk507_odom_link_but_not_a_frame() -> None:
    found = _findings("sk507.sdf", "SK507")
    assert [f.link for f in found] == ["odom"]  # the <frame name="map"> is no link
    assert found[0].fix == "remove 'odom' from the SDF; odometry or localization publishes it"


def test_sk508_link_named_optical_is_not() -> None:
    found = _findings("sk508.sdf", "SK508")
    assert [f.link for f in found] == ["flat_optical_frame"]
    (f,) = found
    assert f.line == 7  # its <pose>, where SDF writes the rotation
    assert f.fix is not None and f.fix.startswith("turn the <pose> of link 'flat_optical_frame'")


def test_sk509_sensor_far_from_its_link() -> None:
    found = _findings("sk509.sdf", "SK509")
    assert _sensors(found) == {"far_lidar"}
    assert found[0].fix == "write the link poses and the sensor <pose> between them in metres"


def test_sk302_invalid_inertia() -> None:
    found = _findings("sk302.sdf", "SK302")
    assert [f.link for f in found] == ["bad_link"]  # default_link: sdformat's unit moments
    (f,) = found
    assert f.severity == Severity.ERROR
    assert f.message.endswith("sdformat reports it invalid and gz-sim refuses to spawn the robot")


def test_urdf_only_rules_say_nothing_of_a_valid_sdf() -> None:
    # A free body, a ball joint, a revolute joint without <limit>, a root with mass, a
    # fixed joint and an optical link turned by -1.57: all valid SDF.
    report = validate_file(FRAMES / "urdf_only.sdf")
    assert report.robot is not None and report.robot.sdf is not None
    assert [f for f in report.findings if f.rule in URDF_ONLY] == []
    # the same file's camera is judged: it stamps an optical frame (within 0.5 degree)
    assert [f.rule for f in report.findings if f.rule == "SK502"] == []


def test_classic_default_frame_drops_the_scopes() -> None:
    # gazebo_ros's SensorFrameID: the parent link's name without its scopes
    # (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_ros/src/utils.cpp:40-61).
    (robot,) = load_robot(FRAMES / "classic_nested.sdf", sdf=True).robots
    (s,) = robot.sensors
    fr = sensor_frames(robot, s, "classic", convert(robot))
    assert fr.link == "head::cam_link" and fr.published == "cam_link"


@pytest.fixture(scope="module")
def sdf_tool(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return sdformat_tool(tmp_path_factory, TOOL_SOURCE)


@pytest.mark.parametrize("path", sorted(FRAMES.glob("*.sdf")), ids=lambda p: p.name)
def test_libsdformat_reads_the_inputs_as_the_tests_say(sdf_tool: Path, path: Path) -> None:
    # Every input is valid SDF but sk302.sdf, where libsdformat reports the inertia SK302
    # reports (gazebosim/sdformat@sdformat12_12.8.0:src/Link.cc:180-187).
    res = subprocess.run(
        [str(sdf_tool), str(path)], capture_output=True, text=True, timeout=60, check=False
    )
    errors = [line for line in res.stdout.splitlines() if line.startswith("ERROR")]
    want = ["ERROR A link named bad_link has invalid inertia."] if path.name == "sk302.sdf" else []
    assert errors == want


TB3_JAZZY = (
    "ROBOTIS-GIT__turtlebot3_simulations/turtlebot3_gazebo/models/turtlebot3_waffle/model.jazzy.sdf"
)


@needs_corpus
def test_turtlebot3_sdf_camera_and_lidar() -> None:
    report = validate_file(CORPUS / TB3_JAZZY)
    assert report.error is None
    by_rule = {(f.rule, f.sensor) for f in report.findings}
    # the camera stamps camera_rgb_frame, x-forward in the SDF and in turtlebot3's URDF
    assert ("SK502", "camera") in by_rule
    fix = next(f.fix for f in report.findings if f.rule == "SK502")
    assert fix is not None and "<optical_frame_id>" in fix
    # lidar_joint has a <pose> in base_scan: TF's base_scan depends on who publishes it
    assert ("SK503", "hls_lfcd_lds") not in by_rule


def test_fix_never_edits_sdf(tmp_path: Path) -> None:
    """--fix's fixers write URDF and xacro text: an SDF finding with a URDF fixer (SK502)
    is not marked fixable, and --fix leaves the file byte for byte, saying why."""
    import sys

    path = tmp_path / "sk502.sdf"
    shutil.copyfile(FRAMES / "sk502.sdf", path)
    before = path.read_bytes()
    argv = [sys.executable, "-m", "sensorkit", "validate", str(path), "--target", "harmonic"]
    plain = subprocess.run(argv, capture_output=True, text=True, check=False)
    assert "SK502 error" in plain.stdout and "[*]" not in plain.stdout and "fixable" not in plain.stdout
    fixed = subprocess.run([*argv, "--fix"], capture_output=True, text=True, check=False)
    assert fixed.returncode == 1 and path.read_bytes() == before
    assert "SK502: --fix edits URDF and xacro files; change the SDF by hand" in fixed.stderr
