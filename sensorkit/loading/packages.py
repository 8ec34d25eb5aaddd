"""Resolve ROS package names to folders, as ``$(find pkg)`` and ``package://pkg/`` need.

Order (first hit wins):
1. ``--package-path NAME=DIR`` (explicit),
2. ``--package-path DIR`` (scanned for package.xml),
3. ``AMENT_PREFIX_PATH`` (``<prefix>/share/<pkg>``),
4. ``ROS_PACKAGE_PATH`` (scanned for package.xml),
5. with no ``--package-path`` at all: the workspace around the file being loaded, i.e. its
   own package and the packages beside it, as in a colcon ``src/``.

Scans are lazy (nothing is read until a package is asked for) and bounded, so a stray
``--package-path /`` cannot hang sensorkit.

A package name is a name (:func:`valid_package_name`): ``$(find /abs)``,
``$(find ../x)`` and ``package://../x`` name no package and resolve to nothing, whatever
``AMENT_PREFIX_PATH`` holds. Under ``--untrusted`` a resolver is *confined*
(:meth:`PackageResolver.confine_to`): :meth:`PackageResolver.allows` says whether a path
lies in the workspace, the ``--package-path`` folders or a package it found (real paths).
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

_SKIP_DIRS = {"build", "install", "log", "node_modules", "__pycache__"}
_NAME_RE = rb"<name>\s*([^<\s]+)\s*</name>"  # compiled on first use
MAX_SCAN_DIRS = 5000
MAX_SCAN_DEPTH = 5


def valid_package_name(name: str) -> bool:
    """Whether ``name`` can be a package name at all.

    REP 144 asks for lowercase letters, digits and underscores, starting with a letter
    (ros-infrastructure/rep@11ca24a:rep-0144.rst:51 "only consist of lowercase alphanumerics
    and _ separators and start with an alphabetic character"), but real packages also use
    dashes and capitals, so only what cannot be a name is refused: the empty name, ``.``
    and ``..``, any path separator, NUL, and an absolute path.
    """
    return (
        bool(name)
        and name not in (".", "..")
        and not any(c in name for c in ("/", "\\", "\x00"))
        and not os.path.isabs(name)
    )


def _real(path: str | os.PathLike[str]) -> str:
    return os.path.realpath(path)


def package_name(package_xml: Path) -> str | None:
    """The ``<name>`` of a package.xml, read without a full XML parse (it may be broken)."""
    try:
        data = package_xml.read_bytes()[:65536]
    except OSError:
        return None
    m = re.search(_NAME_RE, data)
    return m.group(1).decode("utf-8", "replace") if m else None


def scan_packages(root: Path, *, max_depth: int = MAX_SCAN_DEPTH) -> dict[str, Path]:
    """Every package below ``root`` (a folder holding package.xml), first found wins.

    Like colcon: a package folder is not descended into, folders holding COLCON_IGNORE,
    AMENT_IGNORE or CATKIN_IGNORE and hidden or build folders are skipped.
    """
    return {name: folders[0] for name, folders in scan_all(root, max_depth=max_depth).items()}


def scan_all(root: Path, *, max_depth: int = MAX_SCAN_DEPTH) -> dict[str, list[Path]]:
    """As :func:`scan_packages`, with every folder of each name, in the order found (two
    for a package copied within ``root``, which colcon refuses: :class:`Duplicate`)."""
    found: dict[str, list[Path]] = {}
    if not root.is_dir():
        return found
    stack: list[tuple[Path, int]] = [(root, 0)]
    visited = 0
    while stack and visited < MAX_SCAN_DIRS:
        folder, depth = stack.pop()
        visited += 1
        try:
            names = set(os.listdir(folder))
        except OSError:
            continue
        if names & {"COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE"}:
            continue
        if "package.xml" in names:
            name = package_name(folder / "package.xml")
            if name:
                found.setdefault(name, []).append(folder)
            continue
        if depth >= max_depth:
            continue
        for child in sorted(names, reverse=True):
            if child.startswith(".") or child in _SKIP_DIRS:
                continue
            path = folder / child
            if path.is_dir() and not path.is_symlink():
                stack.append((path, depth + 1))
    return found


def own_package(path: Path) -> Path | None:
    """The package folder holding ``path`` (nearest ancestor with a package.xml)."""
    path = path.resolve()  # a relative path has no parents to walk: same answer from any folder
    for folder in [path.parent, *path.parent.parents]:
        if (folder / "package.xml").is_file():
            return folder
    return None


def workspace_roots(path: Path) -> list[Path]:
    """Where to look for sibling packages of the file at ``path``.

    The nearest ancestor called ``src`` (a colcon workspace) if any; otherwise the
    package's parent and grandparent (a repository of packages, and the folder of
    repositories beside it), or the file's own folder when it is in no package.
    """
    path = path.resolve()
    pkg = own_package(path)
    start = pkg if pkg is not None else path.parent
    for folder in [start, *start.parents]:
        if folder.name == "src":
            return [folder]
    if pkg is None:
        return [path.parent]
    roots = [pkg]
    if pkg.parent != pkg:
        roots.append(pkg.parent)
        if pkg.parent.parent != pkg.parent:
            roots.append(pkg.parent.parent)
    return roots


def repository_of(path: Path) -> Path:
    """The repository of the file at ``path``: what an untrusted file may read within.

    The nearest enclosing git work tree (a folder holding ``.git``, a folder or a
    worktree's file), else the colcon workspace (the folder holding the nearest ``src/``
    above the file), else the file's package, else the file's own folder; never a folder
    above these. The file's folder is taken with its links resolved, the file's own name
    not: a symlinked input is in the repository its link sits in (and must point inside
    it: :meth:`PackageResolver.allows`).
    """
    folder = Path(_real(Path(path).absolute().parent))
    chain = [folder, *folder.parents]
    for at in chain:
        if os.path.lexists(at / ".git"):
            return at
    for at in chain:
        if at.name == "src" and at.parent != at:
            return at.parent
    for at in chain:
        if (at / "package.xml").is_file():
            return at
    return folder


def readable_area(
    path: Path, folders: Iterable[Path] = (), env: Mapping[str, str] | None = None
) -> list[str]:
    """The real folders an untrusted expansion of ``path`` may read (issue 36): its
    repository (:func:`repository_of`), the ``--package-path`` ``folders``, and the
    ``share`` folder of each ``AMENT_PREFIX_PATH`` prefix in ``env`` (os.environ when
    None). The one function resolution, includes, ``load_yaml``, meshes, textures, launch
    files, SDF includes and Landlock confine by; sibling-package heuristics
    (:func:`workspace_roots`) never widen it."""
    env = os.environ if env is None else env
    roots = [repository_of(path), *folders]
    roots += [Path(p) / "share" for p in env.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    return list(dict.fromkeys(_real(r) for r in roots))


def inside(real: str, roots: Iterable[str]) -> bool:
    """Whether the real path ``real`` is one of ``roots`` or below one."""
    return any(real == r or real.startswith(r.rstrip(os.sep) + os.sep) for r in roots)


# colcon refuses a workspace holding two packages of one name: get_packages raises
# "Duplicate package names not supported" (colcon/colcon-core@b37a8d4:
# colcon_core/package_selection/__init__.py:185-196), and a COLCON_IGNORE file makes it
# skip a folder (colcon_core/package_identification/ignore.py:11-15).
COLCON_DUPLICATE_SOURCE = "colcon/colcon-core@b37a8d4:colcon_core/package_selection/__init__.py:185-196"


@dataclass(frozen=True)
class Duplicate:
    """A package found twice or more in one folder searched (a workspace's ``src``, a
    ``--package-path DIR``, or the folders around a file in no workspace)."""

    name: str
    root: Path
    folders: tuple[Path, ...]
    used: Path
    own: bool  # ``used`` is the package holding the file being read
    workspace: bool  # ``root`` is what colcon builds: a ``src`` or a --package-path DIR


@dataclass
class PackageResolver:
    """Maps package names to folders; records every place it searched."""

    explicit: dict[str, Path] = field(default_factory=dict)
    scan_dirs: list[Path] = field(default_factory=list)
    use_environment: bool = True
    workspace_of: Path | None = None
    frozen_env: dict[str, str] | None = None
    confined: list[str] | None = None  # --untrusted: the real folders paths must lie in
    _cache: dict[str, Path | None] = field(default_factory=dict, repr=False)
    _scanned: dict[Path, dict[str, list[Path]]] = field(default_factory=dict, repr=False)

    @classmethod
    def from_options(
        cls, package_paths: Sequence[str] = (), *, near: Path | None = None, untrusted: bool = False
    ) -> PackageResolver:
        """Build a resolver from ``--package-path`` values (``NAME=DIR`` or ``DIR``).

        With no ``--package-path`` at all, the workspace around ``near`` is searched too.
        With ``untrusted`` and ``near``, the resolver is confined (:meth:`confine_to`).
        A ``NAME=DIR`` whose NAME cannot be a package name is a UsageError.
        """
        explicit: dict[str, Path] = {}
        scan: list[Path] = []
        for item in package_paths:
            name, sep, folder = item.partition("=")
            if sep and name and "/" not in name:
                if not valid_package_name(name):
                    from sensorkit.base.errors import UsageError

                    shown = repr(name[:80])
                    raise UsageError(f"--package-path {shown}=DIR: {shown} is not a package name")
                explicit[name] = Path(folder).expanduser().resolve()
            else:
                scan.append(Path(item).expanduser().resolve())
        resolver = cls(
            explicit=explicit,
            scan_dirs=scan,
            workspace_of=None if package_paths or near is None else near.resolve(),
        )
        if untrusted and near is not None:
            resolver.confine_to(near)
        return resolver

    def confine_to(self, near: Path) -> None:
        """Confine to :func:`readable_area` of ``near``: its repository, the
        ``--package-path`` folders and AMENT_PREFIX_PATH's share folders (``--untrusted``;
        the same folders an untrusted xacro expansion may read). A package found outside
        is not found."""
        env = self.frozen_env if self.frozen_env is not None else None
        self.confined = readable_area(near, [*self.explicit.values(), *self.scan_dirs], env)

    def area(self) -> list[str]:
        """The real folders a confined resolver allows (empty when not confined)."""
        return list(self.confined or ())

    def allows(self, path: Path) -> bool:
        """Whether ``path`` may be opened or named: always when not confined, else only
        inside an allowed folder (real paths: symlinks and ``..`` resolved)."""
        if self.confined is None:
            return True
        return inside(_real(path), self.confined)

    def for_file(self, path: Path) -> PackageResolver:
        """The same resolver, searching the workspace around ``path`` when allowed."""
        if self.explicit or self.scan_dirs:
            return self
        other = PackageResolver(
            explicit=dict(self.explicit),
            scan_dirs=list(self.scan_dirs),
            use_environment=self.use_environment,
            workspace_of=path.resolve(),
            frozen_env=self.frozen_env,
        )
        if self.confined is not None:
            other.confine_to(path)
        return other

    def _scan(self, root: Path, max_depth: int = MAX_SCAN_DEPTH) -> dict[str, list[Path]]:
        if root not in self._scanned:
            self._scanned[root] = scan_all(root, max_depth=max_depth)
        return self._scanned[root]

    def freeze_environment(self) -> None:
        """Remember the package path variables now (before an untrusted child drops them)."""
        self.frozen_env = {v: os.environ.get(v, "") for v in ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH")}

    def _env_paths(self, var: str) -> list[Path]:
        if not self.use_environment:
            return []
        env = self.frozen_env if self.frozen_env is not None else os.environ
        return [Path(p) for p in env.get(var, "").split(os.pathsep) if p]

    def _workspace(self) -> list[Path]:
        return workspace_roots(self.workspace_of) if self.workspace_of is not None else []

    def searched(self) -> list[str]:
        """Human-readable list of every place searched, in order."""
        places = [f"--package-path {n}={p}" for n, p in self.explicit.items()]
        places += [f"--package-path {p}" for p in self.scan_dirs]
        places += [f"AMENT_PREFIX_PATH {p}/share" for p in self._env_paths("AMENT_PREFIX_PATH")]
        places += [f"ROS_PACKAGE_PATH {p}" for p in self._env_paths("ROS_PACKAGE_PATH")]
        places += [f"workspace {p}" for p in self._workspace()]
        if not places:
            places.append("nowhere: pass --package-path DIR or NAME=DIR")
        return places

    def find(self, name: str) -> Path | None:
        """The folder of package ``name``, or None (also for what cannot be a package name:
        ``..``, an absolute path). A confined resolver finds only packages inside its area."""
        if name in self._cache:
            return self._cache[name]
        result = self._find(name) if valid_package_name(name) else None
        if result is not None and not self.allows(result):
            result = None  # --untrusted: a package outside the readable area is not found
        self._cache[name] = result
        return result

    def _find(self, name: str) -> Path | None:
        hit = self._where(name)
        return hit[0] if hit is not None else None

    def _where(self, name: str) -> tuple[Path, Path | None, bool] | None:
        """(folder of ``name``, the scanned root it was found in or None, whether that
        root is what colcon builds)."""
        if name in self.explicit:
            return self.explicit[name], None, False
        for root in self.scan_dirs:
            hits = self._scan(root).get(name)
            if hits:
                return hits[0], root, True
        for prefix in self._env_paths("AMENT_PREFIX_PATH"):
            share = prefix / "share" / name
            if (share / "package.xml").is_file() or share.is_dir():
                return share, None, False  # an overlay: the first prefix wins, by design
        for root in self._env_paths("ROS_PACKAGE_PATH"):
            hits = self._scan(root).get(name)
            if hits:
                return hits[0], None, False
        own = self._own()
        for root in self._workspace():
            hits = self._scan(root, max_depth=3).get(name)
            if hits:
                # the package holding the file is the copy it means (its own includes)
                first = own if own is not None and own in hits else hits[0]
                return first, root, root.name == "src"
        return None

    def _own(self) -> Path | None:
        if self.workspace_of is None:
            return None
        own = own_package(self.workspace_of)
        return own.resolve() if own is not None else None

    def duplicate(self, name: str) -> Duplicate | None:
        """The copies of package ``name`` in the one folder searched that gave it, when
        there are two or more (colcon refuses such a workspace: COLCON_DUPLICATE_SOURCE);
        None when it has one, or came from ``NAME=DIR`` or an install prefix."""
        where = self._where(name) if valid_package_name(name) else None
        if where is None or where[1] is None or (found := self.find(name)) is None:
            return None
        folders = self._scanned[where[1]][name]  # scanned by _where
        if len(folders) < 2:
            return None
        return Duplicate(name, where[1], tuple(folders), found, found == self._own(), where[2])

    def known(self) -> Iterable[str]:
        """Names found so far (for messages)."""
        return sorted(k for k, v in self._cache.items() if v is not None)
