"""xacro's own command line beside sensorkit's fast xacro (sensorkit.loading.xacro_fast),
on the same files in the same environment: tests/test_xacro_fast.py compares them.

xacro's ``$(find pkg)`` needs ``ament_index_python``, which is not on PyPI: :func:`setup`
builds an install prefix with an ament resource-index marker and ``share/NAME`` linked to
each package of the corpus (in ``conftest.corpus_package_paths`` order, first found wins)
and a stand-in module doing the real one's lookup over ``AMENT_PREFIX_PATH`` (as
benchmarks/bench_real.py does). Both sides run with it.

Run as a program (``python tests/xacro_peer.py < jobs.json``), this file is the fast side:
one process expands every job in turn with xacro's own ``main`` under xacro_fast's changes,
so the caches carry over from file to file as in a long-lived server. Each job is expanded
as ``xacro_expand.expand`` does it: bounded, by the allow-list evaluator, first; where that
stops with ``NotHere`` or fails, again with only the lexing and compiling caches (what the
forked child runs). The answer says which one gave the output.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import sys
from pathlib import Path
from typing import Any

STAND_IN = '''"""Stand-in for ament_index_python: the package lookup of the real one."""
import os


class PackageNotFoundError(KeyError):
    pass


def get_search_paths():
    return [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]


def get_package_prefix(package_name):
    for prefix in get_search_paths():
        marker = os.path.join(prefix, "share", "ament_index", "resource_index", "packages", package_name)
        if os.path.isfile(marker):
            return prefix
    raise PackageNotFoundError(f"package '{package_name}' not found, searching: {get_search_paths()}")


def get_package_share_directory(package_name, print_warning=True):
    return os.path.join(get_package_prefix(package_name), "share", package_name)
'''


def setup(tmp: Path, package_roots: list[str]) -> dict[str, str]:
    """The environment both sides run in (see the module doc)."""
    from sensorkit.loading.packages import scan_packages

    found: dict[str, Path] = {}
    for root in package_roots:
        for name, folder in scan_packages(Path(root)).items():
            found.setdefault(name, folder)
    prefix = tmp / "prefix"
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True)
    for name, folder in found.items():
        (index / name).touch()
        (prefix / "share" / name).symlink_to(folder, target_is_directory=True)
    module = tmp / "pythonpath" / "ament_index_python"
    module.mkdir(parents=True)
    (module / "__init__.py").write_text(STAND_IN)
    (module / "packages.py").write_text(
        "from ament_index_python import *  # noqa\n"
        "from ament_index_python import PackageNotFoundError  # noqa\n"
    )
    env = dict(os.environ, AMENT_PREFIX_PATH=str(prefix))
    env.pop("ROS_PACKAGE_PATH", None)
    root = str(Path(__file__).resolve().parent.parent)
    env["PYTHONPATH"] = os.pathsep.join([str(tmp / "pythonpath"), root])
    return env


def _run_main(argv: list[str]) -> tuple[int, str, str]:
    """xacro's command line (``xacro.main``) in this process: status, stdout, stderr."""
    import xacro

    out, err = io.StringIO(), io.StringIO()
    saved = sys.argv
    sys.argv = ["xacro", *argv]
    code = 0
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            xacro.main()
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    finally:
        sys.argv = saved
    return code, out.getvalue(), err.getvalue()


def _reset() -> None:
    """xacro's module state as a fresh process has it (sensorkit does the same)."""
    import xacro

    xacro.all_includes = []
    xacro.substitution_args_context.clear()
    xacro.init_stacks(None)
    xacro.root_dir = os.curdir
    xacro.verbosity = 1


def expand_fast(argv: list[str], timeout: float = 60.0) -> dict[str, Any]:
    """One job as sensorkit expands it (see the module doc)."""
    import xacro
    import xacro.substitution_args as sa

    from sensorkit.loading import xacro_fast
    from sensorkit.loading.xacro_expand import MEMORY_LIMIT

    for how in ("bounded", "child"):
        undo: list[Any] = []
        _reset()
        xacro_fast.speed_up(xacro, undo)
        if how == "bounded":
            xacro_fast.bound(xacro, sa, timeout, MEMORY_LIMIT, undo)
        try:
            code, out, err = _run_main(argv)
        except xacro_fast.NotHere:
            continue
        finally:
            for step in reversed(undo):
                step()
        if code == 0 or how == "child":
            return {"how": how, "code": code, "out": out, "err": err}
    raise AssertionError("unreachable")


def main() -> None:
    jobs = json.load(sys.stdin)
    from sensorkit.loading import xacro_fast

    assert xacro_fast.supported(), "the installed xacro is not one xacro_fast was tested with"
    answers = [expand_fast(argv) for argv in jobs]
    json.dump(answers, sys.stdout)


if __name__ == "__main__":
    main()
