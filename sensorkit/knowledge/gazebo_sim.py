"""Gazebo Sim (Fortress, Harmonic, Jetty) facts consulted by rules, bridge generation and auto.

Sensor types that sdformat parses but gz-sim never creates, with what to use instead:

- ``ray`` and ``lidar`` parse as ``SensorType::LIDAR`` (gazebosim/sdformat@sdf14:
  src/Sensor.cc:383-390); gz-sim creates no CPU lidar: "Sensor type LIDAR not supported yet.
  Try using a GPU LIDAR instead." (gazebosim/gz-sim@gz-sim8:src/SdfEntityCreator.cc:1092-1098;
  @ign-gazebo6:src/SdfEntityCreator.cc:917; @gz-sim10:src/SdfEntityCreator.cc:1131).
- ``multicamera`` parses as ``SensorType::MULTICAMERA`` (sdformat@sdf14:src/Sensor.cc:379-382)
  and has no branch in SdfEntityCreator: "Sensor type [...] not supported yet."
  (gz-sim@gz-sim8:src/SdfEntityCreator.cc:1227-1229; @ign-gazebo6:1031; @gz-sim10:1263).

Such a sensor publishes nothing on any Gazebo Sim version, so it is never bridged and never
counted as evidence that a description targets Gazebo Sim.
"""

from __future__ import annotations

GZ_UNSUPPORTED_SENSOR_TYPES: dict[str, str] = {
    "ray": 'type="gpu_lidar" with a <lidar> block',
    "lidar": 'type="gpu_lidar" (the CPU lidar is not implemented)',
    "multicamera": 'one <sensor type="camera"> per eye, each with its own <topic>',
}
