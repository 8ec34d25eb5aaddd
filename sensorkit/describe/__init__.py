"""The describe layer: what a robot publishes, computed from the model.

Per sensor, the camera_info, depth range and LaserScan geometry a simulator publishes
(:mod:`.published`), its topics by role (:mod:`.sensor_topics`), gathered with its frames
for every sensor of a robot (:mod:`.sensorinfo`, records in :mod:`.views`); the topics of
a whole robot (:mod:`.topics`) and the ros_gz_bridge entries that carry them
(:mod:`.bridge`), the pinhole and scan maths the simulators use (:mod:`.intrinsics`),
stereo pairs (:mod:`.stereo`) and IMU noise densities (:mod:`.imu_noise`).
"""
