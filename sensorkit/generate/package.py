"""``sensorkit new``: a robot YAML in, a colcon-ready ament package out.

The package is built complete in a temporary folder beside the output folder, expanded
with xacro once (the bridge is read from that expansion), and only then renamed into
place, so a failure never leaves a half-written package and ``--force`` swaps the old
one out in a single rename.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from sensorkit.base.atomic import check_replaceable, editing, staged_folder, tidy_beside
from sensorkit.base.errors import InputError
from sensorkit.describe.bridge import BridgeEntry, bridge_entries
from sensorkit.describe.intrinsics import InvalidValue
from sensorkit.exporters.bridge import bridge_file_text
from sensorkit.generate import render, rviz
from sensorkit.generate.reader import Mark
from sensorkit.generate.readme import readme
from sensorkit.generate.spec import RobotSpec, load_spec

if TYPE_CHECKING:
    from sensorkit.describe.topics import Topic


@dataclass
class GeneratedPackage:
    """What :func:`new_package` wrote (or, with ``dry_run``, would write)."""

    spec: RobotSpec
    path: Path
    files: list[str]  # relative to path, sorted, "/"-separated
    bridge: list[BridgeEntry] = field(default_factory=list)
    dry_run: bool = False

    @property
    def robot_xacro(self) -> Path:
        return self.path / "urdf" / f"{self.spec.name}.urdf.xacro"


def _write(root: Path, rel: str, data: str | bytes) -> None:
    path = root / rel
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        path.write_text(data, encoding="utf-8", newline="\n")
    else:
        path.write_bytes(data)


def _listing(root: Path) -> list[str]:
    return sorted(p.relative_to(root).as_posix() for p in root.rglob("*") if p.is_file())


def _where(spec: RobotSpec, message: str) -> Mark | None:
    """The YAML place a macro's own check points at (``sensorkit_<type> <name>: ...``)."""
    for s in spec.sensors:
        if re.search(rf"\b{re.escape(s.macro.macro)} {re.escape(s.name)}\b", message):
            return s.mark
    if spec.base_macro.macro in message:
        return spec.marks.get("base_params") or spec.marks.get("base")
    return None


def _expand(spec: RobotSpec, xacro_file: Path) -> etree._Element:
    from sensorkit.loading.packages import PackageResolver
    from sensorkit.loading.xacro_expand import expand

    outcome = expand(xacro_file, {}, PackageResolver(use_environment=False))
    if outcome.xml is None:
        text = " ".join(outcome.message.split())
        mark = _where(spec, text)
        place = str(mark) if mark else str(spec.path)
        msg = f"{place}: the generated description does not expand: {text}"
        raise InputError(msg)
    return etree.fromstring(outcome.xml.encode("utf-8"))


def ros_topics(spec: RobotSpec, root: Path, urdf: str) -> list[Topic]:
    """Every ROS topic of the package's robot's sensors on its simulator, as
    ``sensorkit topics`` lists them (on Gazebo Sim, as the written bridge names them).

    Empty for ``sim: none``: no simulator, so no topics sensorkit can name.
    """
    if spec.sim not in ("classic", "gz"):
        return []
    from sensorkit.describe.sensorinfo import describe, load
    from sensorkit.describe.topics import BridgeConfig, robot_topics
    from sensorkit.loading.bridge import read_bridge

    robot = load(root / urdf)
    info = describe(robot, "classic" if spec.sim == "classic" else spec.gz_version)
    bridge = None
    if spec.sim == "gz":
        name = "config/bridge.yaml"
        bridge = BridgeConfig([name], read_bridge(root / name, name))
    return robot_topics(info, bridge).ros_topics


def camera_images(topics: Sequence[Topic]) -> list[render.CameraImage]:
    """The camera image topics among ``topics``."""
    from sensorkit.describe.topics import IMAGE_ROLES

    return [
        render.CameraImage(t.name, t.encoding or "", t.sensor, t.role == "depth_image")
        for t in topics
        if t.role in IMAGE_ROLES and t.name is not None
    ]


