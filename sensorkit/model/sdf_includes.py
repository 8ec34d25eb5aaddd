"""SK107: what to say of an SDF ``<include>`` that leads to no file.

The reader keeps every include (:class:`~sensorkit.model.sdf_read.Include`); one with no
``path`` brought no model. A model's includes are checked by the SK107 rule
(:mod:`sensorkit.lint.rules.sdf`); a world's own includes belong to no model, so the reader
turns them into findings itself (a world whose every include fails has no model to check).
Both say it in the words of :func:`include_finding`.

What Gazebo does with such an include: libsdformat reports URI_LOOKUP ("Unable to find
uri[...]") or ATTRIBUTE_MISSING (no ``<uri>``) (gazebosim/sdformat@sdformat12_12.8.0:
src/parser.cc:1399-1408, :1441-1446), and a server given a world that has errors loads
nothing of it (gazebosim/gz-sim@gz-sim8_8.14.0:src/Server.cc:83-91, the default behaviour
src/ServerConfig.cc:298-299; gazebosim/gz-sim@ignition-gazebo6_6.16.0:src/Server.cc:
136-141), nor does the create service spawn such a model
(gazebosim/gz-sim@gz-sim8_8.14.0:src/systems/user_commands/UserCommands.cc:925-930): an
error. An ``http(s)://`` URI is a Gazebo Fuel model that the server downloads through its
find-file callback (gazebosim/gz-sim@gz-sim8_8.14.0:src/Server.cc:72-74): sensorkit does
not download, so that is a limit of what it knows (info), as is an include that
``--untrusted`` does not read: the trust boundary, not a defect of the input.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

from sensorkit.base.consequence import UNKNOWN, Consequence, Role
from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.knowledge.classic_models import (
    CLASSIC_INSTALLED_MODELS,
    CLASSIC_INSTALLED_SOURCE,
    CLASSIC_SEARCH_PATH,
    CLASSIC_SKIPS_SOURCE,
    GZ_SEARCH_PATH,
    GZ_SEARCH_SOURCE,
    search_path,
)
from sensorkit.loading.uris import OUTSIDE

if TYPE_CHECKING:
    from lxml import etree

    from sensorkit.loading.document import Document


class Include(Protocol):
    """What is read of an include (:class:`sensorkit.model.sdf_read.Include`)."""

    @property
    def uri(self) -> str: ...
    @property
    def element(self) -> etree._Element: ...
    @property
    def path(self) -> Path | None: ...
    @property
    def why(self) -> str: ...
    @property
    def searched(self) -> tuple[str, ...]: ...
    @property
    def via(self) -> str: ...
    @property
    def within(self) -> tuple[str, ...]: ...


FUEL_SCHEMES = ("http://", "https://")
REFUSED = "Gazebo Sim loads no part of a world that holds it, nor spawns the model"


READ_SCHEMES = ("model://", "package://", "file://")


def _model_name(uri: str) -> str:
    """NAME of ``model://NAME/...`` or ``package://NAME/...`` ("" for a path)."""
    for scheme in READ_SCHEMES[:2]:
        if uri.startswith(scheme):
            return uri[len(scheme) :].partition("/")[0]
    return ""


def _classic(target: str | None) -> bool:
    return target in ("classic", "ros1")


def include_finding(inc: Include, doc: Document, target: str | None = None) -> Finding | None:
    """The SK107 finding of an include that brought no file (None when it did), said for
    ``target`` (None: not known, Gazebo Sim's words). A nested include (written in a
    model another include brought) names the chain of includes from the file given."""
    found = _include_finding(inc, doc, target)
    if found is None or not inc.within:
        return found
    chain = " -> ".join([doc.display, *inc.within, inc.uri or "<include>"])
    return dataclasses.replace(found, message=f"{found.message} (nested: {chain})")


