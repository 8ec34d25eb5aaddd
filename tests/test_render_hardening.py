"""Issue 10, "Render bounded and honest": rays that must see every link where it is, and
a robot written on one long line.

Expected values come from the robots' numbers with plain trigonometry, and from
``wall_bot.urdf``, the small robot whose base and sensors the big ones copy.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from sensorkit.render import render_preview

HERE = Path(__file__).parent / "render_robots"
WALL_BOT = HERE / "wall_bot.urdf"
WALL_SCENE = HERE / "wall_scene.urdf"
CM = 0.01
MM = 0.001

INERTIAL = (
    '<inertial><origin xyz="{xyz}" rpy="{rpy}"/><mass value="0.1"/>'
    '<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>'
)
TILTED = INERTIAL.format(xyz="0.01 0.02 -0.01", rpy="0.1 0.2 0.3")
# a 0.3 x 0.02 x 0.3 m plate centred at world (0, -1, 0.4): its face y = -0.99 is in the
# laser's plane (the laser is at (0.1, 0, 0.4)), behind the camera
PLATE = (
    '<visual><origin xyz="0 -1.0 {z}"/><geometry><box size="0.3 0.02 0.3"/></geometry></visual>'
    '<collision><origin xyz="0 -1.0 {z}"/><geometry><box size="0.3 0.02 0.3"/></geometry></collision>'
)
REVOLUTE = '<axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/>'


def _joint(name: str, parent: str, child: str, xyz: str, kind: str = "fixed", rpy: str = "0 0 0") -> str:
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz}" rpy="{rpy}"/>{REVOLUTE if kind == "revolute" else ""}</joint>'
    )


def _wall_bot_pieces() -> tuple[str, str, str, str]:
    wall = WALL_BOT.read_text()

    def grab(pattern: str) -> str:
        found = re.search(pattern, wall, re.S)
        assert found is not None, pattern
        return found.group(0)

    blocks = "".join(re.findall(r"<gazebo reference=.*?</gazebo>", wall, re.S))
    return (
        grab(r'<link name="base_link">.*?</link>'),
        grab(r'<link name="camera_link">.*?</link>'),
        grab(r'<link name="laser_link">.*?</link>'),
        blocks,
    )


def big_robot(shape: str, links: int = 200) -> tuple[str, dict[str, float], str]:
    """wall_bot's base and sensors reached through ``links`` links, the plate on a deep one.

    ``chain``: base_link - l001 - ... , 1 mm apart, every third joint revolute; the
    sensors hang from the last link. ``fan``: base_link holds 98 twigs of two links (half
    on revolute joints), then the camera, on a revolute joint whose origin turns it by
    -0.5 rad, and the laser. Returns the URDF, joint positions that leave the sensors
    where wall_bot has them (but only if pybullet sets every joint of every body), and the
    link holding the plate.
    """
    base, cam, laser, blocks = _wall_bot_pieces()
    parts = [base]
    if shape == "chain":
        n = links - 3  # base_link and the chain; camera_link, its optical frame, laser_link
        names = ["base_link"] + [f"l{i:03d}" for i in range(1, n)]
        for i in range(1, n):
            plate = PLATE.format(z=round(0.4 - 0.001 * i, 6)) if i == n - 3 else ""
            parts.append(f'<link name="{names[i]}">{TILTED}{plate}</link>')
            kind = "revolute" if i % 3 == 0 else "fixed"
            parts.append(_joint(f"j{i:03d}", names[i - 1], names[i], "0 0 0.001", kind))
        holder, hz, cam_kind, cam_rpy = names[-1], 0.001 * (n - 1), "fixed", "0 0 0"
        # turned in the first body, turned back in the second: only right if both are set
        joints, plate_link = {"j021": 0.5, "j168": -0.5}, names[n - 3]
    else:
        twigs = (links - 4) // 2
        for i in range(1, twigs + 1):
            kind = "revolute" if i % 2 else "fixed"
            parts.append(f'<link name="f{i:03d}">{TILTED}</link>')
            parts.append(_joint(f"k{i:03d}", "base_link", f"f{i:03d}", "0 0 0.05", kind))
            plate = PLATE.format(z=0.34) if i == twigs else ""
            parts.append(f'<link name="g{i:03d}">{TILTED}{plate}</link>')
            parts.append(_joint(f"h{i:03d}", f"f{i:03d}", f"g{i:03d}", "0 0 0.01"))
        holder, hz, cam_kind, cam_rpy = "base_link", 0.0, "revolute", "0 0 -0.5"
        joints, plate_link = {"camera_joint": 0.5, "k001": 0.3}, f"g{twigs:03d}"
    parts += [
        cam,
        _joint("camera_joint", holder, "camera_link", f"0.25 0 {round(0.5 - hz, 6)}", cam_kind, cam_rpy),
        '<link name="camera_optical_frame"/>',
        _joint(
            "camera_optical_joint", "camera_link", "camera_optical_frame", "0 0 0",
            rpy="-1.5707963267948966 0 -1.5707963267948966",
        ),
        laser,
        _joint("laser_joint", holder, "laser_link", f"0.1 0 {round(0.4 - hz, 6)}"),
        blocks,
    ]
    text = f'<?xml version="1.0"?>\n<robot name="big_{shape}">\n' + "\n".join(parts) + "\n</robot>\n"
    assert text.count("<link ") == links
    return text, joints, plate_link


def laser_angles() -> np.ndarray:
    return -3.14159 + np.arange(360) * (2 * 3.14159 / 359)  # wall_bot's scan


def plate_beams(margin: float = 0.02) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Beams of the laser at (0.1, 0, 0.4) that meet the plate's face y = -0.99 within
    |x| <= 0.15 - margin, their exact ranges, and the beams that miss it by > margin."""
    a = laser_angles()
    with np.errstate(divide="ignore"):
        t = np.where(np.sin(a) < 0, 0.99 / -np.sin(a), np.inf)
    x = 0.1 + t * np.cos(a)
    on = np.isfinite(t) & (np.abs(x) <= 0.15 - margin)
    off = ~np.isfinite(t) | (np.abs(x) >= 0.15 + margin)
    return on, t, off


