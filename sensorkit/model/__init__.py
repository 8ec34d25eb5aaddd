"""The robot model: frames, joints, sensors, and what the simulator keeps."""

from __future__ import annotations

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
    from sensorkit.loading.untrusted import Untrusted


@dataclass
class Loaded:
    """A robot, or the findings (SK101..SK103) that say why it could not be read."""

    robot: Robot | None
    findings: list[Finding] = field(default_factory=list)


def load_robot(
    path: Path,
    *,
    args: dict[str, str] | None = None,
    package_paths: tuple[str, ...] | list[str] = (),
    timeout: float = 60.0,
    untrusted: Untrusted | None = None,
    overlay: Mapping[str, bytes] | None = None,
    cache: ExpansionCache | None = None,
) -> Loaded:
    """Load and model a URDF/xacro file. Raises InputError for unreadable/non-robot input.

    ``overlay`` maps absolute paths to bytes read instead of those files (stdin, ``--fix``).
    ``cache``: the expansion cache to use (see ``sensorkit.loading.cache``), if any.
    """
    resolver = PackageResolver.from_options(list(package_paths), near=path)
    result = load_description(
        path,
        args=args,
        resolver=resolver,
        timeout=timeout,
        untrusted=untrusted,
        overlay=overlay,
        cache=cache,
    )
    if result.document is None:
        return Loaded(None, result.findings)
    return Loaded(build_robot(result.document), result.findings)


__all__ = ["Loaded", "Robot", "build_robot", "load_robot"]
