"""SK5xx: frames. The data must be where TF says it is."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING

from sensorkit.base.consequence import Consequence, Role
from sensorkit.base.findings import Finding, Severity, SourceRef
from sensorkit.knowledge.gazebo_sim import (
    GZ_FRAMED_KINDS,
    GZ_NAVSAT_TYPES,
    gz_never_created,
)
from sensorkit.knowledge.limits import ANGLE_TOL, POSITION_TOL
from sensorkit.lint.rules.base import Context, rule
from sensorkit.lint.rules.bridge import no_image_in_ros
from sensorkit.lint.rules.frame_joints import blamed_optical_joint, rpy_text, sdf_optical_fix
from sensorkit.lint.rules.optical_text import not_optical
from sensorkit.lint.rules.tf_frames import (
    gz_default_in_tf,
    gz_sensor_poses_published,
    in_tf,
    prefix_finding,
)
from sensorkit.model import transforms as tf
from sensorkit.model.frames import SensorFrames, optical_frame_at
from sensorkit.model.parse import child
from sensorkit.model.parts import Joint
from sensorkit.model.robot import Robot
from sensorkit.model.targets import is_gz

if TYPE_CHECKING:
    from sensorkit.model.sensors import Sensor
    from sensorkit.model.transforms import Mat

EXACT_TOL = 1e-4  # below this an optical rotation counts as written exactly (1.5708 passes)
OPTICAL_RPY = "${-pi/2} 0 ${-pi/2}"


def _chain_joints(robot: Robot, top: str, frame: str) -> list[Joint]:
    """Joints from ``top`` down to ``frame`` (empty unless ``top`` is an ancestor)."""
    below = robot.path_up(frame, top)
    if not below:
        return []
    return [robot.parent_joint[link] for link in reversed(below)]


def _exists(robot: Robot, name: str) -> bool:
    return name in robot.link_map


@rule(
    "SK501",
    "error/warning/info",
    "the published frame names an existing link (error; info on SDF, whose TF may come from a "
    "URDF beside it); a Gazebo Sim sensor with no frame tag is stamped MODEL::LINK::SENSOR, "
    "which TF does not have (warning)",
    formats=("urdf", "sdf"),
)
def frame_exists(ctx: Context) -> Iterator[Finding]:
    robot = ctx.robot
    gz = is_gz(ctx.target)
    # The model publishes its sensors' poses: the scoped name may well be in TF (below).
    poses = gz and gz_sensor_poses_published(robot)
    for s in robot.sensors:
        fr = ctx.frames_of(s)
        if gz and gz_never_created(ctx.target, s.type):
            continue  # never created (SK613): it stamps nothing
        if gz and fr.is_default and fr.image_frame is None and _gz_stamps_scoped_name(s):
            if poses or gz_default_in_tf(ctx, s, fr) or robot.sdf is not None:
                # An SDF model's PosePublisher is often added where it is spawned, out of
                # sensorkit's sight: osrf/subt@083c6a8:submitted_models/
                # costar_husky_sensor_config_1/launch/spawner.rb:29-32 adds one with
                # <publish_sensor_pose> true to the model it includes, putting the sensor's
                # scoped name in TF. Said of an SDF model, the warning may be false.
                continue
            yield _gz_default_frame(ctx, s, fr)
            continue
        for frame, how in ((fr.published, fr.how), (fr.image_frame, fr.image_how)):
            if frame is None or (fr.is_default and how == fr.how) or in_tf(ctx, frame):
                continue
            if fr.spec is not None and fr.spec.world_frame_ok and frame.strip("/") in WORLD_FRAMES:
                continue
            yield _missing_frame(
                ctx, frame, f"sensor {s.name!r} publishes in frame", how, s.source, s.name
            )
    # Model-level plugins that stamp data with a frame they read (hector's frameId, p3d ...).
    if is_gz(ctx.target):
        return
    from sensorkit.knowledge import plugins as known
    from sensorkit.model.frames import ros_generation

    for p in robot.model_plugins:
        spec = known.lookup(p.filename, ros_generation(ctx.target))
        if spec is None:
            continue
        for param in spec.frame_params:
            given = p.param(param)
            if not given:
                continue
            frame = known.stamped_frame(spec, given)  # ROS 1 tf::resolve drops a leading "/"
            if in_tf(ctx, frame):
                continue
            if spec.world_frame_ok and frame.strip("/") in WORLD_FRAMES:
                continue
            yield _missing_frame(
                ctx,
                frame,
                f"plugin {p.name!r} ({p.filename}) stamps its data with",
                param,
                p.source,
                None,
            )
            break


def _gz_stamps_scoped_name(s: Sensor) -> bool:
    """A gz sensor whose data, with no frame tag, reaches ROS stamped with its scoped name
    (see sensorkit/knowledge/gazebo_sim.py for the sources)."""
    return s.kind in GZ_FRAMED_KINDS or s.type in GZ_NAVSAT_TYPES


def _gz_default_frame(ctx: Context, s: Sensor, fr: SensorFrames) -> Finding:
    """A gz sensor with no frame tag is stamped with its scoped name, which TF never has.

    gz-sensors falls back to the sensor's name (gazebosim/gz-sensors@gz-sensors8:
    src/Sensor.cc:184-195), which gz-sim sets to MODEL::LINK::SENSOR
    (gazebosim/gz-sim@gz-sim8:src/rendering/RenderUtil.cc:1719-1721).
    """
    from sensorkit.model.frames import GZ_FRAME_TAGS

    tag = GZ_FRAME_TAGS[ctx.target][0]
    # ros_gz_bridge turns "::" into "/" in every frame it carries (gazebosim/ros_gz@jazzy
    # 739cb42:ros_gz_bridge/src/convert/utils.cpp:47-49, used by the header's conversion,
    # std_msgs.cpp:171-175, and NavSatFix's, sensor_msgs.cpp:516; the same on humble 5cc92f8
    # and ros2 a4d00a9).
    ros_frame = (fr.published or "").replace("::", "/")
    want = (optical_frame_at(ctx.robot, fr.T_world_render) if s.is_camera else fr.link) or fr.link
    launch = ctx.launch
    spawned = launch.spawn_name() if launch is not None else None
    model = (
        f"as {', '.join(launch.files)} spawns it"
        if spawned is not None and launch is not None
        else "shown as the URDF's robot name"
    )
    unless = (
        "no static transform of the launch files read adds it, so TF cannot place the data"
        if launch is not None and not launch.empty
        else "unless a launch file adds a static transform for it, TF cannot place the data"
    )
    return ctx.finding(
        "SK501",
        Severity.WARNING,
        f"sensor {s.name!r} has no frame tag: Gazebo Sim stamps its data {fr.published!r} "
        f"(MODEL::LINK::SENSOR, MODEL being the name the robot is spawned under, {model}), "
        f"which ros_gz_bridge hands to ROS as {ros_frame!r}, a frame "
        f"robot_state_publisher never publishes: {unless}",
        s.source,
        sensor=s.name,
        frame=fr.published,
        fix=f"add <{tag}>{want}</{tag}> to the sensor"
        + (" (an optical frame at the camera)" if s.is_camera else ""),
    )


# Frames outside the robot that a world-referenced plugin (p3d, bumper) may name.
WORLD_FRAMES = frozenset({"world", "map", "odom"})


def _missing_frame(
    ctx: Context, frame: str, what: str, how: str | None, where: SourceRef, sensor: str | None
) -> Finding:
    from sensorkit.base.suggest import closest

    prefixed = prefix_finding(ctx, frame, what, how, where, sensor)
    if prefixed is not None:
        return prefixed
    close = closest(frame, ctx.robot.link_map)
    sev, what_it_is = Severity.ERROR, "which is not a link of this robot: TF cannot place its data and RViz shows nothing"
    fix = f"add a link {frame!r} or name an existing one"
    if ctx.robot.sdf is not None:
        # TF for an SDF model often comes from a URDF beside it, unseen: nav2's gz_waffle.sdf.xacro
        # stamps 'camera_depth_frame', a link of the turtlebot3_waffle.urdf next to it
        # (ros-navigation/nav2_minimal_turtlebot_simulation@nav2_minimal_tb3_sim/urdf/turtlebot3_waffle.urdf:284)
        sev, fix = Severity.INFO, f"make sure the URDF TF is built from has a frame {frame!r}"
        what_it_is = (
            "which is no frame of this SDF model: TF must get it from elsewhere (a URDF that "
            "robot_state_publisher reads beside the SDF), or it cannot place the data; "
            "sensorkit does not see that URDF"
        )
    return ctx.finding(
        "SK501",
        sev,
        f"{what} {frame!r} (<{how}>), {what_it_is}",
        where,
        sensor=sensor,
        frame=frame,
        fix=f"did you mean {close[0]!r}?" if close else fix,
    )


def _stamped(
    ctx: Context, wanted: Callable[[Sensor], bool], *, position: bool = True
) -> Iterator[tuple[Sensor, SensorFrames, str | None, Mat]]:
    """The sensors ``wanted`` picks, each with its frames, the frame its data is stamped
    with (a camera's image frame, else the published one) and that frame's pose from the
    render pose; a sensor whose frame has no such pose is left out (for an SDF model, also
    one whose frame TF's publishers place differently: ``SensorFrames.T_render_frame``;
    ``position=False``: only its rotation is used, and only it must agree)."""
    robot = ctx.robot
    for s in robot.sensors:
        if not wanted(s):
            continue
        fr = ctx.frames_of(s)
        frame = fr.camera_frame if s.is_camera else fr.published
        T = fr.T_render_frame(robot, frame, position=position)
        if T is not None:
            yield s, fr, frame, T


@rule(
    "SK502",
    "error/info",
    "camera/depth image frame is optical: its rotation from the render pose is Rz(-pi/2)*Rx(-pi/2) "
    '(z forward, x right, y down) within 0.5 degree; say what the data will look like otherwise ("point cloud points up")',
    formats=("urdf", "sdf"),
)
def camera_optical(ctx: Context) -> Iterator[Finding]:
    robot = ctx.robot
    sdf = robot.sdf is not None
    for s, fr, frame, T in _stamped(ctx, lambda s: s.is_camera, position=False):
        if fr.is_default and fr.image_frame is None and not fr.plugin:
            continue
        R = tf.rotation(T)
        err = tf.angle_between(R, tf.R_BODY_OPTICAL)
        if err <= ANGLE_TOL:
            continue
        existing = optical_frame_at(robot, fr.T_world_render)
        where = (
            "its plugin's frame_name" if fr.how == "frame_name" else f"<{fr.image_how or fr.how}>"
        )
        if fr.how == "default":
            where = "the plugin names no frame, so Gazebo uses the link it sits on" + (
                "" if sdf else " after lumping"
            )
        message = (
            f"camera {s.name!r} stamps its images with {frame!r} ({where}), "
            f"{not_optical(R, is_gz(ctx.target))}"
        )
        unseen = no_image_in_ros(ctx, s, turned=tf.rotation_angle(R) > ANGLE_TOL)
        severity = Severity.ERROR if unseen is None else Severity.INFO
        consequence = None if unseen is None else Consequence(Role.FRAME, frame, frame)
        if unseen is not None:
            message = f"{message}; {unseen}"
        # In SDF the rotation is the link's <pose>, not a joint's: no joint is blamed.
        joint, rpy, _why = (None, None, "") if sdf else blamed_optical_joint(ctx, s, fr, frame)
        if joint is not None and rpy is not None:
            # The frame is a link whose only role is this camera's optical frame: the wrong
            # rotation is its joint's rpy, and that is where the finding points.
            text = rpy_text(rpy, robot.document.expanded)
            origin = child(joint.element, "origin")
            yield ctx.finding(
                "SK502",
                severity,
                f"{message}; the rotation comes from joint {joint.name!r}",
                origin if origin is not None else joint.element,
                sensor=s.name,
                frame=frame,
                link=fr.link,
                joint=joint.name,
                consequence=consequence,
                fix=f'write rpy="{text}" on joint {joint.name!r}',
            )
            continue
        yield ctx.finding(
            "SK502",
            severity,
            message,
            s.source,
            sensor=s.name,
            frame=frame,
            link=fr.link,
            consequence=consequence,
            fix=(
                f"publish in {existing!r}, which is already an optical frame at the camera"
                if existing
                else sdf_optical_fix(ctx, s, fr)
                if sdf
                else f"add a link {fr.link}_optical_frame with a fixed joint from {fr.link!r}: "
                f'<origin xyz="0 0 0" rpy="{OPTICAL_RPY}"/>, and publish in it '
                f"(frame_name / gz_frame_id)"
            ),
        )


@rule(
    "SK503",
    "error",
    "the published frame is co-located with the render origin (within 1 mm); report the offset",
    formats=("urdf", "sdf"),
)
def frame_position(ctx: Context) -> Iterator[Finding]:
    robot = ctx.robot
    # an IMU's frame position only matters through its lever arm
    for s, fr, frame, T in _stamped(ctx, lambda s: s.is_camera or s.kind == "lidar"):
        off = tf.translation(T)  # in the sensor's own frame
        dist = tf.norm(off)
        if dist <= POSITION_TOL or _stereo_right_eye(s, fr, off):
            continue
        if is_gz(ctx.target) and _gz_stereo_right_eye(ctx, s, off):
            continue
        yield ctx.finding(
            "SK503",
            Severity.ERROR,
            f"sensor {s.name!r} renders from one point but its frame {frame!r} sits {dist * 1000:.1f} mm away "
            f"(offset x {off[0]:+.4f}, y {off[1]:+.4f}, z {off[2]:+.4f} m in the sensor's frame): "
            "every point is displaced by that much",
            s.source,
            sensor=s.name,
            frame=frame,
            fix=(
                f"name a frame at the sensor in the plugin (<frame_name>{optical_frame_at(robot, fr.T_world_render) or fr.link}</frame_name>)"
                if fr.is_default
                else f'stamp a link placed where the sensor renders (<pose relative_to="{fr.link}"> the '
                f"sensor's <pose>, with a fixed joint), or move the sensor to {frame!r}"
                if robot.sdf is not None
                else _publish_at_sensor(robot, s, fr, frame)
            ),
        )


def _publish_at_sensor(robot: Robot, s: Sensor, fr: SensorFrames, frame: str | None) -> str:
    """SK503's fix on URDF: what ``--fix`` does where a link sits at the sensor already
    (the camera's optical frame, or the lidar's own link turned as it renders), else to
    move the stamped frame there. A lidar stamped ``base_link`` was told to move the base."""
    at = optical_frame_at(robot, fr.T_world_render) if s.is_camera else _own_link_at(robot, fr)
    if at is not None and at != frame:
        return f"publish in {at!r}, the link at the sensor (<frame_name>{at}</frame_name>; --fix does this)"
    return f'move {frame!r} to the sensor\'s origin: xyz="0 0 0" on its joint (and the same <pose> as the sensor)'


def _own_link_at(robot: Robot, fr: SensorFrames) -> str | None:
    """The sensor's own link when it sits where the sensor renders, turned alike."""
    if fr.T_world_render is None or not fr.link:
        return None
    T = robot.T_world_link(fr.link)
    if T is None:
        return None
    gap = tf.norm([a - b for a, b in zip(tf.translation(T), tf.translation(fr.T_world_render), strict=True)])
    turn = tf.angle_between(tf.rotation(T), tf.rotation(fr.T_world_render))
    return fr.link if gap <= POSITION_TOL and turn <= ANGLE_TOL else None


def _stereo_right_eye(s: Sensor, fr: SensorFrames, off: tuple[float, float, float]) -> bool:
    """The ROS stereo convention: the right eye publishes in the left eye's optical frame.

    Its camera_info carries the baseline instead, P[0][3] = Tx = -fx * baseline
    (ROS 2 ``hack_baseline``: ros-simulation/gazebo_ros_pkgs@ros2:
    gazebo_plugins/src/gazebo_ros_camera.cpp:399 reads it, :458 writes P[3] with it; ROS 1
    ``hackBaseline``: @noetic-devel:gazebo_plugins/src/gazebo_ros_camera_utils.cpp:191-197,
    :610).
    Seen from the right eye's body frame (x forward, y left), the left eye sits the baseline
    to its left: offset (0, +baseline, 0).
    """
    if not s.is_camera or fr.plugin is None:
        return False
    text = fr.plugin.param("hack_baseline") or fr.plugin.param("hackBaseline")
    try:
        baseline = float(text) if text is not None else 0.0
    except ValueError:
        return False
    if not baseline > 0:
        return False
    return tf.norm((off[0], off[1] - baseline, off[2])) <= POSITION_TOL


def _gz_stereo_right_eye(ctx: Context, s: Sensor, off: tuple[float, float, float]) -> bool:
    """Gazebo Sim's stereo pairs: the right eye stamped with the left eye's optical frame.

    gz-sim gives a camera a baseline itself when another camera was created on the same
    parent link before it (gazebosim/gz-sim@ign-gazebo6:src/systems/sensors/Sensors.cc:831-861,
    the same at @gz-sim8:src/systems/sensors/Sensors.cc:1189-1224): the first camera on the
    link is the left one, unless its Topic() holds "right" and the new one's "left" (then
    they swap, :851-855), and the right one gets SetBaseline(|y_right - y_left|), the two
    sensors' y in the link's frame (:857-860). Every gz camera type derives from
    CameraSensor (gazebosim/gz-sensors@gz-sensors8:include/gz/sensors/DepthCameraSensor.hh:64,
    RgbdCameraSensor.hh:52, ThermalCameraSensor.hh:64, ...), so the dynamic_cast at :832
    takes them all. SetBaseline writes P[3] = -fx * baseline into camera_info
    (gazebosim/gz-sensors@ign-sensors6:src/CameraSensor.cc:805-815,
    @gz-sensors8:src/CameraSensor.cc:794-804): the ROS stereo convention, as Classic's
    hack_baseline (see _stereo_right_eye). The parent is the link after fixed-joint lumping,
    so cameras of lumped links pair up too (gz-sim@gz-sim8:src/rendering/RenderUtil.cc:1323 passes the parent node's
    name); sensorkit takes the cameras in the order the description lists them. Accepted,
    as for Classic, only when the stamped frame sits exactly that baseline to the right
    eye's left, (0, +baseline, 0) in its frame.
    """
    robot, conv = ctx.robot, ctx.conversion
    if not s.is_camera or s.reference is None:
        return False
    link = conv.survivor(s.reference)
    on_link = [
        c
        for c in robot.sensors
        if c.is_camera
        and c.reference is not None
        and conv.survivor(c.reference) == link
        and not gz_never_created(ctx.target, c.type)
    ]
    if len(on_link) < 2 or not any(c is s for c in on_link):
        return False
    first = on_link[0]
    if s is first:
        # The first camera is a right eye only when a later one swaps with it (its topic
        # holds "right", the later one's "left"); the last such SetBaseline wins.
        swaps = [c for c in on_link[1:] if _swaps(robot, link, first, c)]
        if not swaps:
            return False
        left = swaps[-1]
    elif _swaps(robot, link, first, s):
        return False  # s is the left eye: its baseline stays 0
    else:
        left = first
    y = [_y_on_link(robot, c, link, ctx.target) for c in (left, s)]
    if y[0] is None or y[1] is None:
        return False
    baseline = abs(y[1] - y[0])
    return baseline > 0 and tf.norm((off[0], off[1] - baseline, off[2])) <= POSITION_TOL


def _swaps(robot: Robot, link: str, first: Sensor, later: Sensor) -> bool:
    """gz-sim's swap (Sensors.cc:851-855 at ign-gazebo6): the first camera's topic holds
    "right" and the later one's "left"."""
    return "right" in _gz_topic(first, link, robot) and "left" in _gz_topic(later, link, robot)


def _gz_topic(s: Sensor, link: str, robot: Robot) -> str:
    """The sensor's Topic() as gz-sensors has it: its <topic>, else the scoped default
    /world/WORLD/model/MODEL/link/LINK/sensor/NAME/image (see topic_names.py)."""
    return s.topic or f"/world/WORLD/model/{robot.name}/link/{link}/sensor/{s.name}/image"


def _y_on_link(robot: Robot, s: Sensor, link: str, target: str) -> float | None:
    """The sensor's y in ``link``'s frame (its <pose> after lumping)."""
    from sensorkit.model.frames import render_pose

    T_world_link, T_world_render = robot.world_pose(link), render_pose(robot, s, target)
    if T_world_link is None or T_world_render is None:
        return None
    return tf.translation(tf.relative(tf.pose_matrix(T_world_link), T_world_render))[1]


@rule(
    "SK504",
    "error",
    "lidar, IMU and other body sensors are published in a frame with identity rotation from the render pose (x forward, z up)",
    formats=("urdf", "sdf"),
)
def body_frame(ctx: Context) -> Iterator[Finding]:
    for s, fr, _frame, T in _stamped(ctx, lambda s: s.kind in ("lidar", "imu"), position=False):
        R = tf.rotation(T)
        err = tf.rotation_angle(R)
        if err <= ANGLE_TOL:
            continue
        what = "scan" if s.kind == "lidar" else "IMU data"
        optical = tf.angle_between(R, tf.R_BODY_OPTICAL) <= ANGLE_TOL
        yield ctx.finding(
            "SK504",
            Severity.ERROR,
            f"{s.kind} {s.name!r} publishes in {fr.published!r}, rotated {math.degrees(err):.1f} degrees from where it measures"
            + (" (an optical frame)" if optical else "")
            + f": the {what} appears turned by that much in TF",
            s.source,
            sensor=s.name,
            frame=fr.published,
            fix=f"publish in {fr.link!r} (or a frame with rpy 0 0 0 from it)",
        )


def _approx_joints(ctx: Context) -> Iterator[tuple[Joint, float, str]]:
    """Joints into frames used (or named) as optical whose rotation is nearly, not exactly, optical."""
    robot = ctx.robot
    seen: set[str] = set()
    candidates: list[tuple[str, str | None]] = []
    for s in robot.sensors:
        if s.is_camera:
            fr = ctx.frames_of(s)
            frame = fr.camera_frame
            if frame is not None and frame in robot.link_map and fr.link is not None:
                candidates.append((frame, fr.link))
    for lk in robot.links:
        if "optical" in lk.name and lk.name in robot.parent_joint:
            candidates.append((lk.name, None))
    for frame, top in candidates:
        joint = robot.parent_joint.get(frame)
        if joint is None or joint.name in seen:
            continue
        if top is not None:
            joints = _chain_joints(robot, top, frame)
            rotated = [j for j in joints if j.origin.rpy != (0.0, 0.0, 0.0)]
            if len(rotated) != 1:
                continue
            joint = rotated[0]
        R = tf.rpy_to_matrix(joint.origin.rpy)
        err = tf.angle_between(R, tf.R_BODY_OPTICAL)
        if EXACT_TOL < err <= ANGLE_TOL and joint.name not in seen:
            seen.add(joint.name)
            yield joint, err, frame


@rule(
    "SK505",
    "info",
    "optical rotation written approximately (e.g. -1.57 for -pi/2): report the angular error and suggest `${-pi/2}`",
)
def approximate_optical(ctx: Context) -> Iterator[Finding]:
    # URDF only: it points at the joint origin that writes the rotation; in SDF the rotation
    # is a link's <pose>, maybe relative to another frame, which this rule does not locate.
    for joint, err, frame in _approx_joints(ctx):
        text = joint.origin.rpy_text or " ".join(f"{v:g}" for v in joint.origin.rpy)
        yield ctx.finding(
            "SK505",
            Severity.INFO,
            f'joint {joint.name!r} into {frame!r} writes the optical rotation approximately (rpy "{text}"): '
            f"off by {math.degrees(err):.3f} degrees",
            joint.source,
            joint=joint.name,
            frame=frame,
            fix=f'write rpy="{OPTICAL_RPY}" (xacro) or rpy="-1.5707963267948966 0 -1.5707963267948966"',
        )


@rule(
    "SK506",
    "info",
    "a frame used as optical frame lacks the REP 103 `_optical` naming",
    formats=("urdf", "sdf"),
)
def optical_naming(ctx: Context) -> Iterator[Finding]:
    seen: set[str] = set()
    for s, fr, frame, T in _stamped(ctx, lambda s: s.is_camera, position=False):
        if frame is None or frame in seen or "optical" in frame:
            continue
        if tf.angle_between(tf.rotation(T), tf.R_BODY_OPTICAL) <= ANGLE_TOL:
            seen.add(frame)
            yield ctx.finding(
                "SK506",
                Severity.INFO,
                f"camera {s.name!r} publishes in {frame!r}, an optical frame whose name does not say so",
                s.source,
                sensor=s.name,
                frame=frame,
                fix=f"REP 103: call it {fr.link}_optical_frame",
            )


@rule(
    "SK507",
    "warning",
    "the robot description defines `odom` or `map` links, which clash with the TF that localization "
    "publishes (`world` fixed to the robot is a legitimate Gazebo idiom)",
    formats=("urdf", "sdf"),
)
def reserved_frames(ctx: Context) -> Iterator[Finding]:
    # SDF: sdformat_urdf hands robot_state_publisher every link by its name (see
    # tf_frames.sdf_maybe_in_tf); a nested model's link is scoped ("inner::odom"), no clash.
    sdf = ctx.robot.sdf is not None
    for lk in ctx.robot.links:
        if lk.name.lstrip("/") in ("odom", "map"):
            yield ctx.finding(
                "SK507",
                Severity.WARNING,
                f"link {lk.name!r} is part of the robot description: robot_state_publisher "
                + (
                    "fed this SDF (sdformat_urdf publishes every link by name) would fight "
                    if sdf
                    else "will fight "
                )
                + f"localization/odometry over the {lk.name!r} frame",
                lk.source,
                link=lk.name,
                fix=f"remove {lk.name!r} from the {'SDF' if sdf else 'URDF'}; odometry or localization publishes it",
            )
