"""SK4xx: sensor definitions."""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Iterator

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.limits import (
    CLASSIC_TEXTURE_NAMED_TYPES,
    PLAUSIBLE_CAMERA_PIXELS,
    PROTOBUF_MAX_BYTES,
    as_float,
    frame_bytes,
)
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.parse import local
from sensorkit.model.sensors import CameraSpec, Sensor
from sensorkit.model.targets import is_gz

# sdformat's <image><format> values and the gz-rendering spellings it also accepts.
IMAGE_FORMATS = {
    "L8",
    "L16",
    "L_INT8",
    "L_INT16",
    "R_FLOAT16",
    "R_FLOAT32",
    "R8G8B8",
    "B8G8R8",
    "RGB_INT8",
    "BGR_INT8",
    "RGB_INT16",
    "RGB_FLOAT16",
    "RGB_FLOAT32",
    "R16G16B16",
    "BAYER_RGGB8",
    "BAYER_BGGR8",
    "BAYER_GBRG8",
    "BAYER_GRBG8",
    "RGBA_INT8",
    "BGRA_INT8",
}
WIDE_ANGLE = {"wideanglecamera", "wide_angle_camera"}


@rule(
    "SK401",
    "error/warning",
    '`<gazebo reference="X">`: X is an existing link or joint (error when the block holds a sensor '
    "or plugin, which is lost; warning for material/physics settings that apply to nothing)",
    "none (silently ignored)",
)
def gazebo_reference(ctx: Context) -> Iterator[Finding]:
    # An error when the block carries a sensor or plugin: sdformat's URDF conversion inserts a
    # <gazebo reference> block only into the link of that name (gazebosim/sdformat@sdf9
    # (9ee2d4f):src/parser_urdf.cc:2084-2095, called per created link at :2851), so a block
    # naming no link is inserted nowhere and its sensor never exists.
    robot = ctx.robot
    # once, not per block: 33,000 blocks each holding a sensor took minutes (issue 25)
    sensor_blocks = {id(s.block) for s in robot.sensors if s.block is not None}
    for block in robot.gazebo:
        ref = block.reference
        if ref is None or ref in robot.link_map or ref in robot.joint_map:
            continue
        from sensorkit.base.suggest import closest

        close = closest(ref, [*robot.link_map, *robot.joint_map])
        has_sensor = id(block.element) in sensor_blocks
        # A sensor or plugin in the block is lost; material, friction or colour settings
        # only apply to nothing (shared files often style every variant's links).
        carries = has_sensor or any(local(el) == "plugin" for el in block.element)
        yield ctx.finding(
            "SK401",
            Severity.ERROR if carries else Severity.WARNING,
            f'<gazebo reference="{ref}">: no link or joint is called {ref!r}; Gazebo silently '
            f"ignores this block{' and its sensor' if has_sensor else ''}",
            block.source,
            link=ref,
            fix=f"did you mean {close[0]!r}?" if close else "name an existing link",
        )


@rule(
    "SK402",
    "error/warning",
    "sensor names unique within the link they end up on after fixed-joint lumping (Gazebo Sim: "
    "sdformat refuses a duplicate; Gazebo Classic: two cameras or two depth cameras abort "
    "gzserver, other pairs are found by name only once: warning); every sensor has a name",
    formats=("urdf", "sdf"),
)
def unique_sensors(ctx: Context) -> Iterator[Finding]:
    # Gazebo Sim: sdformat loads a link's sensors with loadUniqueRepeated: a second sensor of
    # the same name in one link is a DUPLICATE_NAME error (gazebosim/sdformat@sdf14:
    # src/Link.cc:167, src/Utils.hh:128-136). Sensors on different links are scoped apart
    # (world::model::link::sensor), so equal names there collide only through topics or
    # nodes: SK605 and SK604.
    # Gazebo Classic 11 creates both (gazebosim/gazebo-classic@upstream/11.10.2+dfsg via
    # elysia-best/gazebo-classic: gazebo/physics/Link.cc:185-209, gazebo/sensors/
    # SensorManager.cc:488-531, no duplicate check); see CLASSIC_TEXTURE_NAMED_TYPES for the
    # types that then abort gzserver. Any other type works, but SensorManager::GetSensor
    # matches the scoped name world::model::link::sensor and returns the first
    # (SensorManager.cc:883-888), so the second cannot be looked up by name.
    conv = ctx.conversion
    by_link: dict[tuple[str, str], list[Sensor]] = defaultdict(list)
    for s in ctx.robot.sensors:
        if not s.name:
            yield ctx.finding(
                "SK402",
                Severity.ERROR,
                "a <sensor> has no name",
                s.source,
                fix="give every sensor a unique name",
            )
            continue
        link = conv.survivor(s.reference) if s.reference in ctx.robot.link_map else s.reference
        by_link[(str(link), s.name)].append(s)
    for (link, name), items in by_link.items():
        where = (
            f"on link {link!r}"
            if all(x.reference == link for x in items)
            else f"on links {', '.join(sorted({str(x.reference) for x in items}))}, which lumping merges into {link!r}"
        )
        for s in items[1:]:
            severity, what = _duplicate_effect(ctx, s, items[0])
            yield ctx.finding(
                "SK402",
                severity,
                f"sensor name {name!r} is used {len(items)} times {where}: {what}",
                s.source,
                sensor=name,
                link=s.reference,
                fix="give every sensor on a link its own name",
            )


