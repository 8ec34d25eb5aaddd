"""``sensorkit check-recording`` (issue 39): recordings of the example car, written with
rosbags' writers in the three formats (tests/bags.py, whose values come from the
simulators' source formulas, cited there), checked against the car's description.

For every rule SK801-SK810 a correct recording passes, a perturbation fails, and a near
miss (just inside a tolerance) passes; a camera stamped in its body frame fails with the
explanation SK502 gives for the description.
"""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from bags import (
    IDENTITY_Q,
    OPTICAL_Q,
    Scene,
    bare_mcap,
    car_scene,
    classic_camera_info,
    harmonic_scene,
    write_bag,
)
from conftest import ROOT
from conftest import run_cli as cli

from sensorkit.base.findings import Finding, Severity

pytest.importorskip("rosbags")

CAR = ROOT / "examples" / "orbslam3_car" / "urdf" / "orbslam3_car.urdf.xacro"
CAMERA_TOPICS = (
    "/camera/image_raw",
    "/camera/camera_info",
    "/camera/depth/image_raw",
    "/camera/depth/camera_info",
    "/camera/points",
)


@pytest.fixture(scope="module")
def described() -> tuple[list[object], list[object]]:
    """The car, described and its topics listed as `sensorkit topics` lists them."""
    from sensorkit.describe.sensorinfo import describe, load
    from sensorkit.describe.topics import robot_topics

    info = describe(load(CAR), "auto")
    return [info], [robot_topics(info)]


def small(scene: Scene, count: int = 3) -> Scene:
    """Fewer messages a topic (three stamps measure a rate)."""
    for topic in scene.streams:
        scene = scene.with_stream(topic, count=count)
    return scene


@pytest.fixture
def run(
    tmp_path: Path, described: tuple[list[object], list[object]]
) -> Callable[..., list[Finding]]:
    counter = iter(range(1000))

    def go(scene: Scene, fmt: str = "sqlite3") -> list[Finding]:
        from sensorkit.recording.check import check_recording

        path = write_bag(scene, tmp_path / f"rec{next(counter)}", fmt)
        infos, topics = described
        return check_recording(infos, topics, path).findings  # type: ignore[arg-type]

    return go


def of(findings: list[Finding], rule: str) -> list[Finding]:
    return [f for f in findings if f.rule == rule]


# --------------------------------------------------------------------------- the values


def test_the_formula_values_are_the_simulators() -> None:
    """simulators.md's worked example (640x480, hfov 2.0 rad, Classic: fx =
    205.46963709898583, cx = 320.5, cy = 240.5), from tests/bags.py's formula."""
    info = classic_camera_info(640, 480, 2.0)
    assert info["k"][0] == pytest.approx(205.46963709898583, abs=1e-12)
    assert info["k"][2] == 320.5 and info["k"][5] == 240.5


def test_the_optical_quaternion_is_rep_103() -> None:
    """OPTICAL_Q turns the optical frame's z (forward) onto the body's x, x (right) onto
    -y, y (down) onto -z (REP 103)."""
    from sensorkit.recording.tf import quaternion_matrix

    R = quaternion_matrix(*OPTICAL_Q)
    assert np.allclose(R @ [0, 0, 1], [1, 0, 0]) and np.allclose(R @ [1, 0, 0], [0, -1, 0])
    assert np.allclose(R @ [0, 1, 0], [0, 0, -1])


# --------------------------------------------------------------------------- formats


@pytest.mark.parametrize("fmt", ["ros1", "sqlite3", "mcap", "bare-mcap"])
def test_a_correct_recording_passes_in_every_format(
    fmt: str, tmp_path: Path, described: tuple[list[object], list[object]]
) -> None:
    from sensorkit.recording.check import check_recording

    scene = small(car_scene())
    path = write_bag(scene, tmp_path / "car", "mcap" if fmt == "bare-mcap" else fmt)
    if fmt == "bare-mcap":
        path = bare_mcap(path, tmp_path / "car.mcap")
    infos, topics = described
    result = check_recording(infos, topics, path)  # type: ignore[arg-type]
    assert result.findings == [], [f.message for f in result.findings]
    rec = result.recording
    assert set(rec.samples) == set(scene.streams)  # every predicted topic was read
    assert rec.tf.knows("camera_optical_frame") and rec.ros1 == (fmt == "ros1")
    scan = rec.samples["/lidar/scan"]
    assert scan.frame_ids == ["lidar_link"] * 3 and len(scan.messages) == 2
    # the stamps read from raw bytes are the decoded headers' (ROS 1 and CDR layouts)
    first = scan.messages[0].header.stamp
    assert scan.stamps[0] == first.sec * 10**9 + first.nanosec


