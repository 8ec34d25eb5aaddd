"""A minimal LSP client over a subprocess's stdin/stdout: Content-Length framing,
requests with ids, notifications, and waiting (with a timeout) for a message.

Used by tests/test_lsp.py and benchmarks/bench_lsp.py; written here, not taken from
pygls, so the tests check the wire format an editor sees.
"""

from __future__ import annotations

import json
import os
import queue
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

Message = dict[str, Any]


def uri(path: Path) -> str:
    return path.resolve().as_uri()


class Client:
    """``python -m sensorkit lsp`` started, spoken to as an editor does."""

    def __init__(self, cwd: Path | None = None, env: dict[str, str] | None = None) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "sensorkit", "lsp"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            cwd=cwd,
            env={**os.environ, **(env or {})},
        )
        self.inbox: queue.Queue[Message] = queue.Queue()
        self.seen: list[Message] = []  # every message from the server, in order
        self.next_id = 0
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    # ------------------------------------------------------------------ wire

    def _read(self) -> None:
        out = self.proc.stdout
        assert out is not None
        while True:
            length = None
            while True:
                line = out.readline()
                if not line:
                    return
                line = line.strip()
                if not line:
                    break
                name, _, value = line.decode("ascii").partition(":")
                if name.lower() == "content-length":
                    length = int(value)
            if length is None:
                continue
            self.inbox.put(json.loads(out.read(length)))

    def _write(self, message: Message) -> None:
        body = json.dumps({"jsonrpc": "2.0", **message}).encode("utf-8")
        stdin = self.proc.stdin
        assert stdin is not None
        stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        stdin.flush()

    def notify(self, method: str, params: Any = None) -> None:
        self._write({"method": method, "params": params})

    def respond(self, rid: Any, result: Any = None) -> None:
        """Answer a request of the server's (client/registerCapability, ...)."""
        self._write({"id": rid, "result": result})

    def send_request(self, method: str, params: Any = None) -> int:
        self.next_id += 1
        self._write({"id": self.next_id, "method": method, "params": params})
        return self.next_id

    def request(self, method: str, params: Any = None, timeout: float = 60) -> Any:
        rid = self.send_request(method, params)
        msg = self.wait(lambda m: m.get("id") == rid and "method" not in m, timeout)
        assert "error" not in msg, msg
        return msg.get("result")

    def wait(self, pred: Callable[[Message], bool], timeout: float = 60) -> Message:
        """The first message (already seen or coming) for which ``pred`` holds."""
        for m in self.seen:
            if pred(m):
                self.seen.remove(m)
                return m
        end = time.monotonic() + timeout
        while True:
            left = end - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"no such message within {timeout} s; seen: {self.seen[-5:]}")
            try:
                m = self.inbox.get(timeout=left)
            except queue.Empty:
                continue
            if pred(m):
                return m
            self.seen.append(m)

    def diagnostics(
        self, path: Path, version: int | None = None, timeout: float = 60
    ) -> list[Message]:
        """The next publishDiagnostics for ``path`` (for ``version``, when given)."""
        want = uri(path)

        def pred(m: Message) -> bool:
            if m.get("method") != "textDocument/publishDiagnostics":
                return False
            p = m["params"]
            return bool(p["uri"] == want and (version is None or p.get("version") == version))

        return list(self.wait(pred, timeout)["params"]["diagnostics"])

    # ------------------------------------------------------------------ protocol

    def initialize(self, root: Path, options: Any = None, capabilities: Any = None) -> Any:
        result = self.request(
            "initialize",
            {
                "processId": os.getpid(),
                "rootUri": uri(root),
                "capabilities": capabilities or {},
                "initializationOptions": options,
            },
        )
        self.notify("initialized", {})
        return result

    def open(self, path: Path, text: str | None = None, version: int = 1) -> None:
        text = path.read_text() if text is None else text
        self.notify(
            "textDocument/didOpen",
            {
                "textDocument": {
                    "uri": uri(path),
                    "languageId": "xml",
                    "version": version,
                    "text": text,
                }
            },
        )

    def change(self, path: Path, text: str, version: int) -> None:
        self.notify(
            "textDocument/didChange",
            {
                "textDocument": {"uri": uri(path), "version": version},
                "contentChanges": [{"text": text}],
            },
        )

    def close_document(self, path: Path) -> None:
        self.notify("textDocument/didClose", {"textDocument": {"uri": uri(path)}})

    def close(self, timeout: float = 30) -> int:
        """shutdown, exit; the process's exit status."""
        self.request("shutdown", None, timeout)
        self.notify("exit")
        try:
            return self.proc.wait(timeout)
        finally:
            self.kill()

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(10)
        for stream in (self.proc.stdin, self.proc.stdout, self.proc.stderr):
            if stream is not None:
                stream.close()


def apply_edits(text: str, edits: list[Message]) -> str:
    """``text`` with LSP TextEdits applied (positions in UTF-16 units, as negotiated by
    default), last first."""
    lines = text.split("\n")

    def offset(pos: Message) -> int:
        before = sum(len(line) + 1 for line in lines[: pos["line"]])
        row = lines[pos["line"]] if pos["line"] < len(lines) else ""
        units, i = 0, 0
        while i < len(row) and units < pos["character"]:
            units += 2 if ord(row[i]) > 0xFFFF else 1
            i += 1
        return before + i

    spans = sorted(
        ((offset(e["range"]["start"]), offset(e["range"]["end"]), e["newText"]) for e in edits),
        reverse=True,
    )
    for start, end, new in spans:
        text = text[:start] + new + text[end:]
    return text