def _duplicate_effect(ctx: Context, s: Sensor, first: Sensor) -> tuple[Severity, str]:
    if is_gz(ctx.target):
        return Severity.ERROR, "sdformat refuses the duplicate"
    if s.type == first.type and s.type in CLASSIC_TEXTURE_NAMED_TYPES:
        return Severity.ERROR, (
            f"Gazebo Classic creates both {s.type} sensors, and the second's render texture name is "
            "already taken: Ogre throws 'Resource with the name ... already exists' and gzserver aborts"
        )
    return Severity.WARNING, (
        "Gazebo Classic creates and runs both, but finds a sensor by its scoped name "
        "(world::model::link::sensor) and gets only the first"
    )


def _cameras(ctx: Context) -> Iterator[Sensor]:
    for s in ctx.robot.sensors:
        if s.is_camera:
            yield s


@rule(
    "SK403",
    "error/warning",
    "camera image width/height positive integers; format known (an error on Gazebo Sim, where "
    "sdformat refuses it; a warning on Gazebo Classic, which renders PF_R8G8B8 that gazebo_ros "
    "labels bgr8, unless it is a Classic-only format gazebo_ros mislabels); above 4096x4096 "
    "(warning: beyond any real camera; over 2 GB Gazebo Sim cannot publish)",
    "sdformat (format)",
    formats=("urdf", "sdf"),
)
def camera_image(ctx: Context) -> Iterator[Finding]:
    for s in _cameras(ctx):
        for cam in s.cameras:
            for problem in cam.problems:
                if problem.startswith("image"):
                    yield ctx.finding(
                        "SK403",
                        Severity.ERROR,
                        f"sensor {s.name!r}: {problem}",
                        cam.source,
                        sensor=s.name,
                        fix="write a positive whole number",
                    )
            for what, value in (("width", cam.width), ("height", cam.height)):
                if value is not None and value <= 0:
                    yield ctx.finding(
                        "SK403",
                        Severity.ERROR,
                        f"sensor {s.name!r}: image {what} {value} is not positive",
                        cam.source,
                        sensor=s.name,
                        fix="write a positive whole number",
                    )
            if cam.width and cam.height and cam.width > 0 and cam.height > 0:
                yield from _too_large_camera(ctx, s, cam)
            if cam.format is not None and cam.format not in IMAGE_FORMATS:
                yield _unknown_format(ctx, s, cam)


def _unknown_format(ctx: Context, s: Sensor, cam: CameraSpec) -> Finding:
    """Error where the camera does not work, warning on Classic, where it renders bgr8
    (sources: sensorkit.knowledge.sdf_values)."""
    from sensorkit.knowledge.sdf_values import (
        CLASSIC_EXTRA_IMAGE_FORMATS,
        CLASSIC_UNKNOWN_FORMAT,
        GZ_UNKNOWN_FORMAT,
    )

    msg = f"sensor {s.name!r}: image format {cam.format!r} is unknown"
    if is_gz(ctx.target):
        severity, msg = Severity.ERROR, f"{msg}: {GZ_UNKNOWN_FORMAT}"
    elif cam.format in CLASSIC_EXTRA_IMAGE_FORMATS:
        severity = Severity.ERROR
        msg += (
            ": Gazebo Classic renders it in its own layout, but gazebo_ros does not know it "
            "and labels the image bgr8, 3 bytes a pixel: the image is garbled"
        )
    else:
        severity, msg = Severity.WARNING, f"{msg}: {CLASSIC_UNKNOWN_FORMAT}"
    return ctx.finding(
        "SK403",
        severity,
        msg,
        cam.source,
        sensor=s.name,
        fix="use R8G8B8 (or B8G8R8, L8, L16, R_FLOAT32, BAYER_*)",
    )


