"""find_launch_files: the launch files that start a robot, found beside its description.

The robot's own package's ``launch/`` folder, and the ``launch/`` folders of the packages
beside it whose names say they start it in a simulator or on the robot.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from sensorkit.loading.packages import own_package, package_name

SIBLING_SUFFIXES = ("_gazebo", "_sim", "_simulation", "_bringup", "_ignition_bringup", "_gz")
PATTERNS = ("*.launch.py", "*.launch.xml", "*.launch.yaml", "*.launch", "*_launch.py")
MAX_FOUND = 200


def _launch_files(package: Path) -> list[Path]:
    folder = package / "launch"
    if not folder.is_dir():
        return []
    found = {p for pattern in PATTERNS for p in folder.rglob(pattern) if p.is_file()}
    return sorted(found)


def find_launch_files(robot_file: Path, roots: Sequence[Path] = ()) -> list[Path]:
    """Launch files of the robot's package and of its simulation and bringup siblings."""
    own = own_package(robot_file)
    if own is None:
        return []
    packages = [own]
    base = (package_name(own / "package.xml") or own.name).removesuffix("_description")
    folders = {own.parent, *roots}
    for folder in sorted(folders):
        try:
            children = sorted(p for p in folder.iterdir() if (p / "package.xml").is_file())
        except OSError:
            continue
        for child in children:
            name = package_name(child / "package.xml") or child.name
            if child != own and name.startswith(base) and name.endswith(SIBLING_SUFFIXES):
                packages.append(child)
    out: list[Path] = []
    for package in packages:
        out.extend(p for p in _launch_files(package) if p not in out)
    return out[:MAX_FOUND]
