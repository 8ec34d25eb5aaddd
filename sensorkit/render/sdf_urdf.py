"""An SDF model as the URDF subset pybullet draws.

pybullet reads SDF only in part (no ``relative_to``, no nested models, no ``model://``),
so a model read from SDF is drawn from a URDF written here: one ``<link>`` per SDF link
(named with its scope, as the Robot names it), its ``<visual>`` and ``<collision>``
elements with their poses resolved into the link's frame, and one ``<joint>`` per Robot
joint (whose origin is already the child link in the parent link). The result is a copy
of the Robot whose document and link elements are that URDF, with the same joints,
sensors and SDF frame graph, so everything the preview does on a URDF robot holds.

A visual's or collision's ``<pose>`` is in its link unless it names another frame
(``SemanticPose`` with the parent link as its default:
gazebosim/sdformat@sdformat12_12.8.0:src/Visual.cc:236-243,
gazebosim/sdformat@sdformat12_12.8.0:src/Collision.cc:187-194, the parent set at
gazebosim/sdformat@sdformat12_12.8.0:src/Link.cc:476-493).

Drawn: ``<box>``, ``<cylinder>``, ``<sphere>`` and ``<mesh>`` files pybullet reads
(.obj, .stl, .dae), with the ``<diffuse>`` (else ``<ambient>``) colour of the material.
Not drawn, each with a note: ``<plane>``, ``<heightmap>``, ``<polyline>``, ``<capsule>``,
``<ellipsoid>``, ``<image>``, a ``<submesh>`` (the whole mesh would be drawn), meshes at
web (Fuel) URIs or not found, and textures and material scripts. Joints other than
revolute, continuous and prismatic are drawn fixed (they stay at zero in the preview).
Links that no joint connects to the rest (several root links) are drawn where the model
places them, tied to the first root.
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from sensorkit.loading import PackageResolver
from sensorkit.loading.document import Document
from sensorkit.loading.sdf_files import resolve_model_uri
from sensorkit.model.parse import child, children, parse_vec, text_of
from sensorkit.model.parts import Joint, Link
from sensorkit.model.robot import Robot
from sensorkit.model.sdf_frames import between, scoped
from sensorkit.model.sdf_read import Element, SdfModel, read_pose
from sensorkit.model.transforms import Pose, compose, matrix_to_rpy, pose_matrix

__all__ = ["NOT_DRAWN", "sdf_render_robot"]

NOT_DRAWN = ("plane", "heightmap", "polyline", "capsule", "ellipsoid", "image")
_MOVING = ("revolute", "continuous", "prismatic")


def _num(v: float) -> str:
    return repr(float(v))


def _origin(parent: etree._Element, p: Pose) -> None:
    rpy = matrix_to_rpy(pose_matrix(p))
    etree.SubElement(
        parent,
        "origin",
        xyz=" ".join(_num(v) for v in (p[9], p[10], p[11])),
        rpy=" ".join(_num(v) for v in rpy),
    )


def _file_of(doc: Document, el: etree._Element) -> Path:
    """The file an element was read from (included models are in files of their own)."""
    from sensorkit.loading.marks import LOC_ATTR

    cur: etree._Element | None = el
    while cur is not None:
        idx, _, _ = (cur.get(LOC_ATTR) or "").partition(":")
        if idx.isdigit() and int(idx) < len(doc.files):
            return Path(doc.files[int(idx)])
        cur = cur.getparent()
    return doc.path


def _mesh_file(uri: str, doc: Document, el: etree._Element, resolver: PackageResolver) -> str:
    """An absolute path for a mesh URI, the URI itself for package:// (the URDF writer
    resolves those), or raises ValueError with why it cannot be drawn."""
    if uri.startswith("package://"):
        return uri
    if uri.startswith(("http://", "https://")):
        msg = "web (Fuel) URIs are not fetched"
        raise ValueError(msg)
    got = resolve_model_uri(uri, _file_of(doc, el), resolver)
    if got.path is None:
        if not uri.startswith("model://") and got.searched:  # a path: no model folder asked
            raise ValueError(f"no file at {got.searched[0]}")
        raise ValueError(got.why)
    return str(got.path.resolve())


def _geometry(
    geom: etree._Element | None, doc: Document, resolver: PackageResolver
) -> etree._Element:
    """The URDF ``<geometry>`` of an SDF one, or raises ValueError with why not drawn."""
    shape = next((c for c in geom if isinstance(c.tag, str)), None) if geom is not None else None
    if shape is None:
        msg = "no geometry"
        raise ValueError(msg)
    out = etree.Element("geometry")
    kind = shape.tag
    if kind == "box":
        size, why = parse_vec(text_of(shape, "size") or "1 1 1", 3)
        if size is None:
            raise ValueError(f"box size {why}")
        etree.SubElement(out, "box", size=" ".join(_num(v) for v in size))
    elif kind in ("cylinder", "sphere"):
        attrs = {"radius": text_of(shape, "radius") or ("0.5" if kind == "sphere" else "1")}
        if kind == "cylinder":
            attrs["length"] = text_of(shape, "length") or "1"
        for key, value in attrs.items():
            if parse_vec(value, 1)[0] is None:
                raise ValueError(f"{kind} {key} {value!r} is not a number")
        etree.SubElement(out, kind, attrs)
    elif kind == "mesh":
        if child(shape, "submesh") is not None:
            msg = "a <submesh> is not drawn"
            raise ValueError(msg)
        mesh = etree.SubElement(
            out, "mesh", filename=_mesh_file(text_of(shape, "uri") or "", doc, shape, resolver)
        )
        scale = text_of(shape, "scale")
        if scale:
            mesh.set("scale", scale)
    else:
        raise ValueError(f"<{kind}> geometry is not drawn")
    return out


def _colour(part: etree._Element) -> str | None:
    mat = child(part, "material")
    for tag in ("diffuse", "ambient"):
        rgba, _ = parse_vec(text_of(mat, tag) or "", 4)
        if rgba is None:
            rgba3, _ = parse_vec(text_of(mat, tag) or "", 3)
            rgba = (*rgba3, 1.0) if rgba3 is not None else None
        if rgba is not None:
            return " ".join(_num(v) for v in rgba)
    return None


def _part(
    sm: SdfModel,
    item: Element,
    part: etree._Element,
    doc: Document,
    resolver: PackageResolver,
) -> etree._Element:
    """The URDF ``<visual>``/``<collision>`` of an SDF one, its pose in its link's frame;
    raises ValueError with why it is not drawn."""
    raw, rel, _, problem = read_pose(part, item.version)
    if problem is not None:
        raise ValueError(problem)
    frame = scoped(item.scope, rel) if rel is not None else item.name
    P_frame, P_link = sm.pose_of(frame), sm.pose_of(item.name)
    if P_frame is None or P_link is None:
        msg = f"its pose is relative to {rel!r}, which does not resolve"
        raise ValueError(msg)
    out = etree.Element(part.tag, name=part.get("name", ""))
    _origin(out, between(P_link, compose(P_frame, raw)))
    out.append(_geometry(child(part, "geometry"), doc, resolver))
    rgba = _colour(part) if part.tag == "visual" else None
    if rgba is not None:
        mat = etree.SubElement(out, "material", name=f"{item.name}/{part.get('name', '')}")
        etree.SubElement(mat, "color", rgba=rgba)
    return out


def _joint(root: etree._Element, joint: Joint) -> None:
    kind = joint.type if joint.type in (*_MOVING, "fixed") else "fixed"
    el = etree.SubElement(root, "joint", name=joint.name, type=kind)
    etree.SubElement(el, "parent", link=joint.parent or "")
    etree.SubElement(el, "child", link=joint.child or "")
    _origin(el, joint.origin.pose())
    if kind in _MOVING and joint.axis is not None:
        etree.SubElement(el, "axis", xyz=" ".join(_num(v) for v in joint.axis))
    if kind in ("revolute", "prismatic"):
        limit = joint.limit or {}
        lower, upper = limit.get("lower"), limit.get("upper")
        etree.SubElement(
            el,
            "limit",
            lower=_num(lower if lower is not None else -1e16),
            upper=_num(upper if upper is not None else 1e16),
            effort="0",
            velocity="0",
        )


def _ties(robot: Robot, sm: SdfModel, root: etree._Element) -> tuple[list[Joint], list[str]]:
    """Fixed joints that hold every further root link where the model places it, from
    the first root (pybullet loads one tree)."""
    roots = robot.roots()
    if len(roots) < 2:
        return [], []
    first = roots[0]
    P_first = sm.pose_of(first)
    ties: list[Joint] = []
    for name in roots[1:]:
        P = sm.pose_of(name)
        if P_first is None or P is None:
            continue
        from sensorkit.model.sdf_build import exact_origin

        link = robot.link_map[name]
        origin = exact_origin(between(P_first, P), None, robot.document)
        tie = Joint(f"{first}__to__{name}", "fixed", first, name, origin, link.element, link.doc)
        _joint(root, tie)
        ties.append(tie)
    note = (
        f"SDF: {len(roots) - 1} link(s) no joint connects ({', '.join(roots[1:])}) are "
        f"drawn where the model places them, held to {first!r}"
    )
    return ties, [note]


def sdf_render_robot(robot: Robot, resolver: PackageResolver) -> tuple[Robot, list[str]]:
    """A copy of the SDF ``robot`` whose document and link elements are the URDF subset
    pybullet draws, and a note for each thing not drawn."""
    sm = robot.sdf
    assert sm is not None
    doc = robot.document
    root = etree.Element("robot", name=robot.name)
    items = {item.name: item for item in sm.links}
    notes: list[str] = []
    links: list[Link] = []
    for link in robot.links:
        el = etree.SubElement(root, "link", name=link.name)
        item = items.get(link.name)
        parts = (
            []
            if item is None
            else [*children(item.element, "visual"), *children(item.element, "collision")]
        )
        for part in parts:
            assert item is not None
            try:
                el.append(_part(sm, item, part, doc, resolver))
            except ValueError as why:
                where = doc.locate(part)
                notes.append(
                    f"SDF: not drawn: {part.tag} {part.get('name', '')!r} of link "
                    f"{link.name!r} ({where}): {why}"
                )
        links.append(Link(link.name, el, link.doc, link.inertial, link.meshes))
    for joint in robot.joints:
        if joint.parent in robot.link_map and joint.child in robot.link_map:
            _joint(root, joint)
    ties, tie_notes = _ties(robot, sm, root)
    urdf_doc = Document(path=doc.path, root=root)
    out = Robot(
        name=robot.name,
        document=urdf_doc,
        links=links,
        joints=[*robot.joints, *ties],
        sensors=robot.sensors,
        model_plugins=robot.model_plugins,
        sdf=sm,
    )
    out.index_tree()
    return out, notes + tie_notes
