"""`sensorkit validate` against `xacro FILE > out.urdf && check_urdf out.urdf` on real robots.

Run by hand (never in the test suite)::

    .venv/bin/python benchmarks/bench_real.py                 # every robot, 15 pairs each
    .venv/bin/python benchmarks/bench_real.py --runs 7 --only turtlebot4
    .venv/bin/python benchmarks/bench_real.py --profile pr2   # where one validate's CPU goes

The robots are the non-pending entries of tests/realworld/robots.yaml, their files in
../shared/corpus/realworld, each run with its xacro args. For each robot, two commands run in
paired, interleaved rounds (peer then sensorkit, then sensorkit then peer, ...) and their CPU
times (user + sys of the process and everything it waited for) are compared by median:

- the peer, what users run today without sensorkit: ``xacro FILE name:=value ... >
  out.urdf`` (xacro from this venv), then ``check_urdf out.urdf`` (Debian's
  liburdfdom-tools); the two processes' CPU times are summed;
- ``sensorkit validate FILE --arg name:=value ...`` as a user runs it (report to /dev/null;
  with ``--no-cache`` when the CLI has it, so the figure is the cold CLI).

xacro's ``$(find pkg)`` needs ``ament_index_python``, which is not on PyPI. The script builds
an install prefix in a temporary folder: ament resource-index markers
(``share/ament_index/resource_index/packages/NAME``) and ``share/NAME`` linked to each package
of the corpus (as tests/labelled.py finds them: the corpus's repositories, then the real-world
set, first found wins; a robot's ``packages:`` come first), and a stand-in module doing the
real one's lookup over ``AMENT_PREFIX_PATH``. Both commands run with
``AMENT_PREFIX_PATH`` set to that prefix (sensorkit reads it before the workspace), so they
resolve packages alike. A robot whose peer fails (xacro or check_urdf exits non-zero) is
listed apart with the reason and left out of the median.

Both commands are Python programs: each gets its bytecode cached in the temporary folder
(some shells set PYTHONDONTWRITEBYTECODE), and the checking run before the timed ones
compiles it.

``--profile ROBOT`` breaks one sensorkit run down instead: interpreter start, imports (with
``-X importtime``, the 15 slowest by cumulative time), xacro expansion, model, rules, report
(see ``bench_real_phases.py``).
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus"
REALWORLD = CORPUS / "realworld"
ROBOTS = ROOT / "tests" / "realworld" / "robots.yaml"
VENV_BIN = Path(sys.executable).parent
CHECK_URDF = "/usr/bin/check_urdf"

# What ament_index_python.packages does for get_package_share_directory (the real module is
# built by colcon, not published on PyPI): the first AMENT_PREFIX_PATH prefix holding the
# package's resource-index marker, and its share/NAME.
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


@dataclass
class Robot:
    file: str
    args: dict[str, str]
    packages: dict[str, str]
    label: str = ""
    env: dict[str, str] = field(default_factory=dict)

    @property
    def path(self) -> Path:
        return REALWORLD / self.file

    def peer_cmds(self, out: Path) -> tuple[list[str], list[str]]:
        xacro = [
            str(VENV_BIN / "xacro"),
            str(self.path),
            *(f"{k}:={v}" for k, v in self.args.items()),
        ]
        return xacro, [CHECK_URDF, str(out)]

    def sensorkit_cmd(self, no_cache: bool) -> list[str]:
        cmd = [str(VENV_BIN / "sensorkit"), "validate", str(self.path)]
        for k, v in self.args.items():
            cmd += ["--arg", f"{k}:={v}"]
        return [*cmd, "--no-cache"] if no_cache else cmd


def load_robots() -> list[Robot]:
    """The non-pending robots, each labelled by its file's stem (and what tells it apart)."""
    robots = []
    for entry in yaml.safe_load(ROBOTS.read_text()) or []:
        if entry.get("pending") or entry.get("launch"):
            continue
        args = {k: str(v) for k, v in (entry.get("args") or {}).items()}
        packages = {k: str(v) for k, v in (entry.get("packages") or {}).items()}
        robots.append(Robot(entry["file"], args, packages))
    stems = [re.sub(r"(\.urdf)?\.xacro$|\.urdf$", "", Path(r.file).name) for r in robots]
    for r, stem in zip(robots, stems, strict=True):
        same_stem = [o for o, s in zip(robots, stems, strict=True) if s == stem]
        label = stem
        if len({o.file for o in same_stem}) > 1:
            label = f"{Path(r.file).parent.name}/{stem}"
        same_file = [o for o in same_stem if o.file == r.file]
        if len(same_file) > 1:
            others = [o.args for o in same_file if o is not r]
            diff = [f"{k}={v}" for k, v in r.args.items() if any(o.get(k) != v for o in others)]
            label += f" ({','.join(diff)})"
        r.label = label
    return robots


