"""Read a Python launch file (``*.launch.py``) as an AST: the nodes it starts, the launch
files it includes, the launch arguments it declares. Nothing in it is run or imported.

``Node`` keywords (package, executable, name, namespace, arguments, parameters,
remappings, ros_arguments) as launch_ros's Node takes them
(ros2/launch_ros@humble:launch_ros/launch_ros/actions/node.py); ``node_executable``,
``node_name`` and ``node_namespace`` are the Foxy/Eloquent spellings.
``DeclareLaunchArgument(name, default_value=...)``
(ros2/launch@humble:launch/launch/actions/declare_launch_argument.py);
``IncludeLaunchDescription(SOURCE, launch_arguments=...)``
(ros2/launch@humble:launch/launch/actions/include_launch_description.py); the
``RosGzBridge(bridge_name=, config_file=, namespace=)`` action
(gazebosim/ros_gz@jazzy:ros_gz_bridge/ros_gz_bridge/actions/ros_gz_bridge.py:34-44), which
includes ros_gz_bridge's own launch file with the config file (:146-152).
"""

from __future__ import annotations

import ast
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from sensorkit.loading.launch.python_eval import (
    UNKNOWN,
    Evaluator,
    Scope,
    body_nodes,
    call_name,
    launch_args_of,
    make_scope,
)
from sensorkit.loading.launch.spec import Include, NodeSpec

_SOURCES = {"PythonLaunchDescriptionSource", "XMLLaunchDescriptionSource",
            "YAMLLaunchDescriptionSource", "AnyLaunchDescriptionSource",
            "FrontendLaunchDescriptionSource"}
_PUSH_NS = {"PushRosNamespace", "PushROSNamespace"}


@dataclass
class FileReading:
    """What one launch file (any front end) gives the reader."""

    nodes: list[NodeSpec] = field(default_factory=list)
    includes: list[Include] = field(default_factory=list)
    # The launch configurations it sets, for the files it includes.
    configs: dict[str, str | None] = field(default_factory=dict)
    pushes_namespace: bool = False


def _scopes(tree: ast.Module) -> list[tuple[list[ast.stmt], Scope]]:
    """Module body and every function body, each with its scope."""
    module = make_scope(tree.body, None, [])
    out: list[tuple[list[ast.stmt], Scope]] = [(tree.body, module)]
    stack: list[tuple[ast.AST, Scope]] = [(n, module) for n in tree.body]
    while stack:
        node, parent = stack.pop()
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            a = node.args
            params = [x.arg for x in [*a.posonlyargs, *a.args, *a.kwonlyargs]]
            params += [x.arg for x in (a.vararg, a.kwarg) if x is not None]
            scope = make_scope(node.body, parent, params)
            out.append((node.body, scope))
            stack.extend((n, scope) for n in node.body)
        elif isinstance(node, ast.ClassDef):
            stack.extend((n, parent) for n in node.body)
        else:
            stack.extend((n, parent) for n in ast.iter_child_nodes(node)
                         if isinstance(n, ast.stmt))
    return out


def read_python(text: str, file: str, inherited: dict[str, str | None],
                share: Callable[[str], str]) -> FileReading:
    """Read one Python launch file (raises SyntaxError, RecursionError, ValueError)."""
    tree = ast.parse(text, filename=file)
    scopes = _scopes(tree)
    declared: dict[str, tuple[ast.expr | None, Scope]] = {}
    calls: list[tuple[ast.Call, Scope]] = []
    for body, scope in scopes:
        calls.extend((n, scope) for n in body_nodes(body) if isinstance(n, ast.Call))
    values: dict[str, Any] = dict(inherited)

    def config(name: str, default: Callable[[], Any] | None) -> Any:
        if name in values:
            return values[name] if values[name] is not None else UNKNOWN
        if name in declared:
            expr, where = declared[name]
            return ev.eval(expr, where) if expr is not None else UNKNOWN
        return default() if default is not None else UNKNOWN

    ev = Evaluator(config=config, share=share)
    for call, scope in calls:
        if call_name(call.func) == "DeclareLaunchArgument":
            _declare(ev, call, scope, declared)
    out = FileReading(pushes_namespace=any(call_name(c.func) in _PUSH_NS for c, _ in calls))
    for call, scope in calls:
        _action(ev, call, scope, file, out)
    out.configs = dict(inherited)
    for name in declared:
        out.configs[name] = Evaluator.text(config(name, None))
    return out


def _declare(ev: Evaluator, call: ast.Call, scope: Scope,
             declared: dict[str, tuple[ast.expr | None, Scope]]) -> None:
    kw = {k.arg: k.value for k in call.keywords if k.arg is not None}
    name_expr = call.args[0] if call.args else kw.get("name")
    name = Evaluator.text(ev.eval(name_expr, scope))
    if name is not None and name not in declared:
        declared[name] = (kw.get("default_value"), scope)


