"""A newcomer's mistakes with sensorkit, each run and judged against what the docs promise.

Run by hand (never in the test suite): `.venv/bin/python benchmarks/newcomer_mistakes.py`
(`--only ID` for some, `--json` for a machine-readable list).

Each mistake is one entry: a fresh temporary folder with the files the mistake needs
(copies of tests/robots/ and examples/, or small inline texts), one command line run as
`python -m sensorkit ...` in that folder (NO_COLOR=1, COLUMNS=100, XDG_CACHE_HOME inside
it), and what a clean answer does: the exit status, the words the user must be told (the
file, the option, the next step), the words that must not appear, and the user's files
that must keep every byte. The expectations are what README.md promises (CLI conventions:
an error is one line "sensorkit: ..." on stderr, exit status 2), not what sensorkit prints
today. The verdict follows from the entry alone:

- traceback: "Traceback (most recent call last)" in the output, or killed by a signal
  (SIGPIPE excepted where the entry pipes into `head`);
- silent-wrong: exit 0 where the entry expects a refusal or a finding, or a user file
  changed that must not;
- misleading: another exit status, a required word missing or a forbidden one present,
  an exit-2 error that is not one "sensorkit: " line on stderr, a temporary file's name
  (".new-", ".prev", ".sensorkit-tmp") instead of the user's path, or stderr output on a
  quiet exit;
- clean: otherwise.

Permissions: run as root, each command runs without CAP_DAC_OVERRIDE and
CAP_DAC_READ_SEARCH (capsh), so read-only and unreadable files behave as for a user.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TRACEBACK = "Traceback (most recent call last)"
TEMP_NAMES = (".new-", ".prev", ".sensorkit-tmp")
VERDICTS = ("clean", "misleading", "silent-wrong", "traceback")
# stderr lines that report, not err: the settings taken and the files a folder stands for
# and render preview's progress
NOTE = re.compile(
    r"^(sensorkit: (.* from \S*(sensorkit\.toml|pyproject\.toml)|.*: found \d+ )|loading \S+$)"
)


@dataclass(frozen=True)
class Copy:
    """A file or folder of this repository, copied in."""

    src: str


@dataclass(frozen=True)
class Link:
    """A symbolic link to `target` (relative to the link, as written)."""

    target: str


@dataclass(frozen=True)
class Hard:
    """A second name (hard link) of an earlier file of the setup."""

    target: str


@dataclass(frozen=True)
class Dir:
    """An empty folder."""


Setup = str | bytes | Copy | Link | Hard | Dir


@dataclass(frozen=True)
class Mistake:
    id: str
    what: str
    argv: tuple[str, ...]
    files: dict[str, Setup] = field(default_factory=dict)
    status: frozenset[int] = frozenset({2})
    words: tuple[str, ...] = ()
    forbid: tuple[str, ...] = ()
    unchanged: tuple[str, ...] = ()
    modes: dict[str, int] = field(default_factory=dict)
    stdin: bytes | None = None
    pipe: str | None = None  # `sensorkit ARGV | PIPE` through sh -c; SIGPIPE is no crash
    quiet: bool = False  # stderr must stay empty
    one_line: bool | None = None  # default: when 2 is the only status expected


def m(id: str, what: str, cmd: str, status: int | tuple[int, ...] = 2, **kw: object) -> Mistake:
    st = frozenset(status if isinstance(status, tuple) else (status,))
    return Mistake(id, what, tuple(shlex.split(cmd)), status=st, **kw)  # type: ignore[arg-type]


# ---- inline robots -------------------------------------------------------------------
INERTIAL = (
    '<inertial><mass value="1"/>'
    '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'
)
PLAIN = f"""<?xml version="1.0"?>
<robot name="plain">
  <link name="base_link">{INERTIAL}</link>
