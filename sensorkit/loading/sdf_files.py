"""SDF files on disk: strict parsing of an ``<sdf>`` file, the file a ``model://`` URI
names, and the source marks that let one Document locate elements of several files.

An SDF description is read without any expansion: lines are the file's own. When a model
``<include>``s another file, every element of every file read is stamped with
``LOC_ATTR`` ("FILE_INDEX:LINE", as xacro's expansion stamps them) and the Document is
marked ``expanded``, so that ``Document.locate`` names the file each element came from.

``model://NAME/REST``, ``package://NAME/REST`` and a relative ``NAME/REST`` that is not
beside the including file are looked up, first hit wins, in:

1. each folder of ``GZ_SIM_RESOURCE_PATH`` (then the older ``IGN_GAZEBO_RESOURCE_PATH``
   and libsdformat's own ``SDF_PATH``), as ``FOLDER/NAME/REST``;
2. the package ``NAME`` as the resolver finds it (``--package-path``, the environment,
   the workspace), as ``PACKAGE/REST``;
3. the folders beside the including model's own folder (a ``models/`` folder holding
   several models), as ``PARENT/NAME/REST``;
4. each folder of Gazebo Classic's ``GAZEBO_MODEL_PATH`` (the include records that it was
   found only there: Gazebo Sim does not search it).

Under ``--untrusted`` (a confined resolver) only places inside the workspace and the
resolved packages are looked at, and nothing is said of what lies outside.

A folder found is a model folder: the file is the one its ``model.config`` names
(the ``<sdf>`` of the highest ``version``), else ``model.sdf``.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from sensorkit.base.errors import InputError
from sensorkit.base.findings import Finding
from sensorkit.loading.document import (
    Document,
    OverLimit,
    display_path,
    drop_default_namespace,
    max_elements,
    parse_bounded,
    read_input,
)
from sensorkit.loading.formats import is_sdf_path
from sensorkit.loading.input_findings import (
    encoding_finding,
    limit_finding,
    prefixed_root_finding,
    xml_finding,
)
from sensorkit.loading.marks import LOC_ATTR, forbid_entities
from sensorkit.loading.packages import PackageResolver, valid_package_name
from sensorkit.loading.uris import OUTSIDE, UriTarget, resolve_uri

# Schemes libsdformat strips before looking the rest up in SDF_PATH, which gz-sim fills
# with GZ_SIM_RESOURCE_PATH's folders (gazebosim/sdformat@sdformat12_12.8.0:src/SDF.cc:87-124;
# gazebosim/gz-sim@gz-sim8_8.9.0:src/Util.cc:486-540): ``package://PKG/REST`` is
# ``FOLDER/PKG/REST`` (gazebosim/ros_gz@2.1.1:ros_gz_sim/README.md:96-113).
SEARCHED_SCHEMES = ("model://", "package://")
RESOURCE_VARS = ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH")
# Gazebo Classic's model path (sensorkit.knowledge.classic_models), searched last: a model
# found only there is recorded with ``via`` so that a Gazebo Sim target can say it is not.
CLASSIC_VARS = ("GAZEBO_MODEL_PATH",)


def parse_sdf(
    path: Path, overlay: Mapping[str, bytes] | None = None, untrusted: bool = False
) -> tuple[etree._Element | None, list[Finding]]:
    """The ``<sdf>`` root of ``path`` (namespace dropped) or SK101 findings.

    Raises InputError for an unreadable file or one whose root is not ``<sdf>``.
    """
    key = os.path.abspath(path)
    data = overlay[key] if overlay and key in overlay else read_input(path)
    where = display_path(path)
    if not data.strip():
        return None, [xml_finding(where, "the file is empty", 1, 1)]
    refused = encoding_finding(where, data)
    if refused is not None:
        return None, [refused]
    reason = forbid_entities(data)
    if reason:
        return None, [xml_finding(where, reason, 1, 1)]
    try:
        root = parse_bounded(data, max_elements(untrusted))
    except etree.XMLSyntaxError as exc:
        line, col = exc.position if exc.position else (exc.lineno, exc.offset)
        return None, [xml_finding(where, str(exc.msg), line, col)]
    except OverLimit as exc:
        return None, [limit_finding("SK101", where, str(exc), exc.line)]
    tag = etree.QName(root).localname if isinstance(root.tag, str) else "?"
    if tag != "sdf":
        msg = f"{where}: root element is <{tag}>, not <sdf>: not an SDF description"
        raise InputError(msg)
    refused = prefixed_root_finding(root, where)
    if refused is not None:
        return None, [refused]
    return drop_default_namespace(root), []


def stamp(root: etree._Element, index: int) -> None:
    """Mark every element under ``root`` with its file ``index`` and line (LOC_ATTR)."""
    for el in root.iter():
        if isinstance(el.tag, str) and el.sourceline is not None:
            el.set(LOC_ATTR, f"{index}:{el.sourceline}")


def add_file(doc: Document, root: etree._Element, path: Path) -> None:
    """Make ``doc`` locate elements of ``root`` (read from ``path``) in that file."""
    if not doc.expanded:
        doc.files = [str(doc.path)]
        stamp(doc.root, 0)
        doc.expanded = True
    doc.files.append(str(path))
    stamp(root, len(doc.files) - 1)


@dataclass(frozen=True)
class ModelUri:
    """Where a ``model://`` URI leads: a file, or why not (with the places searched)."""

    path: Path | None
    why: str = ""
    searched: tuple[str, ...] = ()
    via: str = ""  # "GAZEBO_MODEL_PATH" when found only through Gazebo Classic's path


