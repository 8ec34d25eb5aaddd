"""SK620: a Gazebo Sim world whose systems leave its cameras and GPU lidars unrendered.

gz-sim creates the gz-sensors object of a rendering sensor (camera, depth, RGB-D, thermal,
segmentation, bounding-box, wide-angle camera, GPU lidar) in the Sensors system only, so a
world that lists its systems and not that one has cameras that publish no image and lidars
that publish no scan (sources: GZ_RENDERING_SENSOR_TYPES and GZ_SENSORS_SYSTEM_SOURCE in
:mod:`sensorkit.knowledge.gazebo_sim`). A world that lists no system at all gets the
server's default configuration, which a user may have edited: it is not judged. The
Sensors system found anywhere in the world (a model's plugin too) is enough.
"""

from __future__ import annotations

from collections.abc import Iterator

from sensorkit.base.findings import Finding, Severity
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.targets import is_gz


@rule(
    "SK620",
    "error",
    "a Gazebo Sim world lists its systems (`<plugin>`s) without the Sensors system "
    "(`gz-sim-sensors-system`; Fortress `ignition-gazebo-sensors-system`) while it holds "
    "cameras or GPU lidars: only that system renders them, so they publish nothing; the fix "
    "is the plugin line for the target",
    formats=("sdf",),
)
def world_without_sensors_system(ctx: Context) -> Iterator[Finding]:
    from sensorkit.knowledge.gazebo_sim import (
        GZ_RENDERING_SENSOR_TYPES,
        GZ_SENSORS_SYSTEM_CLASS,
        GZ_SENSORS_SYSTEM_FILE,
        GZ_SENSORS_SYSTEM_SOURCE,
        gz_never_created,
        gz_sensors_system_line,
        gz_version,
    )

    sm = ctx.robot.sdf
    if sm is None or sm.world is None or not sm.world_systems or not is_gz(ctx.target):
        return
    for p in sm.world_plugins:
        library = (p.get("filename") or "").strip().rsplit("/", 1)[-1]
        if GZ_SENSORS_SYSTEM_FILE.match(library) or GZ_SENSORS_SYSTEM_CLASS.match(
            (p.get("name") or "").strip()
        ):
            return
    rendered = [
        s.name
        for s in ctx.robot.sensors
        if s.type in GZ_RENDERING_SENSOR_TYPES and gz_never_created(ctx.target, s.type) is None
    ]
    if not rendered:
        return
    world = sm.world.get("name", "")
    shown = ", ".join(repr(n) for n in rendered)
    yield ctx.finding(
        "SK620",
        Severity.ERROR,
        f"world {world!r} lists its systems but not the Sensors system, which alone renders "
        f"cameras and GPU lidars in Gazebo Sim {gz_version(ctx.target)}: "
        f"{'sensor' if len(rendered) == 1 else 'sensors'} {shown} of model {sm.name!r} "
        f"{'publishes' if len(rendered) == 1 else 'publish'} no data "
        f"({GZ_SENSORS_SYSTEM_SOURCE.get(ctx.target, GZ_SENSORS_SYSTEM_SOURCE['harmonic'])})",
        sm.world,
        fix=f"add {gz_sensors_system_line(ctx.target)} to <world name={world!r}>",
    )
