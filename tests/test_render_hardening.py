"""Issue 10, "Render bounded and honest": rays that must see every link where it is.

Expected values come from the robots' numbers with plain trigonometry.
"""

from __future__ import annotations

import math
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


