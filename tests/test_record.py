"""sensorkit.base.record: dataclasses that share one __repr__/__eq__/__hash__ behave as plain ones."""

from __future__ import annotations

import dataclasses
import subprocess
import sys
import textwrap
from dataclasses import dataclass, field

import pytest

from sensorkit.base.record import FrozenRecord, Record


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
    from Record and writes its own __init__ (compiling them per class was a fifth of the
    start-up, then ~7 ms of ~120 for the __init__s alone)."""
    code = textwrap.dedent(
        """
        import dataclasses, sys
        seen = []
        orig = dataclasses._process_class
        def spy(cls, init, repr, eq, *rest):
            seen.append((cls.__module__ + "." + cls.__qualname__, repr or init, eq))
            return orig(cls, init, repr, eq, *rest)
        dataclasses._process_class = spy
        sys.argv = ["sensorkit", "validate", sys.argv[1]]
        from sensorkit.lint.engine import Options, validate_paths
        from pathlib import Path
        validate_paths([Path(sys.argv[2])], Options())
        import sensorkit.cli.validate, sensorkit.cli.common, sensorkit.lint.config
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
    assert out[:-1] == [], f"dataclasses compiling their own __init__/__repr__/__eq__: {out[:-1]}"


def _classes_with_own_init() -> list[type]:
    import importlib
    import pkgutil

    import sensorkit

    found = []
    for mod in pkgutil.walk_packages(sensorkit.__path__, "sensorkit."):
        if mod.name.endswith("__main__"):
            continue  # runs the program
        module = importlib.import_module(mod.name)
        for obj in vars(module).values():
            if (
                isinstance(obj, type)
                and obj.__module__ == module.__name__
                and dataclasses.is_dataclass(obj)
                and not obj.__dataclass_params__.init  # type: ignore[attr-defined]
            ):
                found.append(obj)
    return found


def _twin(cls: type) -> type:
    """The class as ``@dataclass`` would have written its ``__init__``."""
    specs = []
    for f in dataclasses.fields(cls):
        kw: dict[str, object] = {"init": f.init}
        if f.default is not dataclasses.MISSING:
            kw["default"] = f.default
        if f.default_factory is not dataclasses.MISSING:
            kw["default_factory"] = f.default_factory
        specs.append((f.name, f.type, dataclasses.field(**kw)))  # type: ignore[call-overload]
    return dataclasses.make_dataclass(cls.__name__ + "Twin", specs)


_POST_CALLS: list[object] = []


def _record_post(self: object) -> None:
    _POST_CALLS.append(self)


def test_hand_written_inits_do_what_dataclass_would() -> None:
    """A dataclass declared ``init=False`` writes its __init__ by hand (start-up): it must
    take the fields' parameters in order with their defaults and annotations, set every
    field from them (defaults and fresh factory values otherwise) and call __post_init__.
    A field added without its parameter, or a default that drifts, fails here."""
    import inspect

    from sensorkit.base.record import FACTORY

    classes = _classes_with_own_init()
    assert len(classes) >= 35, [c.__qualname__ for c in classes]
    for cls in classes:
        name = f"{cls.__module__}.{cls.__qualname__}"
        assert "__init__" in cls.__dict__, f"{name}: init=False but no __init__ of its own"
        fields = dataclasses.fields(cls)
        params = list(inspect.signature(cls.__init__).parameters.values())[1:]
        wanted = [f for f in fields if f.init]
        assert [p.name for p in params] == [f.name for f in wanted], name
        for p, f in zip(params, wanted, strict=True):
            assert p.kind is p.POSITIONAL_OR_KEYWORD, (name, p.name)
            assert p.annotation == f.type, (name, p.name, p.annotation, f.type)
            if f.default is not dataclasses.MISSING:
                assert p.default == f.default and type(p.default) is type(f.default), (name, p.name)
            elif f.default_factory is not dataclasses.MISSING:
                assert p.default is FACTORY, (name, p.name)
            else:
                assert p.default is p.empty, (name, p.name)
        twin = _twin(cls)
        no_default = dataclasses.MISSING
        given = [
            f.name for f in wanted if f.default is no_default and f.default_factory is no_default
        ]
        required = [object() for _ in given]
        everything = [object() for _ in wanted]
        post = getattr(cls, "__post_init__", None)
        if post is not None:
            cls.__post_init__ = _record_post  # type: ignore[attr-defined]
        try:
            for args in (required, everything):
                mine, theirs, again = cls(*args), twin(*args), cls(*args)
                for f in fields:
                    if not f.init and f.default is dataclasses.MISSING:
                        continue
                    a, b = getattr(mine, f.name), getattr(theirs, f.name)
                    if f.init and (len(args) == len(everything) or f.name in given):
                        assert a is b, (name, f.name, a, b)  # the argument itself
                        continue
                    assert type(a) is type(b) and a == b, (name, f.name, a, b)  # the default
                    if isinstance(a, (list, dict, set)):
                        assert a is not getattr(again, f.name), (name, f.name, "shared")
                if post is not None:
                    assert _POST_CALLS[-2:] == [mine, again], name
        finally:
            if post is not None:
                cls.__post_init__ = post  # type: ignore[attr-defined]
