"""The pygls server: LSP messages in, :class:`~sensorkit.lsp.documents.Documents` events
and publications out. The only module of sensorkit that imports pygls.

A handler that fails logs the error with ``window/logMessage`` and answers nothing; the
server goes on. Everything sensorkit needs (the engine, the rules, the knowledge tables)
is imported once, at start, and stays loaded.
"""

from __future__ import annotations

import asyncio
import os
import sys
import traceback
from collections.abc import Callable, Iterator
from functools import wraps
from pathlib import Path
from typing import Any, TypeVar

from lsprotocol import types as lsp
from pygls import uris
from pygls.lsp.server import LanguageServer

from sensorkit import __version__
from sensorkit.base.errors import UsageError
from sensorkit.base.findings import Finding
from sensorkit.lint.engine import Options
from sensorkit.lsp.analysis import Analysis
from sensorkit.lsp.convert import diagnostic, text_edit, to_text
from sensorkit.lsp.documents import Documents, Publish
from sensorkit.lsp.fixes import QuickFix, has_safe_fix, offer, plan
from sensorkit.lsp.framing import TOO_LARGE, BoundedInput, too_large_error
from sensorkit.lsp.hover import hover_text, sensors_at
from sensorkit.lsp.settings import Overrides, settings_for

__all__ = ["SensorkitServer", "serve"]

F = TypeVar("F", bound=Callable[..., Any])


class SensorkitServer(LanguageServer):
    """A LanguageServer holding the open robots and the client's overrides."""

    def __init__(self) -> None:
        super().__init__(
            "sensorkit", __version__, text_document_sync_kind=lsp.TextDocumentSyncKind.Full
        )
        self.overrides = Overrides()
        self.docs = Documents(self.options_for)
        self.uris: dict[str, str] = {}  # path -> the URI the client named it by

    def uri(self, path: str) -> str:
        """The URI of ``path`` as the client spells it (an open document's), else made."""
        return self.uris.get(path) or uris.from_fs_path(path) or path

    def options_for(self, path: Path) -> Options:
        return settings_for(path, self.overrides).options

    def log(self, message: str, kind: lsp.MessageType = lsp.MessageType.Error) -> None:
        self.window_log_message(lsp.LogMessageParams(type=kind, message=message))

    # ------------------------------------------------------------------ text

    def lines(self, path: str) -> list[str]:
        """The file's lines as the editor has them (its buffer, else the disk)."""
        doc = self.docs.open.get(path)
        if doc is not None:
            text = doc.text
        else:
            try:
                text = to_text(Path(path).read_bytes())
            except OSError:
                return []
        return [line.rstrip("\r") for line in text.split("\n")]

    def units(self, line: str, index: int) -> int:
        """A code-point index on ``line`` in the client's position units."""
        return int(self.workspace.position_codec.client_num_units(line[:index]))

    def send(self, publications: list[Publish]) -> None:
        for pub in publications:
            lines = self.lines(pub.path)
            self.text_document_publish_diagnostics(
                lsp.PublishDiagnosticsParams(
                    uri=self.uri(pub.path),
                    version=pub.version,
                    diagnostics=[diagnostic(f, lines, self.units) for f in pub.findings],
                )
            )
        for a in self.docs.analyses.values():
            if a.report is not None:
                for err in a.report.internal_errors:
                    self.log(f"sensorkit: internal error: {err}")
                a.report.internal_errors.clear()

    def edit(self, fix: QuickFix) -> lsp.WorkspaceEdit:
        changes: dict[str, list[lsp.TextEdit]] = {}
        for path, (old, new) in fix.changes.items():
            e = text_edit(old, new, self.units)
            if e is not None:
                changes[self.uri(path)] = [e]
        return lsp.WorkspaceEdit(changes=changes)


def path_of(uri: str) -> str | None:
    """The absolute path of a ``file:`` URI (None for another scheme)."""
    path = uris.to_fs_path(uri)
    return os.path.abspath(path) if path else None


def guarded(func: F) -> F:
    """A handler whose failure is logged to the client, never the end of the server."""

    @wraps(func)
    def wrapper(server: SensorkitServer, params: Any) -> Any:
        try:
            return func(server, params)
        except Exception as exc:
            failed(server, func.__name__, exc)
            return None

    return wrapper  # type: ignore[return-value]


def failed(server: SensorkitServer, name: str, exc: Exception) -> None:
    """Log a handler's failure to the client (the traceback with SENSORKIT_DEBUG)."""
    detail = traceback.format_exc() if os.environ.get("SENSORKIT_DEBUG") else repr(exc)
    server.log(f"sensorkit: {name} failed: {detail}")


SERVER = SensorkitServer()


@SERVER.feature(TOO_LARGE)
@guarded
def too_large(server: SensorkitServer, params: Any) -> None:
    """A message over framing.MAX_MESSAGE, not read: a JSON-RPC error for its id."""
    server.protocol._send_data(too_large_error(params))


