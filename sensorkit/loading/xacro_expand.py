"""Run the real xacro library, isolated, with line tracking and package resolution.

xacro keeps module-level state (file and macro stacks, included files, substitution
args, the root folder). Each expansion runs in a forked child process where that is
available (Linux, macOS), so every call starts from the same clean module, a runaway
expression (``${10**10**10}``) can be stopped by a timeout and a memory bomb by a
memory limit. Elsewhere it runs in-process after resetting xacro's globals.

Line tracking: xacro parses with minidom, which records no line numbers. We hand xacro
a parser that stamps every non-xacro element with ``sk_loc_="<file index>:<line>"``;
the stamp survives macro instantiation (xacro clones elements), so each element of the
expanded robot still says which file and line it was written in.
"""

from __future__ import annotations

import io
import os
import re
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sensorkit.base.errors import UsageError
from sensorkit.base.regular import MAX_READ, CappedText, read_regular
from sensorkit.loading import marks
from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.reads import ExpandDeps, Recording, record_reads
from sensorkit.loading.xacro_errors import PackageMissing, where_failed
from sensorkit.loading.xacro_errors import classify as _classify

if TYPE_CHECKING:  # untrusted.py (and its evaluator) load only for --untrusted
    from sensorkit.loading.untrusted import Confinement, Untrusted

LOC_ATTR = marks.LOC_ATTR  # defined in marks (plain URDFs never import this module)
forbid_entities = marks.forbid_entities

MAX_INCLUDE_DEPTH = 64
DEFAULT_TIMEOUT = 60.0
# Address space the expansion child may add to what it inherits (RLIMIT_AS): a
# property-doubling bomb stops at it with a MemoryError, an SK102 error.
MEMORY_LIMIT = 1024**3
# The child's answer is read up to this many bytes: the input limit (64 MiB,
# loading.document.MAX_FILE_BYTES) and 1 MiB for the rest of the outcome.
MAX_ANSWER_BYTES = 65 * 1024**2


@dataclass
class ExpandOutcome:
    """What one expansion produced: XML text, or a classified failure."""

    xml: str | None = None
    files: list[str] = field(default_factory=list)
    includes: list[str] = field(default_factory=list)
    error_kind: str | None = None  # "xml", "xacro", "package", "timeout", "memory"
    message: str = ""
    error_file: str | None = None
    error_line: int | None = None
    error_column: int | None = None
    stack: list[str] = field(default_factory=list)
    macro_file: str | None = None  # where the innermost macro being expanded was defined
    macro_line: int | None = None
    package: str | None = None
    searched: list[str] = field(default_factory=list)
    # what the expansion read (see sensorkit.loading.reads); None: not recorded
    deps: ExpandDeps | None = None
    packages: list[str] = field(default_factory=list)  # the names $(find) resolved


def _loc_parser(
    files: list[str],
    orig_parse: Any,
    confine: Confinement | None = None,
    overlay: Mapping[str, bytes] | None = None,
) -> Any:
    import xml.dom.minidom
    from xml.dom import expatbuilder

    import xacro

    Attr = xml.dom.minidom.Attr
    set_attribute_node = xml.dom.minidom._set_attribute_node  # type: ignore[attr-defined]

    class _LineBuilder(expatbuilder.ExpatBuilderNS):
        file_index = 0

        def start_element_handler(self, name: str, attributes: Any) -> None:
            super().start_element_handler(name, attributes)
            node: Any = self.curNode
            tag = node.tagName
            if not tag.startswith("xacro:") or tag in ("xacro:macro", "xacro:include"):
                line = getattr(self, "_parser").CurrentLineNumber  # noqa: B009 (private in typeshed)
                # What node.setAttribute(LOC_ATTR, ...) does for a name the element does
                # not have yet, without its lookups and checks: a third of the stamping
                # cost, and the same Attr in the same place (the expansion's output is
                # byte-identical on the corpus).
                attr = Attr(LOC_ATTR)
                attr.value = f"{self.file_index}:{line}"
                attr.ownerDocument = self.document
                set_attribute_node(node, attr)

    def parse(inp: Any, filename: str | None = None) -> Any:
        if inp is not None or filename is None:
            return orig_parse(inp, filename)
        full = os.path.abspath(os.path.join(xacro.root_dir, filename))
        stack = [os.path.abspath(f) for f in (xacro.filestack or []) if f]
        if stack.count(full) > 1:
            chain = " -> ".join(stack[stack.index(full) :])
            raise xacro.XacroException(f"include loop: {chain}")
        if len(stack) > MAX_INCLUDE_DEPTH:
            raise xacro.XacroException(f"includes nested deeper than {MAX_INCLUDE_DEPTH}")
        if confine is not None and not confine.allows(full):
            # ``full`` is the include's own (expanded) filename: glob results outside were
            # dropped by _confined_includes, so this names what the user wrote, never a
            # file found outside, and is said whether or not anything is there.
            if xacro.filestack:
                xacro.filestack.pop()
            raise xacro.XacroException(confine.refuse(full))
        try:
            data = overlay[full] if overlay and full in overlay else read_regular(full, MAX_READ)
        except OSError as exc:
            if xacro.filestack:
                xacro.filestack.pop()
            raise xacro.XacroException(f"{exc.strerror}: {exc.filename}", exc=exc) from None
        reason = forbid_entities(data)
        if reason:
            raise xacro.XacroException(reason)
        if full not in files:
            files.append(full)
        builder = _LineBuilder()
        builder.file_index = files.index(full)
        doc: xml.dom.minidom.Document = builder.parseString(data)
        return doc

    return parse


