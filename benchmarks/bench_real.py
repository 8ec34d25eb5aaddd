"""`sensorkit validate` against `xacro FILE > out.urdf && check_urdf out.urdf` on real robots.

Run by hand (never in the test suite)::

    .venv/bin/python benchmarks/bench_real.py                 # every robot, 15 pairs each
    .venv/bin/python benchmarks/bench_real.py --runs 7 --only turtlebot4
    .venv/bin/python benchmarks/bench_real.py --profile pr2   # where one validate's CPU goes

The robots are the non-pending entries of tests/realworld/robots.yaml, their files in
../shared/corpus/realworld, each run with its xacro args. For each robot, the commands run in
interleaved rounds (each round in another order: rotated, and reversed every other round) and
their CPU times (user + sys of the process and everything it waited for) are compared by
median; wall times and the load average are recorded beside them:

- the peer, what users run today without sensorkit: ``xacro FILE name:=value ... >
  out.urdf`` (xacro from this venv), then ``check_urdf out.urdf`` (Debian's
  liburdfdom-tools); the two processes' CPU times are summed;
- cold: ``sensorkit validate FILE --arg name:=value ... --no-cache`` as a user runs it
  (report to /dev/null);
- warm: the same without ``--no-cache``, its expansion cache (a folder of its own) filled
  by the checking run: what a pre-commit hook or a second run pays;
- with ``--baseline PROGRAM``, cold and warm of another sensorkit program too (another
  checkout's ``.venv/bin/sensorkit``): before and after in the same rounds.

At the end, ``sensorkit --version`` against ``xacro --version``.

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

# The stand-in for ament_index_python the tests give xacro too (tests/xacro_peer.py): the
# first AMENT_PREFIX_PATH prefix holding the package's resource-index marker, and its share/NAME.
sys.path.insert(0, str(ROOT / "tests"))
from xacro_peer import STAND_IN  # noqa: E402


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

    def floor_cmd(self, expand: bool) -> list[str]:
        """``--floors``: a process that imports typer (and, with ``expand``, then runs
        xacro's command line in-process on the robot, output to /dev/null). No typer CLI
        that expands with xacro can cost less: the floor under cold (with ``expand``) and
        under a warm run that only reads a stored result (without)."""
        code = "import typer\n"
        if expand:
            code += (
                "import sys, xacro\n"
                f"sys.argv = ['xacro', {str(self.path)!r}, "
                + "".join(f"{f'{k}:={v}'!r}, " for k, v in self.args.items())
                + "'-o', '/dev/null']\nxacro.main()\n"
            )
        return [str(VENV_BIN / "python"), "-c", code]

    def sensorkit_cmd(self, no_cache: bool, binary: Path | None = None) -> list[str]:
        cmd = [str(binary or VENV_BIN / "sensorkit"), "validate", str(self.path)]
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


WALL: list[float] = []  # the wall seconds of each cpu_of call since it was last cleared


def cpu_of(
    cmd: list[str], env: dict[str, str], cwd: Path, stdout: Path | None = None
) -> tuple[float, int, str]:
    """CPU seconds (user + sys of ``cmd`` and what it waited for), exit code, and the first
    stderr line saying an error (else the last one). Its wall seconds join ``WALL``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    with open(stdout or os.devnull, "wb") as out:
        proc = subprocess.run(
            cmd, stdout=out, stderr=subprocess.PIPE, env=env, cwd=cwd, check=False
        )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    WALL.append(time.perf_counter() - start)
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
    r: Robot, env: dict[str, str], tmp: Path, no_cache: bool, binary: Path | None = None
) -> tuple[float, str | None]:
    t, rc, err = cpu_of(r.sensorkit_cmd(no_cache, binary), dict(env, **r.env), tmp)
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


# The sides of a round: the peer, sensorkit cold (--no-cache) and warm (its cache filled by
# the checking run), with --baseline the same two of another sensorkit (another venv), and
# with --floors what typer alone costs ("typer") and typer then xacro's CLI ("typer+x").
SIDES = ("peer", "cold", "warm", "base", "base_warm", "typer", "typer+x")


