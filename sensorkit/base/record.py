"""``__repr__``, ``__eq__`` and ``__hash__`` for dataclasses, written once instead of per class.

``@dataclass`` writes each class's methods as source text and compiles it: about a
millisecond per class here, a fifth of ``sensorkit validate``'s start-up over the ~35
classes it loads, most of it for ``__repr__`` and ``__eq__``, which a run seldom calls.
A class declared ``@dataclass(repr=False, eq=False)`` that derives from :class:`Record`
(or :class:`FrozenRecord` when ``frozen=True``) behaves as the plain dataclass would:

- ``repr``: ``Name(field=value, ...)`` over the fields with ``repr=True``, guarded
  against recursion;
- ``==``: the tuples of ``compare=True`` fields, for instances of the very same class
  (``NotImplemented`` otherwise); instances are unhashable, as with ``eq=True``;
- ``FrozenRecord``: hashable by the same fields (``hash=`` of a field as dataclass reads it).

The field names of each class are looked up once, on first use.

The same classes are declared ``init=False`` and write their ``__init__`` by hand: one
parameter per field, in order, with the field's default (``FACTORY`` where the field has
a default factory), assigning each (``object.__setattr__`` when frozen) and calling
``__post_init__`` last, as dataclass's own would. Compiling those ~35 ``__init__``s cost
~7 ms of a ~120 ms ``sensorkit validate``. ``tests/test_record.py`` holds every such
``__init__`` to its fields: add a field, add its parameter.
"""

from __future__ import annotations

from dataclasses import fields
from reprlib import recursive_repr
from typing import Any

_NAMES: dict[tuple[type, str], tuple[str, ...]] = {}


class _Factory:
    __slots__ = ()

    def __repr__(self) -> str:
        return "<factory>"


# The default of an ``__init__`` parameter whose field has a default factory, in the
# classes that write their own ``__init__`` (``@dataclass(init=False)``): the parameter
# reads ``x: list[str] = FACTORY`` and the body ``[] if x is FACTORY else x``, as
# dataclass's own ``__init__`` does with its private ``<factory>`` marker.
FACTORY: Any = _Factory()


def _names(cls: type, what: str) -> tuple[str, ...]:
    key = (cls, what)
    names = _NAMES.get(key)
    if names is None:
        fs = fields(cls)
        if what == "hash":
            names = tuple(f.name for f in fs if (f.compare if f.hash is None else f.hash))
        else:
            names = tuple(f.name for f in fs if getattr(f, what))
        _NAMES[key] = names
    return names


class Record:
    """Mixin for ``@dataclass(repr=False, eq=False)`` classes: see the module docstring."""

    __slots__ = ()

    @recursive_repr()
    def __repr__(self) -> str:
        names = _names(type(self), "repr")
        inner = ", ".join(f"{n}={getattr(self, n)!r}" for n in names)
        return f"{self.__class__.__qualname__}({inner})"

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        names = _names(type(self), "compare")
        return tuple(getattr(self, n) for n in names) == tuple(getattr(other, n) for n in names)

    __hash__: Any = None  # as dataclass(eq=True) leaves a mutable class


class FrozenRecord(Record):
    """Mixin for ``@dataclass(frozen=True, repr=False, eq=False)`` classes: hashable."""

    __slots__ = ()

    def __hash__(self) -> int:
        return hash(tuple(getattr(self, n) for n in _names(type(self), "hash")))
