"""Run the rules on robot descriptions: load, model, check, filter, suppress, sort.

The engine is the only place that touches files during validation (reading the
description, checking that referenced meshes exist); rules only read the model.
"""

from __future__ import annotations

import gc
import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from sensorkit.base.errors import InputError, UsageError
from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.lint.rules import RULES, Context, MissingFile, RuleInfo
from sensorkit.lint.rules.base import Bridge
from sensorkit.lint.suppress import collect
from sensorkit.loading.document import display_path
from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.uris import resolve_uri
from sensorkit.model import Loaded, load_robot
from sensorkit.model.frames import sensor_frames
from sensorkit.model.parts import Link
from sensorkit.model.robot import Robot
from sensorkit.model.sdf import Conversion, convert
from sensorkit.model.targets import TARGETS, detect_target, is_gz

if TYPE_CHECKING:
    from sensorkit.loading.bridge import BridgeTopic
    from sensorkit.loading.cache import ExpansionCache
    from sensorkit.loading.launch_facts import LaunchFacts
    from sensorkit.loading.untrusted import Untrusted


@dataclass
class Options:
    """What to check and how. ``select``/``ignore`` take ids or prefixes (``SK5``)."""

    target: str = "auto"
    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    fail_on: Severity | None = Severity.ERROR  # None: never (no finding fails)
    args: dict[str, str] = field(default_factory=dict)
    package_paths: tuple[str, ...] = ()
    timeout: float = 60.0
    bridges: tuple[str, ...] = ()  # ros_gz_bridge YAML files (none: look in the package's config/)
    untrusted: Untrusted | None = None  # --untrusted: see sensorkit.loading.untrusted
    target_origin: str = "--target"  # where a target other than auto came from
    # absolute path -> bytes read instead of that file (``-``: the robot read from stdin)
    overlay: dict[str, bytes] = field(default_factory=dict)
    # Bridge entries not on disk yet, read as if in the first bridge file: add-* checks
    # a sensor together with the entries the same add appends to the package's bridge.
    bridge_pending: tuple[BridgeTopic, ...] = ()
    launch: tuple[str, ...] = ()  # launch files given with --launch (none: the reader looks)
    # What the launch files say, when the caller has it already (tests, a re-check): used
    # instead of reading them.
    launch_facts: LaunchFacts | None = None
    # Where xacro expansions are looked up and kept (sensorkit.loading.cache); None: no
    # cache. Never used under --untrusted.
    cache: ExpansionCache | None = None
    # What --fix would do to each finding, worked out while the model is alive (the
    # findings' indexes -> "safe" or "unsafe"): the CLI passes the fix layer's answer
    # (``sensorkit.fix.marks``), which the lint layer cannot import. None: not asked.
    fixability: Callable[[FileReport, Options], dict[int, str]] | None = None

    def __post_init__(self) -> None:
        if not self.timeout >= 1:
            msg = f"--timeout {self.timeout:g}: give at least 1 second for one xacro expansion"
            raise UsageError(msg)
        if self.target not in ("auto", *TARGETS):
            msg = f"unknown target {self.target!r}: use auto, " + ", ".join(TARGETS)
            raise UsageError(msg)
        for item in (*self.select, *self.ignore):
            if not any(rid.startswith(item.upper()) for rid in RULES):
                msg = f"no rule matches {item!r} (rule ids look like SK502; prefixes like SK5 select a family)"
                raise UsageError(msg)

    def wants(self, rule_id: str) -> bool:
        if self.select and not any(rule_id.startswith(s.upper()) for s in self.select):
            return False
        return not any(rule_id.startswith(i.upper()) for i in self.ignore)


