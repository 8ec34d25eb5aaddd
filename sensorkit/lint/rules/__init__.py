"""Validation rules, one module per family, all registered in ``RULES`` by id.

``RULE_ORDER`` is the order in which the engine runs the rules and ``RULES`` lists them:
a run's findings come out rule after rule in it, until a report sorts them. It is the
order the families were registered in when SK6xx was one module (modules in alphabetical
order, rules in their order of writing); its rules now live in several modules and
interleave, so the order is written out here and ``put_in_order`` holds ``RULES`` to it.
"""

from sensorkit.lint.rules import (  # noqa: F401  (registration)
    bridge,
    bridge_flow,
    calibration,
    focal,
    frame_joints,
    frames,
    gz_frames,
    gz_world,
    input,
    lidar,
    mass,
    model_plugins,
    noise,
    placement,
    plugins,
    principal,
    recording,
    ros1,
    sdf,
    sensor_blocks,
    sensors,
    topics,
    tree,
)
from sensorkit.lint.rules.base import RULES, Context, MissingFile, RuleInfo, put_in_order

RULE_ORDER = (
    "SK501", "SK502", "SK503", "SK504", "SK505", "SK506", "SK507",  # frames
    "SK508", "SK509",  # frame_joints
    "SK101", "SK102", "SK103", "SK104", "SK105", "SK106",  # input
    "SK301", "SK302", "SK303", "SK304",  # mass
    "SK601", "SK602", "SK603", "SK604", "SK605", "SK606",  # plugins, ros1, topics, ...
    "SK607", "SK612", "SK615", "SK608", "SK609", "SK610", "SK611", "SK614",  # ... bridge, gz_frames
    "SK401", "SK402", "SK403", "SK404", "SK405", "SK406", "SK407", "SK408", "SK409",  # sensors
    "SK613",  # sensors
    "SK412",  # focal
    "SK410", "SK411",  # placement, principal
    "SK201", "SK202", "SK203", "SK204", "SK205", "SK206", "SK207",  # tree
    "SK107", "SK208", "SK209", "SK510",  # sdf
    "SK413", "SK414", "SK417",  # calibration
    "SK415", "SK416",  # sensor_blocks
    "SK801", "SK802", "SK803", "SK804", "SK805",  # recording (check-recording)
    "SK806", "SK807", "SK808", "SK809", "SK810",  # recording
    "SK616",  # model_plugins
    "SK617", "SK618", "SK619",  # bridge_flow
    "SK620",  # gz_world
)  # fmt: skip
put_in_order(RULE_ORDER)

__all__ = ["RULES", "RULE_ORDER", "Context", "MissingFile", "RuleInfo"]