def _resource_dirs(names: tuple[str, ...] = RESOURCE_VARS) -> list[Path]:
    out: list[Path] = []
    for var in names:
        for part in os.environ.get(var, "").split(os.pathsep):
            if part:
                out.append(Path(part))
    return out


def model_file(found: Path) -> Path | None:
    """The SDF file of a model folder (model.config's newest ``<sdf>``, else model.sdf),
    or ``found`` itself when it is a file."""
    if found.is_file():
        return found
    if not found.is_dir():
        return None
    config = found / "model.config"
    best: tuple[tuple[int, ...], str] | None = None
    if config.is_file():
        try:
            text = config.read_bytes()[:262144].decode("utf-8", "replace")
        except OSError:
            text = ""
        for m in re.finditer(r"<sdf(\s[^>]*)?>\s*([^<\s]+)\s*</sdf>", text):
            ver = re.search(r"version\s*=\s*[\"']([0-9.]+)", m.group(1) or "")
            key = tuple(int(p) for p in ver.group(1).split(".") if p) if ver else ()
            if best is None or key > best[0]:
                best = (key, m.group(2))
    if best is not None and (found / best[1]).is_file():
        return found / best[1]
    if (found / "model.sdf").is_file():
        return found / "model.sdf"
    return None


def resolve_model_uri(uri: str, including: Path, resolver: PackageResolver) -> ModelUri:
    """The file ``uri`` (``model://``, ``package://``, ``file://``, or a path) names, from
    the file ``including`` it; see the module's docstring for the order."""
    if uri.startswith("file://"):
        uri = uri[len("file://") :]
    scheme = next((s for s in SEARCHED_SCHEMES if uri.startswith(s)), None)
    if scheme is None and "://" in uri:
        return ModelUri(None, "only model://, package:// and file:// URIs and paths can be read")
    candidates: list[Path] = []
    if scheme is None:
        path = Path(uri) if os.path.isabs(uri) else including.parent / uri
        if not resolver.allows(path):  # says nothing of what is there
            return ModelUri(None, OUTSIDE)
        got = model_file(path)
        if got is not None or os.path.isabs(uri):
            return ModelUri(got, "" if got else "no model there", (str(path),))
        candidates.append(path)  # a relative name is looked up as model:// is (SDF.cc:119-124)
    name, _, rest = uri[len(scheme or "") :].partition("/")
    candidates += [d / name / rest if rest else d / name for d in _resource_dirs()]
    if valid_package_name(name):
        pkg = resolver.find(name)
        if pkg is not None:
            candidates.append(pkg / rest if rest else pkg)
    model_dir = including.resolve().parent
    for folder in (model_dir.parent, model_dir):
        candidates.append(folder / name / rest if rest else folder / name)
    first_classic = len(candidates)
    candidates += [d / name / rest if rest else d / name for d in _resource_dirs(CLASSIC_VARS)]
    allowed = [(i, c) for i, c in enumerate(candidates) if resolver.allows(c)]  # --untrusted: inside only
    for i, cand in allowed:
        got = model_file(cand)
        if got is not None:
            return ModelUri(got, via=CLASSIC_VARS[0] if i >= first_classic else "")
    searched = tuple(str(c) for _, c in allowed)
    if len(allowed) < len(candidates):  # not inside; what lies outside is not looked at
        return ModelUri(None, OUTSIDE, searched)
    why = "not found in the model paths, the packages, or beside the including model"
    return ModelUri(None, why, searched)


