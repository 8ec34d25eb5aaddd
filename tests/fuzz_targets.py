"""What the fuzz runs do with a generated input, and what counts as a failure.

One function per target takes a :class:`~fuzz_strategies.FuzzInput` and a scratch folder
and returns a :class:`Outcome`. A failure is an *uncaught exception*: an exception other
than sensorkit's own (``SensorkitError``, or an ``OSError``, which the CLI turns into one
line and exit 2) escaping the API; ``internal_errors`` in a FileReport (or an add's
"validator internal error" note); a CLI exit code other than 0/1/2, a traceback in its
output, or a signal. add-* must in addition refuse with exit 2 and leave every file
byte-identical, or succeed and leave a file that still parses and loads and that holds
the original bytes with only the insertion added. Hangs are the caller's to time
(``run_bounded`` in-process, a watchdog in ``benchmarks/fuzz_long.py``).

Shared by ``tests/test_fuzz.py`` (short, in CI) and ``benchmarks/fuzz_long.py``.
"""

from __future__ import annotations

import contextlib
import gc
import inspect
import os
import shutil
import signal
import subprocess
import sys
import traceback
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from fuzz_strategies import XACRO_NS, FuzzInput
from lxml import etree

ROOT = Path(__file__).resolve().parent.parent
REGRESSIONS = ROOT / "tests" / "regressions" / "fuzz"
XACRO_TIMEOUT = 3.0  # validate's --timeout in fuzz runs: bombs are stopped quickly
# A target taking longer than this on one input is a hang (xacro expansions without a
# --timeout, as in add-*, export and render, wait up to 60 s: those cases draw no bombs).
BOUNDS = {"render": 60.0, "cli_subprocess": 90.0}
DEFAULT_BOUND = 30.0
RENDER_MAX_PIXELS = 64 * 64
RENDER_MAX_RAYS = 2000


class Hang(Exception):
    """Raised by ``run_bounded``'s alarm; targets let it through."""


@dataclass
class Outcome:
    """``problem`` is empty when sensorkit behaved; else one line saying what went wrong."""

    target: str
    problem: str = ""
    detail: str = ""  # a traceback or the output, for the report
    note: str = ""  # how it ended when fine: "ok", "refused", "exit 2", ...

    @property
    def ok(self) -> bool:
        return not self.problem


def bound(target: str) -> float:
    return BOUNDS.get(target, DEFAULT_BOUND)


# ------------------------------------------------------------------------------ helpers


def _clean_error(exc: BaseException) -> bool:
    from sensorkit.base.errors import SensorkitError

    return isinstance(exc, (SensorkitError, OSError))


def _crash(target: str, exc: BaseException) -> Outcome:
    tb = "".join(traceback.format_exception(exc))
    where = traceback.extract_tb(exc.__traceback__)[-1] if exc.__traceback__ else None
    at = f" at {Path(where.filename).name}:{where.lineno}" if where else ""
    return Outcome(target, f"{type(exc).__name__}{at}: {str(exc)[:200]}", tb)


def snapshot(folder: Path) -> dict[str, bytes]:
    out: dict[str, bytes] = {}
    for p in sorted(folder.rglob("*")):
        if p.is_file() and not p.is_symlink():
            out[str(p.relative_to(folder))] = p.read_bytes()
    return out


def _prefix_len(a: bytes, b: bytes) -> int:
    lo, hi = 0, min(len(a), len(b))
    while lo < hi:  # binary search on slice equality: memcmp speed on MB files
        mid = (lo + hi + 1) // 2
        if a[:mid] == b[:mid]:
            lo = mid
        else:
            hi = mid - 1
    return lo


def _one_insertion(old: bytes, new: bytes) -> bool:
    if len(new) < len(old):
        return False
    p = _prefix_len(old, new)
    s = _prefix_len(old[p:][::-1], new[p:][::-1])
    return p + s >= len(old)


