"""LaserScan metadata and the configuration snippets of the tools that consume a scan.

Every range the snippets write is checked against the scan's own ``range_max``: a
consumer that trusts readings past what the sensor can return marks phantom obstacles
or never clears them.
"""

from __future__ import annotations

from collections.abc import Sequence

from sensorkit.describe.intrinsics import LASER_SCAN_FIELDS, InvalidValue, LaserScanParams
from sensorkit.exporters import _text as t

__all__ = [
    "amcl_yaml",
    "nav2_obstacle_layer_yaml",
    "scan_yaml",
    "slam_toolbox_yaml",
]


def _range_at_most(name: str, value: float | None, default: float, scan: LaserScanParams) -> float:
    chosen = default if value is None else t.finite(value, name)
    if chosen <= 0.0:
        msg = f"{name} must be greater than zero, got {chosen!r}"
        raise InvalidValue(msg)
    if chosen > scan.range_max:
        msg = f"{name} ({chosen!r}) must not exceed the scan's range_max ({scan.range_max!r})"
        raise InvalidValue(msg)
    return chosen


def scan_yaml(scan: LaserScanParams, *, frame_id: str | None = None) -> str:
    """The fixed fields of the ``sensor_msgs/LaserScan`` the sensor publishes.

    ``header.frame_id`` (when given), ``angle_min``, ``angle_max``, ``angle_increment``,
    ``time_increment``, ``scan_time``, ``range_min``, ``range_max`` (reals); the number
    of ranges is noted in a comment.
    """
    lines = [f"# sensor_msgs/LaserScan: {scan.samples} ranges per message"]
    if frame_id is not None:
        lines += ["header:", f"  frame_id: {t.string(frame_id, 'frame_id')}"]
    lines += [f"{name}: {t.real(getattr(scan, name), name)}" for name in LASER_SCAN_FIELDS]
    return "\n".join(lines) + "\n"


def _scan_node_yaml(node_name: str, scan_topic: str, reals: Sequence[tuple[str, float]]) -> str:
    """A node's ROS 2 parameters: ``scan_topic``, then each of ``reals`` (name, value)."""
    lines = [
        f"{t.string(node_name, 'node_name')}:",
        "  ros__parameters:",
        f"    scan_topic: {t.string(scan_topic, 'scan_topic')}",
        *(f"    {name}: {t.real(value, name)}" for name, value in reals),
    ]
    return "\n".join(lines) + "\n"


def slam_toolbox_yaml(
    scan: LaserScanParams,
    *,
    scan_topic: str = "/scan",
    max_laser_range: float | None = None,
    node_name: str = "slam_toolbox",
) -> str:
    """slam_toolbox parameters: ``scan_topic`` and ``max_laser_range`` (<= range_max).

    ``max_laser_range`` defaults to the scan's ``range_max``.

    Raises:
        InvalidValue: ``max_laser_range`` is not in (0, range_max].
    """
    max_range = _range_at_most("max_laser_range", max_laser_range, scan.range_max, scan)
    return _scan_node_yaml(node_name, scan_topic, [("max_laser_range", max_range)])


def nav2_obstacle_layer_yaml(
    scan: LaserScanParams,
    *,
    topic: str = "/scan",
    obstacle_max_range: float | None = None,
    raytrace_max_range: float | None = None,
    max_obstacle_height: float = 2.0,
    inf_is_valid: bool = True,
    costmap: str = "local_costmap",
    layer_name: str = "obstacle_layer",
    source_name: str = "scan",
) -> str:
    """A Nav2 ``nav2_costmap_2d::ObstacleLayer`` block fed by this scan.

    The observation source has ``topic``, ``data_type: LaserScan``, ``marking`` and
    ``clearing``, ``obstacle_max_range`` (default min(2.5, range_max)) and
    ``raytrace_max_range`` (default min(3.0, range_max)), both <= range_max, and
    ``inf_is_valid`` (Gazebo reports "no return" as +inf; with ``true`` those beams
    still clear free space). Nested under ``<costmap>: <costmap>: ros__parameters`` as
    in ``nav2_params.yaml``; add ``layer_name`` to that costmap's ``plugins`` list.

    Raises:
        InvalidValue: a range is not in (0, range_max] or a name is empty.
    """
    obstacle = _range_at_most(
        "obstacle_max_range", obstacle_max_range, min(2.5, scan.range_max), scan
    )
    raytrace = _range_at_most(
        "raytrace_max_range", raytrace_max_range, min(3.0, scan.range_max), scan
    )
    height = t.positive(max_obstacle_height, "max_obstacle_height")
    cm = t.string(costmap, "costmap")
    layer = t.string(layer_name, "layer_name")
    source = t.string(source_name, "source_name")
    lines = [
        f"{cm}:",
        f"  {cm}:",
        "    ros__parameters:",
        f"      # add {t.quoted(layer_name)} to this costmap's plugins list",
        f"      {layer}:",
        f"        plugin: {t.quoted('nav2_costmap_2d::ObstacleLayer')}",
        "        enabled: true",
        f"        observation_sources: {source}",
        f"        {source}:",
        f"          topic: {t.string(topic, 'topic')}",
        "          data_type: LaserScan",
        "          marking: true",
        "          clearing: true",
        f"          max_obstacle_height: {t.real(height, 'max_obstacle_height')}",
        f"          obstacle_max_range: {t.real(obstacle, 'obstacle_max_range')}",
        "          obstacle_min_range: 0.0",
        f"          raytrace_max_range: {t.real(raytrace, 'raytrace_max_range')}",
        "          raytrace_min_range: 0.0",
        f"          inf_is_valid: {t.boolean(inf_is_valid)}",
    ]
    return "\n".join(lines) + "\n"


def amcl_yaml(
    scan: LaserScanParams,
    *,
    scan_topic: str = "scan",
    laser_min_range: float | None = None,
    laser_max_range: float | None = None,
    node_name: str = "amcl",
) -> str:
    """Nav2 AMCL parameters: ``scan_topic``, ``laser_min_range``, ``laser_max_range``.

    The ranges default to the scan's own ``range_min`` and ``range_max``.

    Raises:
        InvalidValue: ``laser_max_range`` exceeds range_max or the minimum is not below
            the maximum.
    """
    max_range = _range_at_most("laser_max_range", laser_max_range, scan.range_max, scan)
    min_range = (
        scan.range_min if laser_min_range is None else t.finite(laser_min_range, "laser_min_range")
    )
    if not 0.0 <= min_range < max_range:
        msg = (
            "need 0 <= laser_min_range < laser_max_range, got "
            f"laser_min_range={min_range!r}, laser_max_range={max_range!r}"
        )
        raise InvalidValue(msg)
    return _scan_node_yaml(
        node_name, scan_topic, [("laser_min_range", min_range), ("laser_max_range", max_range)]
    )