def element_file(doc: Document, el: etree._Element) -> Path:
    """The file an element of ``doc`` was read from (its nearest stamped ancestor's)."""
    if doc.expanded:
        cur: etree._Element | None = el
        while cur is not None:
            idx, _, _line = (cur.get(LOC_ATTR) or "").partition(":")
            if idx.isdigit() and int(idx) < len(doc.files):
                return Path(doc.files[int(idx)])
            cur = cur.getparent()
    return doc.path


def resolve_mesh_uri(uri: str, holder: Path, resolver: PackageResolver) -> UriTarget:
    """Where gz-sim finds the mesh ``uri`` written in the SDF file ``holder``: a path to
    check (``path``), an unknown package (``missing_package``), or nothing to say (both
    None: the simulator may know more than sensorkit does).

    - a relative path is in the folder of the SDF file that holds it (gz-sim's
      ``asFullPath``: gazebosim/gz-sim@gz-sim8_8.9.0:src/Util.cc:389-440,
      src/Conversions.cc:220); not said of xacro text, which gz-sim reads from a string
      and resolves from its own working folder (Util.cc:421-427);
    - ``model://NAME/REST`` and ``package://NAME/REST`` are ``FOLDER/NAME/REST`` in the
      folders gz-common searches, GZ_SIM_RESOURCE_PATH's (Util.cc:486-540 puts them in
      its file path), the package NAME and the folders beside ``holder``'s model folder,
      as an include is found: a file found there is the one; when the model or package
      folder is found but not the file, that folder's file is missing; a ``package://``
      whose package is found nowhere is an unknown package (as for URDF); a
      ``model://`` whose model is found nowhere is left unsaid;
    - ``file://`` and absolute paths are themselves; other schemes (Fuel URLs) unsaid.
    """
    scheme = next((s for s in SEARCHED_SCHEMES if uri.startswith(s)), None)
    if scheme is None:
        if "://" not in uri and not os.path.isabs(uri) and not is_sdf_path(holder):
            return UriTarget(None)
        if "://" in uri and not uri.startswith("file://"):
            return UriTarget(None)
        return resolve_uri(uri, holder.parent, resolver)
    name, _, rest = uri[len(scheme) :].partition("/")
    if not valid_package_name(name) or not rest:
        return UriTarget(None)
    folders = [d / name for d in _resource_dirs()]
    pkg = resolver.find(name)
    if pkg is not None:
        folders.append(pkg)
    model_dir = holder.resolve().parent
    folders += [model_dir.parent / name, model_dir / name]
    found = [f for f in folders if resolver.allows(f) and f.is_dir()]
    for folder in found:
        if (folder / rest).is_file():
            return UriTarget(folder / rest)
    if found:
        return UriTarget(found[0] / rest)
    if scheme == "package://":
        return UriTarget(None, f"package {name!r} not found", name)
    return UriTarget(None)
