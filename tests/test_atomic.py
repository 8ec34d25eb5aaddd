"""Atomic writes and staged folders: nothing half-written, nothing precious replaced."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from sensorkit.base.atomic import check_replaceable, staged_folder, write_bytes, write_text
from sensorkit.base.errors import UsageError, WriteFailed


def test_write_text_keeps_mode_and_leaves_no_temp(tmp_path: Path) -> None:
    target = tmp_path / "camera_info.yaml"
    write_text(target, "a: 1\n")
    assert target.read_text(encoding="utf-8") == "a: 1\n"
    os.chmod(target, 0o640)
    write_text(target, "a: 2\r\n", fsync=False)
    assert target.read_bytes() == b"a: 2\r\n"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640
    assert sorted(p.name for p in tmp_path.iterdir()) == ["camera_info.yaml"]


def test_write_leaves_nothing_on_failure(tmp_path: Path) -> None:
    with pytest.raises(WriteFailed, match=r"missing/x\.yaml: cannot write in its folder .*No such file"):
        write_text(tmp_path / "missing" / "x.yaml", "a: 1\n")
    target = tmp_path / "x.yaml"
    target.write_text("old\n", encoding="utf-8")
    with pytest.raises(UnicodeEncodeError):
        write_text(target, "\udcff")
    assert target.read_text(encoding="utf-8") == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.yaml"]


def test_write_bytes_follows_a_symlink(tmp_path: Path) -> None:
    real = tmp_path / "robot.urdf"
    real.write_bytes(b"old")
    link = tmp_path / "link.urdf"
    link.symlink_to(real)
    write_bytes(link, b"new")
    assert link.is_symlink() and real.read_bytes() == b"new"


def test_staged_folder_publishes_whole_or_not_at_all(tmp_path: Path) -> None:
    out = tmp_path / "out"
    with staged_folder(out) as temp:
        (temp / "a.txt").write_text("1")
    assert (out / "a.txt").read_text() == "1"
    with pytest.raises(RuntimeError), staged_folder(out) as temp:
        (temp / "b.txt").write_text("2")
        raise RuntimeError
    assert sorted(p.name for p in out.iterdir()) == ["a.txt"]
    with staged_folder(out) as temp:
        (temp / "c.txt").write_text("3")
    assert sorted(p.name for p in out.iterdir()) == ["c.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]  # no staging left behind
    with staged_folder(tmp_path / "dry", publish=False) as temp:
        (temp / "d.txt").write_text("4")
    assert not (tmp_path / "dry").exists()


def test_check_replaceable(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "file").write_text("x")
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "robot.yaml").write_text("x")
    check_replaceable(tmp_path / "new", force=False)
    for out, force, inputs in (
        (tmp_path / "file", True, []),
        (tmp_path / "full", False, []),
        (tmp_path / "full", True, [tmp_path / "full" / "robot.yaml"]),
        (tmp_path, True, []),
        (tmp_path.parent, True, []),
    ):
        with pytest.raises(UsageError):
            check_replaceable(out, force=force, inputs=inputs)
    check_replaceable(tmp_path / "full", force=True)
