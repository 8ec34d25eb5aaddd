"""``sensorkit lsp`` driven as an editor drives it: a subprocess spoken to in JSON-RPC
over stdin/stdout (tests/lsp_client.py frames the messages itself).

initialize, didOpen (a finding with its code, line, file, severity and source), didChange
of an unsaved buffer (the finding cleared; the disk never read for it nor written), a
finding in an included file published for that file and seen through an unsaved include,
a quick fix whose edit removes the finding, hover on a sensor, shutdown and exit 0.
"""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

pytest.importorskip("pygls", reason="sensorkit-ros[lsp] is part of the test extra")

from lsp_client import Client, Message, apply_edits, uri
from test_fix import CAMERA_XACRO, OPTICAL, _package, _top, robot

APPROX = "-1.57 0 -1.57"


@pytest.fixture
def ws(tmp_path: Path) -> Path:
    (tmp_path / "sensorkit.toml").write_text('target = "classic"\n')
    return tmp_path


@pytest.fixture
def client(ws: Path) -> Iterator[Client]:
    c = Client(cwd=ws)
    try:
        c.initialize(ws)
        yield c
    finally:
        c.kill()


def line_of(text: str, needle: str) -> int:
    """0-based line of the first line holding ``needle``."""
    return next(i for i, line in enumerate(text.split("\n")) if needle in line)


def only(diags: list[Message], code: str) -> list[Message]:
    return [d for d in diags if d.get("code") == code]


def test_diagnostics_follow_the_unsaved_buffer_and_a_quick_fix_clears_them(
    ws: Path, client: Client
) -> None:
    path = ws / "rover.urdf"
    bad = robot(optical=APPROX)
    path.write_text(bad)
    client.open(path, version=1)
    (d,) = only(client.diagnostics(path, 1), "SK505")
    assert d["source"] == "sensorkit"
    assert d["severity"] == 3  # info -> Information
    assert d["range"]["start"]["line"] == line_of(bad, '<joint name="camera_optical_joint"')
    start, end = d["range"]["start"]["character"], d["range"]["end"]["character"]
    row = bad.split("\n")[d["range"]["start"]["line"]]
    assert row[start:end] == '<joint name="camera_optical_joint" type="fixed">'
    assert "fix:" in d["message"]

    # a buffer that fixes it, not saved: cleared
    good = robot(optical=OPTICAL)
    client.change(path, good, 2)
    assert only(client.diagnostics(path, 2), "SK505") == []
    assert path.read_text() == bad

    # back to the finding, then the quick fix the server offers for it
    client.change(path, bad, 3)
    (d,) = only(client.diagnostics(path, 3), "SK505")
    actions = client.request(
        "textDocument/codeAction",
        {
            "textDocument": {"uri": uri(path)},
            "range": d["range"],
            "context": {"diagnostics": [d]},
        },
    )
    (action,) = [a for a in actions if a["kind"] == "quickfix"]
    assert action["diagnostics"][0]["code"] == "SK505"
    changes = action["edit"]["changes"]
    assert list(changes) == [uri(path)]
    fixed = apply_edits(bad, changes[uri(path)])
    assert f'rpy="{OPTICAL}"' in fixed
    assert path.read_text() == bad  # the server never writes
    fix_all = client.request(
        "textDocument/codeAction",
        {
            "textDocument": {"uri": uri(path)},
            "range": d["range"],
            "context": {"diagnostics": [], "only": ["source.fixAll"]},
        },
    )
    (every,) = fix_all
    assert every["kind"] == "source.fixAll.sensorkit"
    assert apply_edits(bad, every["edit"]["changes"][uri(path)]) == fixed
    client.change(path, fixed, 4)
    assert only(client.diagnostics(path, 4), "SK505") == []

    # what `validate --fix` writes is what the quick fix made
    from sensorkit.fix.apply import fix_paths
    from sensorkit.lint.engine import Options

    fix_paths([path], Options(target="classic"))
    assert path.read_text() == fixed

    assert client.close() == 0


