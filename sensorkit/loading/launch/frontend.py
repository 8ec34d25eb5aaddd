"""Read XML and YAML launch files (ROS 2 launch front ends; ROS 1 roslaunch XML too).

Both front ends describe the same entities (ros2/launch@humble:launch/launch/frontend/parser.py:130
the root must be ``launch``; launch_xml/launch_xml/parser.py:42 and
launch_yaml/launch_yaml/parser.py:60 the file extensions; launch_yaml/launch_yaml/entity.py:
76-82 a YAML child is a map with one key, its type):

- ``node`` with ``pkg``, ``exec``, ``name``, ``namespace``, ``args`` and children
  ``param`` (``name``/``value`` or ``from``) and ``remap`` (``from``/``to``)
  (ros2/launch_ros@humble:launch_ros/launch_ros/actions/node.py:310-342); ROS 1 writes
  ``type`` and ``ns``;
- ``arg`` with ``name``, ``default`` (ros2/launch@humble:launch/launch/actions/
  declare_launch_argument.py:169-170), ``let``;
- ``include`` with ``file`` and ``arg`` children (``name``/``value``)
  (ros2/launch@humble:launch/launch/actions/include_launch_description.py:88-95);
- substitutions ``$(var x)`` (launch/substitutions/launch_configuration.py:32),
  ``$(find-pkg-share p)`` (launch_ros/substitutions/find_package.py:99), ``$(dirname)``;
  ROS 1's ``$(arg x)`` and ``$(find p)``. Any other substitution is unknown.
- ``args`` is split like a shell line (launch/actions/execute_process.py _parse_cmdline,
  shlex.split of the text).
- ``ros_gz_bridge`` with ``config_file`` and ``namespace``
  (gazebosim/ros_gz@jazzy:ros_gz_bridge/ros_gz_bridge/actions/ros_gz_bridge.py:30,77-95).
"""

from __future__ import annotations

import re
import shlex
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from sensorkit.loading.launch.python_launch import FileReading
from sensorkit.loading.launch.spec import Include, NodeSpec

_PUSH = {"push-ros-namespace", "push_ros_namespace"}


@dataclass
class Entity:
    type: str
    attrs: dict[str, str]
    children: list[Entity] = field(default_factory=list)
    line: int | None = None


@dataclass
class Context:
    file: Path
    share: Callable[[str], str]
    configs: dict[str, str | None]


def substitute(text: str, ctx: Context) -> str | None:
    """``text`` with its ``$(...)`` substitutions resolved (None: one is unknown)."""
    out, i = [], 0
    while True:
        start = text.find("$(", i)
        if start < 0:
            out.append(text[i:])
            return "".join(out)
        out.append(text[i:start])
        depth, j = 0, start + 1
        while j < len(text):
            depth += {"(": 1, ")": -1}.get(text[j], 0)
            if depth == 0:
                break
            j += 1
        if depth:
            return None
        value = _one(text[start + 2 : j], ctx)
        if value is None:
            return None
        out.append(value)
        i = j + 1


def _one(inner: str, ctx: Context) -> str | None:
    resolved = substitute(inner, ctx)
    if resolved is None:
        return None
    parts = resolved.split()
    if not parts:
        return None
    kind, args = parts[0], parts[1:]
    if kind in ("var", "arg") and len(args) == 1:
        return ctx.configs.get(args[0])
    if kind in ("find-pkg-share", "find") and len(args) == 1:
        return ctx.share(args[0])
    if kind == "dirname" and not args:
        return str(ctx.file.parent)
    return None


def split_args(text: str, ctx: Context) -> list[str | None]:
    """``args`` split like a shell line, each token with its substitutions resolved."""
    subs: list[str] = []

    def hold(m: re.Match[str]) -> str:
        subs.append(m.group(0))
        return f"\x01{len(subs) - 1}\x01"

    held = re.sub(r"\$\((?:[^()]|\$\([^()]*\))*\)", hold, text)
    try:
        tokens = shlex.split(held)
    except ValueError:
        tokens = held.split()
    out: list[str | None] = []
    for token in tokens:
        back = re.sub(r"\x01(\d+)\x01", lambda m: subs[int(m.group(1))], token)
        out.append(substitute(back, ctx))
    return out


def read_entities(root: Entity, ctx: Context) -> FileReading:
    """What one XML or YAML launch file gives the reader."""
    if root.type != "launch":
        raise ValueError("the root is not <launch>")
    out = FileReading()
    inherited = dict(ctx.configs)
    _walk(root.children, ctx, out)
    out.configs = {**inherited, **ctx.configs}
    return out


