"""summary.json and index.html for a preview.

index.html is self-contained: every picture is inlined as a base64 data URI, so the
file can be attached to a CI run or mailed on its own. Nothing is fetched from the
network. Depth and range arrays stay beside it as .npy files.
"""

from __future__ import annotations

import base64
import html
import json
import math
from typing import TYPE_CHECKING, Any

from sensorkit import __version__
from sensorkit.base.atomic import write_text

if TYPE_CHECKING:
    from pathlib import Path

    from sensorkit.render.result import PreviewResult, SensorPreview

__all__ = ["GENERATOR", "is_preview", "summary_dict", "write_index", "write_summary"]

GENERATOR = "sensorkit render preview"  # summary.json's "generator": what made this folder

CONVENTIONS = {
    "pixels": "0-based pixel centres: pixel (i, r) covers [i-0.5, i+0.5] x [r-0.5, r+0.5] (OpenCV, image_geometry)",
    "rendered_principal_point": (
        "Gazebo renders a symmetric frustum, optical axis at ((W-1)/2, (H-1)/2); with gz "
        "<lens><intrinsics>, at (cx-0.5, cy-0.5). The preview reproduces that exactly "
        "(pybullet's own projection would put it at (W/2, H/2-1))."
    ),
    "camera_info": "classic cx=(W+1)/2 (first pixel centre 1), gz cx=W/2 (first pixel centre 0.5); reprojection compares after that offset and reports the 0-based bias",
    "depth": "depth.npy: float32 H x W, metres along the optical axis (32FC1); +inf nothing within range, -inf nearer than the near clip",
    "ranges": "ranges.npy: float32 from angle_min to angle_max (vertical x horizontal for 3D lidars, lowest row first); +inf no return",
    "points": "points.npy: float32 V x H x 3 in the sensor's frame (x forward, y left, z up); NaN no return",
    "render_pose": "x forward, y left, z up, in the frame of the robot's root link (at the origin)",
}


def _rel(path: Path, base: Path) -> str:
    try:
        return path.relative_to(base).as_posix()
    except ValueError:
        return str(path)


def _clean(value: Any) -> Any:
    """JSON-safe: non-finite floats become strings ("inf", "-inf", "nan")."""
    if isinstance(value, float):
        return value if math.isfinite(value) else str(value)
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    return value


def _sensor_dict(s: SensorPreview, base: Path) -> dict[str, Any]:
    return {
        "name": s.name,
        "sensor": s.sensor,
        "type": s.type,
        "kind": s.kind,
        "link": s.link,
        "status": s.status,
        "skipped": s.skipped,
        "folder": _rel(s.directory, base) if s.directory else None,
        "files": {k: _rel(v, base) for k, v in s.files.items()},
        **{k: v for k, v in s.info.items() if k != "colour"},
        "checks": [c.to_dict() for c in s.checks],
        "findings": [f.to_dict() for f in s.findings],
        "notes": s.notes,
    }


def summary_dict(result: PreviewResult) -> dict[str, Any]:
    """Everything summary.json holds (JSON-ready: no NaN or infinity)."""
    base = result.out_dir
    findings = None if result.findings is None else [f.to_dict() for f in result.findings]
    out: dict[str, Any] = _clean(
        {
            "generator": GENERATOR,
            "sensorkit": __version__,
            "robot": result.robot,
            "file": str(result.source),
            "target": result.target,
            "target_reason": result.target_reason,
            "scene": result.scene,
            "joints": result.joints,
            "status": result.status,
            "verdict": result.verdict.to_dict(),
            "seconds": round(result.seconds, 3),
            "files": {k: _rel(v, base) for k, v in result.files.items()},
            "conventions": CONVENTIONS,
            "sensors": [_sensor_dict(s, base) for s in result.sensors],
            "validate": {"findings": findings, "error": result.findings_error},
            "pictures": {f.key: f.facts for f in result.figures},
            "notes": result.notes,
            "placement": result.placement,
        }
    )
    return out