@dataclass
class FileReport:
    """Findings for one file, with what was validated."""

    path: Path
    findings: list[Finding] = field(default_factory=list)
    target: str | None = None
    target_reason: str = ""
    robot: Robot | None = None
    error: str | None = None  # the file could not be validated at all
    internal_errors: list[str] = field(default_factory=list)
    suppressed: int = 0
    sensors_checked: int = 0  # kept when ``robot`` is dropped (validate_paths)
    macro_only: bool = False  # a xacro that only defines macros/properties: nothing to check
    launch_note: str | None = None  # "bridges from launch/sim.launch.py": the launch files read
    fixable: dict[int, str] = field(default_factory=dict)  # index in findings -> safe/unsafe
    more_sensors: int = 0  # the sensors of an SDF world's models after the first (``robot``)
    # --untrusted: the readable area (packages.readable_area), named in the output's header
    readable: list[str] = field(default_factory=list)

    @property
    def display(self) -> str:
        return display_path(self.path)

    @property
    def sensor_count(self) -> int:
        if self.robot is not None:
            return len(self.robot.sensors) + self.more_sensors
        return self.sensors_checked + self.more_sensors


@dataclass
class Report:
    """The reports of the files one run validated, in input order."""

    files: list[FileReport] = field(default_factory=list)

    @property
    def findings(self) -> list[Finding]:
        return [f for fr in self.files for f in fr.findings]

    @property
    def skipped(self) -> list[FileReport]:
        """Macro-only xacro files given explicitly: nothing in them to check or say."""
        return [
            fr for fr in self.files if fr.macro_only and not fr.findings and not fr.internal_errors
        ]

    def summary(self) -> dict[str, int]:
        out = {"error": 0, "warning": 0, "info": 0}
        for f in self.findings:
            out[f.severity.label] += 1
        return out

    def exit_code(self, fail_on: Severity | None) -> int:
        """2 if a file could not be checked, else 1 if a finding is at ``fail_on`` or
        above (None: never), else 0."""
        if any(fr.error or fr.internal_errors for fr in self.files):
            return 2
        if fail_on is None:
            return 0
        return 1 if any(f.severity >= fail_on for f in self.findings) else 0


def find_missing_files(
    robot: Robot,
    resolver: PackageResolver,
    links: Iterable[Link] | None = None,
    seen_packages: set[str] | None = None,
) -> tuple[list[MissingFile], list[Finding]]:
    """SK104 data (missing files) and SK103 findings (unknown packages in package:// URIs).

    ``links`` (default: all) and ``seen_packages`` (packages already reported, updated)
    let a re-check look at new links only and say each package once, as a full run does.
    """
    if robot.sdf is not None:  # the SDF modules load only for an SDF robot
        from sensorkit.loading.sdf_files import element_file, resolve_mesh_uri
    base = robot.document.path.resolve().parent
    missing: list[MissingFile] = []
    findings: list[Finding] = []
    seen_pkg: set[str] = set() if seen_packages is None else seen_packages
    exists: dict[Path, bool] = {}
    for link in robot.links if links is None else links:
        holder = element_file(robot.document, link.element) if robot.sdf is not None else None
        for uri, src in link.meshes:
            if holder is not None:  # SDF: as gz-sim finds it, from the file holding it
                target = resolve_mesh_uri(uri, holder, resolver)
            else:
                target = resolve_uri(uri, base, resolver)
            path, pkg = target.path, target.missing_package
            if pkg is None and path is not None and uri.startswith("package://"):
                findings += _duplicate(resolver, uri, src, robot, seen_pkg)
            if pkg is not None:
                if pkg not in seen_pkg:
                    seen_pkg.add(pkg)
                    findings.append(
                        Finding(
                            "SK103",
                            Severity.ERROR,
                            f"{uri!r}: package {pkg!r} not found; searched: "
                            + "; ".join(resolver.searched()),
                            src,
                            link=link.name,
                            fix=f"pass --package-path {pkg}=DIR (the folder holding its package.xml) or --package-path WORKSPACE/src",
                        )
                    )
                continue
            if path is None:
                continue
            if path not in exists:
                exists[path] = path.is_file()
            if not exists[path]:
                missing.append(MissingFile(uri, src, f"no file at {path}", link.name))
    return missing, findings


