"""SK608, SK614: the frame a Gazebo Sim sensor stamps.

Frame tags a gz version ignores or has deprecated, and a depth camera's point cloud
that gz-sensors computes x-forward but stamps with the optical frame.
"""

from __future__ import annotations

from collections.abc import Iterator

from sensorkit.base.consequence import UNKNOWN, Consequence, Role
from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.limits import ANGLE_TOL
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.coincide import frame_consequence
from sensorkit.lint.rules.topic_names import gz_topics, is_bridged, norm_topic
from sensorkit.model.frames import GZ_DEPRECATED_FRAME_TAGS, GZ_FRAME_TAGS, GZ_OPTICAL_FRAME_ID
from sensorkit.model.parse import child
from sensorkit.model.sensors import Sensor
from sensorkit.model.targets import is_gz

GZ_FRAME_TAG_NAMES = ("gz_frame_id", "ignition_frame_id", "frame_id")


@rule(
    "SK608",
    "error/warning/info",
    "a gz frame tag that the chosen gz version ignores (`ignition_frame_id` on harmonic+, `frame_id` before jetty, "
    "`optical_frame_id` on jetty, a tag another one overrides) or has deprecated (`gz_frame_id` on jetty). "
    "Severity by consequence: the frame written against the one stamped (an error when the default "
    "is stamped instead, info when it is the same frame; a warning when another tag names the frame "
    "read, since which was meant is unknown); a deprecated tag still read is a warning",
    formats=("urdf", "sdf"),
)
def ignored_frame_tags(ctx: Context) -> Iterator[Finding]:
    target = ctx.target
    if not is_gz(target):
        return
    read = GZ_FRAME_TAGS[target]
    deprecated = GZ_DEPRECATED_FRAME_TAGS.get(target, ())
    for s in ctx.robot.sensors:
        for tag in GZ_FRAME_TAG_NAMES:
            if tag not in s.frame_tags:
                continue
            first = next(t for t in read if t in s.frame_tags) if tag in read else None
            if tag not in read:
                why, fix = f"is ignored by {target}; it reads <{read[0]}>", None
            elif first != tag:
                why, fix = (
                    f"is ignored by {target}: <{first}> takes precedence",
                    f"keep one frame tag: <{first}>",
                )
            elif tag in deprecated:
                why, fix = (
                    f"is deprecated on {target}: still read, with a warning at every start",
                    None,
                )
            else:
                continue
            if tag in deprecated and first == tag:
                yield ctx.finding(
                    "SK608",
                    Severity.WARNING,
                    f"sensor {s.name!r}: <{tag}> {why}",
                    child(s.element, tag),
                    sensor=s.name,
                    frame=s.frame_tags[tag],
                    fix=fix or f"write <{read[0]}>{s.frame_tags[tag]}</{read[0]}>",
                )
                continue
            yield ctx.judged(
                "SK608",
                _stamped(ctx, s, s.frame_tags[tag]),
                f"sensor {s.name!r}: <{tag}> {why}",
                child(s.element, tag),
                sensor=s.name,
                frame=s.frame_tags[tag],
                fix=fix or f"write <{read[0]}>{s.frame_tags[tag]}</{read[0]}>",
            )
        for tag, value, el in s.misplaced_frame_tags:
            yield ctx.judged(
                "SK608",
                _stamped(ctx, s, value),
                f"sensor {s.name!r}: <{tag}> inside <camera> is never read (gz-sensors reads it from <sensor>)",
                el,
                sensor=s.name,
                frame=value,
                fix=f"move <{read[0]}>{value}</{read[0]}> directly under <sensor>",
            )
        cam = s.camera
        if cam is not None and cam.optical_frame_id and target not in GZ_OPTICAL_FRAME_ID:
            yield ctx.judged(
                "SK608",
                _stamped(ctx, s, cam.optical_frame_id),
                f"sensor {s.name!r}: <optical_frame_id> is ignored by {target}",
                child(cam.element, "optical_frame_id"),
                sensor=s.name,
                frame=cam.optical_frame_id,
                fix=f"set <{read[0]}>{cam.optical_frame_id}</{read[0]}> on the sensor instead",
            )


def _stamped(ctx: Context, s: Sensor, written: str) -> Consequence:
    """The frame ``s`` is stamped with (a camera's image frame), against ``written``: an
    ignored tag changes nothing where the frame read is the same frame
    (:mod:`sensorkit.lint.rules.coincide`)."""
    fr = ctx.frames_of(s)
    used = fr.camera_frame if s.is_camera else fr.published
    if used is None:
        return Consequence(Role.FRAME, written, UNKNOWN)
    c = frame_consequence(ctx.robot, s, written, used)
    if not c.equal and not (fr.is_default and fr.image_frame is None):
        # The frame read is written too, in another tag: which of the two the author meant
        # sensorkit cannot tell, so it promises no broken data (a warning, as SK410 does).
        return Consequence(Role.FLAG, written, used)
    return c


@rule(
    "SK614",
    "warning",
    "on Gazebo Sim, a bridge carries a depth or RGB-D camera's point cloud, which gz-sensors computes "
    "x-forward but stamps with the optical frame (gz-sensors#488): RViz shows it turned on its side",
    formats=("urdf", "sdf"),
)
def xforward_cloud(ctx: Context) -> Iterator[Finding]:
    bridge = ctx.bridge
    if not is_gz(ctx.target) or bridge is None or not bridge.files:
        return
    from sensorkit.knowledge.gazebo_sim import (
        CLOUD_FIX,
        GZ_XFORWARD_CLOUD_NOTE,
        GZ_XFORWARD_CLOUD_TYPES,
    )

    bridged = {norm_topic(t.gz) for t in bridge.topics if t.to_ros}
    for s in ctx.robot.sensors:
        if s.type not in GZ_XFORWARD_CLOUD_TYPES or not s.topic:
            continue
        cloud = next((t for t in gz_topics(s) if t.endswith("/points")), None)
        if cloud is None or not is_bridged(cloud, False, bridged):
            continue
        fr = ctx.frames_of(s)
        frame = fr.camera_frame
        T = fr.T_render_frame(ctx.robot, frame)
        if T is not None:
            from sensorkit.model.transforms import R_BODY_OPTICAL, angle_between, rotation

            if angle_between(rotation(T), R_BODY_OPTICAL) > ANGLE_TOL:
                continue  # stamped with an x-forward frame: the cloud lands right (SK502 covers images)
        yield ctx.finding(
            "SK614",
            Severity.WARNING,
            f"sensor {s.name!r}: the bridge carries its cloud {cloud}, but {GZ_XFORWARD_CLOUD_NOTE}: "
            f"stamped {frame!r}, RViz shows the cloud turned on its side (depth along the camera's "
            "right, the scene's up pointing ahead)",
            s.source,
            sensor=s.name,
            frame=frame,
            fix=CLOUD_FIX,
        )
