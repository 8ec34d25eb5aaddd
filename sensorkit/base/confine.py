"""Confining a forked child: it dies with its parent, has limits, and reads only named folders.

Each helper does what the platform offers and nothing elsewhere (never an error):

- :func:`die_with_parent`: Linux ``prctl(PR_SET_PDEATHSIG, SIGKILL)``, so a child never
  outlives a parent killed with SIGKILL (a CI timeout, the OOM killer), plus a check
  that the parent is still the one that forked it (it may have died before the call);
- :func:`limit_resources`: ``RLIMIT_AS`` (as growth over what the child inherited),
  ``RLIMIT_CPU`` (so a child stops on its own, whatever happens to its parent) and
  ``RLIMIT_FSIZE``; limits are only ever lowered;
- :func:`wipe_initial_environment`: zero the environment block the process was started
  with (``/proc/self/environ`` and the memory behind it), after ``os.environ`` is cleared;
- :func:`restrict_reads`: Landlock (Linux >= 5.13): from then on the process opens files
  only below the given paths and only to read them; it writes, creates, removes and runs
  nothing, connects nowhere over TCP (Landlock ABI >= 4) and signals no process outside
  itself (ABI >= 6). False where the kernel has no Landlock: nothing is restricted then.

The Landlock numbers are the kernel's UAPI (include/uapi/linux/landlock.h; the system
calls are 444, 445 and 446 on every architecture that uses the generic table, x86_64
and aarch64 included).
"""

from __future__ import annotations

import contextlib
import os
import signal
import stat
import sys
from collections.abc import Iterable
from functools import lru_cache
from typing import Any

PR_SET_PDEATHSIG = 1
PR_SET_NO_NEW_PRIVS = 38
SYS_LANDLOCK_CREATE_RULESET = 444
SYS_LANDLOCK_ADD_RULE = 445
SYS_LANDLOCK_RESTRICT_SELF = 446
LANDLOCK_CREATE_RULESET_VERSION = 1
LANDLOCK_RULE_PATH_BENEATH = 1
READ_FILE = 1 << 2
READ_DIR = 1 << 3
FS_ABI1 = (1 << 13) - 1  # execute .. make_sym: every right of ABI 1
FS_REFER = 1 << 13  # ABI 2
FS_TRUNCATE = 1 << 14  # ABI 3
FS_IOCTL_DEV = 1 << 15  # ABI 5
NET_TCP = 1 | 2  # bind, connect (ABI 4)
SCOPES = 1 | 2  # abstract unix sockets, signals (ABI 6)


@lru_cache(maxsize=1)
def _libc() -> Any:
    """The C library through ctypes, or None (not Linux, or no ctypes)."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.syscall.restype = ctypes.c_long
        return libc
    except (ImportError, OSError, AttributeError):
        return None


def _long(value: int) -> Any:
    import ctypes

    return ctypes.c_long(value)


def preload() -> None:
    """Load what the helpers use, before forking (each child then has it already)."""
    _libc()
    with contextlib.suppress(ImportError):
        import resource  # noqa: F401


def die_with_parent(parent: int) -> None:
    """In a child just forked from ``parent``: be killed when the parent dies."""
    libc = _libc()
    if libc is not None:
        import ctypes

        libc.prctl(PR_SET_PDEATHSIG, ctypes.c_ulong(signal.SIGKILL), _long(0), _long(0), _long(0))
    if os.getppid() != parent:  # the parent died before prctl: nobody waits for us
        os._exit(1)


def _rlimit(kind: int, value: int) -> None:
    import resource

    _soft, hard = resource.getrlimit(kind)
    if hard != resource.RLIM_INFINITY:
        value = min(value, hard)
    with contextlib.suppress(ValueError, OSError):
        resource.setrlimit(kind, (value, value if kind != resource.RLIMIT_CPU else hard))


def limit_resources(
    *,
    memory_growth: int | None = None,
    cpu_seconds: float | None = None,
    file_size: int | None = None,
) -> None:
    """Lower this process's limits: address space to what it has plus ``memory_growth``,
    CPU time to ``cpu_seconds`` (SIGXCPU, then SIGKILL 2 s later), files it writes to
    ``file_size`` bytes (a longer write fails with EFBIG instead of killing it)."""
    try:
        import resource
    except ImportError:
        return
    if memory_growth is not None:
        _rlimit(resource.RLIMIT_AS, _address_space() + memory_growth)
    if cpu_seconds is not None:
        seconds = max(1, int(cpu_seconds + 0.999))
        with contextlib.suppress(ValueError, OSError):
            _soft, hard = resource.getrlimit(resource.RLIMIT_CPU)
            if hard == resource.RLIM_INFINITY or hard > seconds + 2:
                hard = seconds + 2
            resource.setrlimit(resource.RLIMIT_CPU, (min(seconds, hard), hard))
    if file_size is not None:
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        _rlimit(resource.RLIMIT_FSIZE, file_size)


def _address_space() -> int:
    """Bytes of address space this process holds now (0 where unknown)."""
    try:
        with open("/proc/self/statm", "rb") as f:
            pages = int(f.read().split()[0])
        return pages * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def wipe_initial_environment() -> None:
    """Zero the environment block this process was started with (after ``os.environ``
    holds only what it may keep): ``os.environ`` keeps its own copies, and each kept
    name is set again so that C's ``getenv`` sees it too."""
    libc = _libc()
    if libc is None:
        return
    import ctypes

    try:
        with open("/proc/self/stat", "rb") as f:
            fields = f.read().rsplit(b")", 1)[1].split()
        start, end = int(fields[47]), int(fields[48])  # env_start, env_end (proc(5))
    except (OSError, ValueError, IndexError):
        return
    if 0 < start < end:
        ctypes.memset(start, 0, end - start)
        for name, value in os.environb.items():
            os.putenv(name, value)


