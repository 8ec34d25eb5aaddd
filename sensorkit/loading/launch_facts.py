"""What a robot's launch files say about its sensors (issue 24): the records.

Launch files are read, never run (sensorkit.loading.launch reads Python launch files as an
AST, and XML and YAML ones as data). What they say that matters to sensors:

- ros_gz_bridge entries given as ``parameter_bridge`` arguments, as its ``config_file``
  parameter, or through the ``ros_gz_bridge`` launch action;
- frames a ``static_transform_publisher`` puts in TF;
- ``robot_state_publisher``'s ``frame_prefix``;
- the name the robot is spawned under (``ros_gz_sim create -name``, ``spawn_entity.py
  -entity``), which is the MODEL part of every Gazebo Sim default frame and topic;
- remappings given to nodes.

A value the reader cannot resolve is never guessed: the record holds ``None`` where it
stands and the launch is marked ``partial`` for what it could not read, so a rule that
depends on it stays silent.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from sensorkit.base.findings import SourceRef
from sensorkit.loading.bridge import BridgeTopic


@dataclass(frozen=True)
class StaticTransform:
    """A ``static_transform_publisher``: ``child`` is in TF, under ``parent``."""

    parent: str
    child: str
    source: SourceRef


@dataclass(frozen=True)
class Spawn:
    """A robot spawned into the simulator: under ``name`` (None: not resolved), from a
    ``topic`` (robot_description) or a ``file``."""

    tool: str  # "ros_gz_sim create" | "spawn_entity.py"
    name: str | None
    topic: str | None
    file: str | None
    source: SourceRef


@dataclass(frozen=True)
class NodeRemap:
    """A remapping given to a node in a launch file (``from:=to``)."""

    package: str | None
    executable: str | None
    node_name: str | None
    namespace: str | None
    src: str
    dst: str
    source: SourceRef


@dataclass(frozen=True)
class DeadBridge:
    """A parameter_bridge that exits at start: ``argument`` is one it cannot parse, and
    ``topics`` every entry its arguments and config_file would have bridged, none of which
    exist. ros_gz_bridge's main() prints its usage and returns -1 on such an argument,
    before it spins the node (gazebosim/ros_gz@humble 5cc92f8 and @jazzy 739cb42:
    ros_gz_bridge/src/parameter_bridge.cpp:92-98, the loop over the arguments, and :173,
    the spin it never reaches); the config_file entries belong to that node
    (ros_gz_bridge/src/ros_gz_bridge.cpp:47-55 on both branches), so they go with it."""

    argument: str
    topics: tuple[BridgeTopic, ...]
    source: SourceRef


@dataclass
class LaunchProblem:
    """A launch file that could not be read, or a part of one that could not be resolved."""

    file: str
    message: str
    line: int | None = None


@dataclass
class LaunchFacts:
    """Everything the launch files read for one robot say about its sensors."""

    files: list[str] = field(default_factory=list)  # display paths, in the order read
    bridges: list[BridgeTopic] = field(default_factory=list)
    # A bridge whose arguments or config file could not be resolved: what it carries is
    # unknown, so no rule may say a topic is not bridged.
    bridge_unknown: bool = False
    bridge_unknown_in: list[str] = field(default_factory=list)  # the files that start one
    static_transforms: list[StaticTransform] = field(default_factory=list)
    # A static_transform_publisher whose frames could not be resolved: it may publish any
    # frame, so no rule may say a frame is missing from TF.
    static_transform_unknown: bool = False
    # robot_state_publisher's frame_prefix: "" when given empty or absent from a
    # robot_state_publisher that was found, None when no robot_state_publisher was found
    # or its value could not be resolved (frame_prefix_unknown).
    frame_prefix: str | None = None
    frame_prefix_unknown: bool = False
    spawns: list[Spawn] = field(default_factory=list)
    remaps: list[NodeRemap] = field(default_factory=list)
    # A remapping that could not be resolved: a topic may have another name than written.
    remap_unknown: bool = False
    problems: list[LaunchProblem] = field(default_factory=list)
    dead_bridges: list[DeadBridge] = field(default_factory=list)

    @property
    def empty(self) -> bool:
        return not self.files

    def static_frames(self) -> set[str]:
        """Frames a static transform publishes (parents and children, prefix-free)."""
        return {t.child for t in self.static_transforms} | {t.parent for t in self.static_transforms}

    def spawn_name(self) -> str | None:
        """The one MODEL name the robot is spawned under, or None (none, several, unknown)."""
        names = {s.name for s in self.spawns}
        if len(names) != 1:
            return None
        return next(iter(names))
