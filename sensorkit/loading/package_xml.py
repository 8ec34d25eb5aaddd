"""The ROS generation a robot file's package is built for, from its package.xml (issue 35).

``--target auto`` weighs it (sensorkit.model.targets.detect_target): a package whose
``<buildtool_depend>`` is ``catkin`` is a ROS 1 package, one whose build tool is an
``ament_*`` one (``ament_cmake``, ``ament_python``, ``ament_cmake_python``) a ROS 2 package.
``<buildtool_depend>`` is the build tool the package needs (REP 140/149), and
``<export><build_type>`` the build system colcon runs (``ament_python`` for a Python
package, whose buildtool_depend may be absent). A dependency with a ``condition`` attribute
(``$ROS_VERSION == 1``) belongs to a package built for both generations: it says neither.

The nearest package.xml up from the robot file is the file's package, as colcon and catkin
find it (sensorkit.loading.packages.own_package). Reading it is I/O, so it lives here; the
rules never read it.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from sensorkit.loading.document import display_path, strict_parser
from sensorkit.loading.packages import own_package

__all__ = ["PackageGeneration", "package_generation", "read_generation"]

MAX_PACKAGE_XML = 1 << 20  # a package.xml is a few kB; a larger one is not read


@dataclass(frozen=True)
class PackageGeneration:
    """The ROS generation (``ros1`` or ``ros2``) a package.xml says, and why in words."""

    ros: str
    path: Path
    tool: str  # the build tool that says it: "catkin", "ament_cmake", ...

    @property
    def why(self) -> str:
        ros = "ROS 1" if self.ros == "ros1" else "ROS 2"
        return f"package.xml ({display_path(self.path)}) builds with {self.tool}: a {ros} package"


def _tools(root: etree._Element) -> list[str]:
    """The build tools a package.xml names without a condition."""
    out: list[str] = []
    for el in root.iter("buildtool_depend", "build_type"):
        if el.get("condition") is not None:
            continue
        parent = el.getparent()
        if el.tag == "build_type" and (parent is None or parent.tag != "export"):
            continue
        text = (el.text or "").strip()
        if text:
            out.append(text)
    return out


def read_generation(package_xml: Path) -> PackageGeneration | None:
    """What ``package_xml`` says (None: unreadable, broken, both generations or neither)."""
    try:
        if package_xml.stat().st_size > MAX_PACKAGE_XML:
            return None
        root = etree.fromstring(package_xml.read_bytes(), strict_parser())
    except (OSError, etree.XMLSyntaxError, ValueError):
        return None
    if root is None or root.tag != "package":
        return None
    tools = _tools(root)
    ros1 = [t for t in tools if t == "catkin"]
    ros2 = [t for t in tools if t.startswith("ament_")]
    if bool(ros1) == bool(ros2):
        return None
    return PackageGeneration("ros1" if ros1 else "ros2", package_xml, (ros1 or ros2)[0])


def package_generation(robot_file: Path) -> PackageGeneration | None:
    """What the package holding ``robot_file`` (nearest package.xml up) says, or None."""
    try:
        folder = own_package(Path(robot_file))
    except (OSError, RuntimeError, ValueError):
        return None
    return None if folder is None else read_generation(folder / "package.xml")
