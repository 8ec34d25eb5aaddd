"""The sensor, plugin, topic and bridge rules (SK4xx, SK6xx) on SDF models: each rule that
runs on SDF has a trigger of its own written in SDF and a near miss that it leaves alone."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from sensorkit.lint.engine import Options, validate_file
from sensorkit.lint.rules import RULES

HERE = Path(__file__).parent / "robots" / "sdf" / "sensors"

# rule -> (target, the SDF file stem, the bridge YAML or None). The trigger is
# STEM_trigger.sdf (or the bridge named), the near miss STEM_near.sdf (or bridge_ok.yaml).
CASES: dict[str, tuple[str, str, str | None]] = {
    "SK402": ("harmonic", "sk402", None),
    "SK403": ("harmonic", "sk403", None),
    "SK404": ("harmonic", "sk404", None),
    "SK405": ("harmonic", "sk405", None),
    "SK406": ("harmonic", "sk406", None),
    "SK407": ("harmonic", "sk407", None),
    "SK408": ("harmonic", "sk408", None),
    "SK409": ("classic", "sk409", None),
    "SK410": ("harmonic", "sk410", None),
    "SK411": ("classic", "sk411", None),
    "SK412": ("harmonic", "sk412", None),
    "SK413": ("classic", "sk413", None),
    "SK414": ("harmonic", "sk414", None),
    "SK415": ("harmonic", "sk415", None),
    "SK416": ("harmonic", "sk416", None),
    "SK417": ("classic", "sk417", None),
    "SK601": ("classic", "sk601", None),
    "SK602": ("classic", "sk602", None),
    "SK603": ("classic", "sk603", None),
    "SK604": ("classic", "sk604", None),
    "SK605": ("classic", "sk605", None),
    "SK606": ("classic", "sk606", None),
    "SK607": ("classic", "sk607", None),
    "SK608": ("harmonic", "sk608", None),
    "SK609": ("classic", "sk609", None),
    "SK610": ("classic", "sk610", None),
    "SK611": ("auto", "sk611", None),
    "SK613": ("harmonic", "sk613", None),
    "SK612": ("harmonic", "bridged", "bridge_sk612"),
    "SK614": ("harmonic", "bridged", "bridge_sk614"),
    "SK615": ("harmonic", "bridged", "bridge_sk615"),
    "SK617": ("harmonic", "bridged", "bridge_sk617"),  # cam's entry runs ROS_TO_GZ
    "SK618": ("harmonic", "bridged", "bridge_sk618"),  # /camm: did you mean cam?
    "SK620": ("harmonic", "sk620", None),  # a world with systems, none of them Sensors
}


def _rules(path: Path, target: str, bridge: str | None = None, **kw: object) -> list[str]:
    bridges = (str(HERE / f"{bridge}.yaml"),) if bridge else ()
    options = Options(target=target, bridges=bridges, **kw)  # type: ignore[arg-type]
    report = validate_file(path, options)
    assert report.error is None and not report.internal_errors, report
    return [f.rule for f in report.findings]


def _files(
    stem: str, bridge: str | None
) -> tuple[tuple[Path, str | None], tuple[Path, str | None]]:
    if bridge is not None:
        return (HERE / f"{stem}.sdf", bridge), (HERE / f"{stem}.sdf", "bridge_ok")
    return (HERE / f"{stem}_trigger.sdf", None), (HERE / f"{stem}_near.sdf", None)


@pytest.mark.parametrize("rule_id", sorted(CASES))
def test_the_rule_runs_on_sdf(rule_id: str) -> None:
    assert "sdf" in RULES[rule_id].formats


@pytest.mark.parametrize("rule_id", sorted(CASES))
def test_an_sdf_trigger_reports_the_rule(rule_id: str) -> None:
    target, stem, bridge = CASES[rule_id]
    (path, yaml), _ = _files(stem, bridge)
    assert rule_id in _rules(path, target, yaml)


@pytest.mark.parametrize("rule_id", sorted(CASES))
def test_an_sdf_near_miss_does_not(rule_id: str) -> None:
    target, stem, bridge = CASES[rule_id]
    _, (path, yaml) = _files(stem, bridge)
    assert rule_id not in _rules(path, target, yaml)


def test_sk607_on_gz_names_a_sensor_the_bridge_leaves_out() -> None:
    path = HERE / "bridged.sdf"
    report = validate_file(
        path, Options(target="harmonic", bridges=(str(HERE / "bridge_sk607.yaml"),))
    )
    assert [(f.rule, f.sensor) for f in report.findings] == [("SK607", "cam")]
    assert "SK607" not in _rules(path, "harmonic", "bridge_ok")


def test_sk401_and_sk105_stay_urdf_only() -> None:
    # <gazebo reference> and URDF parsers' silently ignored tags mean nothing in SDF.
    assert RULES["SK401"].formats == ("urdf",)
    assert RULES["SK105"].formats == ("urdf",)


def test_a_nested_models_scoped_topic_names_each_model(tmp_path: Path) -> None:
    # gz-sim scopes an entity by each ancestor's type and name (gazebosim/gz-sim@
    # gz-sim8_8.9.0:src/Util.cc:138-183): a sensor of a nested model's link publishes on
    # /world/W/model/OUTER/model/INNER/link/LINK/sensor/NAME/..., not .../link/INNER::LINK.
    path = tmp_path / "nested.sdf"
    path.write_text(
        '<?xml version="1.0"?>\n<sdf version="1.9"><model name="outer"><link name="base"/>'
        '<model name="inner"><link name="l"><sensor name="imu" type="imu"><imu/></sensor>'
        "</link></model></model></sdf>\n"
    )
    report = validate_file(path, Options(target="harmonic", select=("SK607",)))
    [finding] = report.findings
    assert "/world/WORLD/model/MODEL/model/inner/link/l/sensor/imu/imu" in finding.message


def test_a_bridge_of_a_world_with_other_models_is_not_judged_per_model(tmp_path: Path) -> None:
    # One bridge serves every model of a world, and each model is checked on its own: the
    # entry of another model's sensor is no stale entry (SK612) of this one.
    model = (HERE / "bridged.sdf").read_text().split('<sdf version="1.9">')[1].split("</sdf>")[0]
    other = '<model name="other"><link name="l"><sensor name="c2" type="camera"><topic>camx</topic><camera/></sensor></link></model>'
    world = tmp_path / "world.sdf"
    world.write_text(
        f'<?xml version="1.0"?>\n<sdf version="1.9"><world name="w">{model}{other}</world></sdf>\n'
    )
    assert "SK612" not in _rules(world, "harmonic", "bridge_sk612")
    alone = tmp_path / "alone.sdf"
    alone.write_text(
        f'<?xml version="1.0"?>\n<sdf version="1.9"><world name="w">{model}</world></sdf>\n'
    )
    assert "SK612" in _rules(alone, "harmonic", "bridge_sk612")


def test_validate_reports_an_sdf_sensor_rule_through_the_cli() -> None:
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "sensorkit",
            "validate",
            "--target",
            "harmonic",
            str(HERE / "sk613_trigger.sdf"),
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    assert out.returncode == 1, out.stderr
    assert "sk613_trigger.sdf:5: SK613 error" in out.stdout


def test_sk620_a_world_without_the_sensors_system_names_the_target_plugin(tmp_path: Path) -> None:
    """Issue 38: a world that lists its systems without the Sensors system renders nothing.
    Only that system enables gz-sim's rendering sensors (gazebosim/gz-sim@gz-sim8_8.14.0:
    src/systems/sensors/Sensors.cc:808-810, the one SetEnableSensors(true) in src/) and
    creates the camera and GPU lidar objects (:1119-1169; @ignition-gazebo6_6.16.0 :526,
    :777-812). A world with no <plugin> gets the default server.config instead
    (src/SimulationRunner.cc:1762-1769), which a user may have edited: not judged."""
    trigger = (HERE / "sk620_trigger.sdf").read_text()

    def findings(text: str, target: str) -> list[Any]:
        path = tmp_path / "world.sdf"
        path.write_text(text)
        report = validate_file(path, Options(target=target, select=("SK620",)))
        assert report.error is None and not report.internal_errors, report
        return list(report.findings)

    (f,) = findings(trigger, "harmonic")
    assert f.severity.name == "ERROR" and f.source.line == 3
    assert "sensor 'cam' of model 'post' publishes no data" in f.message
    assert f.fix.startswith('add <plugin filename="gz-sim-sensors-system" name="gz::sim::systems::Sensors">')
    assert "<render_engine>ogre2</render_engine>" in f.fix and "ignition" not in f.fix + f.message
    (f,) = findings(trigger, "fortress")  # the advice names the chosen target's spelling only
    assert 'filename="ignition-gazebo-sensors-system" name="ignition::gazebo::systems::Sensors"' in f.fix
    assert "gz-sim-sensors" not in f.fix and "Fortress" in f.message
    gpu = trigger.replace('type="camera"', 'type="gpu_lidar"')
    assert [f.rule for f in findings(gpu, "jetty")] == ["SK620"]
    # near misses: Classic; no system listed at all; the Sensors system in any spelling a
    # release loads, or on a model; a world whose sensors render nothing
    assert not findings(trigger, "classic")
    plugins = [ln for ln in trigger.splitlines() if "<plugin " in ln]
    bare = "\n".join(ln for ln in trigger.splitlines() if ln not in plugins)
    assert not findings(bare, "harmonic")
    for spelled in (
        '<plugin filename="libignition-gazebo6-sensors-system.so" name="x"/>',
        '<plugin filename="custom" name="ignition::gazebo::systems::Sensors"/>',
    ):
        assert not findings(trigger.replace(plugins[0], spelled), "harmonic"), spelled
    on_model = trigger.replace("<static>", '<plugin filename="gz-sim-sensors-system" name="s"/><static>')
    assert not findings(on_model, "harmonic")
    imu = trigger.replace('type="camera"', 'type="imu"')
    assert not findings(imu, "harmonic")
