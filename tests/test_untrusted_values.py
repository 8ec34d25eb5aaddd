"""Issue 36, items 2 and 3 (causes 2, 3 and 4): values are only data, and sizes are
counted before they are built.

Cause 2: ``${xacro.load_yaml}``, ``str(xacro)``, ``f'{x!r}'``, ``'%(load_yaml)r' % xacro``
and ``min([], default=math)`` printed function and namespace reprs with addresses: the
evaluator handed out objects. Now a name or attribute that yields a function, a module, a
namespace or a class is an SK102 naming the construct, and may only be called.

Cause 3 and 4: ``('{0}'*20000).format(s)``, ``'%(a)s'*n % d``, comprehensions of big
strings and an ``xacro.message`` flood reached ~1 GB; ``round(7, -10**8)`` and a sort loop
ran into the 60 s timeout. Each is refused (or bounded) before it is computed; the bound
tests run under a protective memory limit with the peak RSS measured (test_bounds.py).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from test_bounds import GB, sensorkit

from sensorkit.base.regular import CappedText
from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.untrusted import Untrusted
from sensorkit.loading.xacro_expand import expand

FORMATS = ("text", "json", "sarif", "github")
HEAD = (
    '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '<xacro:arg name="rb" default="}"/>\n'
)
INERTIAL = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
# What an object's repr looks like in a message.
REPR = re.compile(r"0x[0-9a-f]{6,}|<function|<module|<built-in|<class|<bound method|NameSpace|Table\(")

# cause 2, each with (a word of) what the SK102 names
OBJECTS = [
    ("${xacro.load_yaml}", "xacro.load_yaml (a function) as a value"),
    ("${str(xacro)}", "passing a namespace as an argument"),
    ("${f'{xacro.load_yaml!r$(arg rb)'}", "xacro.load_yaml (a function) as a value"),
    ("${'%(load_yaml)r' % xacro}", "xacro (a namespace) as a value"),
    ("${min([], default=math)}", "passing a namespace as an argument"),
    ("${xacro}", "xacro (a namespace) as a value"),
    ("${python.float}", "python.float (a class) as a value"),
    ("${'a'.upper}", "'a'.upper (a function) as a value"),
    ("${xacro.get('load_yaml')}", "(a function) as a value"),
    ("${[v for v in xacro.values()]}", "(a function)"),
    ("${python['len']}", "(a function) as a value"),
]
# what real robots do with functions and namespaces, still allowed
CALLS = [
    ("${xacro.load_yaml('cfg.yaml')['cam']['fov']}", "1.2"),
    ("${math.pi > 3}", "True"),
    ("${python.list(python.map(python.float, ['1', '2']))}", "[1.0, 2.0]"),
    ("${python.sorted(['bb', 'a'], key=python.len)}", "['a', 'bb']"),
    ("${xacro.load_yaml('cfg.yaml').cam.name}", "front"),
    ("${python.isinstance(1, python.int)}", "True"),
]


def _robot(folder: Path, exprs: list[str]) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "cfg.yaml").write_text("cam: {fov: 1.2, name: front}\n")
    links = "".join(f'<link name="l{i}_{e}">{INERTIAL}</link>\n' for i, e in enumerate(exprs))
    path = folder / "robot.urdf.xacro"
    path.write_text(HEAD + links + "</robot>\n")
    return path


def _expand(path: Path) -> object:
    return expand(path, {}, PackageResolver(), untrusted=Untrusted())


@pytest.mark.parametrize(("expr", "said"), OBJECTS, ids=[o[0] for o in OBJECTS])
def test_an_object_is_no_value(tmp_path: Path, expr: str, said: str) -> None:
    outcome = _expand(_robot(tmp_path / "ws", [expr]))
    message = getattr(outcome, "message", "")
    assert getattr(outcome, "error_kind", None) == "xacro", getattr(outcome, "xml", None)
    assert said in message and "--untrusted" in message, message
    assert not REPR.search(message), message


def test_no_repr_reaches_any_output_format(tmp_path: Path) -> None:
    paths = [_robot(tmp_path / "ws" / f"o{i}", [expr]) for i, (expr, _) in enumerate(OBJECTS)]
    for fmt in FORMATS:
        run = sensorkit("validate", "--untrusted", "--format", fmt, *map(str, paths), cwd=tmp_path)
        out = run.out + run.err
        assert run.code == 1, out[-2000:]
        assert out.count("SK102") >= len(OBJECTS), (fmt, out[-3000:])
        assert not REPR.search(out), (fmt, REPR.search(out), out[-3000:])


@pytest.mark.parametrize(("expr", "value"), CALLS, ids=[c[0] for c in CALLS])
def test_functions_and_namespaces_may_still_be_called(tmp_path: Path, expr: str, value: str) -> None:
    """The near miss: ``xacro.load_yaml(...)``, ``math.pi``, ``map(float, ...)``."""
    outcome = _expand(_robot(tmp_path / "ws", [expr]))
    assert getattr(outcome, "error_kind", None) is None, getattr(outcome, "message", "")
    assert f'name="l0_{value}"' in str(getattr(outcome, "xml", "")), getattr(outcome, "xml", "")


# -- item 3: sizes counted before they are built ----------------------------------------
SIZES = [
    ("${len(('{0$(arg rb)'*20000).format('a'*1000))}", "text over 1,000,000 characters"),
    ("${len(('{$(arg rb)'*20000).format(*(['a'*100]*20000)))}", "text over 1,000,000 characters"),
    ("${len(('%(a)s'*20000) % python.dict(a='a'*1000))}", "text over 1,000,000 characters"),
    ("${len(('%s'*2000) % python.tuple(['a'*1000]*2000))}", "text over 1,000,000 characters"),
    ("${len([s + 'x' for s in ['a'*100000]*1000])}", "a comprehension over 16,000,000 characters"),
    ("${len([(i, 'a'*100000 + str(i)) for i in python.range(1000)])}", "a comprehension over"),
    ("${round(7, -10**8)}", "round to more than 10,000 digits"),
    ("${round(7.5, ndigits=10**9)}", "round to more than 10,000 digits"),
    ("${len([len(python.sorted(xs)) for i in python.range(1000)])}", "over 1,000,000 steps"),
    ("${len([xs.count('b') for i in python.range(1000)])}", "over 1,000,000 steps"),
    ("${len([str(i) in xs for i in python.range(1000)])}", "over 1,000,000 steps"),
]


def _sized(folder: Path, expr: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "robot.urdf.xacro"
    path.write_text(
        '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:arg name="rb" default="}"/>\n'
        "<xacro:property name=\"xs\" value=\"${'a'*900000}\"/>\n"
        f'<link name="l_{expr}">{INERTIAL}</link>\n</robot>\n'
    )
    return path


@pytest.mark.parametrize(("expr", "said"), SIZES, ids=[s[0][:50] for s in SIZES])
def test_sizes_are_refused_before_they_are_built(tmp_path: Path, expr: str, said: str) -> None:
    outcome = _expand(_sized(tmp_path / "ws", expr))
    message = getattr(outcome, "message", "")
    assert getattr(outcome, "error_kind", None) == "xacro", message
    assert said in message, message


@pytest.mark.parametrize(
    "expr",
    [
        "${len(('{0$(arg rb)'*100).format('a'*1000))}",  # 100 kB: under the bound
        "${len(('%(a)s'*100) % python.dict(a='a'*1000))}",
        "${len([s + 'x' for s in ['a'*1000]*1000])}",
        "${round(7, -3)}",
        "${len([len(python.sorted(xs)) for i in python.range(3)])}",
    ],
)
def test_sizes_just_under_the_bounds_are_computed(tmp_path: Path, expr: str) -> None:
    outcome = _expand(_sized(tmp_path / "ws", expr))
    assert getattr(outcome, "error_kind", None) is None, getattr(outcome, "message", "")


def test_the_steps_of_a_whole_expansion_are_bounded(tmp_path: Path) -> None:
    """A macro that runs an expression just under the per-expression bound again and
    again stops at the expansion's total (MAX_TOTAL_STEPS), not at the timeout."""
    expr = "${len([xs.count('b') for i in python.range(8)])}"
    calls = "".join(f'<link name="l{i}_{expr}"/>\n' for i in range(40))
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(
        '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        "<xacro:property name=\"xs\" value=\"${'a'*900000}\"/>\n"
        f"{calls}</robot>\n"
    )
    outcome = _expand(path)
    message = getattr(outcome, "message", "")
    assert getattr(outcome, "error_kind", None) == "xacro", message
    assert "steps in one expansion" in message, message


def test_a_message_flood_stays_small(tmp_path: Path) -> None:
    """20 expressions each printing 7 MB through xacro.message (as many as the steps
    bound lets through: each character printed costs): 140 MB of captured stderr in the
    expansion child before; now its first MiB is kept and the rest dropped."""
    flood = "${len([xacro.message('a'*100000) for i in python.range(70)])}"
    links = "".join(f'<link name="l{i}_{flood}">{INERTIAL}</link>\n' for i in range(20))
    (tmp_path / "robot.urdf.xacro").write_text(
        '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f"{links}</robot>\n"
    )
    run = sensorkit("validate", "--untrusted", "robot.urdf.xacro", cwd=tmp_path)
    assert "stopped without an answer" not in run.out and "MemoryError" not in run.out, run.out[-1000:]
    assert run.code in (0, 1) and "SK102" not in run.out, run.out[-1000:]
    assert run.rss < GB / 2, f"{run.rss / GB:.2f} GB"


def test_captured_text_is_capped() -> None:
    sink = CappedText(10)
    assert sink.write("a" * 8) == 8 and sink.write("b" * 8) == 8
    assert sink.getvalue() == "a" * 8 + "bb" and sink.dropped == 6
