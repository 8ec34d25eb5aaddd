"""The expansion cache: a xacro robot that has not changed is not expanded again.

An entry is found by what the expansion was asked (sensorkit's and xacro's code, the
Python version, the absolute top file, the args) and holds what it gave (the XML, the
files it read in order, the includes) with everything it read
(``sensorkit.loading.reads.ExpandDeps``). A lookup is a hit only if every one of those
reads still gives what it gave: each file's bytes hash the same (read from the overlay
where it holds the file), each include glob matches the same files, each environment
variable has the same value (or is still unset), each ``$(find pkg)`` resolves to the
same folder with the resolver at hand, and the working folder is the same where it
mattered. An expansion that used something that cannot be checked so (see
``reads``) is not stored, nor is a failed one, nor any under ``--untrusted``
(``load_description`` neither looks up nor stores then).

Two stores behind one interface (``get`` / ``put``): ``MemoryCache`` for a process that
validates again and again (an editor server), ``DiskCache`` under
``$XDG_CACHE_HOME/sensorkit`` (default ``~/.cache/sensorkit``) for the CLI. Any problem
with the cache (a file unreadable, corrupt, truncated or of another format, a full disk,
a read-only folder) is a miss, never an error: the robot is then expanded as without a
cache, and the output is the same byte for byte.
"""

from __future__ import annotations

import contextlib
import glob
import hashlib
import hmac
import json
import os
import sys
from collections import OrderedDict
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.reads import ExpandDeps, digest

if TYPE_CHECKING:  # the expander loads when a robot is expanded (a plain URDF never is)
    from sensorkit.loading.xacro_expand import ExpandOutcome

FORMAT = 2  # of a disk entry; another is a miss (1: a plain hash, no MAC)
MAX_DISK_BYTES = 64 * 1024**2  # the disk store's bound: the least recently used go first
MAX_MEMORY_ENTRIES = 256
_MAGIC = b"sensorkit-expansion"


@dataclass
class Entry:
    """One stored expansion: what it read and what it gave."""

    deps: ExpandDeps
    xml: str
    files: list[str]
    includes: list[str]


class ExpansionCache:
    """Looks up and stores expansions; subclasses say where entries live (``get``/``put``)."""

    def get(self, key: str) -> Entry | None:
        raise NotImplementedError

    def put(self, key: str, entry: Entry) -> None:
        raise NotImplementedError

    def lookup(
        self,
        path: Path,
        args: Mapping[str, str],
        resolver: PackageResolver,
        overlay: Mapping[str, bytes] | None = None,
    ) -> ExpandOutcome | None:
        """The stored expansion of ``path`` with ``args`` if everything it read still
        holds, else None (also on any problem with the cache)."""
        try:
            entry = self.get(cache_key(path, args))
            if entry is None or not still_holds(entry.deps, resolver, overlay):
                return None
            from sensorkit.loading.xacro_expand import ExpandOutcome

            return ExpandOutcome(
                xml=entry.xml,
                files=list(entry.files),
                includes=list(entry.includes),
                deps=entry.deps,
            )
        except Exception:  # a cache must never be why a robot cannot be checked
            return None

    def store(self, path: Path, args: Mapping[str, str], outcome: ExpandOutcome) -> None:
        """Keep a successful, replayable expansion (anything else is left out)."""
        deps = outcome.deps
        if outcome.error_kind is not None or outcome.xml is None:
            return
        if deps is None or not deps.cacheable:
            return
        entry = Entry(deps, outcome.xml, list(outcome.files), list(outcome.includes))
        with contextlib.suppress(Exception):
            self.put(cache_key(path, args), entry)


def still_holds(
    deps: ExpandDeps, resolver: PackageResolver, overlay: Mapping[str, bytes] | None
) -> bool:
    """Whether every read in ``deps`` gives what it gave (cheapest checks first)."""
    if not deps.cacheable:
        return False
    if deps.cwd is not None and os.getcwd() != deps.cwd:
        return False
    if any(os.environ.get(name) != value for name, value in deps.env.items()):
        return False
    if any(sorted(glob.glob(p)) != names for p, names in deps.globs.items()):
        return False
    for name, folder in deps.packages.items():
        hit = resolver.find(name)
        if (None if hit is None else str(hit)) != folder:
            return False
    return all(_file_digest(p, overlay) == d for p, d in deps.files.items())


