"""The describe layer: what a robot publishes, computed from the model.

Per sensor, its camera_info, LaserScan geometry, frames and topics (:mod:`.sensorinfo`),
the topics of a whole robot (:mod:`.topics`), the pinhole and scan maths the simulators
use (:mod:`.intrinsics`), stereo pairs (:mod:`.stereo`) and IMU noise densities
(:mod:`.imu_noise`).
"""
