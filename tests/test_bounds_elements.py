"""Issue 36, item 9: a bound a trusted user can raise.

A legitimate 70,000-element generated URDF (a warehouse of shelves) was refused by the
60,000-element bound, and nothing raised it. Plain URDF validation grows about 20 us and
1.8 KiB per element: the trusted default is 500,000, ``--max-elements`` (and the settings
key ``max-elements``) moves it, and --untrusted keeps 60,000. Run as test_bounds.py runs
(a protective memory limit, the peak RSS of the process tree measured); the figures of
each run are printed (``-s``).
"""

from __future__ import annotations

from pathlib import Path

from test_bounds import GB, sensorkit

from sensorkit.loading.document import MAX_ELEMENTS, MAX_ELEMENTS_UNTRUSTED

INERTIAL = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
PER_SHELF = 9  # link, visual, origin, geometry, box; joint, parent, child, origin


def warehouse(path: Path, elements: int) -> int:
    """A URDF of about ``elements`` elements: shelves fixed to the floor. Its count."""
    shelves = max(1, (elements - 7) // PER_SHELF)
    parts = [f'<robot name="warehouse"><link name="floor">{INERTIAL}</link>']
    for i in range(shelves):
        x, y = i % 200, i // 200
        parts.append(
            f'<link name="s{i}"><visual><origin xyz="0 0 1"/><geometry><box size="1 0.5 2"/>'
            f'</geometry></visual></link><joint name="j{i}" type="fixed"><parent link="floor"/>'
            f'<child link="s{i}"/><origin xyz="{x} {y} 0"/></joint>'
        )
    parts.append("</robot>\n")
    path.write_text("".join(parts))
    return 7 + shelves * PER_SHELF


def _figures(what: str, run: object) -> None:
    print(f"{what}: {getattr(run, 'seconds', 0):.1f} s, {getattr(run, 'rss', 0) / 2**20:.0f} MiB peak RSS")


def test_a_70000_element_warehouse_validates_by_default(tmp_path: Path) -> None:
    n = warehouse(tmp_path / "w.urdf", 70_000)
    assert MAX_ELEMENTS_UNTRUSTED < n < MAX_ELEMENTS
    run = sensorkit("validate", "w.urdf", "-q", cwd=tmp_path)
    _figures(f"{n} elements", run)
    assert run.code in (0, 1) and "SK101" not in run.out, run.out[-1000:]
    assert run.rss < GB and run.seconds < 60
    untrusted = sensorkit("validate", "--untrusted", "w.urdf", cwd=tmp_path)
    assert "SK101" in untrusted.out and f"more than {MAX_ELEMENTS_UNTRUSTED} elements" in untrusted.out
    assert "--max-elements" in untrusted.out  # the message names the option


def test_600000_elements_are_refused_naming_the_option(tmp_path: Path) -> None:
    n = warehouse(tmp_path / "w.urdf", 600_000)
    assert n > MAX_ELEMENTS
    for fmt in ("text", "json", "sarif", "github"):
        run = sensorkit("validate", "-f", fmt, "w.urdf", cwd=tmp_path)
        assert run.code == 1 and "SK101" in run.out, run.out[-1000:]
        assert f"more than {MAX_ELEMENTS} elements" in run.out and "--max-elements" in run.out
    _figures(f"{n} elements refused", run)
    assert run.rss < GB and run.seconds < 60


def test_max_elements_raises_the_bound(tmp_path: Path) -> None:
    n = warehouse(tmp_path / "w.urdf", 600_000)
    run = sensorkit("validate", "--max-elements", "700000", "-q", "w.urdf", cwd=tmp_path, timeout=300)
    _figures(f"{n} elements, --max-elements 700000", run)
    assert run.code in (0, 1) and "SK101" not in run.out, run.out[-1000:]
    (tmp_path / "sensorkit.toml").write_text("max-elements = 700000\n")
    by_file = sensorkit("validate", "-q", "w.urdf", cwd=tmp_path, timeout=300)
    assert by_file.code in (0, 1) and "SK101" not in by_file.out, by_file.out[-1000:]


def test_the_settings_file_cannot_raise_the_untrusted_bound(tmp_path: Path) -> None:
    """The settings file comes with the pull request: under --untrusted it only lowers."""
    warehouse(tmp_path / "w.urdf", 70_000)
    (tmp_path / "sensorkit.toml").write_text("max-elements = 700000\n")
    run = sensorkit("validate", "--untrusted", "w.urdf", cwd=tmp_path)
    assert f"more than {MAX_ELEMENTS_UNTRUSTED} elements" in run.out, run.out[-1000:]
    (tmp_path / "sensorkit.toml").write_text("max-elements = 1000\n")
    lowered = sensorkit("validate", "w.urdf", cwd=tmp_path)
    assert "more than 1000 elements" in lowered.out, lowered.out[-1000:]