def _duplicate(
    resolver: PackageResolver, uri: str, src: SourceRef, robot: Robot, seen: set[str]
) -> list[Finding]:
    """SK103 for a mesh's package found twice (said once, and not again when the
    expansion's own ``$(find)`` said it: input_findings.duplicate_findings)."""
    name = uri[len("package://") :].partition("/")[0]
    if name in seen or name in robot.document.packages:
        return []
    seen.add(name)
    dup = resolver.duplicate(name)
    if dup is None:
        return []
    from sensorkit.loading.input_findings import duplicate_finding

    return [duplicate_finding(dup, src, display_path)]


def load_launch(robot: Robot, options: Options) -> LaunchFacts | None:
    """What the robot's launch files say (``--launch`` files, else those the reader finds
    beside the robot), or None when nothing was read.

    The reader (sensorkit.loading.launch) is imported here, not at module level: a run
    with no launch file to read does not pay for it.
    """
    if options.launch_facts is not None:  # given (an empty one: none read, none looked for)
        return None if options.launch_facts.empty else options.launch_facts
    from sensorkit.loading import launch as reader
    from sensorkit.loading.packages import own_package

    # Where to look: the robot's package and its siblings (the workspace folder holding it);
    # --untrusted: only its readable area (packages.readable_area), never a folder above.
    pkg = own_package(robot.document.path)
    roots = [pkg.parent] if pkg is not None else [robot.document.path.resolve().parent]
    if options.untrusted is not None:
        from sensorkit.loading.packages import readable_area

        roots = [Path(r) for r in readable_area(robot.document.path, _named_folders(options))]
    paths: list[Path]
    if options.launch:
        paths = [Path(p) for p in options.launch]
    else:
        paths = reader.find_launch_files(robot.document.path, roots)
    if not paths:
        return None
    # --package-path NAME=DIR names a package's folder for FindPackageShare and $(find-pkg-share).
    named = {
        name: Path(folder).expanduser().resolve()
        for name, sep, folder in (p.partition("=") for p in options.package_paths)
        if sep and name and "/" not in name
    }
    facts = reader.read_launch(paths, roots=roots, package_paths=named)
    return None if facts.empty else facts


def _named_folders(options: Options) -> list[Path]:
    """The folders of the ``--package-path`` items (``NAME=DIR`` and ``DIR``)."""
    return [Path(p.partition("=")[2] or p).expanduser() for p in options.package_paths]


def launch_note(facts: LaunchFacts | None, bridge: Bridge | None) -> str | None:
    """What the text header says of the launch files read: ``bridges from
    config/bridge.yaml, launch/sim.launch.py`` (every bridge file, when a launch file adds
    to them) and ``launch files read: ...`` for the others; None when none was read."""
    if facts is None or facts.empty:
        return None
    parts: list[str] = []
    bridging = list(dict.fromkeys(t.file for t in facts.bridges))
    if bridging:
        files = bridge.files if bridge is not None else bridging
        parts.append("bridges from " + ", ".join(files))
    rest = [f for f in facts.files if f not in bridging]
    if rest:
        parts.append("launch files read: " + ", ".join(rest))
    return "; ".join(parts)


def load_bridges(robot: Robot, options: Options, launch: LaunchFacts | None = None) -> Bridge:
    """The ros_gz_bridge entries that apply: --bridge files, else the package's config/,
    and the bridges the launch files start (``launch``)."""
    from sensorkit.loading.bridge import BridgeError, find_bridge_files, read_bridge
    from sensorkit.loading.packages import own_package

    if options.bridges:
        paths = [Path(b) for b in options.bridges]
    else:
        pkg = own_package(robot.document.path)
        paths = find_bridge_files(pkg) if pkg is not None else []
    out = Bridge(files=[display_path(p) for p in paths])
    for p in paths:
        try:
            out.topics.extend(read_bridge(p, display_path(p)))
        except BridgeError as exc:
            raise UsageError(f"--bridge {exc}") from None
    out.topics.extend(options.bridge_pending)
    if launch is not None and launch.bridges:
        # A YAML given as --bridge (or found in config/) that a launch file also starts as
        # a bridge's config_file is one bridge: its entries are counted once (MOGI-ROS/
        # Week-9-10-Simple-arm@425c335:bme_ros2_simple_arm/launch/spawn_robot.launch.py:118-129
        # starts config/gz_bridge.yaml, the file robots.yaml passes as --bridge).
        given = set(out.files)
        for f in dict.fromkeys(t.file for t in launch.bridges):
            if f not in out.files:
                out.files.append(f)
        out.topics.extend(t for t in launch.bridges if t.file not in given)
    return out


