"""Issue 25: ``--untrusted`` evaluates ``${...}`` and ``$(eval ...)`` by allow-list.

The deny-list before it (loading/untrusted.py check_expression) let a nested field in a
format spec through: ``'{0:{1.__globals__[os].environ[SK_SECRET]}}'.format(1,
xacro.load_yaml)`` printed an environment variable (in-process expansion) or xacro's
module globals (forked). Python's ``eval`` is no longer called on untrusted input: every
construct, function and method is on a list (sensorkit/loading/safe_eval.py), and sizes
are bounded before they are computed.

xacro's lexer ends ``${...}`` at the first ``}`` and ``$(...)`` at the first ``)``
(xacro/__init__.py LEXER: ``EXPR=r"^\\$\\{[^\\}]*\\}"``, ``EXTENSION=r"^\\$\\([^\\)]*\\)"``),
but it expands substitutions inside an expression before evaluating it (eval_text
``handle_expr``: ``safe_eval(eval_text(s, symbols), symbols)``), so an attacker writes
``$(arg rb)`` for ``}`` and ``${rp}`` for ``)``, as these robots do.
"""

from __future__ import annotations

import json
import secrets
from pathlib import Path
from typing import Any

import pytest
from conftest import run_cli

from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.untrusted import UnsafeExpression, Untrusted, check_expression
from sensorkit.loading.xacro_expand import expand

FORMATS = ("text", "json", "sarif", "github")
HEAD = (
    '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '<xacro:arg name="rb" default="}"/><xacro:property name="rp" value=")"/>\n'
    '<xacro:property name="f_nested" value="\'{0:{1.__globals__[os].environ[SK_SECRET]}}\'"/>\n'
    "<xacro:property name=\"f_attr\" value=\"'{0.__globals__}'\"/>\n"
    "<xacro:property name=\"f_item\" value=\"'{0[os]}'\"/>\n"
    "<xacro:property name=\"f_wide\" value=\"'{:999999999}'\"/>\n"
    '<xacro:property name="width" value="0.4"/><xacro:property name="name" value="cam"/>\n'
    '<xacro:property name="xs" value="${[3, 1, 2]}"/>\n'
)
INERTIAL = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
# The leak, word for word (What broke 2), and xacro's module globals it printed
# when the environment was cleared.
LEAK = "${'{0:{1.__globals__[os].environ[SK_SECRET]$(arg rb)$(arg rb)'.format(1, xacro.load_yaml)}"
GLOBALS = "${'{0:{1.__globals__$(arg rb)$(arg rb)'.format(1, xacro.load_yaml)}"
# What a value of xacro's module globals looks like in a message.
GLOBALS_MARKS = ("SourceFileLoader", "__loader__", "__builtins__", "environ(")

