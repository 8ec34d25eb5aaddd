"""The protocol's input, with a bound on the size of one message (issue 36, item 7).

pygls reads ``Content-Length`` bytes at once: ``Content-Length: 100000000000`` ended the
server in a MemoryError. :class:`BoundedInput` stands between the stream and pygls' reader
(which calls only ``readline`` and ``read``): a message declared over :data:`MAX_MESSAGE`
is not read into memory. Its first 64 KiB are read to find its ``id``, the rest is
discarded as it comes, and pygls gets in its place a small notification,
:data:`TOO_LARGE`, that the server answers with a JSON-RPC error (``-32600``, Invalid
Request) for that id. The server keeps running and reads the next message.
"""

from __future__ import annotations

import json
import re
from typing import BinaryIO

MAX_MESSAGE = 64 * 1024 * 1024
MAX_HEADER = 8192  # one header line (a longer one is cut; pygls ignores what it cannot parse)
TOO_LARGE = "sensorkit/messageTooLarge"
_HEAD = 65536
_LENGTH = re.compile(rb"Content-Length:\s*(\d+)\r\n", re.IGNORECASE)
_ID = re.compile(rb'"id"\s*:\s*(-?\d{1,18}|"(?:[^"\\]|\\.){0,200}")')
_BODY_BYTES = 512  # the stand-in notification, padded to this length


class BoundedInput:
    """``readline`` and ``read`` of ``raw``, with over-long messages replaced (see above)."""

    def __init__(self, raw: BinaryIO, limit: int = MAX_MESSAGE) -> None:
        self.raw, self.limit = raw, limit
        self.oversized = 0  # the declared length of the message whose body comes next
        self.discard = 0  # bytes of an over-long body still to skip

    def _skip(self) -> None:
        while self.discard > 0:
            chunk = self.raw.read(min(self.discard, 1 << 20))
            if not chunk:
                self.discard = 0
                return
            self.discard -= len(chunk)

    def readline(self, size: int = -1) -> bytes:
        self._skip()
        line = self.raw.readline(MAX_HEADER)
        m = _LENGTH.fullmatch(line)
        if m is not None and int(m.group(1)) > self.limit:
            self.oversized = int(m.group(1))
            return b"Content-Length: %d\r\n" % _BODY_BYTES
        return line

    def read(self, n: int = -1) -> bytes:
        if not self.oversized:
            return self.raw.read(n)
        length, self.oversized = self.oversized, 0
        head = self.raw.read(min(_HEAD, length))
        self.discard = length - len(head)
        m = _ID.search(head)
        msg_id = json.loads(m.group(1)) if m is not None else None
        params = {"id": msg_id, "length": length, "limit": self.limit}
        body = json.dumps({"jsonrpc": "2.0", "method": TOO_LARGE, "params": params})
        return body.encode("utf-8").ljust(_BODY_BYTES)

    def close(self) -> None:
        self.raw.close()


def too_large_error(params: object) -> dict[str, object]:
    """The JSON-RPC error answering the over-long message ``params`` (of TOO_LARGE) stands for."""

    def get(key: str) -> object:
        return params.get(key) if isinstance(params, dict) else getattr(params, key, None)

    length, limit = get("length"), get("limit")
    message = f"message of {length} bytes refused: sensorkit lsp reads messages up to {limit} bytes"
    return {"jsonrpc": "2.0", "id": get("id"), "error": {"code": -32600, "message": message}}