def test_a_rosbag2_without_message_definitions_is_read(
    tmp_path: Path, described: tuple[list[object], list[object]]
) -> None:
    """rosbag2 before Iron stores no message definitions: rosbags needs a typestore, and
    the newest distribution's is taken (a recording of a wrong K is still found)."""
    import sqlite3

    from sensorkit.recording.check import check_recording

    path = write_bag(_k(small(car_scene()), dfx=300.0 - FX), tmp_path / "humble", "sqlite3")
    (db,) = path.glob("*.db3")
    with sqlite3.connect(db) as con:
        con.execute("DELETE FROM message_definitions")
    infos, topics = described
    found = check_recording(infos, topics, path).findings  # type: ignore[arg-type]
    assert [f.rule for f in found] == ["SK806"], [f.message for f in found]


def test_the_shipped_example_recording_passes() -> None:
    res = cli(
        "check-recording", str(ROOT / "examples/orbslam3_car/recordings/car_sim.mcap"), str(CAR)
    )
    assert res.returncode == 0, res.stdout + res.stderr
    assert "ok: no findings (2 sensors checked)" in res.stdout


# --------------------------------------------------------------------------- each rule


def _move_tf(scene: Scene, child: str, dx: float) -> Scene:
    _p, _c, xyz, q = next(e for e in scene.tf_static if e[1] == child)
    return scene.with_tf(child, (xyz[0] + dx, xyz[1], xyz[2]), q)


def _turn_tf(scene: Scene, child: str, degrees: float) -> Scene:
    """The child's recorded rotation turned further about its parent's z."""
    _p, _c, xyz, (x, y, z, w) = next(e for e in scene.tf_static if e[1] == child)
    h = math.radians(degrees) / 2
    qz = (0.0, 0.0, math.sin(h), math.cos(h))
    a, b = qz, (x, y, z, w)
    q = (
        a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
        a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
        a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
        a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2],
    )
    return scene.with_tf(child, xyz, q)


def _k(scene: Scene, dfx: float = 0.0, dcx: float = 0.0) -> Scene:
    info = dict(scene.streams["/camera/camera_info"].fields)
    k, p = list(info["k"]), list(info["p"])
    k[0] += dfx
    k[4] += dfx
    p[0] += dfx
    p[5] += dfx
    k[2] += dcx
    p[2] += dcx
    return scene.with_fields("/camera/camera_info", k=k, p=p)


def _fields(scene: Scene, names: list[str]) -> Scene:
    return scene.with_fields("/camera/points", fields=[(n, 4 * i) for i, n in enumerate(names)])


def _plus(scene: Scene, topic: str, like: str) -> Scene:
    """``scene`` with one more topic, recorded as ``like`` is."""
    return Scene({**scene.streams, topic: scene.streams[like]}, scene.tf_static)


def _rate(scene: Scene, hz: float) -> Scene:
    return scene.with_stream("/lidar/scan", rate=hz, count=6)


FX = 640 / (2 * math.tan(1.0))  # the edge moves by dfx * 320 / FX px
SCAN = car_scene().streams["/lidar/scan"].fields

