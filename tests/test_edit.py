"""``sensorkit add-*``: acceptance on hand-written robots, byte preservation, refusals.

Every test works on a copy in ``tmp_path``; the fixtures in ``tests/edit_robots`` are
never edited.
"""

from __future__ import annotations

import difflib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from lxml import etree
from typer.testing import CliRunner

from sensorkit.base.errors import EditRefused, UsageError
from sensorkit.base.findings import Severity
from sensorkit.base.resources import macros_dir
from sensorkit.cli import app
from sensorkit.edit import AddRequest, add_sensor, apply_add, plan_add
from sensorkit.lint.engine import Options, validate_file

ROBOTS = Path(__file__).resolve().parent / "edit_robots"
XACRO_BIN = Path(sys.executable).parent / "xacro"
CHECK_URDF = "/usr/bin/check_urdf"


# --------------------------------------------------------------------------- helpers


def cli(*args: object) -> tuple[int, str, str]:
    result = CliRunner().invoke(app, [str(a) for a in args])
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


def lines_kept(old: bytes, new: bytes) -> bool:
    """Every original line is still there, whole and in order: the diff only adds."""
    a = old.splitlines(keepends=True)
    b = new.splitlines(keepends=True)
    ops = difflib.SequenceMatcher(None, a, b, autojunk=False).get_opcodes()
    return all(tag in ("equal", "insert") for tag, *_ in ops)


def is_subsequence(old: bytes, new: bytes) -> bool:
    it = iter(new)
    return all(any(c == d for d in it) for c in old)


def snapshot(folder: Path) -> dict[str, bytes]:
    return {
        str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()
    }


def check_urdf(path: Path) -> subprocess.CompletedProcess[str]:
    exe = CHECK_URDF if Path(CHECK_URDF).exists() else shutil.which("check_urdf")
    if exe is None:
        pytest.fail("check_urdf is missing (apt-get install liburdfdom-tools)")
    return subprocess.run([exe, str(path)], capture_output=True, text=True, timeout=20, check=False)


def no_warnings(path: Path) -> None:
    report = validate_file(path, Options())
    assert report.error is None, report.error
    bad = [f for f in report.findings if f.severity >= Severity.WARNING]
    assert not bad, [(f.rule, f.message) for f in bad]


