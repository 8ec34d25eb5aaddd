"""Rendering: the robot in pybullet, seen through its own sensors.

This package is the only place in sensorkit that imports pybullet, and only
``sensorkit.render.sim`` does, when a preview runs; importing ``sensorkit.render``
itself stays light.

Modules: ``preview`` (``render_preview``, the entry point, step by step), ``admission``
(what is refused before pybullet starts), ``plan`` (the jobs), ``workers`` (running them,
here or in forked processes), ``session`` (what the jobs share), ``camera_job`` /
``lidar_job`` / ``imu_job`` (one sensor each: render, write, check, draw), ``assemble``
(validate, the overview, the files), ``sim`` (pybullet), ``camera`` and ``lidar``
(sensor geometry and checks), ``scene`` (shapes with exact geometry), ``poses``
(kinematics at given joints), ``urdf_out`` (the URDF pybullet loads), ``overview`` /
``raster`` / ``png`` (pictures; PNG files through Pillow, imported when a picture is
written or read), ``overview_figure`` (the overview's ticks, frame names and colour key),
``svg`` (the labelled figures' SVG), ``pictures``
(depth and scans, labelled; the side view), ``mount_pictures`` (IMU axes, the robot
close up, stereo pairs), ``result`` (what a preview gives back), ``report``
(summary.json, index.html).
"""

from __future__ import annotations

from sensorkit.render.preview import render_preview
from sensorkit.render.result import PreviewResult, SensorPreview

__all__ = ["PreviewResult", "SensorPreview", "render_preview"]