def _glob_escapes(spec: str, confine: Confinement) -> bool:
    """Whether the glob ``spec`` could list a folder outside ``confine``: its literal
    leading folder is outside, or a ``..`` follows a wildcard."""
    parts = spec.split(os.sep)
    first = next(i for i, part in enumerate(parts) if re.search(r"[*[?]", part))
    prefix = os.sep.join(parts[:first]) or os.sep
    return not confine.allows(prefix) or ".." in parts[first:]


def _confined_includes(confine: Confinement) -> Any:
    """xacro's ``get_include_files`` under --untrusted.

    xacro globs a filename holding ``*``, ``[`` or ``?`` and includes every match
    (xacro 2.1.1 from PyPI, xacro/__init__.py:470-491 get_include_files). Here a pattern
    that could list a folder outside the confinement is refused naming the pattern as
    written, before anything is listed; matches outside (through a symlink) are left out
    silently, so nothing tells whether anything exists outside.
    """
    import glob

    import xacro

    def include_files(filename_spec: str, symbols: Any) -> Any:
        spec = xacro.abs_filename_spec(xacro.eval_text(filename_spec, symbols))
        if re.search(r"[*[?]+", spec):  # xacro's own test for a glob
            if _glob_escapes(spec, confine):
                raise xacro.XacroException(confine.refuse(filename_spec.strip()))
            names = [n for n in sorted(glob.glob(spec)) if confine.allows(n)]
        else:
            names = [spec]
        for name in names:
            xacro.all_includes.append(name)
            yield name

    return include_files


def _plain_text_fast(eval_text: Any) -> Any:
    """xacro's ``eval_text`` returning text with no ``$`` as it is, without lexing it.

    xacro evaluates every attribute and text node with ``eval_text`` (xacro/__init__.py,
    ``eval_all``), which runs its lexer even on text with nothing to substitute. The lexer's
    TEXT token is ``[^$]+``, so such a text lexes to one token and comes back unchanged
    (an empty one joins to ``''``): answering that at once is the same result. On the
    corpus the expanded XML is byte-identical and expansion takes 15-26 % less CPU.
    """

    def fast(text: Any, symbols: Any) -> Any:
        if type(text) is str and "$" not in text:
            return text
        return eval_text(text, symbols)

    return fast


def _reset_xacro() -> None:
    import xacro

    xacro.all_includes = []
    xacro.substitution_args_context.clear()
    xacro.init_stacks(None)
    xacro.root_dir = os.curdir
    xacro.verbosity = 0


