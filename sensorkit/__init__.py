"""sensorkit: correct-by-construction sensors for URDF/xacro robots on ROS 2 and Gazebo.

The package is layered; a layer imports only the layers below it, and siblings inside a
package import each other without circles (``lint-imports`` holds both, from the
contracts in pyproject.toml; tests/test_layers.py runs it). Bottom up:

1. ``base``: errors, findings, atomic writes, shipped data, "did you mean";
2. ``loading``: strict XML, isolated xacro with line tracking, packages, bridge YAML;
3. ``knowledge``: what sensorkit knows of plugins and simulators, as data with sources;
4. ``model``: links, joints, transforms, sensors, what Gazebo's conversion keeps;
5. ``lint``: the rules and the engine that runs them, report formats, settings;
6. ``describe``: what a robot publishes (camera_info, topics, frames, bridges);
7. ``recording``: ``check-recording``, a bag checked against what ``describe`` predicts
   (the only layer that imports rosbags, the extra ````sensorkit-ros[recording]````);
8. ``exporters``: config files for other tools (camera_info, ORB-SLAM3, Kalibr, ...);
9. ``generate``: ``sensorkit new``, whole packages from a robot YAML;
10. ``edit``: ``sensorkit add-*``, byte-preserving edits of a user's robot;
11. ``fix``: ``validate --fix``, a fixer per rule;
12. ``render``: ``render preview``, the only layer that imports pybullet and Pillow;
13. ``lsp``: ``sensorkit lsp``, the language server (pygls): diagnostics, fixes, hover;
14. ``cli``: the only layer that prints, exits or parses options; with ``lsp`` the only
    ones that speak a protocol.
"""

__version__ = "0.1.0"
