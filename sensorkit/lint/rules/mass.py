"""SK3xx: mass, and what the URDF-to-SDF conversion keeps.

On SDF only SK302 runs. SK301 and SK303 are the conversion's (massless links dropped,
fixed joints lumped), which an SDF model never goes through (sensorkit.model.sdf.convert).
SK304's fix, a massless root link, is no fix in SDF: a link without <inertial> weighs 1 kg
there (gazebosim/sdformat@sdformat12_12.8.0:sdf/1.9/inertial.sdf:8).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from sensorkit.base.consequence import UNKNOWN, Consequence, Role
from sensorkit.base.findings import Finding, Severity
from sensorkit.lint.rules.base import Context, rule
from sensorkit.model.frames import optical_frame_at
from sensorkit.model.parse import stod_prefix
from sensorkit.model.parts import Inertial, Link
from sensorkit.model.sensors import Sensor
from sensorkit.model.targets import is_gz

# gz-math MassMatrix3 compares with machine epsilon scaled by a tolerance of 10.
_EPS = 10 * 2.220446049250313e-16


def principal_moments(inertia: dict[str, float]) -> tuple[float, float, float]:
    """Eigenvalues of the symmetric inertia tensor (closed form when diagonal)."""
    ixx, iyy, izz = inertia["ixx"], inertia["iyy"], inertia["izz"]
    ixy, ixz, iyz = inertia["ixy"], inertia["ixz"], inertia["iyz"]
    if ixy == 0.0 and ixz == 0.0 and iyz == 0.0:
        return tuple(sorted((ixx, iyy, izz)))  # type: ignore[return-value]
    ev = sorted(_eigvalsh3(((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz))))
    return (ev[0], ev[1], ev[2])


def _eigvalsh3(m: tuple[tuple[float, float, float], ...]) -> list[float]:
    """Eigenvalues of a symmetric 3x3 matrix: cyclic Jacobi rotations, in pure Python.

    Jacobi is as accurate as LAPACK's eigvalsh for a matrix this small (each eigenvalue
    within a few ulps of the largest), without importing numpy on the validate path.
    """
    big = max(abs(v) for row in m for v in row)
    if big == 0.0 or big - big != 0.0:
        return [m[0][0], m[1][1], m[2][2]]
    shift = -math.frexp(big)[1]  # scale by a power of two (exact) to keep squares finite
    a = [[math.ldexp(v, shift) for v in row] for row in m]
    for _ in range(64):
        off = a[0][1] ** 2 + a[0][2] ** 2 + a[1][2] ** 2
        if off <= 1e-40 * (a[0][0] ** 2 + a[1][1] ** 2 + a[2][2] ** 2) or off == 0.0:
            break
        for p, q, r in ((0, 1, 2), (0, 2, 1), (1, 2, 0)):
            apq = a[p][q]
            if apq == 0.0:
                continue
            theta = (a[q][q] - a[p][p]) / (2.0 * apq)
            t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1.0))
            c = 1.0 / math.sqrt(t * t + 1.0)
            s = t * c
            a[p][p] -= t * apq
            a[q][q] += t * apq
            a[p][q] = a[q][p] = 0.0
            arp, arq = a[r][p], a[r][q]
            a[r][p] = a[p][r] = c * arp - s * arq
            a[r][q] = a[q][r] = s * arp + c * arq
    return [math.ldexp(a[i][i], -shift) for i in range(3)]


def inertia_problem(inertial: Inertial) -> str | None:
    """Why gz-math would call this inertial invalid, or None."""
    if inertial.problems:
        return "; ".join(inertial.problems)
    mass = inertial.mass
    if mass is None:
        return "no mass"
    if mass < 0:
        return f"mass {mass:g} is negative"
    values = inertial.inertia
    if None in values.values():
        missing = [k for k, v in values.items() if v is None]
        return "<inertia> lacks " + ", ".join(missing)
    full: dict[str, float] = values  # type: ignore[assignment]  # no None left
    moments = principal_moments(full)
    lo, mid, hi = moments
    scale = max(1.0, abs(lo), abs(mid), abs(hi))
    if moments[0] < -_EPS * scale:
        return (
            f"inertia is not positive definite (principal moments {moments[0]:.3g}, "
            f"{moments[1]:.3g}, {moments[2]:.3g})"
        )
    a, b, c = moments
    if a + b + _EPS * scale < c:
        return (
            f"principal moments {a:.3g} + {b:.3g} < {c:.3g}: no real body has this inertia "
            "(triangle inequality)"
        )
    return None


@rule(
    "SK301",
    "error/info",
    "a link joined by a non-fixed joint has an `<inertial>` with mass > 0, else Gazebo drops "
    "it and its subtree (name what is lost). Severity by consequence: an error when what is "
    "lost holds a sensor (it publishes nothing) or a body (a visual or collision the robot "
    "loses); info when the links lost hold neither, so they only ever fed TF. A massless link "
    "fixed to `world` is not created but the links below it are kept: reported only when it "
    "holds a sensor, a body or joints to links below",
    "sdformat, at spawn",
)
def massless_links(ctx: Context) -> Iterator[Finding]:
    # An error: sdformat's URDF conversion returns before creating the link or recursing into its
    # children when a link not lumped away has no <inertial> or mass <= 0 ("urdf2sdf: link[...]
    # is not modeled in sdf.", "child links ignored": gazebosim/sdformat@sdf9 (9ee2d4f):
    # src/parser_urdf.cc:2658-2760; the recursion it skips is :2776-2780).
    robot, conv = ctx.robot, ctx.conversion
    lost_by: dict[str, list[str]] = {}  # cause -> the links it drops, in conv.dropped's order
    for n, c in conv.dropped.items():
        lost_by.setdefault(c, []).append(n)
    for name, cause in conv.dropped.items():
        if name != cause:
            continue
        link = robot.link_map[name]
        lost = lost_by[name]
        lost_set = set(lost)
        sensors = [s.name for s in robot.sensors if s.reference in lost_set]
        joint = robot.parent_joint.get(name)
        what = "has no <inertial>" if link.inertial is None else "has zero mass"
        kept_below: list[str] = []
        if name in conv.uncreated:
            # Fixed to 'world' by a joint lumping would reduce: sdformat creates no link for
            # it but converts the links below it (sensorkit.model.sdf's module doc, with the
            # lines of sdformat 9, 12 and 14). Only what it holds itself is lost.
            kept_below = [
                j.child for j in robot.child_joints.get(name, [])
                if j.child is not None and j.child not in lost_set
            ]
            if not sensors and not any(_has_body(robot.link_map[n]) for n in lost) and not kept_below:
                continue  # nothing Gazebo would simulate is lost, and sdformat says nothing
        if joint is None:
            where = f"the root link {name!r} {what}, even with the links fixed to it"
            loss = "Gazebo drops the whole robot"
        elif name in conv.uncreated:
            where = f"link {name!r} (fixed joint {joint.name!r} to 'world') {what}"
            loss = (
                "sdformat never lumps a link into 'world' and creates no link without mass, so "
                "Gazebo has no such link; the links below it are still converted"
            )
        elif joint.name in conv.preserved_joints:
            where = f"link {name!r} (fixed joint {joint.name!r} with preserveFixedJoint) {what}"
            loss = "Gazebo drops it and everything below it"
        else:
            where = f"link {name!r} (joined by {joint.type} joint {joint.name!r}) {what}"
            loss = "Gazebo drops it and everything below it"
        detail = f"{len(lost)} links: {_few(lost)}"
        if sensors:
            detail += f"; sensors: {_few(sensors)}"
        bodies = [n for n in lost if _has_body(robot.link_map[n])]
        if sensors:
            cons = Consequence(Role.OUTPUT, f"sensors {_few(sensors)}", "none of them")
        elif bodies:
            cons = Consequence(Role.GEOMETRY, f"the bodies of {_few(bodies)}", "none of them")
        elif kept_below:
            # The joints to the links below name a parent the SDF lacks (sdformat writes the
            # URDF parent's name: gazebosim/sdformat@sdf9 9ee2d4f3:src/parser_urdf.cc:3066, in CreateJoint);
            # what Gazebo then does with them sensorkit has not read.
            cons = Consequence(Role.GEOMETRY, f"joints from {name!r} to {_few(kept_below)}", UNKNOWN)
            detail += f"; the joints to {_few(kept_below)} name it as their parent"
        else:
            # Nothing Gazebo would simulate: no sensor, visual or collision. Such a link only
            # names a frame for TF (robot_state_publisher places it from the URDF), e.g. PR2's
            # l_gripper_l_finger_tip_frame, "the same as the l_finger_tip_link" (pr2_common
            # pr2_description/urdf/gripper_v0/gripper.urdf.xacro:349-352).
            cons = Consequence(Role.GEOMETRY, "no body or sensor", "no body or sensor")
            detail += "; they hold no sensor, visual or collision: only TF knows them"
        yield ctx.judged(
            "SK301",
            cons,
            f"{where}: {loss} ({detail})",
            link.source,
            link=name,
            joint=joint.name if joint else None,
            sensor=sensors[0] if sensors else None,
            fix=(
                f'give {name!r} an <inertial> with <mass value="..."/> > 0 and an <inertia> '
                "(e.g. a box: ixx = m/12 (y²+z²), iyy = m/12 (x²+z²), izz = m/12 (x²+y²))"
            ),
        )


def _has_body(link: Link) -> bool:
    """Whether Gazebo would simulate something of ``link``: a visual or a collision."""
    return any(
        isinstance(c.tag, str) and c.tag in ("visual", "collision") for c in link.element
    )


def _few(names: list[str], n: int = 8) -> str:
    return ", ".join(names[:n]) + (f" and {len(names) - n} more" if len(names) > n else "")


@rule(
    "SK302",
    "error/warning/info",
    "inertia finite, positive definite, triangle inequality (tolerance as gz-math): an error on Gazebo Sim "
    "for a link that survives fixed-joint lumping (sdformat refuses it and gz-sim refuses to spawn the "
    "robot); moments that are not positive definite or break the triangle inequality are a warning "
    "otherwise (Gazebo Classic simulates the values as written). An SDF number followed by other text "
    "is read by sdformat as the number it starts with: info when words follow (the number written is "
    "the one simulated), a warning when digits or a separator follow",
    "gz sdf -k",
    formats=("urdf", "sdf"),
)
def inertia_valid(ctx: Context) -> Iterator[Finding]:
    # SDF: the same check on every link, none lumped (sensorkit.model.sdf.convert): sdformat
    # reports "A link named X has invalid inertia." for the MassMatrix3 gz-math rejects
    # (gazebosim/sdformat@sdformat12_12.8.0:src/Link.cc:180-187), and gz-sim's server
    # stops loading a world whose SDF has errors (gazebosim/gz-sim@gz-sim8_8.9.0:
    # src/Server.cc:81-91, EXIT_IMMEDIATELY its default: src/ServerConfig.cc:299).
    # Gazebo Sim: sdformat's Link::Load reports LINK_INERTIA_INVALID when gz-math's
    # MassMatrix3 rejects the values (gazebosim/sdformat@sdf14:src/Link.cc:302-309), and
    # gz-sim's create service refuses an entity whose SDF has any error
    # (gazebosim/gz-sim@gz-sim8:src/systems/user_commands/UserCommands.cc:925-930). A link
    # a fixed joint lumps has its inertia added to its parent's first, so only a surviving
    # link is known to be refused. Gazebo Classic takes ixx..izz as written, unchecked
    # (elysia-best/gazebo-classic@upstream/11.10.2+dfsg:gazebo/physics/Inertial.cc:127-149):
    # it simulates a body no real one is, which a user would fix.
    # Links read from the same <mass> and <inertia> text share their mass object and
    # inertia dict (the reader's memo): each such combination is judged once. Keyed by
    # identity, so values that compare equal but print differently (0.0 and -0.0) stay
    # apart.
    judged: dict[tuple[int, ...], str | None] = {}
    for link in ctx.robot.links:
        inertial = link.inertial
        if inertial is None:
            continue
        for tag, text, value in inertial.lenient:
            yield _lenient_number(ctx, link.name, tag, text, value, inertial)
        if inertial.problems:
            problem = inertia_problem(inertial)
        else:
            key = (id(inertial.mass), id(inertial.inertia))
            if key in judged:
                problem = judged[key]
            else:
                problem = judged[key] = inertia_problem(inertial)
        if problem:
            refused = is_gz(ctx.target) and not ctx.conversion.is_lumped(link.name)
            # Only the moments' shape is a matter of target: no mass, a negative one or a
            # missing or unreadable moment stay errors everywhere.
            shape_only = problem.startswith(("inertia is not positive definite", "principal moments"))
            yield ctx.finding(
                "SK302",
                Severity.ERROR if refused or not shape_only else Severity.WARNING,
                f"link {link.name!r} inertial: {problem}"
                + (": sdformat reports it invalid and gz-sim refuses to spawn the robot" if refused and shape_only else ""),
                inertial.source,
                link=link.name,
                fix="compute the inertia from the link's shape and mass (box, cylinder, sphere formulas)",
            )


def _lenient_number(
    ctx: Context, link: str, key: str, text: str, value: float, inertial: Inertial
) -> Finding:
    """An SDF inertial number followed by other text: sdformat's std::stod reads the number
    and ignores the rest without a word (sensorkit.model.parse.stod_prefix, with the lines
    of sdformat 9, 12 and 14), so the value simulated is that number. Words after it (a
    pasted "Source Control") leave the number the author wrote: info, naming it. Digits or
    a separator after it ("1,5", "0.5.3") leave what was meant unclear: a warning."""
    rest = _rest(text)
    shown = f"{key} {text.strip()!r}"
    if rest[:1] in tuple("0123456789.,"):
        return ctx.finding(
            "SK302",
            Severity.WARNING,
            f"link {link!r} inertial: {shown} is not a number; sdformat reads {value:g} and "
            f"ignores {rest!r}, which may have been meant as part of it",
            inertial.source,
            link=link,
            fix=f"write the number alone, e.g. {value:g} if that is what was meant",
        )
    return ctx.judged(
        "SK302",
        Consequence(Role.GEOMETRY, value, value),
        f"link {link!r} inertial: {shown} is not a number as a whole; sdformat reads the "
        f"{value:g} it starts with and ignores {rest!r} without a word",
        inertial.source,
        link=link,
        fix=f"write {value:g} alone",
    )


def _rest(text: str) -> str:
    read = stod_prefix(text)
    return read[1] if read is not None else ""


@rule(
    "SK303",
    "error/info",
    "a sensor sits on a link that fixed-joint lumping removes and its plugin has no explicit "
    "frame: the published frame silently becomes the surviving parent link. Severity by "
    "consequence: info when the survivor coincides with the link for the sensor's data (an "
    "IMU: turned alike), an error when the data lands in another place or rotation",
)
def lumped_sensor_frame(ctx: Context) -> Iterator[Finding]:
    if is_gz(ctx.target):
        return
    from sensorkit.lint.rules.coincide import coincide_note, frame_consequence

    conv = ctx.conversion
    for sensor in ctx.robot.sensors:
        fr = ctx.frames_of(sensor)
        # Only plugins whose default frame follows lumping (gazebo_ros::SensorFrameID) move.
        if fr.link is None or fr.spec is None or not fr.spec.lumped or not fr.is_default:
            continue
        if conv.is_lumped(fr.link):
            survivor = conv.survivor(fr.link)
            c = frame_consequence(ctx.robot, sensor, fr.link, survivor)
            note = (
                coincide_note(ctx.robot, sensor, fr.link, survivor)
                if c.equal
                else ": the data lands where TF places that link, not where the sensor measures"
            )
            yield ctx.judged(
                "SK303",
                c,
                f"sensor {sensor.name!r} is on {fr.link!r}, which fixed-joint lumping merges into "
                f"{survivor!r}; with no frame_name its data is stamped {survivor!r}, not {fr.link!r}{note}",
                sensor.source,
                sensor=sensor.name,
                link=fr.link,
                frame=survivor,
                fix=f"add <frame_name>{_frame_for(ctx, sensor, fr.link)}</frame_name> to the plugin",
            )


def _frame_for(ctx: Context, sensor: Sensor, link: str) -> str:
    if sensor.is_camera:
        return (
            optical_frame_at(ctx.robot, ctx.frames_of(sensor).T_world_render)
            or f"{link}_optical_frame"
        )
    return link


@rule(
    "SK304",
    "info",
    "root link carries inertia (KDL/robot_state_publisher ignores it)",
    "kdl_parser, at run time",
)
def root_inertia(ctx: Context) -> Iterator[Finding]:
    root = ctx.robot.root()
    if root is None:
        return
    link = ctx.robot.link_map[root]
    if link.inertial is not None and link.mass > 0 and not math.isnan(link.mass):
        yield ctx.finding(
            "SK304",
            Severity.INFO,
            f"root link {root!r} has an inertial: KDL (robot_state_publisher) ignores a root inertia",
            link.inertial.source,
            link=root,
            fix=f'add a massless root: <link name="base_footprint"/> with a fixed joint to {root!r}',
        )
