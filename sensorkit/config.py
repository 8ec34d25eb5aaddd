"""``[tool.sensorkit]`` in pyproject.toml: defaults for validate, overridden by flags.

```toml
[tool.sensorkit]
target = "harmonic"
select = ["SK5", "SK6"]
ignore = ["SK104"]
fail-on = "warning"
package-path = ["src"]        # relative to the pyproject.toml
args = { namespace = "robot1" }
```
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sensorkit.errors import UsageError

KEYS = {"target", "select", "ignore", "fail-on", "package-path", "args"}


@dataclass
class Config:
    path: Path | None = None
    target: str | None = None
    select: list[str] = field(default_factory=list)
    ignore: list[str] = field(default_factory=list)
    fail_on: str | None = None
    package_paths: list[str] = field(default_factory=list)
    args: dict[str, str] = field(default_factory=dict)


def find_pyproject(start: Path) -> Path | None:
    for folder in [start, *start.parents]:
        candidate = folder / "pyproject.toml"
        if candidate.is_file():
            return candidate
    return None


def _strings(value: Any, key: str, where: Path) -> list[str]:
    if isinstance(value, str):
        return [value]
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return list(value)
    msg = f"{where}: [tool.sensorkit] {key} must be a string or a list of strings"
    raise UsageError(msg)


def load_config(start: Path | None = None) -> Config:
    """Read the nearest pyproject.toml's ``[tool.sensorkit]`` (empty Config if none)."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        return Config()
    path = find_pyproject((start or Path.cwd()).resolve())
    if path is None:
        return Config()
    try:
        data = tomllib.loads(path.read_text("utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        msg = f"{path}: cannot read: {exc}"
        raise UsageError(msg) from None
    tool = data.get("tool", {})
    table = tool.get("sensorkit") if isinstance(tool, dict) else None  # `tool = 1`: not ours
    if table is None:
        return Config(path=path)
    if not isinstance(table, dict):
        msg = f"{path}: [tool.sensorkit] must be a table"
        raise UsageError(msg)
    unknown = set(table) - KEYS
    if unknown:
        msg = f"{path}: [tool.sensorkit] has unknown keys {sorted(unknown)}; known: {sorted(KEYS)}"
        raise UsageError(msg)
    cfg = Config(path=path)
    if "target" in table:
        cfg.target = str(table["target"])
    cfg.select = _strings(table.get("select", []), "select", path)
    cfg.ignore = _strings(table.get("ignore", []), "ignore", path)
    if "fail-on" in table:
        cfg.fail_on = str(table["fail-on"])
    cfg.package_paths = [
        p if "=" in p else str((path.parent / p).resolve())
        for p in _strings(table.get("package-path", []), "package-path", path)
    ]
    args = table.get("args", {})
    if not isinstance(args, dict):
        msg = f"{path}: [tool.sensorkit] args must be a table"
        raise UsageError(msg)
    cfg.args = {str(k): str(v) for k, v in args.items()}
    return cfg
