"""What loading leaves on, and refuses in, every document: kept apart from
``xacro_expand`` so that reading a plain URDF does not import the xacro machinery."""

from __future__ import annotations

import re

LOC_ATTR = "sk_loc_"  # "FILE_INDEX:LINE" on elements xacro expanded, for their source line

_ENTITY_RE = rb"<!ENTITY"  # compiled on first use: only files with a DOCTYPE


def forbid_entities(data: bytes) -> str | None:
    """A reason to refuse the bytes, or None. URDF never needs a DTD with entities.

    The whole file is searched: a DOCTYPE may follow any amount of comment.
    """
    # b"!" first: a one-byte search (memchr) is ten times faster than the longer one
    if b"!" in data and b"<!DOCTYPE" in data and re.search(_ENTITY_RE, data, re.IGNORECASE):
        return (
            "DTD entity declarations are not allowed (entity expansion and external "
            "entities are refused for safety); remove the <!DOCTYPE ...> block"
        )
    return None
