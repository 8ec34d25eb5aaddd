"""Reading values out of XML: numbers and vectors from attribute text, children by tag
name, and :class:`Origin`, the pose an ``<origin>`` (or an SDF ``<pose>``) writes.

Shared by every reader of the model (URDF links and joints, Gazebo sensors) and by the
rules that read elements themselves. Nothing here raises on bad text: a value that does
not read is ``None`` plus why.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from lxml import etree

from sensorkit.base.findings import SourceRef

if TYPE_CHECKING:
    from sensorkit.model.transforms import Mat, Pose
    from sensorkit.model.transforms_np import Mat as NpMat

Vec3 = tuple[float, float, float]


def parse_vec3(text: str) -> tuple[Vec3 | None, str | None]:
    """Three finite numbers from an attribute, or (None, why): ``parse_vec``'s fast path."""
    try:
        a, b, c = text.split()
        v = (float(a), float(b), float(c))
    except ValueError:
        return None, f"{text!r} is not 3 numbers"
    if v[0] - v[0] or v[1] - v[1] or v[2] - v[2]:  # NaN for NaN and inf, 0.0 otherwise
        return None, f"{text!r} is not finite"
    return v, None


def parse_vec(text: str | None, n: int = 3) -> tuple[tuple[float, ...] | None, str | None]:
    """``n`` numbers from an attribute, or (None, why)."""
    if text is None:
        return None, None
    if n == 3:
        return parse_vec3(text)
    parts = text.split()
    if len(parts) != n:
        return None, f"{text!r} is not {n} numbers"
    try:
        values = tuple(map(float, parts))
    except ValueError:
        return None, f"{text!r} is not {n} numbers"
    if sum(values) - sum(values) != 0.0:  # any NaN or inf makes this NaN
        return None, f"{text!r} is not finite"
    return values, None


def parse_float(text: str | None) -> tuple[float | None, str | None]:
    """One finite number, or (None, why)."""
    if text is None:
        return None, None
    try:
        value = float(text)
    except ValueError:
        return None, f"{text!r} is not a number"
    if value - value != 0.0:
        return None, f"{text!r} is not finite"
    return value, None


# The longest prefix std::strtod reads as a decimal number, an infinity or a NaN (hex
# floats are left out: a text they start is reported unread).
_STOD_PREFIX = re.compile(r"\s*([+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan))", re.I)


def stod_prefix(text: str) -> tuple[float, str] | None:
    """What sdformat reads from a ``double`` that is not a number as a whole, and the text
    it ignores; None when it reads nothing (std::stod throws, sdformat reports the value).

    sdformat parses a double with ``std::stod(tmp)`` and no end pointer, so the digits that
    start the text are the value and the rest is ignored without a word
    (gazebosim/sdformat@sdf9 9ee2d4f3:src/Param.cc:359-362, Gazebo Classic; @sdf12
    b9417e5b:src/Param.cc:707-709, Fortress; @sdf14 8512585c:src/Param.cc:916-919,
    Harmonic); std::stod skips leading white space itself."""
    m = _STOD_PREFIX.match(text)
    if m is None or m.end() == len(text.rstrip()):
        return None
    rest = text[m.end():].strip()
    try:
        return float(m.group(1)), rest
    except ValueError:  # pragma: no cover - the pattern reads only what float() reads
        return None


def local(el: etree._Element) -> str:
    """Tag name without namespace ('' for comments and processing instructions)."""
    tag = el.tag
    if not isinstance(tag, str):
        return ""
    if tag[0] == "{":
        return tag.rsplit("}", 1)[-1]
    return tag


def children(el: etree._Element, name: str) -> list[etree._Element]:
    """Child elements called ``name`` (documents are namespace-free after loading)."""
    if name.isidentifier():  # a plain tag name: a loop costs less than lxml's findall()
        return [c for c in el if c.tag == name]
    return list(el.findall(name))


def child(el: etree._Element | None, name: str) -> etree._Element | None:
    """The first child element called ``name`` (or matching an ElementPath), or None."""
    if el is None:
        return None
    if name.isidentifier():  # a plain tag name: a loop costs less than lxml's find()
        for c in el:
            if c.tag == name:
                return c
        return None
    return el.find(name)


def text_of(el: etree._Element | None, *path: str) -> str | None:
    """Stripped text of a descendant by child names, or None."""
    cur = el
    for name in path:
        cur = child(cur, name)
        if cur is None:
            return None
    if cur is None or cur.text is None:
        return None
    return str(cur.text).strip()


_ZERO: Vec3 = (0.0, 0.0, 0.0)


@dataclass(slots=True)
class Origin:
    """A URDF ``<origin>``: xyz and rpy, zeros when absent; notes when unreadable.

    Read-only once made: the model builder hands one Origin to every element whose
    attributes read the same (robots repeat "0 0 0" and a few poses thousands of times).
    """

    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    problems: tuple[str, ...] = ()
    rpy_text: str | None = None
    source: SourceRef | None = None
    _pose: Pose | None = field(default=None, init=False, repr=False, compare=False)

    @classmethod
    def from_text(
        cls, xyz_text: str | None, rpy_text: str | None, source: SourceRef | None = None
    ) -> Origin:
        """The origin written ``xyz=xyz_text rpy=rpy_text`` (None: the attribute is absent)."""
        xyz: Vec3 | None = _ZERO
        rpy: Vec3 | None = _ZERO
        problems: list[str] = []
        if xyz_text is not None:
            xyz, why = parse_vec3(xyz_text)
            if why:
                problems.append(f"xyz {why}")
        if rpy_text is not None:
            rpy, why = parse_vec3(rpy_text)
            if why:
                problems.append(f"rpy {why}")
        return cls(xyz or _ZERO, rpy or _ZERO, tuple(problems), rpy_text, source)

    def pose(self) -> Pose:
        """The origin as a flat pose (see :mod:`sensorkit.model.transforms`), memoised."""
        p = self._pose
        if p is None:
            from sensorkit.model.transforms import pose

            p = self._pose = pose(self.xyz, self.rpy)
        return p

    def transform(self) -> Mat:
        """The origin as a pure-Python 4x4 matrix."""
        from sensorkit.model.transforms import pose_matrix

        return pose_matrix(self.pose())

    def matrix(self) -> NpMat:
        """The origin as a 4x4 numpy array (for rendering and export)."""
        from sensorkit.model.transforms_np import transform

        return transform(self.xyz, self.rpy)
