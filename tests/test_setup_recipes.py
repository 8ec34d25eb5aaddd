"""Issue 38: every set-up recipe of the README runs as written: the quick start on a colcon
workspace, pipx and pip from a clone, pre-commit from a clone (its `rev:` exists, and
`pre-commit autoupdate` moves it), the `repo: local` hook, the CI job's commands, the
Neovim snippet in a headless Neovim, and `sensorkit lsp` typed in a terminal.

The installs are real (a virtual environment, pip's cache makes them quick); they need the
package index, as `bash tests/run` does."""

from __future__ import annotations

import os
import pty
import re
import select
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml
from conftest import ROOT

ACCEPTANCE = ROOT / "tests" / "robots" / "acceptance"
BIN = Path(sys.executable).parent  # the test venv: sensorkit, pre-commit, pipx
NVIM_MIN = (0, 8)  # vim.lsp.start and vim.fs.find/dirname came in Neovim 0.8


def _readme() -> str:
    return (ROOT / "README.md").read_text()


def _block(after: str, lang: str, text: str | None = None) -> str:
    """The first ```lang block after the heading ``after``."""
    text = _readme() if text is None else text
    section = text.split(after, 1)[1]
    found = re.search(rf"```{lang}\n(.*?)```", section, flags=re.S)
    assert found, (after, lang)
    return found.group(1)


