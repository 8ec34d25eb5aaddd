"""Which reader a file goes to, told by its name alone: split from ``sdf_files`` so that
loading a URDF does not import the SDF reader to learn that it is not SDF."""

from __future__ import annotations

from pathlib import Path

SDF_SUFFIXES = (".sdf", ".world")


def is_sdf_path(path: Path) -> bool:
    """Whether ``path`` is read as SDF (by its name: ``.sdf``, ``.world``)."""
    return path.name.lower().endswith(SDF_SUFFIXES)


def is_sdf_xacro(path: Path) -> bool:
    """Whether ``path`` is SDF written with xacro (``.sdf.xacro``, ``.world.xacro``): it
    is expanded first, and the result read as SDF."""
    return path.name.lower().endswith(tuple(s + ".xacro" for s in SDF_SUFFIXES))