def expand_in_process(
    path: Path,
    args: dict[str, str],
    resolver: PackageResolver,
    untrusted: Untrusted | None = None,
    overlay: Mapping[str, bytes] | None = None,
    bounded: float | None = None,
) -> ExpandOutcome:
    """Expand ``path`` with xacro in this process (resets xacro's globals first).

    With ``untrusted``, xacro's ways of reading the machine are narrowed for the duration
    (see ``sensorkit.loading.untrusted``); everything patched is restored afterwards.
    ``overlay`` maps absolute paths to bytes read instead of the file's (``--fix`` checks
    an edit before it writes anything). ``bounded``: a trusted expansion evaluated by the
    allow-list evaluator within that many seconds (``xacro_fast.bound``); it raises
    ``xacro_fast.NotHere`` where the forked child must expand instead.
    """
    import xacro
    import xacro.substitution_args as sa

    from sensorkit.loading import xacro_fast

    files: list[str] = []
    out = ExpandOutcome(files=files)
    saved_sa = {k: getattr(sa, k) for k in ("_eval_find", "_eval_env", "_eval_optenv", "_eval")}
    saved_dict = {k: sa._eval_dict.get(k) for k in ("find", "env", "optenv")}
    saved_x = {
        k: getattr(xacro, k) for k in ("parse", "safe_eval", "get_include_files", "eval_text")
    }
    saved_python: dict[str, Any] = {}
    orig_stderr = sys.stderr
    confine = None
    if untrusted is not None:
        from sensorkit.loading.untrusted import confinement_for

        confine = confinement_for(path, resolver.explicit.values(), resolver.scan_dirs)
    find = _finder(resolver, confine, out.packages)
    _reset_xacro()
    undo: list[Any] = []
    xacro_fast.speed_up(xacro, undo)
    xacro.eval_text = _plain_text_fast(saved_x["eval_text"])
    if confine is not None:
        xacro.get_include_files = _confined_includes(confine)
    sa._eval_find = find
    sa._eval_dict["find"] = find
    if untrusted is not None and confine is not None:
        _narrow(xacro, sa, untrusted, confine, saved_sa, saved_x, saved_python)
    elif bounded is not None:
        xacro_fast.bound(xacro, sa, bounded, MEMORY_LIMIT, undo)
    reads = _record_reads(xacro, sa, out, untrusted, overlay)
    xacro.parse = _loc_parser(files, saved_x["parse"], confine, reads.overlay if reads else overlay)
    if bounded is not None and reads is not None:  # the language server's kept includes
        xacro_fast.reuse_includes(xacro, find, files, reads, undo)
    sys.stderr = CappedText()  # what xacro prints, never read: its first MiB only
    try:
        doc = xacro.process_file(os.path.abspath(path), mappings=dict(args), verbosity=0)
        out.xml = doc.documentElement.toxml()
        out.includes = [os.path.abspath(p) for p in xacro.all_includes]
    except xacro_fast.OverTime:
        out.error_kind, out.message = "timeout", _timeout_message(bounded or 0)
    except BaseException as exc:  # classify everything; never let xacro escape
        if isinstance(exc, (KeyboardInterrupt, xacro_fast.NotHere)):
            raise
        _classify(exc, out)
    finally:
        if reads is not None:
            reads.restore()
        for step in reversed(undo):
            step()
        stack_files = [f for f in (xacro.filestack or []) if f]
        macros = list(xacro.macrostack or [])
        _restore(xacro, sa, saved_x, saved_sa, saved_dict, saved_python)
        sys.stderr = orig_stderr
    if out.error_kind is not None:
        where_failed(out, stack_files, macros, files)
    _reset_xacro()
    return out


def _finder(resolver: PackageResolver, confine: Confinement | None, found: list[str]) -> Any:
    """``$(find pkg)`` through ``resolver`` (a folder found joins ``confine``; its name
    joins ``found``)."""

    def find(pkg: str) -> str:
        # resolver.find finds nothing for what cannot be a package name (an absolute
        # path, ``..``: packages.valid_package_name), so only a package's own folder,
        # found by name, ever joins the folders an untrusted expansion may read.
        hit = resolver.find(pkg)
        if hit is None:
            raise PackageMissing(pkg, resolver.searched())
        if confine is not None:
            confine.add(hit)
        if pkg not in found:
            found.append(pkg)
        return str(hit)

    return find


def _restore(
    xacro: Any,
    sa: Any,
    saved_x: dict[str, Any],
    saved_sa: dict[str, Any],
    saved_dict: dict[str, Any],
    saved_python: dict[str, Any],
) -> None:
    """Put back everything ``expand_in_process`` patched in xacro for one expansion."""
    for k, v in saved_x.items():
        setattr(xacro, k, v)
    xacro.__dict__.pop("open", None)
    xacro._global_symbols.get("python", {}).update(saved_python)
    for k, v in saved_sa.items():
        setattr(sa, k, v)
    for k, v in saved_dict.items():
        if v is not None:
            sa._eval_dict[k] = v


def _record_reads(
    xacro: Any,
    sa: Any,
    out: ExpandOutcome,
    untrusted: Untrusted | None,
    overlay: Mapping[str, bytes] | None,
) -> Recording | None:
    """Record what the expansion reads into ``out.deps`` (for the expansion cache); never
    under ``untrusted``, whose results are not cached. Call after the expansion's own
    patches of ``sa``; ``expand_in_process`` restores the patches in its ``finally``."""
    if untrusted is not None:
        return None
    reads = record_reads(xacro, sa, overlay)
    out.deps = reads.deps
    return reads


