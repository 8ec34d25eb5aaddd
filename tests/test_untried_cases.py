"""Issue 36, item 10: the cases not tried before, each a test.

- a full disk for ``export`` (RLIMIT_FSIZE: the kernel fails the write with EFBIG, as a
  full disk fails it; ``new`` on a full medium: tests/test_write_races.py);
- a read-only output folder (root writes through file modes, so a folder in /proc,
  where nothing may be created whoever asks);
- a file changed by another process while ``--fix`` runs;
- a settings file whose package paths point outside the repository, opened by the
  language server;
- (an ``$(optenv)`` variable changing between two cached runs: tests/test_cache_trust.py).
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
EXAMPLE = ROOT / "examples" / "humble_three_sensors"


def _robot() -> Path:
    return EXAMPLE / "urdf" / "robot_with_sensors.xacro"


def _export(out: Path, fsize: int | None = None) -> subprocess.CompletedProcess[str]:
    limit = (
        "import resource, signal\nsignal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
        f"resource.setrlimit(resource.RLIMIT_FSIZE, ({fsize}, {fsize}))\n"
        if fsize is not None
        else ""
    )
    code = limit + textwrap.dedent(
        f"""
        import sys
        from sensorkit.cli import main
        sys.argv = ["sensorkit", "export", {str(_robot())!r}, "-o", {str(out)!r}, "--no-cache"]
        main()
        """
    )
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=180, check=False,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )  # fmt: skip


def test_export_on_a_full_disk_says_so_in_one_line(tmp_path: Path) -> None:
    out = tmp_path / "cfg"
    res = _export(out, fsize=300)
    assert res.returncode in (1, 2), res.stdout + res.stderr
    assert "Traceback" not in res.stderr and "Errno" not in res.stderr, res.stderr
    assert "File too large" in res.stderr, res.stderr
    assert all(len(line) < 400 for line in res.stderr.splitlines())
    ok = _export(tmp_path / "cfg2")  # the near miss: without the limit it writes
    assert ok.returncode == 0, ok.stderr
    assert any((tmp_path / "cfg2").rglob("*.yaml"))


def test_export_into_a_folder_nobody_may_write(tmp_path: Path) -> None:
    out = Path("/proc/self/sensorkit_export")
    res = _export(out)
    assert res.returncode == 2, res.stdout + res.stderr
    assert "Traceback" not in res.stderr, res.stderr
    lines = [x for x in res.stderr.splitlines() if x.strip()]
    assert len(lines) == 1 and "/proc/self is not writable" in lines[0], res.stderr
    assert "nothing was written" in lines[0]


def test_fix_while_another_process_writes_the_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Another process (not this one) changes the robot between the plan and the write:
    its change is kept, and the fix is made again on top of it."""
    from test_fix import OPTICAL, fix, robot, write

    from sensorkit.fix import apply

    path = write(tmp_path, "rover.urdf", robot(optical="-1.57 0 -1.57"))
    plan = apply.plan_file
    calls: list[int] = []

    def other_process(*args: object, **kw: object) -> object:
        out = plan(*args, **kw)  # type: ignore[arg-type]
        if not calls:
            subprocess.run(
                [sys.executable, "-c",
                 "import sys, pathlib; p = pathlib.Path(sys.argv[1]); "
                 "p.write_text(p.read_text().replace('a rover for', 'another process rover for'))",
                 str(path)],
                check=True, timeout=60,
            )  # fmt: skip
        calls.append(1)
        return out

    monkeypatch.setattr(apply, "plan_file", other_process)
    fix(path)
    text = path.read_text()
    assert "another process rover" in text and f'rpy="{OPTICAL}"' in text


def test_lsp_with_package_paths_outside_the_repository(tmp_path: Path) -> None:
    """The settings file's package-path names a folder above the repository and one that
    is not there: the server reports, publishes diagnostics and keeps running."""
    from lsp_client import Client

    repo = tmp_path / "runner" / "checkout"
    (repo / ".git").mkdir(parents=True)
    outside = tmp_path / "runner" / "outside_pkg"
    outside.mkdir()
    (outside / "package.xml").write_text("<package><name>outside_pkg</name></package>")
    (repo / "sensorkit.toml").write_text(
        f'package-path = ["{outside}", "{tmp_path / "gone"}"]\n'
    )
    robot = repo / "r.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base_link"/>'
        '<link name="l_$(find outside_pkg)"/></robot>\n'
    )
    c = Client(cwd=repo)
    try:
        c.initialize(repo)
        c.open(robot)
        diags = c.diagnostics(robot, timeout=120)
        assert isinstance(diags, list)
        assert c.proc.poll() is None
        assert c.close() == 0
    finally:
        c.kill()