</robot>
"""
XACRO_HEAD = '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
XACRO_MISSING_ARG = XACRO_HEAD + '  <link name="$(arg prefix)base_link"/>\n</robot>\n'
XACRO_FIND = (
    XACRO_HEAD + '  <xacro:include filename="$(find no_such_pkg)/urdf/cam.xacro"/>\n'
    f'  <link name="base_link">{INERTIAL}</link>\n</robot>\n'
)
XACRO_UNDEF = XACRO_HEAD + (
    '  <link name="base_link"><visual><geometry><cylinder radius="${wheel_radius}" length="0.1"/>'
    "</geometry></visual></link>\n</robot>\n"
)
XACRO_INCLUDE_MISSING = XACRO_HEAD + (
    '  <xacro:include filename="parts/wheels.xacro"/>\n'
    f'  <link name="base_link">{INERTIAL}</link>\n</robot>\n'
)
XACRO_MACRO_PARAM = XACRO_HEAD + (
    '  <xacro:macro name="wheel" params="side radius">\n'
    '    <link name="${side}_wheel"/>\n  </xacro:macro>\n'
    f'  <link name="base_link">{INERTIAL}</link>\n'
    '  <xacro:wheel side="left"/>\n</robot>\n'
)
XACRO_ARG = XACRO_HEAD + (
    '  <xacro:arg name="prefix" default=""/>\n'
    f'  <link name="$(arg prefix)base_link">{INERTIAL}</link>\n</robot>\n'
)
MACRO_ONLY = XACRO_HEAD + (
    '  <xacro:macro name="bumper" params="parent">\n'
    '    <link name="bumper"/>\n  </xacro:macro>\n</robot>\n'
)
BAD_XML = '<?xml version="1.0"?>\n<robot name="r">\n  <link name="base_link">\n</robot>\n'
SDF = '<?xml version="1.0"?>\n<sdf version="1.9">\n  <model name="m"><link name="l"/></model>\n</sdf>\n'
PACKAGE_XML = (
    '<?xml version="1.0"?>\n<package format="3">\n  <name>my_robot</name>\n'
    "  <version>0.0.0</version>\n  <description>d</description>\n"
    '  <maintainer email="a@b.c">a</maintainer>\n  <license>MIT</license>\n</package>\n'
)
LAUNCH_PY = "from launch import LaunchDescription\n\ndef generate_launch_description():\n    return LaunchDescription([])\n"
PNG = b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 4


def robot_yaml(sensors: str = "", head: str = "") -> str:
    head = head or "name: my_robot\nbase: diff_drive\nsim: classic\n"
    camera = "  - {type: camera, name: front_camera, parent: base_link, xyz: [0.2, 0, 0.1]}\n"
    return head + "sensors:\n" + (sensors or camera)


BAD = {"r.urdf": Copy("tests/robots/acceptance/sk502_bad.urdf")}
GOOD = {"r.urdf": Copy("tests/robots/acceptance/sk502_fixed.urdf")}
YAML = {"robot.yaml": Copy("examples/harmonic_robot/robot.yaml")}
CAR = {
    "car": Copy("examples/orbslam3_car"),
    "macros": Copy("macros"),
    "templates": Copy("templates"),
}
CAR_X = "car/urdf/orbslam3_car.urdf.xacro"
PKG = {
    "ws/robot.yaml": Copy("examples/harmonic_robot/robot.yaml"),
    "ws/pkg": Copy("examples/harmonic_robot/harmonic_robot_description"),
}
PKG_X = "ws/pkg/urdf/harmonic_robot.urdf.xacro"
ADD = "add-camera r.urdf --name cam2 --parent base_link --xyz 0.2 0 0.3"
RO = {"ro": 0o555}
# sk502_fixed with its optical rotation written approximately: one SK505 info, --fix-able
APPROX = (
    (ROOT / "tests/robots/acceptance/sk502_fixed.urdf")
    .read_text()
    .replace('rpy="-1.5707963267948966 0 -1.5707963267948966"', 'rpy="-1.57 0 -1.57"')
)


def help_mistakes() -> list[Mistake]:
    return [
        m("H01", "sensorkit alone", "", (0, 2), words=("validate", "--help"), one_line=False),
        m("H02", "a misspelt command", "valdiate r.urdf", 2, files=BAD, words=("validate",)),
        m("H03", "git's habit: sensorkit help", "help", 2, words=("help",)),
        m("H04", "lowercase -v for the version", "-v", 2, words=("-v",)),
        m("H05", "help of validate: groups, escaped markup, plain usage", "validate --help", 0,
          words=("[tool.sensorkit]", "Rules", "Fixing", "example"), forbid=("{files}",)),
        m("H06", "help of rules", "rules --help", 0, words=("example",)),
        m("H07", "help of new", "new --help", 0, words=("robot", "example", "[tool.sensorkit]")),
        m("H08", "help of intrinsics", "intrinsics --help", 0,
          words=("--convention", "example", "[tool.sensorkit]"), forbid=("{file}",)),
        m("H09", "help of export", "export --help", 0, words=("--out", "example"), forbid=("{file}",)),
        m("H10", "help of topics", "topics --help", 0, words=("example", "[tool.sensorkit]"),
          forbid=("{file}",)),
        m("H11", "help of frames", "frames --help", 0, words=("dot", "example"), forbid=("{file}",)),
        m("H12", "help of render", "render --help", 0, words=("preview",)),
        m("H13", "help of render preview", "render preview --help", 0,
          words=("--out", "example", "[tool.sensorkit]"), forbid=("{file}",)),
        m("H14", "help of lsp", "lsp --help", 0, words=("language server",)),
        m("H15", "-h instead of --help", "validate -h", 0, words=("--fix",)),
        *(m(f"H{16 + n}", f"help of {cmd}: defaults shown", f"{cmd} --help", 0,
            words=("--parent", "default", "example", "[tool.sensorkit]"), forbid=("{file}",))
          for n, cmd in enumerate(("add-camera", "add-depth-camera", "add-lidar", "add-stereo", "add-imu"))),
    ]  # fmt: skip


def validate_mistakes() -> list[Mistake]:
    return [
        m("V01", "validate a robot YAML", "validate robot.yaml", files=YAML,
          words=("robot.yaml", "sensorkit new")),
        m("V02", "validate package.xml", "validate package.xml", files={"package.xml": PACKAGE_XML},
          words=("package.xml",)),
        m("V03", "validate an empty file", "validate empty.urdf", (1, 2), files={"empty.urdf": ""},
          words=("empty.urdf",)),
        m("V04", "validate a binary file named .urdf", "validate photo.urdf", (1, 2),
          files={"photo.urdf": PNG}, words=("photo.urdf",)),
        m("V05", "validate a PNG", "validate photo.png", files={"photo.png": PNG}, words=("photo.png",)),
        m("V06", "validate a folder with no robot", "validate empty_dir", files={"empty_dir": Dir()},
          words=("empty_dir",)),
        m("V07", "validate a file that is not there", "validate nothere.urdf", words=("nothere.urdf",)),
        m("V08", "validate an unreadable file", "validate r.urdf", files=BAD, modes={"r.urdf": 0o000},
          words=("r.urdf",)),
        m("V09", "validate a dangling symlink", "validate link.urdf",
          files={"link.urdf": Link("gone.urdf")}, words=("link.urdf",)),
        m("V10", "validate through a symlink", "validate link.urdf", 1,
          files={**BAD, "link.urdf": Link("r.urdf")}, words=("SK502", "link.urdf")),
        m("V11", "validate a launch file", "validate sim.launch.py", files={"sim.launch.py": LAUNCH_PY},
          words=("sim.launch.py",)),
        m("V12", "a robot YAML among robots", "validate r.urdf robot.yaml", files={**BAD, **YAML},
          words=("robot.yaml", "sensorkit new")),
        m("V13", "an SDF model given to validate (read since issue 28)", "validate model.sdf", 0,
          files={"model.sdf": SDF}, words=("model.sdf", "no findings")),
        m("V14", "validate with no file", "validate", words=("FILE",)),
        m("V15", "xacro's habit: name:=value after the file", "validate robot.xacro prefix:=left_", 0,
          files={"robot.xacro": XACRO_ARG}),
        m("V16", "--arg without :=", "validate robot.xacro --arg prefix", files={"robot.xacro": XACRO_ARG},
          words=("--arg", "prefix")),
        m("V17", "--arg with an empty name", "validate robot.xacro --arg :=x",
          files={"robot.xacro": XACRO_ARG}, words=("--arg",)),
        m("V18", "--arg name:= (empty value is legal xacro)", "validate robot.xacro --arg prefix:=", 0,
          files={"robot.xacro": XACRO_ARG}),
        m("V19", "a xacro arg with no default not given", "validate robot.xacro", 1,
          files={"robot.xacro": XACRO_MISSING_ARG}, words=("SK102", "prefix", "robot.xacro")),
        m("V20", "$(find) of a package not in the workspace", "validate robot.xacro", 1,
          files={"robot.xacro": XACRO_FIND}, words=("SK103", "no_such_pkg", "--package-path")),
        m("V21", "an undefined xacro property", "validate robot.xacro", 1,
          files={"robot.xacro": XACRO_UNDEF}, words=("SK102", "wheel_radius")),
        m("V22", "an include that is not there", "validate robot.xacro", 1,
          files={"robot.xacro": XACRO_INCLUDE_MISSING}, words=("parts/wheels.xacro",)),
        m("V23", "a macro called without a parameter", "validate robot.xacro", 1,
          files={"robot.xacro": XACRO_MACRO_PARAM}, words=("SK102", "radius")),
        m("V24", "broken XML", "validate r.urdf", 1, files={"r.urdf": BAD_XML},
          words=("SK101", "r.urdf:")),
        m("V25", "--format xml", "validate r.urdf --format xml", files=BAD,
          words=("--format", "xml", "sarif")),
        m("V26", "--target noetic", "validate r.urdf --target noetic", files=BAD,
          words=("noetic", "ros1")),
        m("V27", "--target gazebo", "validate r.urdf --target gazebo", files=BAD,
          words=("gazebo", "classic")),
        m("V28", "--jobs -1", "validate r.urdf --jobs -1", files=BAD, words=("--jobs", "-1")),
        m("V29", "--jobs abc", "validate r.urdf -j abc", files=BAD, words=("--jobs", "abc")),
        m("V30", "--select an id that does not exist", "validate r.urdf --select SK999", files=BAD,
          words=("SK999",)),
        m("V31", "--ignore a prefix matching nothing", "validate r.urdf --ignore SK9", files=BAD,
          words=("SK9",)),
        m("V32", "--fail-on fatal", "validate r.urdf --fail-on fatal", files=BAD,
          words=("--fail-on", "fatal")),
        m("V33", "--fix with stdin", "validate --fix -", files=BAD, stdin=b"<robot name='r'/>",
          words=("--fix", "stdin")),
        m("V34", "--diff with stdin", "validate --diff -", files=BAD, stdin=b"<robot name='r'/>",
          words=("--diff", "stdin")),
        m("V35", "--fix on a read-only file", "validate --fix r.urdf", files=BAD, modes={"r.urdf": 0o444},
          words=("r.urdf",), unchanged=("r.urdf",)),
        m("V36", "--fix in a read-only folder", "validate --fix ro/r.urdf",
          files={"ro/r.urdf": Copy("tests/robots/acceptance/sk502_bad.urdf")}, modes=RO,
          words=("ro", "not writable"), unchanged=("ro/r.urdf",)),
        m("V37", "--fix on a hard-linked file", "validate --fix r.urdf",
          files={**BAD, "twin.urdf": Hard("r.urdf")}, words=("r.urdf", "hard link"),
          unchanged=("r.urdf", "twin.urdf")),
        m("V38", "--stdin-filename without -", "validate r.urdf --stdin-filename x.urdf", files=BAD,
          words=("--stdin-filename",)),
        m("V39", "empty stdin", "validate -", (1, 2), stdin=b"", words=("stdin",)),
        m("V40", "--config pointing nowhere", "validate r.urdf --config nowhere.toml", files=BAD,
          words=("nowhere.toml",)),
        m("V41", "sensorkit.toml with a misspelt key", "validate r.urdf",
          files={**BAD, "sensorkit.toml": 'targte = "classic"\n'}, words=("sensorkit.toml", "targte")),
        m("V42", "sensorkit.toml that is not TOML", "validate r.urdf",
          files={**BAD, "sensorkit.toml": "target = harmonic\n"}, words=("sensorkit.toml",)),
        m("V43", "sensorkit.toml with an unknown target", "validate r.urdf",
          files={**BAD, "sensorkit.toml": 'target = "noetic"\n'}, words=("sensorkit.toml", "noetic")),
        m("V44", "pyproject [tool.sensorkit] with a typo", "validate r.urdf",
          files={**BAD, "pyproject.toml": '[tool.sensorkit]\nignroe = ["SK502"]\n'},
          words=("pyproject.toml", "ignroe")),
        m("V45", "--config is a folder", "validate r.urdf --config conf", files={**BAD, "conf": Dir()},
          words=("conf", "is a folder")),
        m("V46", "--config is the robot", "validate r.urdf --config r.urdf", files=BAD, words=("r.urdf",)),
        m("V47", "--package-path to nowhere", "validate robot.xacro --package-path nowhere",
          files={"robot.xacro": XACRO_FIND}, words=("nowhere",)),
        m("V48", "--bridge file not there", f"validate {PKG_X} --bridge bridge.yaml", files=PKG,
          words=("bridge.yaml",)),
        m("V49", "--launch file not there", "validate r.urdf --launch sim.launch.py", files=BAD,
          words=("sim.launch.py",)),
        m("V50", "--timeout -5", "validate r.urdf --timeout -5", files=BAD, words=("--timeout",)),
        m("V51", "pre-commit: robots and a macro-only file", "validate r.urdf parts.xacro", 1,
          files={**BAD, "parts.xacro": MACRO_ONLY}, words=("macro-only",)),
        m("V52", "pre-commit: 30 clean files at once",
          "validate " + " ".join(f"r{i}.urdf" for i in range(30)), 0,
          files={f"r{i}.urdf": Copy("tests/robots/acceptance/sk502_fixed.urdf") for i in range(30)},
          words=("30 files",)),
        m("V53", "one error in one file: plurals", "validate r.urdf", 1, files=BAD,
          words=("1 error,", "1 file"), forbid=("1 errors", "1 files")),
        m("V54", "a misspelt option", "validate r.urdf --targte classic", files=BAD,
          words=("--targte", "--target")),
        m("V55", "--target with no value", "validate r.urdf --target", files=BAD, words=("--target",)),
        m("V56", "an option as the value of another", "validate --target --fix r.urdf", files=BAD,
          words=("--target", "value"), unchanged=("r.urdf",)),
        m("V57", "--color rainbow", "validate r.urdf --color rainbow", files=BAD, words=("--color",)),
        m("V58", "a folder of only build/", "validate ws",
          files={"ws/build/r.urdf": Copy("tests/robots/acceptance/sk502_fixed.urdf")}, words=("ws",)),
        m("V59", "--fix --diff together on a fixable robot", "validate --fix --diff r.urdf", (1, 2),
          files=BAD, unchanged=("r.urdf",)),
        m("V61", "--diff in CI: a diff to apply exits 1", "validate --diff r.urdf", 1,
          files={"r.urdf": APPROX}, words=("SK505",), unchanged=("r.urdf",)),
        m("V60", "--exit-zero hides findings, not errors", "validate nothere.urdf --exit-zero",
          words=("nothere.urdf",)),
    ]  # fmt: skip


def add_mistakes() -> list[Mistake]:
    keep = ("r.urdf",)
    return [
        m("A01", "add-camera into a robot YAML", "add-camera robot.yaml --name c --parent base_link",
          files=YAML, words=("robot.yaml", "sensorkit new"), unchanged=("robot.yaml",)),
        m("A02", "add-camera into a folder", "add-camera . --name c --parent base_link", files=GOOD,
          words=("is a folder",), forbid=("hard link",), unchanged=keep),
        m("A03", "a parent link the robot does not have", "add-camera r.urdf --name c --parent chassis",
          files=GOOD, words=("chassis",), unchanged=keep),
        m("A04", "the same sensor name twice", "add-camera r.urdf --name front_camera --parent base_link",
          files=GOOD, words=("front_camera",), unchanged=keep),
        m("A05", "--xyz with two numbers before --diff",
          "add-camera r.urdf --name c --parent base_link --xyz 0.2 0 --diff", files=GOOD,
          words=("--xyz", "value"), forbid=("valid float",), unchanged=keep),
        m("A06", "--xyz a b c", "add-camera r.urdf --name c --parent base_link --xyz a b c", files=GOOD,
          words=("--xyz",), unchanged=keep),
        m("A07", "--hfov abc", ADD + " --hfov abc", files=GOOD, words=("--hfov",), unchanged=keep),
        m("A08", "--hfov 4 (beyond pi)", ADD + " --hfov 4", files=GOOD, words=("SK404", "cam2"),
          unchanged=keep),
        m("A09", "--width -640", ADD + " --width -640", files=GOOD, words=("width",), unchanged=keep),
        m("A10", "--sim gazebo", ADD + " --sim gazebo", files=GOOD, words=("--sim", "classic"),
          unchanged=keep),
        m("A11", "--gz-version noetic", ADD + " --sim gz --gz-version noetic", files=GOOD,
          words=("--gz-version", "harmonic"), unchanged=keep),
        m("A12", "add into a read-only file", ADD, files=GOOD, modes={"r.urdf": 0o444},
          words=("r.urdf", "read-only"), unchanged=keep),
        m("A13", "add into a file in a read-only folder", ADD.replace("r.urdf", "ro/r.urdf"),
          files={"ro/r.urdf": Copy("tests/robots/acceptance/sk502_fixed.urdf")}, modes=RO,
          words=("ro", "not writable"), unchanged=("ro/r.urdf",)),
        m("A14", "-o names a folder", ADD + " -o outdir", files={**GOOD, "outdir": Dir()},
          words=("outdir", "is a folder"), unchanged=keep),
        m("A15", "-o into a read-only folder", ADD + " -o ro/out.urdf", files={**GOOD, "ro": Dir()},
          modes=RO, words=("ro", "not writable"), unchanged=keep),
        m("A16", "add into an empty file", "add-camera e.urdf --name c --parent base_link",
          files={"e.urdf": ""}, words=("e.urdf",), unchanged=("e.urdf",)),
        m("A17", "add without --name", "add-camera r.urdf --parent base_link", files=GOOD,
          words=("--name",), unchanged=keep),
        m("A18", "a name with a space", "add-camera r.urdf --name 'front cam' --parent base_link",
          files=GOOD, words=("front cam",), unchanged=keep),
        m("A19", "--param without =", ADD + " --param foo", files=GOOD, words=("--param",),
          unchanged=keep),
        m("A20", "--param of no macro parameter", ADD + " --param nosuch=1", files=GOOD, words=("nosuch",),
          unchanged=keep),
        m("A21", "--sim classic into a package new made for gz",
          f"add-camera {PKG_X} --name c2 --parent base_link --sim classic", files=PKG,
          words=("--sim", "robot.yaml"), unchanged=(PKG_X, "ws/robot.yaml")),
        m("A22", "add into stdin", "add-camera - --name c --parent base_link", stdin=PLAIN.encode(),
          words=("stdin",)),
        m("A23", "add into a xacro whose $(find) fails",
          "add-camera robot.xacro --name c --parent base_link", files={"robot.xacro": XACRO_FIND},
          words=("no_such_pkg",), unchanged=("robot.xacro",)),
        m("A24", "add into a dangling symlink", "add-camera l.urdf --name c --parent base_link",
          files={"l.urdf": Link("gone.urdf")}, words=("l.urdf",)),
        m("A25", "add into a hard-linked file", ADD, files={**GOOD, "twin.urdf": Hard("r.urdf")},
          words=("r.urdf", "hard link"), unchanged=("r.urdf", "twin.urdf")),
        m("A26", "add into a binary file", "add-camera p.urdf --name c --parent base_link",
          files={"p.urdf": PNG}, words=("p.urdf",), unchanged=("p.urdf",)),
        m("A27", "add-lidar --samples 0", "add-lidar r.urdf --name l --parent base_link --samples 0",
          files=GOOD, words=("samples",), unchanged=keep),
        m("A28", "add-imu named as a link that exists", "add-imu r.urdf --name camera --parent base_link",
          files=GOOD, words=("camera",), unchanged=keep),
        m("A29", "add-stereo with no --parent in a robot with no base_link",
          "add-stereo p.urdf --name st --parent base_footprint", files={"p.urdf": PLAIN},
          words=("base_footprint",), unchanged=("p.urdf",)),
        m("A30", "add-depth-camera --near larger than --far",
          ADD.replace("add-camera", "add-depth-camera") + " --near 5 --far 1", files=GOOD, words=("near",),
          unchanged=keep),
        m("A31", "add-camera into a robot.yaml-made package's YAML by mistake",
          "add-camera ws/robot.yaml --name c --parent base_link", files=PKG, words=("sensorkit new",),
          unchanged=("ws/robot.yaml",)),
        m("A32", "add into an SDF model", "add-camera model.sdf --name c --parent l",
          files={"model.sdf": SDF}, words=("model.sdf",), unchanged=("model.sdf",)),
    ]  # fmt: skip


def new_mistakes() -> list[Mistake]:
    y = "robot.yaml"
    sens = "  - {type: camera, name: cam, parent: base_link, xyz: [0.2, 0, 0.1]}\n"
    return [
        m("N01", "new on a URDF", "new r.urdf -o out", files=BAD, words=("r.urdf", "robot YAML"),
          forbid=("malformed YAML",)),
        m("N02", "new on a xacro", f"new {CAR_X} -o out", files=CAR, words=("robot YAML",)),
        m("N03", "new without -o", "new robot.yaml", files=YAML, words=("-o",)),
        m("N04", "new into a folder with the user's files", "new robot.yaml -o out",
          files={**YAML, "out/notes.txt": "mine\n"}, words=("out", "--force"),
          unchanged=("out/notes.txt",)),
        m("N05", "-o names a file", "new robot.yaml -o out.txt", files={**YAML, "out.txt": "x\n"},
          words=("out.txt",), unchanged=("out.txt",)),
        m("N06", "-o inside a read-only folder", "new robot.yaml -o ro/pkg", files={**YAML, "ro": Dir()},
          modes=RO, words=("ro", "not writable")),
        m("N07", "sensor type lidar (not lidar_2d)", "new robot.yaml -o out",
          files={y: robot_yaml("  - {type: lidar, name: l, parent: base_link, xyz: [0, 0, 0.2]}\n")},
          words=("robot.yaml:", "lidar_2d")),
        m("N08", "sensor: instead of sensors:", "new robot.yaml -o out",
          files={y: robot_yaml().replace("sensors:", "sensor:")}, words=("robot.yaml", "sensor")),
        m("N09", "an unknown base", "new robot.yaml -o out",
          files={y: robot_yaml(head="name: r\nbase: tank\nsim: classic\n")}, words=("tank", "diff_drive")),
        m("N10", "sim: gazebo", "new robot.yaml -o out",
          files={y: robot_yaml(head="name: r\nbase: diff_drive\nsim: gazebo\n")},
          words=("gazebo", "classic")),
        m("N11", "a parent link the base does not have", "new robot.yaml -o out",
          files={y: robot_yaml(sens.replace("base_link", "chassis"))}, words=("chassis",)),
        m("N12", "xyz with two numbers", "new robot.yaml -o out",
          files={y: robot_yaml(sens.replace("[0.2, 0, 0.1]", "[0.2, 0]"))}, words=("robot.yaml:", "xyz")),
        m("N13", "two sensors of one name", "new robot.yaml -o out", files={y: robot_yaml(sens + sens)},
          words=("cam",)),
        m("N14", "an empty robot YAML", "new robot.yaml -o out", files={y: ""}, words=("robot.yaml",)),
        m("N15", "a tab in the YAML", "new robot.yaml -o out",
          files={y: robot_yaml().replace("  - {", "\t- {")}, words=("robot.yaml:",)),
        m("N16", "a misspelt macro option", "new robot.yaml -o out",
          files={y: robot_yaml(sens.replace("}", ", options: {widht: 640}}"))}, words=("widht",)),
        m("N17", "new on a folder", "new ws -o out", files={"ws": Dir()}, words=("ws", "is a folder")),
        m("N18", "new on a YAML that is not there", "new robots.yaml -o out", words=("robots.yaml",)),
        m("N19", "gz_version noetic", "new robot.yaml -o out",
          files={y: robot_yaml(head="name: r\nbase: diff_drive\nsim: gz\ngz_version: noetic\n")},
          words=("noetic", "harmonic")),
        m("N20", "a name with a dash (not a ROS package name)", "new robot.yaml -o out",
          files={y: robot_yaml(head="name: my-robot\nbase: diff_drive\nsim: classic\n")},
          words=("my-robot",)),
    ]  # fmt: skip


def other_mistakes() -> list[Mistake]:
    preview = "render preview r.urdf --out p"
    return [
        m("R01", "render a robot YAML", "render preview robot.yaml --out p", files=YAML,
          words=("robot.yaml", "sensorkit new")),
        m("R02", "render without preview", "render r.urdf", files=BAD, words=("preview",)),
        m("R03", "--out a folder of the user's", preview, files={**BAD, "p/notes.txt": "mine\n"},
          words=("p", "--force"), unchanged=("p/notes.txt",)),
        m("R04", "--out inside a read-only folder", "render preview r.urdf --out ro/p",
          files={**BAD, "ro": Dir()}, modes=RO, words=("ro", "not writable")),
        m("R05", "--out names a file", "render preview r.urdf --out p.txt", files={**BAD, "p.txt": "x\n"},
          words=("p.txt",), unchanged=("p.txt",)),
        m("R06", "--max-pixels -1", preview + " --max-pixels -1", files=BAD, words=("--max-pixels",)),
        m("R07", "--scene not there", preview + " --scene world.urdf", files=BAD, words=("world.urdf",)),
        m("R08", "render stdin", "render preview - --out p", stdin=PLAIN.encode(), words=("stdin",)),
        m("R09", "--sensor no such sensor", preview + " --sensor rear", files=BAD,
          words=("rear", "front_camera")),
        m("R10", "render preview of a folder", "render preview . --out p", files=BAD,
          words=("is a folder",)),
        m("I01", "intrinsics of a robot with no camera", "intrinsics p.urdf", files={"p.urdf": PLAIN},
          words=("camera",)),
        m("I02", "intrinsics --sensor no such camera", "intrinsics r.urdf --sensor rear", files=BAD,
          words=("rear", "front_camera")),
        m("I03", "intrinsics --format yaml", "intrinsics r.urdf --format yaml", files=BAD,
          words=("--format", "kalibr")),
        m("I04", "intrinsics --convention ros", "intrinsics r.urdf --convention ros", files=BAD,
          words=("--convention", "classic")),
        m("I05", "intrinsics --imu of no IMU", "intrinsics r.urdf --imu imu9", files=BAD, words=("imu9",)),
        m("I06", "intrinsics of a robot YAML", "intrinsics robot.yaml", files=YAML,
          words=("sensorkit new",)),
        m("E01", "export without --out: told where it went", "export r.urdf", 0, files=BAD,
          words=("sensorkit-export",), forbid=("1 sensors",)),
        m("E02", "export --out names a file", "export r.urdf --out c.txt", files={**BAD, "c.txt": "x\n"},
          words=("c.txt",), unchanged=("c.txt",)),
        m("E03", "export --out inside a read-only folder", "export r.urdf --out ro/c",
          files={**BAD, "ro": Dir()}, modes=RO, words=("ro", "not writable")),
        m("E04", "export into a folder of the user's", "export r.urdf --out c",
          files={**BAD, "c/notes.txt": "mine\n"}, words=("c", "--force"), unchanged=("c/notes.txt",)),
        m("E05", "export a robot YAML", "export robot.yaml --out c", files=YAML, words=("sensorkit new",)),
        m("T01", "topics of a robot YAML", "topics robot.yaml", files=YAML, words=("sensorkit new",)),
        m("T02", "topics --format csv", "topics r.urdf --format csv", files=BAD,
          words=("--format", "json")),
        m("T03", "topics --bridge not there", f"topics {PKG_X} --bridge bridge.yaml", files=PKG,
          words=("bridge.yaml",)),
        m("T04", "topics --bridge given the robot", f"topics {PKG_X} --bridge {PKG_X}", files=PKG,
          words=(PKG_X,)),
        m("T05", "topics --bridge on a Classic robot is said to be ignored",
          "topics r.urdf --bridge b.yaml", 0, files={**BAD, "b.yaml": "[]\n"},
          words=("--bridge", "ignored")),
        m("F01", "frames of a robot YAML", "frames robot.yaml", files=YAML, words=("sensorkit new",)),
        m("F02", "frames --format png", "frames r.urdf --format png", files=BAD,
          words=("--format", "dot")),
        m("F03", "frames of a folder", "frames .", files=BAD, words=("is a folder",)),
        m("S01", "rules of an id that does not exist", "rules SK999", words=("SK999",)),
        m("S02", "rules --format yaml", "rules --format yaml", words=("--format",)),
        m("P01", "sensorkit rules | head -1", "rules", (0, 141), pipe="head -1", quiet=True,
          forbid=("Broken pipe",)),
        m("P02", "sensorkit validate | head -1", "validate r.urdf", (1, 141), files=BAD, pipe="head -1",
          quiet=True, forbid=("Broken pipe",)),
        m("P03", "sensorkit frames -f dot | head -1", "frames r.urdf -f dot", (0, 141), files=BAD,
          pipe="head -1", forbid=("Broken pipe",)),
    ]  # fmt: skip


# ---- issue 38: a newcomer's second hour ---------------------------------------------------
FIXED = (ROOT / "tests/robots/acceptance/sk502_fixed.urdf").read_text()
HARMONIC = {"pkg": Copy("examples/harmonic_robot/harmonic_robot_description")}
HARMONIC_X = "pkg/urdf/harmonic_robot.urdf.xacro"
PREFIXED_ROOT = FIXED.replace("<robot name=", '<urdf:robot xmlns:urdf="http://www.ros.org" name=', 1).replace(
    "</robot>", "</urdf:robot>"
)
XACRO_BANNER = FIXED.replace(
    "<robot ",
    "<!-- |    This document was autogenerated by xacro from src/bot/urdf/bot.urdf.xacro | -->\n<robot ",
    1,
)
MESH_TWICE = XACRO_HEAD + (
    '  <xacro:macro name="standoff" params="n">\n'
    '    <link name="standoff_${n}"><visual><geometry>'
    '<mesh filename="meshes/standoff.dae"/></geometry></visual></link>\n'
    '    <joint name="j_${n}" type="fixed"><parent link="base_link"/>'
    '<child link="standoff_${n}"/></joint>\n  </xacro:macro>\n'
    f'  <link name="base_link">{INERTIAL}</link>\n'
    '  <xacro:standoff n="1"/>\n  <xacro:standoff n="2"/>\n</robot>\n'
)
DEGREES_YAML = robot_yaml(
    "  - {type: camera, name: front_camera, parent: base_link, xyz: [0.2, 0, 0.1], rpy: [0, 15, 0]}\n"
)
BRIDGE_YAML = (
    "- ros_topic_name: /front_camera/image_raw\n  gz_topic_name: /front_camera/image\n"
    "  ros_type_name: sensor_msgs/msg/Image\n  gz_type_name: gz.msgs.Image\n"
    "  direction: GZ_TO_ROS\n"
)


LIDAR_ON_BASE = f"""<?xml version="1.0"?>
<robot name="r">
  <link name="base_link">{INERTIAL}</link>
  <link name="laser_link">{INERTIAL}</link>
  <joint name="laser_joint" type="fixed"><parent link="base_link"/><child link="laser_link"/>
    <origin xyz="0.1 0 0.2"/></joint>
  <gazebo reference="laser_link">
    <sensor name="laser" type="ray"><update_rate>10</update_rate>
      <ray><scan><horizontal><samples>360</samples><min_angle>-3.14</min_angle>
        <max_angle>3.14</max_angle></horizontal></scan><range><min>0.1</min><max>10</max></range></ray>
      <plugin name="laser_plugin" filename="libgazebo_ros_ray_sensor.so">
        <output_type>sensor_msgs/LaserScan</output_type><frame_name>base_link</frame_name>
      </plugin>
    </sensor>
  </gazebo>
