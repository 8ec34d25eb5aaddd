"""Issue 10: fault injection on every write sensorkit makes to a user's file.

- kill -9 at each step of the write (temp file created, data written, fsync, chmod,
  chown, rename, folder fsync): the file is the old bytes or the whole new file, and the
  temporary file a killed run leaves is removed by the next edit;
- the medium fails (file too large by RLIMIT_FSIZE, a real kernel error; disk full and
  I/O errors injected at fsync): exit 2, one line naming the user's file, byte-identical,
  no temporary file left;
- read-only folder, foreign owner: refused or kept.

The steps are counted, not assumed: a profiling hook in the child process counts the
C-level calls ``sensorkit.base.atomic`` makes and SIGKILLs the process at call K.
"""

from __future__ import annotations

import errno
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from sensorkit.base.errors import WriteFailed
from sensorkit.edit import AddRequest, add_sensor

ROBOTS = Path(__file__).resolve().parent / "edit_robots"

CHILD = textwrap.dedent(
    """
    import os, signal, sys
    from pathlib import Path
    from sensorkit.edit import AddRequest, add_sensor

    path, name, kill_at = Path(sys.argv[1]), sys.argv[2], int(sys.argv[3])
    STEPS = {"write", "flush", "fsync", "chmod", "chown", "replace", "mkstemp", "open", "close"}
    count = 0

    def hook(frame, event, arg):
        global count
        if event not in ("c_call", "call"):
            return
        fname = arg.__name__ if event == "c_call" else frame.f_code.co_name
        caller = frame if event == "c_call" else frame.f_back
        if caller is None or not caller.f_code.co_filename.endswith("atomic.py"):
            return
        if fname in STEPS:
            count += 1
            if count == kill_at:
                os.kill(os.getpid(), signal.SIGKILL)

    sys.setprofile(hook)
    add_sensor(AddRequest(path=path, kind="camera", name=name, parent="base_link", xyz=(0.2, 0.0, 0.05)))
    sys.setprofile(None)
    print("steps", count)
    """
)


def _child(path: Path, name: str, kill_at: int) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", CHILD, str(path), name, str(kill_at)],
        capture_output=True, text=True, timeout=120, check=False,
    )  # fmt: skip


def _temps(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".sensorkit-tmp"))


def _place(robot: str, folder: Path) -> Path:
    """A fresh copy of the robot (and the files it includes) in ``folder``."""
    src = ROBOTS / robot
    if src.parent != ROBOTS:
        shutil.copytree(src.parent, folder)
    else:
        folder.mkdir()
        shutil.copyfile(src, folder / src.name)
    return folder / src.name


@pytest.mark.parametrize("robot", ["rover.urdf", "xacro_robot/robot.urdf.xacro"])
def test_kill_9_at_every_write_step_loses_nothing(tmp_path: Path, robot: str) -> None:
    original = (ROBOTS / robot).read_bytes()
    # The whole new file, from a run that is not killed.
    clean = _place(robot, tmp_path / "clean")
    res = _child(clean, "cam_k", 0)
    assert res.returncode == 0, res.stderr
    steps = int(res.stdout.split()[-1])
    assert steps >= 5, res.stdout  # mkstemp, write, fsync, chmod, replace at least
    expected = clean.read_bytes()
    assert expected != original

    outcomes = set()
    for k in range(1, steps + 1):
        path = _place(robot, tmp_path / f"k{k}")
        folder = path.parent
        res = _child(path, "cam_k", k)
        assert res.returncode == -9, (k, res.returncode, res.stderr)
        now = path.read_bytes()
        assert now in (original, expected), f"step {k}: half-written file"
        outcomes.add("old" if now == original else "new")
        # The next edit cleans what the killed one left, and lands on top of it.
        res = _child(path, "cam_next", 0)
        assert res.returncode == 0, (k, res.stderr)
        assert _temps(folder) == [], (k, _temps(folder))
        text = path.read_text()
        assert 'name="cam_next"' in text
    assert outcomes == {"old", "new"}  # the kill landed both before and after the rename


