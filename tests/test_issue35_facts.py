"""Issue 35 item 8: facts about the simulators found wrong, each pinned to its source.

- <optical_frame_id> is read from <camera> only (gazebosim/sdformat@sdf12 b9417e5:
  src/Camera.cc:383-388; @sdf14 8512585: :385-390), so one written directly under <sensor>
  is lost (SK410), where before it was taken as read anyway.
- A gz lidar's vertical rows are at least 1 (gazebosim/gz-sensors@ign-sensors6 7cfaddf:
  src/Lidar.cc:378-386; @gz-sensors8 c8159af: :389-397), while the GPU rays render <samples>
  rows (gz-sensors8 src/GpuLidarSensor.cc:212-214). A vertical <samples> of 0 is not saved by
  that clamp: "Lidar: Image has 0 size!" (src/Lidar.cc:145-148), 0 rows rendered, a scan of
  no ranges written one row into (:272-296).
"""

from __future__ import annotations

from collections.abc import Callable

from builders import gz_robot

from sensorkit.base.findings import Severity


def _of(report, rule: str):  # type: ignore[no-untyped-def]
    return [f for f in report.findings if f.rule == rule]


OPTICAL = "<optical_frame_id>camera_optical_frame</optical_frame_id>"


def test_optical_frame_id_under_sensor_is_lost(check: Callable) -> None:
    text = gz_robot(camera_tags=f"<topic>front_camera/image_raw</topic>{OPTICAL}")
    for target in ("fortress", "harmonic"):
        found = _of(check(text, target=target), "SK410")
        assert [f.severity for f in found] == [Severity.ERROR], target
        assert "<optical_frame_id>" in found[0].message and "camera.sdf" in found[0].message
    # Near miss: inside <camera>, where sdformat reads it.
    near = gz_robot(camera_tags="<topic>front_camera/image_raw</topic>").replace(
        "</clip></camera>", f"</clip>{OPTICAL}</camera>"
    )
    assert OPTICAL in near
    assert not _of(check(near, target="harmonic"), "SK410")


def _vertical(samples: str, resolution: str, lo: str = "0", hi: str = "0") -> str:
    vertical = (
        f"<vertical><samples>{samples}</samples><resolution>{resolution}</resolution>"
        f"<min_angle>{lo}</min_angle><max_angle>{hi}</max_angle></vertical>"
    )
    return gz_robot().replace("</horizontal></scan>", f"</horizontal>{vertical}</scan>")


def _sk406(check: Callable, text: str, target: str = "harmonic") -> list[tuple[Severity, str]]:
    return [(f.severity, f.message) for f in _of(check(text, target=target), "SK406")]


def test_gz_vertical_rows_are_at_least_one(check: Callable) -> None:
    # One vertical sample at resolution 0.5: 0.5 rows, clamped to the one row cast: info.
    found = _sk406(check, _vertical("1", "0.5"))
    assert [s for s, _ in found] == [Severity.INFO]
    assert "publishes 1, at least one row" in found[0][1]
    # Near miss, Gazebo Classic has no such clamp (a warning, it publishes 0 rows).
    from builders import lidar_sensor, robot

    vertical = "<vertical><samples>1</samples><resolution>0.5</resolution><min_angle>0</min_angle><max_angle>0</max_angle></vertical>"
    found = _sk406(check, robot(lidar=lidar_sensor(vertical=vertical)), "classic")
    assert [s for s, _ in found] == [Severity.WARNING] and "publishes 0" in found[0][1]
    # Near miss: two samples at 0.5 make one row from two cast: still a warning on gz.
    found = _sk406(check, _vertical("2", "0.25", "-0.1", "0.1"))
    assert [s for s, _ in found] == [Severity.WARNING]
    # A whole count says nothing.
    assert _sk406(check, _vertical("1", "1")) == []


def test_gz_vertical_samples_zero_stays_an_error(check: Callable) -> None:
    found = _sk406(check, _vertical("0", "1"))
    assert [s for s, _ in found] == [Severity.ERROR]
    assert "vertical samples 0 < 1" in found[0][1]