@SERVER.feature(lsp.INITIALIZE)
@guarded
def initialize(server: SensorkitServer, params: lsp.InitializeParams) -> None:
    try:
        server.overrides = Overrides.parse(params.initialization_options)
    except UsageError as exc:
        server.log(f"sensorkit: {exc}")


WATCHED = (
    "**/*.urdf",
    "**/*.xacro",
    "**/*.sdf",
    "**/*.world",
    "**/*.yaml",
    "**/*.yml",
    "**/sensorkit.toml",
    "**/pyproject.toml",
)


@SERVER.feature(lsp.INITIALIZED)
@guarded
def initialized(server: SensorkitServer, params: lsp.InitializedParams) -> None:
    """Ask the client to say when a file changes on disk (a checkout, another editor), if
    it can: the robots that read it are validated again."""
    caps = server.client_capabilities.workspace
    watch = caps.did_change_watched_files if caps is not None else None
    if watch is None or not watch.dynamic_registration:
        return
    options = lsp.DidChangeWatchedFilesRegistrationOptions(
        watchers=[lsp.FileSystemWatcher(glob_pattern=g) for g in WATCHED]
    )
    server.client_register_capability(
        lsp.RegistrationParams(
            registrations=[
                lsp.Registration(
                    id="sensorkit-watch",
                    method=lsp.WORKSPACE_DID_CHANGE_WATCHED_FILES,
                    register_options=options,
                )
            ]
        )
    )


@SERVER.feature(lsp.WORKSPACE_DID_CHANGE_WATCHED_FILES)
@guarded
def files_changed(server: SensorkitServer, params: lsp.DidChangeWatchedFilesParams) -> None:
    paths = {p for c in params.changes if (p := path_of(c.uri)) is not None}
    server.send(server.docs.disk_changed(paths))


@SERVER.feature(lsp.TEXT_DOCUMENT_DID_OPEN)
@guarded
def did_open(server: SensorkitServer, params: lsp.DidOpenTextDocumentParams) -> None:
    doc = params.text_document
    path = path_of(doc.uri)
    if path is not None:
        server.uris[path] = doc.uri
        server.send(server.docs.opened(path, doc.text, doc.version))


# Edits closer together than this are validated once, for the last: while one robot is
# validated, the keystrokes that arrive meanwhile are read in this window and only the
# newest text is checked, so diagnostics catch up with typing instead of trailing it.
SETTLE_S = 0.01


@SERVER.feature(lsp.TEXT_DOCUMENT_DID_CHANGE)
async def did_change(server: SensorkitServer, params: lsp.DidChangeTextDocumentParams) -> None:
    try:
        path = path_of(params.text_document.uri)
        if path is None:
            return
        version = params.text_document.version
        text = server.workspace.get_text_document(params.text_document.uri).source
        server.docs.edited(path, text, version)
        await asyncio.sleep(SETTLE_S)
        if server.docs.version(path) == version:  # else a newer edit validates
            server.send(server.docs.refresh(path))
    except Exception as exc:  # an async handler: guarded by hand
        failed(server, "did_change", exc)


@SERVER.feature(lsp.TEXT_DOCUMENT_DID_SAVE, lsp.SaveOptions(include_text=True))
@guarded
def did_save(server: SensorkitServer, params: lsp.DidSaveTextDocumentParams) -> None:
    path = path_of(params.text_document.uri)
    if path is not None:
        server.send(server.docs.saved(path, params.text))


@SERVER.feature(lsp.TEXT_DOCUMENT_DID_CLOSE)
@guarded
def did_close(server: SensorkitServer, params: lsp.DidCloseTextDocumentParams) -> None:
    path = path_of(params.text_document.uri)
    if path is not None:
        server.send(server.docs.closed(path))


@SERVER.feature(lsp.TEXT_DOCUMENT_HOVER)
@guarded
def hover(server: SensorkitServer, params: lsp.HoverParams) -> lsp.Hover | None:
    path = path_of(params.text_document.uri)
    if path is None:
        return None
    line = params.position.line + 1
    for analysis in server.docs.analyses_of(path):
        found = sensors_at(analysis, path, line)
        if found:
            text = hover_text(analysis, found)
            if text:
                return lsp.Hover(
                    contents=lsp.MarkupContent(kind=lsp.MarkupKind.Markdown, value=text)
                )
    return None


@SERVER.feature(
    lsp.TEXT_DOCUMENT_CODE_ACTION,
    lsp.CodeActionOptions(
        code_action_kinds=[lsp.CodeActionKind.QuickFix, lsp.CodeActionKind.SourceFixAll],
        resolve_provider=True,
    ),
)
@guarded
def code_action(server: SensorkitServer, params: lsp.CodeActionParams) -> list[lsp.CodeAction]:
    path = path_of(params.text_document.uri)
    if path is None:
        return []
    only = params.context.only
    out: list[lsp.CodeAction] = []
    if only is None or any(k.startswith(lsp.CodeActionKind.QuickFix) for k in only):
        for d in params.context.diagnostics:
            action = quick_fix(server, path, d)
            if action is not None:
                out.append(action)
    if only is not None and any(k.startswith(lsp.CodeActionKind.SourceFixAll) for k in only):
        for analysis in server.docs.analyses_of(path)[:1]:
            overlay = server.docs.overlay()
            fix = plan(analysis.top, analysis.options, overlay, None, analysis.sources)
            if fix is not None:
                kind = f"{lsp.CodeActionKind.SourceFixAll.value}.sensorkit"
                out.append(lsp.CodeAction(title=fix.title, kind=kind, edit=server.edit(fix)))
    return out