</robot>
"""


DUP_PACKAGE_XML = (
    '<?xml version="1.0"?><package format="3"><name>my_robot</name><version>0.0.1</version>'
    '<description>d</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>'
    "</package>\n"
)
DUP_TOP = "ws/src/b/my_robot/urdf/robot.urdf.xacro"
DUP_WS: dict[str, Setup] = {
    "ws/src/a/my_robot/package.xml": DUP_PACKAGE_XML,
    "ws/src/a/my_robot/urdf/parts.xacro": XACRO_HEAD + '  <link name="old_link"/>\n</robot>\n',
    "ws/src/b/my_robot/package.xml": DUP_PACKAGE_XML,
    "ws/src/b/my_robot/urdf/parts.xacro": XACRO_HEAD + '  <link name="new_link"/>\n</robot>\n',
    DUP_TOP: XACRO_HEAD
    + f'  <link name="base_link">{INERTIAL}</link>\n'
    + '  <xacro:include filename="$(find my_robot)/urdf/parts.xacro"/>\n</robot>\n',
}
GZ_CAMERA = (
    '<sensor name="cam" type="camera"><update_rate>30</update_rate><topic>cam</topic>'
    "<camera><horizontal_fov>1.0</horizontal_fov><image><width>320</width><height>240</height>"
    "</image><clip><near>0.1</near><far>100</far></clip></camera></sensor>"
)
NESTED_WORLD: dict[str, Setup] = {
    "world.sdf": '<?xml version="1.0"?>\n<sdf version="1.9">\n  <world name="demo">\n'
    "    <include><uri>model://rover</uri></include>\n  </world>\n</sdf>\n",
    "rover/model.sdf": '<?xml version="1.0"?>\n<sdf version="1.9">\n  <model name="rover">\n'
    '    <link name="chassis"><sensor name="imu" type="imu"><update_rate>100</update_rate>'
    "<topic>imu</topic><imu/></sensor></link>\n"
    "    <include><uri>model://headd</uri><name>head</name></include>\n  </model>\n</sdf>\n",
    "head/model.sdf": '<?xml version="1.0"?>\n<sdf version="1.9">\n  <model name="head">\n'
    f'    <link name="cam_link">{GZ_CAMERA}</link>\n  </model>\n</sdf>\n',
}
NO_SENSORS_WORLD = (
    '<?xml version="1.0"?>\n<sdf version="1.9">\n  <world name="yard">\n'
    '    <plugin filename="gz-sim-physics-system" name="gz::sim::systems::Physics"/>\n'
    '    <model name="post"><static>true</static>\n'
    f'      <link name="l">{GZ_CAMERA}</link>\n    </model>\n  </world>\n</sdf>\n'
)


def second_hour_mistakes() -> list[Mistake]:
    """Issue 38's list: silent wrongs and misleading messages met following the README."""
    u16 = {"r.urdf": FIXED.encode("utf-16")}
    return [
        m("K01", "a URDF saved as UTF-16 (check_urdf refuses it)", "validate r.urdf", 1, files=u16,
          words=("SK101", "UTF-16", "save the file as UTF-8")),
        m("K02", "a xacro saved as UTF-16", "validate r.urdf.xacro", 1,
          files={"r.urdf.xacro": XACRO_ARG.encode("utf-16")}, words=("SK101", "UTF-16")),
        m("K03", "a URDF saved as UTF-32", "validate r.urdf", 1, files={"r.urdf": FIXED.encode("utf-32")},
          words=("UTF-32",)),
        m("K04", "a <urdf:robot xmlns:urdf=...> root", "validate r.urdf", 1,
          files={"r.urdf": PREFIXED_ROOT}, words=("<urdf:robot>", "Could not find the 'robot' element")),
        m("K05", "a misspelt xacro arg", f"validate {HARMONIC_X} --arg simm:=gz", 0, files=HARMONIC,
          words=("did you mean 'sim'", "xacro ignores it")),
        m("K06", "a misspelt xacro arg, the xacro way (name:=value)", f"validate {HARMONIC_X} simm:=gz", 0,
          files=HARMONIC, words=("did you mean 'sim'",)),
        m("K07", "a misspelt xacro arg given to topics", f"topics {HARMONIC_X} --arg simm:=gz", 0,
          files=HARMONIC, words=("warning", "did you mean 'sim'"), one_line=False),
        m("K08", "an arg value with a space", "validate robot.xacro --arg 'prefix:=my robot/'", 0,
          files={"robot.xacro": XACRO_ARG}, words=("white space", "prefix:=my_robot/")),
        m("K09", "rpy in degrees in a robot YAML", "new robot.yaml -o pkg",
          files={"robot.yaml": DEGREES_YAML}, words=("robot.yaml:", "more than 2π", "radians")),
        m("K10", "add-camera onto an optical frame", "add-camera r.urdf --name c2 --parent camera_optical_frame",
          files={"r.urdf": FIXED}, words=("optical frame", "pass --parent camera_link"),
          unchanged=("r.urdf",)),
        m("K11", "add-camera into a URDF xacro generated", "add-imu r.urdf --name imu --parent base_link",
          files={"r.urdf": XACRO_BANNER}, words=("generated by xacro", "add-imu src/bot/urdf/bot.urdf.xacro"),
          unchanged=("r.urdf",)),
        m("K12", "--select SK502 --ignore SK5", "validate r.urdf --select SK502 --ignore SK5", files=BAD,
          words=("--ignore SK5", "nothing would be checked"), forbid=("no findings",)),
        m("K13", "--config naming a pyproject.toml without [tool.sensorkit]",
          "validate r.urdf --config pyproject.toml", files={**BAD, "pyproject.toml": '[project]\nname = "x"\n'},
          words=("[tool.sensorkit]",)),
        m("K14", "a bridge YAML passed as the robot", "validate bridge.yaml",
          files={"bridge.yaml": BRIDGE_YAML}, words=("ros_gz_bridge", "--bridge bridge.yaml"),
          forbid=("sensorkit new",)),
        m("K15", "topics: each topic once", f"topics {HARMONIC_X}", 0, files=HARMONIC,
          words=("sensor_msgs/msg/Image",), forbid=("[sensor_msgs/msg/Image]",), one_line=False),
        m("K16", "topics --format list: what ros2 topic list -t prints", f"topics {HARMONIC_X} -f list", 0,
          files=HARMONIC, words=("/front_camera/image_raw [sensor_msgs/msg/Image]",), one_line=False),
        m("K17", "a missing mesh used by two macro calls", "validate robot.xacro", 0,
          files={"robot.xacro": MESH_TWICE}, words=("SK104", "2 uses of it")),
        m("K18", "the lsp extra's install line", "lsp -h", 0, words=("language server",)),
        m("K19", "a UTF-16 URDF given to add-camera (edited in UTF-16, and said)",
          "add-camera r.urdf --name c2 --parent base_link", 0, files=u16,
          words=("UTF-16", "save the file as UTF-8")),
        m("K20", "rpy in degrees on the command line (the near miss of K09)",
          "add-camera r.urdf --name c2 --parent base_link --rpy 0 15 0", files=BAD,
          words=("more than 2π",), unchanged=("r.urdf",)),
        m("K21", "topics on a world whose include does not resolve", "topics world.sdf", 0,
          files={"world.sdf": (ROOT / "tests/robots/sdf/world.sdf").read_text()},
          words=("SK107", "does not resolve", "not listed"), one_line=False),
        m("K22", "a lidar stamped base_link: the fix line", "validate lidar.urdf", 1,
          files={"lidar.urdf": LIDAR_ON_BASE}, words=("publish in 'laser_link'", "--fix does this"),
          forbid=("move 'base_link'",)),
        m("K23", "two copies of one package in a workspace (colcon refuses it)",
          f"validate {DUP_TOP}", 1, files=DUP_WS,
          words=("SK103", "ws/src twice", "Duplicate package names not supported",
                 "sensorkit read ws/src/b/my_robot", "COLCON_IGNORE")),
        m("K24", "topics on a robot whose package is twice in the workspace", f"topics {DUP_TOP}", 0,
          files=DUP_WS, words=("warning", "SK103", "twice"), forbid=("not listed",), one_line=False),
        m("K25", "topics on a world whose robot's nested include is missing", "topics world.sdf", 0,
          files=NESTED_WORLD, words=("SK107", "model://headd", "world.sdf -> model://rover", "not listed"),
          one_line=False),
        m("K26", "a Harmonic world with a camera and no Sensors system", "validate world.sdf --target harmonic",
          1, files={"world.sdf": NO_SENSORS_WORLD},
          words=("SK620", 'filename="gz-sim-sensors-system"', "render_engine"),
          forbid=("fortress", "ignition")),
        m("K27", "a Fortress world with a camera and no Sensors system", "validate world.sdf --target fortress",
          1, files={"world.sdf": NO_SENSORS_WORLD},
          words=("SK620", 'filename="ignition-gazebo-sensors-system"'), forbid=("gz-sim-sensors-system",)),
        m("K28", "a world validated for Harmonic: no advice about Fortress",
          "validate world.sdf --target harmonic", 1,
          files={"world.sdf": NO_SENSORS_WORLD.replace("<topic>cam</topic>",
                                                       "<topic>cam</topic><ignition_frame_id>l</ignition_frame_id>")},
          words=("SK608", "<gz_frame_id>"), forbid=("fortress", "ignition-gazebo")),
        m("K29", "new: the header names the robot YAML the user has", "new robot.yaml -o bot_description", 0,
          files={"robot.yaml": "name: bot\nsim: none\nsensors:\n  - {type: imu, name: imu, parent: base_link}\n"},
          pipe="{ cat >/dev/null; head -6 bot_description/urdf/bot.urdf.xacro; }",
          words=("Change ../robot.yaml", "sensorkit new robot.yaml -o bot_description")),
    ]