def only_insertions(old: bytes, new: bytes) -> bool:
    """``new`` is ``old`` with one block inserted, and maybe the xacro namespace
    declaration added (in any of the encodings add-* writes)."""
    if _one_insertion(old, new):
        return True
    decl = f' xmlns:xacro="{XACRO_NS}"'
    for enc in ("utf-8", "utf-16-le", "utf-16-be", "utf-32-le", "utf-32-be"):
        d = decl.encode(enc)
        start = 0
        while (i := new.find(d, start)) != -1:
            if _one_insertion(old, new[:i] + new[i + len(d) :]):
                return True
            start = i + 1
    return False


def _parses(data: bytes) -> str | None:
    from lxml import etree

    from sensorkit.loading.document import strict_parser

    try:
        etree.fromstring(data, strict_parser())
    except etree.XMLSyntaxError as exc:
        return str(exc)
    return None


@contextlib.contextmanager
def _cwd(folder: Path) -> Iterator[None]:
    old = os.getcwd()
    os.chdir(folder)
    try:
        yield
    finally:
        os.chdir(old)


def _invoke(argv: list[str], cwd: Path) -> Any:
    from typer.testing import CliRunner

    from sensorkit.cli import app

    try:
        with _cwd(cwd):
            return CliRunner().invoke(app, argv)
    finally:
        gc.enable()  # `validate` switches the collector off for its short process


def _check_cli(target: str, res: Any, argv: list[str]) -> Outcome:
    exc = res.exception
    out = (res.stdout or "") + (res.stderr or "")
    shown = " ".join(argv[:2] if argv[0] == "render" else argv[:1])  # no paths: problems group
    if isinstance(exc, Hang):
        raise exc
    if exc is not None and not isinstance(exc, SystemExit):
        o = _crash(target, exc)
        o.problem = f"CLI `{shown}`: {o.problem}"
        o.detail = f"argv: {argv}\n{o.detail}"
        return o
    if res.exit_code not in (0, 1, 2):
        return Outcome(target, f"CLI `{shown}` exited {res.exit_code}", out[-3000:])
    if "Traceback (most recent call last)" in out:
        return Outcome(target, f"CLI `{shown}` printed a traceback", out[-3000:])
    if "internal error" in (res.stderr or ""):
        return Outcome(target, f"CLI `{shown}` reported an internal error", out[-3000:])
    return Outcome(target, note=f"exit {res.exit_code}")


# ------------------------------------------------------------------------------ targets


def _options(inp: FuzzInput, work: Path | None = None) -> Any:
    from sensorkit.base.findings import Severity
    from sensorkit.lint.engine import Options
    from sensorkit.loading.untrusted import Untrusted

    k = inp.knobs
    bridges: tuple[str, ...] = ()
    if k.get("bridge") is not None and work is not None:
        (work / "given_bridge.yaml").write_bytes(k["bridge"].encode("utf-8", "surrogateescape"))
        bridges = (str(work / "given_bridge.yaml"),)
    return Options(
        bridges=bridges,
        target=k.get("target", "auto"),
        select=tuple(k.get("select", ())),
        ignore=tuple(k.get("ignore", ())),
        fail_on=Severity.parse(k.get("fail_on", "error")),
        args=dict(inp.case.args),
        timeout=XACRO_TIMEOUT,
        untrusted=Untrusted() if k.get("untrusted") else None,
    )


def t_validate(inp: FuzzInput, work: Path) -> Outcome:
    """validate_file in-process, and the report rendered in the chosen format."""
    from sensorkit.lint.engine import Report, validate_file
    from sensorkit.lint.report import render

    path = inp.case.write(work)
    try:
        options = _options(inp, work)
        report = validate_file(path, options)
        text = render(Report([report]), inp.knobs.get("format", "text"), color=False)
        assert isinstance(text, str)
    except BaseException as exc:
        if isinstance(exc, (KeyboardInterrupt, Hang)):
            raise
        if not _clean_error(exc):  # a bad --bridge file is a usage error (exit 2)
            return _crash(inp.target, exc)
        return Outcome(inp.target, note="refused")
    if report.internal_errors:
        return Outcome(
            inp.target,
            f"internal_errors: {report.internal_errors[0][:300]}",
            "\n".join(report.internal_errors),
        )
    return Outcome(inp.target, note="error" if report.error else "ok")