def _file_digest(path: str, overlay: Mapping[str, bytes] | None) -> str | None:
    if overlay and path in overlay:
        return digest(overlay[path])
    try:
        with open(path, "rb") as f:
            return digest(f.read())
    except OSError:
        return None


_CODE: list[Any] = []  # the signature of the code an expansion runs, once per process


def _code_signature() -> list[Any]:
    """sensorkit's version and the files of the code that expands (xacro, yaml, the
    loader): an upgrade, or an edit of a development checkout, starts afresh."""
    if not _CODE:
        import importlib.util

        import sensorkit

        here = Path(__file__).parent
        files = [
            here / n
            for n in ("xacro_expand.py", "xacro_fast.py", "reads.py", "marks.py", "cache.py")
        ]
        for name in ("xacro", "yaml"):
            spec = importlib.util.find_spec(name)
            for folder in (spec.submodule_search_locations or []) if spec else []:
                files += sorted(Path(folder).glob("*.py"))
        stats = []
        for f in files:
            try:
                st = f.stat()
                stats.append([str(f), st.st_size, st.st_mtime_ns])
            except OSError:
                stats.append([str(f), None, None])
        _CODE.extend([sensorkit.__version__, sys.version, stats])
    return _CODE


def cache_key(path: Path, args: Mapping[str, str]) -> str:
    """The name of the entry for ``path`` expanded with ``args`` (see the module doc)."""
    what = [FORMAT, _code_signature(), os.path.abspath(path), sorted(args.items())]
    return hashlib.sha256(json.dumps(what).encode("utf-8")).hexdigest()


class MemoryCache(ExpansionCache):
    """Entries kept in this process, the least recently used dropped past ``limit``."""

    def __init__(self, limit: int = MAX_MEMORY_ENTRIES) -> None:
        self.limit = limit
        self.entries: OrderedDict[str, Entry] = OrderedDict()

    def get(self, key: str) -> Entry | None:
        entry = self.entries.get(key)
        if entry is not None:
            self.entries.move_to_end(key)
        return entry

    def put(self, key: str, entry: Entry) -> None:
        self.entries[key] = entry
        self.entries.move_to_end(key)
        while len(self.entries) > self.limit:
            self.entries.popitem(last=False)


def default_folder() -> Path:
    """``$XDG_CACHE_HOME/sensorkit`` (an absolute XDG_CACHE_HOME), else ``~/.cache/sensorkit``."""
    base = os.environ.get("XDG_CACHE_HOME", "")
    root = Path(base) if os.path.isabs(base) else Path.home() / ".cache"
    return root / "sensorkit"