def _too_large_camera(ctx: Context, s: Sensor, cam: CameraSpec) -> Iterator[Finding]:
    """A warning for a frame beyond any real camera (``knowledge.limits``)."""
    assert cam.width is not None and cam.height is not None
    pixels = cam.width * cam.height
    if pixels <= PLAUSIBLE_CAMERA_PIXELS:
        return
    size = frame_bytes(cam.width, cam.height, cam.format, s.is_depth)
    size_f = as_float(size)
    rate = (
        f" ({size_f * s.update_rate / 1e9:.3g} GB/s at {s.update_rate:g} Hz)"
        if s.update_rate
        else ""
    )
    msg = (
        f"sensor {s.name!r}: {cam.width}x{cam.height} = {as_float(pixels) / 1e6:.3g} MP per frame "
        f"is beyond any real camera (4K is 8.3 MP): {size_f / 1e6:.3g} MB per image{rate}"
    )
    if size > PROTOBUF_MAX_BYTES and is_gz(ctx.target):
        msg += "; Gazebo Sim cannot publish it at all (a frame over 2 GB exceeds protobuf's message limit)"
    yield ctx.finding(
        "SK403",
        Severity.WARNING,
        msg,
        cam.source,
        sensor=s.name,
        fix="check width and height for a typo (render preview refuses it unless --max-pixels allows)",
    )


@rule(
    "SK404",
    "error/warning",
    "horizontal_fov > 0 and < pi for pinhole cameras (warning above 2.6 rad)",
    "sdformat (bounds only)",
    formats=("urdf", "sdf"),
)
def camera_fov(ctx: Context) -> Iterator[Finding]:
    # An error at and past pi: Gazebo Classic renders vfov = 2 atan(tan(hfov / 2) / ratio),
    # clamped to [0.001, 0.999 pi] (elysia-best/gazebo-classic@upstream/11.10.2+dfsg:
    # gazebo/rendering/Camera.cc:2025-2035, LimitFOV :1563-1566): past pi tan is negative and
    # the image collapses to a 0.001 rad sliver; camera_info's fx = width / (2 tan(hfov / 2))
    # (gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:366-374) is then
    # negative, or about 0 at pi. Gazebo Sim computes the same vfov and hands it to ogre-next
    # (gazebosim/gz-rendering@gz-rendering8 ff0c5b8:ogre2/src/Ogre2Camera.cc:181-183).
    for s in _cameras(ctx):
        for cam in s.cameras:
            if any(p.startswith("horizontal_fov") for p in cam.problems):
                yield ctx.finding(
                    "SK404",
                    Severity.ERROR,
                    f"sensor {s.name!r}: {cam.problems[0]}",
                    cam.source,
                    sensor=s.name,
                    fix="write the field of view in radians",
                )
                continue
            h = cam.hfov
            if h is None:
                continue
            if h <= 0 or (h >= math.pi and s.type not in WIDE_ANGLE):
                yield ctx.finding(
                    "SK404",
                    Severity.ERROR,
                    f"sensor {s.name!r}: horizontal_fov {h:g} rad is outside (0, pi): a pinhole camera cannot see that",
                    cam.source,
                    sensor=s.name,
                    fix="horizontal_fov is in radians (1.047 = 60 degrees); use a wideanglecamera for more than 180 degrees",
                )
            elif h > 2.6 and s.type not in WIDE_ANGLE:
                yield ctx.finding(
                    "SK404",
                    Severity.WARNING,
                    f"sensor {s.name!r}: horizontal_fov {h:g} rad ({math.degrees(h):.0f} degrees) stretches a pinhole image badly at the edges",
                    cam.source,
                    sensor=s.name,
                    fix="use at most about 2.6 rad, or a wideanglecamera",
                )