def _env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PIP_", "PIPX_", "PRE_COMMIT"))}
    env["PATH"] = f"{BIN}{os.pathsep}{env.get('PATH', '')}"
    # The recipes install sensorkit and its dependencies three times over (pip, pipx,
    # pre-commit): pip's byte-compiling of ~300 MB of packages is 40 % of each install's CPU,
    # and Python compiles what a command imports anyway. Nothing a recipe asserts changes.
    env.update(PIP_NO_COMPILE="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    env.update(extra)
    return env


def _run(cmd: str | list[str], cwd: Path, timeout: int = 600, **env: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        cmd, cwd=cwd, shell=isinstance(cmd, str), capture_output=True, text=True,
        timeout=timeout, check=False, env=_env(**env),
    )  # fmt: skip


def _copy_of_the_clone(dest: Path) -> Path:
    """The project as a user's clone holds it, without the test venv and caches."""
    ignore = shutil.ignore_patterns(".venv", ".git", "__pycache__", "*.egg-info", ".pytest_cache",
                                    ".mypy_cache", ".ruff_cache", "build", "dist")  # fmt: skip
    shutil.copytree(ROOT, dest, ignore=ignore)
    return dest


# --------------------------------------------------------------------------- the quick start


def _workspace(tmp_path: Path) -> Path:
    """A colcon workspace with the README's robot: a description package under src/."""
    ws = tmp_path / "ros2_ws"
    pkg = ws / "src" / "my_robot_description"
    shutil.copytree(ROOT / "examples" / "harmonic_robot" / "harmonic_robot_description", pkg)
    (pkg / "urdf" / "harmonic_robot.urdf.xacro").rename(pkg / "urdf" / "my_robot.urdf.xacro")
    for build in ("build", "install", "log"):  # colcon's own folders, which validate skips
        (ws / build).mkdir()
    (ws / "install" / "junk.urdf").write_text("not a robot")
    return ws


def test_the_quick_start_runs_on_a_colcon_workspace(tmp_path: Path) -> None:
    lines = [ln for ln in _block("## Quick start", "sh").splitlines() if ln.strip()]
    assert len(lines) == 5, lines
    assert lines[0] == "pipx install ./sensorkit"  # run by test_pipx_installs_from_a_clone
    assert lines[1] == "cd ~/ros2_ws"
    ws = _workspace(tmp_path)
    for line in lines[2:]:
        assert line.startswith("sensorkit "), line
        res = _run(line, cwd=ws, timeout=900)
        assert res.returncode == 0, (line, res.stdout, res.stderr)
        assert "Traceback" not in res.stderr
        if " validate " in line:
            assert "0 errors, 0 warnings" in res.stdout and "in 2 files" in res.stdout, res.stdout
            assert "junk" not in res.stdout + res.stderr
        if " topics " in line:
            assert "/front_camera/image_raw" in res.stdout, res.stdout
    page = (ws / "preview" / "index.html").read_text()
    assert "PASS" in page


# --------------------------------------------------------------------------- installs


def test_pipx_installs_from_a_clone_into_its_own_home(tmp_path: Path) -> None:
    line = "pipx install ./sensorkit"
    assert f"| `{line}` |" in _readme()
    _copy_of_the_clone(tmp_path / "sensorkit")
    home, bin_dir = tmp_path / "pipx", tmp_path / "bin"
    res = _run(line, cwd=tmp_path, PIPX_HOME=str(home), PIPX_BIN_DIR=str(bin_dir),
               PIPX_MAN_DIR=str(tmp_path / "man"), HOME=str(tmp_path))  # fmt: skip
    assert res.returncode == 0, res.stdout + res.stderr
    exe = bin_dir / "sensorkit"
    assert exe.exists(), res.stdout
    assert (home / "venvs" / "sensorkit-ros").is_dir()  # the distribution's own name
    res = subprocess.run([str(exe), "validate", str(ACCEPTANCE / "sk502_bad.urdf")],
                         capture_output=True, text=True, timeout=120, check=False)  # fmt: skip
    assert res.returncode == 1 and ": SK502 " in res.stdout, res.stdout + res.stderr


def test_the_set_up_line_and_pip_from_a_clone_install_sensorkit(tmp_path: Path) -> None:
    clone = _copy_of_the_clone(tmp_path / "sensorkit")
    setup = _block("## Set up", "sh").strip()
    res = _run(setup, cwd=clone, timeout=900)
    assert res.returncode == 0 and "ok: no findings" in res.stdout, res.stdout + res.stderr
    # the install table's pip line, from beside the clone, into that venv (activated, as a
    # user's); its dependencies are there already, so this costs a wheel build
    line = "pip install ./sensorkit"
    assert f"| `{line}` |" in _readme()
    res = _run(f". sensorkit/.venv/bin/activate && {line} && pip list --format freeze && sensorkit --version",
               cwd=tmp_path, timeout=900)  # fmt: skip
    assert res.returncode == 0, res.stdout + res.stderr
    assert res.stdout.splitlines()[-1].startswith("sensorkit "), res.stdout
    assert "sensorkit-ros==" in res.stdout, res.stdout  # the distribution's own name


# --------------------------------------------------------------------------- pre-commit and CI


def _user_repo(tmp_path: Path, config: str, robot: str) -> Path:
    repo = tmp_path / "ws"
    (repo / "src" / "bot" / "urdf").mkdir(parents=True)
    shutil.copyfile(ACCEPTANCE / robot, repo / "src" / "bot" / "urdf" / "bot.urdf")
    (repo / ".pre-commit-config.yaml").write_text(config)
    for cmd in ("git init -q", "git add -A"):
        assert _run(cmd, cwd=repo).returncode == 0
    return repo


def _ci_commands() -> list[str]:
    job = yaml.safe_load(_block("## CI", "yaml"))
    steps = job["jobs"]["sensors"]["steps"]
    runs = [s["run"] for s in steps if "run" in s]
    assert runs[0] == "pip install pre-commit"  # the test extra has it
    return runs[1:]


def test_pre_commit_from_a_clone_with_the_readme_rev(tmp_path: Path) -> None:
    if not (ROOT / ".git").exists():
        pytest.skip("not a git checkout: pre-commit needs the repository's history")
    if _run("git rev-parse --is-shallow-repository", cwd=ROOT).stdout.strip() == "true":
        pytest.skip("a shallow clone may lack the README's rev: fetch the history to test it")
    config = _block("## pre-commit", "yaml")
    rev = yaml.safe_load(config)["repos"][0]["rev"]
    assert re.fullmatch(r"[0-9a-f]{40}", rev), rev
    # the rev exists in this repository and holds the hook
    shown = _run(f"git show {rev}:.pre-commit-hooks.yaml", cwd=ROOT)
    assert shown.returncode == 0 and "id: sensorkit-validate" in shown.stdout, shown.stderr
    clone = tmp_path / "sensorkit"
    assert _run(f"git clone -q {ROOT} {clone}", cwd=tmp_path).returncode == 0
    url = re.search(r"repo: (\S+)", config)
    assert url and url.group(1).startswith("https://")
    repo = _user_repo(tmp_path, config.replace(url.group(1), str(clone)), "sk502_bad.urdf")
    cache = str(tmp_path / "cache")
    res = _run("pre-commit autoupdate", cwd=repo, PRE_COMMIT_HOME=cache)
    assert res.returncode == 0, res.stdout + res.stderr
    head = _run("git rev-parse HEAD", cwd=clone).stdout.strip()
    assert f"rev: {head}" in (repo / ".pre-commit-config.yaml").read_text()  # moved on
    for cmd in _ci_commands():
        res = _run(cmd, cwd=repo, timeout=900, PRE_COMMIT_HOME=cache)
        assert res.returncode == 1, res.stdout + res.stderr
        assert ": SK502 " in res.stdout and "Failed" in res.stdout, res.stdout
    # near miss: the robot fixed, the hook passes
    shutil.copyfile(ACCEPTANCE / "sk502_fixed.urdf", repo / "src" / "bot" / "urdf" / "bot.urdf")
    res = _run(_ci_commands()[0], cwd=repo, timeout=900, PRE_COMMIT_HOME=cache)
    assert res.returncode == 0 and "Passed" in res.stdout, res.stdout + res.stderr


def test_pre_commit_local_hook_for_a_vendored_copy(tmp_path: Path) -> None:
    text = _readme()
    start = text.index("```yaml\nrepos:\n  - repo: local")
    config = text[start + len("```yaml\n") : text.index("```", start + 3)]
    repo = _user_repo(tmp_path, config, "sk502_bad.urdf")
    cache = str(tmp_path / "cache")
    res = _run("pre-commit run sensorkit-validate --all-files", cwd=repo, PRE_COMMIT_HOME=cache)
    assert res.returncode == 1 and ": SK502 " in res.stdout, res.stdout + res.stderr
    (repo / "notes.xml").write_text("<robot/>")  # not a robot file: the hook leaves it
    shutil.copyfile(ACCEPTANCE / "sk502_fixed.urdf", repo / "src" / "bot" / "urdf" / "bot.urdf")
    _run("git add -A", cwd=repo)
    res = _run("pre-commit run sensorkit-validate --all-files", cwd=repo, PRE_COMMIT_HOME=cache)
    assert res.returncode == 0 and "notes.xml" not in res.stdout, res.stdout + res.stderr


# --------------------------------------------------------------------------- editors


def _nvim() -> tuple[str, tuple[int, ...]] | None:
    exe = os.environ.get("SENSORKIT_TEST_NVIM") or shutil.which("nvim")
    if not exe:
        return None
    out = subprocess.run([exe, "--version"], capture_output=True, text=True, timeout=30,
                         check=False).stdout  # fmt: skip
    found = re.search(r"NVIM v(\d+)\.(\d+)", out)
    return (exe, (int(found.group(1)), int(found.group(2)))) if found else None


CHECK_LUA = """
local ok = vim.wait(60000, function() return #vim.diagnostic.get(0) > 0 end, 100)
local get = vim.lsp.get_clients or vim.lsp.get_active_clients
local lines = { 'clients ' .. #get({ bufnr = 0 }) }
for _, d in ipairs(vim.diagnostic.get(0)) do
  table.insert(lines, string.format('%s %d %s', tostring(d.code), d.lnum + 1, d.source or ''))
end
vim.fn.writefile(lines, vim.env.SK_OUT)
vim.cmd('qa!')
"""


def test_the_readme_neovim_snippet_attaches_and_shows_diagnostics(tmp_path: Path) -> None:
    assert "**Neovim 0.8 or newer**" in _readme()
    found = _nvim()
    if found is None or found[1] < NVIM_MIN:
        seen = "none installed" if found is None else "found {}.{}".format(*found[1])
        pytest.skip(f"needs Neovim 0.8 or newer for the README's snippet ({seen}; Debian 12 ships 0.7)")
    exe = found[0]
    snippet = _block("**Neovim 0.8 or newer**", "lua")
    assert "vim.lsp.start(" in snippet and "nvim_create_autocmd" in snippet
    # only vim.fs functions that Neovim 0.8 has (vim.fs.root is 0.10)
    assert set(re.findall(r"vim\.fs\.(\w+)", snippet)) <= {"find", "dirname", "basename", "dir", "parents", "normalize"}
    (tmp_path / "init.lua").write_text(snippet)
    (tmp_path / "check.lua").write_text(CHECK_LUA)
    robot = tmp_path / "robot.urdf"
    shutil.copyfile(ACCEPTANCE / "sk502_bad.urdf", robot)
    out = tmp_path / "out.txt"
    argv = [exe, "--headless", "-n", "-i", "NONE", "-u", str(tmp_path / "init.lua")]
    env = {"SK_OUT": str(out), "XDG_STATE_HOME": str(tmp_path / "state"),
           "XDG_DATA_HOME": str(tmp_path / "data"), "XDG_CONFIG_HOME": str(tmp_path / "cfg")}  # fmt: skip
    res = _run([*argv, str(robot), "-c", f"luafile {tmp_path / 'check.lua'}"], cwd=tmp_path,
               timeout=120, **env)  # fmt: skip
    lines = out.read_text().splitlines() if out.exists() else []
    assert lines and lines[0] == "clients 1", (lines, res.stderr)
    assert "SK502 37 sensorkit" in lines[1:], lines
    # near miss: an XML file that is no robot gets no client
    plain = tmp_path / "plain.xml"
    plain.write_text("<a/>\n")
    check = CHECK_LUA.replace("60000", "1")
    (tmp_path / "check.lua").write_text(check)
    _run([*argv, str(plain), "-c", f"luafile {tmp_path / 'check.lua'}"], cwd=tmp_path, timeout=120, **env)
    assert out.read_text().splitlines() == ["clients 0"]


def _read_until(fd: int, needle: bytes, seconds: float) -> bytes:
    seen = b""
    end = time.monotonic() + seconds
    while needle not in seen and time.monotonic() < end:
        ready, _, _ = select.select([fd], [], [], 0.2)
        if ready:
            try:
                seen += os.read(fd, 4096)
            except OSError:
                break
    return seen


def test_lsp_on_a_terminal_says_it_waits_for_an_editor_and_one_ctrl_c_ends_it() -> None:
    pid, fd = pty.fork()
    if pid == 0:  # the child: sensorkit lsp on a terminal
        os.execv(sys.executable, [sys.executable, "-m", "sensorkit", "lsp"])
    done = 0
    try:
        said = _read_until(fd, b"Ctrl-C ends it", 60)
        assert b"waiting for an editor" in said and b"Ctrl-C ends it" in said, said
        os.write(fd, b"\x03")  # one Ctrl-C, as the terminal sends it
        end = time.monotonic() + 10
        while time.monotonic() < end:
            done, status = os.waitpid(pid, os.WNOHANG)
            if done:
                break
            time.sleep(0.05)
        assert done, "one Ctrl-C did not end sensorkit lsp"
        assert os.waitstatus_to_exitcode(status) == 130
    finally:
        if not done:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
        os.close(fd)


def test_lsp_from_an_editor_prints_nothing_to_stderr() -> None:
    # near miss: stdin a pipe (an editor): no word on stderr, and end of input ends it
    res = subprocess.run([sys.executable, "-m", "sensorkit", "lsp"], input="", capture_output=True,
                         text=True, timeout=60, check=False)  # fmt: skip
    assert res.returncode == 0 and res.stderr == "", res.stderr
