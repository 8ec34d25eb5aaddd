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

from pathlib import Path

import fuzz_targets as ft
import pytest

REGRESSIONS = sorted(ft.REGRESSIONS.glob("*.json"))


@pytest.mark.parametrize("path", REGRESSIONS, ids=[p.stem for p in REGRESSIONS])
def test_regression_replays_cleanly(path: Path) -> None:
    out = ft.run_bounded(ft.load_regression(path))
    assert out.ok, f"{out.problem}\n{out.detail}"
