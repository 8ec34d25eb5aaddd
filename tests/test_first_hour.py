"""Issue 27: what a newcomer meets in the first hour: the README's set-up and install lines,
the pre-commit hook, one error style, and refusals that name the next step."""

from __future__ import annotations

import json
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from conftest import ROOT, run_cli

ROBOTS = Path(__file__).resolve().parent / "edit_robots"

# pre-commit's manifest schema (pre_commit/clientlib.py MANIFEST_HOOK_DICT): required keys.
PRE_COMMIT_REQUIRED = ("id", "name", "entry", "language")


def test_pre_commit_hooks_file_is_what_pre_commit_requires() -> None:
    hooks = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())
    assert isinstance(hooks, list)
    (hook,) = [h for h in hooks if h["id"] == "sensorkit-validate"]
    assert all(isinstance(hook.get(key), str) and hook[key] for key in PRE_COMMIT_REQUIRED)
    assert hook["entry"] == "sensorkit validate" and hook["language"] == "python"
    files = re.compile(hook["files"])
    names = ("robot.urdf.xacro", "a.urdf", "b.xacro", "src/bot/urdf/bot.urdf.xacro")
    for name in (*names, "model.sdf", "robot.sdf.xacro", "empty.world"):  # SDF too (issue 28)
        assert files.search(name), name
    for name in ("x.yaml", "robot.urdf.bak", "model.config", "model.sdf.orig"):
        assert not files.search(name), name


def _readme_blocks(lang: str) -> list[str]:
    readme = (ROOT / "README.md").read_text()
    return re.findall(rf"```{lang}\n(.*?)```", readme, flags=re.S)


def test_readme_pre_commit_config_uses_the_hook_with_repo_and_rev() -> None:
    configs = [yaml.safe_load(b) for b in _readme_blocks("yaml") if "repos:" in b]
    assert configs, "README has no .pre-commit-config.yaml snippet"
    (repo,) = configs[0]["repos"]
    assert repo["repo"].startswith("https://") and repo["rev"]
    assert [h["id"] for h in repo["hooks"]] == ["sensorkit-validate"]


def test_readme_says_how_to_run_and_install_sensorkit() -> None:
    readme = (ROOT / "README.md").read_text()
    setup = readme.split("## Set up", 1)[1].split("\n## ", 1)[0]
    # the set-up stays two commands: the try-it line and the test run
    assert (
        "```sh\npython3 -m venv .venv && .venv/bin/pip install . && .venv/bin/sensorkit validate"
        in setup
    )
    assert "```sh\nbash tests/run\n```" in setup
    assert ". .venv/bin/activate" in setup and "`.venv/bin/sensorkit`" in setup
    # install from a clone (issue 38: the name `sensorkit` on PyPI is another project's);
    # tests/test_setup_recipes.py runs both
    sh = "".join(_readme_blocks("sh"))
    assert "pipx install ./sensorkit\n" in sh and "`pip install ./sensorkit`" in readme
    assert "pip install sensorkit" not in readme.replace("`pip install sensorkit` does", "")
    jobs = [yaml.safe_load(b) for b in _readme_blocks("yaml") if "jobs:" in b and "pre-commit" in b]
    assert jobs, "README has no GitHub Actions job running the hook"
    steps = jobs[0]["jobs"]["sensors"]["steps"]
    assert any("sensorkit-validate" in step.get("run", "") for step in steps)


# --------------------------------------------------------------------------- one error style


def _rover(tmp_path: Path) -> Path:
    path = tmp_path / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", path)
    return path


def _one_line(res: subprocess.CompletedProcess[str]) -> str:
    assert res.returncode == 2, (res.stdout, res.stderr)
    assert "Traceback" not in res.stderr and len(res.stderr.strip().splitlines()) == 1, res.stderr
    return res.stderr.strip()


