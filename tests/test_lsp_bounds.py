"""Issue 36, item 7 (cause 9): the language server refuses a message over 64 MiB with a
JSON-RPC error and keeps running.

``Content-Length: 100000000000`` ended ``sensorkit lsp`` in a MemoryError traceback:
pygls reads the declared length at once. Spoken to over real stdio (tests/lsp_client.py).
"""

from __future__ import annotations

import json
from pathlib import Path

from lsp_client import Client

from sensorkit.lsp.framing import MAX_MESSAGE


def _raw(c: Client, data: bytes) -> None:
    stdin = c.proc.stdin
    assert stdin is not None
    for at in range(0, len(data), 1 << 20):
        stdin.write(data[at : at + (1 << 20)])
    stdin.flush()


def _stderr(c: Client) -> str:
    err = c.proc.stderr
    assert err is not None
    return err.read().decode("utf-8", "replace")


def test_a_message_over_64_mib_is_an_error_and_the_server_goes_on(tmp_path: Path) -> None:
    c = Client(cwd=tmp_path)
    try:
        c.initialize(tmp_path)
        head = b'{"jsonrpc": "2.0", "id": 99, "method": "textDocument/hover", "params": {"pad": "'
        body = head + b"x" * (MAX_MESSAGE + 1 - len(head) - 3) + b'"}}'
        assert len(body) == MAX_MESSAGE + 1  # just over
        _raw(c, b"Content-Length: %d\r\n\r\n" % len(body) + body)
        answer = c.wait(lambda m: m.get("id") == 99, timeout=120)
        assert answer["error"]["code"] == -32600, answer
        assert f"up to {MAX_MESSAGE} bytes" in answer["error"]["message"], answer
        assert c.proc.poll() is None  # still running: the next request is answered
        assert c.request("shutdown", None, 60) is None
        c.notify("exit")
        assert c.proc.wait(30) == 0
        assert "MemoryError" not in _stderr(c)
    finally:
        c.kill()


def test_a_message_at_the_limit_is_read(tmp_path: Path) -> None:
    """The near miss: exactly 64 MiB is an ordinary request (an unknown method: its own
    error, -32601, not the size's)."""
    c = Client(cwd=tmp_path)
    try:
        c.initialize(tmp_path)
        head = b'{"jsonrpc": "2.0", "id": 98, "method": "sensorkit/none", "params": {"pad": "'
        body = head + b"x" * (MAX_MESSAGE - len(head) - 3) + b'"}}'
        assert len(body) == MAX_MESSAGE
        _raw(c, b"Content-Length: %d\r\n\r\n" % len(body) + body)
        answer = c.wait(lambda m: m.get("id") == 98, timeout=120)
        assert answer.get("error", {}).get("code") != -32600, answer
        assert c.close() == 0
    finally:
        c.kill()


def test_a_declared_100_gb_message_ends_no_server(tmp_path: Path) -> None:
    """The issue's header: an error for its id, at once, and no MemoryError."""
    c = Client(cwd=tmp_path)
    try:
        c.initialize(tmp_path)
        start = json.dumps({"jsonrpc": "2.0", "id": 7, "method": "textDocument/hover", "params": {"pad": ""}})
        _raw(c, b"Content-Length: 100000000000\r\n\r\n" + start.encode()[:-3] + b"y" * 70_000)
        answer = c.wait(lambda m: m.get("id") == 7, timeout=60)
        assert answer["error"]["code"] == -32600 and "100000000000 bytes" in answer["error"]["message"]
        assert c.proc.poll() is None
        stdin = c.proc.stdin
        assert stdin is not None
        stdin.close()  # the client goes: the rest never comes
        c.proc.wait(30)
        err = _stderr(c)
        assert "MemoryError" not in err and "Traceback" not in err, err[-2000:]
    finally:
        c.kill()
