"""The IMUs of a preview: nothing to render, but where they measure is worth a look.

``draw_imus`` gives each IMU's record the frame checks every sensor gets (its link where
pybullet puts it, the frame its data is stamped with) and a picture of its axes
(``sensorkit.render.mount_pictures.imu_figure``), after the cameras and lidars are done.
"""

from __future__ import annotations

from sensorkit.render.result import SensorPreview
from sensorkit.render.session import Session, topics_of

__all__ = ["draw_imus"]


def draw_imus(run: Session, previews: list[SensorPreview]) -> None:
    """Give each IMU (nothing to render) its frame checks and a picture of its axes."""
    from sensorkit.render.mount_pictures import imu_figure

    for k, p in enumerate(previews):
        sensor = next(
            (x for x in run.robot.sensors if x.name == p.sensor and x.kind == "imu"), None
        )
        if p.kind != "imu" or sensor is None:
            continue
        T_render = run.T_world_render(sensor)
        if T_render is None:
            continue
        imu = SensorPreview(p.name, p.sensor, p.type, p.kind, p.link)
        frames = run.frames(sensor)
        imu.info["frames"] = run.frame_info(frames, T_render)
        imu.info["topics"] = topics_of(sensor, run.target)
        fcheck, stamped = run.placement_checks(
            imu, sensor, T_render, frames.published, frames.how, optical=False
        )
        R_stamped = stamped[1][:3, :3] if stamped is not None else None
        figure = imu_figure(
            T_render[:3, :3], R_stamped, frames.published, fcheck.status, fcheck.message
        )
        imu.add_figure(figure)
        previews[k] = imu