# rule -> (trigger, its severity, a word of its message, near miss)
CASES: dict[str, list[tuple[Callable[[Scene], Scene], Severity, str, Callable[[Scene], Scene]]]] = {
    "SK801": [
        (lambda s: s.without("/camera/points"), Severity.ERROR, "/camera/points", lambda s: s),
        (
            lambda s: _plus(s, "/front/image_raw", "/camera/image_raw"),
            Severity.INFO,
            "no sensor of the description publishes it",
            # image_transport's topics beside a predicted image are not said
            lambda s: _plus(s, "/camera/image_raw/extra", "/camera/image_raw"),
        ),
    ],
    "SK802": [
        (
            lambda s: s.with_stream(
                "/lidar/scan",
                msgtype="sensor_msgs/msg/PointCloud2",
                fields=s.streams["/camera/points"].fields,
            ),
            Severity.ERROR,
            "recorded as sensor_msgs/msg/PointCloud2",
            lambda s: s,
        )
    ],
    "SK803": [
        (
            lambda s: s.with_stream("/lidar/scan", frame="laser"),
            Severity.ERROR,
            "'laser'",
            lambda s: s,
        ),
    ],
    "SK804": [
        (
            lambda s: s.with_stream("/lidar/scan", frame="laser"),
            Severity.ERROR,
            "neither /tf",
            lambda s: s,
        ),
        (lambda s: Scene(s.streams, []), Severity.INFO, "no /tf or /tf_static", lambda s: s),
    ],
    "SK805": [
        # a missing optical rotation: the TF says camera_optical_frame is camera_link's
        (
            lambda s: s.with_tf("camera_optical_frame", (0.0, 0.0, 0.0), IDENTITY_Q),
            Severity.ERROR,
            "which is not an optical frame",
            lambda s: _turn_tf(s, "camera_optical_frame", 0.4),  # under 0.5 degree
        ),
        (
            lambda s: _turn_tf(s, "camera_optical_frame", 0.6),
            Severity.ERROR,
            "0.6 degrees",
            lambda s: s,
        ),
        (
            lambda s: _move_tf(s, "lidar_link", 0.0011),  # 1.1 mm
            Severity.ERROR,
            "1.1 mm",
            lambda s: _move_tf(s, "lidar_link", 0.0009),
        ),
    ],
    "SK806": [
        (
            lambda s: _k(s, dfx=300.0 - FX),
            Severity.ERROR,
            "K is [300",
            lambda s: _k(s, dfx=FX * 0.009 / 320),
        ),
        # the image edge moves by just over / just under 1 px: error / warning
        (lambda s: _k(s, dfx=FX * 1.05 / 320), Severity.ERROR, "1.05 px", lambda s: s),
        (lambda s: _k(s, dcx=0.95), Severity.WARNING, "0.95 px", lambda s: _k(s, dcx=0.009)),
        (
            lambda s: s.with_fields("/camera/camera_info", width=320, height=240),
            Severity.ERROR,
            "320x240",
            lambda s: s,
        ),
        (
            lambda s: s.with_fields("/camera/camera_info", d=[0.1, 0.0, 0.0, 0.0, 0.0]),
            Severity.ERROR,
            "D is [0.1",
            lambda s: s.with_fields("/camera/camera_info", d=[]),  # empty D: no distortion
        ),
        (
            lambda s: s.with_fields("/camera/camera_info", distortion_model="rational_polynomial"),
            Severity.WARNING,
            "'rational_polynomial'",
            lambda s: s,
        ),
    ],
    "SK807": [
        (
            lambda s: s.with_fields("/camera/image_raw", encoding="bgr8"),
            Severity.ERROR,
            "'bgr8', the camera publishes 'rgb8'",
            lambda s: s,
        ),
        (
            lambda s: s.with_fields(
                "/camera/depth/image_raw", width=320, height=240, step=1280, data_bytes=1280 * 240
            ),
            Severity.ERROR,
            "320x240",
            lambda s: s,
        ),
    ],
    "SK808": [
        (
            lambda s: s.with_fields("/lidar/scan", ranges=[12.0] * 359),
            Severity.ERROR,
            "359 beams",
            # float32 rounding, as a LaserScan holds it, and 5e-6 rad: within 1e-5 rad
            lambda s: s.with_fields(
                "/lidar/scan",
                angle_increment=float(np.float32(SCAN["angle_increment"])),
                angle_min=SCAN["angle_min"] + 5e-6,
            ),
        ),
        (
            lambda s: s.with_fields("/lidar/scan", angle_min=-3.0),
            Severity.ERROR,
            "angle_min -3",
            lambda s: s,
        ),
        (
            lambda s: s.with_fields("/lidar/scan", range_max=10.0),
            Severity.ERROR,
            "range_max 10",
            lambda s: s,
        ),
    ],
    "SK809": [
        (
            lambda s: _fields(s, ["x", "y", "z"]),
            Severity.WARNING,
            "without rgb",
            lambda s: _fields(s, ["rgb", "x", "y", "z"]),
        ),
        (lambda s: _fields(s, ["x", "y", "rgb"]), Severity.ERROR, "no field z", lambda s: s),
    ],
    "SK810": [
        (
            lambda s: _rate(s, 5.0),
            Severity.WARNING,
            "5 Hz",
            lambda s: _rate(s, 9.2),
        ),  # half; 8 % off
        (
            lambda s: _rate(s, 8.8),
            Severity.WARNING,
            "8.8 Hz",
            lambda s: _rate(s, 10.8),
        ),  # 12 %; 8 %
    ],
}