# Each escape, and (a word of) what the SK102 message names.
ESCAPES = [
    (LEAK, "nested format field"),
    (GLOBALS, "nested format field"),
    ("${f_nested.format(1, xacro.load_yaml)}", "nested format field"),
    ("${f_attr.format(xacro.load_yaml)}", "attribute or an item"),
    ("${f_item.format(xacro.load_yaml.__globals__)}", "attribute .__globals__"),
    ("${().__class__.__bases__}", "attribute .__bases__"),
    ("${''.__class__}", "attribute .__class__"),
    ("${(lambda: 1)()}", "lambda"),
    ("${[c for c in [1]][0].__class__}", "attribute .__class__"),
    ("${[g for g in [(x for x in [1])]][0].gi_frame}", "attribute .gi_frame"),
    ("${(x := xacro.load_yaml)}", "':='"),
    ("${__import__('os')}", "name __import__"),
    ("${xacro.load_yaml.__globals__}", "attribute .__globals__"),
    ("${python.dict(a=xacro.load_yaml)['a'].__globals__}", "attribute .__globals__"),
    ("$(eval getattr(1, 'real'${rp})", "name getattr"),
    ("$(eval globals(${rp})", "name globals"),
    ("$(eval open('/proc/self/environ'${rp})", "name open"),
    ("$(eval vars(${rp})", "name vars"),
]
# Runaway sizes: refused before they are computed (issue 25 What broke 5).
BOUNDS = [
    ("${9**9**9}", "an integer over 10,000 digits"),
    ("${len('a'*2000000000)}", "a str over 1,000,000 characters"),
    ("${[0]*10**7}", "a list over 1,000,000 elements"),
    ("${len(python.range(10**12))}", "a range over 1,000,000 elements"),
    ("${len([x for x in python.range(10**6) for y in python.range(10**6)])}", "over 1,000,000 steps"),
    ("${'%999999999d' % 1}", "text over 1,000,000 characters"),
    ("${'%*d' % (10**9, 1)}", "'*' width"),
    ("${f_wide.format(1)}", "format width"),
    ("${python.sum([[0]*1000]*1000, [])}", "sum of anything but numbers"),
    ("${'x'.join(['a'*1000000]*1000)}", "a str over 1,000,000 characters"),
    ("${str([['a'*1000]*1000]*1000)}", "text over 1,000,000 characters"),
    ("${math.factorial(10**7)}", "factorial of a number over 10,000"),
    ("${2 * 3 ** 10**6}", "an integer over 10,000 digits"),
]
# What real robots write (and the corpus uses: see the report of issue 25): the same
# result with and without --untrusted.
ORDINARY = [
    "${pi/2}", "${radians(30)}", "${width/2}", "${sqrt(width**2+1)}", "${math.pi}",
    "${1 if width > 0 else 2}", "${'%s_link' % name}", "${name + '_link'}", "${[1,2][0]}",
    "${xs[0] * -1}", "${python.sorted(xs)[0]}", "${len(xs)}", "${name.upper()}",
    "${[x * 2 for x in xs]}", "${python.sum(x for x in xs)}", "${max(xs) - min(xs)}",
    "${name in ['cam', 'lidar']}", "${not (width > 1 and name == 'cam')}",
    "${round(width * 3.14159, 3)}", "${int(width * 10) // 3}", "${str(width).replace('.', '_')}",
    "${xacro.arg('rb')}", "$(eval 1 + 2 * 3)", "$(eval 'x' + 'y')", "$(eval radians(90${rp})",
    "$(eval max(1, 2${rp})", "${f_ok.format(name, n=3)}",
    "${xacro.load_yaml('cfg.yaml')['cam']['fov'] * 2}", "${xacro.load_yaml('cfg.yaml').cam.fov}",
]  # fmt: skip


def _robot(folder: Path, names: list[str]) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "cfg.yaml").write_text("cam: {fov: 1.2, name: front}\n")
    links = "".join(f'<link name="l{i}_{n}">{INERTIAL}</link>\n' for i, n in enumerate(names))
    ok = "<xacro:property name=\"f_ok\" value=\"'{}_{n}'\"/>\n"
    path = folder / "robot.urdf.xacro"
    path.write_text(HEAD + ok + links + "</robot>\n")
    return path


def _expand(path: Path, untrusted: bool) -> Any:
    return expand(path, {}, PackageResolver(), untrusted=Untrusted() if untrusted else None)


@pytest.mark.parametrize("inprocess", [False, True], ids=["forked", "in-process"])
def test_the_format_spec_leak_is_refused_in_every_format(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, inprocess: bool
) -> None:
    """What broke 2: the secret (in-process) or xacro's globals (forked) reached the output."""
    secret = "sk-" + secrets.token_hex(12)
    monkeypatch.setenv("SK_SECRET", secret)
    if inprocess:
        monkeypatch.setenv("SENSORKIT_XACRO_INPROCESS", "1")
    leak = _robot(tmp_path / "ws" / "leak", [LEAK])
    globs = _robot(tmp_path / "ws" / "globals", [GLOBALS])
    for fmt in FORMATS:
        res = run_cli("validate", "--untrusted", "--format", fmt, str(leak), str(globs))
        out = res.stdout + res.stderr
        assert secret not in out, (fmt, out[:2000])
        assert not any(m in out for m in GLOBALS_MARKS), (fmt, out[:2000])
        assert res.returncode in (1, 2), out[:2000]
        if res.returncode == 1:  # a finding per file (exit 2 would be a refusal of the mode)
            assert out.count("SK102") >= 2 and "nested format field" in out, (fmt, out[:2000])


