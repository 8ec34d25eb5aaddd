"""The expansion cache (sensorkit.loading.cache) never gives a stale robot.

Each change to what an expansion read (an included file, a YAML read by load_yaml, an
environment variable, an arg, a new file matching an include glob, a package found
elsewhere, an overlay) gives the robot a fresh expansion gives; an unchanged robot is not
expanded again; a broken cache is a miss; --untrusted never touches it; and the CLI
prints the same bytes with the cache off, cold and warm.
"""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml
from conftest import REALWORLD, corpus_package_paths, needs_corpus, run_cli
from lxml import etree

from sensorkit.loading import cache as cache_mod
from sensorkit.loading import xacro_expand
from sensorkit.loading.cache import FORMAT, DiskCache, ExpansionCache, MemoryCache
from sensorkit.loading.document import load_description
from sensorkit.loading.packages import PackageResolver

ROOT = Path(__file__).resolve().parent.parent
XMLNS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

TOP = f"""<?xml version="1.0"?>
<robot name="r" {XMLNS}>
  <xacro:arg name="width" default="1"/>
  <xacro:include filename="parts/body.xacro"/>
  <xacro:include filename="$(find extpkg)/urdf/ext.xacro"/>
  <xacro:include filename="plugins/*.xacro"/>
  <xacro:property name="cfg" value="${{xacro.load_yaml('config.yaml')}}"/>
  <link name="base_link">
    <visual><geometry><box size="$(arg width) ${{cfg['depth']}} 1"/></geometry></visual>
  </link>
  <link name="opt_$(optenv SK_TEST_OPT none)"/>
  <link name="req_$(env SK_TEST_REQ)"/>
  <xacro:body/>
  <xacro:ext/>
</robot>
"""
BODY = f"""<robot {XMLNS}>
  <xacro:macro name="body"><link name="body_v1"/></xacro:macro>
</robot>
"""
EXT = f"""<robot {XMLNS}>
  <xacro:macro name="ext">
    <link name="ext"><visual><geometry><mesh filename="file://$(find extpkg)/m.stl"/></geometry></visual></link>
  </xacro:macro>
</robot>
"""


def _plugin(name: str) -> str:
    return f'<robot {XMLNS}><link name="plugin_{name}"/></robot>\n'