def _narrow(
    xacro: Any,
    sa: Any,
    untrusted: Untrusted,
    confine: Confinement,
    saved_sa: dict[str, Any],
    saved_x: dict[str, Any],
    saved_python: dict[str, Any],
) -> None:
    """Patch xacro for an untrusted expansion (``expand_in_process`` restores it all)."""
    from sensorkit.loading.untrusted import HIDDEN_PYTHON_NAMES, UnsafeExpression, XacroEvaluator

    def env(name: str) -> str:
        if name not in untrusted.env:
            msg = f"$(env {name}): not allowed with --untrusted (pass --env {name} to allow it)"
            raise sa.SubstitutionException(msg)
        value: str = saved_sa["_eval_env"](name)
        return value

    def optenv(name: str, default: str = "") -> str:
        if name not in untrusted.env:
            return default
        value: str = saved_sa["_eval_optenv"](name, default)
        return value

    def guarded_open(file: Any, *a: Any, **kw: Any) -> Any:
        # xacro.load_yaml calls the module-level name ``open`` (xacro/__init__.py load_yaml)
        if not confine.allows(str(file)):
            raise xacro.XacroException(confine.refuse(str(file)))
        if a or kw:  # load_yaml opens for reading text, nothing else
            raise xacro.XacroException(f"--untrusted: opening {file} that way is not allowed")
        return io.TextIOWrapper(io.BytesIO(read_regular(str(file), MAX_READ)), encoding=None)

    evaluator = XacroEvaluator(xacro, sa)  # by allow-list, never Python's eval

    def safe_eval(expr: str, symbols: Any, local: Any = None) -> Any:
        try:
            return evaluator.expression(expr, symbols, local)
        except UnsafeExpression as exc:
            raise xacro.XacroException(str(exc)) from None

    def eval_sub(s: str, context: Any) -> Any:
        try:
            return evaluator.substitution(s, context)
        except UnsafeExpression as exc:
            raise sa.SubstitutionException(str(exc)) from None

    sa._eval_env = env
    sa._eval_optenv = optenv
    sa._eval_dict["env"] = env
    sa._eval_dict["optenv"] = optenv
    sa._eval = eval_sub
    xacro.safe_eval = safe_eval
    xacro.open = guarded_open
    python = xacro._global_symbols.get("python", {})
    for name in HIDDEN_PYTHON_NAMES:  # restored by expand_in_process
        if name in python:
            saved_python[name] = python.pop(name)


def expand(
    path: Path,
    args: dict[str, str],
    resolver: PackageResolver,
    *,
    timeout: float = DEFAULT_TIMEOUT,
    untrusted: Untrusted | None = None,
    overlay: Mapping[str, bytes] | None = None,
) -> ExpandOutcome:
    """Expand ``path`` isolated from this process where possible (see the module doc).

    Under ``untrusted`` the in-process mode is refused (a UsageError): it would run the
    expansion with this process's whole environment and files.
    """
    if not hasattr(os, "fork") or os.environ.get("SENSORKIT_XACRO_INPROCESS"):
        if untrusted is not None:
            why = "SENSORKIT_XACRO_INPROCESS is set" if hasattr(os, "fork") else "no fork here"
            raise UsageError(f"--untrusted needs xacro expanded in a forked process ({why})")
        return expand_in_process(path, args, resolver, untrusted, overlay)
    if untrusted is None:
        here = _expand_here(path, args, resolver, overlay, timeout)
        if here is not None:
            return here
    import multiprocessing as mp
    import pickle

    warm()
    ctx = mp.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)
    proc = ctx.Process(
        target=_child,
        args=(path, args, resolver, send, untrusted, overlay, os.getpid(), timeout),
        daemon=True,
    )
    proc.start()
    send.close()
    outcome: ExpandOutcome | None = None
    try:
        if recv.poll(timeout):
            try:
                outcome = pickle.loads(recv.recv_bytes(MAX_ANSWER_BYTES))
            except OSError as exc:  # "bad message length": over the cap, not read
                outcome = None if "length" not in str(exc) else _too_large()
            except (EOFError, pickle.UnpicklingError):
                outcome = None
            if outcome is None:
                proc.join(5)
                code = proc.exitcode
                outcome = ExpandOutcome(
                    error_kind="memory" if code and code < 0 else "xacro",
                    message=f"xacro stopped without an answer (exit status {code})",
                )
        else:
            outcome = ExpandOutcome(error_kind="timeout", message=_timeout_message(timeout))
    finally:
        if proc.is_alive():
            proc.kill()
        proc.join(5)
        recv.close()
    return outcome


def _timeout_message(timeout: float) -> str:
    return f"xacro did not finish within {timeout:g} s (a runaway expression?)"


