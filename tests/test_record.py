"""sensorkit.record: dataclasses that share one __repr__/__eq__/__hash__ behave as plain ones."""

from __future__ import annotations

import dataclasses
import subprocess
import sys
import textwrap
from dataclasses import dataclass, field

import pytest

from sensorkit.record import FrozenRecord, Record


@dataclass
class PlainBox:
    a: int
    b: list[int] = field(default_factory=list)
    hidden: str = field(default="x", repr=False, compare=False)


@dataclass(repr=False, eq=False)
class RecordBox(Record):
    a: int
    b: list[int] = field(default_factory=list)
    hidden: str = field(default="x", repr=False, compare=False)


@dataclass(frozen=True)
class PlainKey:
    file: str
    line: int | None = None
    note: str = field(default="", compare=False)
    weight: float = field(default=0.0, hash=False)


@dataclass(frozen=True, repr=False, eq=False)
class RecordKey(FrozenRecord):
    file: str
    line: int | None = None
    note: str = field(default="", compare=False)
    weight: float = field(default=0.0, hash=False)


def test_repr_and_eq_match_a_plain_dataclass() -> None:
    for args in [(1,), (2, [3, 4]), (5, [], "y")]:
        p, r = PlainBox(*args), RecordBox(*args)  # type: ignore[arg-type]
        assert repr(r) == repr(p).replace("PlainBox", "RecordBox")
        assert (r == RecordBox(*args)) == (p == PlainBox(*args))  # type: ignore[arg-type]
    assert RecordBox(1, [2], "y") == RecordBox(1, [2], "z")  # compare=False is left out
    assert RecordBox(1) != RecordBox(2)
    assert RecordBox(1).__eq__(PlainBox(1)) is NotImplemented  # another class never equals
    assert PlainBox.__hash__ is None and RecordBox.__hash__ is None
    with pytest.raises(TypeError):
        hash(RecordBox(1))


def test_frozen_record_hashes_as_a_frozen_dataclass() -> None:
    for args in [("f",), ("f", 3), ("g", 3, "n", 1.5)]:
        p, r = PlainKey(*args), RecordKey(*args)  # type: ignore[arg-type]
        assert hash(p) == hash(r)
        assert repr(r) == repr(p).replace("PlainKey", "RecordKey")
    assert len({RecordKey("f", 1, "a"), RecordKey("f", 1, "b")}) == 1  # note: compare=False
    assert len({RecordKey("f", 1, "a", 1.0), RecordKey("f", 1, "a", 2.0)}) == 2  # weight compares
    assert hash(RecordKey("f", 1, "a", 1.0)) == hash(RecordKey("f", 1, "a", 2.0))  # hash=False
    with pytest.raises(dataclasses.FrozenInstanceError):
        RecordKey("f").line = 2  # type: ignore[misc]


def test_a_recursive_record_prints() -> None:
    box = RecordBox(1)
    box.b.append(box)  # type: ignore[arg-type]
    assert repr(box) == "RecordBox(a=1, b=[...])"


def test_validate_compiles_no_dataclass_repr_or_eq() -> None:
    """Start-up: every dataclass ``sensorkit validate`` loads takes its __repr__ and __eq__
    from Record (compiling them per class was a fifth of the start-up)."""
    code = textwrap.dedent(
        """
        import dataclasses, sys
        seen = []
        orig = dataclasses._process_class
        def spy(cls, init, repr, eq, *rest):
            seen.append((cls.__module__ + "." + cls.__qualname__, repr, eq))
            return orig(cls, init, repr, eq, *rest)
        dataclasses._process_class = spy
        sys.argv = ["sensorkit", "validate", sys.argv[1]]
        from sensorkit.engine import Options, validate_paths
        from pathlib import Path
        validate_paths([Path(sys.argv[2])], Options())
        import sensorkit.cli.validate, sensorkit.cli.common, sensorkit.config
        for name, r, e in seen:
            if name.startswith("sensorkit.") and (r or e):
                print(name)
        print(len(seen))
        """
    )
    robot = "examples/harmonic_robot/harmonic_robot_description/urdf/harmonic_robot.urdf.xacro"
    out = subprocess.run(
        [sys.executable, "-c", code, "validate", robot],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.split()
    assert int(out[-1]) >= 30, out  # the spy saw the classes
    assert out[:-1] == [], f"dataclasses compiling their own __repr__/__eq__: {out[:-1]}"