@pytest.fixture
def robot(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A xacro robot reading each kind of input the cache must check."""
    top = tmp_path / "robot" / "top.urdf.xacro"
    (top.parent / "parts").mkdir(parents=True)
    (top.parent / "plugins").mkdir()
    top.write_text(TOP)
    (top.parent / "parts" / "body.xacro").write_text(BODY)
    (top.parent / "plugins" / "a.xacro").write_text(_plugin("a"))
    (top.parent / "config.yaml").write_text("depth: 0.5\n")
    _package(tmp_path / "second" / "extpkg")
    (tmp_path / "first").mkdir()
    monkeypatch.setenv("SK_TEST_REQ", "one")
    monkeypatch.delenv("SK_TEST_OPT", raising=False)
    return top


def _package(folder: Path) -> None:
    (folder / "urdf").mkdir(parents=True)
    (folder / "package.xml").write_text("<package><name>extpkg</name></package>\n")
    (folder / "urdf" / "ext.xacro").write_text(EXT)


def _resolver(top: Path) -> PackageResolver:
    base = top.parent.parent
    return PackageResolver.from_options([str(base / "first"), str(base / "second")])


@pytest.fixture
def expansions(monkeypatch: pytest.MonkeyPatch) -> list[Path]:
    """Every xacro expansion made, by path (a hit makes none)."""
    made: list[Path] = []
    real = xacro_expand.expand

    def counting(path: Path, *a: Any, **kw: Any) -> Any:
        made.append(path)
        return real(path, *a, **kw)

    monkeypatch.setattr(xacro_expand, "expand", counting)
    return made


def _xml(top: Path, cache: ExpansionCache | None, **kw: Any) -> str:
    result = load_description(top, resolver=_resolver(top), cache=cache, **kw)
    assert result.document is not None, result.findings
    return etree.tostring(result.document.root, encoding="unicode")


@pytest.fixture(params=["memory", "disk"])
def store(request: pytest.FixtureRequest, tmp_path: Path) -> ExpansionCache:
    return MemoryCache() if request.param == "memory" else DiskCache(tmp_path / "cache")


@pytest.fixture
def fresh(robot: Path) -> Callable[..., str]:
    """The robot as loaded with no cache at all (what every lookup must give)."""
    return lambda **kw: _xml(robot, None, **kw)


def _hit_then(
    robot: Path, store: ExpansionCache, expansions: list[Path], fresh: Callable[..., str], **kw: Any
) -> Iterator[str]:
    """Load twice now (the second a hit), then once per ``next``, each load checked
    against a cache-less one."""
    first = _xml(robot, store, **kw)
    assert len(expansions) == 1
    assert _xml(robot, store, **kw) == first  # a hit: no expansion
    assert len(expansions) == 1

    def later() -> Iterator[str]:
        while True:
            got = _xml(robot, store, **kw)
            assert got == fresh(**kw)
            yield got

    return later()


def test_an_unchanged_robot_is_not_expanded_again(
    robot: Path, store: ExpansionCache, expansions: list[Path]
) -> None:
    first = _xml(robot, store)
    for _ in range(3):
        assert _xml(robot, store) == first
    assert expansions == [robot]
    assert 'name="plugin_a"' in first and 'name="body_v1"' in first


def test_editing_an_included_file(
    robot: Path, store: ExpansionCache, expansions: list[Path], fresh: Callable[..., str]
) -> None:
    loads = _hit_then(robot, store, expansions, fresh)
    body = robot.parent / "parts" / "body.xacro"
    for n in range(2, 5):
        body.write_text(BODY.replace("body_v1", f"body_v{n}"))
        assert f'name="body_v{n}"' in next(loads)


def test_editing_a_yaml_read_by_load_yaml(
    robot: Path, store: ExpansionCache, expansions: list[Path], fresh: Callable[..., str]
) -> None:
    loads = _hit_then(robot, store, expansions, fresh)
    for depth in ("0.25", "0.75", "0.5"):
        (robot.parent / "config.yaml").write_text(f"depth: {depth}\n")
        assert f'size="1 {depth} 1"' in next(loads)


def test_changing_a_variable_read_by_optenv(
    robot: Path,
    store: ExpansionCache,
    expansions: list[Path],
    fresh: Callable[..., str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    loads = _hit_then(robot, store, expansions, fresh)
    for value in ("a", "b", None, "a"):
        if value is None:
            monkeypatch.delenv("SK_TEST_OPT")
        else:
            monkeypatch.setenv("SK_TEST_OPT", value)
        assert f'name="opt_{value or "none"}"' in next(loads)


def test_changing_a_variable_read_by_env(
    robot: Path,
    store: ExpansionCache,
    expansions: list[Path],
    fresh: Callable[..., str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    loads = _hit_then(robot, store, expansions, fresh)
    for value in ("two", "three", "one"):
        monkeypatch.setenv("SK_TEST_REQ", value)
        assert f'name="req_{value}"' in next(loads)


def test_changing_an_arg(
    robot: Path, store: ExpansionCache, expansions: list[Path], fresh: Callable[..., str]
) -> None:
    seen = {_xml(robot, store, args={"width": w}) for w in ("2", "3", "2", "1", "3")}
    assert len(seen) == 3
    assert len(expansions) == 3  # one per distinct arg; the repeats were hits
    for w in ("2", "3", "1"):
        assert f'size="{w} 0.5 1"' in _xml(robot, store, args={"width": w})
        assert _xml(robot, store, args={"width": w}) == fresh(args={"width": w})


def test_a_new_file_matching_an_include_glob(
    robot: Path, store: ExpansionCache, expansions: list[Path], fresh: Callable[..., str]
) -> None:
    loads = _hit_then(robot, store, expansions, fresh)
    for name in ("b", "c"):
        (robot.parent / "plugins" / f"{name}.xacro").write_text(_plugin(name))
        assert f'name="plugin_{name}"' in next(loads)
    (robot.parent / "plugins" / "b.xacro").unlink()
    assert 'name="plugin_b"' not in next(loads)


def test_a_package_found_elsewhere(
    robot: Path, store: ExpansionCache, expansions: list[Path], fresh: Callable[..., str]
) -> None:
    """The same package, byte for byte, now found first in another folder: only
    re-resolving $(find) tells (the files the first expansion read are all still there)."""
    loads = _hit_then(robot, store, expansions, fresh)
    first = robot.parent.parent / "first" / "extpkg"
    _package(first)
    assert f"file://{first}/m.stl" in next(loads)
    shutil.rmtree(first)
    assert f"file://{robot.parent.parent / 'second' / 'extpkg'}/m.stl" in next(loads)


def test_an_overlay_differing_from_the_disk(
    robot: Path, store: ExpansionCache, expansions: list[Path], fresh: Callable[..., str]
) -> None:
    loads = _hit_then(robot, store, expansions, fresh)
    body = str(robot.parent / "parts" / "body.xacro")
    config = str(robot.parent / "config.yaml")
    edited = {body: BODY.replace("body_v1", "body_unsaved").encode()}
    got = _xml(robot, store, overlay=edited)
    assert 'name="body_unsaved"' in got and got == fresh(overlay=edited)
    assert 'name="body_v1"' in next(loads)  # the disk again
    yaml_edit = {config: b"depth: 0.125\n"}  # load_yaml reads the overlay too
    got = _xml(robot, store, overlay=yaml_edit)
    assert 'size="1 0.125 1"' in got and got == fresh(overlay=yaml_edit)
    assert 'size="1 0.5 1"' in next(loads)
    same = {body: BODY.encode()}  # an overlay equal to the disk: a hit
    count = len(expansions)
    assert _xml(robot, store, overlay=same) == next(loads)
    assert len(expansions) == count + 1  # next(loads) compared with one fresh expansion


@pytest.mark.parametrize(
    "expr",
    ["${hash('a')}", "${python.set(['a', 'b'])}", "${''.__class__}", "$(eval str(hash('a')))"],
)
def test_what_cannot_be_replayed_is_not_stored(tmp_path: Path, expr: str) -> None:
    top = tmp_path / "r.urdf.xacro"
    top.write_text(f'<robot name="r" {XMLNS}><link name="l"><x v="{expr}"/></link></robot>')
    store = MemoryCache()
    load_description(top, cache=store)
    assert not store.entries
    top.write_text(f'<robot name="r" {XMLNS}><link name="l"><x v="${{1+1}}"/></link></robot>')
    load_description(top, cache=store)
    assert len(store.entries) == 1  # the same robot without it is stored


def test_a_failed_expansion_is_not_stored(robot: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("SK_TEST_REQ")
    store = MemoryCache()
    result = load_description(robot, resolver=_resolver(robot), cache=store)
    assert result.document is None and result.findings[0].rule == "SK102"
    assert not store.entries


# --- a broken cache is a miss ----------------------------------------------------------


def _entry_file(folder: Path) -> Path:
    (entry,) = (folder / "expansions").glob("*.json")
    return entry


@pytest.mark.parametrize(
    "damage",
    [
        lambda b: b[: len(b) // 2],  # truncated
        lambda b: b"",
        lambda b: b[:-20] + bytes(c ^ 1 for c in b[-20:]),  # corrupt payload
        lambda b: b.replace(b"sensorkit-expansion %d " % FORMAT, b"sensorkit-expansion 99 ", 1),
        lambda b: b"\x00\xff garbage\n{",
    ],
    ids=["truncated", "empty", "corrupt", "other-format", "garbage"],
)
def test_a_damaged_entry_is_a_miss(
    robot: Path, tmp_path: Path, expansions: list[Path], damage: Callable[[bytes], bytes]
) -> None:
    store = DiskCache(tmp_path / "cache")
    first = _xml(robot, store)
    entry = _entry_file(tmp_path / "cache")
    entry.write_bytes(damage(entry.read_bytes()))
    assert _xml(robot, store) == first
    assert len(expansions) == 2  # expanded again
    assert _xml(robot, store) == first and len(expansions) == 2  # and stored whole again


def test_a_forged_entry_that_holds_is_believed_so_the_damage_tests_can_fail(
    robot: Path, tmp_path: Path, expansions: list[Path]
) -> None:
    store = DiskCache(tmp_path / "cache")
    _xml(robot, store)
    key = next(iter(k.stem for k in (tmp_path / "cache" / "expansions").glob("*.json")))
    entry = store.get(key)
    assert entry is not None
    entry.xml = entry.xml.replace("body_v1", "forged")
    store.put(key, entry)
    assert 'name="forged"' in _xml(robot, store) and len(expansions) == 1


def test_an_unwritable_cache_is_ignored(
    robot: Path, tmp_path: Path, fresh: Callable[..., str]
) -> None:
    blocked = tmp_path / "blocked"
    blocked.mkdir()
    (blocked / "expansions").write_text("a file where the folder would be\n")
    assert _xml(robot, DiskCache(blocked)) == fresh()
    not_a_folder = tmp_path / "file"
    not_a_folder.write_text("")
    assert _xml(robot, DiskCache(not_a_folder)) == fresh()


def test_an_unreadable_entry_is_a_miss(robot: Path, tmp_path: Path, expansions: list[Path]) -> None:
    store = DiskCache(tmp_path / "cache")
    first = _xml(robot, store)
    entry = _entry_file(tmp_path / "cache")
    entry.unlink()
    entry.mkdir()  # reading it fails (root reads any file, but no folder as a file)
    assert _xml(robot, store) == first and len(expansions) == 2


def test_the_disk_store_stays_under_its_bound(
    robot: Path, tmp_path: Path, expansions: list[Path]
) -> None:
    store = DiskCache(tmp_path / "cache")
    _xml(robot, store)
    size = _entry_file(tmp_path / "cache").stat().st_size
    store.limit = int(4.5 * size)  # room for four entries
    for w in range(10):
        _xml(robot, store, args={"width": str(w)})
        files = list(store.folder.iterdir())
        assert sum(f.stat().st_size for f in files) <= store.limit
    assert len(files) == 4 and not [f for f in files if f.name.endswith(".tmp")]
    count = len(expansions)
    _xml(robot, store, args={"width": "9"})  # the most recent are kept
    _xml(robot, store, args={"width": "6"})
    assert len(expansions) == count
    _xml(robot, store, args={"width": "0"})  # the oldest went
    assert len(expansions) == count + 1


def test_the_default_folder_follows_xdg_cache_home(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "x"))
    assert cache_mod.default_folder() == tmp_path / "x" / "sensorkit"
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/ignored")
    assert cache_mod.default_folder() == Path.home() / ".cache" / "sensorkit"


# --- the CLI -----------------------------------------------------------------------------


def _cli_robots() -> list[tuple[str, list[str]]]:
    ws = ROOT / "tests" / "robots" / "workspace" / "src"
    out = [
        (str(ws / "rover_description" / "urdf" / "rover.urdf.xacro"), []),
        (str(ROOT / "tests" / "robots" / "acceptance" / "sk502_bad.urdf"), []),
    ]
    listing = yaml.safe_load((ROOT / "tests" / "realworld" / "robots.yaml").read_text())
    wanted = (
        "turtlebot__turtlebot4/turtlebot4_description/urdf/standard/turtlebot4.urdf.xacro",
        "PR2__pr2_common/pr2_description/robots/pr2.urdf.xacro",
        "husarion__rosbot_xl_ros/rosbot_xl_description/urdf/rosbot_xl.urdf.xacro",
    )
    for entry in listing:
        if entry["file"] in wanted and not entry.get("pending"):
            wanted = tuple(w for w in wanted if w != entry["file"])
            args = [f"--arg={k}:={v}" for k, v in (entry.get("args") or {}).items()]
            paths = [f"--package-path={p}" for p in corpus_package_paths()]
            out.append((str(REALWORLD / entry["file"]), args + paths))
    return out


def _validate(cache_home: Path, file: str, extra: list[str], *flags: str) -> tuple[str, str, int]:
    os.environ["XDG_CACHE_HOME"] = str(cache_home)
    done = run_cli("validate", file, *extra, *flags)
    assert done.returncode in (0, 1), done.stderr
    return done.stdout, done.stderr, done.returncode


@needs_corpus
@pytest.mark.parametrize("index", range(5))
def test_the_cli_prints_the_same_with_the_cache_off_cold_and_warm(
    tmp_path: Path, index: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    robots = _cli_robots()
    if index >= len(robots):
        pytest.skip("fewer robots in the corpus")
    file, extra = robots[index]
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))  # restored after the test
    home = tmp_path / "home"
    for fmt in ("json", "text"):
        off = _validate(home, file, extra, "-f", fmt, "--no-cache")
        assert not (home / "sensorkit").exists()  # --no-cache writes nothing either
        cold = _validate(home, file, extra, "-f", fmt)
        warm = _validate(home, file, extra, "-f", fmt)
        assert off == cold == warm
        shutil.rmtree(home, ignore_errors=True)
    if file.endswith(".xacro"):
        _validate(home, file, extra)
        assert list((home / "sensorkit" / "expansions").glob("*.json"))


def test_the_cli_uses_the_cache_it_was_given(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A forged entry is printed by a trusted run (the cache is read), never by
    --untrusted, which neither reads nor writes the cache folder."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "home"))
    top = tmp_path / "ws" / "r.urdf.xacro"
    top.parent.mkdir()
    top.write_text(
        f'<robot name="r" {XMLNS}><link name="base_link"/><link name="${{\'a\' + \'b\'}}"/>'
        '<joint name="j" type="fixed"><parent link="base_link"/><child link="ab"/></joint></robot>'
    )
    base = ["validate", str(top), "-f", "json"]
    untrusted = run_cli(*base, "--untrusted")
    assert untrusted.returncode in (0, 1), untrusted.stderr
    assert not (tmp_path / "home" / "sensorkit").exists()  # wrote nothing
    trusted = run_cli(*base)
    # the same report, but for the readable area --untrusted names (issue 36)
    got, want = json.loads(untrusted.stdout), json.loads(trusted.stdout)
    assert got.pop("readable") and want.pop("readable") == {}
    assert got == want
    store = DiskCache(tmp_path / "home" / "sensorkit")
    (key,) = [f.stem for f in store.folder.glob("*.json")]
    entry = store.get(key)
    assert entry is not None
    entry.xml = entry.xml.replace('"ab"', '"forged"')
    store.put(key, entry)
    assert "forged" in run_cli(*base).stdout  # the trusted run believes the cache
    before = sorted((f.name, f.stat().st_mtime_ns) for f in store.folder.iterdir())
    again = run_cli(*base, "--untrusted")
    assert "forged" not in again.stdout and again.stdout == untrusted.stdout
    assert sorted((f.name, f.stat().st_mtime_ns) for f in store.folder.iterdir()) == before
    assert "forged" not in run_cli(*base, "--no-cache").stdout