def t_validate_paths(inp: FuzzInput, work: Path) -> Outcome:
    """validate_paths on the robot, every other file of the case, and a missing file."""
    from sensorkit.lint.fleet import validate_paths

    path = inp.case.write(work)
    others = [work / rel for rel in inp.case.files if (work / rel) != path][:4]
    try:
        report = validate_paths([path, *others, work / "missing.urdf"], _options(inp))
        report.exit_code(_options(inp).fail_on)
        report.summary()
    except BaseException as exc:
        if isinstance(exc, (KeyboardInterrupt, Hang)):
            raise
        return _crash(inp.target, exc)
    for fr in report.files:
        if fr.internal_errors:
            return Outcome(
                inp.target, f"internal_errors in {fr.path.name}: {fr.internal_errors[0][:300]}"
            )
    return Outcome(inp.target, note="ok")


def t_cli_validate(inp: FuzzInput, work: Path) -> Outcome:
    path = inp.case.write(work)
    k = inp.knobs
    argv = ["validate", str(path), "--format", k.get("format", "text"), "--target", k.get("target", "auto"),
            "--fail-on", k.get("fail_on", "error"), "--timeout", str(XACRO_TIMEOUT)]  # fmt: skip
    if k.get("untrusted"):
        argv.append("--untrusted")
    for s in k.get("select", ()):
        argv += ["--select", s]
    for s in k.get("ignore", ()):
        argv += ["--ignore", s]
    for name, value in inp.case.args.items():
        argv += ["--arg", f"{name}:={value}"]
    if k.get("bridge") is not None:
        (work / "given_bridge.yaml").write_bytes(k["bridge"].encode("utf-8", "surrogateescape"))
        argv += ["--bridge", str(work / "given_bridge.yaml")]
    if k.get("pyproject") is not None:
        (work / "pyproject.toml").write_bytes(k["pyproject"].encode("utf-8", "surrogateescape"))
    return _check_cli(inp.target, _invoke(argv, work), argv)


def _refused_by_ros(data: bytes) -> str | None:
    """The head of validate's SK101 message for an input ROS's readers refuse as a whole
    (an encoding other than UTF-8, a prefixed root element), or None."""
    from sensorkit.loading.input_findings import encoding_finding, prefixed_root_finding

    found = encoding_finding("input", data)
    if found is None:
        try:
            root = etree.fromstring(data, etree.XMLParser(resolve_entities=False, no_network=True))
        except etree.XMLSyntaxError:
            return None
        found = prefixed_root_finding(root, "input")
    return None if found is None else found.message.split(":", 1)[0]