def is_preview(folder: Path) -> bool:
    """Is ``folder`` an earlier preview, and nothing else? Its summary.json says sensorkit
    wrote it, and every entry in it is one that summary names (summary, overview, index,
    the sensors' folders): a file put there by hand makes it a folder to keep."""
    try:
        data = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return False
    if not isinstance(data, dict) or data.get("generator") != GENERATOR:
        return False
    named: set[str] = set()
    try:
        named.update(str(v).split("/")[0] for v in data["files"].values())
        named.update(str(s["folder"]).split("/")[0] for s in data["sensors"] if s.get("folder"))
        return all(entry.name in named for entry in folder.iterdir())
    except (OSError, KeyError, TypeError, AttributeError):
        return False


def write_summary(result: PreviewResult) -> None:
    text = json.dumps(summary_dict(result), indent=2, allow_nan=False) + "\n"
    write_text(result.files["summary"], text, fsync=False)


# ---- index.html ----------------------------------------------------------------------
_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:24px;color:#222;background:#fafafa;max-width:1400px}
h1{font-size:22px;margin:0 0 4px} h2{font-size:18px;margin:18px 0 6px;border-bottom:1px solid #ddd}
h3{font-size:15px;margin:16px 0 6px}
table{border-collapse:collapse;margin:6px 0;font-size:13px;background:#fff}
td,th{border:1px solid #ddd;padding:4px 8px;text-align:left;vertical-align:top}
th{background:#f0f0f0} .meta{color:#555;font-size:13px}
.ok{color:#17702a;font-weight:600} .warn{color:#a05a00;font-weight:600}
.fail,.error{color:#b3171b;font-weight:600} .skipped,.info{color:#777}
.warning{color:#a05a00;font-weight:600}
.imgs{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}
.imgs figure{margin:0;background:#fff;border:1px solid #ddd;padding:6px}
.imgs img{max-width:640px;image-rendering:pixelated;display:block}
figcaption{font-size:12px;color:#555;margin-top:4px;max-width:640px}
.swatch{display:inline-block;width:12px;height:12px;border-radius:2px;margin-right:6px;vertical-align:middle}
code{font-size:12px;background:#f1f1f1;padding:1px 4px;border-radius:3px}
.verdict{font-size:17px;font-weight:700;padding:10px 14px;margin:10px 0 4px;border-radius:4px;border:2px solid}
.verdict.fail{background:#fde8e8;border-color:#b3171b;color:#8a1014}
.verdict.pass{background:#e8f6ea;border-color:#17702a;color:#115420}
.verdict.never{background:#f0f0f0;border-color:#888;color:#333}
.verdict ul{font-size:13px;font-weight:400;margin:6px 0 0;padding-left:20px}
.rviz{border-color:#e600c8 !important}
.findings{font-size:13px;margin:4px 0 10px;padding-left:20px}
.sensors{display:grid;grid-template-columns:repeat(auto-fill,minmax(620px,1fr));gap:10px 18px}
.sensors .imgs img{max-width:280px} .sensors figure.rviz img{max-width:646px}
.sensors figcaption{max-width:646px}
.top-list{list-style:none;padding-left:0} .top-list li{margin:2px 0}
.finding summary,.verdict li{white-space:normal;overflow-wrap:anywhere}
.top{display:flex;gap:18px;align-items:flex-start} .top-findings{flex:1 1 0;min-width:320px}
details summary{cursor:pointer;font-size:13px;color:#333;margin:4px 0}
details summary h2{display:inline;border:0}
"""


def _text(text: str) -> str:
    """``text`` escaped, each number joined to its unit by a non-breaking space."""
    from sensorkit.render.svg import glue_units

    return html.escape(glue_units(text))


def _img(path: Path, alt: str, width: int | None = None) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    size = f' width="{width}"' if width else ""
    return f'<img alt="{html.escape(alt)}" src="data:image/png;base64,{data}"{size}>'


def _status(text: str) -> str:
    return f'<span class="{html.escape(text)}">{html.escape(text)}</span>'


def _fmt(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.6g}" if math.isfinite(value) else str(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_fmt(v) for v in value) + "]"
    return html.escape(str(value))


def _amount(value: Any, unit: str, decimals: int | None = None) -> str:
    """A number with its unit, as ``svg.quantity`` writes it (escaped; empty for None)."""
    from sensorkit.render.svg import quantity

    if not isinstance(value, (int, float)):
        return "" if value is None else _fmt(value)
    return html.escape(quantity(float(value), unit, decimals))


def _vec(values: Any, unit: str) -> str:
    from sensorkit.render.svg import vector

    if not isinstance(values, (list, tuple)):
        return _fmt(values)
    return html.escape(vector(list(values), unit))


def _sensor_html(s: SensorPreview, base: Path) -> str:
    e = html.escape
    colour = s.info.get("colour")
    swatch = f'<span class="swatch" style="background:{colour}"></span>' if colour else ""
    parts = [
        '<section class="sensor">',
        f'<h3 id="{e(s.name)}">{swatch}{e(s.name)} <span class="meta">{e(s.type)} on {e(str(s.link))}</span> {_status(s.status)}{_counts(s)}</h3>',
        _sensor_findings_html(s),
        _rviz_html(s),
    ]
    if s.skipped:
        parts.append(f"<p class='meta'>Not rendered: {e(s.skipped)}</p></section>")
        return "\n".join(parts)
    figures = _figures_html(s)
    if figures:
        parts.append('<div class="imgs">' + "".join(figures) + "</div>")
    facts = [*_frame_facts(s), *_camera_facts(s), *_scan_facts(s), *_file_facts(s, base)]
    parts.append(
        f"<details class='checks'><summary>{_checks_summary(s)}</summary>{_checks_html(s)}<table>"
        + "".join(f"<tr><th>{e(k)}</th><td>{v}</td></tr>" for k, v in facts)
        + "</table>"
    )
    if s.notes:
        parts.append(
            "<ul class='meta'>" + "".join(f"<li>{_text(n)}</li>" for n in s.notes) + "</ul>"
        )
    parts.append("</details></section>")
    return "\n".join(parts)


def _checks_summary(s: SensorPreview) -> str:
    """``checks: 4 ok, 1 warn (self_occlusion) · facts and files``: the collapsed line."""
    e = html.escape
    counts = []
    for status in ("fail", "warn", "ok", "skipped"):
        these = [c.name for c in s.checks if c.status == status]
        if these:
            named = f" ({e(', '.join(these))})" if status in ("fail", "warn") else ""
            counts.append(f"{len(these)} {_status(status)}{named}")
    return f"checks: {', '.join(counts) or 'none'} &middot; facts and files"


def _figures_html(s: SensorPreview) -> list[str]:
    """The sensor's pictures: rgb, depth and scan first (labelled where a figure is),
    then its other figures."""
    e = html.escape
    figures = []
    labelled = {"depth_png": "depth", "scan_png": "scan"}  # files shown by s.figures
    for key, caption in (
        ("rgb", "rgb.png"),
        ("depth_png", "depth.png (near warm, far blue; grey: nothing in range)"),
        ("scan_png", "scan.png (top-down, forward up)"),
    ):
        if labelled.get(key) in s.figures:
            figures.append(s.figures[labelled[key]].html())
        elif key in s.files:
            figures.append(
                f"<figure>{_img(s.files[key], caption)}<figcaption>{e(caption)}</figcaption></figure>"
            )
    figures += [f.html() for k, f in s.figures.items() if k not in labelled.values()]
    return figures


def _checks_html(s: SensorPreview) -> str:
    """The sensor's checks, one a row."""
    e = html.escape
    rows = "".join(
        f"<tr><td>{e(c.name)}</td><td>{_status(c.status)}</td><td>{_amount(c.value, c.unit)}</td>"
        f"<td>{_amount(c.limit, c.unit)}</td><td>{_text(c.message)}</td></tr>"
        for c in s.checks
    )
    return f"<table><tr><th>check</th><th>status</th><th>value</th><th>limit</th><th>what it means</th></tr>{rows}</table>"


# The facts table of a sensor: (heading, HTML) rows.
_Facts = list[tuple[str, str]]


def _frame_facts(s: SensorPreview) -> _Facts:
    """Where the sensor is rendered from and the frames its data is stamped with."""
    facts: _Facts = []
    frames = s.info.get("frames", {})
    if frames:
        pose = frames.get("render_pose", {})
        facts.append(
            (
                "render pose (xyz, rpy)",
                f"{_vec(pose.get('xyz'), 'm')}, {_vec(pose.get('rpy'), 'rad')}",
            )
        )
        facts.append(
            (
                "published frame",
                f"{_fmt(frames.get('published_frame'))} ({_fmt(frames.get('published_how'))})",
            )
        )
        if frames.get("camera_frame") != frames.get("published_frame"):
            facts.append(("image frame", _fmt(frames.get("camera_frame"))))
    return facts


def _camera_facts(s: SensorPreview) -> _Facts:
    """camera_info's K and what the simulator renders."""
    intr = s.info.get("intrinsics")
    if not intr:
        return []
    r = intr["rendered"]
    return [
        (
            "camera_info K",
            f"fx {_amount(intr['fx'], 'px')}, fy {_amount(intr['fy'], 'px')}, cx {_amount(intr['cx'], 'px')}, cy {_amount(intr['cy'], 'px')} ({html.escape(str(intr['convention']))})",
        ),
        (
            "rendered",
            f"fx {_amount(r['fx'], 'px')}, fy {_amount(r['fy'], 'px')}, principal point {_vec((r['cx'], r['cy']), 'px')} 0-based; clip {_amount(r['near'], 'm')} to {_amount(r['far'], 'm')}",
        ),
    ]


def _scan_facts(s: SensorPreview) -> _Facts:
    """A lidar's beams, and its rows for a 3D one."""
    scan = s.info.get("scan")
    if not scan:
        return []
    facts = [
        (
            "scan",
            f"{scan['samples']} beams, {_amount(scan['angle_min'], 'rad')} to {_amount(scan['angle_max'], 'rad')}, step {_amount(scan['angle_increment'], 'rad', 3)}, range {_amount(scan['range_min'], 'm')} to {_amount(scan['range_max'], 'm')}",
        )
    ]
    if "vertical" in s.info:
        v = s.info["vertical"]
        facts.append(
            (
                "vertical",
                f"{v['samples']} rows, {_amount(v['angle_min'], 'rad')} to {_amount(v['angle_max'], 'rad')}",
            )
        )
    return facts


def _file_facts(s: SensorPreview, base: Path) -> _Facts:
    """The sensor's topics, and its files, linked."""
    e = html.escape
    facts: _Facts = []
    if s.info.get("topics"):
        topics = s.info["topics"]
        facts.append(
            ("topics", ", ".join(f"{e(k)} <code>{e(v)}</code>" for k, v in topics.items()))
        )
    files = ", ".join(
        f'<a href="{e(_rel(p, base))}">{e(_rel(p, base))}</a>' for p in s.files.values()
    )
    facts.append(("files", files))
    return facts


def _counts(s: SensorPreview) -> str:
    """`` <span class="error">1 error</span>``: the sensor's findings by severity."""
    from sensorkit.render.gate import found_text

    out = ""
    for label in ("error", "warning", "info"):
        these = [f for f in s.findings if f.severity.label == label]
        if these:
            out += f' &middot; <span class="{label}">{found_text(these)}</span>'
    return out


def _sensor_findings_html(s: SensorPreview) -> str:
    """validate's findings about this sensor, at the top of its section."""
    if not s.findings:
        return ""
    e = html.escape
    rows = "".join(
        f"<li>{_status(f.severity.label)} <b>{e(f.rule)}</b> "
        f"<span class='meta'>{e(f'{f.file}:{f.line}' if f.line else f.file or '')}</span> {_text(f.message)}"
        + (f"<br><span class='meta'>fix: {e(f.fix)}</span>" if f.fix else "")
        + "</li>"
        for f in s.findings
    )
    return f"<ul class='findings' id='findings-{e(s.name)}'>{rows}</ul>"


def _rviz_html(s: SensorPreview) -> str:
    """What RViz will show, for a sensor whose data is stamped with another frame: rviz.png
    with, in each panel, its axes, a scale bar and the stamped frame's name."""
    if "rviz_png" not in s.files:
        return ""
    e = html.escape
    rviz = s.info.get("rviz", {})
    frame = rviz.get("frame", "?")
    caption = (
        f"What RViz will show: {s.name}'s data placed by the frame it is stamped with, "
        f"{frame!r} (magenta), beside where the sensor really sees it (its colour). Left: "
        "from above; right: from the side, along the sensor's heading."
    )
    panels = rviz.get("panels")
    picture = (
        _rviz_svg(s.files["rviz_png"].read_bytes(), frame, panels)
        if panels
        else _img(s.files["rviz_png"], "what RViz will show")
    )
    return (
        f"<div class='imgs'><figure class='rviz' id='rviz-{e(s.name)}'>"
        f"{picture}<figcaption>{_text(caption)}</figcaption></figure></div>"
    )


def _bar_length(room: float, px_per_m: float) -> float:
    """The longest 1, 2 or 5 x 10^k metres whose bar fits in ``room`` pixels (0: none)."""
    if not px_per_m > 0 or not math.isfinite(px_per_m):
        return 0.0
    raw = room / px_per_m
    base = 10.0 ** math.floor(math.log10(raw))
    return max(m * base for m in (1.0, 2.0, 5.0) if m * base <= raw * 1.0001)


def _rviz_svg(png: bytes, frame: str, panels: list[dict[str, Any]]) -> str:
    """rviz.png under a band of labels: per panel the view, the stamped frame, its two
    axes as arrows and a scale bar of a round length."""
    from sensorkit.render.rviz import PANEL
    from sensorkit.render.svg import Svg, metres

    w, h = PANEL
    band = 46  # below the picture: axes, scale bar, frame
    width = panels[-1]["x0"] + w
    svg = Svg(width, 20 + h + band)
    svg.image(png, 0, 20, width, h)
    for panel in panels:
        x0 = float(panel["x0"])
        view = "from above" if panel["view"] == "top" else "from the side"
        svg.text(x0 + 2, 14, f"{view}; magenta: in {frame!r}", size=12,
                 class_="rviz-frame")  # fmt: skip
        y = 20 + h + 20
        right, up = panel["axes"]
        svg.line((x0 + 8, y), (x0 + 38, y), "#222", 1.5, class_="axis")
        svg.line((x0 + 8, y), (x0 + 8, y - 16), "#222", 1.5, class_="axis")
        svg.text(x0 + 42, y + 4, right, size=12, class_="axis-name")
        svg.text(x0 + 12, y - 6, up, size=12, class_="axis-name")
        k = float(panel["px_per_m"])
        step = _bar_length(w - 8 - 110, k)  # right of the axis names
        if step > 0:
            bar = step * k
            xr = x0 + w - 8
            svg.line((xr - bar, y), (xr, y), "#222", 2.0, class_="scale-bar")
            svg.line((xr - bar, y - 4), (xr - bar, y + 4), "#222", 1.0)
            svg.line((xr, y - 4), (xr, y + 4), "#222", 1.0)
            svg.text(xr - bar / 2, y + 18, metres(step), size=12, anchor="middle",
                     class_="scale-label")  # fmt: skip
    return str(svg)


def _verdict_html(result: PreviewResult) -> str:
    e = html.escape
    v = result.verdict
    kind = "never" if v.fail_on == "never" else "fail" if v.failed else "pass"
    shown = v.reasons[:10]
    more = (
        f"<li>and {len(v.reasons) - len(shown)} more below</li>"
        if len(v.reasons) > len(shown)
        else ""
    )
    reasons = "".join(f"<li>{_text(r)}</li>" for r in shown) + more
    return (
        f"<div id='verdict' class='verdict {kind}'>{e(v.text)}"
        + (f"<ul>{reasons}</ul>" if reasons and kind != "pass" else "")
        + f"</div>\n<p class='meta' id='counts'>{e(v.counts_text)} &middot; --fail-on {e(v.fail_on)}</p>"
    )


def _findings_html(result: PreviewResult) -> str:
    e = html.escape
    if result.findings is None:
        return (
            f"<p class='meta'>validate did not run: {e(result.findings_error or 'unavailable')}</p>"
        )
    if not result.findings:
        return "<p class='ok'>validate found nothing to report.</p>"
    rows = []
    for f in sorted(result.findings, key=lambda f: (-int(f.severity), f.sort_key())):
        where = f"{f.file}:{f.line}" if f.line else (f.file or "")
        short = f"{f.file.rsplit('/', 1)[-1]}:{f.line}" if f.file and f.line else where
        about = f.sensor or f.link or f.joint or f.frame or ""
        fix = f"<br><span class='meta'>fix: {e(f.fix)}</span>" if f.fix else ""
        rows.append(
            f"<li><details class='finding'><summary>{_status(f.severity.label)} <b>{e(f.rule)}</b> "
            f"{e(about)} <span class='meta'>{e(short)}</span> {_text(f.message)}</summary>"
            f"<div class='meta'>{e(where)}</div>{_text(f.message)}{fix}</details></li>"
        )
    return "<ul class='findings top-list'>" + "".join(rows) + "</ul>"


def _pictures_html(result: PreviewResult) -> str:
    """Each stereo pair (sensorkit.render.mount_pictures); the robot close up stands
    beside the overview."""
    out = []
    for title, prefix in (("Stereo pairs", "stereo:"),):
        shown = [f.html() for f in result.figures if f.key.startswith(prefix)]
        if shown:
            out.append(f"<h2>{title}</h2><div class='imgs'>{''.join(shown)}</div>")
    return "\n".join(out)


def _overview_html(result: PreviewResult) -> str:
    """The overview figure (ticks, frame names, colour key), or the bare picture."""
    figure = next((f for f in result.figures if f.key == "overview"), None)
    if figure is not None:
        return figure.html()
    return f"<figure>{_img(result.files['overview'], 'overview')}</figure>"


def write_index(result: PreviewResult) -> None:
    e = html.escape
    base = result.out_dir
    legend = "".join(
        f"<tr><td><span class='swatch' style='background:{s.info['colour']}'></span><a href='#{e(s.name)}'>{e(s.name)}</a></td>"
        f"<td>{e(s.type)}</td><td>{_status(s.status)}{_counts(s)}</td></tr>"
        for s in result.sensors
        if "colour" in s.info
    )
    skipped = "".join(
        f"<tr><td><a href='#{e(s.name)}'>{e(s.name)}</a></td><td>{e(s.type)}</td><td>{_status(s.status)}</td></tr>"
        for s in result.sensors
        if "colour" not in s.info
    )
    joints = ", ".join(f"{e(k)}={v:g}" for k, v in result.joints.items()) or "all at zero"
    notes = "".join(f"<li>{_text(n)}</li>" for n in result.notes)
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>sensorkit preview: {e(result.robot)}</title>
<style>{_CSS}</style></head><body>
<h1>sensorkit preview: {e(result.robot)}</h1>
{_verdict_html(result)}
<p class="meta">{e(str(result.source))} &middot; target {e(result.target)} ({e(result.target_reason)}) &middot; scene {e(result.scene)}
&middot; joints {joints} &middot; sensorkit {e(__version__)} &middot; {result.seconds:.2f} s</p>
{f"<p class='warning' id='placement'>{e(result.placement)}</p>" if result.placement else ""}
<div class="top"><div class="top-findings"><h2 id="findings">validate's findings</h2>
{_findings_html(result)}
<table><tr><th>sensor</th><th>type</th><th>status</th></tr>{legend}{skipped}</table></div>
<div><h2>Overview</h2>{_overview_html(result)}</div></div>
<div class="imgs">{"".join(f.html() for f in result.figures if f.key == "closeup")}</div>
{_pictures_html(result)}
<h2>Sensors</h2>
<div class="sensors">{"".join(_sensor_html(s, base) for s in result.sensors) or "<p class='meta'>The robot has no sensors to render.</p>"}</div>
<details><summary><h2>Conventions</h2></summary>
<table>{"".join(f"<tr><th>{e(k)}</th><td>{e(v)}</td></tr>" for k, v in CONVENTIONS.items())}</table></details>
{f"<h2>Notes</h2><ul class='meta'>{notes}</ul>" if notes else ""}
<p class="meta">Files: <a href="summary.json">summary.json</a> &middot; <a href="overview.png">overview.png</a></p>
</body></html>
"""
    write_text(result.files["index"], page, fsync=False)