def test_a_finding_in_an_include_goes_to_that_file(ws: Path, client: Client) -> None:
    pkg = _package(ws / "src" / "rover_description", "rover_description")
    cam = pkg / "urdf" / "sensors" / "camera.urdf.xacro"
    cam.parent.mkdir(parents=True)
    cam.write_text(CAMERA_XACRO)
    top = pkg / "urdf" / "rover.urdf.xacro"
    top.write_text(_top("sensors/camera.urdf.xacro"))
    client.open(top, version=1)
    assert only(client.diagnostics(top, 1), "SK505") == []
    (d,) = only(client.diagnostics(cam), "SK505")
    assert d["range"]["start"]["line"] == line_of(
        CAMERA_XACRO, '<joint name="camera_optical_joint"'
    )
    assert d["severity"] == 3 and d["source"] == "sensorkit"

    # the fix, asked from the include, edits the include
    actions = client.request(
        "textDocument/codeAction",
        {"textDocument": {"uri": uri(cam)}, "range": d["range"], "context": {"diagnostics": [d]}},
    )
    (action,) = [a for a in actions if a["kind"] == "quickfix"]
    assert list(action["edit"]["changes"]) == [uri(cam)]
    fixed = apply_edits(CAMERA_XACRO, action["edit"]["changes"][uri(cam)])
    assert 'rpy="${-pi/2} 0 ${-pi/2}"' in fixed

    # the include opened and fixed in its buffer, unsaved: the top sees it, cleared
    client.open(cam, version=1)
    client.diagnostics(cam, 1)
    client.change(cam, fixed, 2)
    assert only(client.diagnostics(cam, 2), "SK505") == []
    assert cam.read_text() == CAMERA_XACRO

    # back to the finding; the robot closed: the include's finding goes with it
    client.change(cam, CAMERA_XACRO, 3)
    assert only(client.diagnostics(cam, 3), "SK505")
    client.close_document(top)
    assert client.diagnostics(cam, 3) == []
    assert client.close() == 0


def test_hover_on_a_sensor_says_its_topics_and_intrinsics(ws: Path, client: Client) -> None:
    path = ws / "rover.urdf"
    text = robot()
    path.write_text(text)
    client.open(path)
    client.diagnostics(path, 1)

    def hover(line: int) -> str | None:
        got = client.request(
            "textDocument/hover",
            {"textDocument": {"uri": uri(path)}, "position": {"line": line, "character": 5}},
        )
        return None if got is None else str(got["contents"]["value"])

    said = hover(line_of(text, '<sensor name="front_camera"'))
    assert said is not None
    assert "/front_camera/image_raw" in said and "/front_camera/camera_info" in said
    assert "camera_optical_frame" in said and "rgb8" in said and "640x480" in said
    assert "sensorkit.toml" in said  # the target came from the settings file
    assert hover(line_of(text, '<gazebo reference="camera_link"')) == said
    assert hover(line_of(text, '<link name="base_link"')) is None
    assert client.close() == 0


def test_an_sdf_model_is_validated_as_it_is_typed(ws: Path, client: Client) -> None:
    path = ws / "model.sdf"
    good = '<sdf version="1.9">\n<model name="m">\n<link name="base_link"/>\n</model>\n</sdf>\n'
    path.write_text(good)
    client.open(path, version=1)
    assert client.diagnostics(path, 1) == []
    client.change(path, good.replace("</model>", "</modle>"), 2)
    (d,) = only(client.diagnostics(path, 2), "SK101")
    assert d["range"]["start"]["line"] == 3
    client.change(path, good, 3)
    assert client.diagnostics(path, 3) == []
    assert client.close() == 0


def test_a_bad_settings_file_is_a_diagnostic_not_a_crash(ws: Path, client: Client) -> None:
    (ws / "sensorkit.toml").write_text('target = "gazebo11"\n')
    path = ws / "rover.urdf"
    path.write_text(robot())
    client.open(path)
    (d,) = client.diagnostics(path, 1)
    assert "gazebo11" in d["message"] and d["severity"] == 1
    (ws / "sensorkit.toml").write_text('target = "classic"\n')
    client.change(path, robot(optical=APPROX), 2)
    assert only(client.diagnostics(path, 2), "SK505")
    assert client.close() == 0


def test_without_pygls_lsp_says_how_to_install_it(monkeypatch: pytest.MonkeyPatch) -> None:
    from typer.testing import CliRunner

    from sensorkit.cli import app

    monkeypatch.setitem(sys.modules, "pygls", None)
    result = CliRunner().invoke(app, ["lsp"])
    assert result.exit_code == 2
    assert result.stderr.strip().splitlines() == [
        "sensorkit: lsp needs pygls, which is not installed: pip install 'sensorkit-ros[lsp]' "
        "(from a clone: pip install './sensorkit[lsp]'; with pipx: pipx inject sensorkit-ros pygls)"
    ]