def resolves_edits(server: SensorkitServer) -> bool:
    """The client asks for a code action's edit when it is chosen (codeAction/resolve)."""
    doc = server.client_capabilities.text_document
    ca = doc.code_action if doc is not None else None
    support = ca.resolve_support if ca is not None else None
    return support is not None and "edit" in support.properties


def finding_at(
    server: SensorkitServer, path: str, code: str, line: int
) -> Iterator[tuple[Analysis, Finding]]:
    """``(analysis, finding)`` for each open robot with a finding ``code`` at ``line``
    (0-based) of ``path``."""
    for analysis in server.docs.analyses_of(path):
        for f in analysis.by_file.get(path, ()):
            if f.rule == code and (f.line or 1) - 1 == line:
                yield analysis, f
                break


def quick_fix(server: SensorkitServer, path: str, d: lsp.Diagnostic) -> lsp.CodeAction | None:
    """The safe fix of the finding diagnostic ``d`` of ``path`` shows, if it has one: from
    the first open robot (the file's own, else one including it) whose fixers fix it.

    A client that resolves edits gets the action at once, its edit computed when chosen
    (:func:`resolve`): the fixer alone says whether there is one. Otherwise the edit is
    planned now, as ``validate --fix`` plans it.
    """
    if d.source != "sensorkit" or not isinstance(d.code, str) or not has_safe_fix(d.code):
        return None
    overlay = server.docs.overlay()
    lazy = resolves_edits(server)
    for analysis, finding in finding_at(server, path, d.code, d.range.start.line):
        if lazy:
            title = offer(analysis, finding, overlay)
            if title is None:
                continue
            data = {"uri": server.uri(path), "code": d.code, "line": d.range.start.line}
            return lsp.CodeAction(
                title=title, kind=lsp.CodeActionKind.QuickFix, diagnostics=[d], data=data
            )
        fix = plan(analysis.top, analysis.options, overlay, finding, analysis.sources)
        if fix is not None:
            return lsp.CodeAction(
                title=fix.title,
                kind=lsp.CodeActionKind.QuickFix,
                diagnostics=[d],
                edit=server.edit(fix),
                is_preferred=True,
            )
    return None


@SERVER.feature(lsp.CODE_ACTION_RESOLVE)
@guarded
def resolve(server: SensorkitServer, action: lsp.CodeAction) -> lsp.CodeAction:
    """The edit of a quick fix offered by :func:`quick_fix`, planned now."""
    data = action.data if isinstance(action.data, dict) else {}
    path = path_of(str(data.get("uri", "")))
    code, line = data.get("code"), data.get("line")
    if path is None or not isinstance(code, str) or not isinstance(line, int):
        return action
    overlay = server.docs.overlay()
    for analysis, finding in finding_at(server, path, code, line):
        fix = plan(analysis.top, analysis.options, overlay, finding, analysis.sources)
        if fix is not None:
            action.edit = server.edit(fix)
            return action
    server.log(f"sensorkit: {code} at line {line + 1}: no fix any more", lsp.MessageType.Info)
    return action


def warm() -> None:
    """Import xacro now, so the first document does not pay for it: expansions run in
    this process (its lexing and parsing caches stay warm from edit to edit), or in a
    child forked from it with xacro loaded (sensorkit.loading.xacro_expand); the included
    files' results are kept from edit to edit (sensorkit.loading.xacro_fast). The describe
    layer is left to the first hover: it brings numpy, and each forked expansion costs more
    with numpy in this process (~40 ms of CPU per edit on turtlebot4, 3 paired runs)."""
    from sensorkit.loading.xacro_expand import warm as warm_xacro
    from sensorkit.loading.xacro_fast import keep_includes

    warm_xacro()
    keep_includes()  # an edit re-expands only the includes it can change


def serve() -> None:
    """Speak LSP on stdin/stdout until the client says exit.

    The protocol gets its own copies of file descriptors 0 and 1; the process's stdin
    becomes /dev/null and its stdout goes to stderr. So nothing printed by a library (or
    by an expansion child) reaches the protocol stream, and a forked xacro child never
    meets the lock of a ``sys.stdin`` that pygls' reader thread is blocked in: the child
    closes ``sys.stdin`` first thing (multiprocessing does), which would wait on that
    lock forever.
    """
    warm()
    proto_in = BoundedInput(os.fdopen(os.dup(0), "rb"))  # no message over 64 MiB is read
    proto_out = os.fdopen(os.dup(1), "wb")
    null = os.open(os.devnull, os.O_RDONLY)
    os.dup2(null, 0)
    os.close(null)
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    SERVER.start_io(proto_in, proto_out)  # type: ignore[arg-type]  # readline and read only
