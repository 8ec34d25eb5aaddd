from __future__ import annotations

import shutil
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from sensorkit.base.findings import Finding, Severity
from sensorkit.lint.engine import FileReport, Options, validate_file

ROOT = Path(__file__).resolve().parent.parent
# Public robots fetched from other repositories live beside the project, never in it:
# ../shared/corpus (with its licences and MANIFEST.md) and its labelled real-world set.
CORPUS = ROOT.parent / "shared" / "corpus"
REALWORLD = CORPUS / "realworld"
NO_CORPUS = "../shared/corpus is absent: the public robots live beside the project, not in it (CI has them)"
needs_corpus = pytest.mark.skipif(not CORPUS.is_dir(), reason=NO_CORPUS)


def corpus_package_paths() -> tuple[str, ...]:
    """Where the corpus robots find their packages: the corpus's repositories, then the
    real-world set's (in that order: two repositories ship a package of one name). The
    real-world set sits inside the corpus folder, so the corpus is named repository by
    repository to keep it out of the first scan."""
    if not CORPUS.is_dir():
        return ()
    repos = sorted(p for p in CORPUS.iterdir() if p.is_dir() and p != REALWORLD)
    return (*map(str, repos), str(REALWORLD))


@pytest.fixture(autouse=True)
def own_cache_home(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Every test its own XDG_CACHE_HOME (the expansion cache, sensorkit.loading.cache),
    beside its tmp_path, not in it: no test writes the user's cache, and none sees
    another's entries. Subprocesses inherit it."""
    folder = tmp_path_factory.mktemp("cache-home")
    monkeypatch.setenv("XDG_CACHE_HOME", str(folder))
    return folder


# Every finding a rule makes while the suite runs, held to the severities its rule declares
# (RuleInfo.severity, e.g. "error/warning/info"; issue 35): a severity a rule does not
# declare fails the test that produced it.
_UNDECLARED: list[str] = []


@pytest.fixture(scope="session", autouse=True)
def _declared_severities() -> Iterator[None]:
    from sensorkit.lint.rules.base import RULES, Context

    original = Context.finding

    def finding(self: Context, rule_id: str, severity: Severity, *args: Any, **kw: Any) -> Finding:
        info = RULES.get(rule_id)
        if info is not None and severity.label not in info.severity.split("/"):
            _UNDECLARED.append(f"{rule_id} made {severity.label}, declares {info.severity}: {args[0] if args else ''}")
        return original(self, rule_id, severity, *args, **kw)

    Context.finding = finding  # type: ignore[method-assign]
    yield
    Context.finding = original  # type: ignore[method-assign]


@pytest.fixture(autouse=True)
def severity_is_declared() -> Iterator[None]:
    start = len(_UNDECLARED)
    yield
    assert not _UNDECLARED[start:], "a finding's severity its rule does not declare: " + "; ".join(_UNDECLARED[start:])


@pytest.fixture
def check(tmp_path: Path) -> Callable[..., FileReport]:
    """Write a robot to a file and validate it."""
    counter = iter(range(10**6))

    def run(text: str, *, suffix: str = ".urdf", target: str = "auto", **kw: object) -> FileReport:
        path = tmp_path / f"robot{next(counter)}{suffix}"
        path.write_text(text)
        report = validate_file(path, Options(target=target, **kw))  # type: ignore[arg-type]
        assert not report.internal_errors, report.internal_errors
        return report

    return run


def rules_of(report: FileReport) -> set[str]:
    return {f.rule for f in report.findings}


def check_urdf_bin() -> str:
    exe = shutil.which("check_urdf")
    if exe is None:
        pytest.fail("check_urdf is missing: apt-get install liburdfdom-tools (the test command installs it)")
    return exe


def run_check_urdf(path: Path, timeout: float = 20) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [check_urdf_bin(), str(path)], check=False, capture_output=True, text=True, timeout=timeout
    )


def run_cli(*args: str, cwd: Path | None = None, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    """Run ``python -m sensorkit ARGS`` as a user would (a fresh process)."""
    return subprocess.run(
        [sys.executable, "-m", "sensorkit", *args],
        check=False,
        capture_output=True,
        text=True,
        timeout=timeout,
        cwd=cwd,
    )


def sdformat_tool(factory: pytest.TempPathFactory, source: Path) -> Path:
    """``tests/tools/NAME.cc`` built against Debian's libsdformat12 (the independent SDF
    reader; tests/run installs g++, pkg-config and libsdformat-dev), once per run: the
    xdist workers share one build, keyed by the source and the compiler flags."""
    import fcntl
    import hashlib
    import os

    cxx = shutil.which("g++") or shutil.which("c++")
    pkg = shutil.which("pkg-config")
    if cxx is None or pkg is None:
        pytest.fail("g++ and pkg-config are missing: bash tests/run installs them")
    flags = subprocess.run([pkg, "--cflags", "--libs", "sdformat12"], capture_output=True, text=True, check=False)
    if flags.returncode != 0:
        pytest.fail("libsdformat is missing: apt-get install libsdformat-dev (bash tests/run installs it)")
    base = factory.getbasetemp()
    shared = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base
    key = hashlib.blake2b(source.read_bytes() + flags.stdout.encode() + cxx.encode(), digest_size=8).hexdigest()
    exe = shared / f"{source.stem}-{key}"
    with open(shared / f"{source.stem}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not exe.is_file():
            partial = exe.with_suffix(".partial")
            built = subprocess.run([cxx, "-O0", "-o", str(partial), str(source), *flags.stdout.split()],
                                   capture_output=True, text=True, check=False, timeout=300)
            assert built.returncode == 0, built.stderr
            partial.rename(exe)
    return exe
