"""Read a robot's launch files, never run them (issue 24): see
sensorkit.loading.launch_facts for what is read, and each module for its sources.

The two names load their modules on first use (PEP 562): looking for launch files
(``discover``) does not import the reader, which a robot with none never needs."""

from __future__ import annotations

from typing import TYPE_CHECKING

from sensorkit.base.lazy import lazy_exports

if TYPE_CHECKING:
    from sensorkit.loading.launch.discover import find_launch_files
    from sensorkit.loading.launch.reader import read_launch

__getattr__ = lazy_exports(
    __name__, {"find_launch_files": "discover", "read_launch": "reader"}, globals()
)

__all__ = ["find_launch_files", "read_launch"]
