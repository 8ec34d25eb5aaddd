"""Issue 36, item 8 (cause 10): a cache that only its owner writes.

- An entry edited by someone else, with its digest recomputed, was served: entries now
  carry a MAC keyed by a random per-user key (``key``, mode 0600, in the cache folder).
- A cache folder pre-created by another user with mode 0777 was used as is: a folder not
  the user's own, or writable by the group or others, is not used, and the output says so
  once.

And item 10's last case: an environment variable read by ``$(optenv)`` that changes
between two cached runs gives the new value, not the cached one.
"""

from __future__ import annotations

import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from sensorkit.loading.cache import DiskCache
from sensorkit.loading.reads import digest

XMLNS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
ROBOT = (
    f'<robot name="r" {XMLNS}><link name="base_link"/><link name="l_${{\'a\' + \'b\'}}"/>'
    '<link name="opt_$(optenv SK_OPT_36 none)"/>'
    '<joint name="j" type="fixed"><parent link="base_link"/><child link="l_ab"/></joint>'
    '<joint name="k" type="fixed"><parent link="base_link"/><child link="opt_$(optenv SK_OPT_36 none)"/></joint>'
    "</robot>"
)
ROOT = Path(__file__).parents[1]


def _run(tmp_path: Path, *files: Path, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "sensorkit", "validate", "-f", "json", *map(str, files)],
        capture_output=True, text=True, check=False, timeout=120, cwd=tmp_path,
        env={**os.environ, "PYTHONPATH": str(ROOT), "XDG_CACHE_HOME": str(tmp_path / "home"), **(env or {})},
    )  # fmt: skip


def _robot(tmp_path: Path, name: str = "r.urdf.xacro") -> Path:
    path = tmp_path / "ws" / name
    path.parent.mkdir(exist_ok=True)
    path.write_text(ROBOT)
    return path


def _entries(tmp_path: Path) -> list[Path]:
    folder = tmp_path / "home" / "sensorkit" / "expansions"
    return sorted(folder.glob("*.json")) if folder.is_dir() else []


def test_an_entry_edited_with_its_digest_recomputed_is_not_served(tmp_path: Path) -> None:
    robot = _robot(tmp_path)
    first = _run(tmp_path, robot)
    (entry,) = _entries(tmp_path)
    head, _, payload = entry.read_bytes().partition(b"\n")
    forged = payload.replace(b"l_ab", b"l_forged")
    magic, fmt, _ = head.split(b" ")
    entry.write_bytes(b" ".join([magic, fmt, digest(forged).encode()]) + b"\n" + forged)
    again = _run(tmp_path, robot)
    assert "forged" not in again.stdout and again.stdout == first.stdout, again.stdout


def test_an_entry_its_owner_wrote_is_served(tmp_path: Path) -> None:
    """The near miss: the cache still works (an entry written through DiskCache, with
    the key, is believed), and its key file is private."""
    robot = _robot(tmp_path)
    _run(tmp_path, robot)
    store = DiskCache(tmp_path / "home" / "sensorkit")
    key = _entries(tmp_path)[0].stem
    entry = store.get(key)
    assert entry is not None
    entry.xml = entry.xml.replace('"l_ab"', '"l_mine"')
    store.put(key, entry)
    assert "l_mine" in _run(tmp_path, robot).stdout
    mode = stat.S_IMODE((tmp_path / "home" / "sensorkit" / "key").stat().st_mode)
    assert mode == 0o600, oct(mode)


@pytest.mark.parametrize("mode", [0o777, 0o775, 0o757])
def test_a_folder_others_may_write_is_not_used_and_said_once(tmp_path: Path, mode: int) -> None:
    folder = tmp_path / "home" / "sensorkit"
    folder.mkdir(parents=True)
    folder.chmod(mode)
    robots = [_robot(tmp_path, "a.urdf.xacro"), _robot(tmp_path, "b.urdf.xacro")]
    res = _run(tmp_path, *robots)
    assert res.returncode in (0, 1), res.stderr
    assert res.stderr.count("expansion cache not used") == 1, res.stderr
    assert "writable by the group or others" in res.stderr, res.stderr
    assert list(folder.iterdir()) == []  # nothing read from it, nothing written to it


def test_a_private_folder_is_used(tmp_path: Path) -> None:
    """The near miss: mode 0700 (and 0755: not writable by others) is used."""
    for mode in (0o700, 0o755):
        home = tmp_path / f"h{mode:o}"
        (home / "sensorkit").mkdir(parents=True)
        (home / "sensorkit").chmod(mode)
        store = DiskCache(home / "sensorkit")
        assert store.usable(create=True) and store.problem is None


def test_a_key_others_may_read_is_not_used(tmp_path: Path) -> None:
    robot = _robot(tmp_path)
    _run(tmp_path, robot)
    key = tmp_path / "home" / "sensorkit" / "key"
    key.chmod(0o644)
    res = _run(tmp_path, robot)
    assert res.stderr.count("expansion cache not used") == 1 and "key" in res.stderr, res.stderr


def test_an_optenv_variable_that_changes_between_cached_runs(tmp_path: Path) -> None:
    """Item 10: the cache records $(optenv) lookups; a changed value is a miss, each run
    gives its own value (in-process loads through the same disk cache, then the CLI)."""
    robot = _robot(tmp_path)
    assert "opt_first" in _xml_of(robot, "first", tmp_path)
    assert _entries(tmp_path)  # stored
    assert "opt_second" in _xml_of(robot, "second", tmp_path)
    assert "opt_none" in _xml_of(robot, None, tmp_path)
    assert "opt_first" in _xml_of(robot, "first", tmp_path)
    one = _run(tmp_path, robot, env={"SK_OPT_36": "first"})
    two = _run(tmp_path, robot, env={"SK_OPT_36": "second"})
    assert one.returncode in (0, 1) and two.returncode in (0, 1), two.stderr
    assert one.stdout == _run(tmp_path, robot, env={"SK_OPT_36": "first"}).stdout


def _xml_of(robot: Path, value: str | None, tmp_path: Path) -> str:
    """The expanded XML a cached load gives with SK_OPT_36 = ``value``."""
    from sensorkit.loading.document import load_description

    old = os.environ.pop("SK_OPT_36", None)
    if value is not None:
        os.environ["SK_OPT_36"] = value
    try:
        result = load_description(robot, cache=DiskCache(tmp_path / "home" / "sensorkit"))
        assert result.document is not None, result.findings
        from lxml import etree

        return etree.tostring(result.document.root, encoding="unicode")
    finally:
        os.environ.pop("SK_OPT_36", None)
        if old is not None:
            os.environ["SK_OPT_36"] = old
