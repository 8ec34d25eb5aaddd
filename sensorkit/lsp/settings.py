"""The engine's options for one document: the settings file found upward from it (as
the CLI finds it: :func:`sensorkit.lint.config.load_config`), under what the client sends
as ``initializationOptions``, which win as the CLI's flags do.

initializationOptions (every key optional)::

    {"target": "harmonic", "args": {"gazebo": "ignition"},
     "packagePaths": ["/ws/src", "name=/dir"], "select": ["SK5"], "ignore": ["SK104"]}

Input is trusted, as a robot opened in one's own editor is: the server never expands
with ``--untrusted``'s limits.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sensorkit.base.errors import UsageError
from sensorkit.lint.config import Config, load_config, package_folder
from sensorkit.lint.engine import Options
from sensorkit.loading.cache import MemoryCache
from sensorkit.loading.document import display_path

# The server's expansions, kept in memory for its life: an edit to one file of a robot
# expands again, a re-check with nothing changed (a hover, a settings reload, a file
# saved as it was) does not. The cache checks every file it read (sensorkit.loading.cache).
EXPANSIONS = MemoryCache()

__all__ = ["Overrides", "Settings", "settings_for"]


@dataclass(frozen=True)
class Overrides:
    """What the client's initializationOptions set (None / empty: the settings file's)."""

    target: str | None = None
    args: dict[str, str] = field(default_factory=dict)
    package_paths: tuple[str, ...] = ()
    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()

    @classmethod
    def parse(cls, data: Any) -> Overrides:
        """From initializationOptions (None or an object); a bad value is a UsageError."""
        if data is None:
            return cls()
        if not isinstance(data, dict):
            msg = "initializationOptions must be an object"
            raise UsageError(msg)
        unknown = set(data) - {"target", "args", "packagePaths", "select", "ignore"}
        if unknown:
            msg = f"initializationOptions: unknown keys {sorted(unknown)}"
            raise UsageError(msg)
        target = data.get("target")
        if target is not None and not isinstance(target, str):
            msg = "initializationOptions.target must be a string"
            raise UsageError(msg)
        args = data.get("args") or {}
        if not isinstance(args, dict):
            msg = "initializationOptions.args must be an object of NAME: VALUE"
            raise UsageError(msg)
        return cls(
            target=target,
            args={str(k): str(v) for k, v in args.items()},
            package_paths=_strings(data, "packagePaths"),
            select=_strings(data, "select"),
            ignore=_strings(data, "ignore"),
        )


def _strings(data: dict[str, Any], key: str) -> tuple[str, ...]:
    value = data.get(key) or []
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        msg = f"initializationOptions.{key} must be a list of strings"
        raise UsageError(msg)
    return tuple(value)


@dataclass(frozen=True)
class Settings:
    """The options a document is validated with, and the settings file they came from."""

    options: Options
    config: Config


def settings_for(path: Path, overrides: Overrides) -> Settings:
    """The options for validating ``path``: ``overrides`` over the settings file found
    upward from it. Raises UsageError for a bad settings file or a missing package folder."""
    cfg = load_config(path)
    for item in overrides.package_paths:
        if not Path(package_folder(item)).expanduser().is_dir():
            msg = f"initializationOptions.packagePaths {item}: no such folder"
            raise UsageError(msg)
    for item in cfg.package_paths:
        if not Path(package_folder(item)).is_dir():
            msg = f"{cfg.path}: package-path {item}: no such folder"
            raise UsageError(msg)
    target = overrides.target or cfg.target or "auto"
    origin = "initializationOptions" if overrides.target else display_path(cfg.path or "--target")
    options = Options(
        target=target,
        select=overrides.select or tuple(cfg.select),
        ignore=overrides.ignore or tuple(cfg.ignore),
        args={**cfg.args, **overrides.args},
        package_paths=overrides.package_paths or tuple(cfg.package_paths),
        launch=tuple(cfg.launch),
        target_origin=origin,
        cache=EXPANSIONS,
    )
    return Settings(options, cfg)
