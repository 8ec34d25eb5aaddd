"""Atomic publication: a reader sees the old file (or folder) or the new one, never half.

One place for every write sensorkit makes: the user's robot files (``add-*``), exported
configs, preview images, and whole generated folders (``new``, ``export``).
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import shutil
import stat
import tempfile
import threading
from collections.abc import Iterable, Iterator
from pathlib import Path

from sensorkit.base.errors import UsageError, WriteFailed

__all__ = [
    "check_editable",
    "check_replaceable",
    "check_writable_out",
    "editing",
    "medium_failed",
    "staged_folder",
    "sweep",
    "tidy_beside",
    "write_bytes",
    "write_text",
]

# Errors of the medium, not of the request: disk full, quota, file too large, I/O.
_WRITE_ERRNOS = {errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EIO, errno.EROFS}
LOCK_WAIT_S = 60.0  # how long a second writer waits for the first before giving up

# Every temporary file and staging folder carries its writer's pid ("sk<pid>-"), so any
# later writer can tell one a killed run left (its pid is gone) from a live writer's.
_TEMP_SUFFIX = ".sensorkit-tmp"
_OWNED = re.compile(r"\.sk(\d+)-[^.]*\.sensorkit-tmp\Z")
_swept: set[str] = set()  # folders this process has swept already (write_bytes)
_held = threading.local()  # folders whose editing lock this thread holds (re-entrant)


def _alive(pid: int) -> bool:
    """Whether process ``pid`` exists (one of another user's counts: it may be a writer)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True
    return True


def sweep(folder: str | os.PathLike[str], *, locked: bool = False) -> None:
    """Remove the ``.*.sensorkit-tmp`` files a killed writer left in ``folder``.

    A temporary file whose writer's pid (in its name) is gone is removed. One without a
    pid (an older sensorkit's) is removed only by a caller holding the folder lock of
    :func:`editing` (``locked``): then no locking writer is live there. A live writer's
    file is never touched.
    """
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        if not (name.startswith(".") and name.endswith(_TEMP_SUFFIX)):
            continue
        owned = _OWNED.search(name)
        if (owned is None and locked) or (owned is not None and not _alive(int(owned.group(1)))):
            with contextlib.suppress(OSError):
                os.unlink(os.path.join(folder, name))


def medium_failed(
    exc: OSError, what: Path, unchanged: str = "it is unchanged"
) -> WriteFailed | None:
    """A one-line WriteFailed naming the user's ``what`` for a full disk, quota, file too
    large, read-only file system or I/O error (never the temporary name); else None."""
    if exc.errno not in _WRITE_ERRNOS:
        return None
    return WriteFailed(f"{what}: could not be written ({os.strerror(exc.errno or 0)}); {unchanged}")


def _umask() -> int:
    old = os.umask(0o022)
    os.umask(old)
    return old


def write_bytes(path: Path, data: bytes, *, mode: int | None = None, fsync: bool = True) -> None:
    """Write ``data`` to ``path`` through a temporary file in its folder and ``os.replace``.

    ``mode=None`` keeps an existing file's permission bits (a new file gets 0o666 less the
    umask). A symlink is followed, so the link itself survives. ``fsync`` makes the data
    and the rename durable (the default for users' files; generated outputs may skip it).
    The temporary file is removed if anything fails. The folder must exist. The first
    write of a process into a folder removes the temporary files killed writers left there
    (:func:`sweep`).
    """
    real = Path(os.path.realpath(path))
    if str(real.parent) not in _swept:
        sweep(real.parent)
        _swept.add(str(real.parent))
    if mode is None:
        try:
            mode = real.stat().st_mode
        except FileNotFoundError:
            mode = 0o666 & ~_umask()
    try:
        prefix = f".{real.name}.sk{os.getpid()}-"
        fd, tmp = tempfile.mkstemp(dir=real.parent, prefix=prefix, suffix=_TEMP_SUFFIX)
    except OSError as exc:  # a read-only or full folder: say so of the user's file
        why = os.strerror(exc.errno or 0)
        msg = f"{path}: cannot write in its folder {real.parent} ({why}); nothing was written"
        raise WriteFailed(msg) from None
    try:
        with os.fdopen(fd, "wb") as out:
            out.write(data)
            if fsync:
                out.flush()
                os.fsync(out.fileno())
        os.chmod(tmp, stat.S_IMODE(mode))
        _keep_owner(real, tmp)
        os.replace(tmp, real)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        failed = medium_failed(exc, path) if isinstance(exc, OSError) else None
        if failed is not None:
            raise failed from None  # name the user's file, never the temporary one
        raise
    if fsync:
        with contextlib.suppress(OSError):  # make the rename itself durable where possible
            dir_fd = os.open(real.parent, os.O_RDONLY)
            try:
                os.fsync(dir_fd)
            finally:
                os.close(dir_fd)


def _keep_owner(real: Path, tmp: str) -> None:
    """As root, give the new file the old one's owner and group (else it becomes root's)."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        return
    try:
        st = real.stat()
    except FileNotFoundError:
        return
    os.chown(tmp, st.st_uid, st.st_gid)


def check_editable(path: Path) -> None:
    """Refuse to edit a file in place that an editor would not touch silently.

    A file (or folder) without its owner's write permission (0444: what ``chmod a-w``
    means, even to root) and a hard-linked file (replacing it would split the links: the other names
    keep the old content) are refused with a one-line reason. A symlink is fine: its
    target is edited and the link stays a link.
    """
    real = Path(os.path.realpath(path))
    if real.is_dir():
        msg = f"{path} is a folder; name the URDF or xacro file in it to edit"
        raise UsageError(msg)
    try:
        folder = real.parent.stat()
    except FileNotFoundError:
        return
    if not folder.st_mode & stat.S_IWUSR:
        msg = (
            f"{path}: its folder {real.parent} is not writable (read-only, mode "
            f"{stat.S_IMODE(folder.st_mode):o}); nothing was written: make it writable "
            "(chmod u+w)"
        )
        raise UsageError(msg)
    try:
        st = real.stat()
    except FileNotFoundError:
        return
    if not st.st_mode & stat.S_IWUSR:
        msg = (
            f"{path}: is read-only (mode {stat.S_IMODE(st.st_mode):o}); nothing was written: "
            "make it writable (chmod u+w)"
        )
        raise UsageError(msg)
    if st.st_nlink > 1:
        msg = (
            f"{path}: has {st.st_nlink} hard links; editing it would leave the other names "
            "with the old content, so nothing was written (edit a copy, or use -o)"
        )
        raise UsageError(msg)


@contextlib.contextmanager
def editing(*paths: Path, wait_s: float = LOCK_WAIT_S) -> Iterator[None]:
    """Hold an advisory lock on the folders of ``paths`` from reading to the last rename.

    Two sensorkit writers on one file take turns: the second waits (at most ``wait_s``),
    then reads what the first wrote, so no update is lost. The lock is ``flock`` on the
    folder itself, which has a stable inode (the file's is replaced by every write) and
    leaves nothing behind. Folders are locked in sorted order (no two writers wait on each
    other), and a folder this thread already holds is not locked again (a nested
    ``editing`` of it is a no-op). Stale ``*.sensorkit-tmp`` files a killed run left there
    are removed once the lock is held (:func:`sweep`).
    """
    held: set[str] = _held.__dict__.setdefault("folders", set())
    folders = sorted({os.path.realpath(Path(p).parent) for p in paths} - held)
    fds: list[int] = []
    try:
        for folder in folders:
            fds.append(_lock(folder, wait_s))
            held.add(folder)
            sweep(folder, locked=True)
        yield
    finally:
        for folder, fd in zip(folders, fds, strict=False):
            held.discard(folder)
            os.close(fd)  # closing releases the flock


def _lock(folder: str, wait_s: float) -> int:
    """An open descriptor of ``folder`` holding its exclusive flock."""
    import fcntl
    import time

    fd = os.open(folder, os.O_RDONLY)
    deadline = time.monotonic() + wait_s
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return fd
        except BlockingIOError:
            if time.monotonic() > deadline:
                os.close(fd)
                msg = f"{folder}: another sensorkit is still writing there after {wait_s:g} s; try again"
                raise UsageError(msg) from None
            time.sleep(0.02)


def write_text(
    path: str | os.PathLike[str], text: str, *, encoding: str = "utf-8", fsync: bool = True
) -> None:
    """``write_bytes`` for text (no newline translation: ``text`` is written as given)."""
    write_bytes(Path(path), text.encode(encoding), fsync=fsync)


def check_replaceable(
    out: Path, *, force: bool, inputs: Iterable[Path] = (), flag: str = "--out"
) -> None:
    """Refuse an output folder that is a file, non-empty without ``force``, or precious.

    A folder that would be replaced whole must not be the working folder, one of its
    ancestors, the home folder or a file system root, nor hold any of ``inputs``.
    """
    if out.exists() and not out.is_dir():
        msg = f"{out}: exists and is not a folder"
        raise UsageError(msg)
    resolved = out.resolve()
    cwd = Path.cwd().resolve()
    if resolved in {cwd, Path.home().resolve(), Path(resolved.anchor)} or resolved in cwd.parents:
        msg = f"{out}: refusing to write into this folder (it would be replaced whole); choose a subfolder"
        raise UsageError(msg)
    if not out.is_dir() or not any(out.iterdir()):
        return
    if not force:
        msg = f"{out}: folder is not empty; choose another {flag} or pass --force to replace it"
        raise UsageError(msg)
    for path in inputs:
        if resolved in path.resolve().parents:
            msg = f"{out}: holds {path.name}; --force would delete it, choose another {flag}"
            raise UsageError(msg)


@contextlib.contextmanager
def staged_folder(out: Path, *, publish: bool = True) -> Iterator[Path]:
    """Yield an empty folder beside ``out`` to fill; on success it replaces ``out`` whole.

    On an exception (or with ``publish=False``) the staging folder is deleted and ``out``
    is untouched; a full disk or I/O error names ``out`` in one line (WriteFailed). Folders
    get the usual 0o777 less the umask. The folder lock of :func:`editing` is held on
    ``out``'s parent throughout (a caller may hold it already, to read its inputs under
    it); once it is held, what a killed writer of ``out`` left beside it is tidied (see
    :func:`tidy_beside`).

    A symlink ``out`` stays a symlink: its target folder is the one replaced (renaming
    the link itself would swap the link for a folder and leave the target stale).
    """
    if out.is_symlink():
        out = Path(os.path.realpath(out))
    check_writable_out(out)
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
    except PermissionError:
        raise UsageError(_not_writable(_existing_ancestor(out.parent))) from None
    with editing(out):  # two writers of one folder take turns (new, export, render preview)
        tidy_beside(out)
        try:
            yield from _staged(out, publish)
        except OSError as exc:
            failed = medium_failed(exc, out, "nothing was written there")
            if failed is None:
                raise
            raise failed from None


def _existing_ancestor(path: Path) -> Path:
    while not path.exists() and path.parent != path:
        path = path.parent
    return path


def _not_writable(folder: Path) -> str:
    try:
        mode = f" (mode {stat.S_IMODE(folder.stat().st_mode):o})"
    except OSError:
        mode = ""
    return f"{folder} is not writable{mode}; nothing was written"


def check_writable_out(out: Path) -> None:
    """Refuse an output folder ``out`` that cannot be written, naming the folder at fault
    in one line (UsageError "FOLDER is not writable"): ``out`` itself when it exists, else
    the nearest existing folder above it, which the staging folder or ``mkdir`` needs.
    As for :func:`check_editable`, a folder without its owner's write permission counts
    as not writable even to root (what ``chmod a-w`` means)."""
    folders = [out] if out.is_dir() else []
    folders.append(_existing_ancestor(out.parent))
    for folder in folders:
        try:
            mode = folder.stat().st_mode
        except OSError:
            continue
        if not mode & stat.S_IWUSR or not os.access(folder, os.W_OK):
            raise UsageError(_not_writable(folder))


def tidy_beside(out: Path) -> None:
    """Under the lock of :func:`editing` on ``out``'s parent, every ``.NAME.new-*`` /
    ``.NAME.old-*`` beside ``out`` belongs to a writer that was killed (a live one would
    hold the lock). A staging folder is deleted; a previous ``out`` moved aside but not
    yet replaced (killed between the two renames of :func:`_replace_folder`) is put back,
    else deleted."""
    import glob

    if os.path.realpath(out.parent) not in _held.__dict__.get("folders", ()):
        msg = f"{out.parent}: tidied without its lock"
        raise RuntimeError(msg)

    prefix = f".{glob.escape(out.name)}"
    for old in sorted(out.parent.glob(f"{prefix}.old-*")):
        if not old.is_dir() or old.is_symlink():
            continue
        if not out.exists() and not out.is_symlink():
            os.replace(old, out)
        else:
            shutil.rmtree(old, ignore_errors=True)
    for new in out.parent.glob(f"{prefix}.new-*"):
        if new.is_dir() and not new.is_symlink():
            shutil.rmtree(new, ignore_errors=True)


def _staged(out: Path, publish: bool) -> Iterator[Path]:
    try:
        temp = Path(tempfile.mkdtemp(prefix=f".{out.name}.new-{os.getpid()}-", dir=out.parent))
    except PermissionError:
        raise UsageError(_not_writable(out.parent)) from None
    try:
        yield temp
        umask = _umask()
        for folder in [temp, *(p for p in temp.rglob("*") if p.is_dir())]:
            folder.chmod(0o777 & ~umask)
        if publish:
            _replace_folder(temp, out)
    finally:
        with contextlib.suppress(FileNotFoundError):
            shutil.rmtree(temp)


def _replace_folder(temp: Path, out: Path) -> None:
    if not out.exists():
        os.replace(temp, out)
        return
    if not any(out.iterdir()):
        out.rmdir()  # POSIX would replace an empty folder, Windows would not
        os.replace(temp, out)
        return
    old = Path(tempfile.mkdtemp(prefix=f".{out.name}.old-{os.getpid()}-", dir=out.parent))
    old.rmdir()
    os.replace(out, old)
    try:
        os.replace(temp, out)
    except BaseException:
        os.replace(old, out)
        raise
    shutil.rmtree(old, ignore_errors=True)
