"""Loading: plain URDF, xacro, packages, and bad input of every kind (never a traceback or a hang)."""

from __future__ import annotations

from pathlib import Path

import pytest
from builders import robot
from conftest import CORPUS, ROOT, needs_corpus, rules_of
from conftest import run_cli as cli

from sensorkit.base.findings import Finding
from sensorkit.lint.engine import Options, validate_file
from sensorkit.loading.document import looks_like_xacro
from sensorkit.loading.marks import forbid_entities
from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.xacro_expand import expand, expand_in_process

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
BOMB = """<?xml version="1.0"?>
<!DOCTYPE lolz [<!ENTITY lol "lol"><!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
<!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
<!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
<!ENTITY lol5 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
<!ENTITY lol6 "&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;">
<!ENTITY lol7 "&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;">
<!ENTITY lol8 "&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;">
<!ENTITY lol9 "&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;">]>
<robot name="&lol9;"><link name="a"/></robot>
"""
SECRET = "sensorkit-secret-canary-1234"




def write(tmp_path: Path, name: str, text: str | bytes) -> Path:
    p = tmp_path / name
    p.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(text, bytes):
        p.write_bytes(text)
    else:
        p.write_text(text)
    return p


def test_malformed_xml_is_sk101_with_line_and_column(tmp_path: Path) -> None:
    p = write(tmp_path, "bad.urdf", '<?xml version="1.0"?>\n<robot name="r">\n  <link name="a">\n</robot>\n')
    report = validate_file(p)
    (f,) = report.findings
    assert f.rule == "SK101" and f.line == 4 and f.column is not None and f.file and f.file.endswith("bad.urdf")


@pytest.mark.parametrize("content", [b"", b"   \n", bytes(range(256)) * 4, b"\x89PNG\r\n\x1a\n\x00\x00"])
def test_empty_or_binary_is_sk101(tmp_path: Path, content: bytes) -> None:
    report = validate_file(write(tmp_path, "x.urdf", content))
    assert rules_of(report) == {"SK101"}


def test_non_robot_root_is_a_one_line_error(tmp_path: Path) -> None:
    # A .sdf file is read as SDF (issue 28); SDF in a file named .urdf is not, and says how
    p = write(tmp_path, "model.urdf", '<sdf version="1.9"><model name="m"/></sdf>')
    res = cli("validate", str(p))
    assert res.returncode == 2 and "Traceback" not in res.stderr
    assert res.stderr.count("\n") == 1 and "<sdf>" in res.stderr and ".sdf" in res.stderr
    p = write(tmp_path, "launch.urdf", "<launch><node/></launch>")
    res = cli("validate", str(p))
    assert res.returncode == 2 and res.stderr.count("\n") == 1 and "<launch>" in res.stderr


def test_an_sdf_file_is_validated(tmp_path: Path) -> None:
    p = write(tmp_path, "model.sdf", '<sdf version="1.9"><model name="m"><link name="a"/></model></sdf>')
    res = cli("validate", str(p))
    assert res.returncode == 0 and "harmonic" in res.stdout and "SDF" in res.stdout


def test_missing_file_and_folder_are_exit_2(tmp_path: Path) -> None:
    for target in (tmp_path / "nope.urdf", tmp_path):
        res = cli("validate", str(target))
        assert res.returncode == 2 and "Traceback" not in res.stderr and res.stderr.startswith("sensorkit: ")


def test_entity_bomb_is_refused_quickly(tmp_path: Path) -> None:
    for suffix in (".urdf", ".urdf.xacro"):
        report = validate_file(write(tmp_path, "bomb" + suffix, BOMB))
        assert rules_of(report) == {"SK101"}
        assert "entity" in report.findings[0].message


def test_external_entity_content_never_leaks(tmp_path: Path) -> None:
    secret = write(tmp_path, "secret.txt", SECRET)
    text = f'<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY x SYSTEM "file://{secret}">]>\n<robot name="&x;"><link name="&x;"/></robot>\n'
    for suffix in (".urdf", ".xacro"):
        p = write(tmp_path, "ext" + suffix, text)
        for fmt in ("text", "json"):
            res = cli("validate", str(p), "--format", fmt)
            assert SECRET not in res.stdout + res.stderr
            assert res.returncode in (1, 2) and "Traceback" not in res.stderr


def test_cycle_self_joint_two_parents_terminate(check) -> None:
    from builders import joint, link

    text = '<robot name="c">' + link("a") + link("b") + link("c") + joint("j1", "a", "b") + joint("j2", "b", "c") + joint("j3", "c", "b") + joint("j4", "a", "a") + "</robot>"
    report = check(text)
    msgs = [f.message for f in report.findings if f.rule == "SK204"]
    assert any("cycle" in m for m in msgs) and any("itself" in m for m in msgs) and any("2 parent joints" in m for m in msgs)