# Depth-test resolution of Gazebo Classic's depth camera (SK405).
#
# Gazebo Classic writes the published depth as linear view depth in float32:
# depth = gl_Position.w (gazebosim/gazebo-classic@310a1d6:media/materials/programs/depth_map.vert:10,
# @f62d0cd:depth_map.frag:12) into a PF_FLOAT32_R render texture
# (@0106de6:gazebo/rendering/DepthCamera.cc CreateDepthTexture, Ogre::PF_FLOAT32_R), so
# the published value is not quantised by near or far. Which surface wins a pixel is
# still decided by the render target's z-buffer: Ogre 1.9's GL FBO manager prefers
# packed GL_DEPTH24_STENCIL8 (OGRECave/ogre@852f847:RenderSystems/GL/src/
# OgreGLFBORenderTexture.cpp:112-123,468-471; OgreGLRenderSystem.cpp:1167-1181), a 24-bit
# fixed-point buffer holding the standard (non-reversed) projection
# (OgreMain/src/OgreFrustum.cpp:435-436). Its step is 2^-24 of z = f/(f-n)(1-n/d), so at
# distance d two surfaces closer together than d^2 (f-n) / (f n 2^24) can z-fight.
_Z24_STEP = 2.0**-24
# Reported when that band reaches 0.1% of the distance at the far clip. This is a chosen
# materiality floor (sensorkit's, not a simulator fact); it equals far/near > ~1.7e4.
_ZFIGHT_REL = 1e-3


def _classic_zfight_band(near: float, far: float, d: float) -> float:
    """Smallest surface separation Gazebo Classic's 24-bit depth test resolves at distance d."""
    return d * d * (far - near) / (far * near) * _Z24_STEP


@rule(
    "SK405",
    "error/warning",
    "clip 0 < near < far (error); depth cameras on Gazebo Classic with far/near > ~1.7e4 (warning: its 24-bit "
    "depth test lets surfaces within 0.1% of the far clip z-fight); min_depth/max_depth inside the clip range",
    formats=("urdf", "sdf"),
)
def camera_clip(ctx: Context) -> Iterator[Finding]:
    for s in _cameras(ctx):
        for cam in s.cameras:
            for p in cam.problems:
                if "clip" in p:
                    yield ctx.finding(
                        "SK405",
                        Severity.ERROR,
                        f"sensor {s.name!r}: {p}",
                        cam.source,
                        sensor=s.name,
                        fix="write distances in metres",
                    )
            near, far = cam.near, cam.far
            if near is not None and far is not None:
                # near <= 0: Ogre throws "Near clip distance must be greater than zero."
                # (OGRECave/ogre@v1-9-0:OgreMain/src/OgreFrustum.cpp:124-128; Gazebo Classic
                # passes <clip><near> straight to it, gazebo/rendering/Camera.cc:814-815).
                # near >= far is not verified against a simulator here (issue 23 audit).
                if not 0 < near < far:
                    yield ctx.finding(
                        "SK405",
                        Severity.ERROR,
                        f"sensor {s.name!r}: clip near {near:g} / far {far:g} must satisfy 0 < near < far",
                        cam.source,
                        sensor=s.name,
                        fix="e.g. <clip><near>0.05</near><far>50</far></clip>",
                    )
                    continue
                # No depth-precision warning on Gazebo Sim (fortress, harmonic, jetty), for any
                # near or far/near. Its ogre2 depth camera renders into a PFG_D32_FLOAT depth
                # texture (gazebosim/gz-rendering@ff0c5b8 (gz-rendering8):ogre2/src/
                # Ogre2DepthCamera.cc:655,679; same in ignition-rendering6_6.6.4@9ee7e96:670,694,
                # gz-rendering9@f61bf36:655,679, main@dafbffa:665,689) and recovers depth as
                # d = B / (z - A) (ogre2/src/media/materials/programs/GLSL/depth_camera_fs.glsl:107)
                # with A, B from Ogre's getProjectionParamsAB (Ogre2DepthCamera.cc:470-476).
                # ogre-next defaults to reverse depth (ignition-forks/ogre-next@40dcea7 (v2.2.4):
                # OgreMain/src/OgreRenderSystem.cpp:96; @7449a36 (2.3):109), which GL3Plus keeps
                # whenever GL 4.5 or GL_ARB_clip_control is present (glClipControl(GL_LOWER_LEFT,
                # GL_ZERO_TO_ONE): v2.2.4 RenderSystems/GL3Plus/src/OgreGL3PlusRenderSystem.cpp:
                # 3262-3270; 2.3 :3298-3305), and the A, B pair follows it (OgreFrustum.cpp:118-127).
                # Reversed float32 depth keeps about 2^-24 of the distance at every distance (our
                # float32 model of that shader: near 0.02, far 300 steps by ~2e-5 m at 100 m).
                # Only GL3Plus without clip control (GL < 4.5, no ARB_clip_control) falls back to
                # forward depth; the Vulkan and Metal render systems were not checked.
                if s.is_depth and not is_gz(ctx.target):
                    band = _classic_zfight_band(near, far, far)
                    if band >= _ZFIGHT_REL * far:
                        yield ctx.finding(
                            "SK405",
                            Severity.WARNING,
                            f"sensor {s.name!r}: far/near = {far / near:.0f}: Gazebo Classic's 24-bit depth test "
                            f"cannot separate surfaces less than ~{band:.2g} m apart at the far clip ({far:g} m), "
                            "so they can z-fight (the published depth values are linear float32 and are not coarsened)",
                            cam.source,
                            sensor=s.name,
                            fix="raise near or lower far: the band grows as far^2/near",
                        )
            if not s.is_depth or near is None or far is None or not 0 < near < far:
                continue
            lo, hi = _depth_range(s)
            for what, value in (("min_depth", lo), ("max_depth", hi)):
                if value is not None and not (near - 1e-9 <= value <= far + 1e-9):
                    yield ctx.finding(
                        "SK405",
                        Severity.WARNING,
                        f"sensor {s.name!r}: {what} {value:g} is outside the clip range [{near:g}, {far:g}]",
                        cam.source,
                        sensor=s.name,
                        fix=f"keep {what} within the clip range",
                    )


