"""The robot as pybullet can load it: expanded URDF with every file reference made absolute.

pybullet refuses a whole URDF when one mesh is missing, so a ``<visual>`` or
``<collision>`` whose mesh cannot be found (unknown package, no file, a format pybullet
does not read) is left out and a note says so; a material texture that cannot be found
loses its ``<texture>``. Gazebo extensions, transmissions and ros2_control blocks are
dropped (pybullet ignores them), and so are sensorkit's internal line stamps.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from sensorkit.loading import PackageResolver
from sensorkit.loading.uris import resolve_uri
from sensorkit.loading.xacro_expand import LOC_ATTR
from sensorkit.model.robot import Robot, local

__all__ = ["PreparedUrdf", "prepare_urdf", "resolve_file"]

# What pybullet's URDF importer reads (it also takes .dae for visuals, less reliably).
MESH_SUFFIXES = (".obj", ".stl", ".dae")
TEXTURE_SUFFIXES = (".png", ".jpg", ".jpeg", ".tga", ".bmp")
_DROP = {"gazebo", "transmission", "ros2_control"}


# pybullet reads a URDF in lines of at most 8191 bytes and puts a newline after each piece
# (bulletphysics/bullet3@examples/Importers/ImportURDFDemo/BulletUrdfImporter.cpp:165-172):
# a longer line gets a newline in the middle of a name or a number, and the file fails to
# load or loads changed.
_LINE_LIMIT = 8191


def _serialise(root: etree._Element) -> bytes:
    """``root`` as XML whose lines pybullet reads whole: re-indented when one is too long
    (whitespace between URDF elements means nothing)."""
    text: bytes = etree.tostring(root, xml_declaration=True, encoding="utf-8")
    if max(len(line) for line in text.split(b"\n")) > _LINE_LIMIT:
        etree.indent(root, space=" ")
        text = etree.tostring(root, xml_declaration=True, encoding="utf-8")
    return text


@dataclass
class PreparedUrdf:
    text: bytes
    notes: list[str] = field(default_factory=list)
    dropped: int = 0


def resolve_file(uri: str, base: Path, resolver: PackageResolver) -> tuple[Path | None, str]:
    """An existing file for a reference, or (None, why not)."""
    target = resolve_uri(uri, base, resolver)
    if target.path is None:
        return None, target.why
    if not target.path.is_file():
        return None, f"no file at {target.path}"
    return target.path.resolve(), ""


def prepare_urdf(robot: Robot, resolver: PackageResolver, *, what: str = "robot") -> PreparedUrdf:
    """The URDF text pybullet should load for ``robot``, and what had to be left out."""
    root = copy.deepcopy(robot.document.root)
    base = robot.document.path.resolve().parent
    out = PreparedUrdf(b"")
    for el in list(root):
        if local(el) in _DROP or not isinstance(el.tag, str):
            root.remove(el)
    for el in root.iter():
        if LOC_ATTR in el.attrib:
            del el.attrib[LOC_ATTR]
    for mesh in list(root.iter("mesh")):
        uri = (mesh.get("filename") or "").strip()
        path, why = resolve_file(uri, base, resolver) if uri else (None, "no filename")
        if path is not None and path.suffix.lower() not in MESH_SUFFIXES:
            why = f"pybullet cannot read {path.suffix or 'this'} meshes"
            path = None
        if path is None:
            holder = mesh
            while holder is not None and local(holder) not in ("visual", "collision"):
                holder = holder.getparent()
            if holder is not None and holder.getparent() is not None:
                link = holder.getparent()
                out.notes.append(
                    f"{what}: left out a {local(holder)} of link {link.get('name')!r}: mesh {uri!r}: {why}"
                )
                link.remove(holder)
                out.dropped += 1
            continue
        mesh.set("filename", str(path))
    for tex in list(root.iter("texture")):
        uri = (tex.get("filename") or "").strip()
        if not uri:
            continue
        path, why = resolve_file(uri, base, resolver)
        if path is None or path.suffix.lower() not in TEXTURE_SUFFIXES:
            parent = tex.getparent()
            if parent is not None:
                parent.remove(tex)
            out.notes.append(f"{what}: left out texture {uri!r}: {why or 'unsupported format'}")
            continue
        tex.set("filename", str(path))
    etree.cleanup_namespaces(root)
    out.text = _serialise(root)
    return out
