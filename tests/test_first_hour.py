"""Issue 27: what a newcomer meets in the first hour: the README's set-up and install lines,
the pre-commit hook, one error style, and refusals that name the next step."""

from __future__ import annotations

import re

import yaml
from conftest import ROOT

# pre-commit's manifest schema (pre_commit/clientlib.py MANIFEST_HOOK_DICT): required keys.
PRE_COMMIT_REQUIRED = ("id", "name", "entry", "language")


def test_pre_commit_hooks_file_is_what_pre_commit_requires() -> None:
    hooks = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())
    assert isinstance(hooks, list)
    (hook,) = [h for h in hooks if h["id"] == "sensorkit-validate"]
    assert all(isinstance(hook.get(key), str) and hook[key] for key in PRE_COMMIT_REQUIRED)
    assert hook["entry"] == "sensorkit validate" and hook["language"] == "python"
    files = re.compile(hook["files"])
    for name in ("robot.urdf.xacro", "a.urdf", "b.xacro", "src/bot/urdf/bot.urdf.xacro"):
        assert files.search(name), name
    for name in ("x.yaml", "robot.urdf.bak", "world.sdf"):
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
    sh = "".join(_readme_blocks("sh"))
    assert "pip install git+https://" in sh and "pipx install git+https://" in sh
    jobs = [yaml.safe_load(b) for b in _readme_blocks("yaml") if "jobs:" in b and "pre-commit" in b]
    assert jobs, "README has no GitHub Actions job running the hook"
    steps = jobs[0]["jobs"]["sensors"]["steps"]
    assert any("sensorkit-validate" in step.get("run", "") for step in steps)
