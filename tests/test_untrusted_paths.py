"""Issue 25, packages and paths: under ``--untrusted`` nothing outside the workspace and
the resolved packages is opened, listed or named.

Every case writes a secret outside the workspace (``tmp_path/outside``, the workspace
is ``tmp_path/ws``) and checks that neither its content nor the name of a file the user
did not write reaches stdout/stderr in any format, or render's output; where the user
wrote the outside path, the output must not change with whether anything is there.
Each case has a near miss inside the workspace that still works.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from sensorkit.base.errors import UsageError
from sensorkit.loading.packages import PackageResolver, valid_package_name
from sensorkit.loading.uris import OUTSIDE, resolve_uri

SECRET = "SK_SECRET_CONTENT"
HEAD = '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
INERTIAL = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
FORMATS = ("text", "json", "sarif", "github")
# A small valid OBJ: pybullet would load it if it were handed the path.
OBJ = f"# {SECRET}\nv 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"
CAMERA = """
  <link name="cam_link">INERTIAL<visual><geometry><box size="0.03 0.08 0.03"/></geometry></visual></link>
  <joint name="cam_joint" type="fixed"><parent link="base_link"/><child link="cam_link"/>
    <origin xyz="0.25 0 0.5"/></joint>
  <gazebo reference="cam_link">
    <sensor name="cam" type="camera"><update_rate>10</update_rate>
      <camera><horizontal_fov>1.2</horizontal_fov>
        <image><width>64</width><height>48</height><format>R8G8B8</format></image>
        <clip><near>0.05</near><far>20</far></clip></camera>
      <plugin name="cam_controller" filename="libgazebo_ros_camera.so"/>
    </sensor>
  </gazebo>
""".replace("INERTIAL", INERTIAL)


def _outside(tmp_path: Path) -> Path:
    out = tmp_path / "outside"
    out.mkdir(exist_ok=True)
    (out / "secret.txt").write_text(SECRET + "\n")
    (out / "leakname_zq.xacro").write_text(
        f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="{SECRET}"/></robot>'
    )
    (out / "secret_mesh.obj").write_text(OBJ)
    (out / "secret_tex.png").write_text(SECRET)
    return out


def _robot(folder: Path, body: str, name: str = "robot.urdf.xacro") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text(HEAD + body + "\n</robot>\n")
    return path


def _validate(robot: Path, fmt: str, *, cwd: Path, env: dict[str, str] | None = None) -> str:
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", "validate", "--untrusted", "--format", fmt, str(robot)],
        check=False,
        capture_output=True,
        text=True,
        timeout=120,
        cwd=cwd,
        env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[1]), **(env or {})},
    )
    assert res.returncode in (0, 1, 2), res.stderr
    assert "Traceback" not in res.stderr, res.stderr
    return res.stdout + res.stderr


def _yaml_link(expr: str) -> str:
    return f'<xacro:property name="y" value="${{xacro.load_yaml(\'{expr}\')}}"/>\n<link name="base_${{y}}">{INERTIAL}</link>'


@pytest.mark.parametrize(
    "find",
    [
        "$(find /proc/self/cwd/outside)/secret.txt",
        "$(find OUTSIDE)/secret.txt",
        "$(find ../..)/outside/secret.txt",
    ],
)
def test_find_takes_no_path_for_a_package_name(tmp_path: Path, find: str) -> None:
    """What broke 1: with AMENT_PREFIX_PATH set, ``<prefix>/share/<name>`` with an absolute
    or ``..`` name is a folder outside, which $(find) handed back and allowed."""
    outside = _outside(tmp_path)
    prefix = tmp_path / "prefix"
    (prefix / "share").mkdir(parents=True)
    robot = _robot(tmp_path / "ws", _yaml_link(find.replace("OUTSIDE", str(outside))))
    env = {"AMENT_PREFIX_PATH": str(prefix)}  # <prefix>/share/../.. is tmp_path
    for fmt in FORMATS:
        out = _validate(robot, fmt, cwd=tmp_path, env=env)
        assert SECRET not in out, out
        assert "SK102" in out or "SK103" in out, out


def test_find_of_a_package_in_the_workspace_still_reads_its_files(tmp_path: Path) -> None:
    """Near miss: a real package's file, found by name, is read and echoed as usual."""
    _outside(tmp_path)
    pkg = tmp_path / "ws" / "src" / "my_pkg"
    (pkg / "config").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>my_pkg</name></package>")
    (pkg / "config" / "v.yaml").write_text("SK_INSIDE_VALUE\n")
    robot = _robot(pkg / "urdf", _yaml_link("$(find my_pkg)/config/v.yaml"))
    out = _validate(robot, "text", cwd=tmp_path)
    assert "SK_INSIDE_VALUE" in out and "SK102" not in out, out


