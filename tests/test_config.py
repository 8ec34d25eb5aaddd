"""Issue 12: one settings file for every command, found upward from the robot file.

A ``sensorkit.toml`` (or ``[tool.sensorkit]`` in a pyproject.toml) beside or above the
robot applies to validate, add-*, render, intrinsics, export and new; flags win; the
command says where each setting came from.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROBOTS = Path(__file__).resolve().parent / "edit_robots"


def _cli(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "sensorkit", *args],
        capture_output=True, text=True, timeout=120, check=False, cwd=cwd,
    )  # fmt: skip


@pytest.fixture
def project(tmp_path: Path) -> Path:
    """A project folder with the settings file, the robot one folder below, run from elsewhere."""
    from builders import gz_robot

    # Sensors with <topic> but no simulator-specific tag: auto takes it for Classic.
    text = gz_robot(camera_tags="<topic>front_camera/image_raw</topic>", lidar_tags="<topic>scan</topic>")
    start = text.index('<gazebo><plugin filename="gz-sim-sensors-system"')
    text = text[:start] + text[text.index("</gazebo>", start) + len("</gazebo>") :]
    text = text.replace('type="gpu_lidar"', 'type="gpu_ray"')  # both simulators create gpu_ray
    (tmp_path / "proj" / "urdf").mkdir(parents=True)
    (tmp_path / "proj" / "urdf" / "rover.urdf").write_text(text)
    (tmp_path / "elsewhere").mkdir()
    return tmp_path


def test_target_from_sensorkit_toml_changes_every_command(project: Path) -> None:
    path = project / "proj" / "urdf" / "rover.urdf"
    cwd = project / "elsewhere"  # found from the robot file, not from the working folder
    # Without settings: Classic everywhere.
    res = _cli("intrinsics", str(path), cwd=cwd)
    assert res.returncode == 0, res.stderr
    assert json.loads(res.stdout)["convention"] == "classic"
    res = _cli("export", str(path), "--out", str(project / "exp0"), cwd=cwd)
    assert res.returncode in (0, 1) and (project / "exp0").is_dir(), res.stderr  # 1: some files skipped
    assert not list((project / "exp0").rglob("bridge.yaml"))

    (project / "proj" / "sensorkit.toml").write_text('target = "harmonic"\n')
    res = _cli("intrinsics", str(path), cwd=cwd)
    assert res.returncode == 0, res.stderr
    assert json.loads(res.stdout)["convention"] == "gz"
    assert "target harmonic from" in res.stderr and "sensorkit.toml" in res.stderr
    res = _cli("export", str(path), "--out", str(project / "exp1"), cwd=cwd)
    assert res.returncode in (0, 1) and list((project / "exp1").rglob("bridge.yaml")), res.stderr
    res = _cli("validate", str(path), cwd=cwd)
    assert "target harmonic; chosen with" in res.stdout and "sensorkit.toml" in res.stdout
    # add-* writes Gazebo Sim blocks for the project's gz version.
    res = _cli("add-camera", str(path), "--name", "rear_camera", "--parent", "base_link", cwd=cwd)
    assert res.returncode == 0, res.stderr
    text = path.read_text()
    new = text[text.index('name="rear_camera"') - 200 :]
    assert "gz-sim" in text or "gz_frame_id" in new or "<topic>" in new, new[:600]
    assert "libgazebo_ros_camera.so" not in new
    assert "target harmonic from" in res.stderr
    # A flag still wins over the file.
    res = _cli("intrinsics", str(path), "--target", "classic", cwd=cwd)
    assert json.loads(res.stdout)["convention"] == "classic"


def test_pyproject_without_a_table_is_passed_over_and_config_flag_wins(project: Path) -> None:
    path = project / "proj" / "urdf" / "rover.urdf"
    (project / "proj" / "urdf" / "pyproject.toml").write_text('[project]\nname = "x"\n')
    (project / "proj" / "pyproject.toml").write_text('[tool.sensorkit]\ntarget = "fortress"\n')
    res = _cli("intrinsics", str(path), cwd=project / "elsewhere")
    assert json.loads(res.stdout)["convention"] == "gz" and "target fortress" in res.stderr
    other = project / "other.toml"
    other.write_text('target = "classic"\n')
    res = _cli("intrinsics", str(path), "--config", str(other), cwd=project / "elsewhere")
    assert json.loads(res.stdout)["convention"] == "classic", res.stderr


@pytest.mark.parametrize(
    ("text", "says"),
    [("bogus = 1\n", "unknown keys ['bogus']"), ("target = [\n", "cannot read")],
)
def test_bad_settings_files_are_one_line_errors(project: Path, text: str, says: str) -> None:
    (project / "proj" / "sensorkit.toml").write_text(text)
    path = project / "proj" / "urdf" / "rover.urdf"
    for cmd in (["validate", str(path)], ["intrinsics", str(path)], ["render", "preview", str(path)]):
        res = _cli(*cmd, cwd=project / "elsewhere")
        assert res.returncode == 2 and says in res.stderr and len(res.stderr.strip().splitlines()) == 1, (cmd, res.stderr)


def test_missing_config_file_is_a_usage_error(project: Path) -> None:
    res = _cli("validate", str(project / "proj" / "urdf" / "rover.urdf"), "--config", "nope.toml", cwd=project)
    assert res.returncode == 2 and "--config nope.toml: no such file" in res.stderr


def test_new_takes_the_simulator_from_the_settings_file(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(
        "name: my_robot\nsensors:\n  - type: camera\n    name: front_camera\n    xyz: [0.25, 0, 0.1]\n"
    )
    (tmp_path / "sensorkit.toml").write_text('target = "classic"\n')
    res = _cli("new", str(spec), "-o", str(tmp_path / "pkg"), cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    assert not (tmp_path / "pkg" / "config" / "bridge.yaml").exists()  # Classic: no bridge
    assert "target classic from" in res.stderr
    (tmp_path / "sensorkit.toml").unlink()
    res = _cli("new", str(spec), "-o", str(tmp_path / "pkg2"), cwd=tmp_path)
    assert res.returncode == 0 and (tmp_path / "pkg2" / "config" / "bridge.yaml").exists(), res.stderr


def test_untrusted_settings_cannot_widen_package_paths(tmp_path: Path) -> None:
    shutil.copyfile(ROBOTS / "rover.urdf", tmp_path / "rover.urdf")
    (tmp_path / "sensorkit.toml").write_text('package-path = ["/"]\n')
    res = _cli("validate", "--untrusted", str(tmp_path / "rover.urdf"), cwd=tmp_path)
    assert res.returncode == 2 and "outside" in res.stderr