def _action(ev: Evaluator, call: ast.Call, scope: Scope, file: str, out: FileReading) -> None:
    name = call_name(call.func)
    kw = {k.arg: k.value for k in call.keywords if k.arg is not None}
    if name == "Node":
        out.nodes.append(_node(ev, call, scope, file, kw))
    elif name == "ExecuteProcess":
        spec = _ros2_run(ev, kw.get("cmd"), scope, file, call.lineno)
        if spec is not None:
            out.nodes.append(spec)
    elif name == "RosGzBridge":
        config = Evaluator.text(ev.eval(kw.get("config_file"), scope))
        ns = Evaluator.text(ev.eval(kw["namespace"], scope)) if "namespace" in kw else ""
        out.nodes.append(NodeSpec("ros_gz_bridge", "parameter_bridge", None, ns, [],
                                  params=[{"config_file": config}], file=file, line=call.lineno))
    elif name == "IncludeLaunchDescription":
        out.includes.append(_include(ev, call, scope, kw))


def _include(ev: Evaluator, call: ast.Call, scope: Scope, kw: dict[str, ast.expr]) -> Include:
    source = call.args[0] if call.args else kw.get("launch_description_source")
    if isinstance(source, ast.Call) and call_name(source.func) in _SOURCES:
        inner = {k.arg: k.value for k in source.keywords if k.arg is not None}
        source = source.args[0] if source.args else inner.get("launch_file_path")
    path = Evaluator.text(ev.eval(source, scope))
    args_expr = kw.get("launch_arguments")
    args = launch_args_of(ev.eval(args_expr, scope)) if args_expr is not None else {}
    if args is None:
        args = {"\x00unknown": None}
    return Include(path, args, call.lineno)


def _strings(ev: Evaluator, expr: ast.expr | None, scope: Scope) -> tuple[list[str | None] | None, list[int | None]]:
    """A list of arguments, each resolved or None, with each element's line."""
    if expr is None:
        return [], []
    value = ev.eval(expr, scope)
    if not isinstance(value, list):
        return None, []
    lines: list[int | None] = [getattr(e, "lineno", None) for e in expr.elts] if isinstance(
        expr, ast.List | ast.Tuple) else [None] * len(value)
    return [Evaluator.text(v) for v in value], lines


def _node(ev: Evaluator, call: ast.Call, scope: Scope, file: str, kw: dict[str, ast.expr]) -> NodeSpec:
    def one(*keys: str, absent: str | None = None) -> str | None:
        for key in keys:
            if key in kw:
                value = ev.eval(kw[key], scope)
                return "" if value is None else Evaluator.text(value)
        return absent

    args, lines = _strings(ev, kw.get("arguments"), scope)
    ros_args, _ = _strings(ev, kw.get("ros_arguments"), scope)
    if args is not None and ros_args:
        args, lines = [*args, "--ros-args", *ros_args], [*lines, *[call.lineno] * (len(ros_args) + 1)]
    elif ros_args is None:
        args = None
    spec = NodeSpec(one("package"), one("executable", "node_executable"), one("name", "node_name"),
                    one("namespace", "node_namespace", absent=""), args, file=file,
                    line=call.lineno, arg_lines=lines)
    _parameters(ev, kw.get("parameters"), scope, spec)
    _remappings(ev, kw.get("remappings"), scope, spec)
    return spec


def _parameters(ev: Evaluator, expr: ast.expr | None, scope: Scope, spec: NodeSpec) -> None:
    if expr is None:
        return
    value = ev.eval(expr, scope)
    if not isinstance(value, list):
        spec.params.append({None: None})
        return
    for item in value:
        if isinstance(item, dict):
            spec.params.append({k: Evaluator.text(v) if not isinstance(v, bool) else str(v).lower()
                                for k, v in item.items()})
        else:
            spec.params.append(Evaluator.text(item))


def _remappings(ev: Evaluator, expr: ast.expr | None, scope: Scope, spec: NodeSpec) -> None:
    if expr is None:
        return
    value = ev.eval(expr, scope)
    if not isinstance(value, list):
        spec.remaps_unknown = True
        return
    for item in value:
        if isinstance(item, list) and len(item) == 2:
            spec.remaps.append((Evaluator.text(item[0]), Evaluator.text(item[1])))
        else:
            spec.remaps_unknown = True


def _ros2_run(ev: Evaluator, expr: ast.expr | None, scope: Scope, file: str, line: int) -> NodeSpec | None:
    """``ExecuteProcess(cmd=['ros2', 'run', PKG, EXE, ARGS..])`` is that node."""
    args, lines = _strings(ev, expr, scope)
    if not args or len(args) < 4 or args[:2] != ["ros2", "run"]:
        return None
    return NodeSpec(args[2], args[3], None, "", args[4:], file=file, line=line,
                    arg_lines=lines[4:])