MISTAKES = (
    help_mistakes()
    + validate_mistakes()
    + add_mistakes()
    + new_mistakes()
    + other_mistakes()
    + second_hour_mistakes()
)


# ---- running -------------------------------------------------------------------------
def build(tmp: Path, mk: Mistake) -> None:
    for rel, what in mk.files.items():
        p = tmp / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(what, Copy):
            src = ROOT / what.src
            if src.is_dir():
                shutil.copytree(src, p, symlinks=True)
            else:
                shutil.copyfile(src, p)
        elif isinstance(what, Link):
            p.symlink_to(what.target)
        elif isinstance(what, Hard):
            os.link(tmp / what.target, p)
        elif isinstance(what, Dir):
            p.mkdir(exist_ok=True)
        else:
            p.write_bytes(what if isinstance(what, bytes) else what.encode())
    for rel, mode in mk.modes.items():
        os.chmod(tmp / rel, mode)


def without_root_powers(cmd: list[str]) -> list[str]:
    """As root, drop the capabilities that ignore file modes, so modes mean what they say."""
    if os.geteuid() != 0 or shutil.which("capsh") is None:
        return cmd
    caps = "--drop=cap_dac_override,cap_dac_read_search"
    return ["capsh", caps, "--", "-c", 'exec "$0" "$@"', *cmd]


