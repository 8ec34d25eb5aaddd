"""A node's parameter as its launch file sets it: from a map, or from a parameter file.

Parameters apply in the order given, a later one overriding an earlier one (a ROS 2
parameter file is ``NODE: ros__parameters: {...}``, ``/**`` matching every node).
"""

from __future__ import annotations

from pathlib import Path

from sensorkit.base.regular import read_regular
from sensorkit.loading.launch.spec import MAX_LAUNCH_BYTES, NodeSpec, Reading, plain


def param(reading: Reading, spec: NodeSpec, key: str) -> tuple[bool, str | None]:
    """(given, value): given False when no source sets it; value None when unknown."""
    given, value = False, None
    for source in spec.params:
        if isinstance(source, dict):
            if key in source:
                given, value = True, source[key]
            elif None in source:
                given, value = True, None  # ``**more``: may set it
        else:
            found, file_value = _from_file(reading, spec, source, key)
            if found:
                given, value = True, file_value
    return given, value


def _from_file(reading: Reading, spec: NodeSpec, source: str | None, key: str) -> tuple[bool, str | None]:
    """(found, value) of ``key`` in a parameter file (found, None when unreadable)."""
    path = plain(source)
    if path is None or not Path(path).is_file() or not reading.inside(Path(path)):
        return True, None
    import yaml

    from sensorkit.base import yamlguard

    try:
        data = yamlguard.safe_load(read_regular(path, MAX_LAUNCH_BYTES).decode("utf-8"))
    except (OSError, UnicodeDecodeError, yaml.YAMLError, RecursionError):
        return True, None
    if not isinstance(data, dict):
        return False, None
    found, value = False, None
    for node, body in data.items():
        if not _matches(str(node), spec) or not isinstance(body, dict):
            continue
        params = body.get("ros__parameters")
        if isinstance(params, dict) and key in params:
            found, value = True, _scalar(params[key])
    return found, value


def _matches(node: str, spec: NodeSpec) -> bool:
    if node in ("/**", "**"):
        return True
    if spec.name is None:
        return True  # may be this node: counted, so an unknown name never hides a value
    return node.rstrip("/").split("/")[-1] == spec.name


def _scalar(value: object) -> str | None:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str | int | float):
        return str(value)
    return None