def check_add(
    inp: FuzzInput,
    work: Path,
    before: dict[str, bytes],
    refused: bool,
    dry_run: bool,
    cwd: Path | None = None,
) -> Outcome:
    """The add-* contract: refused or dry -> every byte kept; done -> only insertions.

    The result is validated in ``cwd``, the folder the add ran in (None: this process's),
    as ``$(cwd)`` in a xacro resolves against it.
    """
    k = inp.knobs
    after = snapshot(work)
    main = inp.case.main
    if refused or dry_run:
        if after != before:
            changed = sorted(
                set(after) ^ set(before) | {f for f in before if after.get(f) != before[f]}
            )
            how = "refused" if refused else "a dry run"
            return Outcome(inp.target, f"{how} add changed files: {changed[:5]}")
        return Outcome(inp.target, note="refused" if refused else "dry run")
    out_rel = str(_output(Path(main))) if k.get("output") else main
    if k.get("output") and after.get(main) != before.get(main):
        return Outcome(inp.target, "add -o changed the source file")
    new = after.get(out_rel)
    if new is None:
        return Outcome(inp.target, "add reported success but wrote no file")
    if not only_insertions(before[main], new):
        return Outcome(
            inp.target,
            "add changed bytes outside its insertion",
            new.decode("utf-8", "replace")[-3000:],
        )
    why = _parses(new)
    if why:
        return Outcome(inp.target, f"add left a file that does not parse: {why}")
    macro_dir = str(Path(out_rel).parent / "sensors")
    for rel in set(after) - set(before):
        if rel != out_rel and not rel.startswith(macro_dir + "/"):
            return Outcome(inp.target, f"add left an unexpected file {rel}")
    for rel in set(before) & set(after):
        if rel not in (main, out_rel) and after[rel] != before[rel]:
            # add-* keeps a package in step (issue 12): the bridge YAML, robot.yaml and a
            # generated README gain the sensor; never with -o, and only by insertion
            if not k.get("output") and _package_file(rel):
                if only_insertions(before[rel], after[rel]):
                    continue
                return Outcome(inp.target, f"add changed bytes of {rel} outside an insertion")
            return Outcome(inp.target, f"add changed another file {rel}")
    from sensorkit.lint.engine import Options, validate_file

    with _cwd(cwd) if cwd is not None else contextlib.nullcontext():
        report = validate_file(
            work / out_rel, Options(args=dict(inp.case.args), timeout=XACRO_TIMEOUT * 5)
        )
    if report.robot is None and _refused_by_ros(before.get(main, b"")) in {
        f.message.split(":", 1)[0] for f in report.findings if f.rule == "SK101"
    }:
        # The input was already one ROS's readers refuse (UTF-16, a prefixed root): add
        # edits it byte for byte and says so in a note; validate still refuses it.
        return Outcome(inp.target, note="ok: the input was refused by ROS's readers before the add")
    if report.error or report.robot is None or report.internal_errors:
        detail = (
            report.error
            or "; ".join(f"{f.rule} {f.message}" for f in report.findings[:3])
            or str(report.internal_errors)
        )
        return Outcome(inp.target, f"the added file no longer validates: {detail[:300]}")
    return Outcome(inp.target, note="added")


def _package_file(rel: str) -> bool:
    """A file of a package that add-* may extend: a YAML (bridge, robot.yaml) or a README."""
    name = Path(rel).name
    return name == "README.md" or name.endswith((".yaml", ".yml"))


def _output(main: Path) -> Path:
    """Where ``-o`` writes: beside the robot, same suffixes (so it loads the same way)."""
    return main.parent / f"out_{main.name}"


def _request(inp: FuzzInput, path: Path) -> Any:
    from sensorkit.edit import AddRequest

    k = inp.knobs
    return AddRequest(
        path=path,
        kind=k["kind"],
        name=k["name"],
        parent=k["parent"],
        xyz=tuple(k["xyz"]),
        rpy=tuple(k["rpy"]),
        params=dict(k["params"]),
        output=_output(path) if k.get("output") else None,
        args=dict(inp.case.args),
    )


def t_add(inp: FuzzInput, work: Path) -> Outcome:
    """add_sensor in-process, then the add contract."""
    from sensorkit.edit import add_sensor

    path = inp.case.write(work)
    before = snapshot(work)
    refused = False
    notes: list[str] = []
    try:
        result = add_sensor(_request(inp, path), dry_run=bool(inp.knobs.get("dry_run")))
        notes = result.notes
    except BaseException as exc:
        if isinstance(exc, (KeyboardInterrupt, Hang)):
            raise
        if not _clean_error(exc):
            return _crash(inp.target, exc)
        refused = True
    internal = [n for n in notes if "internal error" in n]
    if internal:
        return Outcome(inp.target, f"add noted {internal[0][:300]}")
    return check_add(inp, work, before, refused, bool(inp.knobs.get("dry_run")))


_ADD_COMMANDS = {
    "camera": ["add-camera"],
    "depth_camera": ["add-depth-camera"],
    "lidar_2d": ["add-lidar"],
    "lidar_3d": ["add-lidar", "--3d"],
    "stereo_camera": ["add-stereo"],
    "imu": ["add-imu"],
}


