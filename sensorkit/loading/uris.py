"""File references in robot descriptions: ``package://``, ``file://`` and relative paths."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from sensorkit.loading.packages import PackageResolver, valid_package_name

# Said of a reference a confined (--untrusted) resolver refuses. It names nothing but the
# reference the user wrote (the caller quotes it): never the path it resolved to, nor
# whether that exists.
OUTSIDE = "outside the workspace and the resolved packages; not read with --untrusted"


@dataclass(frozen=True)
class UriTarget:
    """Where a reference points. ``path`` is None when it cannot be resolved here."""

    path: Path | None
    why: str = ""  # why not, when path is None
    missing_package: str | None = None
    refused: bool = False  # --untrusted: outside the confinement (``why`` is OUTSIDE)


def resolve_uri(uri: str, base: Path, resolver: PackageResolver) -> UriTarget:
    """Resolve ``uri`` as ROS tools do; relative paths are taken from the folder ``base``.

    Does not check that the file exists. ``model://`` and other schemes belong to the
    simulator's own search path and are not resolved. A ``package://`` whose package part
    cannot be a package name (``..``, empty) names a package that is not found. With a
    confined resolver (``--untrusted``), a path outside its folders is refused, whatever
    is there.
    """
    if uri.startswith("package://"):
        pkg, _, rel = uri[len("package://") :].partition("/")
        folder = resolver.find(pkg) if valid_package_name(pkg) else None
        if folder is None:
            return UriTarget(None, f"package {pkg!r} not found", pkg)
        return _confined(folder / rel, resolver)
    if uri.startswith("file://"):
        return _confined(Path(uri[len("file://") :]), resolver)
    if "://" in uri:
        return UriTarget(None, "only package:// and file:// URIs can be read outside the simulator")
    path = Path(uri)
    return _confined(path if path.is_absolute() else base / path, resolver)


def _confined(path: Path, resolver: PackageResolver) -> UriTarget:
    if resolver.allows(path):
        return UriTarget(path)
    return UriTarget(None, OUTSIDE, refused=True)
