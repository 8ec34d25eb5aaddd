"""SK8xx: a recording checked against the description (``sensorkit check-recording``).

These rules read a bag, not only the robot: ``sensorkit.recording`` (a layer above
``describe``, whose predictions they compare with) makes their findings. They are
declared here so that the one registry lists them (``sensorkit rules``, SARIF's rule
table, the docs' table); the engine that runs ``validate`` never runs them
(``formats`` names no robot format).
"""

from __future__ import annotations

from sensorkit.lint.rules.base import declare

RECORDING = ("recording",)  # RuleInfo.formats of a rule that checks a bag

declare(
    "SK801",
    "error/info",
    "recording: every topic the description predicts is in the bag (error: no data "
    "recorded); a sensor message topic recorded that no sensor of the description "
    "predicts (info)",
    formats=RECORDING,
)
declare(
    "SK802",
    "error",
    "recording: a predicted topic is recorded with another message type than the one "
    "the sensor publishes",
    formats=RECORDING,
)
declare(
    "SK803",
    "error",
    "recording: header.frame_id is the frame the description predicts (a camera "
    "stamped in a frame that is not optical is explained as SK502 explains it)",
    formats=RECORDING,
)
declare(
    "SK804",
    "error/info",
    "recording: the recorded header.frame_id is a frame of the recorded /tf or "
    "/tf_static (error: TF cannot place the data); a bag with no TF at all (info: "
    "not checked)",
    formats=RECORDING,
)
declare(
    "SK805",
    "error",
    "recording: the recorded TF from a sensor's frame to its parent link agrees with "
    "the description's fixed joint within 1 mm and 0.5 degree (REP 103 optical "
    "rotations included)",
    formats=RECORDING,
)
declare(
    "SK806",
    "error/warning",
    "recording: CameraInfo width, height, K, D, P and distortion model are those "
    "`sensorkit intrinsics` predicts (error when the image edge or principal point "
    "moves by more than 1 px, or D or the size differ; warning for a smaller "
    "difference over 0.01 px, or a distortion model name with all-zero D)",
    formats=RECORDING,
)
declare(
    "SK807",
    "error",
    "recording: Image width, height and encoding are the camera's",
    formats=RECORDING,
)
declare(
    "SK808",
    "error",
    "recording: LaserScan angle_min, angle_max, angle_increment, range_min, range_max "
    "and beam count are the lidar's",
    formats=RECORDING,
)
declare(
    "SK809",
    "error/warning",
    "recording: PointCloud2 fields: x, y and z present (error), and the fields the "
    "simulator's plugin writes (warning)",
    formats=RECORDING,
)
declare(
    "SK810",
    "warning",
    "recording: the rate measured from header stamps is the sensor's <update_rate> within 10 %",
    formats=RECORDING,
)
