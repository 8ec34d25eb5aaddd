"""Issue 36, item 5 (cause 7): the launch reader parses each file once per run and
counts include edges as well as files.

Nine files, each including the next twelve times, hold no cycle and only nine files, but
12**8 paths: the reader parsed a file again on every path to it and never finished.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from sensorkit.loading.launch import reader
from sensorkit.loading.launch.reader import read_launch
from sensorkit.loading.launch.spec import MAX_INCLUDE_EDGES

PKG = "<package format='3'><name>c_sim</name></package>\n"
NODE = '<node pkg="robot_state_publisher" exec="robot_state_publisher"/>'


def _diamond(tmp: Path, files: int, fanout: int) -> Path:
    """``files`` launch files, each including the next ``fanout`` times; the last starts a node."""
    launch = tmp / "c_sim" / "launch"
    launch.mkdir(parents=True)
    (tmp / "c_sim" / "package.xml").write_text(PKG)
    for i in range(files):
        body = (
            NODE
            if i == files - 1
            else f'<include file="$(find-pkg-share c_sim)/launch/l{i + 1}.launch.xml"/>' * fanout
        )
        (launch / f"l{i}.launch.xml").write_text(f"<launch>{body}</launch>\n")
    return launch / "l0.launch.xml"


def test_each_file_is_parsed_once(tmp_path: Path) -> None:
    """5 files, 3 includes each: 81 paths to the last file, one parse of each file."""
    top = _diamond(tmp_path, 5, 3)
    parsed: list[str] = []
    orig = reader._parse

    def count(reading: object, real: Path, *a: object) -> object:
        parsed.append(real.name)
        return orig(reading, real, *a)  # type: ignore[arg-type]

    mp = pytest.MonkeyPatch()
    mp.setattr(reader, "_parse", count)
    try:
        facts = read_launch([top], roots=[tmp_path])
    finally:
        mp.undo()
    assert sorted(parsed) == [f"l{i}.launch.xml" for i in range(5)], parsed
    assert not facts.problems, facts.problems  # 3+9+27+81 = 120 edges: under the bound
    assert len(facts.files) == 5


def test_an_include_diamond_stops_at_the_edge_bound(tmp_path: Path) -> None:
    """The issue's 9 files x 12 includes, in a fresh process (before: no end)."""
    top = _diamond(tmp_path, 9, 12)
    code = (
        "import sys\nfrom pathlib import Path\n"
        "from sensorkit.loading.launch.reader import read_launch\n"
        "f = read_launch([Path(sys.argv[1])], roots=[Path(sys.argv[2])])\n"
        "print(len(f.files), f.bridge_unknown, [p.message for p in f.problems])\n"
    )
    res = subprocess.run(
        [sys.executable, "-c", code, str(top), str(tmp_path)],
        capture_output=True, text=True, check=False, timeout=120,
        env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[1])},
    )  # fmt: skip
    assert res.returncode == 0, res.stderr[-2000:]
    assert f"more than {MAX_INCLUDE_EDGES} launch includes" in res.stdout, res.stdout
    assert res.stdout.startswith("9 True"), res.stdout  # every file seen; what is unread is unknown


def test_a_named_pipe_launch_file_is_a_problem_not_a_hang(tmp_path: Path) -> None:
    """A launch file given (--launch) that is a FIFO blocked the reader for ever (stat
    says 0 bytes); now it is a problem naming what it is, at once."""
    launch = tmp_path / "c_sim" / "launch"
    launch.mkdir(parents=True)
    (tmp_path / "c_sim" / "package.xml").write_text(PKG)
    os.mkfifo(launch / "a.launch.xml")
    code = (
        "import sys\nfrom pathlib import Path\n"
        "from sensorkit.loading.launch.reader import read_launch\n"
        "f = read_launch([Path(sys.argv[1])], roots=[Path(sys.argv[2])])\n"
        "print(f.bridge_unknown, [p.message for p in f.problems])\n"
    )
    res = subprocess.run(
        [sys.executable, "-c", code, str(launch / "a.launch.xml"), str(tmp_path)],
        capture_output=True, text=True, check=False, timeout=60,
        env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[1])},
    )  # fmt: skip
    assert res.returncode == 0, res.stderr[-2000:]
    assert "a named pipe, not a regular file" in res.stdout and res.stdout.startswith("True"), res.stdout