def _own_options(kind: str) -> set[str]:
    from sensorkit.cli import edit

    func = {"camera": edit.add_camera, "depth_camera": edit.add_depth_camera, "lidar_2d": edit.add_lidar,
            "lidar_3d": edit.add_lidar, "stereo_camera": edit.add_stereo, "imu": edit.add_imu}[kind]  # fmt: skip
    return set(inspect.signature(func).parameters) - {
        "file",
        "name",
        "parent",
        "xyz",
        "rpy",
        "param",
        "diff",
        "output",
        "arg",
        "package_path",
    }


def add_argv(inp: FuzzInput, path: Path) -> list[str]:
    k = inp.knobs
    argv = [*_ADD_COMMANDS[k["kind"]], str(path), f"--name={k['name']}", f"--parent={k['parent']}"]
    argv += [
        "--xyz",
        *(repr(float(v)) for v in k["xyz"]),
        "--rpy",
        *(repr(float(v)) for v in k["rpy"]),
    ]
    own = _own_options(k["kind"])
    for key, value in k["params"].items():
        if key in own and key != "size" and "\n" not in value:
            argv.append(f"--{key.replace('_', '-')}={value}")
        elif key == "size" and len(value.split()) == 3:
            argv += ["--size", *value.split()]
        else:
            argv += ["--param", f"{key}={value}"]
    if k.get("output"):
        argv += ["-o", str(_output(path))]
    if k.get("dry_run"):
        argv.append("--diff")
    for name, value in inp.case.args.items():
        argv += ["--arg", f"{name}:={value}"]
    return argv


def t_cli_add(inp: FuzzInput, work: Path) -> Outcome:
    """add-* through the CLI (typer's CliRunner), then the add contract."""
    path = inp.case.write(work)
    before = snapshot(work)
    argv = add_argv(inp, path)
    res = _invoke(argv, work)
    cli = _check_cli(inp.target, res, argv)
    if not cli.ok:
        return cli
    if res.exit_code not in (0, 2):
        return Outcome(
            inp.target, f"add exited {res.exit_code} (0: added, 2: refused)", res.stderr[-2000:]
        )
    if "internal error" in res.stderr:
        return Outcome(inp.target, "add noted a validator internal error", res.stderr[-2000:])
    return check_add(
        inp, work, before, res.exit_code == 2, bool(inp.knobs.get("dry_run")), cwd=work
    )


def t_intrinsics(inp: FuzzInput, work: Path) -> Outcome:
    """intrinsics as the command does it (load, describe, select, document), and via the CLI."""
    from sensorkit.describe.sensorinfo import describe, load
    from sensorkit.exporters.documents import intrinsics_document, select_cameras

    path = inp.case.write(work)
    k = inp.knobs
    try:
        robot = load(path, args=inp.case.args)
        info = describe(robot, k.get("target", "auto"), convention=k.get("convention"))
        cameras = select_cameras(info, k.get("sensor"), k.get("format", "json"))
        text, _ = intrinsics_document(info, cameras, k.get("format", "json"))
        assert isinstance(text, str)
        note = "ok"
    except BaseException as exc:
        if isinstance(exc, (KeyboardInterrupt, Hang)):
            raise
        if not _clean_error(exc):
            return _crash(inp.target, exc)
        note = "refused"
    if k.get("cli"):
        argv = [
            "intrinsics",
            str(path),
            "--format",
            k.get("format", "json"),
            "--target",
            k.get("target", "auto"),
        ]
        if k.get("sensor") is not None:
            argv.append(f"--sensor={k['sensor']}")
        if k.get("convention") is not None:
            argv += ["--convention", k["convention"]]
        for name, value in inp.case.args.items():
            argv += ["--arg", f"{name}:={value}"]
        return _check_cli(inp.target, _invoke(argv, work), argv)
    return Outcome(inp.target, note=note)