@dataclass
class RuleRun:
    """What ``check_robot`` worked out for one robot, kept so that a re-check after a small
    addition (``sensorkit.edit.check``) can reuse it instead of starting over."""

    ctx: Context
    reason: str  # why this target
    resolver: PackageResolver | None  # None when SK103/SK104 are not selected
    seen_packages: set[str]  # packages SK103 has reported
    package_findings: list[Finding]  # SK103 from mesh URIs
    by_rule: dict[str, list[Finding]]  # each selected rule's findings, in rule order
    internal_errors: list[str]

    def findings(self) -> list[Finding]:
        return [*self.package_findings, *(f for fs in self.by_rule.values() for f in fs)]


def make_context(
    robot: Robot,
    options: Options,
    bridge: Bridge | bool | None = True,
    conversion: Conversion | None = None,
) -> tuple[Context, str]:
    """The rules' context for ``robot`` (target, conversion, frames) and why that target.

    ``bridge=True`` loads the bridge files a gz target reads; pass a Bridge (or None) to
    reuse what was loaded for the same file. ``conversion``: ``convert(robot)`` when the
    caller has it already.
    """
    if options.target == "auto":
        target, reason = detect_target(robot)
    else:
        target, reason = options.target, f"chosen with {options.target_origin}"
    conv = conversion if conversion is not None else convert(robot)
    launch = load_launch(robot, options)
    known: Bridge | None = None
    if is_gz(target):
        known = load_bridges(robot, options, launch) if bridge is True else bridge or None
    ctx = Context(
        robot=robot,
        target=target,
        conversion=conv,
        auto=options.target == "auto",
        bridge=known,
        launch=launch,
    )
    model = launch.spawn_name() if launch is not None else None
    for s in robot.sensors:
        ctx.frames[id(s)] = sensor_frames(robot, s, target, conv, model=model)
    return ctx, reason


def run_rule(ctx: Context, info: RuleInfo, errors: list[str]) -> list[Finding]:
    """One rule's findings; a rule that fails adds to ``errors`` instead."""
    if info.func is None:
        return []
    try:
        return list(info.func(ctx))
    except Exception as exc:  # a bug of ours must not hide the other findings
        import traceback

        detail = (
            "".join(traceback.format_exception(exc))
            if os.environ.get("SENSORKIT_DEBUG")
            else repr(exc)
        )
        errors.append(f"rule {info.id} failed on {ctx.robot.document.display}: {detail}")
        return []


def run_rules(robot: Robot, options: Options, resolver: PackageResolver | None = None) -> RuleRun:
    """Every selected rule on a loaded robot (``check_robot``, keeping what it computed)."""
    ctx, reason = make_context(robot, options)
    run = RuleRun(ctx, reason, None, set(), [], {}, [])
    wanted = [info for info in RULES.values() if options.wants(info.id) and info.runs_on(robot)]
    ids = {info.id for info in wanted}
    if "SK104" in ids or "SK103" in ids:
        run.resolver = resolver or PackageResolver.from_options(
            list(options.package_paths),
            near=robot.document.path,
            untrusted=options.untrusted is not None,
        )
        ctx.missing_files, run.package_findings = find_missing_files(
            robot, run.resolver, seen_packages=run.seen_packages
        )
    for info in wanted:
        if info.func is not None:
            run.by_rule[info.id] = run_rule(ctx, info, run.internal_errors)
    return run


def check_robot(
    robot: Robot, options: Options, resolver: PackageResolver | None = None
) -> FileReport:
    """Run every selected rule on an already loaded robot."""
    run = run_rules(robot, options, resolver)
    return FileReport(
        path=robot.document.path,
        robot=robot,
        target=run.ctx.target,
        target_reason=run.reason,
        findings=run.findings(),
        internal_errors=run.internal_errors,
        macro_only=robot.macros_only,
        launch_note=launch_note(run.ctx.launch, run.ctx.bridge),
    )