def test_every_escape_is_an_sk102_naming_it_in_every_format(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    secret = "sk-" + secrets.token_hex(12)
    monkeypatch.setenv("SK_SECRET", secret)
    paths = [_robot(tmp_path / "ws" / f"e{i}", [expr]) for i, (expr, _) in enumerate(ESCAPES)]
    for fmt in FORMATS:
        res = run_cli("validate", "--untrusted", "--format", fmt, *map(str, paths))
        out = res.stdout + res.stderr
        assert res.returncode == 1, out[:2000]
        assert secret not in out and not any(m in out for m in GLOBALS_MARKS), (fmt, out[:3000])
        assert out.count("SK102") >= len(ESCAPES), (fmt, out[:3000])
    for path, (expr, said) in zip(paths, ESCAPES, strict=True):
        outcome = _expand(path, untrusted=True)
        assert outcome.error_kind == "xacro", (expr, outcome.xml)
        assert said in outcome.message and "--untrusted" in outcome.message, (expr, outcome.message)
        assert all(len(line) < 700 for line in outcome.message.splitlines()), outcome.message


@pytest.mark.parametrize(("expr", "said"), BOUNDS, ids=[b[0][:40] for b in BOUNDS])
def test_runaway_sizes_are_refused_before_they_are_computed(tmp_path: Path, expr: str, said: str) -> None:
    outcome = _expand(_robot(tmp_path / "ws", [expr]), untrusted=True)
    assert outcome.error_kind == "xacro", outcome.message
    assert said in outcome.message and "--untrusted" in outcome.message, outcome.message


def test_ordinary_expressions_give_what_xacro_gives(tmp_path: Path) -> None:
    path = _robot(tmp_path / "ws", ORDINARY)
    trusted, untrusted = _expand(path, untrusted=False), _expand(path, untrusted=True)
    assert trusted.error_kind is None and untrusted.error_kind is None, untrusted.message
    assert untrusted.xml == trusted.xml
    assert 'name="l0_1.5707963267948966"' in untrusted.xml and 'name="l6_cam_link"' in untrusted.xml
    assert 'name="l27_2.4"' in untrusted.xml and 'name="l28_1.2"' in untrusted.xml
    res = run_cli("validate", "--untrusted", "--format", "json", str(path))
    plain = run_cli("validate", "--format", "json", str(path))
    # the same report, but for the readable area --untrusted names (issue 36)
    got, want = json.loads(res.stdout), json.loads(plain.stdout)
    assert got.pop("readable") and want.pop("readable") == {}
    assert "SK102" not in res.stdout and got == want, res.stdout + res.stderr


@pytest.mark.parametrize(
    "expr",
    [
        "'{0:{1.__globals__}}'.format(1, f)",  # the nested spec the deny-list missed
        "'{0:{1}}'.format(1, 2)",
        "(lambda: 0)()",
        "(x := 1)",
        "b'bytes'",
    ],
)
def test_the_static_check_refuses_what_it_can_see(expr: str) -> None:
    with pytest.raises(UnsafeExpression):
        check_expression(expr)


def test_functions_are_allowed_by_identity_not_by_name() -> None:
    """A name bound to ``type`` (a property could hold it) is not callable; ``len`` is."""
    import xacro

    from sensorkit.loading.safe_eval import evaluate
    from sensorkit.loading.untrusted import _xacro_functions

    funcs = _xacro_functions(xacro)
    names = {"len": type, "f": len, "xs": [1, 2], "g": getattr}
    assert evaluate("f(xs)", names.__getitem__, funcs) == 2
    for expr in ("len(xs)", "g(xs, 'copy')", "python_map(len, [xs])"):
        with pytest.raises(UnsafeExpression, match=r"calling|passing"):
            evaluate(expr, {**names, "python_map": map, "len": type}.__getitem__, funcs)
    with pytest.raises(UnsafeExpression, match="passing"):
        evaluate("list(m(g, [xs]))", {**names, "m": map, "list": list}.__getitem__, funcs)