def sides_of(base: Path | None, floors: bool) -> list[str]:
    """The sides measured besides the peer, in the order they are reported."""
    return (
        ["cold", "warm"]
        + (["base", "base_warm"] if base else [])
        + (["typer", "typer+x"] if floors else [])
    )


@dataclass
class Row:
    label: str
    cpu: dict[str, float]  # side -> median CPU seconds (the peer: xacro + check_urdf)
    wall: dict[str, float]  # side -> median wall seconds
    xacro: float
    check: float
    load: float  # the 1-minute load average while the robot ran

    def ratio(self, side: str) -> float:
        return self.cpu[side] / self.cpu["peer"]


def measure(
    r: Robot,
    envs: dict[str, dict[str, str]],
    tmp: Path,
    runs: int,
    base: Path | None,
    floors: bool = False,
) -> Row:
    sides = ["peer", *sides_of(base, floors)]
    cpu: dict[str, list[float]] = {k: [] for k in sides}
    wall: dict[str, list[float]] = {k: [] for k in sides}
    xs, cs, loads = [], [], []
    for i in range(runs):
        order = sides[i % len(sides) :] + sides[: i % len(sides)]  # rotated each round
        if i % 2:
            order.reverse()
        for side in order:
            WALL.clear()
            if side == "peer":
                t_x, t_c, _ = run_peer(r, envs["peer"], tmp)
                xs.append(t_x)
                cs.append(t_c)
                cpu[side].append(t_x + t_c)
                wall[side].append(sum(WALL))
                continue
            if side.startswith("typer"):  # the peer's environment: xacro finds packages
                cmd = r.floor_cmd(expand=side == "typer+x")
                cpu[side].append(cpu_of(cmd, dict(envs["peer"], **r.env), tmp)[0])
                wall[side].append(sum(WALL))
                continue
            env = envs["warm" if side.endswith("warm") else "cold"]
            binary = base if side.startswith("base") else None
            cpu[side].append(run_sensorkit(r, env, tmp, not side.endswith("warm"), binary)[0])
            wall[side].append(sum(WALL))
        loads.append(os.getloadavg()[0])
    med = statistics.median
    return Row(
        r.label,
        {k: med(v) for k, v in cpu.items()},
        {k: med(v) for k, v in wall.items()},
        med(xs),
        med(cs),
        med(loads),
    )


def benchmark(robots: list[Robot], runs: int, base: Path | None, floors: bool = False) -> None:
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        peer_env, sk_env = environments(tmp, robots)
        if not has_no_cache(sk_env):
            sys.exit("this sensorkit has no --no-cache: cold and warm cannot be told apart")
        # warm runs read and fill a cache of their own; cold ones never touch it
        envs = {
            "peer": peer_env,
            "cold": sk_env,
            "warm": dict(sk_env, XDG_CACHE_HOME=str(tmp / "cache")),
        }
        rows: list[Row] = []
        apart: list[tuple[str, str]] = []
        t0 = time.perf_counter()
        for r in robots:
            _x, _c, why = run_peer(r, peer_env, tmp)  # checks it, and compiles the bytecode
            _s, sk_why = run_sensorkit(r, envs["warm"], tmp, False)  # fills the cache
            if base is not None:
                run_sensorkit(r, envs["warm"], tmp, False, base)
            if why or sk_why:
                apart.append((r.label, why or sk_why or ""))
                continue
            rows.append(measure(r, envs, tmp, runs, base, floors))
            w = rows[-1]
            print(
                f"  {r.label}: cold {w.ratio('cold'):.2f} warm {w.ratio('warm'):.2f}"
                + (f" (baseline cold {w.ratio('base'):.2f})" if base else "")
                + f" load {w.load:.1f}",
                file=sys.stderr,
                flush=True,
            )
        version = version_cpu(sk_env, runs)
    report(rows, apart, runs, base, version, time.perf_counter() - t0, floors)


