"""Issue 13: command-line habits from ruff, cargo, xacro and ros2 launch that users try first."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
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


def test_pre_commit_hook_takes_sdf_too() -> None:
    # It skipped SDF (and SDF written as xacro) while validate refused SDF; validate reads
    # .sdf, .world and .sdf.xacro since issue 28, so the hook passes them on.
    hook = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())[0]
    pattern = re.compile(hook["files"])
    assert pattern.search("robot.urdf") and pattern.search("robot.urdf.xacro") and pattern.search("parts/arm.xacro")
    assert pattern.search("worlds/world.sdf.xacro") and pattern.search("model.sdf") and pattern.search("a.world")
    assert not pattern.search("model.config") and not pattern.search("robot.yaml")


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
    # The bad example triggers its rule; the good one does not (sensorkit/lint/explain.py).
    from builders import camera_sensor, robot

    from sensorkit.lint.explain import EXAMPLES

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


# --- colour, -q, --exit-zero, macro-only partials, stdin -----------------------------------

ANSI = re.compile(r"\x1b\[[0-9;]*m")
BAD = ROOT / "tests" / "robots" / "acceptance" / "sk502_bad.urdf"  # one SK502 error


def _sk(
    *args: str,
    env: dict[str, str] | None = None,
    stdin: bytes | None = None,
    cwd: Path | None = None,
) -> subprocess.CompletedProcess[str]:
    """``python -m sensorkit ARGS`` with colour variables cleared, then ``env`` set."""
    full = {k: v for k, v in os.environ.items() if k not in ("NO_COLOR", "FORCE_COLOR")}
    full.update(env or {})
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", *args],
        check=False,
        capture_output=True,
        input=stdin if stdin is not None else b"",
        timeout=120,
        cwd=cwd,
        env=full,
    )
    return subprocess.CompletedProcess(
        res.args, res.returncode, res.stdout.decode("utf-8", "replace"), res.stderr.decode("utf-8", "replace")
    )


def _on_a_terminal(*args: str, env: dict[str, str]) -> str:
    """What ``sensorkit ARGS`` writes to stdout when stdout is a terminal (a pty)."""
    import pty

    full = {k: v for k, v in os.environ.items() if k not in ("NO_COLOR", "FORCE_COLOR", "TERM")}
    full.update(env)
    main, child = pty.openpty()
    proc = subprocess.Popen(
        [sys.executable, "-m", "sensorkit", *args], stdout=child, stderr=subprocess.DEVNULL, env=full
    )
    os.close(child)
    chunks = []
    while True:
        try:
            data = os.read(main, 65536)
        except OSError:  # EIO: the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    os.close(main)
    proc.wait(60)
    return b"".join(chunks).decode("utf-8", "replace")


def test_color_always_never_and_no_color() -> None:
    res = _sk("validate", "--color", "always", str(BAD))
    assert res.returncode == 1 and ANSI.search(res.stdout), res.stdout
    # always wins over NO_COLOR (as ruff's --color does)
    assert ANSI.search(_sk("validate", "--color", "always", str(BAD), env={"NO_COLOR": "1"}).stdout)
    for argv, env in (
        (["--color", "never"], {}),
        (["--color", "never"], {"FORCE_COLOR": "1"}),
        ([], {}),  # auto, into a pipe
        ([], {"NO_COLOR": "1"}),
    ):
        res = _sk("validate", *argv, str(BAD), env=env)
        assert res.returncode == 1 and "SK502" in res.stdout and not ANSI.search(res.stdout), (argv, env)
    # auto: FORCE_COLOR colours a pipe; an empty NO_COLOR does not count (no-color.org)
    assert ANSI.search(_sk("validate", str(BAD), env={"FORCE_COLOR": "1"}).stdout)
    assert ANSI.search(_sk("rules", "--color", "always").stdout)
    assert not ANSI.search(_sk("rules").stdout)
    res = _sk("validate", "--color", "sometimes", str(BAD))
    assert res.returncode == 2 and res.stderr.strip() == "sensorkit: --color 'sometimes': use auto, always or never"


def test_color_auto_on_a_terminal_unless_no_color() -> None:
    assert ANSI.search(_on_a_terminal("validate", str(BAD), env={}))
    assert ANSI.search(_on_a_terminal("validate", str(BAD), env={"NO_COLOR": ""}))  # empty: unset
    out = _on_a_terminal("validate", str(BAD), env={"NO_COLOR": "1"})
    assert "SK502" in out and not ANSI.search(out)
    out = _on_a_terminal("validate", "--color", "never", str(BAD), env={})
    assert "SK502" in out and not ANSI.search(out)


def test_every_printing_command_takes_color_and_quiet() -> None:
    import sensorkit.cli

    commands = (
        ["validate"], ["rules"], ["intrinsics"], ["export"], ["topics"], ["render", "preview"],
        ["new"], ["add-camera"], ["add-depth-camera"], ["add-lidar"], ["add-stereo"], ["add-imu"],
        ["frames"], ["check-recording"],
    )  # fmt: skip
    app = sensorkit.cli.app
    registered = {c.name for c in app.registered_commands} | {g.name for g in app.registered_groups}
    # every command but the language server (it speaks JSON-RPC, prints nothing) is listed
    assert registered - {"lsp"} == {cmd[0] for cmd in commands}
    for cmd in commands:
        text = _sk(*cmd, "-h", env={"COLUMNS": "200"}).stdout
        assert "--color" in text, cmd
        assert cmd == ["rules"] or "--quiet" in text, cmd


def test_quiet_prints_only_findings(tmp_path: Path) -> None:
    good = tmp_path / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", good)
    (tmp_path / "sensorkit.toml").write_text('target = "classic"\n')
    loud = _sk("validate", str(good), str(BAD), cwd=tmp_path)
    assert "1 error, 0 warnings," in loud.stdout and "ok: no findings" in loud.stdout
    assert "from sensorkit.toml" in loud.stderr
    res = _sk("validate", "-q", str(good), str(BAD), cwd=tmp_path)
    assert res.returncode == 1 and res.stderr == ""
    assert "SK502" in res.stdout and "rover.urdf" not in res.stdout and "warnings," not in res.stdout
    res = _sk("validate", "--quiet", str(good), cwd=tmp_path)  # near miss: clean, so silent
    assert (res.returncode, res.stdout, res.stderr) == (0, "", "")
    # a file that cannot be read is still said, and still exit 2
    res = _sk("validate", "-q", str(tmp_path / "missing.urdf"))
    assert res.returncode == 2 and "no such file" in res.stderr
    # machine formats are unchanged by -q
    assert json.loads(_sk("validate", "-q", "-f", "json", str(BAD)).stdout)["summary"]["error"] == 1


def test_exit_zero(tmp_path: Path) -> None:
    res = _sk("validate", "--exit-zero", str(BAD))
    assert res.returncode == 0 and "SK502" in res.stdout
    res = _sk("validate", "--exit-zero", "--fail-on", "info", str(BAD))
    assert res.returncode == 0
    assert _sk("validate", str(BAD)).returncode == 1  # near miss: without it
    # usage and input errors stay 2
    res = _sk("validate", "--exit-zero", str(tmp_path / "missing.urdf"))
    assert res.returncode == 2
    res = _sk("validate", "--exit-zero", "--fail-on", "sometimes", str(BAD))
    assert res.returncode == 2 and "--fail-on" in res.stderr
    copy = tmp_path / "bad.urdf"
    shutil.copyfile(BAD, copy)
    res = _sk("validate", "--exit-zero", "--diff", str(copy))
    assert res.returncode == 0 and res.stdout.startswith("---")



def test_fail_on_never_from_the_shared_settings_file(tmp_path: Path) -> None:
    """One sensorkit.toml serves validate and render preview: ``fail-on = "never"``, which
    render took, made validate refuse to run (exit 2) before."""
    copy = tmp_path / "bad.urdf"
    shutil.copyfile(BAD, copy)
    (tmp_path / "sensorkit.toml").write_text('fail-on = "never"\n')
    res = _sk("validate", str(copy), cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    assert "SK502" in res.stdout and "fail-on never from sensorkit.toml" in res.stderr
    assert _sk("validate", "--fail-on", "error", str(copy), cwd=tmp_path).returncode == 1  # flag wins
    res = _sk("validate", "--fail-on", "never", str(BAD))
    assert res.returncode == 0 and "SK502" in res.stdout
    res = _sk("validate", "--fail-on", "never", "--diff", str(copy))  # the fix path too
    # runs; --diff's status says whether it would change a file (issue 27), not findings
    assert res.returncode == 1 and res.stdout.startswith("---")
    # a file that cannot be checked still fails
    assert _sk("validate", "--fail-on", "never", str(tmp_path / "missing.urdf")).returncode == 2
    res = _sk("validate", "--fail-on", "sometimes", str(BAD))
    assert res.returncode == 2 and "(or never)" in res.stderr


MACROS = (
    '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '  <xacro:property name="r" value="0.1"/>\n'
    '  <xacro:macro name="wheel" params="n"><link name="${n}"/></xacro:macro>\n</robot>\n'
)


def test_macro_only_files_given_explicitly_make_no_noise(tmp_path: Path) -> None:
    # pre-commit passes every changed *.xacro, partials included
    (tmp_path / "wheel.xacro").write_text(MACROS)
    (tmp_path / "props.urdf.xacro").write_text(MACROS.replace("<xacro:macro", "<xacro:property name='s' value='1'/><!--").replace("</xacro:macro>", "-->"))
    rover = tmp_path / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", rover)
    res = _sk("validate", "wheel.xacro", "props.urdf.xacro", "rover.urdf", cwd=tmp_path)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "SK203" not in res.stdout and "wheel.xacro" not in res.stdout
    assert res.stdout.splitlines()[-1] == "0 errors, 0 warnings, 0 info in 1 file; 2 macro-only files skipped"
    res = _sk("validate", "-q", "wheel.xacro", cwd=tmp_path)
    assert (res.returncode, res.stdout, res.stderr) == (0, "", "")
    data = json.loads(_sk("validate", "-f", "json", "wheel.xacro", "rover.urdf", cwd=tmp_path).stdout)
    assert data["findings"] == [] and data["macro_only"] == ["wheel.xacro"]
    # Near miss: a xacro that makes a link is a robot, checked and shown.
    (tmp_path / "one.xacro").write_text(MACROS.replace("</robot>", '  <xacro:wheel n="base"/>\n</robot>'))
    res = _sk("validate", "one.xacro", cwd=tmp_path)
    assert "one.xacro (target" in res.stdout and "skipped" not in res.stdout
    # Near miss: a macro file with a real problem still reports it.
    (tmp_path / "broken.xacro").write_text(MACROS.replace("</robot>", "<oops></robot>"))
    res = _sk("validate", "broken.xacro", cwd=tmp_path)
    assert res.returncode == 1 and "SK101" in res.stdout


XNS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def _stdin_workspace(tmp_path: Path) -> bytes:
    """src/rover_pkg with a macro file; returns a top-level xacro that uses it both ways."""
    pkg = tmp_path / "src" / "rover_pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text('<?xml version="1.0"?>\n<package format="3"><name>rover_pkg</name></package>\n')
    (pkg / "urdf" / "part.xacro").write_text(
        f'<robot {XNS}><xacro:macro name="arm" params="n"><link name="${{n}}"/>'
        '<joint name="${n}_j" type="fixed"><parent link="base_link"/><child link="${n}"/></joint>'
        "</xacro:macro></robot>\n"
    )
    part = (pkg / "urdf" / "part.xacro").read_text()
    (pkg / "urdf" / "wheel.xacro").write_text(part.replace('"arm"', '"wheel"'))
    (pkg / "sensorkit.toml").write_text('target = "harmonic"\n')
    return (
        f'<?xml version="1.0"?>\n<robot name="r" {XNS}>\n'
        '  <xacro:include filename="part.xacro"/>\n'
        '  <xacro:include filename="$(find rover_pkg)/urdf/wheel.xacro"/>\n'
        '  <link name="base_link"/>\n  <xacro:arm n="arm"/>\n  <xacro:wheel n="wheel"/>\n'
        "  <!-- sensorkit: ignore-file SK301 -->\n</robot>\n"
    ).encode()


def test_stdin_with_stdin_filename_reads_like_that_file(tmp_path: Path) -> None:
    text = _stdin_workspace(tmp_path)
    name = "src/rover_pkg/urdf/robot.urdf.xacro"  # does not exist: stdin stands for it
    res = _sk("validate", "-", "--stdin-filename", name, "-f", "json", stdin=text, cwd=tmp_path)
    assert res.returncode == 0, res.stdout + res.stderr
    data = json.loads(res.stdout)
    assert data["files"] == [name] and data["target"] == "harmonic"  # settings found from the name
    assert "target harmonic from src/rover_pkg/sensorkit.toml" in res.stderr
    assert data["findings"] == []  # includes resolved; the inline suppression in stdin applies
    # findings name the path given
    bad = BAD.read_bytes()
    res = _sk("validate", "-", "--stdin-filename", "cams/front.urdf", stdin=bad, cwd=tmp_path)
    assert res.returncode == 1 and "cams/front.urdf:37: SK502" in res.stdout, res.stdout


def test_stdin_without_a_name_is_stdin_from_the_working_folder(tmp_path: Path) -> None:
    text = _stdin_workspace(tmp_path)
    res = _sk("validate", "-", stdin=BAD.read_bytes(), cwd=tmp_path)
    assert res.returncode == 1 and "<stdin>:37: SK502" in res.stdout
    # relative includes resolve from the working folder: not found at the top ...
    res = _sk("validate", "-", "-f", "json", stdin=text, cwd=tmp_path)
    assert res.returncode == 1 and json.loads(res.stdout)["findings"][0]["rule"] == "SK102"
    assert "part.xacro" in res.stdout
    # ... and found from inside the package folder
    res = _sk("validate", "-", stdin=text, cwd=tmp_path / "src" / "rover_pkg" / "urdf")
    assert res.returncode == 0, res.stdout + res.stderr
    # Near miss: the same robot as a file gives the same result.
    robot = tmp_path / "src" / "rover_pkg" / "urdf" / "robot.urdf.xacro"
    robot.write_bytes(text)
    assert _sk("validate", str(robot)).returncode == 0


def test_stdin_for_intrinsics_topics_and_export(tmp_path: Path) -> None:
    bad = BAD.read_bytes()
    from_file = _sk("intrinsics", str(BAD), "-f", "camera-info")
    res = _sk("intrinsics", "-", "-f", "camera-info", stdin=bad)
    assert res.returncode == 0 and res.stdout == from_file.stdout and "camera_matrix" in res.stdout
    res = _sk("topics", "-", "-f", "json", stdin=bad)
    assert res.returncode == 0 and json.loads(res.stdout)["topics"], res.stderr
    res = _sk("export", "-", "--stdin-filename", "front.urdf", "-o", str(tmp_path / "out"), stdin=bad)
    assert res.returncode in (0, 1) and "front_camera" in res.stdout, res.stderr
    assert any((tmp_path / "out").rglob("camera_info.yaml"))


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["add-camera", "-", "--name", "c", "--parent", "base_link"], "- (stdin): add-camera edits the robot file in place"),
        (["add-imu", "-", "--name", "i", "--parent", "base_link"], "- (stdin): add-imu edits the robot file in place"),
        (["render", "preview", "-"], "- (stdin): render preview"),
        (["validate", "--fix", "-"], "--fix and --diff edit files"),
        (["validate", "-", "-"], "- (stdin) given twice"),
        (["validate", str(BAD), "--stdin-filename", "x.urdf"], "--stdin-filename only means something with -"),
        (["intrinsics", str(BAD), "--stdin-filename", "x.urdf"], "--stdin-filename only means something with -"),
    ],
)
def test_stdin_where_it_cannot_be_used_is_a_usage_error(argv: list[str], says: str) -> None:
    res = _sk(*argv, stdin=BAD.read_bytes())
    assert res.returncode == 2 and says in res.stderr, res.stderr
    assert len(res.stderr.strip().splitlines()) == 1, res.stderr


def test_stdin_is_read_bounded(monkeypatch: pytest.MonkeyPatch) -> None:
    import io
    import types

    import typer

    from sensorkit.cli import common
    from sensorkit.loading import document

    class Endless(io.RawIOBase):
        read_total = 0

        def readable(self) -> bool:
            return True

        def readinto(self, b: bytearray) -> int:  # type: ignore[override]
            n = len(b)
            b[:n] = b"x" * n
            Endless.read_total += n
            return n

    monkeypatch.setattr(document, "MAX_FILE_BYTES", 1000)
    monkeypatch.setattr(sys, "stdin", types.SimpleNamespace(buffer=io.BufferedReader(Endless(), 256)))
    with pytest.raises(typer.Exit):
        common.stdin_robot(Path("-"), None)
    assert Endless.read_total <= 1001 + 256  # at most one buffer beyond the limit
    # Near miss: exactly the limit is read whole.
    monkeypatch.setattr(sys, "stdin", types.SimpleNamespace(buffer=io.BytesIO(b"y" * 1000)))
    name, overlay = common.stdin_robot(Path("-"), None)
    assert name == Path("<stdin>") and list(overlay.values()) == [b"y" * 1000]
