"""Issue 13: command-line habits from ruff, cargo, xacro and ros2 launch that users try first."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pytest
import yaml
from conftest import ROOT, run_cli

ROBOTS = Path(__file__).resolve().parent / "edit_robots"


def test_short_version_flag() -> None:
    res = run_cli("-V")
    assert res.returncode == 0 and re.fullmatch(r"sensorkit \d+\.\d+\.\d+\s*", res.stdout)


def test_render_without_subcommand_names_the_one_it_needs() -> None:
    res = run_cli("render", "robot.urdf")
    assert res.returncode == 2
    text = " ".join(re.sub(r"[│╭╮╰╯─]", " ", res.stderr).split())  # rich draws a box
    assert "did you mean: sensorkit render preview robot.urdf" in text, res.stderr
    res = run_cli("render", "--bogus")  # an option is not a file: the usual message
    assert res.returncode == 2 and "render preview" not in res.stderr


def test_pre_commit_hook_skips_sdf_written_as_xacro() -> None:
    hook = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())[0]
    pattern = re.compile(hook["files"])
    assert pattern.search("robot.urdf") and pattern.search("robot.urdf.xacro") and pattern.search("parts/arm.xacro")
    assert not pattern.search("worlds/world.sdf.xacro") and not pattern.search("model.sdf")


@pytest.mark.parametrize("cmd", [["validate"], ["intrinsics"], ["export", "--out", "x"], ["render", "preview"]])
def test_a_package_path_that_does_not_exist_is_a_usage_error(tmp_path: Path, cmd: list[str]) -> None:
    path = tmp_path / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", path)
    res = run_cli(*cmd, str(path), "--package-path", str(tmp_path / "nope"), cwd=tmp_path)
    assert res.returncode == 2 and f"--package-path {tmp_path / 'nope'}: no such folder" in res.stderr
    assert len(res.stderr.strip().splitlines()) == 1
    res = run_cli(*cmd, str(path), "--package-path", f"pkg={tmp_path / 'nope'}", cwd=tmp_path)
    assert res.returncode == 2 and "no such folder" in res.stderr
    # Near miss: an existing folder is accepted.
    res = run_cli("validate", str(path), "--package-path", str(tmp_path))
    assert res.returncode == 0, res.stderr


def test_rpy_in_degrees_is_refused_with_a_hint(tmp_path: Path) -> None:
    path = tmp_path / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", path)
    before = path.read_bytes()
    res = run_cli("add-camera", str(path), "--name", "cam", "--parent", "base_link", "--rpy", "0", "0", "90")
    assert res.returncode == 2 and "radians" in res.stderr and "1.5708" in res.stderr, res.stderr
    assert path.read_bytes() == before
    res = run_cli("add-camera", str(path), "--name", "cam", "--parent", "base_link", "--rpy", "0", "0", "6.2")
    assert res.returncode == 0, res.stderr


def test_one_spelling_for_output_folders(tmp_path: Path) -> None:
    path = tmp_path / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", path)
    for spelling in ("--out", "--output", "-o"):
        out = tmp_path / f"exp{spelling}"
        res = run_cli("export", str(path), spelling, str(out))
        assert res.returncode in (0, 1) and out.is_dir(), res.stderr
    spec = tmp_path / "robot.yaml"
    spec.write_text("name: my_robot\n")
    for spelling in ("--out", "--output", "-o"):
        out = tmp_path / f"pkg{spelling}"
        res = run_cli("new", str(spec), spelling, str(out))
        assert res.returncode == 0 and (out / "package.xml").is_file(), res.stderr
    res = run_cli("render", "preview", "-h")
    assert "--output" in res.stdout and "--out" in res.stdout


def test_a_file_that_cannot_be_checked_is_never_a_clean_run(tmp_path: Path) -> None:
    good = tmp_path / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", good)
    bad = tmp_path / "notes.urdf"
    bad.write_text("<html><body>not a robot</body></html>\n")
    res = run_cli("validate", str(good), str(bad))
    assert res.returncode == 2
    assert "1 file could not be checked" in res.stdout, res.stdout
    res = run_cli("validate", "--format", "sarif", str(good), str(bad))
    inv = json.loads(res.stdout)["runs"][0]["invocations"][0]
    assert inv["executionSuccessful"] is False
    uris = [n["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for n in inv["toolExecutionNotifications"]]
    assert len(uris) == 1 and uris[0].endswith("notes.urdf"), uris
    # Near miss: all files checked.
    res = run_cli("validate", "--format", "sarif", str(good))
    assert json.loads(res.stdout)["runs"][0]["invocations"][0] == {"executionSuccessful": True}
    res = run_cli("validate", str(good))
    assert "could not be checked" not in res.stdout


def test_rules_lists_explains_and_validates_its_format() -> None:
    res = run_cli("rules", "-f", "json")
    rows = json.loads(res.stdout)
    assert res.returncode == 0 and {r["id"] for r in rows} >= {"SK101", "SK502", "SK614"}
    assert next(r for r in rows if r["id"] == "SK505")["fixable"]
    res = run_cli("rules", "SK502")
    assert res.returncode == 0 and "bad:" in res.stdout and "good:" in res.stdout and "why:" in res.stdout
    res = run_cli("rules", "sk502", "-f", "json")
    (row,) = json.loads(res.stdout)
    assert row["id"] == "SK502" and "camera_optical_frame" in row["good"]
    for bad in (["rules", "-f", "yaml"], ["rules", "SK999"]):
        res = run_cli(*bad)
        assert res.returncode == 2 and len(res.stderr.strip().splitlines()) == 1, res.stderr


def _plugin_params(fragment: str) -> str:
    return re.search(r"<plugin[^>]*>\s*(.*?)\s*</plugin>", fragment, re.S).group(1)  # type: ignore[union-attr]


@pytest.mark.parametrize("rule", ["SK502", "SK602", "SK505"])
def test_rule_examples_do_what_they_say(check: object, rule: str) -> None:
    # The bad example triggers its rule; the good one does not (sensorkit/explain.py).
    from builders import camera_sensor, robot

    from sensorkit.explain import EXAMPLES

    ex = EXAMPLES[rule]
    if rule == "SK505":
        rpy = re.compile(r'rpy="([^"]+)"')
        bad = robot(optical_rpy=rpy.search(ex.bad).group(1))  # type: ignore[union-attr]
        good = robot(optical_rpy=rpy.search(ex.good).group(1))  # type: ignore[union-attr]
    else:
        bad = robot(camera=camera_sensor(params=_plugin_params(ex.bad)))
        good = robot(camera=camera_sensor(params=_plugin_params(ex.good)))
    rules_bad = {f.rule for f in check(bad).findings}  # type: ignore[operator]
    rules_good = {f.rule for f in check(good).findings}  # type: ignore[operator]
    assert rule in rules_bad and rule not in rules_good, (rules_bad, rules_good)


def test_positional_name_value_is_a_xacro_arg(tmp_path: Path) -> None:
    # `xacro robot.xacro prefix:=zz_` and `ros2 launch ... prefix:=zz_` habits.
    path = tmp_path / "r.urdf.xacro"
    path.write_text(
        '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:arg name="prefix" default="a_"/>\n<link name="$(arg prefix)base"/>\n</robot>\n'
    )
    res = run_cli("validate", str(path), "prefix:=zz_", "-f", "json")
    assert res.returncode in (0, 1), res.stderr
    assert "zz_base" in res.stdout and "a_base" not in res.stdout
    res = run_cli("validate", str(path), "-f", "json")  # near miss: the default
    assert "a_base" in res.stdout
    from sensorkit.cli import xacro_args_as_options

    assert xacro_args_as_options(["validate", "--arg", "a:=1", "b:=2", "x.urdf"]) == [
        "validate", "--arg", "a:=1", "--arg", "b:=2", "x.urdf"
    ]