def test_every_recording_rule_has_a_trigger_and_a_near_miss() -> None:
    from sensorkit.lint.rules import RULES

    assert set(CASES) == {rid for rid, info in RULES.items() if "recording" in info.formats}
    for rid, cases in CASES.items():
        declared = RULES[rid].severity.split("/")
        assert {c[1].label for c in cases} == set(declared), rid


@pytest.mark.parametrize(
    ("rule", "index"), [(rid, i) for rid, cases in CASES.items() for i in range(len(cases))]
)
def test_trigger_and_near_miss(rule: str, index: int, run: Callable[..., list[Finding]]) -> None:
    trigger, severity, words, near = CASES[rule][index]
    base = small(car_scene())
    found = of(run(trigger(base)), rule)
    assert [f.severity for f in found] == [severity], [f.message for f in found]
    assert words in found[0].message, found[0].message
    missed = run(near(base))
    assert missed == [], [f.message for f in missed]


@pytest.mark.parametrize("fmt", ["ros1", "mcap"])
def test_perturbations_fail_in_the_other_formats(
    fmt: str, run: Callable[..., list[Finding]]
) -> None:
    """A wrong K, a missing optical rotation, a wrong frame_id, a missing topic and half
    the rate, in a ROS 1 bag and an MCAP rosbag2 too."""
    scene = _rate(small(car_scene()), 5.0)
    scene = _k(scene, dfx=300.0 - FX).without("/camera/points")
    scene = scene.with_tf("camera_optical_frame", (0.0, 0.0, 0.0), IDENTITY_Q)
    scene = scene.with_stream("/lidar/scan", frame="laser")
    rules = sorted(f.rule for f in run(scene, fmt))
    assert rules == ["SK801", "SK803", "SK804", "SK805", "SK806", "SK810"], rules


# --------------------------------------------------------------------------- Gazebo Sim

HARMONIC = (
    ROOT / "examples/harmonic_robot/harmonic_robot_description/urdf/harmonic_robot.urdf.xacro"
)


@pytest.fixture(scope="module")
def harmonic() -> tuple[list[object], list[object]]:
    """The Harmonic example, its topics named by the bridge.yaml of its package."""
    from sensorkit.describe.sensorinfo import describe, load
    from sensorkit.describe.topics import load_bridge, robot_topics

    info = describe(load(HARMONIC), "auto")
    assert info.target == "harmonic"
    return [info], [robot_topics(info, load_bridge(info.robot, info.target))]


