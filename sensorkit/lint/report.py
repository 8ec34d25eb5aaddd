"""Formatters: text (for people, grouped by sensor), json, sarif 2.1.0 and github."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable
from typing import Any

from sensorkit import __version__
from sensorkit.base.findings import Finding, Severity
from sensorkit.base.quote import clip, plural, shorten
from sensorkit.lint.engine import FileReport, Report
from sensorkit.lint.rules import RULES

FORMATS = ("text", "json", "sarif", "github")
HOME = "https://github.com/sensorkit/sensorkit"
_SARIF_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}


def _loc(f: Finding) -> str:
    if f.file is None:
        return "<unknown>"
    out = f.file
    if f.line:
        out += f":{f.line}"
        if f.column:
            out += f":{f.column}"
    return out


def format_text(report: Report, *, color: bool = False, quiet: bool = False) -> str:
    """Findings grouped per file, then per sensor (robot-wide findings last), each with its fix.

    ``quiet`` (``-q``): only files with findings, and no summary line.
    """
    styles = {Severity.ERROR: "31", Severity.WARNING: "33", Severity.INFO: "36"}

    def sev(s: Severity) -> str:
        return f"\x1b[{styles[s]}m{s.label}\x1b[0m" if color else s.label

    def bold(t: str) -> str:
        return f"\x1b[1m{t}\x1b[0m" if color else t

    lines: list[str] = []
    for fr in report.files:
        if fr.error:
            continue  # said once, on stderr, by the CLI
        if (quiet or fr.macro_only) and not fr.findings and not fr.internal_errors:
            continue  # -q: only files with findings; a macro-only file: counted below
        head = fr.display
        if fr.target:
            head += f" (target {fr.target}; {fr.target_reason}"
            head += f"; {fr.launch_note})" if fr.launch_note else ")"
        lines.append(bold(head))
        if fr.readable:
            lines.append(f"  --untrusted: reads only inside {', '.join(fr.readable)}")
        safe = {id(fr.findings[i]) for i, how in fr.fixable.items() if how == "safe"}
        groups: dict[str | None, list[Finding]] = defaultdict(list)
        for f in fr.findings:
            groups[f.sensor].append(f)
        order = [k for k in groups if k is not None] + ([None] if None in groups else [])
        for key in order:
            lines.append(f"  {'sensor ' + clip(key) if key else 'robot'}:")
            for f in groups[key]:
                mark = " [*]" if id(f) in safe else ""
                lines.append(f"    {_loc(f)}: {f.rule}{mark} {sev(f.severity)}: {f.message}")
                if f.fix:
                    lines.append(f"      fix: {f.fix}")
        if not fr.findings:
            lines.append(f"  ok: no findings ({plural(fr.sensor_count, 'sensor')} checked)")
        for err in fr.internal_errors:
            lines.append(f"  internal error: {shorten(err)}")
    if quiet:
        return "".join(f"{line}\n" for line in lines)
    s = report.summary()
    failed = sum(1 for fr in report.files if fr.error)
    skipped = len(report.skipped)
    checked = len(report.files) - failed - skipped
    counts = f"{plural(s['error'], 'error')}, {plural(s['warning'], 'warning')}, {s['info']} info"
    summary = f"{counts} in {plural(checked, 'file')}"
    if skipped:
        summary += f"; {plural(skipped, 'macro-only file')} skipped"
    if failed:  # never a clean-looking summary when a file could not be checked at all
        summary += f"; {plural(failed, 'file')} could not be checked (see above)"
    lines.append(summary + _fixable_note(report))
    return "\n".join(lines) + "\n"


def _fixable_note(report: Report) -> str:
    """``; N fixable with `--fix` (M more with `--unsafe-fixes`)``, as ruff counts them;
    nothing when no finding has a fix."""
    how = [v for fr in report.files for v in fr.fixable.values()]
    safe, unsafe = how.count("safe"), how.count("unsafe")
    if not safe and not unsafe:
        return ""
    more = f" ({unsafe} more with `--unsafe-fixes`)" if unsafe else ""
    return f"; {safe} fixable with `--fix`{more}"


def to_json(report: Report) -> dict[str, Any]:
    """The JSON output contract of rules.md (fields are only ever added)."""
    targets = {fr.target for fr in report.files if fr.target}
    return {
        "version": 1,
        "files": [fr.display for fr in report.files],
        "target": targets.pop() if len(targets) == 1 else ("mixed" if targets else None),
        "targets": {fr.display: fr.target for fr in report.files},
        "findings": [
            _finding_json(fr, i, f) for fr in report.files for i, f in enumerate(fr.findings)
        ],
        "errors": [{"file": fr.display, "message": fr.error} for fr in report.files if fr.error],
        "macro_only": [fr.display for fr in report.skipped],
        "summary": report.summary(),
        # --untrusted (issue 36): the folders each file's expansion could read
        "readable": {fr.display: fr.readable for fr in report.files if fr.readable},
    }


def _finding_json(fr: FileReport, index: int, f: Finding) -> dict[str, Any]:
    """A finding's JSON, with ``fixable``: ``"safe"`` (``--fix`` fixes it), ``"unsafe"``
    (with ``--unsafe-fixes``) or null (added in issue 27; fields are only ever added)."""
    return {**f.to_dict(), "fixable": fr.fixable.get(index)}


def format_json(report: Report) -> str:
    import json  # only the json and sarif formats: not on the common path

    return json.dumps(to_json(report), indent=2) + "\n"


def to_sarif(report: Report) -> dict[str, Any]:
    """SARIF 2.1.0 with stable ruleIds and the full rule table."""
    ids = sorted(RULES)
    index = {rid: i for i, rid in enumerate(ids)}
    rules = []
    for rid in ids:
        info = RULES[rid]
        level = "note" if info.severity == "info" else info.severity.split("/")[0]
        rules.append(
            {
                "id": rid,
                "name": rid,
                "shortDescription": {"text": info.title},
                "fullDescription": {"text": f"{info.title} (existing tool: {info.existing})"},
                "defaultConfiguration": {"level": level},
                "helpUri": f"{HOME}#rules",
            }
        )
    results = []
    for f in report.findings:
        text = f.message + (f" Fix: {f.fix}" if f.fix else "")
        result: dict[str, Any] = {
            "ruleId": f.rule,
            "ruleIndex": index[f.rule],
            "level": _SARIF_LEVEL[f.severity],
            "message": {"text": text},
        }
        if f.file:
            phys: dict[str, Any] = {"artifactLocation": {"uri": f.file.replace("\\", "/")}}
            if f.line:
                phys["region"] = {"startLine": f.line}
                if f.column:
                    phys["region"]["startColumn"] = f.column
            result["locations"] = [{"physicalLocation": phys}]
        props = {
            k: v
            for k, v in (
                ("link", f.link),
                ("joint", f.joint),
                ("sensor", f.sensor),
                ("frame", f.frame),
            )
            if v
        }
        if props:
            result["properties"] = props
        results.append(result)
    return {
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "sensorkit",
                        "version": __version__,
                        "informationUri": HOME,
                        "rules": rules,
                    }
                },
                "results": results,
                "invocations": [_invocation(report)],
            }
        ],
    }


def _invocation(report: Report) -> dict[str, Any]:
    """SARIF 3.20: a file sensorkit could not check is a failed execution with a
    toolExecutionNotification naming it (a viewer must not show a clean run)."""
    notes = [
        {
            "level": "error",
            "message": {"text": fr.error},
            "locations": [{"physicalLocation": {"artifactLocation": {"uri": fr.display}}}],
        }
        for fr in report.files
        if fr.error
    ]
    inv: dict[str, Any] = {"executionSuccessful": not notes}
    if notes:
        inv["toolExecutionNotifications"] = notes
    readable = {fr.display: fr.readable for fr in report.files if fr.readable}
    if readable:  # --untrusted (issue 36): the folders each file's expansion could read
        inv["properties"] = {"readable": readable}
    return inv


def format_sarif(report: Report) -> str:
    import json

    return json.dumps(to_sarif(report), indent=2) + "\n"


def _gh_escape(text: str, prop: bool = False) -> str:
    out = text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    if prop:
        out = out.replace(":", "%3A").replace(",", "%2C")
    return out


def format_github(report: Report) -> str:
    """GitHub Actions workflow commands (annotations)."""
    kinds = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}
    lines = []
    for fr in report.files:
        if fr.readable:
            where = _gh_escape("--untrusted: reads only inside " + ", ".join(fr.readable))
            lines.append(f"::notice file={_gh_escape(fr.display, True)},title=sensorkit::{where}")
        if fr.error:
            lines.append(
                f"::error file={_gh_escape(fr.display, True)},title=sensorkit::{_gh_escape(fr.error)}"
            )
    for f in report.findings:
        props = []
        if f.file:
            props.append(f"file={_gh_escape(f.file, True)}")
        if f.line:
            props.append(f"line={f.line}")
        if f.column:
            props.append(f"col={f.column}")
        props.append(f"title={_gh_escape(f.rule, True)}")
        text = f.message + (f" Fix: {f.fix}" if f.fix else "")
        lines.append(f"::{kinds[f.severity]} {','.join(props)}::{_gh_escape(text)}")
    return "\n".join(lines) + ("\n" if lines else "")


def render(report: Report, fmt: str, *, color: bool = False, quiet: bool = False) -> str:
    if fmt == "json":
        return format_json(report)
    if fmt == "sarif":
        return format_sarif(report)
    if fmt == "github":
        return format_github(report)
    return format_text(report, color=color, quiet=quiet)


def rule_table(fixable: Callable[[str], str]) -> str:
    """The Markdown rule table for the README, generated from the registry; ``fixable``
    says how ``--fix`` fixes a rule (``sensorkit.fix.fixable``, from the layer above).
    The SDF column says whether the rule runs on SDF models (``only``: on SDF alone;
    ``bag``: a rule of ``check-recording``, which reads a recording)."""
    lines = [
        "| id | severity | checks | existing tool | SDF | `--fix` |",
        "|---|---|---|---|---|---|",
    ]
    for rid in sorted(RULES):
        info = RULES[rid]
        fix = fixable(rid)
        sdf = "yes" if "sdf" in info.formats else ""
        if "recording" in info.formats:
            sdf = "bag"  # check-recording's rules: they read a recording
        elif "urdf" not in info.formats:
            sdf = "only"
        lines.append(
            f"| {rid} | {info.severity} | {info.title} | {info.existing} | {sdf} | {fix} |"
        )
    return "\n".join(lines) + "\n"