def xacro_expand(path: Path) -> str:
    run = subprocess.run(
        [str(XACRO_BIN), path.name],
        cwd=path.parent,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert run.returncode == 0, run.stderr
    return run.stdout


@pytest.fixture
def rover(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", path)
    return path


@pytest.fixture
def xrover(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    shutil.copytree(ROBOTS / "xacro_robot", tmp_path / "xrover")
    return tmp_path / "xrover" / "robot.urdf.xacro"


THREE_ADDS = (
    ("add-camera", "--name", "front_camera", "--parent", "base_link", "--xyz", "0.2", "0", "0.05"),
    (
        "add-depth-camera",
        "--name",
        "depth_camera",
        "--parent",
        "base_link",
        "--xyz",
        "0.2",
        "0",
        "-0.03",
    ),
    ("add-lidar", "--name", "lidar", "--parent", "base_link", "--xyz", "0", "0", "0.12"),
)


# --------------------------------------------------------------------------- acceptance


def test_urdf_three_adds_validate_and_keep_every_line(rover: Path) -> None:
    original = rover.read_bytes()
    for cmd, *rest in THREE_ADDS:
        code, _out, err = cli(cmd, rover, *rest)
        assert code == 0, err
    new = rover.read_bytes()

    code, out, err = cli("validate", rover)
    assert code == 0, out + err
    no_warnings(rover)
    run = check_urdf(rover)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "front_camera_optical_frame" in run.stdout

    assert lines_kept(original, new)
    assert is_subsequence(original, new)
    assert not (rover.parent / "sensors").exists()  # plain URDF: expanded, no macro copy

    code, _out, err = cli(*THREE_ADDS[0][:1], rover, *THREE_ADDS[0][1:])
    assert code == 2
    assert err.count("\n") == 1 and "front_camera" in err and "already used" in err
    assert rover.read_bytes() == new


def test_xacro_three_adds_expand_with_plain_xacro(xrover: Path) -> None:
    folder = xrover.parent
    original = xrover.read_bytes()
    for cmd, *rest in THREE_ADDS:
        code, _out, err = cli(cmd, xrover, *rest)
        assert code == 0, err
    new = xrover.read_bytes()
    text = new.decode()

    # one relative include per macro file, copied byte for byte next to the robot
    for file in ("camera.urdf.xacro", "depth_camera.urdf.xacro", "lidar_2d.urdf.xacro"):
        assert text.count(f'<xacro:include filename="sensors/{file}"/>') == 1
        assert (folder / "sensors" / file).read_bytes() == (macros_dir() / file).read_bytes()
    assert '<xacro:sensorkit_camera name="front_camera" parent="base_link">' in text
    assert '<origin xyz="0.2 0 0.05" rpy="0 0 0"/>' in text

    code, out, err = cli("validate", xrover)
    assert code == 0, out + err
    no_warnings(xrover)
    expanded = folder / "expanded.urdf"
    expanded.write_text(xacro_expand(xrover))
    run = check_urdf(expanded)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "lidar_link" in run.stdout and "depth_camera_link" in run.stdout

    assert lines_kept(original, new)
    assert is_subsequence(original, new)

    before = snapshot(folder)
    code, _out, err = cli("add-camera", xrover, "--name", "front_camera", "--parent", "base_link")
    assert code == 2 and err.count("\n") == 1 and "front_camera" in err
    # a refused add of a new kind leaves no macro copy behind either
    code, _out, err = cli("add-imu", xrover, "--name", "lidar", "--parent", "base_link")
    assert code == 2 and "lidar" in err
    assert snapshot(folder) == before


def test_every_command_on_urdf(rover: Path) -> None:
    adds = [
        ("add-stereo", "--name", "stereo", "--parent", "base_link",
         "--xyz", "0.2", "0", "0.1", "--baseline", "0.1"),
        ("add-imu", "--name", "imu", "--parent", "base_link"),
        ("add-lidar", "--name", "velo", "--parent", "base_link",
         "--xyz", "0", "0", "0.2", "--3d", "--vertical-samples", "8"),
        ("add-camera", "--name", "rear", "--parent", "base_link", "--xyz", "-0.2", "0", "0.05",
         "--rpy", "0", "0", "3.141592653589793", "--width", "320", "--height", "240",
         "--sim", "classic"),
    ]  # fmt: skip
    for cmd, *rest in adds:
        code, _out, err = cli(cmd, rover, *rest)
        assert code == 0, err
    text = rover.read_text()
    assert 'type="gpu_lidar"' not in text  # classic by default
    assert "<vertical>" in text  # the 3D macro was used
    assert "<width>320</width>" in text
    assert "stereo_left_optical_frame" in text
    no_warnings(rover)
    assert check_urdf(rover).returncode == 0


def test_gz_options_reach_the_macro(xrover: Path) -> None:
    code, _out, err = cli(
        "add-camera", xrover, "--name", "cam", "--parent", "base_link",
        "--sim", "gz", "--gz-version", "fortress", "--namespace", "rover1",
    )  # fmt: skip
    assert code == 0, err
    call = next(ln for ln in xrover.read_text().splitlines() if "sensorkit_camera name" in ln)
    assert 'sim="gz"' in call and 'gz_version="fortress"' in call and 'namespace="rover1"' in call
    assert "<ignition_frame_id>cam_optical_frame</ignition_frame_id>" in xacro_expand(xrover)


# --------------------------------------------------------------------------- file style


def test_crlf_file_stays_crlf(rover: Path) -> None:
    data = rover.read_bytes().replace(b"\n", b"\r\n")
    rover.write_bytes(data)
    code, _out, err = cli("add-camera", rover, "--name", "cam", "--parent", "base_link")
    assert code == 0, err
    new = rover.read_bytes()
    assert new.count(b"\n") == new.count(b"\r\n") > data.count(b"\r\n")
    assert lines_kept(data, new) and is_subsequence(data, new)
    assert check_urdf(rover).returncode == 0


def test_tab_indented_file_gets_tabs(rover: Path) -> None:
    lines = rover.read_text().splitlines(keepends=True)
    tabbed = "".join("\t" * ((len(ln) - len(ln.lstrip(" "))) // 2) + ln.lstrip(" ") for ln in lines)
    rover.write_text(tabbed)
    code, _out, err = cli("add-camera", rover, "--name", "cam", "--parent", "base_link")
    assert code == 0, err
    new = rover.read_text()
    added = new.splitlines()[len(tabbed.splitlines()) - 2 : -2]
    assert any(ln.startswith("\t\t<visual>") for ln in added)
    assert all(not ln.startswith(" ") for ln in new.splitlines())
    assert lines_kept(tabbed.encode(), new.encode())


def test_four_space_indent_is_followed(rover: Path) -> None:
    text = rover.read_text().replace("  ", "    ")
    rover.write_text(text)
    assert cli("add-imu", rover, "--name", "imu", "--parent", "base_link")[0] == 0
    assert '\n    <link name="imu_link">\n        <visual>\n' in rover.read_text()


def test_bom_and_encoding_declaration_are_kept(rover: Path) -> None:
    text = rover.read_text().replace(
        '<?xml version="1.0"?>', '<?xml version="1.0" encoding="UTF-8"?>'
    )
    data = b"\xef\xbb\xbf" + text.encode()
    rover.write_bytes(data)
    assert cli("add-camera", rover, "--name", "cam", "--parent", "base_link")[0] == 0
    new = rover.read_bytes()
    assert new.startswith(b'\xef\xbb\xbf<?xml version="1.0" encoding="UTF-8"?>\n')
    assert is_subsequence(data, new) and lines_kept(data, new)
    no_warnings(rover)


def test_latin1_file_keeps_its_bytes(rover: Path) -> None:
    text = rover.read_text().replace(
        '<?xml version="1.0"?>', '<?xml version="1.0" encoding="ISO-8859-1"?>'
    )
    text = text.replace("<!-- Wheels -->", "<!-- Räder, côté gauche et droit -->")
    data = text.encode("latin-1")
    rover.write_bytes(data)
    assert cli("add-camera", rover, "--name", "cam", "--parent", "base_link")[0] == 0
    new = rover.read_bytes()
    assert b"R\xe4der, c\xf4t\xe9" in new
    assert is_subsequence(data, new) and lines_kept(data, new)
    etree.fromstring(new)  # still well-formed in its declared encoding


def test_utf16_with_bom(rover: Path) -> None:
    data = (
        rover.read_text()
        .replace('<?xml version="1.0"?>', '<?xml version="1.0" encoding="UTF-16"?>')
        .encode("utf-16")
    )
    rover.write_bytes(data)
    result = add_sensor(AddRequest(rover, "imu", "imu", "base_link"), dry_run=True)
    assert result.new.startswith(data[:2])
    decoded = result.new.decode("utf-16")
    assert '<link name="imu_link">' in decoded
    assert decoded.startswith(data.decode("utf-16").split("</robot>")[0][:200])


def test_add_into_a_file_ros_refuses_says_so(rover: Path) -> None:
    """add-* edits a UTF-16 file or a prefixed <r:robot> root byte for byte, and says in a
    note that xacro and check_urdf refuse the file (validate's SK101). The long fuzz run
    found the prefixed root edited without a word."""
    text = rover.read_text()
    utf16 = text.replace('<?xml version="1.0"?>', '<?xml version="1.0" encoding="UTF-16"?>')
    rover.write_bytes(utf16.encode("utf-16"))
    notes = add_sensor(AddRequest(rover, "imu", "imu", "base_link"), dry_run=True).notes
    assert any("is UTF-16" in n and "refuse it" in n for n in notes), notes
    prefixed = text.replace("<robot ", '<r:robot xmlns:r="urn:robot" ', 1).replace(
        "</robot>", "</r:robot>"
    )
    rover.write_text(prefixed)
    notes = add_sensor(AddRequest(rover, "imu", "imu", "base_link"), dry_run=True).notes
    assert any("root element is <r:robot>" in n for n in notes), notes
    # near miss: the plain file gets neither note
    rover.write_text(text)
    notes = add_sensor(AddRequest(rover, "imu", "imu", "base_link"), dry_run=True).notes
    assert not any("refuse" in n for n in notes), notes


def test_closing_tag_lookalikes_are_skipped(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "tricky.urdf"
    data = (
        b'<?xml version="1.0"?>\n'
        b"<?note </robot> in a processing instruction?>\n"
        b'<robot name="tricky"><!-- </robot> -->\n'
        b'  <link name="base_link">\n'
        b'    <inertial><mass value="1"/>'
        b'<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>\n'
        b"  </link>\n"
        b'  <gazebo><plugin name="x" filename="libx.so"><note a=">">'
        b"<![CDATA[ </robot> ]]></note></plugin></gazebo></robot  >\n"
        b"<!-- </robot> -->\n"
    )
    path.write_bytes(data)
    result = add_sensor(
        AddRequest(path, "imu", "imu", "base_link", params={"sim": "none"}), dry_run=True
    )
    root = etree.fromstring(result.new)
    assert [c.get("name") for c in root if c.tag == "link"] == ["base_link", "imu_link"]
    assert is_subsequence(data, result.new)
    # the closing tag shared its line: the block starts a new line, the tag follows it
    assert b"</gazebo>\n  <!-- imu: IMU from sensorkit's sensorkit_imu macro -->\n" in result.new
    assert result.new.endswith(b"  </joint>\n</robot  >\n<!-- </robot> -->\n")


# --------------------------------------------------------------------------- diff and -o


def test_diff_writes_nothing(rover: Path, xrover: Path) -> None:
    for path in (rover, xrover):
        before = snapshot(path.parent)
        code, out, err = cli("add-camera", path, "--name", "cam", "--parent", "base_link", "--diff")
        assert code == 0, err
        assert snapshot(path.parent) == before
        assert f"+++ b/{os.path.relpath(path)}" in out
        assert all(ln[:1] in "+ @-\\" for ln in out.splitlines())
    # the xacro diff shows the macro copy as a new file
    assert "--- /dev/null\n+++ b/xrover/sensors/camera.urdf.xacro" in out


def test_output_elsewhere_leaves_input_untouched(xrover: Path, rover: Path) -> None:
    original = xrover.read_bytes()
    out = xrover.parent / "with_camera.urdf.xacro"
    code, _o, err = cli("add-camera", xrover, "--name", "cam", "--parent", "base_link", "-o", out)
    assert code == 0, err
    assert xrover.read_bytes() == original
    assert (out.parent / "sensors" / "camera.urdf.xacro").is_file()
    assert "cam_optical_frame" in xacro_expand(out)

    # another folder: the macro goes next to OUT, the include is relative to OUT
    other = rover.parent / "elsewhere"
    other.mkdir()
    code, _o, err = cli(
        "add-camera", xrover, "--name", "cam", "--parent", "base_link", "-o", other / "r.urdf.xacro"
    )
    assert code == 0
    assert (other / "sensors" / "camera.urdf.xacro").is_file()
    assert "include 'parts/base.urdf.xacro' does not resolve" in err  # told, not hidden
    assert xrover.read_bytes() == original

    urdf_original = rover.read_bytes()
    code, _o, err = cli(
        "add-camera", rover, "--name", "cam", "--parent", "base_link", "-o", other / "r.urdf"
    )
    assert code == 0, err
    assert rover.read_bytes() == urdf_original
    assert lines_kept(urdf_original, (other / "r.urdf").read_bytes())


# --------------------------------------------------------------------------- refusals


def test_missing_parent_names_the_closest_links(rover: Path) -> None:
    original = rover.read_bytes()
    code, _out, err = cli("add-camera", rover, "--name", "cam", "--parent", "base_lnk")
    assert code == 2 and err.count("\n") == 1
    assert "base_lnk" in err and "base_link" in err
    assert rover.read_bytes() == original


@pytest.mark.parametrize(
    ("extra", "clash"),
    [
        ('<link name="cam"/>', "link 'cam'"),
        ('<link name="cam_optical_frame"/>', "link 'cam_optical_frame'"),
        ('<joint name="cam_joint" type="fixed"><parent link="base_link"/><child link="x"/></joint>'
         '<link name="x"/>', "joint 'cam_joint'"),
        ('<joint name="cam_optical_joint" type="fixed"><parent link="base_link"/><child link="x"/>'
         '</joint><link name="x"/>', "joint 'cam_optical_joint'"),
        ('<gazebo reference="base_link"><sensor name="cam" type="imu"/></gazebo>', "sensor 'cam'"),
    ],
)  # fmt: skip
def test_taken_names_refuse(rover: Path, extra: str, clash: str) -> None:
    rover.write_text(rover.read_text().replace("\n</robot>", f"\n  {extra}\n</robot>", 1))
    original = rover.read_bytes()
    code, _out, err = cli("add-camera", rover, "--name", "cam", "--parent", "base_link")
    assert code == 2 and err.count("\n") == 1
    assert clash in err and "'cam'" in err
    assert rover.read_bytes() == original


def test_new_validator_error_refuses(rover: Path) -> None:
    original = rover.read_bytes()
    code, _out, err = cli(
        "add-camera", rover, "--name", "cam", "--parent", "base_link", "--near", "0"
    )
    assert code == 2 and "SK405" in err and err.count("\n") == 1
    assert rover.read_bytes() == original


def test_plugin_node_clash_refuses(rover: Path) -> None:
    text = rover.read_text().replace(
        "\n</robot>",
        '\n  <gazebo reference="base_link">\n    <sensor name="other" type="camera">\n'
        "      <update_rate>10</update_rate>\n"
        '      <plugin name="front_controller" filename="libgazebo_ros_camera.so">\n'
        "        <camera_name>other</camera_name>\n      </plugin>\n"
        "    </sensor>\n  </gazebo>\n</robot>",
        1,
    )
    rover.write_text(text)
    before = rover.read_bytes()
    with pytest.raises(EditRefused, match="SK604"):
        plan_add(AddRequest(rover, "camera", "front", "base_link"))
    assert rover.read_bytes() == before


def test_usage_errors(rover: Path) -> None:
    assert cli("add-camera", rover, "--name", "1cam", "--parent", "base_link")[0] == 2
    code, _o, err = cli(
        "add-camera", rover, "--name", "cam", "--parent", "base_link", "--param", "bogus=1"
    )
    assert code == 2 and "bogus" in err and "hfov" in err
    code, _o, err = cli(
        "add-lidar", rover, "--name", "l", "--parent", "base_link", "--vertical-samples", "4"
    )
    assert code == 2 and "--3d" in err
    with pytest.raises(UsageError):
        plan_add(AddRequest(rover, "sonar", "s", "base_link"))


def test_broken_file_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "broken.urdf"
    path.write_bytes(b'<robot name="r">\n  <link name="a">\n</robot>\n')
    with pytest.raises(EditRefused, match="not well-formed"):
        plan_add(AddRequest(path, "imu", "imu", "a"))


# --------------------------------------------------------------------------- xacro details


def test_second_sensor_of_a_kind_reuses_the_include(xrover: Path) -> None:
    assert cli("add-camera", xrover, "--name", "a", "--parent", "base_link")[0] == 0
    code, _o, err = cli(
        "add-camera", xrover, "--name", "b", "--parent", "base_link", "--xyz", "0", "1", "0"
    )
    assert code == 0, err
    assert xrover.read_text().count("sensors/camera.urdf.xacro") == 1
    assert "b_optical_frame" in xacro_expand(xrover)


def test_namespace_declaration_added_only_when_missing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "plain.urdf.xacro"
    data = (ROBOTS / "rover.urdf").read_bytes()
    path.write_bytes(data)
    assert cli("add-imu", path, "--name", "imu", "--parent", "base_link")[0] == 0
    new = path.read_bytes()
    assert b'<robot name="rover" xmlns:xacro="http://www.ros.org/wiki/xacro">' in new
    assert is_subsequence(data, new)
    assert "imu_link" in xacro_expand(path)
    assert cli("add-camera", path, "--name", "cam", "--parent", "base_link")[0] == 0
    assert path.read_bytes().count(b"xmlns:xacro") == 1


def test_local_macro_copies(xrover: Path) -> None:
    local = xrover.parent / "sensors" / "camera.urdf.xacro"
    local.parent.mkdir()
    shipped = (macros_dir() / "camera.urdf.xacro").read_bytes()

    # identical copy: used silently
    local.write_bytes(shipped)
    result = add_sensor(AddRequest(xrover, "camera", "a", "base_link"), dry_run=True)
    assert [w.role for w in result.writes] == ["robot"] and not result.notes

    # modified copy that still defines the macro: left alone, used, and said so
    modified = shipped.replace(b"0.15 0.15 0.15 1.0", b"0.9 0.1 0.1 1.0")
    local.write_bytes(modified)
    code, _o, err = cli("add-camera", xrover, "--name", "a", "--parent", "base_link")
    assert code == 0 and "modified copy" in err
    assert local.read_bytes() == modified
    assert "0.9 0.1 0.1 1.0" in xacro_expand(xrover)

    # a copy without the macro: refused, nothing touched
    local.write_bytes(b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>\n')
    before = snapshot(xrover.parent)
    code, _o, err = cli("add-camera", xrover, "--name", "b", "--parent", "base_link")
    assert code == 2 and "sensorkit_camera" in err
    assert snapshot(xrover.parent) == before


# --------------------------------------------------------------------------- library and publishing


def test_library_plan_then_apply(xrover: Path) -> None:
    original = xrover.read_bytes()
    result = plan_add(
        AddRequest(
            xrover, "imu", "imu", "base_link", xyz=(0, 0, 0.05), params={"update_rate": "200"}
        )
    )
    assert xrover.read_bytes() == original and not (xrover.parent / "sensors").exists()
    assert [w.role for w in result.writes] == ["macro", "robot"]
    assert (
        result.links == ["imu_link"]
        and result.joints == ["imu_joint"]
        and result.sensors == ["imu"]
    )
    assert result.style == "xacro" and result.original == original
    assert 'update_rate="200"' in result.new.decode()
    apply_add(result)
    assert result.written and xrover.read_bytes() == result.new
    assert (xrover.parent / "sensors" / "imu.urdf.xacro").is_file()


def test_file_changed_after_planning_is_not_overwritten(rover: Path) -> None:
    result = plan_add(AddRequest(rover, "imu", "imu", "base_link"))
    rover.write_bytes(rover.read_bytes() + b"<!-- edited meanwhile -->\n")
    edited = rover.read_bytes()
    with pytest.raises(EditRefused, match="changed"):
        apply_add(result)
    assert rover.read_bytes() == edited


def test_mode_and_symlink_are_kept(rover: Path) -> None:
    os.chmod(rover, 0o640)
    link = rover.parent / "link.urdf"
    link.symlink_to(rover.name)
    assert cli("add-imu", link, "--name", "imu", "--parent", "base_link")[0] == 0
    assert link.is_symlink()
    assert (rover.stat().st_mode & 0o777) == 0o640
    assert b"imu_link" in rover.read_bytes()
    assert not [p for p in rover.parent.iterdir() if p.name.endswith(".sensorkit-tmp")]


def test_add_to_a_robot_with_a_default_namespace(tmp_path: Path) -> None:
    # urdfdom ignores a default xmlns; the validator drops it on load, and so must the
    # re-validation of the result (it once refused this add with a false SK301).
    robot = tmp_path / "ns.urdf"
    robot.write_text(
        '<?xml version="1.0"?>\n<robot name="r" xmlns="http://www.ros.org">\n'
        '  <link name="base_footprint"/>\n'
        '  <joint name="bj" type="fixed"><parent link="base_footprint"/><child link="base_link"/></joint>\n'
        '  <link name="base_link"><inertial><mass value="1"/>'
        '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>\n'
        "</robot>\n"
    )
    result = add_sensor(AddRequest(path=robot, kind="camera", name="cam", parent="base_link"))
    assert result.written
    report = validate_file(robot)
    assert [f for f in report.findings if f.severity >= Severity.WARNING] == []
    assert report.robot is not None and "cam_optical_frame" in report.robot.link_map
