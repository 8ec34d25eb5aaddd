"""Checks computed on every preview, as data: a name, a status, a measured value.

Statuses: ``ok``; ``warn`` (works, but something will bite); ``fail`` (the preview
disagrees with what sensorkit predicts); ``skipped`` (nothing to measure, with why).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from sensorkit.model.transforms_np import Mat, angle_between

__all__ = [
    "STATUS_ORDER",
    "Check",
    "frame_check",
    "pose_check",
    "self_occlusion_check",
    "worst",
]

STATUS_ORDER = {"skipped": 0, "ok": 1, "warn": 2, "fail": 3}
SELF_OCCLUSION_LIMIT = 0.01  # share of pixels or beams


@dataclass
class Check:
    name: str
    status: str
    message: str
    value: float | None = None
    unit: str = ""
    limit: float | None = None
    details: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "status": self.status,
            "value": _json_number(self.value),
            "unit": self.unit,
            "limit": _json_number(self.limit),
            "message": self.message,
            "details": self.details,
        }


def _json_number(value: float | None) -> float | None:
    if value is None or not math.isfinite(value):
        return None
    return float(value)


def worst(checks: list[Check]) -> str:
    """The most severe status among ``checks`` (``skipped`` when empty)."""
    return max((c.status for c in checks), key=STATUS_ORDER.__getitem__, default="skipped")


def self_occlusion_check(
    hit_body: npt.NDArray[np.int32],
    hit_link: npt.NDArray[np.int32],
    robot_links: Mapping[tuple[int, int], str],
    what: str,
) -> Check:
    """Share of pixels or beams that land on the robot itself (warned above 1 %).

    ``robot_links`` names the robot's (body, link index) pairs: a robot over pybullet's
    link limit is loaded as several bodies.
    """
    total = int(hit_body.size)
    bodies = sorted({body for body, _ in robot_links})
    if not bodies or total == 0:
        return Check("self_occlusion", "skipped", "no robot body to hit")
    mine = np.isin(hit_body, bodies)
    share = float(mine.sum()) / total
    links: dict[str, float] = {}
    if mine.any():
        pairs, counts = np.unique(
            np.stack([hit_body[mine], hit_link[mine]], axis=1), axis=0, return_counts=True
        )
        order = np.argsort(-counts, kind="stable")
        for i in order[:5]:
            key = (int(pairs[i][0]), int(pairs[i][1]))
            name = robot_links.get(key, f"{key[0]}:{key[1]}")
            links[name] = round(links.get(name, 0.0) + float(counts[i]) / total, 6)
    status = "warn" if share > SELF_OCCLUSION_LIMIT else "ok"
    if mine.any():
        named = ", ".join(f"{k} {v:.1%}" for k, v in links.items())
        message = f"{share:.1%} of the {what} hit the robot itself ({named})"
    else:
        message = f"no {what} hit the robot itself"
    return Check(
        "self_occlusion",
        status,
        message,
        share * 100.0,
        "%",
        SELF_OCCLUSION_LIMIT * 100.0,
        {"links": links},
    )


def pose_check(T_expected: Mat, T_pybullet: Mat, link: str) -> Check:
    """sensorkit's forward kinematics against pybullet's for the sensor's link."""
    offset = float(np.linalg.norm(T_expected[:3, 3] - T_pybullet[:3, 3]))
    angle = math.degrees(angle_between(T_expected[:3, :3], T_pybullet[:3, :3]))
    ok = offset <= 1e-3 and angle <= 0.05
    message = (
        f"link {link!r} is where sensorkit computes it in pybullet (off by {offset * 1000:.3f} mm, {angle:.4f} deg)"
        if ok
        else f"pybullet places link {link!r} {offset * 1000:.1f} mm and {angle:.2f} deg away from sensorkit's kinematics"
    )
    return Check(
        "render_pose", "ok" if ok else "fail", message, offset, "m", 1e-3, {"angle_deg": angle}
    )


def frame_check(
    T_world_true: Mat,
    T_world_frame: Mat | None,
    frame: str | None,
    how: str,
    *,
    optical: bool,
    sdf: bool = False,
) -> Check:
    """Does the frame the data is stamped with point where the sensor really looks?

    ``T_world_true`` is the frame a consumer should see: the optical frame of the render
    pose for images (z forward, x right, y down), the render pose itself for scans. For an
    SDF model (``sdf``) a frame it does not hold may come from a URDF kept beside it, which
    sensorkit does not see (as SK501 says): not known, so skipped.
    """
    if frame is None:
        return Check(
            "published_frame", "skipped", "the sensor publishes nothing to ROS (no plugin found)"
        )
    if T_world_frame is None and sdf:
        return Check(
            "published_frame",
            "skipped",
            f"the data is stamped {frame!r} ({how}), which is no frame of this SDF model: TF "
            "may have it from a URDF beside the SDF, which sensorkit does not see",
            details={"frame": frame, "how": how},
        )
    if T_world_frame is None:
        return Check(
            "published_frame",
            "warn",
            f"the data is stamped {frame!r} ({how}), which is not a link of the URDF: TF cannot place it",
            details={"frame": frame, "how": how},
        )
    offset = float(np.linalg.norm(T_world_frame[:3, 3] - T_world_true[:3, 3]))
    angle = math.degrees(angle_between(T_world_true[:3, :3], T_world_frame[:3, :3]))
    convention = "optical (z forward, x right, y down)" if optical else "x forward, z up"
    details = {"frame": frame, "how": how, "angle_deg": angle, "offset_m": offset}
    if angle <= 0.5 and offset <= 0.01:
        return Check(
            "published_frame",
            "ok",
            f"{frame!r} matches the sensor's {convention} axes",
            angle,
            "deg",
            0.5,
            details,
        )
    axis = 2 if optical else 0
    seen = T_world_frame[:3, axis]
    true = T_world_true[:3, axis]
    message = (
        f"data stamped {frame!r} will appear turned by {angle:.1f} deg"
        + (f" and moved by {offset:.3f} m" if offset > 0.01 else "")
        + f" from where the sensor looks: consumers read that frame as {convention}; its forward axis points "
        + f"({seen[0]:+.2f}, {seen[1]:+.2f}, {seen[2]:+.2f}) instead of ({true[0]:+.2f}, {true[1]:+.2f}, {true[2]:+.2f})"
    )
    return Check("published_frame", "warn", message, angle, "deg", 0.5, details)