def test_include_loop_is_sk102(tmp_path: Path) -> None:
    write(tmp_path, "b.xacro", f'<robot {XACRO_NS}><xacro:include filename="a.urdf.xacro"/></robot>')
    a = write(tmp_path, "a.urdf.xacro", f'<robot name="r" {XACRO_NS}><xacro:include filename="b.xacro"/><link name="x"/></robot>')
    (f,) = validate_file(a).findings
    assert f.rule == "SK102" and "include loop" in f.message


def test_infinite_macro_recursion_is_sk102(tmp_path: Path) -> None:
    p = write(tmp_path, "r.urdf.xacro", f'<robot name="r" {XACRO_NS}><xacro:macro name="m" params=""><xacro:m/></xacro:macro><xacro:m/></robot>')
    (f,) = validate_file(p).findings
    assert f.rule == "SK102" and "recurs" in f.message


def test_runaway_expression_times_out(tmp_path: Path) -> None:
    p = write(tmp_path, "r.urdf.xacro", f'<robot name="r" {XACRO_NS}><link name="${{str(10**10**10)[:3]}}"/></robot>')
    (f,) = validate_file(p, Options(timeout=3)).findings
    assert f.rule == "SK102" and "did not finish" in f.message


def test_missing_include_names_the_file(tmp_path: Path) -> None:
    p = write(tmp_path, "r.urdf.xacro", f'<robot name="r" {XACRO_NS}>\n<xacro:include filename="parts/wheel.xacro"/>\n<link name="x"/></robot>')
    (f,) = validate_file(p).findings
    assert f.rule == "SK102" and "wheel.xacro" in f.message


def test_unknown_package_lists_places_searched(tmp_path: Path) -> None:
    write(tmp_path, "package.xml", "<package><name>here_pkg</name></package>")
    p = write(tmp_path, "urdf/r.urdf.xacro", f'<robot name="r" {XACRO_NS}>\n  <xacro:include filename="$(find ghost_pkg)/x.xacro"/>\n</robot>')
    (f,) = validate_file(p).findings
    assert f.rule == "SK103" and "ghost_pkg" in f.message and "workspace" in f.message and f.line == 2
    f2 = validate_file(p, Options(package_paths=(str(tmp_path),))).findings[0]
    assert "--package-path" in f2.message


def test_package_uri_for_unknown_package_is_sk103(check) -> None:
    text = robot(extra='<link name="m"><visual><geometry><mesh filename="package://ghost_pkg/meshes/m.stl"/></geometry></visual></link><joint name="mj" type="fixed"><parent link="base_link"/><child link="m"/></joint>')
    assert "SK103" in rules_of(check(text))


def test_undefined_arg_says_how_to_pass_it(tmp_path: Path) -> None:
    p = write(tmp_path, "r.urdf.xacro", f'<robot name="r" {XACRO_NS}><link name="$(arg prefix)base"/></robot>')
    (f,) = validate_file(p).findings
    assert f.rule == "SK102" and "--arg prefix:=" in (f.fix or "")
    ok = validate_file(p, Options(args={"prefix": "my_"}))
    assert ok.robot is not None and "my_base" in ok.robot.link_map


def test_malformed_include_reports_the_include_line(tmp_path: Path) -> None:
    write(tmp_path, "part.xacro", f'<robot {XACRO_NS}>\n<link name="a">\n</robot>\n')
    p = write(tmp_path, "r.urdf.xacro", f'<robot name="r" {XACRO_NS}><xacro:include filename="part.xacro"/></robot>')
    (f,) = validate_file(p).findings
    assert f.rule == "SK101" and f.file and f.file.endswith("part.xacro") and f.line == 3