def version_cpu(env: dict[str, str], runs: int) -> dict[str, float]:
    """Median CPU of ``sensorkit --version`` and ``xacro --version``, interleaved."""
    cmds = {
        "sensorkit": [str(VENV_BIN / "sensorkit"), "--version"],
        "xacro": [str(VENV_BIN / "xacro"), "--version"],
    }
    out: dict[str, list[float]] = {k: [] for k in cmds}
    for i in range(max(runs, 5) * 2):
        for k in list(cmds) if i % 2 == 0 else list(cmds)[::-1]:
            out[k].append(cpu_of(cmds[k], env, Path(tempfile.gettempdir()))[0])
    return {k: statistics.median(v) for k, v in out.items()}


def report(
    rows: list[Row],
    apart: list[tuple[str, str]],
    runs: int,
    base: Path | None,
    version: dict[str, float],
    seconds: float,
    floors: bool = False,
) -> None:
    med = statistics.median
    sides = sides_of(base, floors)
    print(
        f"CPU (user + sys), median of {runs} rotated, interleaved rounds; peer = xacro > out.urdf"
        " && check_urdf; cold = validate --no-cache; warm = validate, cache filled"
        + (f"; base = {base}" if base else "")
        + (
            "; typer = python -c 'import typer'; typer+x = import typer, then xacro's CLI"
            " in-process"
            if floors
            else ""
        )
    )
    head = "".join(f" {k:>9}" for k in sides)
    ratios = "".join(f" {k[:7] + '/p':>9}" for k in sides)
    print(f"{'robot':40} {'load':>5} {'peer':>7}{head}{ratios} {'wall p':>7} {'wall c':>7}")
    for w in sorted(rows, key=lambda w: w.cpu["peer"]):
        cells = "".join(f" {w.cpu[k] * 1e3:9.1f}" for k in sides)
        rs = "".join(f" {w.ratio(k):9.2f}" for k in sides)
        print(
            f"{w.label[:40]:40} {w.load:5.1f} {w.cpu['peer'] * 1e3:7.1f}{cells}{rs}"
            f" {w.wall['peer'] * 1e3:7.0f} {w.wall['cold'] * 1e3:7.0f}"
        )
    print("(ms of CPU; X/p = median X / median peer; wall p, wall c: wall ms of the peer, of cold)")
    if apart:
        print(f"left out ({len(apart)}), the peer or sensorkit failed:")
        for label, why in apart:
            print(f"  {label}: {why[:160]}")
    if rows:
        for k in sides:
            rs = [w.ratio(k) for w in rows]
            print(
                f"{k:9} median ratio {med(rs):.2f} over {len(rows)} robots (range {min(rs):.2f}-{max(rs):.2f});"
                f" median CPU {med(w.cpu[k] for w in rows) * 1e3:.0f} ms, median peer {med(w.cpu['peer'] for w in rows) * 1e3:.0f} ms"
            )
        for name in ("turtlebot4", "pr2"):
            hit = [w for w in rows if name in w.label.lower()]
            for w in hit:
                print(f"{w.label}: " + ", ".join(f"{k} {w.ratio(k):.2f}" for k in sides))
    print(
        f"--version: sensorkit {version['sensorkit'] * 1e3:.0f} ms, xacro {version['xacro'] * 1e3:.0f} ms of CPU"
    )
    print(
        f"load average {' '.join(f'{v:.1f}' for v in os.getloadavg())}"
        f" (median over robots {med(w.load for w in rows) if rows else 0:.1f}); {seconds:.0f} s"
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
    ap.add_argument(
        "--baseline",
        type=Path,
        metavar="SENSORKIT",
        help="another sensorkit program (e.g. another checkout's .venv/bin/sensorkit) run in the same rounds",
    )
    ap.add_argument(
        "--floors",
        action="store_true",
        help="also time `import typer` alone and then xacro's CLI in-process: the least any"
        " typer CLI pays warm (reading a stored result) and cold (expanding with xacro)",
    )
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
    benchmark(robots, a.runs, a.baseline, a.floors)


if __name__ == "__main__":
    main()
