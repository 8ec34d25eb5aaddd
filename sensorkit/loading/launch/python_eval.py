"""Evaluate the expressions of a Python launch file as an AST: never run, never imported.

What is resolved: string, number and boolean literals, f-strings, ``+``, lists and tuples
(a list of substitutions is their concatenation), maps, names assigned once in the module
or in the enclosing functions, ``LaunchConfiguration`` (launch arguments given by an
include, then ``DeclareLaunchArgument`` defaults), ``TextSubstitution``,
``PathJoinSubstitution``, ``FindPackageShare``/``get_package_share_directory`` (to the
package's folder in the workspace), ``os.path.join``, ``str``, ``ParameterValue``. Anything
else (``Command``, ``PythonExpression``, environment variables, loops, calls of the file's
own functions, a name assigned twice or changed in place) is UNKNOWN.
"""

from __future__ import annotations

import ast
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

MAX_EVAL_DEPTH = 60
_MUTATORS = {"append", "extend", "insert", "update", "pop", "remove", "clear", "setdefault"}


class _Unknown:
    def __repr__(self) -> str:
        return "UNKNOWN"


UNKNOWN = _Unknown()


def call_name(node: ast.expr) -> str | None:
    """The last part of a called name: ``launch_ros.actions.Node`` -> ``Node``."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return node.attr
    return None


def dotted(node: ast.expr) -> str:
    if isinstance(node, ast.Attribute):
        return f"{dotted(node.value)}.{node.attr}"
    return node.id if isinstance(node, ast.Name) else "?"


@dataclass
class Scope:
    """Names assigned once in one body (module or function); None: not simple."""

    assigns: dict[str, ast.expr | None]
    parent: Scope | None = None

    def find(self, name: str) -> tuple[ast.expr | None, Scope] | None:
        scope: Scope | None = self
        while scope is not None:
            if name in scope.assigns:
                return scope.assigns[name], scope
            scope = scope.parent
        return None


def body_nodes(body: list[ast.stmt]) -> list[ast.AST]:
    """Every node of a body, nested functions and classes left out (they are scopes)."""
    out: list[ast.AST] = []
    stack: list[ast.AST] = list(reversed(body))
    while stack:
        node = stack.pop()
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef | ast.Lambda):
            continue
        out.append(node)
        stack.extend(reversed(list(ast.iter_child_nodes(node))))
    return out


def make_scope(body: list[ast.stmt], parent: Scope | None, params: list[str]) -> Scope:
    assigns: dict[str, ast.expr | None] = dict.fromkeys(params)
    counts: dict[str, int] = {}

    def bind(name: str, value: ast.expr | None) -> None:
        counts[name] = counts.get(name, 0) + 1
        assigns[name] = value if counts[name] == 1 and name not in params else None

    for node in body_nodes(body):
        if isinstance(node, ast.Assign):
            for target in node.targets:
                if isinstance(target, ast.Name):
                    bind(target.id, node.value if len(node.targets) == 1 else None)
                else:
                    for sub in ast.walk(target):
                        if isinstance(sub, ast.Name):
                            bind(sub.id, None)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            bind(node.target.id, node.value)
        elif isinstance(node, ast.AugAssign | ast.For | ast.With | ast.NamedExpr | ast.comprehension):
            targets = [node.target] if not isinstance(node, ast.With) else [
                i.optional_vars for i in node.items if i.optional_vars is not None]
            for t in targets:
                for sub in ast.walk(t):
                    if isinstance(sub, ast.Name):
                        bind(sub.id, None)
                        bind(sub.id, None)
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr in _MUTATORS and isinstance(node.func.value, ast.Name)):
            bind(node.func.value.id, None)
            bind(node.func.value.id, None)
        elif isinstance(node, ast.Import | ast.ImportFrom | ast.FunctionDef | ast.ClassDef):
            pass
    return Scope(assigns, parent)


@dataclass
class Evaluator:
    """Evaluates expressions of one file; ``config`` resolves a launch configuration."""

    config: Callable[[str, Any], Any]
    share: Callable[[str], str]
    depth: int = 0
    busy: set[tuple[int, str]] = field(default_factory=set)

    def eval(self, node: ast.expr | None, scope: Scope) -> Any:
        if node is None or self.depth > MAX_EVAL_DEPTH:
            return UNKNOWN
        self.depth += 1
        try:
            return self._eval(node, scope)
        finally:
            self.depth -= 1

    def _eval(self, node: ast.expr, scope: Scope) -> Any:
        if isinstance(node, ast.Constant):
            return node.value if isinstance(node.value, str | int | float | bool) or node.value is None else UNKNOWN
        if isinstance(node, ast.Name):
            return self._name(node.id, scope)
        if isinstance(node, ast.List | ast.Tuple):
            if any(isinstance(e, ast.Starred) for e in node.elts):
                return UNKNOWN
            return [self.eval(e, scope) for e in node.elts]
        if isinstance(node, ast.Dict):
            out: dict[Any, Any] = {}
            for k, v in zip(node.keys, node.values, strict=True):
                key = self.eval(k, scope) if k is not None else None
                out[key if isinstance(key, str) else None] = self.eval(v, scope) if k is not None else UNKNOWN
            return out
        if isinstance(node, ast.JoinedStr):
            return self.text([self.eval(v.value if isinstance(v, ast.FormattedValue) else v, scope)
                              if not (isinstance(v, ast.FormattedValue) and (v.format_spec or v.conversion not in (-1, 115)))
                              else UNKNOWN for v in node.values])
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            return self._add(self.eval(node.left, scope), self.eval(node.right, scope))
        if isinstance(node, ast.Call):
            return self._call(node, scope)
        return UNKNOWN

    def _name(self, name: str, scope: Scope) -> Any:
        found = scope.find(name)
        if found is None:
            return UNKNOWN
        expr, where = found
        key = (id(where), name)
        if expr is None or key in self.busy:
            return UNKNOWN
        self.busy.add(key)
        try:
            return self.eval(expr, where)
        finally:
            self.busy.discard(key)

    @staticmethod
    def _add(left: Any, right: Any) -> Any:
        if isinstance(left, str) and isinstance(right, str):
            return left + right
        if isinstance(left, list) and isinstance(right, list):
            return left + right
        if isinstance(left, int | float) and isinstance(right, int | float) and not isinstance(left, bool):
            return left + right
        return UNKNOWN

    @staticmethod
    def text(value: Any) -> str | None:
        """A value as the string launch would make of it (None: unknown)."""
        if isinstance(value, str):
            return value
        if isinstance(value, int | float):
            return str(value)
        if isinstance(value, list):
            parts = [Evaluator.text(v) for v in value]
            return None if any(p is None for p in parts) else "".join(p for p in parts if p)
        return None

    def _call(self, node: ast.Call, scope: Scope) -> Any:
        name = call_name(node.func)
        args = node.args
        kw = {k.arg: k.value for k in node.keywords if k.arg is not None}
        if isinstance(node.func, ast.Attribute) and node.func.attr == "items" and not args:
            base = self.eval(node.func.value, scope)
            return [[k, v] for k, v in base.items()] if isinstance(base, dict) else UNKNOWN
        if any(isinstance(a, ast.Starred) for a in args) or any(k.arg is None for k in node.keywords):
            return UNKNOWN
        first = args[0] if args else None
        if (isinstance(node.func, ast.Attribute) and node.func.attr == "find" and len(args) == 1
                and isinstance(node.func.value, ast.Call) and call_name(node.func.value.func) == "FindPackageShare"):
            # FindPackageShare(...).find(name) is the share folder of name, its own argument
            # (ros2/launch_ros@humble:launch_ros/launch_ros/substitutions/find_package.py:110-112).
            pkg = self.text(self.eval(first, scope))
            return self.share(pkg) if pkg and "\x00" not in pkg else UNKNOWN
        if isinstance(node.func, ast.Attribute) and node.func.attr == "perform_substitution" and len(args) == 1:
            # context.perform_substitution(s) is s performed (ros2/launch@humble:launch/launch/
            # launch_context.py:238-240), as in an OpaqueFunction's body.
            return self.eval(first, scope)
        if name == "GetNamespacedName" and len(args) == 2:
            # create3_sim's substitution, used by create3 and turtlebot4 simulations: name, or
            # namespace/name (iRobotEducation/create3_sim@6a8bc44:irobot_create_common/
            # irobot_create_common_bringup/irobot_create_common_bringup/namespace.py:29-32).
            ns, base = (self.text(self.eval(a, scope)) for a in args)
            if ns is None or base is None:
                return UNKNOWN
            return base if ns == "" else ns + "/" + base
        if name == "LaunchConfiguration":
            var = self.text(self.eval(first or kw.get("variable_name"), scope))
            default = kw.get("default")
            return self.config(var, (lambda: self.eval(default, scope)) if default is not None else None) if var else UNKNOWN
        if name == "TextSubstitution":
            return self.eval(kw.get("text", first), scope)
        if name in ("FindPackageShare", "get_package_share_directory", "get_package_share_path"):
            pkg = self.text(self.eval(first or kw.get("package"), scope))
            return self.share(pkg) if pkg and "\x00" not in pkg else UNKNOWN
        if name in ("PathJoinSubstitution",) and first is not None:
            parts = self.eval(first, scope)
            return self._join(parts if isinstance(parts, list) else [parts])
        if dotted(node.func) in ("os.path.join", "path.join", "join") or (name == "Path" and args):
            return self._join([self.eval(a, scope) for a in args])
        if name in ("str", "ParameterValue") and first is not None:
            value = self.eval(first, scope)
            return self.text(value) if name == "str" else value
        return UNKNOWN

    def _join(self, parts: list[Any]) -> Any:
        texts = [self.text(p) for p in parts]
        if any(t is None for t in texts):
            return UNKNOWN
        out = ""
        for t in texts:
            assert t is not None
            out = t if t.startswith("/") or not out else out.rstrip("/") + "/" + t
        return out


def launch_args_of(value: Any) -> dict[str, str | None] | None:
    """An include's ``launch_arguments`` as a map (None: unknown)."""
    if isinstance(value, dict):
        value = [[k, v] for k, v in value.items()]
    if not isinstance(value, list):
        return None
    out: dict[str, str | None] = {}
    for item in value:
        if not isinstance(item, list) or len(item) != 2:
            return None
        key = Evaluator.text(item[0])
        if key is None:
            return None
        out[key] = Evaluator.text(item[1])
    return out


def as_mapping(value: Any) -> Mapping[Any, Any] | None:
    return value if isinstance(value, dict) else None