@pytest.mark.parametrize(
    "cmd",
    [["export", "{robot}", "--out", "{ro}/x"], ["render", "preview", "{robot}", "-o", "{ro}/prev"],
     ["new", "{spec}", "-o", "{ro}/pkg"], ["export", "{robot}", "--out", "{ro}/x/y"]],
)  # fmt: skip
def test_a_read_only_out_folder_is_not_writable(tmp_path: Path, cmd: list[str]) -> None:
    robot = _rover(tmp_path)
    spec = tmp_path / "robot.yaml"
    spec.write_text("name: bot\n")
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        argv = [c.format(robot=robot, ro=ro, spec=spec) for c in cmd]
        line = _one_line(run_cli(*argv, cwd=tmp_path))
        assert line.startswith(f"sensorkit: {ro} is not writable"), line
        assert "Errno" not in line and ".new-" not in line
        assert list(ro.iterdir()) == []
    finally:
        ro.chmod(0o755)
    # near miss: the same folder writable
    res = run_cli(*argv, cwd=tmp_path)
    assert res.returncode in (0, 1), res.stderr


def test_add_given_a_folder_says_it_is_a_folder(tmp_path: Path) -> None:
    folder = tmp_path / "urdf"
    folder.mkdir()
    (folder / "sub").mkdir()  # a folder with subfolders has several hard links
    line = _one_line(run_cli("add-camera", str(folder), "--name", "cam", "--parent", "base_link"))
    assert line.startswith(f"sensorkit: {folder} is a folder"), line
    assert "hard link" not in line


def test_add_into_sdf_refuses_in_one_line_naming_what_it_edits(tmp_path: Path) -> None:
    sdf = '<sdf version="1.9"><model name="m"><link name="base_link"/></model></sdf>'
    for name in ("model.sdf", "model.urdf"):  # by its name, and by its root
        path = tmp_path / name
        path.write_text(sdf)
        line = _one_line(run_cli("add-camera", str(path), "--name", "cam", "--parent", "base_link"))
        assert "is SDF" in line and "URDF and xacro" in line and "validate" in line, line
        assert path.read_text() == sdf
    # near miss: the same link in a URDF takes the camera
    urdf = tmp_path / "r.urdf"
    urdf.write_text('<robot name="r"><link name="base_link"/></robot>')
    res = run_cli("add-camera", str(urdf), "--name", "cam", "--parent", "base_link")
    assert res.returncode == 0 and "cam" in urdf.read_text(), res.stderr