def corpus_packages() -> dict[str, Path]:
    """Every package of the corpus, as tests/conftest.py's corpus_package_paths orders them."""
    sys.path.insert(0, str(ROOT))
    from sensorkit.loading.packages import scan_packages

    found: dict[str, Path] = {}
    roots = [p for p in sorted(CORPUS.iterdir()) if p.is_dir() and p != REALWORLD] + [REALWORLD]
    for root in roots:
        for name, folder in scan_packages(root).items():
            found.setdefault(name, folder)
    return found


def make_prefix(prefix: Path, packages: dict[str, Path]) -> Path:
    """An install prefix with an ament resource-index marker and share/NAME per package."""
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True)
    for name, folder in packages.items():
        (index / name).touch()
        (prefix / "share" / name).symlink_to(folder, target_is_directory=True)
    return prefix


def environments(tmp: Path, robots: list[Robot]) -> tuple[dict[str, str], dict[str, str]]:
    """The peer's and sensorkit's environments (each robot's own prefix goes first)."""
    shared = make_prefix(tmp / "prefix", corpus_packages())
    module = tmp / "pythonpath" / "ament_index_python"
    module.mkdir(parents=True)
    (module / "__init__.py").write_text(STAND_IN)
    (module / "packages.py").write_text(
        "from ament_index_python import *  # noqa\n"
        "from ament_index_python import PackageNotFoundError  # noqa\n"
    )
    base = dict(os.environ, PYTHONPYCACHEPREFIX=str(tmp / "pycache"), AMENT_PREFIX_PATH=str(shared))
    base.pop("PYTHONDONTWRITEBYTECODE", None)
    base.pop("ROS_PACKAGE_PATH", None)
    for i, r in enumerate(robots):
        if r.packages:
            own = make_prefix(tmp / f"prefix{i}", {k: REALWORLD / v for k, v in r.packages.items()})
            r.env = {"AMENT_PREFIX_PATH": f"{own}{os.pathsep}{shared}"}
    sk = dict(base)
    peer = dict(
        base, PYTHONPATH=str(tmp / "pythonpath") + os.pathsep + os.environ.get("PYTHONPATH", "")
    )
    return peer, sk


