"""NPY outputs, published atomically (a reader never sees half a file)."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sensorkit.base.atomic import write_bytes

__all__ = ["save_npy"]


def save_npy(path: Path, array: npt.NDArray[np.generic]) -> None:
    """``numpy.save`` to ``path``, published atomically."""
    buffer = io.BytesIO()
    np.save(buffer, array, allow_pickle=False)
    write_bytes(path, buffer.getvalue(), fsync=False)
