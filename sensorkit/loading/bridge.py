"""ros_gz_bridge (parameter_bridge) YAML files: which gz topics reach ROS.

A file is a YAML list of maps. ros_gz_bridge reads ``gz_topic_name`` (Fortress's
ros_ign_bridge: ``ign_topic_name``), ``ros_topic_name``, or ``topic_name`` for both,
with ``ros_type_name``, ``gz_type_name`` and ``direction``, which defaults to
BIDIRECTIONAL (gazebosim/ros_gz@humble:ros_gz_bridge/src/bridge_config.cpp:28-45 for the
keys, :76-82 for ign_topic_name, :108 for the default direction).

:func:`find_bridge_files` looks in the robot package's ``config/`` for any YAML of that
shape; :func:`read_bridge` reads one file, with each entry's line.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

MAX_BRIDGE_BYTES = 1 << 20
GZ_KEYS = ("gz_topic_name", "ign_topic_name", "topic_name")
ROS_KEYS = ("ros_topic_name", "topic_name")


@dataclass(frozen=True)
class BridgeTopic:
    gz: str  # gz topic name as written
    ros: str | None
    ros_type: str | None
    direction: str
    file: str
    line: int | None
    # gz_type_name (ign_type_name on Fortress), as written; None: not given (ros_gz_bridge
    # derives it from ros_type_name) (gazebosim/ros_gz@humble:ros_gz_bridge/src/
    # bridge_config.cpp:63-72 reads ign_type_name when gz_type_name is absent)
    gz_type: str | None = None

    @property
    def to_ros(self) -> bool:
        return self.direction.upper() in ("GZ_TO_ROS", "BIDIRECTIONAL", "")


class BridgeError(ValueError):
    """A file given with --bridge that is not a ros_gz_bridge configuration."""


def read_bridge(path: Path, display: str | None = None) -> list[BridgeTopic]:
    """Entries of a parameter_bridge YAML file (raises BridgeError when it is not one)."""
    import yaml

    from sensorkit.base import yamlguard

    name = display or str(path)
    try:
        if path.stat().st_size > MAX_BRIDGE_BYTES:
            raise BridgeError(f"{name}: larger than 1 MiB: not a bridge configuration")
        text = path.read_text("utf-8")
        node = yamlguard.compose(text)
    except (OSError, UnicodeDecodeError) as exc:
        raise BridgeError(f"{name}: cannot read: {exc}") from exc
    except yaml.YAMLError as exc:
        raise BridgeError(f"{name}: not YAML: {str(exc).splitlines()[0]}") from exc
    if not isinstance(node, yaml.SequenceNode):
        raise BridgeError(f"{name}: not a ros_gz_bridge list of topics")
    out: list[BridgeTopic] = []
    for item in node.value:
        if not isinstance(item, yaml.MappingNode):
            raise BridgeError(f"{name}:{item.start_mark.line + 1}: a bridge entry must be a map")
        fields: dict[str, str] = {}
        for k, v in item.value:
            if isinstance(k, yaml.ScalarNode) and isinstance(v, yaml.ScalarNode):
                fields[str(k.value)] = str(v.value)
        gz = next((fields[k] for k in GZ_KEYS if fields.get(k)), None)
        if gz is None:
            raise BridgeError(
                f"{name}:{item.start_mark.line + 1}: entry has no gz_topic_name (or topic_name)"
            )
        ros = next((fields[k] for k in ROS_KEYS if fields.get(k)), None)
        out.append(
            BridgeTopic(
                gz=gz,
                ros=ros,
                ros_type=fields.get("ros_type_name"),
                direction=fields.get("direction", "BIDIRECTIONAL"),
                file=name,
                line=item.start_mark.line + 1,
                gz_type=fields.get("gz_type_name") or fields.get("ign_type_name"),
            )
        )
    return out


def find_bridge_files(package: Path) -> list[Path]:
    """YAML files of the parameter_bridge shape in ``package``/config (two levels deep)."""
    config = package / "config"
    if not config.is_dir():
        return []
    found: list[Path] = []
    candidates = sorted([*config.glob("*.y*ml"), *config.glob("*/*.y*ml")])
    for path in candidates:
        try:
            if read_bridge(path):
                found.append(path)
        except BridgeError:
            continue
    return found
