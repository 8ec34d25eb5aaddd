"""SDF input (issue 28): includes by package:// and bare names, .sdf.xacro, SK103/SK104
on SDF mesh URIs, folders of SDF models, and findings located in the included file.

What gz-sim does is cited beside the code (sensorkit/loading/sdf_files.py) and here:
- an include's URI: libsdformat strips the scheme and looks the rest up in SDF_PATH, which
  gz-sim fills with GZ_SIM_RESOURCE_PATH (gazebosim/sdformat@sdformat12_12.8.0:
  src/SDF.cc:87-137; gazebosim/gz-sim@gz-sim8_8.9.0:src/Util.cc:486-540), so
  ``package://PKG/REST`` is ``FOLDER/PKG/REST`` (gazebosim/ros_gz@2.1.1:
  ros_gz_sim/README.md:96-113);
- a mesh: a relative URI is in the folder of the SDF file holding it
  (gazebosim/gz-sim@gz-sim8_8.9.0:src/Util.cc:389-440, src/Conversions.cc:220);
- a model folder's file is the one its model.config names
  (gazebosim/sdformat@sdformat12_12.8.0:src/parser.cc:1204-1257).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from sensorkit.lint.fleet import find_robots
from sensorkit.model import load_robot

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
INPUT = HERE / "robots" / "sdf" / "input"
MODELS = INPUT / "models"
YARD = INPUT / "ws" / "sk_sdf_world" / "worlds" / "yard.sdf"
XACRO = MODELS / "sk_input_robot" / "robot.sdf.xacro"
PARTS = MODELS / "sk_input_parts" / "model_19.sdf"
RESOURCE_VARS = ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH")


def _env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in RESOURCE_VARS}
    env.update(extra)
    return env


def _validate(path: Path, *args: str, **env: str) -> dict:  # type: ignore[type-arg]
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", "validate", str(path), "-f", "json", *args],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
        cwd=ROOT,
        env=_env(**env),
    )
    assert res.returncode in (0, 1), res.stderr
    return json.loads(res.stdout)  # type: ignore[no-any-return]


def _where(report: dict, rule: str) -> list[tuple[str, int, str]]:  # type: ignore[type-arg]
    return [
        (f["file"], f["line"], f["message"].split("'")[1])
        for f in report["findings"]
        if f["rule"] == rule
    ]


@pytest.fixture(autouse=True)
def _no_resource_path(monkeypatch: pytest.MonkeyPatch) -> None:
    for var in RESOURCE_VARS:
        monkeypatch.delenv(var, raising=False)


def test_a_package_include_resolves_in_the_workspace() -> None:
    # ros_gz_project_template's world includes its robot by package://PKG/models/NAME
    (bot,) = load_robot(YARD, sdf=True).robots
    (inc,) = bot.sdf.includes
    assert inc.uri == "package://sk_sdf_desc/models/sk_bot"
    assert inc.path == INPUT / "ws" / "sk_sdf_desc" / "models" / "sk_bot" / "model.sdf"
    # merged into the world's model: its link and sensor are the model's, unscoped
    assert [lk.name for lk in bot.links] == ["base_link"]
    assert [(s.name, s.reference) for s in bot.sensors] == [("lidar", "base_link")]


def test_a_package_include_resolves_through_the_resource_path(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # outside any workspace: found as FOLDER/PKG/REST in GZ_SIM_RESOURCE_PATH, as gz-sim does
    world = tmp_path / "w.sdf"
    world.write_text(YARD.read_text())
    (bot,) = load_robot(world, sdf=True).robots
    assert bot.sdf.includes[0].path is None
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", str(INPUT / "ws"))
    (bot,) = load_robot(world, sdf=True).robots
    assert bot.sdf.includes[0].path is not None and [s.name for s in bot.sensors] == ["lidar"]


def test_a_bare_include_name_is_looked_up_as_a_model(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # PX4's x500_depth includes <uri>x500</uri>: libsdformat finds FOLDER/x500 in SDF_PATH
    path = tmp_path / "m.sdf"
    path.write_text(
        '<sdf version="1.9"><model name="m">'
        "<include><uri>sk_input_parts</uri></include></model></sdf>"
    )
    (robot,) = load_robot(path, sdf=True).robots
    assert robot.sdf.includes[0].path is None and robot.links == []
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", str(MODELS))
    (robot,) = load_robot(path, sdf=True).robots
    assert robot.sdf.includes[0].path == PARTS  # the file model.config names
    assert [lk.name for lk in robot.links] == ["sk_input_parts::part"]


def test_sdf_xacro_expands_first_and_finds_point_at_its_lines() -> None:
    report = _validate(XACRO)
    assert report["targets"] == {str(XACRO.relative_to(ROOT)): "harmonic"}
    xacro = str(XACRO.relative_to(ROOT))
    parts = str(PARTS.relative_to(ROOT))
    # the macro's mesh: at the .sdf.xacro's line; the include's: at the included file's
    assert _where(report, "SK104") == [
        (parts, 9, "model://sk_input_parts/meshes/gone.dae"),
        (parts, 15, "meshes/lost.dae"),
        (xacro, 7, "model://sk_input_parts/meshes/fin.dae"),
    ]
    assert _where(report, "SK103") == [(parts, 24, "package://sk_no_such_package/meshes/a.dae")]


def test_a_model_include_in_sdf_xacro_resolves_from_its_folder() -> None:
    loaded = load_robot(XACRO, sdf=True)
    (robot,) = loaded.robots
    assert robot.name == "sk_robot"  # $(arg prefix) expanded
    assert [inc.path for inc in robot.sdf.includes] == [PARTS]
    assert [lk.name for lk in robot.links] == ["hull", "fin", "keel", "parts::part"]
    hull = robot.link_map["hull"]
    assert hull.source.file.endswith("robot.sdf.xacro") and hull.source.line == 5


def test_sdf_mesh_uris_trigger_and_near_miss() -> None:
    report = _validate(PARTS)
    where = {uri for _file, _line, uri in _where(report, "SK104")}
    # triggers: the model's folder is found but not the file; a relative path that is not there
    assert where == {"model://sk_input_parts/meshes/gone.dae", "meshes/lost.dae"}
    # near misses, never claimed missing: the same files that are there
    # (model://sk_input_parts/meshes/part.dae, meshes/part.dae); a model found nowhere
    # (GZ_SIM_RESOURCE_PATH at run time may hold it); a Fuel URL
    assert [f["severity"] for f in report["findings"] if f["rule"] == "SK104"] == ["warning"] * 2
    # an unknown package is SK103, as for URDF
    assert [u for _f, _l, u in _where(report, "SK103")] == [
        "package://sk_no_such_package/meshes/a.dae"
    ]
    found = _validate(PARTS, "--package-path", f"sk_no_such_package={MODELS / 'sk_input_parts'}")
    assert _where(found, "SK103") == []


def test_a_mesh_in_an_included_model_points_at_the_included_file() -> None:
    report = _validate(YARD)
    bot = INPUT / "ws" / "sk_sdf_desc" / "models" / "sk_bot" / "model.sdf"
    # body.dae is there; lid.dae is not
    assert _where(report, "SK104") == [
        (str(bot.relative_to(ROOT)), 9, "package://sk_sdf_desc/models/sk_bot/meshes/lid.dae")
    ]


def test_relative_meshes_in_xacro_text_are_left_unsaid() -> None:
    # gz-sim reads an expanded .sdf.xacro from a string: a relative mesh is then resolved
    # from its own working folder (gazebosim/gz-sim@gz-sim8_8.9.0:src/Util.cc:421-427)
    report = _validate(XACRO)
    assert "meshes/keel.dae" not in {u for _f, _l, u in _where(report, "SK104")}


def test_a_folder_gives_sdf_models_and_worlds_once_each() -> None:
    found = find_robots(INPUT)
    rel = [str(p.relative_to(INPUT)) for p in found.files]
    assert rel == [
        "models/sk_input_parts/model_19.sdf",  # model.config's newest, not model.sdf
        "models/sk_input_robot/robot.sdf.xacro",
        "worlds/world.world",
        "ws/sk_sdf_desc/models/sk_bot/model.sdf",
        "ws/sk_sdf_world/worlds/yard.sdf",
    ]
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", "validate", str(INPUT)],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
        cwd=ROOT,
        env=_env(),
    )
    assert "found 5 robot descriptions" in res.stderr, res.stderr
    assert "model_19.sdf" in res.stdout and "sk_input_parts/model.sdf" not in res.stdout


def test_a_world_file_in_a_folder_validates_its_included_models() -> None:
    report = _validate(INPUT / "worlds" / "world.world", GZ_SIM_RESOURCE_PATH=str(MODELS))
    assert {f["file"] for f in report["findings"]} == {str(PARTS.relative_to(ROOT))}


def test_sk101_and_sk102_on_sdf_input(tmp_path: Path) -> None:
    """The loaders' rules hold on SDF: a broken .sdf is SK101 at its line, a .sdf.xacro
    that does not expand is SK102 at the file; near misses: the same files mended."""
    from sensorkit.lint.engine import validate_file

    model = '<sdf version="1.9">\n<model name="m">\n<link name="a"/>\n</model>\n</sdf>\n'
    broken = tmp_path / "broken.sdf"
    broken.write_text(model.replace("</model>", "</modle>"))
    found = [(f.rule, f.line) for f in validate_file(broken).findings]
    assert found == [("SK101", 4)]
    broken.write_text(model)
    assert validate_file(broken).findings == []
    xacro = tmp_path / "robot.sdf.xacro"
    text = (
        '<sdf version="1.9" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:property name="w" value="0.1"/>\n<model name="m">\n<link name="a">\n'
        "<pose>${w} 0 0 0 0 0</pose>\n</link>\n</model>\n</sdf>\n"
    )
    xacro.write_text(text.replace("${w}", "${undefined_w}"))
    report = validate_file(xacro)
    assert [f.rule for f in report.findings] == ["SK102"] and report.findings[0].file
    assert "undefined_w" in report.findings[0].message
    xacro.write_text(text)
    report = validate_file(xacro)
    assert report.findings == [] and report.robot is not None and report.robot.sdf is not None