def _copy(tmp_path: Path) -> Path:
    path = tmp_path / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", path)
    return path


def test_file_too_large_is_a_clean_refusal(tmp_path: Path) -> None:
    # RLIMIT_FSIZE makes the kernel fail the write with EFBIG, as a full disk fails it.
    path = _copy(tmp_path)
    before = path.read_bytes()
    code = textwrap.dedent(
        f"""
        import resource, signal, sys
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, ({len(before)}, {len(before)}))
        from sensorkit.cli import main
        sys.argv = ["sensorkit", "add-camera", {str(path)!r}, "--name", "cam", "--parent", "base_link"]
        main()
        """
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=False)
    assert res.returncode == 2, res.stdout + res.stderr
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and str(path) in lines[0] and "File too large" in lines[0], res.stderr
    assert "sensorkit-tmp" not in res.stderr
    assert path.read_bytes() == before and _temps(tmp_path) == []
    # Near miss: without the limit the same command writes.
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", "add-camera", str(path), "--name", "cam", "--parent", "base_link"],
        capture_output=True, text=True, timeout=120, check=False,
    )  # fmt: skip
    assert res.returncode == 0 and path.read_bytes() != before, res.stderr


@pytest.mark.parametrize("err", [errno.ENOSPC, errno.EIO, errno.EDQUOT])
def test_disk_full_and_io_errors_leave_the_file_unchanged(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, err: int
) -> None:
    from sensorkit.base import atomic

    path = _copy(tmp_path)
    before = path.read_bytes()

    def failing_fsync(fd: int) -> None:
        raise OSError(err, os.strerror(err))

    monkeypatch.setattr(atomic.os, "fsync", failing_fsync)
    with pytest.raises(WriteFailed) as info:
        add_sensor(AddRequest(path=path, kind="camera", name="cam", parent="base_link", xyz=(0.2, 0, 0.05)))
    assert str(path) in str(info.value) and os.strerror(err) in str(info.value)
    assert "sensorkit-tmp" not in str(info.value)
    assert path.read_bytes() == before and _temps(tmp_path) == []


def test_read_only_folder_is_refused_byte_identical(tmp_path: Path) -> None:
    folder = tmp_path / "ro"
    folder.mkdir()
    path = folder / "rover.urdf"
    shutil.copyfile(ROBOTS / "rover.urdf", path)
    before = path.read_bytes()
    folder.chmod(0o555)
    try:
        res = subprocess.run(
            [sys.executable, "-m", "sensorkit", "add-camera", str(path), "--name", "cam", "--parent", "base_link"],
            capture_output=True, text=True, timeout=120, check=False,
        )  # fmt: skip
        assert res.returncode == 2 and "read-only" in res.stderr and str(folder) in res.stderr, res.stderr
        assert len(res.stderr.strip().splitlines()) == 1
        assert path.read_bytes() == before and sorted(p.name for p in folder.iterdir()) == ["rover.urdf"]
    finally:
        folder.chmod(0o755)
    # Near miss: the same folder writable.
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", "add-camera", str(path), "--name", "cam", "--parent", "base_link"],
        capture_output=True, text=True, timeout=120, check=False,
    )  # fmt: skip
    assert res.returncode == 0, res.stderr


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="chown needs root")
def test_foreign_owner_is_kept_when_root_edits(tmp_path: Path) -> None:
    path = _copy(tmp_path)
    os.chown(path, 4242, 4343)
    path.chmod(0o640)
    add_sensor(AddRequest(path=path, kind="camera", name="cam", parent="base_link", xyz=(0.2, 0, 0.05)))
    st = path.stat()
    assert (st.st_uid, st.st_gid, st.st_mode & 0o777) == (4242, 4343, 0o640)
    assert 'name="cam"' in path.read_text()
