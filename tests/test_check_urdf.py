"""urdfdom's check_urdf as an independent parser: every plain URDF in the tests goes through it.

Where urdfdom has a verdict on the tree (it parses, or it refuses), ours agrees. Where we
differ on purpose, the test below says so: urdfdom accepts, or hangs on, descriptions
that are broken.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from builders import inertial, joint, link
from conftest import ROOT, run_check_urdf
from test_rules import CASES

from sensorkit.base.findings import Severity
from sensorkit.lint.engine import Options, validate_file
from sensorkit.loading.document import looks_like_xacro

STRUCTURAL = {"SK101", "SK201", "SK202", "SK203", "SK204", "SK205", "SK206", "SK207"}
# Rule-case robots that urdfdom accepts although they are broken (we report them on purpose).
ON_PURPOSE = {
    "two parents": "urdfdom silently keeps one parent joint",
    "lower > upper": "urdfdom does not compare limits",
    "zero axis": "urdfdom normalises a zero axis to NaN without complaint",
    "mimic of a missing joint": "urdfdom does not resolve mimic targets",
}


def _plain_urdfs() -> list[Path]:
    """Every plain URDF file under tests/ (fixtures and the corpus copy), not xacro in disguise."""
    files = sorted(p for p in (ROOT / "tests").rglob("*.urdf"))
    return [p for p in files if not looks_like_xacro(p, p.read_bytes())]


def _structural_errors(path: Path, target: str = "auto") -> set[str]:
    report = validate_file(path, Options(target=target))
    return {
        f.rule for f in report.findings if f.rule in STRUCTURAL and f.severity == Severity.ERROR
    }


@pytest.mark.parametrize("path", _plain_urdfs(), ids=lambda p: p.name)
def test_files_agree_with_check_urdf(path: Path) -> None:
    res = run_check_urdf(path)
    assert (res.returncode == 0) == (not _structural_errors(path)), res.stdout + res.stderr


def _case_files(tmp_path: Path) -> list[tuple[str, Path, str]]:
    """Each case named RULE-N-KIND, N counting that rule's cases: stable when cases of
    other rules are added to the list."""
    out = []
    seen: dict[str, int] = {}
    for i, (rule, bad, good, target, suffix) in enumerate(CASES):
        n = seen[rule] = seen.get(rule, -1) + 1
        if suffix == ".sdf":  # an SDF case: check_urdf reads URDF only (libsdformat's tests judge it)
            continue
        for kind, text in (("bad", bad), ("good", good)):
            p = tmp_path / f"{i}_{rule}_{kind}.urdf"
            p.write_text(text)
            out.append((f"{rule}-{n}-{kind}", p, target))
    return out


def test_rule_cases_agree_with_check_urdf(tmp_path: Path) -> None:
    differ = []
    for name, path, target in _case_files(tmp_path):
        res = run_check_urdf(path)
        if (res.returncode == 0) != (not _structural_errors(path, target)):
            differ.append(name)
    # Exactly the documented cases differ: two parents, lower > upper, zero axis, mimic target.
    assert sorted(differ) == sorted(
        ["SK204-2-bad", "SK205-2-bad", "SK206-1-bad", "SK207-0-bad"]
    ), differ
    assert len(ON_PURPOSE) == len(differ)


def test_check_urdf_hangs_on_a_cycle_below_the_root_and_we_do_not(tmp_path: Path) -> None:
    text = (
        '<robot name="c">'
        + link("a", inertial(1, 0.1))
        + link("b")
        + link("c")
        + joint("j1", "a", "b")
        + joint("j2", "b", "c")
        + joint("j3", "c", "b")
        + "</robot>"
    )
    p = tmp_path / "cycle.urdf"
    p.write_text(text)
    with pytest.raises(subprocess.TimeoutExpired):
        run_check_urdf(p, timeout=3)
    report = validate_file(p)
    assert any(f.rule == "SK204" and "cycle" in f.message for f in report.findings)
