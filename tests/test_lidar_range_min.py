"""Issue 23, false class 3: lidar <range><min> 0, per sensor type and simulator.

Each case cites the lines it pins; the sources are gathered beside the data in
sensorkit/knowledge/gazebo_sim.py (GZ_LIDAR_NEAR_CLIP_TYPES) and
sensorkit/knowledge/gazebo_ros.py (CLASSIC_LIDAR_NEAR_CLIP_TYPES).
"""

from __future__ import annotations

from builders import gz_robot, lidar_sensor, robot

from sensorkit.base.findings import Severity


def _sk406(report: object) -> list[tuple[Severity, str]]:
    return [(f.severity, f.message) for f in report.findings if f.rule == "SK406"]  # type: ignore[attr-defined]


def _gz(rmin: str, stype: str = "gpu_lidar", tag: str = "lidar") -> str:
    block = "<lidar><scan>" if tag == "lidar" else "<ray><scan>"
    text = gz_robot(lidar_tags="<topic>scan</topic><gz_frame_id>laser_link</gz_frame_id>")
    text = text.replace('type="gpu_lidar"', f'type="{stype}"').replace("<range><min>0.12</min>", f"<range><min>{rmin}</min>")
    if tag != "lidar":
        text = text.replace("<lidar><scan>", block).replace("</range></lidar>", "</range></ray>")
    return text


def test_classic_cpu_ray_min_zero_is_legal(check) -> None:
    # The SDF default is 0 (gazebosim/sdformat@sdf12 b9417e5:sdf/1.6/ray.sdf:50,
    # `<element name="min" type="double" default="0" required="1">`), and Classic's
    # MultiRayShape::Init only starts each ray at `axis * minRange` (gazebosim/gazebo-classic
    # gazebo/physics/MultiRayShape.cc as stored at a9bef0c; gazebo11 itself not fetched).
    for target in ("classic", "ros1"):
        assert _sk406(check(robot(lidar=lidar_sensor(rmin="0")), target=target)) == []
    # Near miss: a negative min, or min >= max, is still an error.
    for rmin, rmax in (("-0.1", "12"), ("12", "12")):
        found = _sk406(check(robot(lidar=lidar_sensor(rmin=rmin, rmax=rmax)), target="classic"))
        assert [sev for sev, _ in found] == [Severity.ERROR]


def test_classic_gpu_ray_min_zero_is_only_info(check) -> None:
    # Classic's GpuRaySensor makes min the GPU laser camera's near clip; Ogre throws on a near
    # clip <= 0, but that was not verified on gazebo11, so it is info, not an error.
    text = robot(lidar=lidar_sensor(stype="gpu_ray", rmin="0", plugin="libgazebo_ros_ray_sensor.so"))
    found = _sk406(check(text, target="classic"))
    assert [sev for sev, _ in found] == [Severity.INFO]
    assert "not verified" in found[0][1]
    # Near miss: a positive min says nothing.
    text = robot(lidar=lidar_sensor(stype="gpu_ray", rmin="0.05", plugin="libgazebo_ros_ray_sensor.so"))
    assert _sk406(check(text, target="classic")) == []


def test_gz_gpu_lidar_min_zero_is_an_error(check) -> None:
    # gz-sensors passes min as the near clip (gazebosim/gz-sensors@ign-sensors6 7cfaddf:
    # src/GpuLidarSensor.cc:200, @gz-sensors8 c8159af:198, @gz-sensors10 ff8c92b:193);
    # gz-rendering scales it to nearClipCube = min / sqrt(3) (gazebosim/gz-rendering@gz-rendering8
    # ff0c5b8:ogre2/src/Ogre2GpuRays.cc:1181-1182) and sets it on Ogre cameras (:783, :1048);
    # ogre-next throws for nearPlane <= 0 (ignition-forks/ogre-next@7449a36 and @40dcea7:
    # OgreMain/src/OgreFrustum.cpp:145-149), in gz-sim's render thread with no catch
    # (gazebosim/gz-sim@gz-sim8 b81e26d:src/systems/sensors/Sensors.cc:469, :528-559): the
    # whole server aborts (issue 35 item 8).
    for target in ("fortress", "harmonic"):
        found = _sk406(check(_gz("0"), target=target))
        assert [sev for sev, _ in found] == [Severity.ERROR], target
        assert "near clip" in found[0][1]
        assert "whole `gz sim` server aborts" in found[0][1]
        # Near miss: a small positive min.
        assert _sk406(check(_gz("0.05"), target=target)) == []
    # sdformat reads type "gpu_ray" as GPU_LIDAR too (gazebosim/sdformat@sdf14 8512585:
    # src/Sensor.cc:352-354), with a <ray> block.
    found = _sk406(check(_gz("0", stype="gpu_ray", tag="ray"), target="harmonic"))
    assert [sev for sev, _ in found] == [Severity.ERROR]


def test_jetty_keeps_a_near_clip_of_one_centimetre(check) -> None:
    # Changed on purpose (issue 35 item 8): Jetty was an error like Harmonic. gz-rendering10's
    # BaseCamera::SetNearClipPlane refuses a near clip <= 0 and keeps 0.01 m
    # (gazebosim/gz-rendering@gz-rendering10 af28689:include/gz/rendering/base/BaseCamera.hh:
    # 731-740, :227; gazebosim/gz-rendering#1082): the lidar works, blind under 1 cm (a limit:
    # warning).
    found = _sk406(check(_gz("0"), target="jetty"))
    assert [sev for sev, _ in found] == [Severity.WARNING]
    assert "keeps 0.01 m" in found[0][1] and "aborts" not in found[0][1]
    # Near miss: a small positive min says nothing on Jetty either.
    assert _sk406(check(_gz("0.05"), target="jetty")) == []


def test_gz_gpu_lidar_without_min_is_min_zero(check) -> None:
    # <min> is required with default 0 (gazebosim/sdformat@sdf12 b9417e5:sdf/1.9/lidar.sdf:50)
    # and sdformat's parser adds it when missing (@sdf12:src/parser.cc:1903-1925): the same
    # near clip 0 as a written 0.
    text = _gz("0").replace("<min>0</min>", "")
    assert "<range><max>" in text
    for target, sev in (("fortress", Severity.ERROR), ("harmonic", Severity.ERROR), ("jetty", Severity.WARNING)):
        found = _sk406(check(text, target=target))
        assert [s for s, _ in found] == [sev], target
        assert "not written" in found[0][1]
    # Near miss: a written positive min.
    assert _sk406(check(_gz("0.05"), target="harmonic")) == []


def test_gz_cpu_lidar_min_zero_is_not_an_sk406_error(check) -> None:
    # The CPU Lidar base class only clamps with min (gz-sensors@gz-sensors8:src/Lidar.cc:523);
    # gz-sim never creates a CPU lidar (sensorkit/knowledge/gazebo_sim.py), another rule's concern.
    assert _sk406(check(_gz("0", stype="lidar"), target="harmonic")) == []