def build_package(spec: RobotSpec, root: Path, *, regen: render.Regen) -> list[BridgeEntry]:
    """Write every file of the package for ``spec`` into the (empty) folder ``root``;
    ``regen`` says where its YAML is (the header and README name it).

    Returns the bridge entries (empty unless ``spec.sim == "gz"``).

    Raises:
        InputError: the assembled description does not expand, or two sensors would
            publish on the same ROS topic.
    """
    urdf = f"urdf/{spec.name}.urdf.xacro"
    _write(root, urdf, render.robot_xacro(spec, regen))
    base = spec.base_macro
    _write(root, f"urdf/{base.file.name}", base.file.read_bytes())
    for macro in {s.type: s.macro for s in spec.sensors}.values():
        _write(root, f"urdf/sensors/{macro.file.name}", macro.file.read_bytes())

    robot = _expand(spec, root / urdf)
    install = ["launch", "rviz", "urdf"]
    entries: list[BridgeEntry] = []
    if spec.sim == "gz":
        entries = bridge_entries(robot, spec.gz_version)
        try:
            text = bridge_file_text(entries, robot=spec.name, gz_version=spec.gz_version)
        except InvalidValue as exc:
            msg = f"{spec.path}: cannot write the ros_gz bridge: {exc}"
            raise InputError(msg) from None
        _write(root, "config/bridge.yaml", text)
        install.append("config")
    world = render.world_sdf(spec)
    if world is not None:
        _write(root, f"worlds/{spec.name}.sdf", world)
        install.append("worlds")
    _write(root, "launch/description.launch.py", render.description_launch(spec))
    sim = render.sim_launch(spec)
    if sim is not None:
        _write(root, "launch/sim.launch.py", sim)
    _write(root, "launch/display.launch.py", render.display_launch(spec))
    topics = ros_topics(spec, root, urdf)
    displays, unshown = rviz.sensor_displays(topics)
    frame = rviz.fixed_frame(spec, robot)
    _write(root, f"rviz/{spec.name}.rviz", rviz.rviz_config(spec, frame, displays, unshown))
    images = camera_images(topics)
    programs: list[str] = []
    if images:
        _write(root, "launch/save_frames.launch.py", render.save_frames_launch(spec, images))
        _write(root, render.SAVE_FRAMES_NODE, render.save_frames_node())
        (root / render.SAVE_FRAMES_NODE).chmod(0o755)
        programs.append(render.SAVE_FRAMES_NODE)
    _write(root, "package.xml", render.package_xml(spec, python_node=bool(programs)))
    _write(root, "CMakeLists.txt", render.cmakelists(spec, sorted(install), programs))
    _write(root, "README.md", readme(spec, regen, entries, images, unshown, frame))
    return entries


def new_package(
    spec_path: Path,
    out: Path,
    *,
    force: bool = False,
    dry_run: bool = False,
    defaults: Mapping[str, str] | None = None,
) -> GeneratedPackage:
    """Generate the ament package described by the robot YAML at ``spec_path`` into ``out``.

    ``out`` must not exist or be empty unless ``force`` (then it is replaced whole).
    With ``dry_run`` everything is built and checked in a temporary folder that is then
    deleted; nothing at ``out`` changes.

    Raises:
        InputError: the YAML is unreadable or wrong (``FILE:LINE:COLUMN: ...``), or the
            result does not expand.
        UsageError: ``out`` is not empty and ``force`` is not given, or is not a folder.
        WriteFailed: a full disk or I/O error, naming ``out``.
        OSError: the file system refused.

    The robot YAML is read under the lock an add-* into the package takes (the folder
    lock of ``out``'s parent, where the YAML of a package ``new`` made lies, and of the
    YAML's own folder), so an add and ``new --force`` take turns and neither loses the
    other's sensor; a killed writer's staging folders beside ``out`` go first, even when
    this run is then refused.
    """
    out.parent.mkdir(parents=True, exist_ok=True)
    real = Path(os.path.realpath(out))
    with editing(out, real, spec_path):
        tidy_beside(real)
        spec = load_spec(spec_path, defaults)
        check_replaceable(out, force=force, inputs=[spec_path], flag="-o")
        with staged_folder(out, publish=not dry_run) as temp:
            entries = build_package(spec, temp, regen=render.regen_for(spec_path, out))
            files = _listing(temp)
    return GeneratedPackage(spec, out, files, entries, dry_run)