def test_a_gazebo_sim_recording(
    tmp_path: Path, harmonic: tuple[list[object], list[object]]
) -> None:
    """gz's camera_info (cx = W/2, fx in float32), the rgbd camera's pitched mount, the
    gpu_lidar's cloud and the IMU pass; Classic's principal point (W+1)/2 is half a pixel
    off (a warning), a cloud without ring a warning, an IMU stamped in base_link an error."""
    from sensorkit.recording.check import check_recording

    infos, topics = harmonic
    scene = small(harmonic_scene())
    path = write_bag(scene, tmp_path / "gz", "mcap")
    found = check_recording(infos, topics, path).findings  # type: ignore[arg-type]
    assert found == [], [f.message for f in found]
    k = list(scene.streams["/front_camera/camera_info"].fields["k"])
    k[2] = (1280 + 1) / 2
    wrong = scene.with_fields("/front_camera/camera_info", k=k)
    wrong = wrong.with_fields(
        "/lidar/points", fields=[("x", 0), ("y", 4), ("z", 8), ("intensity", 16)]
    )
    wrong = wrong.with_stream("/imu/imu", frame="base_link")
    found = check_recording(infos, topics, write_bag(wrong, tmp_path / "gz_bad", "mcap")).findings  # type: ignore[arg-type]
    got = sorted((f.rule, f.severity.label, f.sensor) for f in found)
    assert got == [
        ("SK803", "error", "imu"),
        ("SK806", "warning", "front_camera"),
        ("SK809", "warning", "lidar"),
    ], [f.message for f in found]
    assert (
        "0.50 px" in of(found, "SK806")[0].message
        and "without ring" in of(found, "SK809")[0].message
    )


# --------------------------------------------------------------------------- acceptance


def _sk502_explanation(tmp_path: Path) -> str:
    """What SK502 says of the car with its camera's frame_name set to its body frame."""
    import xacro

    from sensorkit.lint.engine import Options, validate_file

    urdf = xacro.process_file(str(CAR)).toxml()
    wrong = urdf.replace(
        "<frame_name>camera_optical_frame</frame_name>", "<frame_name>camera_link</frame_name>"
    )
    assert wrong != urdf
    path = tmp_path / "car_body_frame.urdf"
    path.write_text(wrong)
    (f,) = [f for f in validate_file(path, Options(target="classic")).findings if f.rule == "SK502"]
    said = f.message[f.message.index("which is not an optical frame") :]
    return said.split("; ")[0]  # without "; the rotation comes from joint ..."


def test_a_camera_stamped_in_its_body_frame_fails_as_sk502_says(
    tmp_path: Path, run: Callable[..., list[Finding]]
) -> None:
    explanation = _sk502_explanation(tmp_path)
    assert "points up at the sky" in explanation
    scene = small(car_scene())
    for topic in CAMERA_TOPICS:
        scene = scene.with_stream(topic, frame="camera_link")
    found = run(scene)
    (f,) = of(found, "SK803")
    assert f.severity is Severity.ERROR and f.sensor == "camera" and f.frame == "camera_link"
    assert explanation in f.message, (explanation, f.message)
    assert of(found, "SK804") == [] and of(found, "SK805") == []  # camera_link is in TF, right
    # the expected camera_info and TF of the same recording pass
    assert of(found, "SK806") == [] and sorted({f.rule for f in found}) == ["SK803"]


def test_a_missing_optical_rotation_in_tf_says_what_sk502_says(
    tmp_path: Path, run: Callable[..., list[Finding]]
) -> None:
    explanation = _sk502_explanation(tmp_path)
    scene = small(car_scene()).with_tf("camera_optical_frame", (0.0, 0.0, 0.0), IDENTITY_Q)
    (f,) = of(run(scene), "SK805")
    assert "'camera_optical_joint'" in f.message and explanation in f.message


# --------------------------------------------------------------------------- bounded


def test_only_a_bounded_sample_is_read(
    tmp_path: Path, described: tuple[list[object], list[object]]
) -> None:
    from sensorkit.recording.bag import Limits
    from sensorkit.recording.check import check_recording

    scene = small(car_scene()).with_stream("/lidar/scan", count=250)
    path = write_bag(scene, tmp_path / "long", "sqlite3")
    infos, topics = described
    result = check_recording(infos, topics, path, limits=Limits(stamps=40, decoded=1))  # type: ignore[arg-type]
    scan = result.recording.samples["/lidar/scan"]
    assert scan.count == 250 and scan.read == 40 and len(scan.stamps) == 40
    assert len(scan.messages) == 1
    image = result.recording.samples["/camera/image_raw"]
    assert image.read == 3 and image.bytes_read < 3 * 1_000_000
    assert result.findings == []