def _include_finding(inc: Include, doc: Document, target: str | None) -> Finding | None:
    uri_el = next((c for c in inc.element if c.tag == "uri"), None)
    where = doc.locate(uri_el if uri_el is not None else inc.element)
    shown = repr(inc.uri)
    if inc.path is not None:
        if inc.via == CLASSIC_SEARCH_PATH and target is not None and not _classic(target):
            return Finding(
                "SK107",
                Severity.ERROR,
                f"<include> {shown} is found only through {CLASSIC_SEARCH_PATH} ({inc.path}), "
                f"Gazebo Classic's model path: Gazebo Sim searches {GZ_SEARCH_PATH} "
                f"({GZ_SEARCH_SOURCE}), so libsdformat reports URI_LOOKUP, and {REFUSED}",
                where,
                fix=f"add the folder that holds {_model_name(inc.uri) or 'it'}/ to {GZ_SEARCH_PATH}",
                consequence=Consequence(Role.GEOMETRY, inc.uri, None),
            )
        return None
    name = _model_name(inc.uri)
    if _classic(target) and inc.uri.startswith("model://") and name in CLASSIC_INSTALLED_MODELS:
        return Finding(
            "SK107",
            Severity.INFO,
            f"<include> {shown} is a model Gazebo 11 installs with itself, on its default "
            f"{CLASSIC_SEARCH_PATH} ({CLASSIC_INSTALLED_SOURCE}): it resolves on Gazebo "
            "Classic; sensorkit does not read it",
            where,
            fix="nothing to change for Gazebo Classic (Gazebo Sim installs no such model: "
            "define it in the world, or include it from Fuel)",
            consequence=Consequence(Role.GEOMETRY, inc.uri, inc.uri),
        )
    if not inc.uri:
        return Finding(
            "SK107",
            Severity.ERROR,
            f"<include> has no <uri>: libsdformat reports ATTRIBUTE_MISSING, and {REFUSED}",
            where,
            fix="name the model: <uri>model://NAME</uri>",
        )
    if inc.why == OUTSIDE:
        return Finding(
            "SK107",
            Severity.INFO,
            f"<include> {shown} is not read: it is not inside the workspace or the resolved "
            "packages, and --untrusted reads nothing outside them (GZ_SIM_RESOURCE_PATH "
            "folders included); the model it brings is not checked",
            where,
            fix="validate without --untrusted, or with the model's folder inside the workspace",
        )
    if inc.uri.startswith(FUEL_SCHEMES):
        return Finding(
            "SK107",
            Severity.INFO,
            f"<include> {shown} is a Gazebo Fuel URI, which Gazebo downloads and sensorkit "
            "does not: the model it brings is not checked",
            where,
            fix="download the model and include it with model:// to have it checked",
        )
    if "://" in inc.uri and not inc.uri.startswith(READ_SCHEMES):
        return Finding(
            "SK107",
            Severity.INFO,
            f"<include> {shown}: sensorkit reads model://, package:// and file:// URIs and "
            "paths only; "
            "the model it brings is not checked",
            where,
            fix="include it with model:// or a path to have it checked",
        )
    return _not_found(inc, where, shown, target)


def _not_found(inc: Include, where: SourceRef, shown: str, target: str | None) -> Finding:
    found = f"searched: {'; '.join(inc.searched)}" if inc.searched else inc.why
    name = _model_name(inc.uri)
    var = search_path(target)
    if name:
        fix = (
            f"add the folder that holds {name}/ to {var}, or pass "
            f"--package-path {name}=DIR (DIR the "
            f"{'package' if inc.uri.startswith('package://') else 'model'}'s folder)"
        )
    else:
        fix = (
            f"add the folder that holds it to {var}, or fix the path "
            "(read relative to the including file)"
        )
    then = (
        f"libsdformat 9 reports URI_LOOKUP and skips the include ({CLASSIC_SKIPS_SOURCE}): "
        "Gazebo Classic loads the world without that model"
        if _classic(target)
        else f"libsdformat reports URI_LOOKUP, and {REFUSED}"
    )
    if inc.uri.startswith("model://"):
        # A model:// URI names a model by its folder on the simulator's model path, which
        # is the environment's when the simulation runs, not the files': a model of another
        # package or repository is put there by its install (ArduPilot/ardupilot_gz includes
        # model://iris_with_standoffs from ArduPilot/ardupilot_gazebo, whose hooks add its
        # models to GZ_SIM_RESOURCE_PATH). Not on the paths sensorkit searched, it may still
        # resolve then: sensorkit cannot tell (issue 35).
        return Finding(
            "SK107",
            Severity.INFO,
            f"<include> {shown} is not on the paths sensorkit searched ({found}): it resolves "
            f"only if {var} holds a folder with {name}/ when the simulation runs, which "
            f"sensorkit cannot tell; the model it brings is not checked (if no folder holds "
            f"it: {then})",
            where,
            fix=fix,
            consequence=Consequence(Role.GEOMETRY, inc.uri, UNKNOWN),
        )
    return Finding(
        "SK107",
        Severity.ERROR,
        f"<include> {shown} does not resolve ({found}; {var} is the target's model path): {then}",
        where,
        fix=fix,
        consequence=Consequence(Role.GEOMETRY, inc.uri, None),
    )
