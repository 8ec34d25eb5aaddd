"""The content of recorded sensor messages against the description: SK806-SK810.

Each check takes a topic's :class:`~sensorkit.recording.bag.TopicSample` and what the
description predicts for it (:class:`~sensorkit.recording.expect.Expected`) and returns
findings. The tolerances are stated in the rule titles and here:

- CameraInfo (SK806): K and P compared by how far they move the image: a focal length
  error of ``d`` moves the image edge by ``d * (W/2) / f`` px, a principal point error of
  ``d`` by ``d`` px. Over 1 px (SK409's threshold for a wrong calibration): error; over
  0.01 px: warning. D's coefficients differ by more than 1e-6, or the size: error. P's
  baseline term ``-fx * B`` differs by more than 1 mm of baseline: error.
- LaserScan (SK808): angles within 1e-5 rad and ranges within 1e-5 relative (the message
  holds float32), beam count exactly.
- Rate (SK810): the mean rate of the sampled header stamps within 10 % of
  ``<update_rate>`` (a simulator steps sensors on its physics clock, so 30 Hz on 1 ms steps
  is 30.3 Hz; half the rate is far outside).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from sensorkit.base.findings import Finding, Severity
from sensorkit.knowledge.messages import POINT_CLOUD_FIELDS, POINT_CLOUD_XYZ

if TYPE_CHECKING:
    from sensorkit.describe.intrinsics import Intrinsics
    from sensorkit.recording.bag import TopicSample
    from sensorkit.recording.expect import Expected

__all__ = [
    "RATE_TOLERANCE",
    "check_camera_info",
    "check_cloud",
    "check_image",
    "check_rate",
    "check_scan",
    "finding",
]

PX_ERROR = 1.0  # px the image edge or principal point may move before K/P is wrong
PX_TOLERANCE = 0.01  # px below which K/P agree
D_TOLERANCE = 1e-6
BASELINE_TOLERANCE = 1e-3  # m
ANGLE_TOLERANCE = 1e-5  # rad
RANGE_TOLERANCE = 1e-5  # relative
RATE_TOLERANCE = 0.10  # relative
MIN_STAMPS = 3  # fewer stamps measure no rate


def finding(
    rule: str,
    severity: Severity,
    message: str,
    exp: Expected,
    *,
    fix: str | None = None,
    frame: str | None = None,
) -> Finding:
    """A finding about ``exp``'s sensor, pointing at the sensor in the description."""
    s = exp.sensor
    return Finding(
        rule,
        severity,
        message,
        s.sensor.source,
        link=s.link,
        sensor=s.name,
        frame=frame,
        fix=fix,
    )


def _array(msg: Any, name: str) -> list[float]:
    """A CameraInfo array by its ROS 2 name (``d``, ``k``, ...) or its ROS 1 one (``D``)."""
    value = getattr(msg, name, None)
    if value is None:
        value = getattr(msg, name.upper(), None)
    return [float(v) for v in (value if value is not None else ())]


def _shift(have: Sequence[float], want: Sequence[float], size: tuple[int, int]) -> float:
    """How far (px) ``have`` moves the image against ``want``: the image edge for the
    focal lengths (3x3 or 3x4 row-major: [0] fx, [4 or 5] fy), the principal point."""
    w, h = size
    step = 4 if len(want) == 12 else 3
    fx, cx, fy, cy = 0, 2, step + 1, step + 2
    out = 0.0
    for i, half in ((fx, w / 2.0), (fy, h / 2.0)):
        if want[i]:
            out = max(out, abs(have[i] - want[i]) * half / abs(want[i]))
    for i in (cx, cy):
        out = max(out, abs(have[i] - want[i]))
    for i, value in enumerate(want):  # the other entries: zeros and ones, exactly
        other = i not in (fx, cx, fy, cy) and (step == 3 or i not in (3, 7))
        if other and abs(have[i] - value) > D_TOLERANCE:
            return math.inf
    return out


def _fmt(values: Sequence[float]) -> str:
    return "[" + ", ".join(f"{v + 0.0:.6g}" for v in values) + "]"


