"""The robot model: frames, joints, sensors, and what the simulator keeps."""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from sensorkit.base.findings import Finding
from sensorkit.loading import PackageResolver, load_description
from sensorkit.model.robot import Robot
from sensorkit.model.urdf import build_robot

if TYPE_CHECKING:
    from sensorkit.loading.cache import ExpansionCache
    from sensorkit.loading.document import Document
    from sensorkit.loading.untrusted import Untrusted


@dataclass
class Loaded:
    """A robot, or the findings (SK101..SK103) that say why it could not be read.

    An SDF world holds several models: ``robots`` is each of them, in document order, and
    ``robot`` the first (None when the world has none). Otherwise ``robots`` is
    ``[robot]``, or empty when there is none.
    """

    robot: Robot | None
    findings: list[Finding] = field(default_factory=list)
    robots: list[Robot] = field(default_factory=list)
    # the packages as the load found them: the rules look meshes up with it (one scan)
    resolver: PackageResolver | None = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not self.robots and self.robot is not None:
            self.robots = [self.robot]


def load_robot(
    path: Path,
    *,
    args: dict[str, str] | None = None,
    package_paths: tuple[str, ...] | list[str] = (),
    timeout: float = 60.0,
    untrusted: Untrusted | None = None,
    overlay: Mapping[str, bytes] | None = None,
    cache: ExpansionCache | None = None,
    sdf: bool = False,
) -> Loaded:
    """Load and model a URDF/xacro file. Raises InputError for unreadable/non-robot input.

    With ``sdf``, an SDF file (``.sdf``, ``.world``) is read too (see
    :mod:`sensorkit.model.sdf_read`): each of its models is in ``Loaded.robots``; a
    ``.sdf.xacro`` is expanded by xacro first and its ``<sdf>`` read the same way. Without
    it, SDF is refused as before (InputError naming ``<sdf>``): the commands take it once
    their rules know SDF.

    ``overlay`` maps absolute paths to bytes read instead of those files (stdin, ``--fix``).
    ``cache``: the expansion cache to use (see ``sensorkit.loading.cache``), if any.
    """
    resolver = PackageResolver.from_options(list(package_paths), near=path)
    loaded = _load(path, resolver, args, timeout, untrusted, overlay, cache, sdf)
    loaded.resolver = resolver
    return loaded


def _load(
    path: Path,
    resolver: PackageResolver,
    args: dict[str, str] | None,
    timeout: float,
    untrusted: Untrusted | None,
    overlay: Mapping[str, bytes] | None,
    cache: ExpansionCache | None,
    sdf: bool,
) -> Loaded:
    from sensorkit.loading.formats import is_sdf_path, is_sdf_xacro

    if untrusted is not None:
        # includes, $(find), meshes: inside the readable area only (packages.readable_area)
        resolver.confine_to(path)
    if sdf and is_sdf_path(path):
        if untrusted is not None and not (overlay and os.path.abspath(path) in overlay):
            from sensorkit.loading.document import confine_input

            confine_input(path, resolver)
        return _load_sdf(path, resolver, overlay)
    sdf_xacro = sdf and is_sdf_xacro(path)
    result = load_description(
        path,
        args=args,
        resolver=resolver,
        timeout=timeout,
        untrusted=untrusted,
        overlay=overlay,
        cache=cache,
        sdf=sdf_xacro,
    )
    if result.document is None:
        return Loaded(None, result.findings)
    if sdf_xacro and result.document.root.tag == "sdf":
        # the expansion is read as SDF; its model:// includes from the file's folder
        loaded = _load_sdf(path, resolver, overlay, result.document)
        loaded.findings[:0] = result.findings
        return loaded
    return Loaded(build_robot(result.document), result.findings)


def _load_sdf(
    path: Path,
    resolver: PackageResolver,
    overlay: Mapping[str, bytes] | None,
    document: Document | None = None,
) -> Loaded:
    from sensorkit.model.sdf_build import build_sdf_robot
    from sensorkit.model.sdf_read import read_models

    read = read_models(path, resolver, overlay, document)
    if read.document is None:
        return Loaded(None, read.findings)
    robots = [build_sdf_robot(read.document, sm) for sm in read.models]
    return Loaded(robots[0] if robots else None, read.findings, robots)


__all__ = ["Loaded", "Robot", "build_robot", "load_robot"]