class DiskCache(ExpansionCache):
    """Entries in files of ``folder/expansions`` (default: ``default_folder()``), each
    written whole (a temporary file renamed into place) and checked by a keyed MAC on
    reading; past ``limit`` bytes in all, the least recently used go first.

    Only its owner writes it (issue 36): the folders must be the user's and not group-
    or world-writable, else the cache is not used (:attr:`problem` says why, once: the
    CLI prints it); each entry carries a MAC keyed by a random per-user key kept in the
    folder (``key``, mode 0600), so an entry anyone else wrote or edited is a miss."""

    def __init__(self, folder: Path | None = None, limit: int = MAX_DISK_BYTES) -> None:
        self.root = folder if folder is not None else default_folder()
        self.folder = self.root / "expansions"
        self.limit = limit
        self._key: bytes | None = None
        self.problem: str | None = None  # why the cache is not used, once found

    def _file(self, key: str) -> Path:
        return self.folder / f"{key}.json"

    def usable(self, create: bool = False) -> bool:
        """Whether the folders are safe to use (made, mode 0700, with ``create``) and the
        key is read; sets :attr:`problem` when they are not."""
        if self._key is not None:
            return True
        if self.problem is not None:
            return False
        if not create and not self.root.exists():
            return False
        try:
            for folder in (self.root, self.folder):
                if create:
                    folder.mkdir(mode=0o700, parents=True, exist_ok=True)
                self.problem = unsafe_folder(folder)
                if self.problem is not None:
                    return False
            self._key = _read_key(self.root / "key", create)
        except OSError as exc:
            if not create:
                return False  # nothing stored yet (or unreadable): a miss, nothing to say
            self.problem = f"{self.root}: {exc.strerror or exc}"
            return False
        if self._key is None:
            self.problem = f"{self.root / 'key'}: not a private file of this user (mode 0600)"
        return self._key is not None

    def get(self, key: str) -> Entry | None:
        if not self.usable():
            return None
        path = self._file(key)
        try:
            data = path.read_bytes()
        except OSError:
            return None
        assert self._key is not None
        entry = _decode(data, self._key)
        if entry is not None:
            with contextlib.suppress(OSError):
                os.utime(path)  # recently used: pruned last
        return entry

    def put(self, key: str, entry: Entry) -> None:
        import tempfile

        if not self.usable(create=True):
            return
        assert self._key is not None
        data = _encode(entry, self._key)
        if len(data) > self.limit // 4:
            return  # one entry may not push out most of the others
        fd, tmp = tempfile.mkstemp(dir=self.folder, prefix=f".{key[:16]}.", suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            os.replace(tmp, self._file(key))
        except BaseException:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
            raise
        self.prune()

    def prune(self) -> None:
        """Remove the least recently used entries while the folder holds over ``limit``
        bytes, and temporary files a killed writer left over an hour ago."""
        import time

        found: list[tuple[float, int, Path]] = []
        total = 0
        for item in self.folder.iterdir():
            try:
                st = item.stat()
            except OSError:
                continue
            if item.name.endswith(".tmp"):
                if st.st_mtime < time.time() - 3600:
                    with contextlib.suppress(OSError):
                        item.unlink()
                continue
            found.append((st.st_mtime, st.st_size, item))
            total += st.st_size
        for _, size, item in sorted(found):
            if total <= self.limit:
                break
            with contextlib.suppress(OSError):
                item.unlink()
            total -= size


def unsafe_folder(folder: Path) -> str | None:
    """Why ``folder`` may not hold the cache (not a folder, another user's, writable by
    the group or others), or None. Its links resolved: the folder itself is checked."""
    import stat

    st = os.stat(folder)
    if not stat.S_ISDIR(st.st_mode):
        return f"{folder}: not a folder"
    if hasattr(os, "getuid") and st.st_uid != os.getuid():
        return f"{folder}: owned by another user"
    if st.st_mode & 0o022:
        return f"{folder}: writable by the group or others (mode {stat.S_IMODE(st.st_mode):o})"
    return None


def _read_key(path: Path, create: bool) -> bytes | None:
    """The MAC key at ``path`` (32 random bytes, made with mode 0600 when ``create``, else
    FileNotFoundError), or None when the file there is not a private regular file of
    this user."""
    import stat

    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_CLOEXEC)
    except FileNotFoundError:
        if not create:
            raise
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o600)
        os.write(fd, os.urandom(32))
        os.lseek(fd, 0, os.SEEK_SET)
    try:
        st = os.fstat(fd)
        private = stat.S_ISREG(st.st_mode) and not st.st_mode & 0o077
        if not private or (hasattr(os, "getuid") and st.st_uid != os.getuid()):
            return None
        key = os.read(fd, 64)
        return key if len(key) == 32 else None
    finally:
        os.close(fd)


def _mac(key: bytes, payload: bytes) -> bytes:
    return hashlib.blake2b(payload, key=key, digest_size=32).hexdigest().encode()


def _encode(entry: Entry, key: bytes) -> bytes:
    payload = json.dumps(asdict(entry), separators=(",", ":")).encode("utf-8")
    return b"%s %d %s\n" % (_MAGIC, FORMAT, _mac(key, payload)) + payload


def _decode(data: bytes, key: bytes) -> Entry | None:
    """The entry in ``data``, or None when it is not one whole entry of this format whose
    MAC under ``key`` holds (an entry written or edited by anyone without the key)."""
    head, _, payload = data.partition(b"\n")
    parts = head.split(b" ")
    if len(parts) != 3 or parts[0] != _MAGIC or parts[1] != str(FORMAT).encode():
        return None
    if not hmac.compare_digest(_mac(key, payload), parts[2]):
        return None
    try:
        raw = json.loads(payload)
        deps = ExpandDeps(**raw["deps"])
        entry = Entry(deps, raw["xml"], raw["files"], raw["includes"])
    except (ValueError, TypeError, KeyError, RecursionError):
        return None
    ok = (
        isinstance(entry.xml, str)
        and _strings(entry.files)
        and _strings(entry.includes)
        and isinstance(deps.files, dict)
        and isinstance(deps.globs, dict)
        and isinstance(deps.env, dict)
        and isinstance(deps.packages, dict)
        and deps.cacheable is True
    )
    return entry if ok else None


def _strings(items: object) -> bool:
    return isinstance(items, list) and all(isinstance(i, str) for i in items)