def test_the_plain_cli_does_not_import_pygls(tmp_path: Path) -> None:
    code = (
        "import sys\n"
        "sys.argv = ['sensorkit', 'topics', '--help']\n"
        "from sensorkit.cli import main\n"
        "try:\n    main()\nexcept SystemExit:\n    pass\n"
        "assert 'pygls' not in sys.modules and 'sensorkit.lsp' not in sys.modules\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=False
    )
    assert run.returncode == 0, run.stderr


def test_a_burst_of_edits_ends_with_the_diagnostics_of_the_last(ws: Path, client: Client) -> None:
    path = ws / "rover.urdf"
    bad, good = robot(optical=APPROX), robot(optical=OPTICAL)
    path.write_text(bad)
    client.open(path)
    assert only(client.diagnostics(path, 1), "SK505")
    for version in range(2, 9):  # sent at once, ending with the fixed text
        client.change(path, good if version % 2 == 0 else bad, version)
    assert only(client.diagnostics(path, 8), "SK505") == []
    client.seen.clear()
    client.request("shutdown", None)  # whatever was published before the answer is in seen
    assert not [m for m in client.seen if m.get("method") == "textDocument/publishDiagnostics"]
    client.notify("exit")
    assert client.proc.wait(30) == 0


# --------------------------------------------------------------------------- positions


def utf16(line: str, index: int) -> int:
    return len(line[:index].encode("utf-16-le")) // 2


def test_a_finding_spans_its_start_tag_or_the_line() -> None:
    from sensorkit.lsp.convert import element_span

    line = '    <origin xyz="0 0 0" rpy="a>b"/>  <!-- x -->'
    s, e = element_span(line)
    assert line[s:e] == '<origin xyz="0 0 0" rpy="a>b"/>'
    line = '  <sensor name="cam"\n'.rstrip("\n")
    s, e = element_span(line)
    assert line[s:e] == '<sensor name="cam"'
    s, e = element_span("  </gazebo>  ")
    assert (s, e) == (2, 11)
    line = '<link name="a"/><link name="b"/>'
    assert element_span(line, column=17) == (16, len(line))
    assert element_span("   ") == (0, 0)


@pytest.mark.parametrize("eol", ["\n", "\r\n"])
def test_an_edit_counts_utf16_units_and_keeps_line_ends(eol: str) -> None:
    from sensorkit.lsp.convert import text_edit

    old = eol.join(['<robot name="😀">', '  <origin rpy="-1.57 0 -1.57"/> <!-- 😀 é -->', ""])
    new = old.replace("-1.57 0 -1.57", OPTICAL)
    e = text_edit(old, new, utf16)
    assert e is not None
    edit = {
        "range": {
            "start": {"line": e.range.start.line, "character": e.range.start.character},
            "end": {"line": e.range.end.line, "character": e.range.end.character},
        },
        "newText": e.new_text,
    }
    assert apply_edits(old, [edit]) == new
    assert text_edit(old, old, utf16) is None
    emoji = eol.join(['<a n="😀"/>', ""])
    e = text_edit(emoji, emoji.replace('"/>', '" m="1"/>'), utf16)
    assert e is not None and e.range.start.character == len('<a n="😀"') + 1  # 😀 is 2 units


def test_bad_initialization_options_are_logged_and_the_server_goes_on(ws: Path) -> None:
    c = Client(cwd=ws)
    try:
        c.initialize(ws, {"target": 5, "args": {"gazebo": "ignition"}})
        said = c.wait(lambda m: m.get("method") == "window/logMessage", 30)
        assert "initializationOptions.target must be a string" in said["params"]["message"]
        path = ws / "rover.urdf"
        path.write_text(robot(optical=APPROX))
        c.open(path)
        assert only(c.diagnostics(path, 1), "SK505")
        assert c.close() == 0
    finally:
        c.kill()


def watched(c: Client, ws: Path) -> list[str]:
    """Initialize as a client that watches files for the server; the globs it registers."""
    watching = {"workspace": {"didChangeWatchedFiles": {"dynamicRegistration": True}}}
    c.initialize(ws, capabilities=watching)
    asked = c.wait(lambda m: m.get("method") == "client/registerCapability", 30)
    (reg,) = asked["params"]["registrations"]
    assert reg["method"] == "workspace/didChangeWatchedFiles"
    c.respond(asked["id"])
    return [w["globPattern"] for w in reg["registerOptions"]["watchers"]]