def t_export(inp: FuzzInput, work: Path) -> Outcome:
    """export as the command does it (describe, plan, publish into a folder), and via the CLI."""
    from sensorkit.describe.sensorinfo import describe, load
    from sensorkit.exporters.robot import export_files, publish_export

    path = inp.case.write(work)
    k = inp.knobs
    out = work / "export_out"
    if k.get("existing"):  # --out already holds something: refused, or replaced with --force
        out.mkdir()
        (out / "old.txt").write_text("an earlier export")
    try:
        robot = load(path, args=inp.case.args)
        info = describe(robot, k.get("target", "auto"))
        plan = export_files(info)
        publish_export(plan.files, out, force=bool(k.get("force")), inputs=[path])
        note = "ok"
    except BaseException as exc:
        if isinstance(exc, (KeyboardInterrupt, Hang)):
            raise
        if not _clean_error(exc):
            return _crash(inp.target, exc)
        note = "refused"
    if k.get("cli"):
        argv = ["export", str(path), "--out", str(out), "--target", k.get("target", "auto")]
        if k.get("force"):
            argv.append("--force")
        for name, value in inp.case.args.items():
            argv += ["--arg", f"{name}:={value}"]
        return _check_cli(inp.target, _invoke(argv, work), argv)
    return Outcome(inp.target, note=note)


