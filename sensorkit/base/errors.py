"""The small error hierarchy.

Findings are data and never raise. These exceptions are for the cases where sensorkit
itself cannot go on (usage, an unreadable file, a refused edit); the CLI turns each into
one line on stderr and exit status 2. Set ``SENSORKIT_DEBUG=1`` to see the traceback.
"""

from __future__ import annotations

from sensorkit.base.quote import shorten


class SensorkitError(Exception):
    """Base class of every error sensorkit raises on purpose."""

    def __str__(self) -> str:
        # One line that quotes at most ~200 characters of any input (issue 25).
        return shorten(super().__str__())


class UsageError(SensorkitError):
    """The caller asked for something that does not make sense (bad option, bad value)."""


class InputError(SensorkitError):
    """A file could not be read or is not something sensorkit can work on."""


class EditRefused(SensorkitError):
    """An edit was refused; the user's file is left byte-identical."""


class WriteFailed(SensorkitError):
    """Writing an output failed (disk full, file too large, I/O error); nothing was replaced."""