def load_as(path: Path, options: Options) -> Loaded:
    """Load and model ``path`` as ``options`` say: args, packages, timeout, trust, the
    overlay and the expansion cache. Raises InputError for unreadable input."""
    return load_robot(
        path,
        args=options.args,
        package_paths=options.package_paths,
        timeout=options.timeout,
        untrusted=options.untrusted,
        overlay=options.overlay or None,
        cache=options.cache,
        sdf=True,
    )


def validate_file(path: Path, options: Options | None = None) -> FileReport:
    """Load, model and check one file. Unreadable input becomes ``FileReport.error``."""
    options = options or Options()
    try:
        loaded = load_as(path, options)
    except InputError as exc:
        report = FileReport(path=path, error=str(exc))
    except RecursionError:
        report = FileReport(
            path=path, error=f"{display_path(path)}: the document nests too deeply to read"
        )
    else:
        report = validate_loaded(path, loaded, options, same_load=True)
    if options.untrusted is not None:
        from sensorkit.loading.packages import readable_area

        report.readable = [display_path(r) for r in readable_area(path, _named_folders(options))]
    return report


def validate_loaded(
    path: Path, loaded: Loaded, options: Options, *, same_load: bool = False
) -> FileReport:
    """``validate_file`` of ``path`` already loaded (as ``options`` says to load it): the
    same rules, filtering, suppression and order, without reading and modelling the
    file a second time (``sensorkit render preview`` validates the robot it rendered).
    ``same_load``: ``loaded`` came from ``load_as(path, options)``, so the rules look
    packages up with the load's resolver instead of scanning the package paths again."""
    resolver = loaded.resolver if same_load else None
    if loaded.robot is None:
        report = FileReport(path=path, findings=list(loaded.findings))
    else:
        report = check_robot(loaded.robot, options, resolver)
        report.findings = loaded.findings + report.findings
        for other in loaded.robots[1:]:  # an SDF world's other models
            more = check_robot(other, options, resolver)
            report.findings += more.findings
            report.internal_errors += more.internal_errors
            report.more_sensors += len(other.sensors)
    report.findings = [f for f in report.findings if options.wants(f.rule)]
    _suppress(report, options.overlay)
    report.findings.sort(key=Finding.sort_key)
    return report


def _suppress(report: FileReport, overlay: dict[str, bytes] | None = None) -> None:
    if not report.findings:  # nothing to suppress: the files need not be read
        report.suppressed = 0
        return
    files: list[tuple[str, Path]] = []
    if report.robot is not None:
        for f in report.robot.document.source_files():
            files.append((display_path(f), Path(f)))
    else:
        files.append((report.display, report.path))
    sup = collect(files, overlay)
    kept = [f for f in report.findings if not sup.suppressed(f)]
    report.suppressed = len(report.findings) - len(kept)
    report.findings = kept


def validate_one(path: Path, options: Options, *, keep: list[object] | None = None) -> FileReport:
    """``validate_file`` keeping only plain data: the model and XML tree are let go.

    ``sensorkit validate`` runs with the garbage collector disabled, so whatever reference
    cycles the model holds would stay until exit: a young-generation collection after each
    file frees them (it only looks at what this file allocated, a fraction of a
    millisecond on a small robot).

    ``keep``: a list that takes the model instead, with no collection. A process that
    exits without teardown right after (``sensorkit validate`` on its last file) so skips
    freeing it: tens of milliseconds on a 10,000-link robot.
    """
    report = validate_file(path, options)
    if options.fixability is not None and report.robot is not None and report.findings:
        report.fixable = options.fixability(report, options)
    if report.robot is not None:
        report.sensors_checked = len(report.robot.sensors)
        if keep is not None:
            keep.append(report.robot)
        report.robot = None
    if keep is None and not gc.isenabled():
        gc.collect(0)
    return report


__all__ = [
    "FileReport",
    "Options",
    "Report",
    "RuleRun",
    "check_robot",
    "load_as",
    "make_context",
    "run_rules",
    "validate_file",
    "validate_loaded",
    "validate_one",
]