def _float(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        return float("nan")


def t_render(inp: FuzzInput, work: Path) -> Outcome:
    """render preview on a tiny robot: the API (one worker) or the CLI (forked workers)."""
    path = inp.case.write(work)
    k = inp.knobs
    if k.get("cli"):
        argv = ["render", "preview", str(path), "--out", str(work / "preview_cli"),
                "--max-pixels", str(RENDER_MAX_PIXELS), "--max-rays", str(RENDER_MAX_RAYS),
                "--target", k.get("target", "auto")]  # fmt: skip
        for name in k.get("sensors", ()):
            argv.append(f"--sensor={name}")
        for name, value in k.get("joints", {}).items():
            argv.append(f"--joint={name}={value}")
        return _check_cli(inp.target, _invoke(argv, work), argv)
    from sensorkit.render import render_preview

    try:
        render_preview(
            path,
            work / "preview",
            args=inp.case.args,
            target=k.get("target", "auto"),
            sensors=tuple(k.get("sensors", ())),
            joints={n: _float(v) for n, v in k.get("joints", {}).items()},
            workers=1,
            max_pixels=RENDER_MAX_PIXELS,
            max_rays=RENDER_MAX_RAYS,
        )
    except BaseException as exc:
        if isinstance(exc, (KeyboardInterrupt, Hang)):
            raise
        if not _clean_error(exc):
            return _crash(inp.target, exc)
        return Outcome(inp.target, note="refused")
    return Outcome(inp.target, note="ok")


def t_cli_subprocess(inp: FuzzInput, work: Path) -> Outcome:
    """``python -m sensorkit ...`` in a fresh process, in the case's folder (its pyproject)."""
    path = inp.case.write(work)
    k = inp.knobs
    if k.get("pyproject") is not None:
        (work / "pyproject.toml").write_bytes(k["pyproject"].encode("utf-8", "surrogateescape"))
    command = k.get("command", "validate")
    if command == "validate":
        argv = [
            "validate",
            str(path),
            "--timeout",
            str(XACRO_TIMEOUT),
            "--format",
            k.get("format", "text"),
        ]
    elif command == "add":
        argv = add_argv(inp, path)
    elif command == "intrinsics":
        argv = ["intrinsics", str(path)]
    elif command == "export":
        argv = ["export", str(path), "--out", str(work / "export_sub")]
    else:
        argv = ["render", "preview", str(path), "--out", str(work / "preview_sub"),
                "--max-pixels", str(RENDER_MAX_PIXELS), "--max-rays", str(RENDER_MAX_RAYS)]  # fmt: skip
    before = snapshot(work) if command == "add" else {}
    env = {key: v for key, v in os.environ.items() if key != "SENSORKIT_DEBUG"}
    env["PYTHONPATH"] = str(ROOT)
    try:
        res = subprocess.run(
            [sys.executable, "-m", "sensorkit", *argv], cwd=work, env=env, capture_output=True,
            text=True, errors="replace", timeout=bound("cli_subprocess") - 5, check=False,
        )  # fmt: skip
    except subprocess.TimeoutExpired:
        return Outcome(
            inp.target,
            f"`sensorkit {command}` did not finish within {bound('cli_subprocess') - 5:g} s",
        )
    shown = " ".join(argv[:2] if argv[0] == "render" else argv[:1])
    if res.returncode < 0:
        return Outcome(
            inp.target, f"`sensorkit {shown}` died of signal {-res.returncode}", res.stderr[-3000:]
        )
    if res.returncode not in (0, 1, 2):
        return Outcome(
            inp.target, f"`sensorkit {shown}` exited {res.returncode}", res.stderr[-3000:]
        )
    if "Traceback (most recent call last)" in res.stderr or "internal error" in res.stderr:
        return Outcome(
            inp.target,
            f"`sensorkit {shown}` printed a traceback or internal error",
            res.stderr[-3000:],
        )
    if command == "add":
        if res.returncode == 1:
            return Outcome(inp.target, "add exited 1 (0: added, 2: refused)", res.stderr[-2000:])
        return check_add(inp, work, before, res.returncode == 2, bool(k.get("dry_run")), cwd=work)
    return Outcome(inp.target, note=f"exit {res.returncode}")


TARGETS: dict[str, Callable[[FuzzInput, Path], Outcome]] = {
    "validate": t_validate,
    "validate_paths": t_validate_paths,
    "cli_validate": t_cli_validate,
    "add": t_add,
    "cli_add": t_cli_add,
    "intrinsics": t_intrinsics,
    "export": t_export,
    "render": t_render,
    "cli_subprocess": t_cli_subprocess,
}


# ------------------------------------------------------------------------------ running


def run(inp: FuzzInput, scratch: Path | None = None) -> Outcome:
    """Run one input in a fresh folder (removed afterwards); never raises."""
    import tempfile

    work = Path(tempfile.mkdtemp(prefix="skfuzz-", dir=scratch))
    try:
        return TARGETS[inp.target](inp, work)
    except Hang:
        raise
    except BaseException as exc:  # the oracle itself must not stop a run
        if isinstance(exc, (KeyboardInterrupt, Hang)):
            raise
        return _crash(inp.target, exc)
    finally:
        with contextlib.suppress(OSError):
            for p in work.rglob("*"):
                if p.is_dir() and not p.is_symlink():
                    p.chmod(0o755)
        shutil.rmtree(work, ignore_errors=True)


def run_bounded(inp: FuzzInput, seconds: float | None = None) -> Outcome:
    """``run`` with a wall-clock bound (SIGALRM; main thread only): over it is a hang."""
    limit = seconds or bound(inp.target)

    def alarm(signum: int, frame: object) -> None:
        raise Hang

    old = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, limit)
    try:
        return run(inp)
    except Hang:
        return Outcome(inp.target, f"hang: no answer within {limit:g} s")
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def save_regression(inp: FuzzInput, outcome: Outcome, folder: Path = REGRESSIONS) -> Path:
    """Keep a failing input as ``<target>-<hash>.json`` (the replay test runs it)."""
    import hashlib

    text = inp.dumps()
    digest = hashlib.sha256(text.encode()).hexdigest()[:12]
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{inp.target}-{digest}.json"
    if not path.exists():
        data = text[:-1] + f',\n "problem": {_json_str(outcome.problem)}\n}}\n'
        path.write_text(data)
    return path


def _json_str(s: str) -> str:
    import json

    return json.dumps(s, ensure_ascii=True)


def load_regression(path: Path) -> FuzzInput:
    return FuzzInput.loads(path.read_text())
