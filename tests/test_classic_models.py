"""Issue 35 item 6: SDF includes on Gazebo Classic search GAZEBO_MODEL_PATH and the models
Gazebo 11 installs; SK107 names the target's own search path.

Sources (sensorkit/knowledge/classic_models.py): elysia-best/gazebo-classic@upstream/
11.10.2+dfsg b64af319:models/CMakeLists.txt:4-12 (ground_plane and sun installed),
gazebo/common/SystemPaths.cc:195-215 (GAZEBO_MODEL_PATH); gazebosim/sdformat@sdformat9_9.10.2
9ee2d4f3:src/parser.cc:976-980 (an include not found is skipped); gazebosim/gz-sim@
gz-sim8_8.9.0:include/gz/sim/Util.hh:327 (GZ_SIM_RESOURCE_PATH).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from sensorkit.lint.engine import FileReport, Options, validate_file

WORLD = """<?xml version="1.0"?>
<sdf version="1.7">
  <world name="w">
    <include><uri>model://{inc}</uri></include>
    <model name="box">
      <link name="base"><inertial><mass>1</mass></inertial>
        <sensor name="cam" type="camera"><camera><horizontal_fov>1</horizontal_fov>
          <image><width>320</width><height>240</height></image><clip><near>0.1</near><far>10</far></clip></camera>
        </sensor>
      </link>
    </model>
  </world>
</sdf>
"""
MODEL = """<?xml version="1.0"?>
<sdf version="1.7"><model name="crate"><link name="l"/></model></sdf>
"""


def _run(tmp_path: Path, inc: str, target: str) -> FileReport:
    tmp_path.mkdir(parents=True, exist_ok=True)
    path = tmp_path / "w.sdf"
    path.write_text(WORLD.format(inc=inc))
    report = validate_file(path, Options(target=target))
    assert not report.internal_errors and report.error is None, report.error
    return report


def _sk107(report: FileReport) -> list:  # type: ignore[type-arg]
    return [f for f in report.findings if f.rule == "SK107"]


@pytest.mark.parametrize("inc", ["sun", "ground_plane"])
def test_a_model_gazebo11_installs_resolves_on_classic(tmp_path: Path, inc: str, monkeypatch: pytest.MonkeyPatch) -> None:
    for var in ("GAZEBO_MODEL_PATH", "GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH"):
        monkeypatch.delenv(var, raising=False)
    for target in ("classic", "ros1"):
        f = _sk107(_run(tmp_path / target, inc, target))
        assert [x.severity.label for x in f] == ["info"] and "Gazebo 11 installs" in f[0].message
        assert "models/CMakeLists.txt:4-12" in f[0].message
    # near miss: Gazebo Sim installs no such model: it resolves only if GZ_SIM_RESOURCE_PATH
    # holds one when the simulation runs, which sensorkit cannot tell (info, issue 35), said
    # in the target's own search path
    f = _sk107(_run(tmp_path / "gz", inc, "harmonic"))
    assert [x.severity.label for x in f] == ["info"] and "GZ_SIM_RESOURCE_PATH" in f[0].message
    assert "Gazebo 11 installs" not in f[0].message and "cannot tell" in f[0].message


def test_a_missing_model_on_classic_names_gazebo_model_path(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("GAZEBO_MODEL_PATH", raising=False)
    # model://crate may be on GAZEBO_MODEL_PATH when the simulation runs: info (issue 35),
    # saying what Gazebo Classic does if it is not
    f = _sk107(_run(tmp_path, "crate", "classic"))
    assert [x.severity.label for x in f] == ["info"]
    assert "GAZEBO_MODEL_PATH" in (f[0].fix or "") and "skips the include" in f[0].message
    assert "GAZEBO_MODEL_PATH holds a folder with crate/" in f[0].message
    assert "GZ_SIM_RESOURCE_PATH" not in f[0].message + (f[0].fix or "")


def test_gazebo_model_path_is_classic_only(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    models = tmp_path / "models"
    (models / "crate").mkdir(parents=True)
    (models / "crate" / "model.sdf").write_text(MODEL)
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(models))
    for var in ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH"):
        monkeypatch.delenv(var, raising=False)
    assert not _sk107(_run(tmp_path / "c", "crate", "classic"))
    f = _sk107(_run(tmp_path / "h", "crate", "harmonic"))
    assert [x.severity.label for x in f] == ["error"] and "found only through GAZEBO_MODEL_PATH" in f[0].message
    # near miss: on GZ_SIM_RESOURCE_PATH too, Gazebo Sim finds it
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", str(models))
    assert not _sk107(_run(tmp_path / "g", "crate", "harmonic"))