@pytest.mark.parametrize(
    ("text", "xacro"),
    [
        (b'<robot name="r"><link name="${n}"/></robot>', True),
        (b'<robot name="r"><link name="$(arg n)"/></robot>', True),
        (b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r"/>', True),
        (b'<robot xmlns:xacro = "http://www.ros.org/wiki/xacro" name="r"/>', True),
        (b'<robot name="r"><xacro:include filename="a.xacro"/></robot>', True),
        # near misses: a dollar, a colon or the word alone is no xacro markup
        (b'<robot name="r"><link name="cost$"/><!-- 10 $ { --></robot>', False),
        (b'<robot name="r"><!-- made by xacro once --><link name="a"/></robot>', False),
        (b'<robot name="r"><!-- see: xacro --><link name="a:b"/></robot>', False),
    ],
)
def test_urdf_files_are_expanded_only_when_they_hold_xacro_markup(
    tmp_path: Path, text: bytes, xacro: bool
) -> None:
    assert looks_like_xacro(tmp_path / "r.urdf", text) is xacro
    assert looks_like_xacro(tmp_path / "r.urdf.xacro", text) is True


@pytest.mark.parametrize(
    "text",
    [
        BOMB.encode(),
        b'<?xml version="1.0"?>\n<!DOCTYPE r [<!entity x "y">]>\n<robot name="r"/>',
    ],
)
def test_entities_are_refused_wherever_the_doctype_is(text: bytes) -> None:
    assert forbid_entities(text) is not None
    assert forbid_entities(b"<!-- " + b"x" * 100_000 + b" -->\n" + text) is not None
    # near misses: a comment with "!" and no DOCTYPE, a DOCTYPE with no entity
    assert forbid_entities(b'<!-- hi! --><robot name="r"/>') is None
    assert forbid_entities(b'<!DOCTYPE robot><robot name="r"/>') is None


@needs_corpus
def test_urdf_with_xacro_markup_is_expanded() -> None:
    p = CORPUS / "ROBOTIS-GIT__turtlebot3/turtlebot3_description/urdf/turtlebot3_burger.urdf"
    report = validate_file(p)
    assert report.robot is not None and "base_footprint" in report.robot.link_map


def test_workspace_of_two_packages_validates_with_no_flags() -> None:
    p = ROOT / "tests/robots/workspace/src/rover_description/urdf/rover.urdf.xacro"
    res = cli("validate", str(p))
    assert res.returncode == 0, res.stdout + res.stderr
    assert "0 errors, 0 warnings" in res.stdout


def test_findings_point_into_the_included_file(tmp_path: Path) -> None:
    import shutil

    ws = tmp_path / "ws"
    shutil.copytree(ROOT / "tests/robots/workspace", ws)
    macro = ws / "src/rover_sensors/urdf/camera.urdf.xacro"
    macro.write_text(macro.read_text().replace("${name}_optical_frame</frame_name>", "${name}_link</frame_name>"))
    report = validate_file(ws / "src/rover_description/urdf/rover.urdf.xacro")
    f = next(f for f in report.findings if f.rule == "SK502")
    lines = macro.read_text().splitlines()
    assert f.file and f.file.endswith("camera.urdf.xacro") and '<sensor name="${name}"' in lines[f.line - 1]


def test_expansion_is_repeatable_in_one_process(tmp_path: Path) -> None:
    p = ROOT / "tests/robots/workspace/src/rover_description/urdf/rover.urdf.xacro"
    resolver = PackageResolver().for_file(p)
    first = expand_in_process(p, {}, resolver)
    other = expand_in_process(p, {"camera_x": "0.5"}, resolver)
    again = expand_in_process(p, {}, resolver)
    assert first.xml and first.xml == again.xml and other.xml != first.xml
    assert expand(p, {}, resolver).xml == first.xml


def test_package_resolution_order(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    for where in ("explicit", "scanned", "ament/share", "rospath"):
        write(tmp_path, f"{where}/pkg/package.xml", "<package><name>pkg</name></package>")
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path / "ament"))
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "rospath"))
    r = PackageResolver.from_options([f"pkg={tmp_path / 'explicit/pkg'}", str(tmp_path / "scanned")])
    assert r.find("pkg") == tmp_path / "explicit/pkg"
    assert PackageResolver.from_options([str(tmp_path / "scanned")]).find("pkg") == tmp_path / "scanned/pkg"
    assert PackageResolver.from_options([]).find("pkg") == tmp_path / "ament/share/pkg"
    monkeypatch.delenv("AMENT_PREFIX_PATH")
    assert PackageResolver.from_options([]).find("pkg") == tmp_path / "rospath/pkg"


def test_cli_never_prints_a_traceback_on_bad_input(tmp_path: Path) -> None:
    files = [
        write(tmp_path, "a.urdf", "<robot"),
        write(tmp_path, "b.urdf", BOMB),
        write(tmp_path, "c.urdf.xacro", f'<robot name="r" {XACRO_NS}><xacro:include filename="$(find nope)/x"/></robot>'),
        write(tmp_path, "d.urdf", '<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/><child link="a"/><origin xyz="nan inf 0"/></joint></robot>'),
    ]
    res = cli("validate", *map(str, files), "--format", "json")
    assert res.returncode == 1 and "Traceback" not in res.stderr


