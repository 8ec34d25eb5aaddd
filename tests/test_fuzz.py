"""Issue 10, fuzzing as a habit: generated robots through every command, and every input
that ever failed replayed.

The strategies (``fuzz_strategies``) make URDF and xacro robots that are valid, nearly
valid, broken or hostile; the targets (``fuzz_targets``) run validate (API and CLI),
add-* (API and CLI, with the byte-preservation contract), intrinsics, export and render
preview on them and say what counts as a failure. This file is the short run for CI
(few examples, ``derandomize``: the same inputs every time); ``benchmarks/fuzz_long.py``
is the long one (100,000+ inputs). Failing inputs live in ``tests/regressions/fuzz/``.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import fuzz_strategies as fs
import fuzz_targets as ft
import pytest
from hypothesis import HealthCheck, given, settings

# A numpy warning inside a command reaches the user's stderr as stray lines (an overflow in
# a norm of far-apart frames did, before math.hypot): in these inputs it is a failure.
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

REGRESSIONS = sorted(ft.REGRESSIONS.glob("*.json"))


@pytest.mark.parametrize("path", REGRESSIONS, ids=[p.stem for p in REGRESSIONS])
def test_regression_replays_cleanly(path: Path) -> None:
    out = ft.run_bounded(ft.load_regression(path))
    assert out.ok, f"{out.problem}\n{out.detail}"


def _check(inp: fs.FuzzInput) -> None:
    out = ft.run_bounded(inp)
    if not out.ok:
        kept = ft.save_regression(inp, out, Path(tempfile.gettempdir()) / "sensorkit-fuzz-failures")
        pytest.fail(
            f"{out.problem}\n(the input is kept in {kept}: add it to {ft.REGRESSIONS})\n{out.detail[-3000:]}"
        )


def short(n: int) -> settings:
    """A few examples, the same ones on every run (CI must be reproducible)."""
    return settings(
        max_examples=n,
        deadline=None,
        derandomize=True,
        database=None,
        suppress_health_check=list(HealthCheck),
    )


@short(80)
@given(fs.fuzz_inputs("validate"))
def test_validate(inp: fs.FuzzInput) -> None:
    _check(inp)


@short(15)
@given(fs.fuzz_inputs("validate_paths"))
def test_validate_paths(inp: fs.FuzzInput) -> None:
    _check(inp)


@short(30)
@given(fs.fuzz_inputs("cli_validate"))
def test_cli_validate(inp: fs.FuzzInput) -> None:
    _check(inp)


@short(30)
@given(fs.fuzz_inputs("add"))
def test_add(inp: fs.FuzzInput) -> None:
    _check(inp)


@short(15)
@given(fs.fuzz_inputs("cli_add"))
def test_cli_add(inp: fs.FuzzInput) -> None:
    _check(inp)


@short(30)
@given(fs.fuzz_inputs("intrinsics"))
def test_intrinsics(inp: fs.FuzzInput) -> None:
    _check(inp)


@short(30)
@given(fs.fuzz_inputs("export"))
def test_export(inp: fs.FuzzInput) -> None:
    _check(inp)


@short(6)
@given(fs.fuzz_inputs("render"))
def test_render(inp: fs.FuzzInput) -> None:
    _check(inp)


@short(3)
@given(fs.fuzz_inputs("cli_subprocess"))
def test_cli_subprocess(inp: fs.FuzzInput) -> None:
    _check(inp)


@pytest.mark.parametrize(
    "piece", [*fs.HOSTILE_XACRO, fs.BOMBS[0]], ids=range(len(fs.HOSTILE_XACRO) + 1)
)
def test_each_hostile_xacro_piece(piece: str) -> None:
    # Every hostile construct once, whatever the random run drew: findings or an error, never
    # a crash; the runaway expression is stopped by the timeout (Options.timeout, 3 s here).
    robot = (
        f'<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="{fs.XACRO_NS}">\n'
        f'<link name="base_link"/>\n{piece}\n</robot>\n'
    )
    files = {"robot.urdf.xacro": robot.encode()}
    if "loop_a" in piece:
        files["parts/loop_a.xacro"] = (
            f'<robot xmlns:xacro="{fs.XACRO_NS}"><xacro:include filename="loop_b.xacro"/></robot>'.encode()
        )
        files["parts/loop_b.xacro"] = (
            f'<robot xmlns:xacro="{fs.XACRO_NS}"><xacro:include filename="loop_a.xacro"/></robot>'.encode()
        )
    _check(fs.FuzzInput("validate", fs.Case(files, "robot.urdf.xacro", label="hostile")))
