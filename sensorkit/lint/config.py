"""Project settings for every command, overridden by flags.

Found upward from the robot file (else the working folder), nearest first: a
``sensorkit.toml`` (keys at top level) or a ``pyproject.toml`` with a
``[tool.sensorkit]`` table (a pyproject without one is passed over); or given with
``--config FILE``. It applies to validate, add-*, render, intrinsics, export, topics and new.

```toml
target = "harmonic"             # validate, add-* (gz blocks), render, intrinsics, export, topics, new
select = ["SK5", "SK6"]         # validate
ignore = ["SK104"]
fail-on = "warning"
package-path = ["src"]          # relative to the file
launch = ["launch/sim.launch.py"] # validate, topics: launch files to read (relative to the file)
args = { namespace = "robot1" } # xacro arguments
```
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sensorkit.base.errors import UsageError

KEYS = {"target", "select", "ignore", "fail-on", "package-path", "args", "launch", "max-elements"}


@dataclass
class Config:
    """Settings read from a configuration file (``path``; None when there is none)."""

    path: Path | None = None
    target: str | None = None
    select: list[str] = field(default_factory=list)
    ignore: list[str] = field(default_factory=list)
    fail_on: str | None = None
    package_paths: list[str] = field(default_factory=list)
    args: dict[str, str] = field(default_factory=dict)
    launch: list[str] = field(default_factory=list)  # launch files, made absolute
    max_elements: int | None = None  # the element bound (issue 36; --max-elements)


    def describe(self, used: Iterable[str]) -> str | None:
        """``"target harmonic, fail-on warning from ./sensorkit.toml"`` for the settings
        a command took from this file, or None when it took none."""
        from sensorkit.loading.document import display_path

        if self.path is None:
            return None
        values = {
            "target": self.target,
            "select": ",".join(self.select),
            "ignore": ",".join(self.ignore),
            "fail-on": self.fail_on,
            "package-path": " ".join(self.package_paths),
            "args": " ".join(f"{k}:={v}" for k, v in self.args.items()),
            "launch": " ".join(display_path(Path(p)) for p in self.launch),
            "max-elements": str(self.max_elements),
        }
        parts = [f"{key} {values[key]}" for key in used if values.get(key)]
        if not parts:
            return None
        return ", ".join(parts) + f" from {display_path(self.path)}"

    def confined_package_paths(self) -> tuple[str, ...]:
        """``package-path`` for ``--untrusted``: only folders inside the pyproject's folder.

        The pyproject.toml comes with the pull request, so a ``package-path = ["/"]`` in
        it must not widen what an untrusted xacro may read; a folder outside has to be
        given on the command line.
        """
        if self.path is None:
            return tuple(self.package_paths)
        home = self.path.parent.resolve()
        for item in self.package_paths:
            folder = Path(item.partition("=")[2] or item).resolve()
            if folder != home and home not in folder.parents:
                msg = (
                    f"{self.path}: [tool.sensorkit] package-path {item!r} lies outside "
                    f"{home}; with --untrusted pass it as --package-path on the command line"
                )
                raise UsageError(msg)
        return tuple(self.package_paths)


def package_folder(item: str) -> str:
    """The folder of a package-path item: ``DIR``, or the DIR of ``NAME=DIR``."""
    name, sep, folder = item.partition("=")
    return folder if sep and name and "/" not in name else item


def find_config(start: Path) -> tuple[Path, dict[str, Any]] | None:
    """The nearest settings file at or above ``start`` and its sensorkit table."""
    for folder in [start, *start.parents]:
        own = folder / "sensorkit.toml"
        if own.is_file():
            return own, _read(own)
        pyproject = folder / "pyproject.toml"
        if pyproject.is_file():
            table = _tool_table(_read(pyproject))
            if table is not None:
                return pyproject, table
    return None


def _tool_table(data: dict[str, Any]) -> Any:
    """``[tool.sensorkit]`` of a pyproject, or None (also when ``tool`` is not a table)."""
    tool = data.get("tool")
    return tool.get("sensorkit") if isinstance(tool, dict) else None


def _read(path: Path) -> dict[str, Any]:
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10: tomllib is 3.11+
        msg = f"{path}: reading settings needs Python 3.11 or newer (tomllib)"
        raise UsageError(msg) from None
    try:
        data: dict[str, Any] = tomllib.loads(path.read_text("utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        msg = f"{path}: cannot read: {exc}"
        raise UsageError(msg) from None
    return data


def _strings(value: Any, key: str, where: Path) -> list[str]:
    if isinstance(value, str):
        return [value]
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return list(value)
    msg = f"{where}: {_table(where)}{key} must be a string or a list of strings"
    raise UsageError(msg)


def _table(path: Path) -> str:
    return "[tool.sensorkit] " if path.name == "pyproject.toml" else ""


def load_config(start: Path | None = None, *, explicit: Path | None = None) -> Config:
    """The settings for a command on a file in ``start`` (or ``explicit``: ``--config``)."""
    if explicit is not None:
        if explicit.is_dir():
            msg = f"--config {explicit} is a folder; name its sensorkit.toml or pyproject.toml"
            raise UsageError(msg)
        if not explicit.is_file():
            msg = f"--config {explicit}: no such file"
            raise UsageError(msg)
        data = _read(explicit)
        table = _tool_table(data) if explicit.name == "pyproject.toml" else data
        if table is None:  # found upward it is passed over; named, it is a mistake
            msg = (
                f"--config {explicit} has no [tool.sensorkit] table, so it holds no settings: "
                "add the table, or name a sensorkit.toml"
            )
            raise UsageError(msg)
        found: tuple[Path, dict[str, Any]] | None = (explicit, table)
    else:
        folder = (start or Path.cwd()).resolve()
        if folder.is_file() or not folder.exists():
            folder = folder.parent
        found = find_config(folder)
    if found is None:
        return Config()
    path, table = found
    if not isinstance(table, dict):
        msg = f"{path}: {_table(path)}must be a table"
        raise UsageError(msg)
    unknown = set(table) - KEYS
    if unknown:
        msg = f"{path}: {_table(path)}has unknown keys {sorted(unknown)}; known: {sorted(KEYS)}"
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
        msg = f"{path}: {_table(path)}args must be a table"
        raise UsageError(msg)
    cfg.args = {str(k): str(v) for k, v in args.items()}
    cfg.launch = [
        str((path.parent / p).resolve()) for p in _strings(table.get("launch", []), "launch", path)
    ]
    if "max-elements" in table:
        value = table["max-elements"]
        if not isinstance(value, int) or isinstance(value, bool) or value < 1:
            raise UsageError(f"{path}: {_table(path)}max-elements must be a whole number over 0")
        cfg.max_elements = value
    return cfg