@dataclass
class Result:
    status: int
    stdout: str
    stderr: str
    changed: list[str]


def run(mk: Mistake) -> Result:
    with tempfile.TemporaryDirectory(prefix="sk-mistake-") as t:
        tmp = Path(t)
        build(tmp, mk)
        before = {rel: (tmp / rel).read_bytes() for rel in mk.unchanged}
        env = dict(os.environ, NO_COLOR="1", COLUMNS="100", XDG_CACHE_HOME=str(tmp / ".cache"))
        env.pop("FORCE_COLOR", None)
        sk = [sys.executable, "-m", "sensorkit", *mk.argv]
        if mk.pipe is None:
            p = subprocess.run(
                without_root_powers(sk),
                cwd=tmp,
                env=env,
                input=mk.stdin or b"",
                capture_output=True,
                check=False,
                timeout=300,
            )
            status, out, err = p.returncode, p.stdout, p.stderr
        else:
            (tmp / ".mk").mkdir()
            line = f"{{ {shlex.join(sk)} 2>.mk/err; echo $? >.mk/status; }} | {mk.pipe}"
            p = subprocess.run(
                without_root_powers(["sh", "-c", line]),
                cwd=tmp,
                env=env,
                capture_output=True,
                check=False,
                timeout=300,
            )
            status = int((tmp / ".mk/status").read_text().strip() or "-1")
            out, err = p.stdout, (tmp / ".mk/err").read_bytes() + p.stderr
        for rel in mk.modes:
            os.chmod(tmp / rel, 0o755)
        changed = [
            rel
            for rel, b in before.items()
            if not (tmp / rel).exists() or (tmp / rel).read_bytes() != b
        ]
        return Result(status, out.decode(errors="replace"), err.decode(errors="replace"), changed)


