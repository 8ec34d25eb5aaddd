"""Run the rules on robot descriptions: load, model, check, filter, suppress, sort.

The engine is the only place that touches files during validation (reading the
description, checking that referenced meshes exist); rules only read the model.
"""

from __future__ import annotations

import os
import traceback
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from sensorkit.errors import InputError, UsageError
from sensorkit.findings import Finding, Severity
from sensorkit.loading.document import display_path
from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.uris import resolve_uri
from sensorkit.model import load_robot
from sensorkit.model.frames import sensor_frames
from sensorkit.model.robot import Robot
from sensorkit.model.sdf import convert
from sensorkit.model.targets import TARGETS, detect_target, is_gz
from sensorkit.rules import RULES, Context, MissingFile
from sensorkit.rules.base import Bridge
from sensorkit.suppress import collect

if TYPE_CHECKING:
    from sensorkit.loading.untrusted import Untrusted


@dataclass
class Options:
    """What to check and how. ``select``/``ignore`` take ids or prefixes (``SK5``)."""

    target: str = "auto"
    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    fail_on: Severity = Severity.ERROR
    args: dict[str, str] = field(default_factory=dict)
    package_paths: tuple[str, ...] = ()
    timeout: float = 60.0
    bridges: tuple[str, ...] = ()  # ros_gz_bridge YAML files (none: look in the package's config/)
    untrusted: Untrusted | None = None  # --untrusted: see sensorkit.loading.untrusted

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

    @property
    def display(self) -> str:
        return display_path(self.path)


@dataclass
class Report:
    files: list[FileReport] = field(default_factory=list)

    @property
    def findings(self) -> list[Finding]:
        return [f for fr in self.files for f in fr.findings]

    def summary(self) -> dict[str, int]:
        out = {"error": 0, "warning": 0, "info": 0}
        for f in self.findings:
            out[f.severity.label] += 1
        return out

    def exit_code(self, fail_on: Severity) -> int:
        if any(fr.error or fr.internal_errors for fr in self.files):
            return 2
        return 1 if any(f.severity >= fail_on for f in self.findings) else 0


def find_missing_files(
    robot: Robot, resolver: PackageResolver
) -> tuple[list[MissingFile], list[Finding]]:
    """SK104 data (missing files) and SK103 findings (unknown packages in package:// URIs)."""
    base = robot.document.path.resolve().parent
    missing: list[MissingFile] = []
    findings: list[Finding] = []
    seen_pkg: set[str] = set()
    exists: dict[Path, bool] = {}
    for link in robot.links:
        for uri, src in link.meshes:
            target = resolve_uri(uri, base, resolver)
            path, pkg = target.path, target.missing_package
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


def load_bridges(robot: Robot, options: Options) -> Bridge:
    """The ros_gz_bridge entries that apply: --bridge files, else the package's config/."""
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
    return out


def check_robot(
    robot: Robot, options: Options, resolver: PackageResolver | None = None
) -> FileReport:
    """Run every selected rule on an already loaded robot."""
    report = FileReport(path=robot.document.path, robot=robot)
    if options.target == "auto":
        report.target, report.target_reason = detect_target(robot)
    else:
        report.target, report.target_reason = options.target, "chosen with --target"
    conv = convert(robot)
    bridge = load_bridges(robot, options) if is_gz(report.target) else None
    ctx = Context(
        robot=robot,
        target=report.target,
        conversion=conv,
        auto=options.target == "auto",
        bridge=bridge,
    )
    for s in robot.sensors:
        ctx.frames[id(s)] = sensor_frames(robot, s, report.target, conv)
    findings: list[Finding] = []
    if options.wants("SK104") or options.wants("SK103"):
        resolver = resolver or PackageResolver.from_options(
            list(options.package_paths), near=robot.document.path
        )
        ctx.missing_files, pkg_findings = find_missing_files(robot, resolver)
        findings.extend(pkg_findings)
    for info in RULES.values():
        if info.func is None or not options.wants(info.id):
            continue
        try:
            findings.extend(info.func(ctx))
        except Exception as exc:  # a bug of ours must not hide the other findings
            detail = (
                "".join(traceback.format_exception(exc))
                if os.environ.get("SENSORKIT_DEBUG")
                else repr(exc)
            )
            report.internal_errors.append(
                f"rule {info.id} failed on {robot.document.display}: {detail}"
            )
    report.findings = findings
    return report


def validate_file(path: Path, options: Options | None = None) -> FileReport:
    """Load, model and check one file. Unreadable input becomes ``FileReport.error``."""
    options = options or Options()
    try:
        loaded = load_robot(
            path,
            args=options.args,
            package_paths=options.package_paths,
            timeout=options.timeout,
            untrusted=options.untrusted,
        )
    except InputError as exc:
        return FileReport(path=path, error=str(exc))
    except RecursionError:
        return FileReport(
            path=path, error=f"{display_path(path)}: the document nests too deeply to read"
        )
    if loaded.robot is None:
        report = FileReport(path=path, findings=list(loaded.findings))
    else:
        report = check_robot(loaded.robot, options)
        report.findings = loaded.findings + report.findings
    report.findings = [f for f in report.findings if options.wants(f.rule)]
    _suppress(report)
    report.findings.sort(key=Finding.sort_key)
    return report


def _suppress(report: FileReport) -> None:
    files: list[tuple[str, Path]] = []
    if report.robot is not None:
        for f in report.robot.document.source_files():
            files.append((display_path(f), Path(f)))
    else:
        files.append((report.display, report.path))
    sup = collect(files)
    kept = [f for f in report.findings if not sup.suppressed(f)]
    report.suppressed = len(report.findings) - len(kept)
    report.findings = kept


def validate_paths(paths: Sequence[Path], options: Options | None = None) -> Report:
    """Validate several files in one call."""
    options = options or Options()
    return Report([validate_file(p, options) for p in paths])


__all__ = ["FileReport", "Options", "Report", "check_robot", "validate_file", "validate_paths"]