def test_validate_a_robot_yaml_points_to_new_and_new_a_urdf_to_validate(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text("name: bot\nsensors: []\n")
    for cmd in (
        ["validate"],
        ["topics"],
        ["frames"],
        ["add-imu", "--name", "i", "--parent", "base_link"],
    ):
        line = _one_line(run_cli(cmd[0], "robot.yaml", *cmd[1:], cwd=tmp_path))
        assert (
            line == "sensorkit: robot.yaml: not a URDF/xacro: robot YAMLs go to `sensorkit new`"
        ), line
    robot = _rover(tmp_path)
    line = _one_line(run_cli("new", "rover.urdf", "-o", "out", cwd=tmp_path))
    assert line.startswith("sensorkit: rover.urdf: not a robot YAML: `sensorkit new` takes a robot YAML; "
                           "URDF/xacro go to `sensorkit validate`"), line  # fmt: skip
    assert not (tmp_path / "out").exists()
    robot.rename(tmp_path / "robot.txt")  # the content, not the name, tells
    line = _one_line(run_cli("new", "robot.txt", "-o", "out", cwd=tmp_path))
    assert "URDF/xacro go to `sensorkit validate`" in line


def test_a_closed_pipe_ends_quietly() -> None:
    # the reader is gone before sensorkit has started: its first write meets a closed pipe
    script = (
        f"{shlex.quote(sys.executable)} -m sensorkit rules | true; echo status=${{PIPESTATUS[0]}}"
    )
    res = subprocess.run(
        ["bash", "-c", script], capture_output=True, text=True, timeout=60, check=False
    )
    assert res.stderr == "", res.stderr
    assert res.stdout.strip() in ("status=0", "status=141"), res.stdout
    # near miss: a reader that reads it all gets it all, status 0
    script = f"{shlex.quote(sys.executable)} -m sensorkit rules | head -1; echo status=${{PIPESTATUS[0]}}"
    res = subprocess.run(
        ["bash", "-c", script], capture_output=True, text=True, timeout=60, check=False
    )
    assert res.stdout.startswith("SK101") and res.stdout.strip().splitlines()[-1] in (
        "status=0",
        "status=141",
    )


def test_summaries_say_one_in_the_singular(tmp_path: Path) -> None:
    bad = ROOT / "tests" / "robots" / "acceptance" / "sk502_bad.urdf"
    res = run_cli("validate", str(bad))
    assert res.stdout.splitlines()[-1].startswith("1 error, 0 warnings, 0 info in 1 file"), (
        res.stdout
    )
    robot = _rover(tmp_path)
    res = run_cli("add-camera", str(robot), "--name", "cam", "--parent", "base_link")
    assert res.returncode == 0, res.stderr
    res = run_cli("validate", str(robot))
    assert "(1 sensor checked)" in res.stdout, res.stdout
    res = run_cli("export", str(robot), "-o", str(tmp_path / "exp"))
    assert " for 1 sensor of " in res.stderr and "1 sensors" not in res.stderr, res.stderr


def test_an_option_where_a_value_belongs_is_a_missing_value(tmp_path: Path) -> None:
    robot = _rover(tmp_path)
    before = robot.read_bytes()
    argv = ["add-camera", str(robot), "--name", "cam", "--parent", "base_link"]
    line = _one_line(run_cli(*argv, "--xyz", "0.2", "0", "--diff"))
    assert line == "sensorkit: --xyz needs 3 values; got '--diff', an option", line
    line = _one_line(run_cli(*argv, "--rpy", "0", "-q", "0"))
    assert line == "sensorkit: --rpy needs 3 values; got '-q', an option", line
    assert robot.read_bytes() == before
    # near miss: a negative number is a value
    res = run_cli(*argv, "--xyz", "0.2", "-0.1", "0", "--diff")
    assert res.returncode == 0 and res.stdout.startswith("---"), res.stderr


def test_an_option_where_one_value_belongs_is_a_missing_value(tmp_path: Path) -> None:
    robot = _rover(tmp_path)
    before = robot.read_bytes()
    line = _one_line(run_cli("validate", "--target", "--fix", str(robot)))
    assert line == "sensorkit: --target needs a value; got '--fix', an option", line
    assert robot.read_bytes() == before
    line = _one_line(run_cli("export", str(robot), "-o", "--force"))
    assert line == "sensorkit: -o needs a value; got '--force', an option", line
    # near misses: flags side by side, a number, stdin
    res = run_cli(
        "validate", "-q", "--exit-zero", "--timeout", "30", "--fail-on", "warning", str(robot)
    )
    assert res.returncode == 0, res.stderr
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", "validate", "--stdin-filename", "x.urdf", "-", "--exit-zero"],
        input=before.decode(), capture_output=True, text=True, timeout=60, check=False,
    )  # fmt: skip
    assert res.returncode == 0, res.stderr


# --------------------------------------------------------------------------- fixable marks

ACCEPTANCE = ROOT / "tests" / "robots" / "acceptance"


def _copy(tmp_path: Path, *names: str) -> list[str]:
    for name in names:
        shutil.copyfile(ACCEPTANCE / name, tmp_path / name)
    return list(names)


def test_fixable_findings_are_marked_and_counted(tmp_path: Path) -> None:
    files = _copy(tmp_path, "sk502_bad.urdf", "sk301_bad.urdf", "sk605_bad.urdf")
    res = run_cli("validate", *files, cwd=tmp_path)
    lines = res.stdout.splitlines()
    marked = [line for line in lines if "[*]" in line]
    assert len(marked) == 1 and ": SK502 [*] error: " in marked[0], res.stdout
    assert any(": SK301 error: " in line for line in lines)  # unsafe: not marked
    assert any(": SK605 error: " in line for line in lines)  # no fixer: not marked
    assert lines[-1].endswith("; 1 fixable with `--fix` (1 more with `--unsafe-fixes`)"), lines[-1]
    data = json.loads(run_cli("validate", "-f", "json", *files, cwd=tmp_path).stdout)
    how = {f["rule"]: f["fixable"] for f in data["findings"]}
    assert how["SK502"] == "safe" and how["SK301"] == "unsafe" and how["SK605"] is None
    # the same with worker processes
    res2 = run_cli("validate", "-j", "2", *files, cwd=tmp_path)
    assert res2.stdout == res.stdout
    # near miss: nothing fixable, no count
    res = run_cli("validate", "sk605_bad.urdf", cwd=tmp_path)
    assert "[*]" not in res.stdout and "fixable" not in res.stdout


