"""The robot as pybullet can load it: expanded URDF with every file reference made absolute.

pybullet refuses a whole URDF when one mesh is missing, so a ``<visual>`` or
``<collision>`` whose mesh cannot be found (unknown package, no file, a format pybullet
does not read) is left out and a note says so; a material texture that cannot be found
loses its ``<texture>``. Gazebo extensions, transmissions and ros2_control blocks are
dropped (pybullet ignores them), and so are sensorkit's internal line stamps.

pybullet holds at most 127 links (and 128 joint position variables, the base's 7
included) per multibody: a bigger robot is split into several bodies (:func:`split_urdf`),
each loaded where sensorkit's kinematics puts its base link.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from sensorkit.loading import PackageResolver
from sensorkit.loading.marks import LOC_ATTR
from sensorkit.loading.uris import resolve_uri
from sensorkit.model.parse import local
from sensorkit.model.robot import Robot

__all__ = [
    "BODY_LINKS",
    "BODY_Q",
    "PreparedUrdf",
    "UrdfPart",
    "prepare_urdf",
    "resolve_file",
    "split_urdf",
]

# What pybullet's URDF importer reads (it also takes .dae for visuals, less reliably).
MESH_SUFFIXES = (".obj", ".stl", ".dae")
TEXTURE_SUFFIXES = (".png", ".jpg", ".jpeg", ".tga", ".bmp")
_DROP = {"gazebo", "transmission", "ros2_control"}

# pybullet's per-multibody limits. The server refuses the state of a body with 128 links or
# more (bulletphysics/bullet3@examples/SharedMemory/PhysicsServerCommandProcessor.cpp:7922,
# `if (mb->getNumLinks() >= MAX_DEGREE_OF_FREEDOM)`, with MAX_DEGREE_OF_FREEDOM 128 at
# bulletphysics/bullet3@examples/SharedMemory/SharedMemoryCommands.h:33), which pybullet
# reports as "getLinkState failed." (bulletphysics/bullet3@examples/pybullet/pybullet.c:5874).
# The same state holds the joint positions in m_actualStateQ[MAX_DEGREE_OF_FREEDOM]
# (bulletphysics/bullet3@examples/SharedMemory/SharedMemoryCommands.h:605), written without
# a bounds check, the base's 7 first. Line numbers at bullet3 commit 6c888f4a (2025-01-29).
BODY_LINKS = 128  # URDF links in one body: the base and 127 pybullet links
BODY_Q = 128 - 7  # joint position variables of one body, the base's 7 aside
# position variables per joint type in pybullet (floating joints become fixed; unknown
# types are counted as pybullet's largest, the spherical joint)
_Q_OF = {"fixed": 0, "floating": 0, "revolute": 1, "continuous": 1, "prismatic": 1, "planar": 3}
_Q_MAX = 4


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
class UrdfPart:
    """One pybullet body of a robot: ``base`` is the link whose pose places it.

    With ``stand_in`` the base is an empty link named like ``base``, which lives (with its
    geometry) in another body; this body then holds some of ``base``'s child subtrees.
    """

    base: str
    links: list[str]  # the robot's links in this body (a stand-in base not counted)
    text: bytes
    stand_in: bool = False


@dataclass
class PreparedUrdf:
    text: bytes
    notes: list[str] = field(default_factory=list)
    dropped: int = 0
    parts: list[UrdfPart] = field(default_factory=list)


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
    out.parts = split_urdf(root, out.text)
    return out


def _tree(root: etree._Element) -> tuple[str, dict[str, list[str]], dict[str, int]] | None:
    """(root link, link -> child links in document order, link -> its parent joint's
    position variables), or None when the links do not form one tree."""
    links = [el.get("name") or "" for el in root if local(el) == "link"]
    children: dict[str, list[str]] = {}
    q_of: dict[str, int] = {}
    has_parent: set[str] = set()
    for el in root:
        if local(el) != "joint":
            continue
        parent = next((c.get("link") for c in el if local(c) == "parent"), None)
        child = next((c.get("link") for c in el if local(c) == "child"), None)
        if parent is None or child is None or child in has_parent:
            return None
        has_parent.add(child)
        children.setdefault(parent, []).append(child)
        q_of[child] = _Q_OF.get((el.get("type") or "").strip(), _Q_MAX)
    roots = [name for name in links if name not in has_parent]
    if len(roots) != 1 or len(set(links)) != len(links):
        return None
    return roots[0], children, q_of


def _preorder(root: str, children: dict[str, list[str]]) -> list[str]:
    order: list[str] = []
    seen: set[str] = set()
    stack = [root]
    while stack:
        link = stack.pop()
        if link in seen:
            continue
        seen.add(link)
        order.append(link)
        stack.extend(reversed(children.get(link, [])))
    return order


def _assign(
    root: str, order: list[str], children: dict[str, list[str]], q_of: dict[str, int]
) -> tuple[dict[str, int], list[str]]:
    """Pack the tree into bodies within pybullet's limits.

    Children first, each link gathers the pieces hanging below it while they fit
    (``BODY_LINKS - 1`` links, ``BODY_Q - 4`` variables, so that any piece still fits
    under a stand-in base with the joint that held it); the pieces that do not fit go,
    largest first, into bodies under a stand-in of that link (first fit). ``order`` is
    the tree in preorder. Returns link -> body index (0 holds the root), and each body's
    base link.
    """
    piece_cap = (BODY_LINKS - 1, BODY_Q - _Q_MAX)
    size: dict[str, tuple[int, int]] = {}  # links and variables of the piece at a link
    binned: dict[str, int] = {}  # child link -> the body it starts a piece in
    bases = [root]
    for link in reversed(order):
        kids = [
            (size[c][0], size[c][1] + q_of.get(c, 0), c)
            for c in children.get(link, [])
            if c in size
        ]
        kids.sort(key=lambda k: (k[0], k[1]), reverse=True)
        links, q = 1, 0
        spill: list[tuple[int, int, str]] = []
        for n, kq, c in kids:
            if links + n <= piece_cap[0] and q + kq <= piece_cap[1]:
                links, q = links + n, q + kq
            else:
                spill.append((n, kq, c))
        room: list[list[int]] = []  # per new body: links (the stand-in counted), variables
        first = len(bases)
        for n, kq, c in spill:
            for k, (used_n, used_q) in enumerate(room):
                if used_n + n <= BODY_LINKS and used_q + kq <= BODY_Q:
                    room[k] = [used_n + n, used_q + kq]
                    binned[c] = first + k
                    break
            else:
                room.append([1 + n, kq])
                binned[c] = first + len(room) - 1
                bases.append(link)
        size[link] = (links, q)
    body = {root: 0}
    for link in order:
        for c in children.get(link, []):
            if c not in body:
                body[c] = binned.get(c, body[link])
    return body, bases


def split_urdf(root: etree._Element, text: bytes) -> list[UrdfPart]:
    """``text`` (the serialised ``root``) as one body when it fits pybullet's limits,
    else as several, each within them. A description that is not one tree is left whole
    (pybullet reports what is wrong with it)."""
    tree = _tree(root)
    if tree is None:
        return [UrdfPart("", [], text)]
    top, children, q_of = tree
    order = _preorder(top, children)
    if len(order) <= BODY_LINKS and sum(q_of.get(link, 0) for link in order) <= BODY_Q:
        return [UrdfPart(top, order, text)]
    body, bases = _assign(top, order, children, q_of)
    members: list[list[str]] = [[] for _ in bases]
    for link in order:
        members[body[link]].append(link)
    parts: list[UrdfPart] = []
    for k, base in enumerate(bases):
        mine = set(members[k])
        out = etree.Element(root.tag, dict(root.attrib), nsmap=root.nsmap)
        if k > 0:
            etree.SubElement(out, "link", name=base)
        for el in root:
            kind = local(el)
            if kind == "link":
                keep = el.get("name") in mine
            elif kind == "joint":
                child = next((c.get("link") for c in el if local(c) == "child"), None)
                keep = child in mine and child != base
            else:
                keep = True  # materials and whatever else the importer reads
            if keep:
                out.append(copy.deepcopy(el))
        part_text = _serialise(out)
        parts.append(UrdfPart(base, members[k], part_text, stand_in=k > 0))
    return parts
