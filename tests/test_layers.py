"""The shape of sensorkit/: layers held by import-linter, rooms of a readable size.

The layer order is written once, in sensorkit/__init__.py's docstring, and declared as
import-linter contracts in pyproject.toml; lint-imports (import-linter's own command, not
code of ours) checks every import, lazy ones and those for type checking included.
"""

from __future__ import annotations

import ast
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import tomllib

import sensorkit

ROOT = Path(__file__).resolve().parent.parent
PKG = ROOT / "sensorkit"
# Knowledge tables are data with a source per row: they may grow past a module's size.
TABLES = {PKG / "knowledge" / "plugins.py"}
MAX_MODULE_LINES = 600
MAX_FUNCTION_LINES = 80


def _contracts() -> list[dict[str, object]]:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]["contracts"]


def test_lint_imports_keeps_every_contract() -> None:
    exe = shutil.which("lint-imports", path=str(Path(sys.executable).parent)) or shutil.which("lint-imports")
    if exe is None:
        pytest.fail("lint-imports is missing: it comes with the test extra (import-linter)")
    p = subprocess.run([exe, "--no-cache"], cwd=ROOT, capture_output=True, text=True, check=False)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "0 broken" in p.stdout, p.stdout


def test_the_contracts_say_what_the_docstring_says() -> None:
    """The docstring's numbered list is the layers contract, bottom up."""
    written = re.findall(r"^\d+\. ``(\w+)``", sensorkit.__doc__ or "", re.M)
    layers = next(c for c in _contracts() if c["type"] == "layers")
    declared = [name for name in reversed(layers["layers"]) if name != "__main__"]  # type: ignore[call-overload]
    assert written == declared


def test_every_package_is_a_layer() -> None:
    layers = next(c for c in _contracts() if c["type"] == "layers")
    packages = {p.name for p in PKG.iterdir() if (p / "__init__.py").is_file()}
    assert packages == set(layers["layers"]) - {"__main__"}  # type: ignore[arg-type]
    loose = sorted(p.name for p in PKG.glob("*.py") if p.name not in {"__init__.py", "__main__.py"})
    assert not loose, f"modules outside a layer: {loose}"


@pytest.mark.parametrize(
    ("added", "said"),
    [
        ("from sensorkit.cli import app", "sensorkit.base.errors -> sensorkit.cli"),  # upward
        ("from sensorkit.base.atomic import write_bytes", "No cycles are allowed in sensorkit.base"),  # atomic imports errors
    ],
    ids=["upward", "circle"],
)
def test_a_circle_and_an_upward_import_are_caught(tmp_path: Path, added: str, said: str) -> None:
    """lint-imports on a copy with one bad lazy import added must fail: the contracts bite."""
    exe = shutil.which("lint-imports", path=str(Path(sys.executable).parent)) or shutil.which("lint-imports")
    assert exe is not None
    shutil.copytree(PKG, tmp_path / "sensorkit", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    errors = tmp_path / "sensorkit" / "base" / "errors.py"
    errors.write_text(errors.read_text() + f"\n\ndef _bad() -> None:\n    {added}  # noqa: F401\n")
    p = subprocess.run([exe, "--no-cache"], cwd=tmp_path, capture_output=True, text=True, check=False,
                       env={"PYTHONPATH": str(tmp_path), "PATH": "/usr/bin:/bin"})
    assert p.returncode != 0
    assert said in p.stdout, p.stdout


def _modules() -> list[Path]:
    return sorted(PKG.rglob("*.py"))


def test_no_module_over_600_lines() -> None:
    big = {str(p.relative_to(ROOT)): n for p in _modules() if p not in TABLES and (n := len(p.read_text().splitlines())) > MAX_MODULE_LINES}
    assert not big, big


def test_no_function_over_80_lines() -> None:
    big = []
    for p in _modules():
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                lines = (node.end_lineno or node.lineno) - node.lineno + 1
                if lines > MAX_FUNCTION_LINES:
                    big.append(f"{p.relative_to(ROOT)}:{node.lineno} {node.name} ({lines} lines)")
    assert not big, big


def test_records_are_plain_dataclasses() -> None:
    """No dataclass writes its own __init__ to win milliseconds (init=False)."""
    hand = []
    for p in _modules():
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.ClassDef):
                for d in node.decorator_list:
                    if isinstance(d, ast.Call) and any(k.arg == "init" for k in d.keywords):
                        hand.append(f"{p.relative_to(ROOT)}:{node.lineno} {node.name}")
    assert not hand, hand