def test_an_include_changed_on_disk_is_read_again(ws: Path) -> None:
    c = Client(cwd=ws)
    try:
        globs = watched(c, ws)
        assert "**/*.xacro" in globs and "**/sensorkit.toml" in globs

        pkg = _package(ws / "src" / "rover_description", "rover_description")
        cam = pkg / "urdf" / "sensors" / "camera.urdf.xacro"
        cam.parent.mkdir(parents=True)
        cam.write_text(CAMERA_XACRO)
        top = pkg / "urdf" / "rover.urdf.xacro"
        top.write_text(_top("sensors/camera.urdf.xacro"))
        c.open(top)
        assert only(c.diagnostics(cam), "SK505")
        cam.write_text(CAMERA_XACRO.replace("-1.57 0 -1.57", "${-pi/2} 0 ${-pi/2}"))
        c.notify("workspace/didChangeWatchedFiles", {"changes": [{"uri": uri(cam), "type": 2}]})
        assert only(c.diagnostics(cam), "SK505") == []
        assert c.close() == 0
    finally:
        c.kill()


def test_a_yaml_read_by_load_yaml_changed_on_disk_is_read_again(ws: Path) -> None:
    """A YAML file the expansion read with xacro.load_yaml is one of the robot's sources
    (the expansion records it): changed on disk, the robot is validated again."""
    c = Client(cwd=ws)
    try:
        assert "**/*.yaml" in watched(c, ws)

        pkg = _package(ws / "src" / "rover_description", "rover_description")
        cam = pkg / "urdf" / "sensors" / "camera.urdf.xacro"
        cam.parent.mkdir(parents=True)
        cam.write_text(
            CAMERA_XACRO.replace(
                f'rpy="{APPROX}"',
                "rpy=\"${xacro.load_yaml('sensors/mount.yaml')['rpy']}\"",
            )
        )
        mount = pkg / "urdf" / "sensors" / "mount.yaml"
        mount.write_text(f"rpy: {APPROX}\n")
        top = pkg / "urdf" / "rover.urdf.xacro"
        top.write_text(_top("sensors/camera.urdf.xacro"))
        c.open(top)
        assert only(c.diagnostics(cam), "SK505")
        exact = "-1.5707963267948966 0 -1.5707963267948966"
        mount.write_text(f"rpy: {exact}\n")
        c.notify("workspace/didChangeWatchedFiles", {"changes": [{"uri": uri(mount), "type": 2}]})
        assert only(c.diagnostics(cam), "SK505") == []
        assert c.close() == 0
    finally:
        c.kill()


def test_a_client_that_resolves_gets_the_edit_when_it_chooses_the_fix(ws: Path) -> None:
    c = Client(cwd=ws)
    try:
        lazy = {"textDocument": {"codeAction": {"resolveSupport": {"properties": ["edit"]}}}}
        c.initialize(ws, capabilities=lazy)
        path = ws / "rover.urdf"
        bad = robot(optical=APPROX)
        path.write_text(bad)
        c.open(path)
        (d,) = only(c.diagnostics(path, 1), "SK505")
        ask = {"textDocument": {"uri": uri(path)}, "range": d["range"]}
        (action,) = c.request("textDocument/codeAction", {**ask, "context": {"diagnostics": [d]}})
        assert "edit" not in action and action["title"].endswith("(SK505)")
        done = c.request("codeAction/resolve", action)
        fixed = apply_edits(bad, done["edit"]["changes"][uri(path)])
        assert f'rpy="{OPTICAL}"' in fixed
        # a finding whose fixer has nothing safe to offer gets no action
        other = {**d, "code": "SK101"}
        assert (
            c.request("textDocument/codeAction", {**ask, "context": {"diagnostics": [other]}}) == []
        )
        assert c.close() == 0
    finally:
        c.kill()


def test_hover_on_a_sensor_written_in_an_included_macro(ws: Path, client: Client) -> None:
    whole = robot(xacro=True)
    start, end = whole.index('  <gazebo reference="camera_link">'), whole.index("</robot>")
    block = whole[start:end]
    inc = ws / "urdf" / "camera.urdf.xacro"
    inc.parent.mkdir()
    inc.write_text(
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f'<xacro:macro name="front_camera">\n{block}</xacro:macro>\n</robot>\n'
    )
    top = ws / "urdf" / "rover.urdf.xacro"
    top.write_text(
        whole[:start]
        + '  <xacro:include filename="camera.urdf.xacro"/>\n  <xacro:front_camera/>\n'
        + whole[end:]
    )
    client.open(top)
    client.diagnostics(top, 1)
    line = line_of(inc.read_text(), '<sensor name="front_camera"')
    got = client.request(
        "textDocument/hover",
        {"textDocument": {"uri": uri(inc)}, "position": {"line": line, "character": 6}},
    )
    assert got is not None and "/front_camera/image_raw" in got["contents"]["value"]
    assert client.close() == 0