def _depth_range(s: Sensor) -> tuple[float | None, float | None]:
    """min/max depth as the plugin (classic) or the depth clip (gz) writes it."""
    from sensorkit.model.parse import parse_float

    lo = hi = None
    for p in s.plugins:
        lo = lo if lo is not None else parse_float(p.param("min_depth"))[0]
        hi = hi if hi is not None else parse_float(p.param("max_depth"))[0]
    from sensorkit.knowledge.gazebo_sim import GZ_READS_DEPTH_CLIP

    cam = s.camera
    if cam is not None and s.type in GZ_READS_DEPTH_CLIP:  # gz depth_camera ignores it
        lo = lo if lo is not None else cam.depth_near
        hi = hi if hi is not None else cam.depth_far
    return lo, hi


@rule(
    "SK407",
    "warning",
    "update_rate present and > 0 for cameras and lidars",
    formats=("urdf", "sdf"),
)
def update_rate(ctx: Context) -> Iterator[Finding]:
    for s in ctx.robot.sensors:
        if not (s.is_camera or s.kind == "lidar"):
            continue
        if s.update_rate_text is None:
            yield ctx.finding(
                "SK407",
                Severity.WARNING,
                f"sensor {s.name!r} has no <update_rate>: it renders as fast as the simulation allows",
                s.source,
                sensor=s.name,
                fix="add <update_rate>30</update_rate> (cameras) or 10 (lidars)",
            )
        elif s.update_rate is None or s.update_rate <= 0:
            yield ctx.finding(
                "SK407",
                Severity.WARNING,
                f"sensor {s.name!r}: update_rate {s.update_rate_text!r} is not > 0",
                s.source,
                sensor=s.name,
                fix="write a positive rate in Hz",
            )


@rule(
    "SK613",
    "error",
    "a sensor type the target's Gazebo Sim never creates (all: `ray`, `lidar`, `multicamera`, "
    "`sonar`, `rfid`, `rfidtag`, `wireless_*`; Fortress also `wideanglecamera`, `air_speed`): it "
    "publishes nothing; name the replacement (`gpu_lidar`, one `camera` per eye)",
    formats=("urdf", "sdf"),
)
def gz_unsupported_type(ctx: Context) -> Iterator[Finding]:
    # Per version, with sources: sensorkit.knowledge.gazebo_sim.GZ_NEVER_CREATED.
    from sensorkit.knowledge.gazebo_sim import gz_never_created, gz_version

    for s in ctx.robot.sensors:
        row = gz_never_created(ctx.target, s.type)
        if row is None:
            continue
        yield ctx.finding(
            "SK613",
            Severity.ERROR,
            f"sensor {s.name!r} has type {s.type!r}, which Gazebo Sim {gz_version(ctx.target)} never "
            f"creates: {row.why}; the sensor publishes nothing ({row.source})",
            s.source,
            sensor=s.name,
            fix=f"use {row.use}",
        )