def judge(mk: Mistake, r: Result) -> tuple[str, str]:
    """The verdict and why, from the entry alone."""
    text = r.stdout + "\n" + r.stderr
    if TRACEBACK in text:
        return "traceback", "a Python traceback"
    signo = -r.status if r.status < 0 else r.status - 128 if r.status > 128 else 0
    if signo and not (mk.pipe and signo == signal.SIGPIPE):
        return "traceback", f"killed by signal {signo}"
    if r.changed:
        return "silent-wrong", "changed " + ", ".join(r.changed)
    if r.status == 0 and 0 not in mk.status:
        return "silent-wrong", "exit 0 where " + "/".join(map(str, sorted(mk.status))) + " is due"
    why = []
    if r.status not in mk.status:
        why.append(f"exit {r.status}, not {'/'.join(map(str, sorted(mk.status)))}")
    low = text.lower()
    why += [f"does not say {w!r}" for w in mk.words if w.lower() not in low]
    why += [f"says {w!r}" for w in mk.forbid if w.lower() in low]
    one_line = mk.one_line if mk.one_line is not None else mk.status == frozenset({2})
    lines = [ln for ln in r.stderr.splitlines() if ln.strip() and not NOTE.match(ln)]
    if one_line and r.status == 2 and (len(lines) != 1 or not lines[0].startswith("sensorkit: ")):
        why.append(f"error is {len(lines)} lines, not one 'sensorkit: ' line")
    why += [f"names a temporary file ({t})" for t in TEMP_NAMES if t in text]
    if mk.quiet and r.stderr.strip():
        why.append("stderr on a quiet exit")
    return ("misleading", "; ".join(why)) if why else ("clean", "")


