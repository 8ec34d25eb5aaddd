"""What an add changes in the ament package around the robot file, beyond the robot file.

Two cases, decided before anything is planned (:func:`read_package`):

- **Generated**: the robot file is the ``urdf/<robot>.urdf.xacro`` that ``sensorkit new
  ROBOT.yaml`` wrote (its header names the YAML), the YAML lies in the package or beside
  it, and every file under ``urdf/`` is byte for byte what that YAML generates now. The
  sensor is appended to the YAML (:mod:`sensorkit.generate.spec_edit`) and the package is
  generated from the new YAML in a temporary folder: each package file still as
  ``new`` wrote it takes the new text (so ``sensorkit new --force`` afterwards changes
  nothing), the robot file included, after a check that it expands to exactly what the
  plain add (the splice) would have given. A file edited by hand is left as it is and
  said, except the bridge and README, which get the generic edits below.
- **Any other package** (a folder with ``package.xml`` above the robot file): for a
  Gazebo Sim sensor, its ros_gz_bridge entries (the ones ``new`` and ``export`` write,
  :func:`sensorkit.describe.bridge.sensor_entries`) are appended to the package's bridge
  YAML; a README written by ``new`` gets a row in its sensor table. Both are pure
  insertions: every byte already there stays.

Nothing here writes: the caller gets :class:`PackagePlan` (files with their old bytes).
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from sensorkit.base.errors import EditRefused, InputError, SensorkitError
from sensorkit.loading.document import display_path

if TYPE_CHECKING:
    from sensorkit.describe.bridge import BridgeEntry
    from sensorkit.generate.spec import RobotSpec
    from sensorkit.loading.bridge import BridgeTopic

# The folders `sensorkit new` writes into, relative to the package (locked by add-*).
PACKAGE_DIRS = ("", "config", "launch", "rviz", "scripts", "urdf", "urdf/sensors", "worlds")
BRIDGE_NAME = "config/bridge.yaml"
README_NAME = "README.md"
SPEC_WHY = "sensor appended"  # FileChange.why of the robot YAML, which is written last
_HEADER = re.compile(r"written by `sensorkit new ([^`\s/\\]+)`")
_TABLE_HEAD = "| sensor | type | parent | xyz | rpy |"


@dataclass(frozen=True)
class FileChange:
    """One package file to write: ``old`` None means a new file."""

    path: Path
    old: bytes | None
    new: bytes
    mode: int | None = None  # a new file's mode (None: the umask's default)
    why: str = ""


@dataclass
class PackageContext:
    """The package around a robot file, read before the add is planned."""

    root: Path
    spec_path: Path | None = None
    spec: RobotSpec | None = None
    spec_bytes: bytes = b""
    yaml_name: str = ""
    defaults: dict[str, str] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)


@dataclass
class PackagePlan:
    """Files an add changes beside the robot file; ``robot`` replaces the splice."""

    changes: list[FileChange] = field(default_factory=list)
    robot: bytes | None = None
    notes: list[str] = field(default_factory=list)
    bridged: list[BridgeTopic] = field(default_factory=list)  # entries the bridge gains


def find_package(path: Path) -> Path | None:
    """The folder holding the nearest ``package.xml`` above ``path``."""
    for folder in Path(os.path.abspath(path)).parents:
        if (folder / "package.xml").is_file():
            return folder
    return None


def lock_paths(path: Path) -> list[Path]:
    """Paths whose folders an add into ``path``'s package locks (``atomic.editing`` locks
    each path's folder): the folders ``new`` writes, ``config/*`` (bridge files), and the
    package's own folder's parent, as written and resolved (a robot YAML beside the
    package; ``new -o PACKAGE`` takes the same lock before it reads that YAML)."""
    pkg = find_package(path)
    if pkg is None:
        return []
    out = [pkg, Path(os.path.realpath(pkg))]
    folders = [pkg / rel for rel in PACKAGE_DIRS]
    if (pkg / "config").is_dir():
        folders += sorted(p for p in (pkg / "config").iterdir() if p.is_dir())
    out += [folder / "package.xml" for folder in folders if folder.is_dir()]
    return out


def read_package(source: Path, data: bytes, *, untrusted: bool) -> PackageContext | None:
    """The package around ``source`` and, when ``sensorkit new`` made it and its YAML
    still generates it, that YAML (see the module doc). None outside a package."""
    pkg = find_package(source)
    if pkg is None:
        return None
    ctx = PackageContext(root=pkg)
    head = data[:4096].decode("utf-8", "replace")
    match = _HEADER.search(head)
    if match is None or source.resolve().parent != (pkg / "urdf").resolve():
        return ctx
    ctx.yaml_name = match.group(1)
    candidates = [pkg / ctx.yaml_name, pkg.parent / ctx.yaml_name]
    spec_path = next((p for p in candidates if p.is_file()), None)
    where = display_path(source)
    if spec_path is None:
        ctx.notes.append(
            f"{where} was written by `sensorkit new {ctx.yaml_name}`, but no {ctx.yaml_name} "
            f"is in {display_path(pkg)} or beside it: add the sensor there too, or "
            "`sensorkit new --force` will drop it"
        )
        return ctx
    shown = display_path(spec_path)
    if untrusted:
        ctx.notes.append(
            f"{shown} not updated: with --untrusted sensorkit does not generate from it "
            "(its ${...} values would run in xacro); add the sensor there too"
        )
        return ctx
    from sensorkit.generate import render
    from sensorkit.generate.spec import load_spec
    from sensorkit.lint.config import load_config
    from sensorkit.model.targets import is_gz

    try:
        target = load_config(spec_path).target
    except SensorkitError as exc:  # a broken settings file: new would refuse it too
        ctx.notes.append(f"{shown} not updated: {exc}")
        return ctx
    if target:  # as `sensorkit new` does for a YAML without `sim:`
        ctx.defaults["sim"] = "gz" if is_gz(target) else "classic"
        if is_gz(target):
            ctx.defaults["gz_version"] = target
    try:
        spec = load_spec(spec_path, ctx.defaults)
    except InputError as exc:
        ctx.notes.append(f"{shown} not updated: it does not read ({exc})")
        return ctx
    regen = render.regen_for(spec_path, pkg)
    expected = render.robot_xacro(spec, regen).encode("utf-8")
    if source.name != f"{spec.name}.urdf.xacro" or expected != data:
        ctx.notes.append(
            f"{shown} not updated: {where} is not what it generates (edited by hand, or "
            "written by another sensorkit version), so the package is edited file by file"
        )
        return ctx
    copies = {f"urdf/{spec.base_macro.file.name}": spec.base_macro.file}
    copies.update({f"urdf/sensors/{s.macro.file.name}": s.macro.file for s in spec.sensors})
    for rel, shipped in copies.items():
        if _read(pkg / rel) != shipped.read_bytes():
            ctx.notes.append(
                f"{shown} not updated: {display_path(pkg / rel)} is not the macro `sensorkit "
                "new` copies (edited by hand, or another sensorkit version), so the package "
                "is edited file by file"
            )
            return ctx
    ctx.spec_path, ctx.spec, ctx.spec_bytes = spec_path, spec, spec_path.read_bytes()
    others = other_generators(pkg, spec_path, ctx.yaml_name)
    if others:  # said first: the notes are printed in order, before what was added
        names = ", ".join(display_path(o) for o in others)
        ctx.notes.insert(
            0,
            f"warning: {shown} also generates {names}: the sensor added to it goes into "
            f"that package too at its next `sensorkit new --force`; if this package is a "
            f"copy, give it its own YAML (copy {ctx.yaml_name} into {display_path(pkg)})",
        )
    return ctx


def other_generators(pkg: Path, spec_path: Path, yaml_name: str) -> list[Path]:
    """The other packages that generate from the robot YAML ``spec_path`` of package
    ``pkg``: a YAML inside ``pkg`` is its own (a copied package copies it too), so there
    are none; a YAML beside ``pkg`` (in its parent folder) is shared with every other
    folder ``Q`` there that holds a ``package.xml``, no ``Q/YAML_NAME`` of its own (which
    it would generate from instead) and a ``Q/urdf/*.urdf.xacro`` whose header says it was
    ``written by `sensorkit new YAML_NAME```: ``sensorkit new --force`` of ``Q`` reads the
    same YAML, so a sensor added here appears there as well."""
    if spec_path.resolve().parent != pkg.resolve().parent:
        return []
    out: list[Path] = []
    for other in sorted(pkg.parent.iterdir()):
        if other.resolve() == pkg.resolve() or not (other / "package.xml").is_file():
            continue
        if (other / yaml_name).exists() or not (other / "urdf").is_dir():
            continue
        for robot in sorted((other / "urdf").glob("*.urdf.xacro")):
            try:
                head = robot.read_bytes()[:4096].decode("utf-8", "replace")
            except OSError:  # another package's file: not a reason to refuse this add
                continue
            match = _HEADER.search(head)
            if match is not None and match.group(1) == yaml_name:
                out.append(other)
                break
    return out


# ----------------------------------------------------------------------------- generated


@dataclass(frozen=True)
class NewSensor:
    """The sensor being added, as the package edits need it."""

    kind: str  # the macro's sensor type ("camera", ...)
    name: str
    parent: str
    xyz: Sequence[str]
    rpy: Sequence[str]
    options: Mapping[str, str]  # what the user set (macro parameter text)
    sensors: Sequence[etree._Element]  # the <sensor> elements its expansion makes
    sim: str | None  # the literal simulator it was expanded for
    gz_version: str


def _files(root: Path) -> dict[str, tuple[bytes, int]]:
    return {
        p.relative_to(root).as_posix(): (p.read_bytes(), p.stat().st_mode & 0o777)
        for p in sorted(root.rglob("*"))
        if p.is_file()
    }


def _canonical(xacro_file: Path) -> bytes:
    """The expansion of ``xacro_file`` without comments, locations and blank text."""
    from sensorkit.loading.packages import PackageResolver
    from sensorkit.loading.xacro_expand import LOC_ATTR, expand

    outcome = expand(xacro_file, {}, PackageResolver(use_environment=False))
    if outcome.xml is None:
        msg = f"internal error: {xacro_file.name} does not expand ({outcome.message})"
        raise EditRefused(msg)
    root = etree.fromstring(outcome.xml.encode("utf-8"))
    for node in list(root.iter(etree.Comment)):
        parent = node.getparent()
        if parent is not None:
            parent.remove(node)
    for el in root.iter():
        el.attrib.pop(LOC_ATTR, None)
        if el.text is not None and not el.text.strip():
            el.text = None
        if el.tail is not None and not el.tail.strip():
            el.tail = None
    return bytes(etree.tostring(root, method="c14n"))


def plan_generated(
    ctx: PackageContext, source: Path, spliced: bytes, sensor: NewSensor
) -> PackagePlan:
    """Append the sensor to the robot YAML and regenerate the package (module doc)."""
    from sensorkit.generate import render
    from sensorkit.generate.package import build_package
    from sensorkit.generate.spec import parse_spec
    from sensorkit.generate.spec_edit import SensorEntry, append_sensor

    assert ctx.spec is not None and ctx.spec_path is not None
    shown = display_path(ctx.spec_path)
    text = ctx.spec_bytes.decode("utf-8")
    entry = SensorEntry(
        sensor.kind, sensor.name, sensor.parent, sensor.xyz, sensor.rpy, sensor.options
    )
    new_text = append_sensor(text, entry, shown)
    try:
        new_spec = parse_spec(new_text, ctx.spec_path, display=shown, defaults=ctx.defaults)
    except InputError as exc:
        msg = f"{shown} would not read with the sensor added: {exc}"
        raise EditRefused(msg) from None
    if [s.name for s in new_spec.sensors] != [*(s.name for s in ctx.spec.sensors), sensor.name]:
        msg = f"internal error: the sensor appended to {shown} does not read back"
        raise EditRefused(msg)
    plan = PackagePlan()
    with tempfile.TemporaryDirectory(prefix="sensorkit-package-") as tmp:
        old_dir, new_dir = Path(tmp) / "old", Path(tmp) / "new"
        old_dir.mkdir()
        new_dir.mkdir()
        try:
            regen = render.regen_for(ctx.spec_path, ctx.root)
            build_package(ctx.spec, old_dir, regen=regen)
            build_package(new_spec, new_dir, regen=regen)
        except InputError as exc:
            msg = f"{shown}: the package does not generate with the sensor added: {exc}"
            raise EditRefused(msg) from None
        old, new = _files(old_dir), _files(new_dir)
        urdf = f"urdf/{ctx.spec.name}.urdf.xacro"
        edited = [
            rel
            for rel, (data, _) in old.items()
            if rel.startswith("urdf/") and _read(ctx.root / rel) != data
        ]
        if edited:  # read_package checked these; the files changed since
            msg = f"{display_path(ctx.root / edited[0])} changed while sensorkit worked"
            raise EditRefused(msg)
        probe = new_dir / "urdf" / ".sensorkit-add.urdf.xacro"
        probe.write_bytes(spliced)
        if _canonical(probe) != _canonical(new_dir / urdf):
            msg = (
                f"internal error: the package generated from {shown} with the sensor differs "
                f"from the add itself; nothing was written"
            )
            raise EditRefused(msg)
    plan.robot = new[urdf][0]
    for rel, (data, mode) in new.items():
        if rel == urdf:
            continue
        path = ctx.root / rel
        current = _read(path)
        before = old.get(rel, (None, 0))[0]
        if current == data:
            continue
        if current == before:
            mode_new = mode if current is None else None
            plan.changes.append(FileChange(path, current, data, mode_new, why="as new writes it"))
            if rel == BRIDGE_NAME:
                plan.bridged += _topics(path, _entries(sensor))
        elif rel == BRIDGE_NAME and current is not None:
            plan.changes += _bridge_append(path, current, sensor, plan)
        elif rel == README_NAME and current is not None:
            plan.changes += _readme_row(path, current, sensor, plan.notes)
        else:
            plan.notes.append(
                f"{display_path(path)} left as it is: it is not what `sensorkit new` "
                f"wrote (edited by hand?); `sensorkit new --force` would rewrite it"
            )
    spec_new = new_text.encode("utf-8")
    plan.changes.append(FileChange(ctx.spec_path, ctx.spec_bytes, spec_new, why=SPEC_WHY))
    return plan


def _read(path: Path) -> bytes | None:
    try:
        return path.read_bytes()
    except FileNotFoundError:
        return None
    except OSError as exc:
        msg = f"{display_path(path)}: cannot read it ({exc.strerror})"
        raise EditRefused(msg) from None


# ----------------------------------------------------------------------------- any package


def plan_package(ctx: PackageContext, sensor: NewSensor) -> PackagePlan:
    """The bridge and README edits of an add into a package ``new`` did not make (or
    whose YAML no longer generates it)."""
    plan = PackagePlan()
    if sensor.sim == "gz":
        bridge = _bridge_file(ctx.root, plan.notes)
        if bridge is not None:
            data = _read(bridge)
            if data is not None:
                plan.changes += _bridge_append(bridge, data, sensor, plan)
        elif _entries(sensor):
            topics = ", ".join(e.gz_topic_name for e in _entries(sensor))
            plan.notes.append(
                f"{display_path(ctx.root)} has no ros_gz_bridge YAML in config/: "
                f"{sensor.name}'s topics ({topics}) reach ROS only through a bridge"
            )
    readme = ctx.root / README_NAME
    data = _read(readme)
    if data is not None and b"sensorkit new" in data:
        plan.changes += _readme_row(readme, data, sensor, plan.notes)
    return plan


def _bridge_file(pkg: Path, notes: list[str]) -> Path | None:
    from sensorkit.loading.bridge import find_bridge_files

    found = find_bridge_files(pkg)
    if len(found) <= 1:
        return found[0] if found else None
    named = pkg / BRIDGE_NAME
    if named in found:
        return named
    notes.append(
        f"{display_path(pkg)} has several ros_gz_bridge YAMLs ("
        + ", ".join(display_path(p) for p in found)
        + "): none was changed; add the new sensor's topics to the one your launch file loads"
    )
    return None


def _entries(sensor: NewSensor) -> list[BridgeEntry]:
    from sensorkit.describe.bridge import sensor_entries

    out: list[BridgeEntry] = []
    for el in sensor.sensors:
        out += sensor_entries(el, sensor.gz_version)
    return out


def _topics(path: Path, entries: Sequence[BridgeEntry]) -> list[BridgeTopic]:
    from sensorkit.loading.bridge import BridgeTopic

    shown = display_path(path)
    return [
        BridgeTopic(e.gz_topic_name, e.ros_topic_name, e.ros_type_name, e.direction, shown, None)
        for e in entries
    ]


def _bridge_append(
    path: Path, data: bytes, sensor: NewSensor, plan: PackagePlan
) -> list[FileChange]:
    """The sensor's bridge entries appended to the bridge YAML ``data`` (nothing else
    changes); entries whose ROS topic the file already has are left out and said."""
    import yaml

    from sensorkit.base import yamlguard
    from sensorkit.exporters.bridge import bridge_yaml

    shown = display_path(path)
    notes = plan.notes
    entries = _entries(sensor)
    if not entries:
        return []
    try:
        text = data.decode("utf-8")
        node = yamlguard.compose(text)
    except (UnicodeDecodeError, yaml.YAMLError):
        notes.append(f"{shown} left as it is: it does not read as YAML")
        return []
    if not isinstance(node, yaml.SequenceNode) or node.flow_style or not node.value:
        notes.append(f"{shown} left as it is: not a block list of bridge entries")
        return []
    have = {
        str(v.value)
        for item in node.value
        if isinstance(item, yaml.MappingNode)
        for k, v in item.value
        if isinstance(k, yaml.ScalarNode)
        and k.value in ("ros_topic_name", "topic_name")
        and isinstance(v, yaml.ScalarNode)
    }
    fresh = [e for e in entries if e.ros_topic_name not in have]
    for e in entries:
        if e not in fresh:
            notes.append(f"{shown} already bridges {e.ros_topic_name}: not added again")
    if not fresh:
        return []
    first = node.value[0].start_mark
    line_start = text.rfind("\n", 0, first.index) + 1
    indent = text[line_start : first.index].rsplit("-", 1)[0]
    newline = "\r\n" if "\r\n" in text else "\n"
    block = "".join(f"{indent}{line}{newline}" for line in bridge_yaml(fresh).splitlines())
    lead = "" if not text or text.endswith("\n") else newline
    new = (text + lead + block).encode("utf-8")
    try:
        loaded = yamlguard.safe_load(new.decode("utf-8"))
    except yaml.YAMLError:
        loaded = None
    if not isinstance(loaded, list) or len(loaded) != len(node.value) + len(fresh):
        notes.append(f"{shown} left as it is: sensorkit could not append to it safely")
        return []
    plan.bridged += _topics(path, fresh)
    why = f"+{len(fresh)} bridge entries"
    return [FileChange(path, data, new, why=why)]


def _readme_row(path: Path, data: bytes, sensor: NewSensor, notes: list[str]) -> list[FileChange]:
    """A row for the sensor after the last row of a generated README's sensor table."""
    text = data.decode("utf-8", "surrogateescape")
    head = text.find(_TABLE_HEAD)
    if head < 0:
        return []
    newline = "\r\n" if "\r\n" in text else "\n"
    at = text.find("\n", head) + 1
    while at > 0 and text.startswith("|", at):
        at = text.find("\n", at) + 1
    if at <= 0:
        notes.append(f"{display_path(path)} left as it is: its sensor table has no end")
        return []
    xyz, rpy = " ".join(sensor.xyz), " ".join(sensor.rpy)
    row = f"| {sensor.name} | {sensor.kind} | {sensor.parent} | {xyz} | {rpy} |{newline}"
    new = (text[:at] + row + text[at:]).encode("utf-8", "surrogateescape")
    return [FileChange(path, data, new, why="sensor table")]