def check_camera_info(sample: TopicSample, exp: Expected, intr: Intrinsics) -> list[Finding]:
    """SK806: the first recorded CameraInfo against ``intr`` (``sensorkit intrinsics``)."""
    if not sample.messages:
        return []
    msg = sample.messages[0]
    out: list[Finding] = []
    topic = exp.name
    fix = "record what the simulator publishes for this description, or correct the description"
    size = (int(msg.width), int(msg.height))
    if size != (intr.width, intr.height):
        out.append(
            finding(
                "SK806",
                Severity.ERROR,
                f"{topic}: camera_info is {size[0]}x{size[1]}, the camera is "
                f"{intr.width}x{intr.height}",
                exp,
                fix=fix,
            )
        )
        return out  # K and P of another size are not comparable
    K, P = _array(msg, "k"), _array(msg, "p")
    want_K = [float(v) for v in intr.K.flatten()]
    want_P = [float(v) for v in intr.P.flatten()]
    # Both simulators publish no skew in K or P, whatever the image is rendered with
    # (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:
    # 427-428, :455-456; gazebosim/gz-sensors@gz-sensors8 c8159af:src/CameraSensor.cc:729-730,
    # :744-745).
    want_K[1] = want_P[1] = 0.0
    worst = 0.0
    said: list[str] = []
    if len(K) == 9:
        moved = _shift(K, want_K, size)
        worst = max(worst, moved)
        if moved > PX_TOLERANCE:
            said.append(f"K is {_fmt(K)}, the description gives {_fmt(want_K)}")
    if len(P) == 12:
        moved = _shift(P, want_P, size)
        baseline = max(abs(P[3] - want_P[3]) / want_P[0], abs(P[7] - want_P[7]) / want_P[5])
        worst = max(worst, moved)
        if moved > PX_TOLERANCE or baseline > BASELINE_TOLERANCE:
            said.append(f"P is {_fmt(P)}, the description gives {_fmt(want_P)}")
            if baseline > BASELINE_TOLERANCE:
                worst = math.inf
    if said:
        sev = Severity.ERROR if worst > PX_ERROR else Severity.WARNING
        what = (
            f"moves the image by {worst:.2f} px"
            if math.isfinite(worst)
            else "not a pinhole K and P a simulator publishes, or another baseline"
        )
        out.append(finding("SK806", sev, f"{topic}: {'; '.join(said)} ({what})", exp, fix=fix))
    return out + _distortion(msg, exp, intr, fix)


def _distortion(msg: Any, exp: Expected, intr: Intrinsics, fix: str) -> list[Finding]:
    """SK806 of a CameraInfo's D and distortion_model."""
    out: list[Finding] = []
    topic = exp.name
    D = _array(msg, "d")
    want_D = list(intr.distortion)
    padded = D + [0.0] * max(0, len(want_D) - len(D))
    if len(padded) != len(want_D) or any(
        abs(a - b) > D_TOLERANCE for a, b in zip(padded, want_D, strict=False)
    ):
        out.append(
            finding(
                "SK806",
                Severity.ERROR,
                f"{topic}: D is {_fmt(D)}, the description gives {_fmt(want_D)} (k1, k2, p1, p2, k3)",
                exp,
                fix=fix,
            )
        )
    model = str(msg.distortion_model)
    if model != "plumb_bob":  # gazebo_ros_camera.cpp:392; gz-sensors PLUMB_BOB, bridged as it
        sev = Severity.ERROR if any(want_D) else Severity.WARNING
        out.append(
            finding(
                "SK806",
                sev,
                f"{topic}: distortion_model is {model!r}, the simulator publishes 'plumb_bob'"
                + ("" if any(want_D) else " (D is all zero, so nothing is distorted)"),
                exp,
                fix=fix,
            )
        )
    return out


def check_image(sample: TopicSample, exp: Expected, size: tuple[int, int] | None) -> list[Finding]:
    """SK807: the first recorded Image's size and encoding against the camera's."""
    if not sample.messages:
        return []
    msg = sample.messages[0]
    out: list[Finding] = []
    have = (int(msg.width), int(msg.height))
    if size is not None and have != size:
        out.append(
            finding(
                "SK807",
                Severity.ERROR,
                f"{exp.name}: images are {have[0]}x{have[1]}, the camera is {size[0]}x{size[1]}",
                exp,
            )
        )
    want = exp.topic.encoding
    if want is not None and str(msg.encoding) != want:
        out.append(
            finding(
                "SK807",
                Severity.ERROR,
                f"{exp.name}: encoding is {str(msg.encoding)!r}, the camera publishes {want!r}",
                exp,
            )
        )
    return out


