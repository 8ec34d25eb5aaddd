"""File references in robot descriptions: ``package://``, ``file://`` and relative paths."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from sensorkit.loading.packages import PackageResolver


@dataclass(frozen=True)
class UriTarget:
    """Where a reference points. ``path`` is None when it cannot be resolved here."""

    path: Path | None
    why: str = ""  # why not, when path is None
    missing_package: str | None = None


def resolve_uri(uri: str, base: Path, resolver: PackageResolver) -> UriTarget:
    """Resolve ``uri`` as ROS tools do; relative paths are taken from the folder ``base``.

    Does not check that the file exists. ``model://`` and other schemes belong to the
    simulator's own search path and are not resolved.
    """
    if uri.startswith("package://"):
        pkg, _, rel = uri[len("package://") :].partition("/")
        folder = resolver.find(pkg)
        if folder is None:
            return UriTarget(None, f"package {pkg!r} not found", pkg)
        return UriTarget(folder / rel)
    if uri.startswith("file://"):
        return UriTarget(Path(uri[len("file://") :]))
    if "://" in uri:
        return UriTarget(None, "only package:// and file:// URIs can be read outside the simulator")
    path = Path(uri)
    return UriTarget(path if path.is_absolute() else base / path)
