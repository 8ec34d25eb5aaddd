"""Output contract: json, sarif 2.1.0, github annotations, text; exit codes, select/ignore, config, suppressions."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from builders import camera_sensor, gz_robot, lidar_sensor, robot
from conftest import ROOT
from conftest import run_cli as cli

from sensorkit.base.findings import Severity
from sensorkit.lint.rules import RULES

BAD = ROOT / "tests/robots/acceptance/sk502_bad.urdf"
GOOD = ROOT / "tests/robots/acceptance/sk502_fixed.urdf"




def test_json_contract() -> None:
    res = cli("validate", str(BAD), str(GOOD), "--format", "json")
    assert res.returncode == 1
    data = json.loads(res.stdout)
    assert data["version"] == 1 and data["target"] == "classic" and len(data["files"]) == 2
    assert data["summary"] == {"error": 1, "warning": 0, "info": 0}
    (f,) = data["findings"]
    for key in ("rule", "severity", "message", "file", "line", "sensor", "frame", "fix"):
        assert key in f
    assert f["rule"] == "SK502" and f["severity"] == "error" and isinstance(f["line"], int)


def test_sarif_structure() -> None:
    res = cli("validate", str(BAD), "--format", "sarif")
    data = json.loads(res.stdout)
    assert data["version"] == "2.1.0" and data["$schema"].endswith("sarif-2.1.0.json")
    (run,) = data["runs"]
    driver = run["tool"]["driver"]
    assert driver["name"] == "sensorkit" and isinstance(driver["version"], str)
    ids = [r["id"] for r in driver["rules"]]
    assert ids == sorted(RULES) and len(set(ids)) == len(ids)
    for r in driver["rules"]:
        assert r["shortDescription"]["text"] and r["defaultConfiguration"]["level"] in ("error", "warning", "note")
    for result in run["results"]:
        assert driver["rules"][result["ruleIndex"]]["id"] == result["ruleId"]
        assert result["level"] in ("error", "warning", "note", "none")
        assert result["message"]["text"]
        loc = result["locations"][0]["physicalLocation"]
        assert loc["artifactLocation"]["uri"].endswith("sk502_bad.urdf")
        assert loc["region"]["startLine"] >= 1


def test_github_annotations() -> None:
    res = cli("validate", str(BAD), "--format", "github")
    (line,) = res.stdout.splitlines()
    assert line.startswith("::error file=") and ",line=" in line and "title=SK502::" in line and "\n" not in line


def test_text_groups_by_sensor_with_fix() -> None:
    out = cli("validate", str(BAD)).stdout
    assert "sensor front_camera:" in out and "fix: " in out and "SK502 [*] error" in out


def test_exit_codes_fail_on_select_ignore(tmp_path: Path) -> None:
    warn = tmp_path / "warn.urdf"
    warn.write_text(robot(camera=camera_sensor(extra="")))  # SK407 warning only
    assert cli("validate", str(warn)).returncode == 0
    assert cli("validate", str(warn), "--fail-on", "warning").returncode == 1
    assert cli("validate", str(BAD), "--ignore", "SK502").returncode == 0
    assert cli("validate", str(BAD), "--select", "SK5").returncode == 1
    assert cli("validate", str(BAD), "--select", "SK4").returncode == 0
    bad_opt = cli("validate", str(BAD), "--select", "XX1")
    assert bad_opt.returncode == 2 and "Traceback" not in bad_opt.stderr
    assert cli("validate", str(BAD), "--target", "gazebo").returncode == 2
    assert cli("validate", str(BAD), "--arg", "oops").returncode == 2


def test_pyproject_config(tmp_path: Path) -> None:
    (tmp_path / "pyproject.toml").write_text('[tool.sensorkit]\nignore = ["SK502"]\nfail-on = "warning"\n')
    robot_file = tmp_path / "r.urdf"
    robot_file.write_text(BAD.read_text())
    assert cli("validate", "r.urdf", cwd=tmp_path).returncode == 0
    robot_file.write_text(robot(camera=camera_sensor(extra="")))
    assert cli("validate", "r.urdf", cwd=tmp_path).returncode == 1  # fail-on warning from config
    (tmp_path / "pyproject.toml").write_text('[tool.sensorkit]\nbogus = 1\n')
    res = cli("validate", "r.urdf", cwd=tmp_path)
    assert res.returncode == 2 and "bogus" in res.stderr


def test_inline_suppression(tmp_path: Path) -> None:
    text = BAD.read_text()
    lines = text.splitlines()
    idx = next(i for i, line in enumerate(lines) if "<sensor " in line)
    p = tmp_path / "s.urdf"
    p.write_text("\n".join([*lines[:idx], "      <!-- sensorkit: ignore SK502 -->", *lines[idx:]]) + "\n")
    assert cli("validate", str(p)).returncode == 0
    p.write_text("\n".join([*lines[:idx], "      <!-- sensorkit: ignore SK503 -->", *lines[idx:]]) + "\n")
    assert cli("validate", str(p)).returncode == 1
    p.write_text(text.replace("<robot ", "<!-- sensorkit: ignore-file SK502 -->\n<robot ", 1))
    assert cli("validate", str(p)).returncode == 0


def test_docs_rule_table_matches_registry() -> None:
    # the table moved from the README to docs/rules.md (issue 38); the README links it
    from sensorkit.fix import fixable
    from sensorkit.lint.report import rule_table

    doc = (ROOT / "docs" / "rules.md").read_text()
    begin, end = "<!-- rules:begin -->\n", "<!-- rules:end -->"
    assert begin in doc and end in doc, "docs/rules.md lacks the generated rule table markers"
    table = doc.split(begin, 1)[1].split(end, 1)[0]
    assert table == rule_table(fixable), "docs/rules.md rule table drifted: run `sensorkit rules --format markdown`"
    assert "(docs/rules.md)" in (ROOT / "README.md").read_text()


def test_the_severity_contract_is_in_the_docs_and_in_rules() -> None:
    """Issue 23: the promise each severity makes is written once (SEVERITY_CONTRACT) and
    said in shared terms in docs/rules.md and by `sensorkit rules`."""
    from sensorkit.base.findings import SEVERITY_CONTRACT

    readme = (ROOT / "docs" / "rules.md").read_text()  # moved from the README (issue 38)
    listing = cli("rules").stdout
    for level, promise in SEVERITY_CONTRACT.items():
        assert f"- **{level.label}**: {promise}" in readme, level
        assert promise in listing, level
    assert set(SEVERITY_CONTRACT) == {Severity.ERROR, Severity.WARNING, Severity.INFO}


def test_validate_does_not_import_pybullet_or_trimesh() -> None:
    # -X importtime logs every import on stderr as it happens (validate ends with os._exit).
    res = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "sensorkit", "validate", str(GOOD)],
        check=False,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert res.returncode == 0, res.stdout + res.stderr
    imported = {line.rsplit("|", 1)[-1].strip() for line in res.stderr.splitlines() if "|" in line}
    assert "sensorkit.lint.engine" in imported  # the log is real
    assert not {m for m in imported if m.split(".")[0] in ("pybullet", "trimesh", "yourdfpy")}


def test_validate_of_sensors_does_not_import_numpy_pybullet_or_rich(tmp_path: Path) -> None:
    # Cameras and lidars with wrong frames (SK502, SK504: frame arithmetic and the search
    # for an optical frame nearby), a tilted inertia (principal moments), classic and gz.
    tilted = '<inertial><mass value="1"/><inertia ixx="0.1" ixy="0.01" ixz="0.02" iyy="0.2" iyz="0.01" izz="0.3"/></inertial>'
    classic = tmp_path / "classic.urdf"
    classic.write_text(
        robot(
            camera=camera_sensor(params="<frame_name>camera_link</frame_name>"),
            lidar=lidar_sensor(params="<frame_name>camera_optical_frame</frame_name>"),
            camera_body=tilted,
        )
    )
    gz = tmp_path / "gz.urdf"
    gz.write_text(gz_robot(camera_tags="<topic>cam</topic><gz_frame_id>camera_link</gz_frame_id>"))
    res = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "sensorkit", "validate", str(classic), str(gz)],
        check=False,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert res.returncode == 1, res.stdout + res.stderr
    assert "SK502" in res.stdout and "SK504" in res.stdout
    imported = {line.rsplit("|", 1)[-1].strip() for line in res.stderr.splitlines() if "|" in line}
    assert "sensorkit.lint.rules.frames" in imported  # the log is real
    assert not {m for m in imported if m.split(".")[0] in ("numpy", "pybullet", "rich")}


def test_pre_commit_hook_file() -> None:
    import yaml

    hooks = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())
    (hook,) = [h for h in hooks if h["id"] == "sensorkit-validate"]
    assert hook["entry"] == "sensorkit validate" and hook["language"] == "python"


def test_readme_example_output_is_what_validate_prints() -> None:
    readme = (ROOT / "README.md").read_text()
    cmd = "$ sensorkit validate tests/robots/acceptance/sk502_bad.urdf\n"
    assert cmd in readme
    shown = readme.split(cmd, 1)[1].split("```", 1)[0]
    res = cli("validate", "tests/robots/acceptance/sk502_bad.urdf", cwd=ROOT)
    assert res.stdout == shown