def cpu_of(
    cmd: list[str], env: dict[str, str], cwd: Path, stdout: Path | None = None
) -> tuple[float, int, str]:
    """CPU seconds (user + sys of ``cmd`` and what it waited for), exit code, and the first
    stderr line saying an error (else the last one)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(stdout or os.devnull, "wb") as out:
        proc = subprocess.run(
            cmd, stdout=out, stderr=subprocess.PIPE, env=env, cwd=cwd, check=False
        )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    lines = [x.strip() for x in proc.stderr.decode("utf-8", "replace").splitlines() if x.strip()]
    said = [x for x in lines if x.lower().startswith("error")] or lines[-1:] or [""]
    return cpu, proc.returncode, said[0]


def run_peer(r: Robot, env: dict[str, str], tmp: Path) -> tuple[float, float, str | None]:
    """xacro's and check_urdf's CPU seconds, and why the peer failed (None if it did not)."""
    out = tmp / "out.urdf"
    out.unlink(missing_ok=True)
    xacro, check = r.peer_cmds(out)
    env = dict(env, **r.env)
    t_x, rc, err = cpu_of(xacro, env, tmp, stdout=out)
    if rc != 0:
        return t_x, 0.0, f"xacro exit {rc}: {err}"
    if out.stat().st_size == 0:
        return t_x, 0.0, "xacro wrote nothing"
    t_c, rc, err = cpu_of(check, env, tmp)
    return t_x, t_c, None if rc == 0 else f"check_urdf exit {rc}: {err}"


def run_sensorkit(
    r: Robot, env: dict[str, str], tmp: Path, no_cache: bool
) -> tuple[float, str | None]:
    t, rc, err = cpu_of(r.sensorkit_cmd(no_cache), dict(env, **r.env), tmp)
    return t, None if rc in (0, 1) else f"sensorkit exit {rc}: {err}"


def has_no_cache(env: dict[str, str]) -> bool:
    help_text = subprocess.run(
        [str(VENV_BIN / "sensorkit"), "validate", "--help"],
        capture_output=True,
        text=True,
        env=dict(env, COLUMNS="200"),
        check=False,
    ).stdout
    return "--no-cache" in help_text


@dataclass
class Row:
    label: str
    xacro: float
    check: float
    peer: float
    sensorkit: float
    pair_ratio: float  # the median of the per-round ratios

    @property
    def ratio(self) -> float:
        return self.sensorkit / self.peer


def measure(
    r: Robot, peer_env: dict[str, str], sk_env: dict[str, str], tmp: Path, runs: int, no_cache: bool
) -> Row:
    xs, cs, ps, ss = [], [], [], []
    for i in range(runs):
        for which in ("peer", "sk") if i % 2 == 0 else ("sk", "peer"):
            if which == "peer":
                t_x, t_c, _ = run_peer(r, peer_env, tmp)
                xs.append(t_x)
                cs.append(t_c)
                ps.append(t_x + t_c)
            else:
                ss.append(run_sensorkit(r, sk_env, tmp, no_cache)[0])
    med = statistics.median
    return Row(
        r.label, med(xs), med(cs), med(ps), med(ss), med(s / p for s, p in zip(ss, ps, strict=True))
    )


def benchmark(robots: list[Robot], runs: int) -> None:
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        peer_env, sk_env = environments(tmp, robots)
        no_cache = has_no_cache(sk_env)
        rows: list[Row] = []
        apart: list[tuple[str, str]] = []
        t0 = time.perf_counter()
        for r in robots:
            _x, _c, why = run_peer(r, peer_env, tmp)  # checks it, and compiles the bytecode
            _s, sk_why = run_sensorkit(r, sk_env, tmp, no_cache)
            if why or sk_why:
                apart.append((r.label, why or sk_why or ""))
                continue
            rows.append(measure(r, peer_env, sk_env, tmp, runs, no_cache))
            print(f"  {r.label}: {rows[-1].ratio:.2f}", file=sys.stderr, flush=True)
    report(rows, apart, runs, no_cache, time.perf_counter() - t0)


def report(
    rows: list[Row], apart: list[tuple[str, str]], runs: int, no_cache: bool, seconds: float
) -> None:
    med = statistics.median
    flag = " --no-cache" if no_cache else " (no --no-cache option: nothing cached)"
    print(
        f"CPU (user + sys), median of {runs} paired interleaved runs; peer = xacro > out.urdf && check_urdf;"
        f" sensorkit = validate{flag}"
    )
    print(
        f"{'robot':44} {'xacro':>7} {'check':>7} {'peer':>7} {'skit':>7} {'skit-peer':>9} {'ratio':>6} {'paired':>6}"
    )
    for w in sorted(rows, key=lambda w: w.peer):
        print(
            f"{w.label[:44]:44} {w.xacro * 1e3:7.1f} {w.check * 1e3:7.1f} {w.peer * 1e3:7.1f} {w.sensorkit * 1e3:7.1f}"
            f" {(w.sensorkit - w.peer) * 1e3:+9.1f} {w.ratio:6.2f} {w.pair_ratio:6.2f}"
        )
    print("(ms; ratio = median sensorkit / median peer; paired = median of the per-round ratios)")
    if apart:
        print(f"left out ({len(apart)}), the peer or sensorkit failed:")
        for label, why in apart:
            print(f"  {label}: {why[:160]}")
    if rows:
        ratios = [w.ratio for w in rows]
        print(
            f"range {min(ratios):.2f}-{max(ratios):.2f}; median sensorkit - peer"
            f" {med(w.sensorkit - w.peer for w in rows) * 1e3:+.0f} ms; median peer {med(w.peer for w in rows) * 1e3:.0f} ms,"
            f" median sensorkit {med(w.sensorkit for w in rows) * 1e3:.0f} ms"
        )
        print(f"median ratio {med(ratios):.2f} over {len(rows)} robots")
    print(
        f"load average {' '.join(f'{v:.1f}' for v in os.getloadavg())}; {seconds:.0f} s",
        file=sys.stderr,
    )


def pick(robots: list[Robot], name: str) -> list[Robot]:
    """The robots whose label or file contains ``name`` (case-insensitive)."""
    name = name.lower()
    return [r for r in robots if name in r.label.lower() or name in r.file.lower()]


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--runs", type=int, default=15, help="paired runs per robot (default 15)")
    ap.add_argument(
        "--only", action="append", default=[], help="robots whose label or file contains this"
    )
    ap.add_argument(
        "--profile", metavar="ROBOT", help="break one sensorkit run down (first robot matching)"
    )
    ap.add_argument("--list", action="store_true", help="list the robots and exit")
    a = ap.parse_args()
    if not REALWORLD.is_dir():
        sys.exit(f"{REALWORLD} is absent: the real robots live beside the project")
    if not Path(CHECK_URDF).is_file() or shutil.which("xacro", path=str(VENV_BIN)) is None:
        sys.exit("needs check_urdf (apt-get install liburdfdom-tools) and xacro in this venv")
    robots = load_robots()
    if a.list:
        print("\n".join(f"{r.label:44} {r.file}" for r in robots))
        return
    if a.profile:
        chosen = pick(robots, a.profile)
        if not chosen:
            sys.exit(f"no robot matches {a.profile!r} (see --list)")
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from bench_real_phases import profile

        with tempfile.TemporaryDirectory() as t:
            _peer, sk_env = environments(Path(t), chosen[:1])
            profile(chosen[0], dict(sk_env, **chosen[0].env), Path(t), max(a.runs, 1))
        return
    if a.only:
        robots = [r for r in robots if any(r in pick(robots, name) for name in a.only)]
    benchmark(robots, a.runs)


if __name__ == "__main__":
    main()