def check_scan(sample: TopicSample, exp: Expected) -> list[Finding]:
    """SK808: the first recorded LaserScan's geometry against the lidar's."""
    scan = exp.sensor.scan
    if not sample.messages or scan is None:
        return []
    msg = sample.messages[0]
    wrong: list[str] = []
    for name in ("angle_min", "angle_max", "angle_increment"):
        have, want = float(getattr(msg, name)), float(getattr(scan, name))
        if not abs(have - want) <= ANGLE_TOLERANCE:
            wrong.append(f"{name} {have:.6g} (the lidar's: {want:.6g})")
    for name in ("range_min", "range_max"):
        have, want = float(getattr(msg, name)), float(getattr(scan, name))
        if not abs(have - want) <= RANGE_TOLERANCE * max(1.0, abs(want)):
            wrong.append(f"{name} {have:.6g} (the lidar's: {want:.6g})")
    beams = len(msg.ranges)
    if beams != scan.samples:
        wrong.append(f"{beams} beams (the lidar's: {scan.samples})")
    if not wrong:
        return []
    return [
        finding(
            "SK808",
            Severity.ERROR,
            f"{exp.name}: the scan has " + ", ".join(wrong),
            exp,
            fix="record the scan the description's lidar publishes, or correct its <ray>/<lidar>",
        )
    ]


def check_cloud(sample: TopicSample, exp: Expected, generation: str) -> list[Finding]:
    """SK809: the first recorded PointCloud2's fields: x, y, z, and the plugin's others."""
    if not sample.messages:
        return []
    names = [str(f.name) for f in sample.messages[0].fields]
    missing = [n for n in POINT_CLOUD_XYZ if n not in names]
    if missing:
        return [
            finding(
                "SK809",
                Severity.ERROR,
                f"{exp.name}: the cloud has no field {', '.join(missing)} (its fields: "
                f"{', '.join(names) or 'none'}): its points cannot be placed",
                exp,
            )
        ]
    want = POINT_CLOUD_FIELDS.get((generation, exp.sensor.sensor.kind))
    if want is None or list(want) == names:
        return []
    lost = [n for n in want if n not in names]
    extra = [n for n in names if n not in want]
    if not lost and not extra:
        return []  # the same fields in another order: consumers find them by name
    said = "; ".join(
        part
        for part in (
            f"without {', '.join(lost)}" if lost else "",
            f"with {', '.join(extra)} as well" if extra else "",
        )
        if part
    )
    return [
        finding(
            "SK809",
            Severity.WARNING,
            f"{exp.name}: the cloud's fields are {', '.join(names)}, {said}, where the "
            f"simulator's plugin writes {', '.join(want)}",
            exp,
        )
    ]


def measured_rate(stamps: Sequence[int]) -> float | None:
    """The mean rate (Hz) of header stamps (ns), or None: fewer than ``MIN_STAMPS``, or
    stamps that do not advance."""
    if len(stamps) < MIN_STAMPS:
        return None
    ordered = sorted(stamps)
    span = ordered[-1] - ordered[0]
    if span <= 0:
        return None
    return (len(ordered) - 1) * 1e9 / span


def check_rate(sample: TopicSample, exp: Expected) -> list[Finding]:
    """SK810: the rate of the sampled header stamps against ``<update_rate>``."""
    want = exp.topic.rate
    if want is None or len(sample.stamps) < MIN_STAMPS:
        return []
    have = measured_rate(sample.stamps)
    if have is None:
        return [
            finding(
                "SK810",
                Severity.WARNING,
                f"{exp.name}: the header stamps of its first {len(sample.stamps)} messages "
                f"do not advance (all {sample.stamps[0] / 1e9:g} s): no rate, and TF cannot "
                "tell when the data was taken",
                exp,
            )
        ]
    if abs(have - want) <= RATE_TOLERANCE * want:
        return []
    return [
        finding(
            "SK810",
            Severity.WARNING,
            f"{exp.name}: {have:.3g} Hz from the header stamps of {len(sample.stamps)} "
            f"messages, where <update_rate> is {want:g} Hz (more than "
            f"{RATE_TOLERANCE:.0%} off)",
            exp,
            fix="the simulation may run slower than real time, or the recorder drops "
            "messages; check the real-time factor and the recorder's QoS",
        )
    ]
