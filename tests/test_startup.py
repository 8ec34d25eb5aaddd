"""Start-up imports only what the command and its input need (issue 37).

Each command runs as the ``sensorkit`` program does (``sensorkit.cli.main``) in a fresh
interpreter, which reports the modules loaded when the process ends (validate ends with
``os._exit``: the report is written just before it). The exact set of sensorkit modules a
plain URDF's validate imports is held here: a new import on that path shows up as a
change of this list, to be made on purpose.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from conftest import ROOT

ACCEPTANCE = ROOT / "tests/robots/acceptance"
XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

DRIVER = """
import os, sys
real = os._exit
def report():
    sys.stderr.write("MODULES " + " ".join(sorted(sys.modules)) + "\\n")
    sys.stderr.flush()
def _exit(code):
    report()
    real(code)
os._exit = _exit
sys.argv = ["sensorkit", *sys.argv[1:]]
from sensorkit.cli import main
try:
    main()
finally:
    report()
"""

# What ``sensorkit validate ROBOT.urdf`` imports for a URDF with no xacro, no launch file,
# no bridge and no fixable finding.
PLAIN_URDF = frozenset(
    """sensorkit sensorkit.base sensorkit.base.consequence sensorkit.base.regular sensorkit.loading.input_findings sensorkit.base.errors sensorkit.base.findings
    sensorkit.knowledge.link_lookups sensorkit.knowledge.sensor_blocks sensorkit.lint.rules.bridge_flow
    sensorkit.lint.rules.calibration sensorkit.lint.rules.coincide sensorkit.lint.rules.model_plugins
    sensorkit.lint.rules.optical_text sensorkit.lint.rules.recording sensorkit.lint.rules.sensor_blocks
    sensorkit.loading.bridge sensorkit.loading.package_xml
    sensorkit.base.lazy sensorkit.base.quote sensorkit.base.suggest sensorkit.cli
    sensorkit.cli.common sensorkit.cli.options sensorkit.cli.root sensorkit.cli.validate
    sensorkit.knowledge sensorkit.knowledge.gazebo_ros sensorkit.knowledge.gazebo_sim
    sensorkit.knowledge.limits sensorkit.knowledge.plugins sensorkit.knowledge.sdf_schema
    sensorkit.knowledge.sdf_values sensorkit.lint sensorkit.lint.config sensorkit.lint.engine
    sensorkit.lint.fleet sensorkit.lint.report sensorkit.lint.rules sensorkit.lint.rules.base
    sensorkit.lint.rules.bridge sensorkit.lint.rules.focal sensorkit.lint.rules.frame_joints
    sensorkit.lint.rules.frames sensorkit.lint.rules.gz_frames sensorkit.lint.rules.gz_world sensorkit.lint.rules.input
    sensorkit.lint.rules.lidar sensorkit.lint.rules.mass sensorkit.lint.rules.noise
    sensorkit.lint.rules.placement sensorkit.lint.rules.plugins sensorkit.lint.rules.principal
    sensorkit.lint.rules.ros1 sensorkit.lint.rules.ros1_values sensorkit.lint.rules.sdf
    sensorkit.lint.rules.sensors sensorkit.lint.rules.tf_frames sensorkit.lint.rules.topic_names
    sensorkit.lint.rules.topics sensorkit.lint.rules.tree sensorkit.lint.suppress
    sensorkit.loading sensorkit.loading.cache sensorkit.loading.document
    sensorkit.loading.formats sensorkit.loading.launch sensorkit.loading.launch.discover
    sensorkit.loading.marks sensorkit.loading.packages sensorkit.loading.reads
    sensorkit.loading.uris sensorkit.model sensorkit.model.frames sensorkit.model.owners
    sensorkit.model.parse sensorkit.model.parts sensorkit.model.poses sensorkit.model.robot
    sensorkit.model.sdf sensorkit.model.sensors sensorkit.model.targets
    sensorkit.model.transforms sensorkit.model.tree sensorkit.model.urdf""".split()  # noqa: SIM905
)


def imported(
    *args: str, cwd: Path | None = None
) -> tuple[set[str], subprocess.CompletedProcess[str]]:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    run = subprocess.run(
        [sys.executable, "-c", DRIVER, *args],
        cwd=cwd or ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    lines = [line for line in run.stderr.splitlines() if line.startswith("MODULES ")]
    assert lines, run.stderr
    return set(lines[-1].split()[1:]), run


def ours(modules: set[str]) -> set[str]:
    return {m for m in modules if m == "sensorkit" or m.startswith("sensorkit.")}


def test_a_plain_urdf_validate_imports_exactly_these_modules() -> None:
    modules, run = imported("validate", str(ACCEPTANCE / "sk502_fixed.urdf"))
    assert run.returncode == 0, run.stdout + run.stderr
    assert ours(modules) == PLAIN_URDF, (
        f"new: {sorted(ours(modules) - PLAIN_URDF)}; gone: {sorted(PLAIN_URDF - ours(modules))}"
    )
    # Nor anything behind them: no xacro, no worker processes, no fix layer, no pictures.
    assert not {"xacro", "multiprocessing", "numpy", "PIL", "pybullet", "rich"} & modules


def test_version_imports_neither_typer_nor_the_engine() -> None:
    modules, run = imported("--version")
    assert run.returncode == 0 and run.stdout.startswith("sensorkit "), run.stderr
    assert ours(modules) == {"sensorkit", "sensorkit.cli"}
    assert "typer" not in modules
    short, run = imported("-V")
    assert run.stdout.startswith("sensorkit ") and "typer" not in short


def test_help_imports_nothing_of_the_engine() -> None:
    modules, run = imported("--help")
    assert run.returncode == 0 and "validate" in run.stdout, run.stderr
    engine = {m for m in ours(modules) if m.split(".")[1:2] not in (["cli"], ["base"], [])}
    assert engine == set(), engine


def test_the_fix_layer_loads_only_for_a_fixable_finding() -> None:
    modules, run = imported("validate", str(ACCEPTANCE / "sk502_bad.urdf"))
    assert "[*]" in run.stdout  # marked: the fixer was asked
    assert "sensorkit.fix.marks" in modules
    plain, _ = imported("validate", str(ACCEPTANCE / "sk502_fixed.urdf"))
    assert not {m for m in plain if m.startswith("sensorkit.fix")}


def test_the_launch_reader_loads_only_when_launch_files_exist(tmp_path: Path) -> None:
    pkg = tmp_path / "bot_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>bot_description</name></package>")
    robot = pkg / "urdf/bot.urdf"
    robot.write_bytes((ACCEPTANCE / "sk502_fixed.urdf").read_bytes())
    modules, _ = imported("validate", str(robot))
    assert "sensorkit.loading.launch.discover" in modules  # it looked
    assert "sensorkit.loading.launch.reader" not in modules
    (pkg / "launch").mkdir()
    (pkg / "launch/sim.launch.py").write_text(
        "def generate_launch_description():\n    return None\n"
    )
    modules, _ = imported("validate", str(robot))
    assert "sensorkit.loading.launch.reader" in modules


def test_the_sdf_reader_loads_only_for_sdf() -> None:
    sdf = next((ROOT / "tests/robots/sdf").rglob("*.sdf"))
    modules, _ = imported("validate", str(sdf))
    assert {"sensorkit.model.sdf_read", "sensorkit.loading.sdf_files"} <= modules
    plain, _ = imported("validate", str(ACCEPTANCE / "sk502_fixed.urdf"))
    assert not {"sensorkit.model.sdf_read", "sensorkit.loading.sdf_files"} & plain


def test_trusted_xacro_is_expanded_here_and_jobs_bring_workers(tmp_path: Path) -> None:
    for i in range(2):
        (tmp_path / f"r{i}.urdf.xacro").write_text(
            f'<robot name="r" {XACRO_NS}><xacro:property name="w" value="0.5"/>'
            '<link name="${w*2}"/></robot>\n'
        )
    modules, run = imported("validate", "r0.urdf.xacro", cwd=tmp_path)
    assert run.returncode in (0, 1), run.stderr
    assert "xacro" in modules and "sensorkit.loading.xacro_fast" in modules
    assert "multiprocessing" not in modules  # no child forked for a trusted robot
    jobs, run = imported("validate", "-j", "2", "r0.urdf.xacro", "r1.urdf.xacro", cwd=tmp_path)
    assert run.returncode in (0, 1), run.stderr
    assert "multiprocessing" in jobs