def _expand_here(
    path: Path,
    args: dict[str, str],
    resolver: PackageResolver,
    overlay: Mapping[str, bytes] | None,
    timeout: float,
) -> ExpandOutcome | None:
    """A trusted expansion in this process, bounded (``xacro_fast``): its outcome when it
    succeeded or ran out of time, else None, and the forked child decides (a failure's
    message is then the child's, whichever evaluator would have met it first)."""
    from sensorkit.loading import xacro_fast

    if not xacro_fast.supported():
        return None
    try:
        out = expand_in_process(path, args, resolver, None, overlay, bounded=timeout)
    except xacro_fast.NotHere:
        _reset_xacro()
        return None
    return out if out.error_kind in (None, "timeout") else None


def warm() -> None:
    """Import xacro and what it imports on first use here, before forking, once.

    Each child starts from this process: imported here, xacro, its substitution_args and
    yaml are loaded once instead of in every child (validating 120 small xacro robots: the
    children's CPU fell from 52 to 16 ms a file; ``resource``, which each child imported
    to set its memory limit, 0.7-0.8 ms more under -X importtime). Importing reads no environment, so an
    --untrusted child still sees only what it keeps.
    """
    import xml.dom.expatbuilder
    import xml.dom.minidom  # noqa: F401

    import xacro
    import xacro.substitution_args  # noqa: F401

    from sensorkit.base import confine

    confine.preload()  # resource and ctypes, which _confine uses


def _child(
    path: Path,
    args: dict[str, str],
    resolver: PackageResolver,
    send: Any,
    untrusted: Untrusted | None = None,
    overlay: Mapping[str, bytes] | None = None,
    parent: int | None = None,
    timeout: float = DEFAULT_TIMEOUT,
) -> None:
    """The expansion child: confined (see ``_confine``), it expands and sends the outcome."""
    import pickle

    _confine(path, resolver, untrusted, parent, timeout)
    try:
        outcome = expand_in_process(path, args, resolver, untrusted, overlay)
    except BaseException as exc:
        outcome = ExpandOutcome(error_kind="xacro", message=str(exc) or repr(exc))
    try:
        send.send_bytes(pickle.dumps(outcome))
    except BaseException:
        send.send_bytes(
            pickle.dumps(ExpandOutcome(error_kind="memory", message="result too large"))
        )
    finally:
        send.close()
        os._exit(0)


def _confine(
    path: Path,
    resolver: PackageResolver,
    untrusted: Untrusted | None,
    parent: int | None,
    timeout: float,
) -> None:
    """Confine the expansion child before it reads anything.

    Always: it dies with its parent, stops on its own after ``timeout`` s of CPU (the
    parent stops waiting then too), grows by at most MEMORY_LIMIT and writes no file.
    Untrusted: its environment holds only the ``--env`` names (the package path
    variables are read first), the block it started with is wiped, and where the kernel
    has Landlock it may only read below the workspace, the package paths and the code it
    runs (see ``_readable``).
    """
    from sensorkit.base import confine

    if parent is not None:
        confine.die_with_parent(parent)
    # The CPU limit stops an orphan (its parent gone); the parent's wall-clock wait
    # decides the timeout. Equal to it, the two raced: a child on a free core reached
    # ``timeout`` s of CPU as the parent's wait ran out, died of SIGXCPU first, and the
    # finding said "stopped without an answer" instead of "did not finish" (test_fleet).
    confine.limit_resources(memory_growth=MEMORY_LIMIT, cpu_seconds=timeout + 2.0, file_size=0)
    if untrusted is None:
        return
    from sensorkit.loading.untrusted import keep_only_environment

    resolver.freeze_environment()  # installed packages stay findable
    keep_only_environment(untrusted.env)
    confine.wipe_initial_environment()
    confine.restrict_reads(_readable(path, resolver))


def _readable(path: Path, resolver: PackageResolver) -> list[str]:
    """What an untrusted child may read: the readable area (packages.readable_area, the
    one function every confinement uses), and the folders of the code the expansion imports on first use (stdlib, xacro, yaml,
    sensorkit)."""
    import yaml

    import sensorkit
    from sensorkit.loading.packages import readable_area

    env = (resolver.frozen_env or {}) if resolver.use_environment else {}
    roots = readable_area(path, [*resolver.explicit.values(), *resolver.scan_dirs], env)
    code = [os, yaml, sensorkit, sys.modules["xacro"]]
    roots += [os.path.dirname(m.__file__ or "") for m in code]
    return [r for r in roots if r]


def _too_large() -> ExpandOutcome:
    return ExpandOutcome(
        error_kind="memory",
        message=f"xacro's output is larger than {MAX_ANSWER_BYTES // 1024**2} MiB: not read",
    )