def first_line(s: str) -> str:
    for ln in s.splitlines():
        if ln.strip(" │╭╰─"):
            return ln.strip()[:90]
    return ""


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument(
        "--only", action="append", default=[], metavar="ID", help="run only this entry (repeatable)"
    )
    ap.add_argument("--json", action="store_true", help="print the results as one JSON document")
    a = ap.parse_args()
    ids = [mk.id for mk in MISTAKES]
    assert len(ids) == len(set(ids)), "duplicate ids"
    chosen = [mk for mk in MISTAKES if not a.only or mk.id in a.only]
    if a.only and len(chosen) != len(set(a.only)):
        sys.exit(f"newcomer_mistakes: unknown id among {', '.join(a.only)}")
    rows = []
    for mk in chosen:
        r = run(mk)
        verdict, why = judge(mk, r)
        rows.append(
            {
                "id": mk.id,
                "what": mk.what,
                "command": "sensorkit "
                + shlex.join(mk.argv)
                + (f" | {mk.pipe}" if mk.pipe else ""),
                "verdict": verdict,
                "why": why,
                "status": r.status,
                "stderr": first_line(r.stderr),
            }
        )
        if not a.json:
            print(f"{mk.id:4} {verdict:12} {r.status:>3}  {first_line(r.stderr)}", flush=True)
            if why:
                print(f"{'':22}{why}", flush=True)
    counts = Counter(row["verdict"] for row in rows)
    if a.json:
        print(json.dumps({"mistakes": rows, "counts": {v: counts[v] for v in VERDICTS}}, indent=2))
    else:
        print(f"\n{len(rows)} mistakes: " + ", ".join(f"{counts[v]} {v}" for v in VERDICTS))


if __name__ == "__main__":
    main()