def landlock_abi() -> int:
    """The kernel's Landlock ABI version, 0 where there is none."""
    libc = _libc()
    if libc is None:
        return 0
    abi = int(
        libc.syscall(
            _long(SYS_LANDLOCK_CREATE_RULESET),
            None,
            _long(0),
            _long(LANDLOCK_CREATE_RULESET_VERSION),
        )
    )
    return max(abi, 0)


def restrict_reads(paths: Iterable[str | os.PathLike[str]]) -> bool:
    """Landlock this process: read-only below ``paths``, nothing else (see the module doc).

    Irreversible, and inherited by every process it forks. False, restricting nothing,
    where the kernel has no Landlock or refuses the ruleset.
    """
    abi = landlock_abi()
    if abi < 1:
        return False
    import ctypes

    libc = _libc()

    class RulesetAttr(ctypes.Structure):
        _fields_ = [("fs", ctypes.c_uint64), ("net", ctypes.c_uint64), ("scoped", ctypes.c_uint64)]

    class PathBeneath(ctypes.Structure):
        _pack_ = 1
        _fields_ = [("allowed", ctypes.c_uint64), ("parent_fd", ctypes.c_int32)]

    fs = FS_ABI1 | (FS_REFER if abi >= 2 else 0) | (FS_TRUNCATE if abi >= 3 else 0)
    fs |= FS_IOCTL_DEV if abi >= 5 else 0
    attr = RulesetAttr(fs, NET_TCP if abi >= 4 else 0, SCOPES if abi >= 6 else 0)
    size = 24 if abi >= 6 else 16 if abi >= 4 else 8
    ruleset = int(
        libc.syscall(_long(SYS_LANDLOCK_CREATE_RULESET), ctypes.byref(attr), _long(size), _long(0))
    )
    if ruleset < 0:
        return False
    try:
        for path in dict.fromkeys(os.fspath(p) for p in paths):
            _allow(libc, ruleset, path, PathBeneath)
        if libc.prctl(PR_SET_NO_NEW_PRIVS, _long(1), _long(0), _long(0), _long(0)) != 0:
            return False
        return int(libc.syscall(_long(SYS_LANDLOCK_RESTRICT_SELF), _long(ruleset), _long(0))) == 0
    finally:
        os.close(ruleset)


def _allow(libc: Any, ruleset: int, path: str, rule_type: Any) -> None:
    """Let ``ruleset`` read ``path`` (a folder: everything below it); skip what is missing."""
    import ctypes

    try:
        fd = os.open(path, os.O_PATH | os.O_CLOEXEC)
    except OSError:
        return
    try:
        is_dir = stat.S_ISDIR(os.fstat(fd).st_mode)
        rule = rule_type(READ_FILE | (READ_DIR if is_dir else 0), fd)
        libc.syscall(
            _long(SYS_LANDLOCK_ADD_RULE),
            _long(ruleset),
            _long(LANDLOCK_RULE_PATH_BENEATH),
            ctypes.byref(rule),
            _long(0),
        )
    finally:
        os.close(fd)
