"""Locate the data that ships with sensorkit (macros/ and templates/).

In an installed wheel they live in ``sensorkit/_data/``; in a source checkout (or an
editable install) they are the top-level ``macros/`` and ``templates/`` folders.
"""

from __future__ import annotations

from pathlib import Path

_PKG = Path(__file__).resolve().parent.parent  # the sensorkit package


def _data_dir(name: str) -> Path:
    for candidate in (_PKG / "_data" / name, _PKG.parent / name):
        if candidate.is_dir():
            return candidate
    msg = f"sensorkit's {name}/ folder is missing from this installation (looked in {_PKG})"
    raise FileNotFoundError(msg)


def macros_dir() -> Path:
    """The folder holding the shipped ``*.urdf.xacro`` sensor macros."""
    return _data_dir("macros")


def templates_dir() -> Path:
    """The folder holding the robot base templates used by ``sensorkit new``."""
    return _data_dir("templates")