def test_every_fixer_rule_is_known_to_validate() -> None:
    from sensorkit.cli.validate import FIXABLE_RULES
    from sensorkit.fix import FIXERS

    assert set(FIXERS) == FIXABLE_RULES


def test_fix_says_why_each_finding_was_left(tmp_path: Path) -> None:
    files = _copy(tmp_path, "sk502_bad.urdf", "sk301_bad.urdf", "sk605_bad.urdf")
    res = run_cli("validate", "--fix", *files, cwd=tmp_path)
    err = res.stderr
    assert "fixed sk502_bad.urdf:37 SK502" in err
    assert (
        "not fixed sk301_bad.urdf:18 SK301: an unsafe fix" in err and "needs --unsafe-fixes" in err
    )
    left = [
        line for line in err.splitlines() if line.startswith("sensorkit: not fixed sk605_bad.urdf")
    ]
    rules = sorted(line.split()[4].rstrip(":") for line in left)
    assert "SK605" in rules and all("no automatic fix for this rule" in line for line in left), err
    remaining = [line for line in res.stdout.splitlines() if re.match(r"\s+\S+:\d+: SK\d+", line)]
    assert len(err.split("sensorkit: not fixed ")) - 1 == len(remaining), (res.stdout, err)


def test_diff_exits_by_whether_it_would_change_a_file(tmp_path: Path) -> None:
    _copy(tmp_path, "sk502_bad.urdf", "sk605_bad.urdf", "sk502_fixed.urdf")
    before = (tmp_path / "sk502_bad.urdf").read_bytes()
    res = run_cli("validate", "--diff", "sk502_bad.urdf", cwd=tmp_path)
    assert res.returncode == 1 and res.stdout.startswith("--- a/sk502_bad.urdf"), res.stderr
    assert (tmp_path / "sk502_bad.urdf").read_bytes() == before
    # errors, but nothing --diff would change: 0
    res = run_cli("validate", "--diff", "sk605_bad.urdf", cwd=tmp_path)
    assert res.returncode == 0 and res.stdout == "", res.stderr
    res = run_cli("validate", "--diff", "sk502_fixed.urdf", cwd=tmp_path)
    assert res.returncode == 0 and res.stdout == ""
    res = run_cli("validate", "--diff", "--exit-zero", "sk502_bad.urdf", cwd=tmp_path)
    assert res.returncode == 0 and res.stdout.startswith("---")


# --------------------------------------------------------------------------- add-* refusals

ONE_LINK = '<robot name="x"><link name="base_link"/></robot>\n'
NO_LINKS = '<robot name="x"><joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>\n'


@pytest.mark.parametrize(
    ("robot", "extra", "says"),
    [
        ("rover", ["--parent", "base_lnk"], "closest: base_link: pass --parent base_link"),
        ("no_links", ["--parent", "a"], "the robot has no links: add the link to mount on first"),
        ("rover", ["--name", "base"], "pass another --name (e.g. base_2)"),
        ("rover", ["--width", "0"], "SK403 sensor 'cam': image width 0 is not positive; write a positive"),
        ("rover", ["--param", "widht=640"], "has no parameter 'widht' (it takes: update_rate, width, height, hfov, format, near, far, noise_stddev, mass, size, namespace, sim, gz_version); check the spelling, or leave it out"),
        ("rover", ["-o", "nodir/out.urdf"], "nodir: no such folder; create it first"),
        ("not_xml", [], "not well-formed XML"),
    ],
)  # fmt: skip
def test_add_refusals_name_the_next_step(
    tmp_path: Path, robot: str, extra: list[str], says: str
) -> None:
    path = tmp_path / "robot.urdf"
    if robot == "rover":
        shutil.copyfile(ROBOTS / "rover.urdf", path)
    else:
        path.write_text({"no_links": NO_LINKS, "not_xml": "hello\n"}[robot])
    before = path.read_bytes()
    argv = ["add-camera", "robot.urdf", "--name", "cam", "--parent", "base_link"]
    for i in range(0, len(extra), 2):  # an option given again replaces the default one
        if extra[i] in argv:
            j = argv.index(extra[i])
            argv[j : j + 2] = extra[i : i + 2]
        else:
            argv += extra[i : i + 2]
    line = _one_line(run_cli(*argv, cwd=tmp_path))
    assert says in line, line
    assert path.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == [
        "robot.urdf"
    ]