def _walk(entities: list[Entity], ctx: Context, out: FileReading) -> None:
    for e in entities:
        a = {k: substitute(v, ctx) for k, v in e.attrs.items()}
        if e.type == "arg":
            name = a.get("name")
            if name is not None and name not in ctx.configs:
                raw = e.attrs.get("default", e.attrs.get("value"))
                ctx.configs[name] = a.get("default", a.get("value")) if raw is not None else None
        elif e.type == "let" and a.get("name") is not None:
            ctx.configs[str(a["name"])] = a.get("value")
        elif e.type == "group":
            saved = dict(ctx.configs)
            if e.attrs.get("ns") or any(c.type in _PUSH for c in e.children):
                out.pushes_namespace = True
            _walk(e.children, ctx, out)
            if e.attrs.get("scoped", "true").lower() != "false":
                ctx.configs.clear()
                ctx.configs.update(saved)
        elif e.type in _PUSH:
            out.pushes_namespace = True
        elif e.type == "node":
            out.nodes.append(_node(e, a, ctx))
        elif e.type == "include":
            args = {str(c.attrs.get("name")): substitute(c.attrs.get("value", ""), ctx)
                    for c in e.children if c.type == "arg" and "name" in c.attrs}
            out.includes.append(Include(a.get("file"), args, e.line))
        elif e.type == "ros_gz_bridge":
            out.nodes.append(NodeSpec("ros_gz_bridge", "parameter_bridge", a.get("bridge_name"),
                                      a.get("namespace", ""), [],
                                      params=[{"config_file": a.get("config_file")}],
                                      file=str(ctx.file), line=e.line))


def _node(e: Entity, a: dict[str, str | None], ctx: Context) -> NodeSpec:
    raw_args = e.attrs.get("args")
    spec = NodeSpec(a.get("pkg"), a.get("exec", a.get("type")), a.get("name"),
                    a.get("namespace", a.get("ns", "")),
                    split_args(raw_args, ctx) if raw_args is not None else [],
                    file=str(ctx.file), line=e.line)
    spec.arg_lines = [e.line] * len(spec.arguments or [])
    for c in e.children:
        if c.type == "remap":
            spec.remaps.append((substitute(c.attrs.get("from", ""), ctx) if "from" in c.attrs else None,
                                substitute(c.attrs.get("to", ""), ctx) if "to" in c.attrs else None))
        elif c.type == "param" and "from" in c.attrs:
            spec.params.append(substitute(c.attrs["from"], ctx))
        elif c.type == "param" and "name" in c.attrs and "value" in c.attrs:
            name = substitute(c.attrs["name"], ctx)
            spec.params.append({name: substitute(c.attrs["value"], ctx)})
        elif c.type == "param":
            spec.params.append({None: None})  # nested or typed from a command: unknown
    return spec


def xml_entities(data: bytes) -> Entity:
    """The entity tree of an XML launch file (raises ValueError when it is not XML)."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False,
                             remove_comments=True, remove_pis=True)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError as exc:
        raise ValueError(str(exc)) from None

    def convert(el: etree._Element) -> Entity:
        kids = [convert(c) for c in el if isinstance(c.tag, str)]
        return Entity(str(el.tag), {str(k): str(v) for k, v in el.attrib.items()}, kids, el.sourceline)

    return convert(root)


def yaml_entities(text: str) -> Entity:
    """The entity tree of a YAML launch file (raises ValueError when it is not one)."""
    import yaml

    from sensorkit.base import yamlguard

    try:
        node = yamlguard.compose(text)
    except yaml.YAMLError as exc:
        raise ValueError(str(exc).splitlines()[0]) from None
    if not isinstance(node, yaml.MappingNode) or len(node.value) != 1:
        raise ValueError("a YAML launch file is a map with one key, launch")
    key, body = node.value[0]
    return _yaml_entity(str(key.value), body)


def _yaml_entity(kind: str, node: object) -> Entity:
    import yaml

    line = node.start_mark.line + 1 if isinstance(node, yaml.Node) else None
    entity = Entity(kind, {}, [], line)
    if isinstance(node, yaml.SequenceNode):
        entity.children = _yaml_children(node)
    elif isinstance(node, yaml.MappingNode):
        for k, v in node.value:
            name = str(k.value)
            if isinstance(v, yaml.ScalarNode):
                entity.attrs[name] = str(v.value)
            elif name == "children" and isinstance(v, yaml.SequenceNode):
                entity.children.extend(_yaml_children(v))
            elif isinstance(v, yaml.SequenceNode):
                entity.children.extend(_yaml_entity(name, item) for item in v.value)
    return entity


def _yaml_children(seq: object) -> list[Entity]:
    import yaml

    out: list[Entity] = []
    for item in getattr(seq, "value", []):
        if isinstance(item, yaml.MappingNode) and len(item.value) == 1:
            k, v = item.value[0]
            out.append(_yaml_entity(str(k.value), v))
        else:
            raise ValueError(f"line {item.start_mark.line + 1}: an entity is a map with one key")
    return out
