"""Reading a file only when it is a regular file, and never past a byte limit (issue 36).

``Path.read_bytes`` on a named pipe blocks until a writer comes (an include named
``fifo`` stopped the expansion at its timeout), on ``/dev/zero`` it never ends (a link to
it grew the parent to 3.7 GB), and ``stat().st_size`` says nothing of either (0 bytes).
:func:`read_regular` follows links, refuses what is not a regular file before opening it
(a device may act on open), opens without blocking, checks the open file again (it may
have been swapped between the two) and reads at most ``limit + 1`` bytes whatever
``stat`` said.
"""

from __future__ import annotations

import errno
import io
import os
import stat

# What any file a description names (an include, a YAML, a launch file) may hold: the
# input limit (sensorkit.loading.document.MAX_FILE_BYTES).
MAX_READ = 64 * 1024 * 1024
KINDS = (
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISFIFO, "a named pipe"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


class NotRegular(OSError):
    """The file is not a regular file (``strerror`` says what it is)."""


class TooLarge(OSError):
    """The file holds more than the limit (``strerror`` says the limit)."""


def kind(mode: int) -> str:
    """What a file of ``mode`` is, in words (``a regular file`` for one)."""
    for test, words in KINDS:
        if test(mode):
            return words
    return "a regular file" if stat.S_ISREG(mode) else "not a regular file"


def _refuse(mode: int, path: str | os.PathLike[str]) -> NotRegular:
    what = kind(mode)
    return NotRegular(errno.EINVAL, f"{what}, not a regular file: not read", os.fspath(path))


def read_regular(path: str | os.PathLike[str], limit: int) -> bytes:
    """The bytes of the regular file at ``path`` (links followed), at most ``limit``.

    Raises NotRegular for a folder, pipe, device or socket, TooLarge past ``limit``
    (counted while reading, never taken from ``stat``), and OSError as ``open`` does.
    """
    mode = os.stat(path).st_mode
    if not stat.S_ISREG(mode):
        raise _refuse(mode, path)
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise _refuse(mode, path)
        chunks: list[bytes] = []
        got = 0
        while got <= limit:
            chunk = os.read(fd, min(1 << 20, limit + 1 - got))
            if not chunk:
                break
            chunks.append(chunk)
            got += len(chunk)
        if got > limit:
            raise TooLarge(errno.EFBIG, f"larger than the {limit} bytes sensorkit reads", os.fspath(path))
        return b"".join(chunks)
    finally:
        os.close(fd)


class CappedText(io.StringIO):
    """A text sink that keeps the first ``cap`` characters written and drops the rest
    (xacro's messages, captured while it expands: ``xacro.message`` in a loop filled a
    plain StringIO by the gigabyte)."""

    def __init__(self, cap: int = 1 << 20) -> None:
        super().__init__()
        self.cap = cap
        self.dropped = 0

    def write(self, s: str) -> int:
        room = self.cap - self.tell()
        if room > 0:
            super().write(s[:room])
        self.dropped += max(0, len(s) - max(room, 0))
        return len(s)
