"""Issue 36, item 1 and causes 1, 5 and 6: under ``--untrusted`` the repository is the limit.

The layout of every case: ``tmp_path/runner`` stands for a CI runner's work folder. It
holds the outside secret (``secret.yaml``, ``secret_mesh.obj``), a sibling checkout
(``sibling/``, a package ``sibling_pkg`` holding the secret too) and the repository under
test, ``runner/checkout`` (a git work tree: a package at its root, as many robot
repositories are). Before issue 36 the package's parent and grandparent were its
"workspace": ``load_yaml('../../secret.yaml')``, an include, ``$(find sibling_pkg)`` and a
render mesh read the runner's folder. Each attack is checked in every output format, and
through ``strace`` for the file opens where strace is installed; each has a near miss
inside the repository that still works.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from sensorkit.base.errors import InputError
from sensorkit.loading.document import read_input
from sensorkit.loading.packages import PackageResolver, readable_area, repository_of

SECRET = "SK_OUTSIDE_SECRET_36"
FORMATS = ("text", "json", "sarif", "github")
XMLNS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
INERTIAL = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
ROOT = Path(__file__).parents[1]


def _layout(tmp_path: Path) -> tuple[Path, Path]:
    """(runner, checkout): the secret above the repository and in a sibling checkout."""
    runner = tmp_path / "runner"
    checkout = runner / "checkout"
    (checkout / ".git").mkdir(parents=True)
    (checkout / "urdf").mkdir()
    (checkout / "config").mkdir()
    (checkout / "package.xml").write_text("<package><name>my_robot</name></package>")
    (checkout / "config" / "inside.yaml").write_text("SK_INSIDE_VALUE\n")
    (runner / "secret.yaml").write_text(SECRET + "\n")
    (runner / "secret.xacro").write_text(f'<robot {XMLNS}><link name="{SECRET}"/></robot>')
    sibling = runner / "sibling"
    sibling.mkdir()
    (sibling / "package.xml").write_text("<package><name>sibling_pkg</name></package>")
    (sibling / "secret.yaml").write_text(SECRET + "\n")
    return runner, checkout


def _robot(checkout: Path, body: str, name: str = "robot.urdf.xacro") -> Path:
    path = checkout / "urdf" / name
    path.write_text(f'<?xml version="1.0"?>\n<robot name="r" {XMLNS}>\n{body}\n</robot>\n')
    return path


def _yaml_link(expr: str) -> str:
    return (
        f'<xacro:property name="y" value="${{xacro.load_yaml(\'{expr}\')}}"/>\n'
        f'<link name="base_${{y}}">{INERTIAL}</link>'
    )


def _env() -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH")}
    return {**env, "PYTHONPATH": str(ROOT), "SENSORKIT_NO_CACHE": "1"}


def _validate(robot: Path, fmt: str, *, cwd: Path, extra: tuple[str, ...] = ()) -> str:
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", "validate", "--untrusted", "--format", fmt, *extra, str(robot)],
        check=False,
        capture_output=True,
        text=True,
        timeout=120,
        cwd=cwd,
        env=_env(),
    )
    assert res.returncode in (0, 1, 2), res.stderr
    assert "Traceback" not in res.stderr, res.stderr
    return res.stdout + res.stderr


def _opens(robot: Path, cwd: Path, tmp_path: Path) -> list[str]:
    """Every openat of the whole process tree of an untrusted validate (strace -f)."""
    log = tmp_path / "strace.log"
    subprocess.run(
        ["strace", "-f", "-qq", "-e", "trace=openat", "-o", str(log), sys.executable, "-m",
         "sensorkit", "validate", "--untrusted", str(robot)],
        check=False, capture_output=True, text=True, timeout=180, cwd=cwd, env=_env(),
    )  # fmt: skip
    return log.read_text().splitlines()


ATTACKS = {
    "load_yaml above": _yaml_link("../../secret.yaml"),
    "load_yaml absolute": _yaml_link("RUNNER/secret.yaml"),
    "include above": '<xacro:include filename="../../secret.xacro"/>',
    "find a sibling checkout": _yaml_link("$(find sibling_pkg)/secret.yaml"),
}


@pytest.mark.parametrize("attack", sorted(ATTACKS))
def test_nothing_above_the_repository_is_read(tmp_path: Path, attack: str) -> None:
    runner, checkout = _layout(tmp_path)
    robot = _robot(checkout, ATTACKS[attack].replace("RUNNER", str(runner)))
    for fmt in FORMATS:
        out = _validate(robot, fmt, cwd=runner)
        assert SECRET not in out, (fmt, out)
        assert "SK102" in out or "SK103" in out, (fmt, out)
    if shutil.which("strace"):
        opens = _opens(robot, runner, tmp_path)
        assert opens, "strace recorded nothing"
        assert not [o for o in opens if "secret" in o], [o for o in opens if "secret" in o]


def test_a_file_inside_the_repository_is_still_read(tmp_path: Path) -> None:
    """The near miss: another folder of the same repository is readable."""
    runner, checkout = _layout(tmp_path)
    robot = _robot(checkout, _yaml_link("../config/inside.yaml"))
    out = _validate(robot, "text", cwd=runner)
    assert "SK_INSIDE_VALUE" in out and "SK102" not in out, out


def test_the_header_names_the_readable_area_in_every_format(tmp_path: Path) -> None:
    runner, checkout = _layout(tmp_path)
    robot = _robot(checkout, f'<link name="base">{INERTIAL}</link>')
    text = _validate(robot, "text", cwd=runner)
    assert "--untrusted: reads only inside checkout" in text, text
    assert json.loads(_validate(robot, "json", cwd=runner).split("\nsensorkit:")[0])[
        "readable"
    ] == {"checkout/urdf/robot.urdf.xacro": ["checkout"]}
    sarif = json.loads(_validate(robot, "sarif", cwd=runner))
    assert sarif["runs"][0]["invocations"][0]["properties"]["readable"]
    assert "reads only inside checkout" in _validate(robot, "github", cwd=runner)
    trusted = subprocess.run(
        [sys.executable, "-m", "sensorkit", "validate", str(robot)],
        capture_output=True, text=True, check=False, cwd=runner, env=_env(),
    )  # fmt: skip
    assert "reads only inside" not in trusted.stdout  # the near miss: trusted input


def test_the_repository_is_the_nearest_git_work_tree_else_colcon_else_package(tmp_path: Path) -> None:
    _runner, checkout = _layout(tmp_path)
    assert repository_of(checkout / "urdf" / "r.xacro") == checkout.resolve()
    ws = tmp_path / "ws"
    pkg = ws / "src" / "repo" / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>pkg</name></package>")
    assert repository_of(pkg / "urdf" / "r.xacro") == ws.resolve()  # the folder holding src/
    (ws / "src" / "repo" / ".git").write_text("gitdir: elsewhere\n")  # a worktree's .git file
    assert repository_of(pkg / "urdf" / "r.xacro") == (ws / "src" / "repo").resolve()
    lone = tmp_path / "lone" / "pkg"
    (lone / "urdf").mkdir(parents=True)
    (lone / "package.xml").write_text("<package><name>lone</name></package>")
    assert repository_of(lone / "urdf" / "r.xacro") == lone.resolve()  # never its parent
    bare = tmp_path / "bare"
    bare.mkdir()
    assert repository_of(bare / "r.urdf") == bare.resolve()


def test_the_area_adds_package_paths_and_ament_shares_only(tmp_path: Path) -> None:
    runner, checkout = _layout(tmp_path)
    prefix = tmp_path / "prefix"
    (prefix / "share").mkdir(parents=True)
    area = readable_area(checkout / "urdf" / "r.xacro", [runner / "sibling"], {"AMENT_PREFIX_PATH": str(prefix)})
    assert area == [str(checkout.resolve()), str((runner / "sibling").resolve()), str((prefix / "share").resolve())]
    confined = PackageResolver.from_options([], near=checkout / "urdf" / "r.xacro", untrusted=True)
    assert confined.find("sibling_pkg") is None  # a sibling checkout is not found
    trusted = PackageResolver.from_options([], near=checkout / "urdf" / "r.xacro")
    assert trusted.find("sibling_pkg") == runner / "sibling"  # trusted keeps its heuristics
    given = PackageResolver.from_options([str(runner / "sibling")], near=checkout / "urdf" / "r.xacro", untrusted=True)
    assert given.find("sibling_pkg") is not None  # the near miss: --package-path


def test_render_preview_reads_no_mesh_above_the_repository(tmp_path: Path) -> None:
    pytest.importorskip("pybullet")
    from sensorkit.loading.untrusted import Untrusted
    from sensorkit.render import render_preview

    runner, checkout = _layout(tmp_path)
    (runner / "secret_mesh.obj").write_text(f"# {SECRET}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    robot = _robot(
        checkout,
        f'<link name="base_link">{INERTIAL}<visual><geometry><mesh filename="../../secret_mesh.obj"/>'
        '</geometry></visual></link>'
        '<link name="cam_link"/><joint name="j" type="fixed"><parent link="base_link"/>'
        '<child link="cam_link"/></joint><gazebo reference="cam_link"><sensor name="cam" type="camera">'
        "<camera><horizontal_fov>1.2</horizontal_fov><image><width>32</width><height>24</height>"
        "</image><clip><near>0.05</near><far>20</far></clip></camera>"
        '<plugin name="c" filename="libgazebo_ros_camera.so"/></sensor></gazebo>',
        "robot.urdf",
    )
    result = render_preview(robot, tmp_path / "out", sensors=("cam",), untrusted=Untrusted())
    assert any("not read with --untrusted" in n for n in result.notes), result.notes
    html = (tmp_path / "out" / "index.html").read_text()
    assert SECRET not in html and "not read with --untrusted" in html
    for file in (tmp_path / "out").rglob("*"):
        if file.is_file():
            assert SECRET.encode() not in file.read_bytes(), file


# -- causes 5 and 6: links, devices and pipes ---------------------------------------------
def test_a_symlinked_input_pointing_outside_is_refused(tmp_path: Path) -> None:
    """Cause 5: the input was read wherever it pointed, its workspace taken from the
    target's. Now the area is the link's repository and the target must lie in it."""
    runner, checkout = _layout(tmp_path)
    (runner / "outside.urdf").write_text(f'<robot name="r"><link name="{SECRET}"/></robot>')
    link = checkout / "urdf" / "robot.urdf"
    link.symlink_to(runner / "outside.urdf")
    for fmt in FORMATS:
        out = _validate(link, fmt, cwd=runner)
        assert SECRET not in out, (fmt, out)
        assert "a link to a file outside its repository" in out, (fmt, out)
    inner = checkout / "urdf" / "inner.urdf"
    inner.write_text(f'<robot name="r"><link name="base">{INERTIAL}</link></robot>')
    (checkout / "urdf" / "alias.urdf").symlink_to(inner)  # the near miss: a link inside
    out = _validate(checkout / "urdf" / "alias.urdf", "text", cwd=runner)
    assert "outside its repository" not in out and "0 errors" in out, out


@pytest.mark.parametrize("untrusted", [False, True])
def test_an_input_linked_to_dev_zero_is_refused_in_one_line(tmp_path: Path, untrusted: bool) -> None:
    """Cause 6: /dev/zero was read without limit (3.7 GB, then a MemoryError traceback),
    trusted or not."""
    link = tmp_path / "robot.urdf"
    link.symlink_to("/dev/zero")
    flags = ("--untrusted",) if untrusted else ()
    res = subprocess.run(
        [sys.executable, "-m", "sensorkit", "validate", *flags, str(link)],
        capture_output=True, text=True, check=False, timeout=60, cwd=tmp_path, env=_env(),
    )  # fmt: skip
    assert res.returncode == 2, res.stderr[-500:]
    assert "Traceback" not in res.stderr and "MemoryError" not in res.stderr
    lines = [x for x in res.stderr.splitlines() if "robot.urdf" in x]
    assert len(lines) == 1, res.stderr
    reason = "outside its repository" if untrusted else "a character device, not a regular file"
    assert reason in lines[0], lines


def test_read_input_refuses_devices_pipes_and_sockets(tmp_path: Path) -> None:
    import socket

    fifo = tmp_path / "pipe.urdf"
    os.mkfifo(fifo)
    sock_path = tmp_path / "s.urdf"
    sock = socket.socket(socket.AF_UNIX)
    try:
        sock.bind(str(sock_path))
        for path, what in ((fifo, "a named pipe"), (Path("/dev/null"), "a character device"),
                           (sock_path, "a socket")):  # fmt: skip
            with pytest.raises(InputError, match=f"{what}, not a regular file"):
                read_input(path)
    finally:
        sock.close()
    ok = tmp_path / "r.urdf"
    ok.write_text('<robot name="r"/>')
    assert read_input(ok) == b'<robot name="r"/>'  # the near miss


def test_reads_are_bounded_whatever_stat_says(tmp_path: Path) -> None:
    from sensorkit.base.regular import TooLarge, read_regular

    f = tmp_path / "f"
    f.write_bytes(b"x" * 101)
    with pytest.raises(TooLarge):
        read_regular(f, 100)
    assert read_regular(f, 101) == b"x" * 101


@pytest.mark.parametrize("untrusted", [False, True])
def test_a_named_pipe_include_is_refused_at_once(tmp_path: Path, untrusted: bool) -> None:
    """Cause 6: an include naming a FIFO blocked until the timeout, and the message
    blamed a runaway expression."""
    runner, checkout = _layout(tmp_path)
    os.mkfifo(checkout / "urdf" / "part.xacro")
    robot = _robot(checkout, f'<xacro:include filename="part.xacro"/><link name="b">{INERTIAL}</link>')
    flags = ("--untrusted",) if untrusted else ()
    for fmt in FORMATS if untrusted else ("text",):
        res = subprocess.run(
            [sys.executable, "-m", "sensorkit", "validate", *flags, "--timeout", "20", "--format", fmt, str(robot)],
            capture_output=True, text=True, check=False, timeout=60, cwd=runner, env=_env(),
        )  # fmt: skip
        out = res.stdout + res.stderr
        assert "a named pipe, not a regular file" in out and "part.xacro" in out, out
        assert "runaway" not in out and "did not finish" not in out, out