def test_progress_shows_only_on_a_terminal_after_two_seconds(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    import io

    from sensorkit.cli import recording as cmd

    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    clock = [100.0]
    monkeypatch.setattr(cmd.time, "monotonic", lambda: clock[0])
    tty, pipe = Tty(), io.StringIO()
    bars = [cmd.ProgressBar("car.bag", tty), cmd.ProgressBar("car.bag", pipe)]
    clock[0] = 101.9
    for bar in bars:
        bar(1, 4, "/camera/image_raw")
    assert tty.getvalue() == ""
    clock[0] = 102.1
    for bar in bars:
        bar(2, 4, "/lidar/scan")
    assert "2/4 /lidar/scan" in tty.getvalue() and "[############............]" in tty.getvalue()
    for bar in bars:
        bar(4, 4, "done")
    assert tty.getvalue().endswith("\r\x1b[K") and pipe.getvalue() == ""


# --------------------------------------------------------------------------- the command


@pytest.fixture(scope="module")
def bad_bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    scene = _k(small(car_scene()), dfx=300.0 - FX)
    return write_bag(scene, tmp_path_factory.mktemp("bad") / "bad", "mcap")


def test_json_sarif_github_and_exit_codes(bad_bag: Path) -> None:
    res = cli("check-recording", str(bad_bag), str(CAR), "-f", "json")
    assert res.returncode == 1, res.stderr
    doc = json.loads(res.stdout)
    assert doc["version"] == 1 and doc["target"] == "classic"
    assert [Path(f).resolve() for f in doc["files"]] == [bad_bag.resolve()]
    (f,) = doc["findings"]
    assert f["rule"] == "SK806" and f["sensor"] == "camera" and f["severity"] == "error"
    assert f["file"].endswith("depth_camera.urdf.xacro") and isinstance(f["line"], int)
    sarif = json.loads(cli("check-recording", str(bad_bag), str(CAR), "-f", "sarif").stdout)
    rules = [r["id"] for r in sarif["runs"][0]["tool"]["driver"]["rules"]]
    assert "SK806" in rules and sarif["runs"][0]["results"][0]["ruleId"] == "SK806"
    gh = cli("check-recording", str(bad_bag), str(CAR), "-f", "github").stdout
    assert re.match(r"::error file=.*,line=\d+,title=SK806::", gh)
    assert cli("check-recording", str(bad_bag), str(CAR), "--exit-zero").returncode == 0
    assert cli("check-recording", str(bad_bag), str(CAR), "--fail-on", "never").returncode == 0


def test_what_cannot_be_read_is_one_line_and_exit_2(tmp_path: Path) -> None:
    junk = tmp_path / "junk.bag"
    junk.write_bytes(b"not a bag at all" * 100)
    for bag in (junk, tmp_path / "missing.mcap"):
        res = cli("check-recording", str(bag), str(CAR))
        assert res.returncode == 2, res.stderr
        (line,) = res.stderr.strip().splitlines()
        assert line.startswith("sensorkit: ") and str(bag) in line and "Traceback" not in res.stderr


def test_without_rosbags_the_error_says_how_to_install(monkeypatch: pytest.MonkeyPatch) -> None:
    from sensorkit.base.errors import UsageError
    from sensorkit.recording import bag

    monkeypatch.setitem(sys.modules, "rosbags", None)
    with pytest.raises(UsageError, match=re.escape("pip install 'sensorkit-ros[recording]'")):
        bag._rosbags()


def test_the_other_commands_never_import_rosbags() -> None:
    code = (
        "import sys, sensorkit.cli, sensorkit.cli.recording, sensorkit.cli.topics; "
        "print('rosbags' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


@pytest.mark.parametrize(("degrees", "optical"), [(0.6, False), (0.4, True)])
def test_sk805_says_a_camera_frame_is_not_optical_past_half_a_degree(
    degrees: float, optical: bool, run: Callable[..., list[Finding]]
) -> None:
    """The optical frame moved 1.1 mm (SK805 either way) and turned 0.6 or 0.4 degrees:
    only past ANGLE_TOL does the message add that the camera's data is stamped with a frame
    that is not optical (recording/frames.py _not_optical)."""
    scene = _turn_tf(_move_tf(small(car_scene()), "camera_optical_frame", 0.0011), "camera_optical_frame", degrees)
    (found,) = of(run(scene), "SK805")
    assert ("not an optical frame" in found.message) is not optical, found.message
