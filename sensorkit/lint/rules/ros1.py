"""SK602, SK611: a description written for ROS 1.

ROS 1 parameter tags and ``<remap>`` inside a ROS 2 plugin (read by nothing), and, under
``--target auto``, a description validated as ROS 1 said once.
"""

from __future__ import annotations

from collections.abc import Iterator

from sensorkit.base.consequence import Consequence, Role
from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.gazebo_ros import ROS1_TO_ROS2_PARAMS, ROS2_PLUGINS
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.plugins import ros_name
from sensorkit.lint.rules.ros1_values import consequence, full_name, why
from sensorkit.model.parse import children, local
from sensorkit.model.robot import all_plugins


@rule(
    "SK602",
    "error/warning/info",
    "ROS 1 parameter tags inside a ROS 2 plugin (`frameName`, `cameraName`, `imageTopicName`, `topicName`, "
    "`robotNamespace`, `hackBaseline`, `updateRate`, ...) are silently ignored: name the ROS 2 form. Severity "
    "by consequence: error when the ignored value moves a topic or frame, or changes a calibration or a drive's "
    "geometry; warning when it changes a rate, noise, limit or flag; info when the value is what ROS 2 does "
    "anyway, or no plugin ever read it",
    formats=("urdf", "sdf"),
)
def ros1_params(ctx: Context) -> Iterator[Finding]:
    if ctx.target != "classic":
        return
    for p in all_plugins(ctx.robot):
        name = ros_name(p)
        if name is None or name not in ROS2_PLUGINS:
            continue
        sensor = p.sensor.name if p.sensor else None
        for el in p.param_elements():
            tag = local(el)
            if tag in ROS1_TO_ROS2_PARAMS:
                c, note = consequence(ctx, p, tag, (el.text or "").strip())
                yield ctx.judged(
                    "SK602",
                    c,
                    f"<{tag}> is a ROS 1 parameter: the ROS 2 {p.filename} never reads it{note}{why(c)}",
                    el,
                    sensor=sensor,
                    fix=f"use {ROS1_TO_ROS2_PARAMS[tag]}"
                    if c.severity is not Severity.INFO
                    else f"remove it (or write {ROS1_TO_ROS2_PARAMS[tag]})",
                )
        ros = p.ros_block()
        if ros is not None:
            for el in children(ros, "remap"):
                src, dst = el.get("from", "FROM"), el.get("to", "TO")
                # ROS 2 leaves the name as the plugin resolves it: the remap's target is
                # what was meant, the source's resolution is what is used.
                c = Consequence(Role.TOPIC, full_name(p, dst), full_name(p, src))
                yield ctx.judged(
                    "SK602",
                    c,
                    f'<remap from="{src}" to="{dst}"/> is ROS 1 launch syntax: gazebo_ros ignores it{why(c)}',
                    el,
                    sensor=sensor,
                    fix=f"<remapping>{src}:={dst}</remapping>",
                )


@rule(
    "SK611",
    "warning",
    "under `--target auto`, a description written for ROS 1 (ROS 1-only plugins and tags, "
    "nothing only ROS 2 has) is said once and validated as ROS 1, instead of one SK602 per tag",
    formats=("urdf", "sdf"),
)
def written_for_ros1(ctx: Context) -> Iterator[Finding]:
    if not (ctx.auto and ctx.target == "ros1"):
        return
    from sensorkit.model.targets import ros1_evidence

    ev = ros1_evidence(ctx.robot)
    if not ev.is_ros1:
        return  # ROS 1 because its package.xml says catkin, not because of its tags
    yield ctx.finding(
        "SK611",
        Severity.WARNING,
        f"this description is written for ROS 1 ({ev.describe()}); validated as ROS 1 Gazebo "
        "Classic. Under ROS 2 none of these plugins publish as written",
        ctx.robot.document.root,
        fix="on ROS 1, pass --target ros1 to say so; to port it to ROS 2, validate with "
        "--target classic: every tag and plugin is listed with its ROS 2 form",
    )


