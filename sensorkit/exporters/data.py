"""Plain dicts of everything sensorkit knows about a sensor, and their JSON text."""

from __future__ import annotations

import json
from collections.abc import Mapping

from sensorkit.describe.intrinsics import (
    LASER_SCAN_FIELDS,
    Intrinsics,
    InvalidValue,
    LaserScanParams,
)

__all__ = ["camera_dict", "laser_scan_dict", "to_json"]


def _merge(base: dict[str, object], metadata: Mapping[str, object]) -> dict[str, object]:
    clash = sorted(set(base) & set(metadata))
    if clash:
        msg = f"metadata keys clash with computed keys: {', '.join(clash)}"
        raise InvalidValue(msg)
    return {**base, **metadata}


def camera_dict(intr: Intrinsics, **metadata: object) -> dict[str, object]:
    """Every intrinsic of ``intr`` as JSON-ready Python values, plus ``metadata``.

    Keys: ``convention``, ``width``, ``height``, ``fx``, ``fy``, ``cx``, ``cy``,
    ``skew``, ``hfov``, ``vfov`` (radians), ``distortion_model``, ``distortion``
    (k1 k2 p1 p2 k3), ``K`` (3x3), ``R`` (3x3), ``P`` (3x4), ``baseline_tx``.

    Raises:
        InvalidValue: a metadata key collides with a computed key.
    """
    base: dict[str, object] = {
        "convention": intr.convention,
        "width": intr.width,
        "height": intr.height,
        "fx": intr.fx,
        "fy": intr.fy,
        "cx": intr.cx,
        "cy": intr.cy,
        "skew": intr.skew,
        "hfov": intr.hfov,
        "vfov": intr.vfov,
        "distortion_model": "plumb_bob",
        "distortion": list(intr.distortion),
        "K": intr.K.tolist(),
        "R": intr.R.tolist(),
        "P": intr.P.tolist(),
        "baseline_tx": intr.baseline_tx,
    }
    return _merge(base, metadata)


def laser_scan_dict(scan: LaserScanParams, **metadata: object) -> dict[str, object]:
    """The LaserScan fields of ``scan`` (plus ``samples``, the range count) and ``metadata``.

    Raises:
        InvalidValue: a metadata key collides with a computed key.
    """
    base: dict[str, object] = {"samples": scan.samples}
    base.update((name, getattr(scan, name)) for name in LASER_SCAN_FIELDS)
    return _merge(base, metadata)


def to_json(data: Mapping[str, object]) -> str:
    """Strict JSON text (no NaN/Infinity), two-space indented, newline-terminated.

    Python floats are written with ``repr`` precision, so they round-trip exactly.

    Raises:
        InvalidValue: ``data`` holds a non-finite float or a value JSON cannot hold.
    """
    try:
        return json.dumps(dict(data), indent=2, allow_nan=False) + "\n"
    except (TypeError, ValueError) as exc:
        msg = f"cannot write JSON: {exc}"
        raise InvalidValue(msg) from exc