def _package(folder: Path, name: str, link: str) -> None:
    (folder / "urdf").mkdir(parents=True)
    (folder / "package.xml").write_text(
        f'<?xml version="1.0"?><package format="3"><name>{name}</name><version>0.0.1</version>'
        '<description>d</description><maintainer email="a@b.c">a</maintainer>'
        "<license>MIT</license></package>\n"
    )
    (folder / "urdf" / "parts.xacro").write_text(
        '<?xml version="1.0"?><robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        f'<link name="{link}"/><joint name="j" type="fixed"><parent link="base_link"/>'
        f'<child link="{link}"/></joint></robot>\n'
    )


DUP_ROBOT = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base_link"/>
  <xacro:include filename="$(find my_robot)/urdf/parts.xacro"/>
</robot>
"""


def test_a_package_twice_in_the_workspace_is_said_as_colcon_refuses_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Issue 38: two copies of one package in a workspace's src/ (colcon refuses to build
    it: "Duplicate package names not supported", colcon/colcon-core@b37a8d4:
    colcon_core/package_selection/__init__.py:185-196) were resolved silently, the first
    in folder order, here the stale copy. Now the copy holding the file is read, and an
    SK103 error names both and the one read; a COLCON_IGNORE file (which colcon skips:
    colcon_core/package_identification/ignore.py:11-15) or --package-path NAME=DIR
    settles it (near misses)."""
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.chdir(tmp_path)
    src = tmp_path / "ws" / "src"
    _package(src / "a" / "my_robot", "my_robot", "old_link")
    _package(src / "b" / "my_robot", "my_robot", "new_link")
    top = src / "b" / "my_robot" / "urdf" / "robot.urdf.xacro"
    top.write_text(DUP_ROBOT)

    def run(*packages: str) -> tuple[list[Finding], list[str]]:
        report = validate_file(top, Options(target="classic", package_paths=packages, cache=None))
        assert report.error is None, report.error
        dups = [f for f in report.findings if f.rule == "SK103"]
        return dups, [lk.name for lk in report.robot.links] if report.robot else []

    dups, links = run()
    assert "new_link" in links and "old_link" not in links  # the file's own copy
    (f,) = dups
    assert f.severity.name == "ERROR" and f.source.line == 4
    assert (
        "package 'my_robot' is in ws/src twice: ws/src/a/my_robot and ws/src/b/my_robot; "
        'colcon refuses to build such a workspace ("Duplicate package names not supported"'
    ) in f.message
    assert "sensorkit read ws/src/b/my_robot (the package holding this file)" in f.message
    assert "COLCON_IGNORE" in f.fix and "--package-path my_robot=DIR" in f.fix
    # near misses: the copy chosen by name, or the other one ignored as colcon ignores it
    assert run(f"my_robot={src / 'b' / 'my_robot'}")[0] == []
    (src / "a" / "my_robot" / "COLCON_IGNORE").touch()
    dups, links = run()
    assert dups == [] and "new_link" in links


def test_a_package_twice_around_a_file_in_no_workspace_is_info(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Outside a colcon src/, which copy a build installs is not known: info, naming both
    and the copy read (a package:// mesh URI is said the same way, once)."""
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.chdir(tmp_path)
    repo = tmp_path / "repos" / "bot"
    _package(repo / "desc_a" / "parts", "parts", "one_link")
    _package(repo / "desc_b" / "parts", "parts", "two_link")
    (repo / "bringup" / "urdf").mkdir(parents=True)
    (repo / "bringup" / "package.xml").write_text(
        (repo / "desc_a" / "parts" / "package.xml").read_text().replace("parts", "bringup")
    )
    top = repo / "bringup" / "urdf" / "robot.urdf.xacro"
    top.write_text(
        DUP_ROBOT.replace("my_robot", "parts").replace(
            '<link name="base_link"/>',
            '<link name="base_link"><visual><geometry><mesh filename="package://parts/m.stl"/>'
            "</geometry></visual></link>",
        )
    )
    report = validate_file(top, Options(target="classic", cache=None))
    (f,) = [f for f in report.findings if f.rule == "SK103"]
    assert f.severity.name == "INFO" and "found twice around this file" in f.message
    assert "sensorkit read repos/bot/desc_a/parts" in f.message
    # near miss: one copy, no finding
    (repo / "desc_b" / "parts" / "package.xml").unlink()
    report = validate_file(top, Options(target="classic", cache=None))
    assert [f for f in report.findings if f.rule == "SK103"] == []