@pytest.mark.parametrize("name", ["", ".", "..", "/abs", "../x", "a/b", "a\\b", "a\x00b"])
def test_what_cannot_be_a_package_name_is_refused(tmp_path: Path, name: str) -> None:
    assert not valid_package_name(name)
    resolver = PackageResolver(explicit={name: tmp_path}, scan_dirs=[tmp_path])
    assert resolver.find(name) is None


@pytest.mark.parametrize("name", ["my_pkg", "ros-gz-sim", "My_Pkg2", "a..b"])
def test_dashes_and_capitals_are_still_names(name: str, tmp_path: Path) -> None:
    """Near miss: REP 144 asks for lowercase and underscores, real packages do not all
    follow it (ros-infrastructure/rep@11ca24a:rep-0144.rst:51)."""
    assert valid_package_name(name)
    assert PackageResolver(explicit={name: tmp_path}).find(name) == tmp_path


@pytest.mark.parametrize("item", ["..=/tmp", ".=/tmp", "a\\b=/tmp"])
def test_package_path_name_must_be_a_name(item: str) -> None:
    with pytest.raises(UsageError, match="is not a package name"):
        PackageResolver.from_options([item])


def test_package_path_with_a_bad_name_exits_2_in_one_line(tmp_path: Path) -> None:
    robot = _robot(tmp_path / "ws", f'<link name="base">{INERTIAL}</link>')
    res = subprocess.run(
        [
            sys.executable,
            "-m",
            "sensorkit",
            "validate",
            "--package-path",
            f"..={tmp_path}",
            str(robot),
        ],
        check=False,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert res.returncode == 2 and "is not a package name" in res.stderr, res.stderr
    assert "Traceback" not in res.stderr


@pytest.mark.parametrize(
    "pattern",
    ["../outside/*.xacro", "OUTSIDE/*.xacro", "sub/*/../../../outside/*.xacro", "*/*.xacro"],
)
def test_include_glob_never_names_what_it_found_outside(tmp_path: Path, pattern: str) -> None:
    """What broke 3: the refusal named the file the glob found outside (its name is what
    leaks). ``*/*.xacro`` reaches outside through a symlink in the workspace."""
    outside = _outside(tmp_path)
    ws = tmp_path / "ws"
    (ws / "sub" / "x").mkdir(parents=True)
    (ws / "link").symlink_to(outside)
    robot = _robot(
        ws,
        f'<xacro:include filename="{pattern.replace("OUTSIDE", str(outside))}"/>\n<link name="base">{INERTIAL}</link>',
    )
    for fmt in FORMATS:
        out = _validate(robot, fmt, cwd=tmp_path)
        assert "leakname_zq" not in out and SECRET not in out, out


def test_include_glob_inside_the_workspace_still_includes(tmp_path: Path) -> None:
    _outside(tmp_path)
    ws = tmp_path / "ws"
    (ws / "parts").mkdir(parents=True)
    (ws / "parts" / "a.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:property name="inside" value="SK_INSIDE_GLOB"/></robot>'
    )
    robot = _robot(
        ws,
        f'<xacro:include filename="parts/*.xacro"/>\n<link name="base_${{inside}}">{INERTIAL}</link>',
    )
    out = _validate(robot, "text", cwd=tmp_path)
    assert "SK102" not in out and "SK_INSIDE_GLOB" in out, out


def _mesh_robot(ws: Path, outside: Path, *, texture: bool = True) -> Path:
    """A robot in package my_pkg at ws/src/my_pkg (a colcon workspace: the confinement is
    ws/src) whose meshes and texture point outside six ways."""
    meshes = [
        f"file://{outside}/secret_mesh.obj",
        f"{outside}/secret_mesh.obj",
        "../../../outside/secret_mesh.obj",
        "package://../outside/secret_mesh.obj",
        "package:///" + str(outside) + "/secret_mesh.obj",
        "package://my_pkg/../../../outside/secret_mesh.obj",
    ]
    visuals = "".join(
        f'<visual><geometry><mesh filename="{m}"/></geometry></visual>' for m in meshes
    )
    tex = (
        '<material name="m"><texture filename="../../../outside/secret_tex.png"/></material>'
        if texture
        else ""
    )
    body = (
        f'<link name="base_link">{INERTIAL}{visuals}'
        f'<visual><geometry><box size="0.5 0.4 0.3"/></geometry>{tex}</visual></link>' + CAMERA
    )
    pkg = ws / "src" / "my_pkg"
    pkg.mkdir(parents=True, exist_ok=True)
    (pkg / "package.xml").write_text("<package><name>my_pkg</name></package>")
    return _robot(pkg, body, "robot.urdf")


def test_validate_says_nothing_of_whether_an_outside_mesh_exists(tmp_path: Path) -> None:
    """SK104 said "no file at <outside path>" only when nothing was there, SK103 let
    ``package://../`` through: either told whether an outside file exists."""
    outside = _outside(tmp_path)
    ws = tmp_path / "ws"
    ws.mkdir()
    robot = _mesh_robot(ws, outside)
    env = {"AMENT_PREFIX_PATH": str(outside / "p")}
    (outside / "p" / "share").mkdir(parents=True)
    with_file = {fmt: _validate(robot, fmt, cwd=tmp_path, env=env) for fmt in FORMATS}
    (outside / "secret_mesh.obj").unlink()
    without = {fmt: _validate(robot, fmt, cwd=tmp_path, env=env) for fmt in FORMATS}
    for fmt in FORMATS:
        assert SECRET not in with_file[fmt]
        assert with_file[fmt] == without[fmt], (fmt, with_file[fmt], without[fmt])
        assert "no file at" not in without[fmt], without[fmt]


def test_validate_still_reports_a_missing_mesh_inside(tmp_path: Path) -> None:
    robot = _robot(
        tmp_path / "ws",
        f'<link name="base">{INERTIAL}<visual><geometry><mesh filename="meshes/gone.stl"/>'
        "</geometry></visual></link>",
        "robot.urdf",
    )
    out = _validate(robot, "text", cwd=tmp_path)
    assert "SK104" in out and "gone.stl" in out, out


def test_resolve_uri_refuses_outside_under_untrusted_only(tmp_path: Path) -> None:
    outside = _outside(tmp_path)
    ws = tmp_path / "ws"
    robot = _robot(ws, "")
    (ws / "meshes").mkdir()
    confined = PackageResolver.from_options([], near=robot, untrusted=True)
    trusted = PackageResolver.from_options([], near=robot)
    for uri in (
        f"file://{outside}/secret_mesh.obj",
        "../outside/secret_mesh.obj",
        str(outside / "x.obj"),
    ):
        target = resolve_uri(uri, ws, confined)
        assert target.path is None and target.refused and target.why == OUTSIDE
        assert resolve_uri(uri, ws, trusted).path is not None
    (ws / "escape").symlink_to(outside)
    assert resolve_uri("escape/secret_mesh.obj", ws, confined).refused
    assert resolve_uri("meshes/x.obj", ws, confined).path == ws / "meshes" / "x.obj"


def test_render_preview_untrusted_opens_no_outside_mesh_or_texture(tmp_path: Path) -> None:
    """What broke 4: render preview --untrusted handed pybullet file://, absolute and ../
    meshes and textures outside the workspace."""
    pytest.importorskip("pybullet")
    from sensorkit.loading.untrusted import Untrusted
    from sensorkit.render import render_preview, urdf_out

    outside = _outside(tmp_path)
    ws = tmp_path / "ws"
    ws.mkdir()
    robot = _mesh_robot(ws, outside)
    loaded: list[bytes] = []
    orig = urdf_out.prepare_urdf

    def spy(*a: object, **kw: object) -> urdf_out.PreparedUrdf:
        prepared = orig(*a, **kw)  # type: ignore[arg-type]
        loaded.extend(part.text for part in prepared.parts)
        return prepared

    mp = pytest.MonkeyPatch()
    mp.setattr(urdf_out, "prepare_urdf", spy)
    try:
        result = render_preview(robot, tmp_path / "out", sensors=("cam",), untrusted=Untrusted())
    finally:
        mp.undo()
    assert loaded and not any(b"outside" in text for text in loaded), loaded
    refused = [n for n in result.notes if OUTSIDE in n]
    unknown = [
        n for n in result.notes if "package '..' not found" in n or "package '' not found" in n
    ]
    assert len(refused) == 5 and len(unknown) == 2, result.notes  # 4 + 2 meshes, the texture
    for file in (tmp_path / "out").rglob("*"):
        if file.is_file():
            assert SECRET.encode() not in file.read_bytes(), file
    html = (tmp_path / "out" / "index.html").read_text()
    assert SECRET not in html and "not read with --untrusted" in html


def test_render_preview_untrusted_still_loads_a_package_mesh_inside(tmp_path: Path) -> None:
    """Near miss: package://my_pkg/meshes/x.obj inside the workspace reaches pybullet."""
    from sensorkit.loading.untrusted import Untrusted
    from sensorkit.model import load_robot
    from sensorkit.render.urdf_out import prepare_urdf

    ws = tmp_path / "ws"
    (ws / "meshes").mkdir(parents=True)
    (ws / "meshes" / "x.obj").write_text(OBJ.replace(SECRET, "inside"))
    (ws / "package.xml").write_text("<package><name>my_pkg</name></package>")
    robot_path = _robot(
        ws,
        f'<link name="base_link">{INERTIAL}<visual><geometry>'
        '<mesh filename="package://my_pkg/meshes/x.obj"/></geometry></visual></link>',
        "robot.urdf",
    )
    loaded = load_robot(robot_path, untrusted=Untrusted())
    assert loaded.robot is not None
    resolver = PackageResolver.from_options([], near=robot_path, untrusted=True)
    prepared = prepare_urdf(loaded.robot, resolver)
    assert prepared.dropped == 0 and prepared.notes == []
    assert str((ws / "meshes" / "x.obj").resolve()).encode() in prepared.text
