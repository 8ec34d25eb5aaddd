"""Many files at once: ``validate --jobs N``, folder arguments, and flat memory.

Behaviour only (the timings are benchmarks/bench_fleet.py's business).
"""

from __future__ import annotations

import gc
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import weakref
from collections.abc import Iterator
from pathlib import Path

import pytest

import sensorkit.lint.engine
import sensorkit.model
from sensorkit.base.errors import UsageError
from sensorkit.lint.engine import Options
from sensorkit.lint.fleet import find_robots, is_partial, validate_paths

ROOT = Path(__file__).resolve().parent.parent
ACCEPTANCE = ROOT / "tests" / "robots" / "acceptance"
XACRO_ROBOT = ROOT / "tests" / "edit_robots" / "xacro_robot"
XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def sk(*args: object, cwd: Path, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run(
        [sys.executable, "-m", "sensorkit", *map(str, args)],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


@pytest.fixture
def mix(tmp_path: Path) -> list[Path]:
    """Good, broken, xacro, a runaway xacro (times out), a failing include, a missing file."""
    for p in sorted(ACCEPTANCE.glob("*.urdf"))[:6]:
        shutil.copy(p, tmp_path / p.name)
    shutil.copytree(XACRO_ROBOT, tmp_path / "xrover")
    (tmp_path / "broken.urdf").write_text('<robot name="b"><link name="a">\n</robot>\n')
    (tmp_path / "runaway.urdf.xacro").write_text(
        f'<robot name="r" {XACRO_NS}><link name="${{10**10**10}}"/></robot>\n'
    )
    (tmp_path / "no_include.urdf.xacro").write_text(
        f'<robot name="n" {XACRO_NS}><xacro:include filename="nope.xacro"/>'
        '<link name="a"/></robot>\n'
    )
    names = [p.name for p in sorted(tmp_path.glob("*.urdf"))]
    files = [Path(n) for n in names[:3]]
    files += [Path("runaway.urdf.xacro"), Path("xrover/robot.urdf.xacro"), Path("missing.urdf")]
    files += [Path("no_include.urdf.xacro"), *map(Path, names[3:])]
    return files


@pytest.mark.parametrize("fmt", ["text", "json", "sarif", "github"])
def test_jobs_2_prints_what_jobs_1_prints(tmp_path: Path, mix: list[Path], fmt: str) -> None:
    one = sk("validate", "-f", fmt, "--timeout", "1", "--jobs", "1", *mix, cwd=tmp_path)
    two = sk("validate", "-f", fmt, "--timeout", "1", "--jobs", "2", *mix, cwd=tmp_path)
    assert one.returncode == two.returncode == 2  # missing.urdf could not be read
    assert one.stdout == two.stdout
    assert one.stderr == two.stderr
    if fmt == "json":
        data = json.loads(two.stdout)
        assert data["files"] == [str(p) for p in mix]  # input order, not finishing order
        text = json.dumps(data["findings"])
        assert "did not finish within 1 s" in text  # the runaway one timed out
        assert "nope.xacro" in text  # the failed include is reported
        assert "SK101" in text  # the broken file


def test_jobs_0_uses_every_core_and_keeps_order(tmp_path: Path, mix: list[Path]) -> None:
    files = [p for p in mix if "runaway" not in p.name][::-1]
    one = sk("validate", "-f", "json", "--jobs", "1", *files, cwd=tmp_path)
    every = sk("validate", "-f", "json", "--jobs", "0", *files, cwd=tmp_path)
    assert one.stdout == every.stdout and one.returncode == every.returncode
    assert json.loads(every.stdout)["files"] == [str(p) for p in files]


def test_a_worker_that_dies_costs_only_its_file(
    tmp_path: Path, mix: list[Path], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    files = [p for p in mix if "runaway" not in p.name and "missing" not in p.name]
    victim = files[2]
    real = sensorkit.lint.engine.validate_file

    def dying(path: Path, options: Options | None = None) -> sensorkit.lint.engine.FileReport:
        if path == victim:
            os._exit(9)  # as a segfault or the OOM killer would: no answer at all
        return real(path, options)

    expected = validate_paths(files, Options())
    monkeypatch.setattr(sensorkit.lint.engine, "validate_file", dying)  # forked workers inherit it
    report = validate_paths(files, Options(), jobs=2)
    assert [fr.path for fr in report.files] == files
    for got, want in zip(report.files, expected.files, strict=True):
        if got.path == victim:
            assert got.error is not None and "worker" in got.error and "exit status 9" in got.error
        else:
            assert got.findings == want.findings and got.error == want.error
    assert report.exit_code(Options().fail_on) == 2


def test_files_queued_behind_a_dying_worker_go_to_another(
    tmp_path: Path, mix: list[Path], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A worker holds the file it validates and the next: when it dies on the first, the
    next is validated by its replacement, not reported as the dead worker's."""
    from sensorkit.lint.fleet import QUEUED, run_pool

    assert QUEUED >= 2
    monkeypatch.chdir(tmp_path)
    files = [p for p in mix if "runaway" not in p.name and "missing" not in p.name]
    real = sensorkit.lint.engine.validate_file

    def dying(path: Path, options: Options | None = None) -> sensorkit.lint.engine.FileReport:
        if path in (files[0], files[3]):
            os._exit(9)
        return real(path, options)

    expected = validate_paths(files, Options())
    monkeypatch.setattr(sensorkit.lint.engine, "validate_file", dying)
    reports = run_pool(files, Options(), 1)  # one worker at a time: it holds files 0 and 1
    assert [fr.path for fr in reports] == files
    for i, (got, want) in enumerate(zip(reports, expected.files, strict=True)):
        if i in (0, 3):
            assert got.error is not None and "exit status 9" in got.error, got.error
        else:
            assert (got.findings, got.error) == (want.findings, want.error), got.path


def test_a_worker_gone_between_files_costs_nothing(
    tmp_path: Path, mix: list[Path], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A worker that dies after its last answer, before the parent sends it the next file
    (the send fails): no file is reported as its, and the next goes to a new worker."""
    import multiprocessing
    from multiprocessing.connection import Connection

    from sensorkit.lint.fleet import run_pool

    monkeypatch.chdir(tmp_path)
    files = [p for p in mix if "runaway" not in p.name and "missing" not in p.name][:2]
    expected = validate_paths(files, Options()).files
    parent = os.getpid()
    real_send = Connection.send
    failed: list[object] = []

    def send(conn: Connection, obj: object) -> None:
        if os.getpid() == parent and obj == (1, files[1]) and not failed:
            for child in multiprocessing.active_children():
                os.kill(child.pid or 0, signal.SIGKILL)  # the worker, answered and idle
            time.sleep(0.5)
            try:
                real_send(conn, obj)
            except OSError as exc:
                failed.append(exc)
                raise
            return
        real_send(conn, obj)

    monkeypatch.setattr(Connection, "send", send)
    # One worker, two files: it holds one at a time (no more files left than workers).
    reports = run_pool(files, Options(), 1)
    assert failed  # the send did fail
    assert [(r.path, r.findings, r.error) for r in reports] == [
        (r.path, r.findings, r.error) for r in expected
    ]


def test_workers_start_with_what_they_inherit_frozen(
    tmp_path: Path, mix: list[Path], monkeypatch: pytest.MonkeyPatch, gc_off: None
) -> None:
    """A worker's collections never walk the parent's objects (each would be copied)."""
    monkeypatch.chdir(tmp_path)
    files = [p for p in mix if "runaway" not in p.name and "missing" not in p.name][:3]
    # as in a `sensorkit validate` process, nothing is frozen yet (an in-process add or
    # render preview earlier in this test process froze what it left, as a command does)
    gc.unfreeze()
    inherited = len(gc.get_objects())

    def frozen(path: Path, options: Options | None = None) -> sensorkit.lint.engine.FileReport:
        return sensorkit.lint.engine.FileReport(path=path, error=str(gc.get_freeze_count()))

    monkeypatch.setattr(sensorkit.lint.engine, "validate_file", frozen)
    reports = validate_paths(files, Options(), jobs=2).files
    assert all(int(fr.error or 0) > inherited // 2 for fr in reports), [fr.error for fr in reports]
    assert gc.get_freeze_count() == 0  # and the parent's collector is as it was


def test_a_callers_own_freeze_is_left_as_it_is(
    tmp_path: Path, mix: list[Path], monkeypatch: pytest.MonkeyPatch, gc_off: None
) -> None:
    """A library caller that froze objects itself: validate_paths freezes nothing more."""
    monkeypatch.chdir(tmp_path)
    files = [p for p in mix if "runaway" not in p.name and "missing" not in p.name][:3]
    gc.unfreeze()
    gc.freeze()
    try:
        before = gc.get_freeze_count()
        keep = [[i] for i in range(1000)]  # tracked objects made after the caller's freeze
        reports = validate_paths(files, Options(), jobs=2).files
        assert len(reports) == len(files) and all(fr.error is None for fr in reports)
        assert gc.get_freeze_count() == before, len(keep)
    finally:
        gc.unfreeze()


def test_what_validating_raises_is_raised_as_with_jobs_1(
    tmp_path: Path, mix: list[Path], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A usage error met while validating (a bad --bridge file) stops the run alike."""
    monkeypatch.chdir(tmp_path)
    files = [p for p in mix if "runaway" not in p.name and "missing" not in p.name]
    real = sensorkit.lint.engine.validate_file

    def failing(path: Path, options: Options | None = None) -> sensorkit.lint.engine.FileReport:
        if path in (files[1], files[3]):
            raise UsageError(f"--bridge: cannot read it for {path}")
        return real(path, options)

    monkeypatch.setattr(sensorkit.lint.engine, "validate_file", failing)
    for jobs in (1, 2):
        with pytest.raises(UsageError, match=re.escape(f"for {files[1]}")):
            validate_paths(files, Options(), jobs=jobs)


def test_ctrl_c_stops_workers_and_xacro_children(tmp_path: Path) -> None:
    for i in range(4):
        (tmp_path / f"r{i}.urdf.xacro").write_text(
            f'<robot name="r" {XACRO_NS}><link name="${{10**10**10}}"/></robot>\n'
        )
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    # SIGINT's default action, as a terminal's foreground job has: a background job of a
    # non-interactive shell (`cmd &`) starts with SIGINT ignored (POSIX), pytest inherits
    # that, and so would sensorkit, which rightly keeps an inherited ignore. A handled
    # signal is reset to its default by exec.
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        proc = subprocess.Popen(
            [sys.executable, "-m", "sensorkit", "validate", "-j", "2", "--timeout", "60", "."],
            cwd=tmp_path,
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,  # its own process group, as a shell job has
        )
    finally:
        signal.signal(signal.SIGINT, old)
    try:
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and len(_group(proc.pid)) < 5:
            time.sleep(0.1)  # the parent, two workers and their two xacro children
        os.killpg(proc.pid, signal.SIGINT)  # what Ctrl-C in a terminal does
        _out, err = proc.communicate(timeout=20)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 130
    assert err.strip().splitlines()[-1] == "sensorkit: interrupted"
    time.sleep(0.5)
    assert not _descendants(proc.pid)


def test_jobs_import_no_numpy(tmp_path: Path, mix: list[Path]) -> None:
    """Whatever the parent imports before forking lengthens every --jobs run: validating
    needs no numpy, so neither the parent nor the workers import it."""
    files = [p for p in mix if "runaway" not in p.name and "missing" not in p.name]
    assert any(p.name.endswith(".xacro") for p in files)  # the parent warms xacro up
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    run = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "sensorkit", "validate", "-j", "2", *files],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert run.returncode in (0, 1), run.stderr
    imported = {line.rsplit("|", 1)[-1].strip() for line in run.stderr.splitlines() if "|" in line}
    assert "xacro" in imported  # the log is real
    assert not {m for m in imported if m.split(".")[0] == "numpy"}


def test_xacro_children_import_nothing_again(tmp_path: Path) -> None:
    """Each xacro expansion runs in a child forked for it: whatever the child imports is
    imported once a file. The process forking them imports it once instead."""
    robot = (
        f'<robot name="r" {XACRO_NS}><xacro:property name="a" value="1"/><link name="l"/></robot>\n'
    )
    for i in range(5):
        (tmp_path / f"r{i}.urdf.xacro").write_text(robot)

    def imports(n: int) -> list[str]:
        files = [f"r{i}.urdf.xacro" for i in range(n)]
        run = subprocess.run(
            [sys.executable, "-X", "importtime", "-m", "sensorkit", "validate", *files],
            cwd=tmp_path,
            env=dict(os.environ, PYTHONPATH=str(ROOT)),
            capture_output=True,
            text=True,
            timeout=120,
            check=False,
        )
        assert run.returncode in (0, 1), run.stderr
        return sorted(
            line.rsplit("|", 1)[-1].strip() for line in run.stderr.splitlines() if "|" in line
        )

    two, five = imports(2), imports(5)
    assert "xacro" in two  # the log is real
    assert five == two


def _group(pgid: int) -> list[str]:
    run = subprocess.run(
        ["ps", "-eo", "pid=,pgid=,ppid="], capture_output=True, text=True, check=True
    )
    rows = [line.split() for line in run.stdout.splitlines()]
    members = {r[0] for r in rows if r[1] == str(pgid)}
    grown = True
    while grown:  # and everything they started, in whatever group
        more = {r[0] for r in rows if r[2] in members} - members
        grown = bool(more)
        members |= more
    return sorted(members)


def _descendants(pid: int) -> list[str]:
    """Processes still running that sensorkit started (by their command line)."""
    run = subprocess.run(["ps", "-eo", "pid=,args="], capture_output=True, text=True, check=True)
    return [
        line
        for line in run.stdout.splitlines()
        if "sensorkit validate -j 2 --timeout 60" in line and str(pid) != line.split()[0]
    ]


# ----------------------------------------------------------------------------- folders


def _write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    robot = f'<robot name="r" {XACRO_NS}>\n  <link name="base_link"/>\n</robot>\n'
    plain = '<robot name="p">\n  <link name="base_link"/>\n</robot>\n'
    src = tmp_path / "src"
    _write(src / "b_pkg" / "urdf" / "robot.urdf.xacro", robot)
    _write(src / "b_pkg" / "urdf" / "plain.urdf", plain)
    _write(src / "a_pkg" / "urdf" / "a.xacro", robot)
    _write(
        src / "a_pkg" / "urdf" / "wheel.urdf.xacro",
        f'<robot {XACRO_NS}>\n  <!-- a macro file -->\n  <xacro:property name="r" value="1"/>\n'
        '  <xacro:arg name="x" default="1"/>\n  <xacro:include filename="other.xacro"/>\n'
        '  <xacro:macro name="wheel" params="n"><link name="${n}"/></xacro:macro>\n</robot>\n',
    )
    _write(
        src / "a_pkg" / "urdf" / "uses_macro.urdf.xacro",
        f'<robot name="u" {XACRO_NS}>\n  <xacro:include filename="wheel.urdf.xacro"/>\n'
        '  <xacro:wheel n="base_link"/>\n</robot>\n',
    )
    _write(src / "a_pkg" / "urdf" / "notes.txt", "not a robot\n")
    _write(src / "a_pkg" / "build" / "copied.urdf", plain)
    _write(src / ".hidden" / "h.urdf", plain)
    _write(src / "ignored_pkg" / "COLCON_IGNORE", "")
    _write(src / "ignored_pkg" / "urdf" / "i.urdf", plain)
    for out in ("build", "install", "log"):
        _write(tmp_path / out / "pkg" / "x.urdf", plain)
    return tmp_path


def test_folder_finds_top_level_descriptions_sorted(workspace: Path) -> None:
    found = find_robots(workspace)
    rel = [str(p.relative_to(workspace)) for p in found.files]
    assert rel == [
        "src/a_pkg/urdf/a.xacro",
        "src/a_pkg/urdf/uses_macro.urdf.xacro",
        "src/b_pkg/urdf/plain.urdf",
        "src/b_pkg/urdf/robot.urdf.xacro",
    ]
    assert [p.name for p in found.partials] == ["wheel.urdf.xacro"]


def test_partial_means_only_macros_properties_includes_args(tmp_path: Path) -> None:
    macro = _write(tmp_path / "m.xacro", f'<robot {XACRO_NS}><xacro:macro name="m"/></robot>')
    mixed = _write(
        tmp_path / "x.xacro", f'<robot {XACRO_NS}><xacro:macro name="m"/><link name="a"/></robot>'
    )
    call = _write(tmp_path / "c.xacro", f"<robot {XACRO_NS}><xacro:m/></robot>")
    broken = _write(tmp_path / "b.xacro", "<robot><xacro:macro")
    urdf = _write(tmp_path / "u.urdf", f'<robot {XACRO_NS}><xacro:macro name="m"/></robot>')
    assert is_partial(macro)
    assert not any(is_partial(p) for p in (mixed, call, broken, urdf))


def test_validate_a_folder(workspace: Path) -> None:
    run = sk("validate", "-f", "json", "src", cwd=workspace)
    assert run.returncode == 1, run.stderr  # massless single links: findings, not failure
    assert (
        run.stderr
        == "sensorkit: src: found 4 robot descriptions (skipped 1 macro-only xacro file)\n"
    )
    assert json.loads(run.stdout)["files"] == [
        "src/a_pkg/urdf/a.xacro",
        "src/a_pkg/urdf/uses_macro.urdf.xacro",
        "src/b_pkg/urdf/plain.urdf",
        "src/b_pkg/urdf/robot.urdf.xacro",
    ]
    two = sk("validate", "-f", "json", "-j", "2", "src", cwd=workspace)
    assert (two.stdout, two.stderr, two.returncode) == (run.stdout, run.stderr, 1)


def test_a_folder_with_no_robot_is_a_usage_error(workspace: Path) -> None:
    run = sk("validate", "src/ignored_pkg", "src/a_pkg/urdf/a.xacro", cwd=workspace)
    assert run.returncode == 2
    assert run.stdout == ""
    assert run.stderr.count("\n") == 1 and "no robot description" in run.stderr
    _write(
        workspace / "only_macros" / "m.xacro", f'<robot {XACRO_NS}><xacro:arg name="a"/></robot>'
    )
    run = sk("validate", "only_macros", cwd=workspace)
    assert run.returncode == 2 and run.stderr.count("\n") == 1
    assert "skipped 1 macro-only xacro file" in run.stderr


# ----------------------------------------------------------------------------- memory


@pytest.fixture
def gc_off() -> Iterator[None]:
    """As ``sensorkit validate`` runs: no automatic collection."""
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


def test_models_are_let_go_file_by_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, gc_off: None
) -> None:
    files = []
    for i in range(6):
        for p in sorted(ACCEPTANCE.glob("*.urdf"))[:2]:
            files.append(tmp_path / f"{i}_{p.name}")
            shutil.copy(p, files[-1])
    shutil.copytree(XACRO_ROBOT, tmp_path / "xrover")
    files.append(tmp_path / "xrover" / "robot.urdf.xacro")
    robots: list[weakref.ref[sensorkit.model.Robot]] = []
    sensors: list[weakref.ref[object]] = []  # a sensor and its plugins refer to each other
    alive_when_next_started: list[int] = []
    real = sensorkit.model.build_robot

    def tracked(doc: sensorkit.model.robot.Document) -> sensorkit.model.Robot:
        alive_when_next_started.append(sum(r() is not None for r in [*robots, *sensors]))
        robot = real(doc)
        robots.append(weakref.ref(robot))
        sensors.extend(weakref.ref(s) for s in robot.sensors)
        return robot

    monkeypatch.setattr(sensorkit.model, "build_robot", tracked)
    report = validate_paths(files, Options())
    assert len(robots) == len(files)
    assert alive_when_next_started == [0] * len(files)
    assert not [r for r in robots if r() is not None]
    assert sensors and not [r for r in sensors if r() is not None]  # nor the XML they hold
    assert [fr.sensor_count for fr in report.files][:2] == [1, 1]  # still said in the text output
