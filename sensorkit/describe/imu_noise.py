"""A simulated IMU's noise as visual-inertial estimators take it: continuous-time densities.

Both simulators add to each sample of each axis white noise drawn with the SDF
``<noise><stddev>`` (a per-sample standard deviation) plus a bias
(gazebosim/gazebo-classic@gazebo/sensors/GaussianNoiseModel.cc ``GaussianNoiseModel::ApplyImpl``;
gazebosim/gz-sensors@gz-sensors8:src/GaussianNoiseModel.cc:111-141). Estimators take
densities instead: ORB-SLAM3 multiplies ``IMU.NoiseGyro``/``NoiseAcc`` by the square root of
``IMU.Frequency`` to get the per-sample value and divides the walks by it
(UZ-SLAMLab/ORB_SLAM3@src/Tracking.cc:613-614), as Kalibr's ``imu.yaml`` does
(ethz-asl/kalibr@aslam_offline_calibration/kalibr/python/kalibr_common/ConfigReader.py:473).
So a density is ``stddev / sqrt(rate)``.

The bias: Gazebo Classic samples it once and keeps it (``GaussianNoiseModel::SampleBias``),
so it never walks. gz-sensors also drives it with ``<dynamic_bias_stddev>`` sigma_b and
``<dynamic_bias_correlation_time>`` tau: each step adds N(0, sigma_b sqrt(tau/2 (1 -
exp(-2 dt/tau)))) (gz-sensors8:src/GaussianNoiseModel.cc:128-139), which is sigma_b sqrt(dt)
for dt much shorter than tau: sigma_b is a random-walk density.

Where the robot says nothing usable, the values of ORB-SLAM3's EuRoC stereo-inertial
example stand in (UZ-SLAMLab/ORB_SLAM3@Examples/Stereo-Inertial/EuRoC.yaml:74-77), each with
a note: a noise-free simulated IMU would otherwise give zero noise, whose inverse
ORB-SLAM3 takes as the measurements' weight.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from sensorkit.model.parse import child, parse_float, text_of
from sensorkit.model.targets import is_gz

if TYPE_CHECKING:
    from lxml import etree

    from sensorkit.model.sensors import Sensor

__all__ = ["DEFAULT_IMU_RATE", "EUROC_NOISE", "ImuNoise", "imu_noise"]

DEFAULT_IMU_RATE = 1000.0
"""Hz assumed for an IMU without a positive ``<update_rate>``: it then samples on every
physics step, 1 ms by default (sdformat ``<physics><max_step_size>`` 0.001)."""


@dataclass(frozen=True)
class ImuNoise:
    """An IMU's rate and noise densities (units per sqrt(Hz))."""

    rate: float  # Hz
    gyro_noise_density: float  # rad/s/sqrt(Hz)
    accel_noise_density: float  # m/s^2/sqrt(Hz)
    gyro_random_walk: float  # rad/s^2/sqrt(Hz)
    accel_random_walk: float  # m/s^3/sqrt(Hz)


EUROC_NOISE = ImuNoise(
    rate=200.0,
    gyro_noise_density=1.7e-04,
    accel_noise_density=2.0e-03,
    gyro_random_walk=1.9393e-05,
    accel_random_walk=3.0e-03,
)
"""ORB-SLAM3's EuRoC stereo-inertial values (Examples/Stereo-Inertial/EuRoC.yaml:74-78)."""

_AXES = ("x", "y", "z")
_GAUSSIAN = frozenset({"gaussian", "gaussian_quantized"})


def _number(el: etree._Element | None, name: str) -> float | None:
    text = text_of(el, name)
    if text is None:
        return None
    value, why = parse_float(text)
    return None if why or value is None else value


def _axes(imu: etree._Element | None, block: str) -> list[etree._Element]:
    """The gaussian ``<noise>`` elements of ``<imu><block><x|y|z>``."""
    out = []
    for axis in _AXES:
        noise = child(child(child(imu, block), axis), "noise")
        if noise is None:
            continue
        kind = (noise.get("type") or text_of(noise, "type") or "").strip().lower()
        if kind in _GAUSSIAN:
            out.append(noise)
    return out


def imu_noise(sensor: Sensor, target: str) -> tuple[ImuNoise, list[str]]:
    """The densities of ``sensor``'s ``<imu>`` noise under ``target``, and notes for every
    value that had to be assumed."""
    notes: list[str] = []
    rate = sensor.update_rate if sensor.update_rate and sensor.update_rate > 0 else None
    if rate is None:
        rate = DEFAULT_IMU_RATE
        notes.append(
            f"no positive <update_rate>: {rate:g} Hz assumed (an IMU without one samples on "
            "every physics step, 1 ms by default)"
        )
    imu = child(sensor.element, "imu")
    if child(imu, "noise") is not None:
        notes.append("the SDF 1.4 <imu><noise> form is not read: give per-axis noise instead")
    values: dict[str, float] = {}
    for block, what, density, walk, euroc_density, euroc_walk in (
        (
            "angular_velocity",
            "gyro",
            "gyro_noise_density",
            "gyro_random_walk",
            EUROC_NOISE.gyro_noise_density,
            EUROC_NOISE.gyro_random_walk,
        ),
        (
            "linear_acceleration",
            "accelerometer",
            "accel_noise_density",
            "accel_random_walk",
            EUROC_NOISE.accel_noise_density,
            EUROC_NOISE.accel_random_walk,
        ),
    ):
        noises = _axes(imu, block)
        stddevs = [v for n in noises if (v := _number(n, "stddev")) is not None and v > 0]
        if stddevs:
            values[density] = max(stddevs) / math.sqrt(rate)
        else:
            values[density] = euroc_density
            notes.append(
                f"no {what} noise (<imu><{block}> has no positive gaussian <stddev>): "
                f"{euroc_density:g}, ORB-SLAM3's EuRoC value"
            )
        walks = [
            sigma
            for n in noises
            if (sigma := _number(n, "dynamic_bias_stddev")) is not None
            and sigma > 0
            and (_number(n, "dynamic_bias_correlation_time") or 0.0) > 0
        ]
        if walks and is_gz(target):
            values[walk] = max(walks)
        else:
            why = (
                "Gazebo Classic keeps the bias constant and ignores <dynamic_bias_stddev>"
                if walks
                else "no <dynamic_bias_stddev> with a <dynamic_bias_correlation_time>: the "
                "simulated bias does not walk"
            )
            values[walk] = euroc_walk
            notes.append(f"{what} random walk {euroc_walk:g}, ORB-SLAM3's EuRoC value ({why})")
    return ImuNoise(rate=rate, **values), notes