# ---- rays see links whose inertial frame is turned ---------------------------------------
@pytest.mark.parametrize("rpy", ["0 0 0", "0.1 0.2 0.3"])
def test_lidar_sees_a_link_whose_inertial_frame_is_turned(rpy: str, tmp_path: Path) -> None:
    # pybullet 3.2.7 left such a link's broadphase box stale: every beam passed through it.
    shield = (
        f'<link name="shield">{INERTIAL.format(xyz="0 0 0", rpy=rpy)}{PLATE.format(z=0.4)}</link>'
        + _joint("shield_joint", "base_link", "shield", "0 0 0")
    )
    robot = tmp_path / "r.urdf"
    robot.write_text(WALL_BOT.read_text().replace("</robot>", shield + "</robot>"))
    result = render_preview(robot, tmp_path / "out", scene=WALL_SCENE, sensors=("laser",))
    ranges = np.load(tmp_path / "out" / "laser" / "ranges.npy")
    on, exact, _ = plate_beams()
    assert np.abs(ranges[on] - exact[on]).max() < CM
    assert math.isclose(float(ranges[on].min()), 0.99, abs_tol=CM)
    assert result.sensors[0].status == "warn"  # the shield shadows the laser


# ---- a URDF on one long line ---------------------------------------------------------------
@pytest.mark.parametrize("one_line", [False, True])
def test_a_robot_written_on_one_line_renders(one_line: bool, tmp_path: Path) -> None:
    # pybullet cuts lines after 8191 bytes (BulletUrdfImporter.cpp:165-172), which broke
    # a name in two: "Cannot load URDF file". 120 links on one line are about 40 kB.
    text, _, _ = big_robot("chain", links=120)
    if one_line:
        text = re.sub(r">\s+<", "><", text)
        assert text.count("\n") <= 2 and len(text) > 8191
    robot = tmp_path / "r.urdf"
    robot.write_text(text)
    result = render_preview(robot, tmp_path / "out", scene=WALL_SCENE, sensors=("laser",))
    assert result.sensors[0].checks[0].status == "ok"
    ranges = np.load(tmp_path / "out" / "laser" / "ranges.npy")
    on, exact, _ = plate_beams()
    assert np.abs(ranges[on] - exact[on]).max() < CM