def test_add_refusal_for_the_wrong_sim_names_the_sim(tmp_path: Path) -> None:
    shutil.copyfile(ROBOTS / "rover.urdf", tmp_path / "robot.urdf")
    (tmp_path / "sensorkit.toml").write_text('target = "harmonic"\n')
    argv = ["add-camera", "robot.urdf", "--name", "cam", "--parent", "base_link", "--diff"]
    res = run_cli(*argv, "--sim", "classic", cwd=tmp_path)
    assert res.returncode == 2
    assert (
        "the robot is checked for target harmonic: pass --sim gz, or leave --sim out" in res.stderr
    )
    assert "remove it" not in res.stderr  # the plugin is the add's own text, not the user's
    # near miss: the sim that fits
    res = run_cli(*argv, "--sim", "gz", cwd=tmp_path)
    assert res.returncode == 0 and res.stdout.startswith("---"), res.stderr


def test_add_to_a_read_only_file_says_to_make_it_writable(tmp_path: Path) -> None:
    path = _rover(tmp_path)
    path.chmod(0o444)
    line = _one_line(run_cli("add-imu", str(path), "--name", "imu", "--parent", "base_link"))
    assert "is read-only" in line and "make it writable (chmod u+w)" in line


def test_add_to_a_file_that_does_not_load_says_validate(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(
        '<robot name="x" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<link name="base_link"/><xacro:nope/></robot>\n'
    )
    line = _one_line(
        run_cli(
            "add-imu", "robot.urdf.xacro", "--name", "imu", "--parent", "base_link", cwd=tmp_path
        )
    )
    assert "does not load" in line and "`sensorkit validate robot.urdf.xacro` shows it" in line, (
        line
    )


def test_add_into_a_package_sharing_its_robot_yaml_warns_first(tmp_path: Path) -> None:
    src = tmp_path / "src"
    src.mkdir()
    (src / "robot.yaml").write_text("name: bot\nsensors: []\n")
    res = run_cli("new", "robot.yaml", "-o", "bot_description", "-q", cwd=src)
    assert res.returncode == 0, res.stderr
    shutil.copytree(src / "bot_description", src / "bot_copy")
    argv = ["add-camera", "bot_copy/urdf/bot.urdf.xacro", "--name", "cam", "--parent", "base_link"]
    res = run_cli(*argv, cwd=src)
    assert res.returncode == 0, res.stderr
    first = next(line for line in res.stderr.splitlines() if "sim=" not in line)
    assert first.startswith("sensorkit: warning: robot.yaml also generates bot_description:"), (
        res.stderr
    )
    assert "copy robot.yaml into bot_copy" in first
    # near miss: a package with its own robot.yaml shares nothing
    shutil.copyfile(src / "robot.yaml", src / "bot_copy" / "robot.yaml")
    res = run_cli(*[a if a != "cam" else "cam2" for a in argv], cwd=src)
    assert res.returncode == 0 and "warning:" not in res.stderr, res.stderr


def test_validate_a_launch_file_or_an_image_is_one_line(tmp_path: Path) -> None:
    (tmp_path / "sim.launch.py").write_text("from launch import LaunchDescription\n")
    (tmp_path / "photo.png").write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00")
    line = _one_line(run_cli("validate", "sim.launch.py", cwd=tmp_path))
    assert (
        line
        == "sensorkit: sim.launch.py: not a URDF/xacro: launch files go to `--launch` (validate, topics)"
    )
    line = _one_line(run_cli("validate", "photo.png", cwd=tmp_path))
    assert line.startswith("sensorkit: photo.png: not a URDF/xacro (it is not XML"), line
    # near miss: a broken .urdf stays a finding (SK101), exit 1
    (tmp_path / "junk.urdf").write_text("junk\n")
    res = run_cli("validate", "junk.urdf", cwd=tmp_path)
    assert res.returncode == 1 and "SK101" in res.stdout


def test_a_read_only_folder_of_an_edited_file_is_not_writable(tmp_path: Path) -> None:
    folder = tmp_path / "ro"
    folder.mkdir()
    shutil.copyfile(ROBOTS / "rover.urdf", folder / "r.urdf")
    folder.chmod(0o555)
    try:
        line = _one_line(
            run_cli("add-imu", "ro/r.urdf", "--name", "imu", "--parent", "base_link", cwd=tmp_path)
        )
    finally:
        folder.chmod(0o755)
    assert "is not writable" in line and "make it writable (chmod u+w)" in line, line


def test_config_given_a_folder_says_it_is_a_folder(tmp_path: Path) -> None:
    _rover(tmp_path)
    (tmp_path / "conf").mkdir()
    line = _one_line(run_cli("validate", "rover.urdf", "--config", "conf", cwd=tmp_path))
    assert (
        line == "sensorkit: --config conf is a folder; name its sensorkit.toml or pyproject.toml"
    ), line
    line = _one_line(run_cli("validate", "rover.urdf", "--config", "nope.toml", cwd=tmp_path))
    assert line == "sensorkit: --config nope.toml: no such file", line


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (["valdiate", "x.urdf"], "sensorkit: No such command 'valdiate'. Did you mean 'validate'? (see '"),
        (["validate", "--targte", "classic", "{robot}"], "sensorkit: validate: No such option: --targte"),
        (["validate"], "sensorkit: validate: Missing argument 'files' (see '"),
        (["validate", "-j", "abc", "{robot}"], "sensorkit: validate: Invalid value for '--jobs' / '-j'"),
        (["add-camera", "{robot}", "--sim", "gazebo"], "sensorkit: add-camera: Invalid value for '--sim'"),
        (["render", "preview", "{robot}", "--nope"], "sensorkit: render preview: No such option: --nope"),
    ],
)  # fmt: skip
def test_a_usage_error_is_one_line(tmp_path: Path, args: list[str], said: str) -> None:
    """click's usage errors (an unknown command or option, a missing or bad value) are one
    line on stderr, exit 2, naming the command and its help, as sensorkit's other errors:
    not a usage line, a hint and a box of five lines."""
    robot = _rover(tmp_path)
    res = run_cli(*[a.format(robot=robot) for a in args], cwd=tmp_path)
    line = _one_line(res)
    assert said in line and res.stdout == "", line
    command = args[0] if args[0] != "render" else "render preview"
    assert line.endswith(f"sensorkit {command} -h')" if args[0] != "valdiate" else "sensorkit -h')")


def test_a_command_group_without_its_command_still_prints_its_help() -> None:
    """The near miss: `sensorkit render` (a group, no command) and `sensorkit` alone print
    their help, as before, exit 2."""
    for args, lists in ((["render"], "preview"), ([], "validate")):
        res = run_cli(*args)
        assert res.returncode == 2 and "Usage:" in res.stdout and lists in res.stdout, args


def test_an_abort_is_one_line_and_another_error_stays_itself(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """run_app's except clauses name only exceptions that exist: click's Abort (EOF or
    Ctrl-C at a prompt) is 'sensorkit: aborted', exit 1; any other exception passes through
    as itself (it was an AttributeError: typer's vendored click has no Abort where looked)."""
    from sensorkit import cli

    def abort(**_kw: object) -> None:
        raise cli._abort_type()

    monkeypatch.setattr(cli, "app", abort)
    assert cli.run_app() == 1 and capsys.readouterr().err == "sensorkit: aborted\n"

    def bug(**_kw: object) -> None:
        raise LookupError("a bug of ours")

    monkeypatch.setattr(cli, "app", bug)
    with pytest.raises(LookupError):
        cli.run_app()
