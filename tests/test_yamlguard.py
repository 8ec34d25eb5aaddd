"""YAML nesting is bounded before PyYAML reads it (sensorkit.base.yamlguard).

The long fuzz run of issue 36 found a bridge YAML of 100,000 ``[`` that cost ~1.5 s of
CPU on each of its reads (PyYAML's scanner walks every open flow level on every token), and
a robot YAML nested past the composer's recursion ended `sensorkit new` in a traceback."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from sensorkit.base import yamlguard
from sensorkit.base.yamlguard import MAX_DEPTH, TooDeep, flow_depth
from sensorkit.cli import app
from sensorkit.loading.bridge import BridgeError, read_bridge
from sensorkit.loading.launch.frontend import yaml_entities


def _nested(depth: int) -> str:
    return "- " + "[" * depth + "1" + "]" * depth + "\n"


def test_flow_depth_counts_brackets_outside_quotes_and_comments() -> None:
    assert flow_depth("a: [1, {b: [2]}]\n") == 3
    assert flow_depth("a: '[[[['\nb: \"[[{{\\\"[\"\n# [[[[[[\nc: 1 # [[[\n") == 0
    assert flow_depth("c: x#[[\n") == 2  # a '#' glued to text starts no comment
    assert flow_depth("a: 'it''s [' \nb: [[1]]\n") == 2
    assert flow_depth("") == 0


def test_nesting_at_the_bound_reads_and_one_more_is_refused_before_pyyaml(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    assert yamlguard.compose(_nested(MAX_DEPTH)) is not None  # just under: read
    assert yamlguard.safe_load(_nested(MAX_DEPTH)) is not None
    called = []
    monkeypatch.setattr(yaml, "compose", lambda *a, **k: called.append(a))
    monkeypatch.setattr(yaml, "safe_load", lambda *a, **k: called.append(a))
    for reader in (yamlguard.compose, yamlguard.safe_load):
        with pytest.raises(TooDeep, match=f"nests {MAX_DEPTH + 1} levels"):
            reader(_nested(MAX_DEPTH + 1))  # just over: refused
        with pytest.raises(yaml.YAMLError):  # every reader's own YAMLError handler says it
            reader(_nested(100_000))
    assert called == []  # PyYAML never saw the deep texts


def test_block_nesting_past_the_composers_recursion_is_a_yaml_error() -> None:
    deep = "".join("  " * i + "-\n" for i in range(3000))
    with pytest.raises(TooDeep, match="nests too deeply"):
        yamlguard.compose(deep)


def test_bridge_and_launch_yaml_refuse_deep_nesting(tmp_path: Path) -> None:
    bridge = tmp_path / "bridge.yaml"
    bridge.write_text(_nested(100_000))
    with pytest.raises(BridgeError, match="not YAML: nests 100000 levels"):
        read_bridge(bridge, "bridge.yaml")
    with pytest.raises(ValueError, match="nests 100000 levels"):
        yaml_entities("launch: " + _nested(100_000))
    # near miss: a flow-style entry list is read
    bridge.write_text("- {gz_topic_name: /scan, ros_topic_name: /scan, ros_type_name: x}\n")
    assert [t.gz for t in read_bridge(bridge, "bridge.yaml")] == ["/scan"]


@pytest.mark.parametrize(
    "text",
    [
        "name: r\nsensors: " + "[" * 3000 + "]" * 3000 + "\n",
        "name: r\nsensors:\n" + "".join("  " * i + "-\n" for i in range(1, 1500)),
    ],
    ids=["flow", "block"],
)
def test_new_says_one_line_for_a_robot_yaml_nested_too_deeply(tmp_path: Path, text: str) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(text)
    result = CliRunner().invoke(app, ["new", str(spec), "-o", str(tmp_path / "out")])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "malformed YAML: nests" in lines[0], result.stderr
    assert not (tmp_path / "out").exists()
