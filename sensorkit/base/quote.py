"""Keep what a message quotes of the user's input short (issue 25: at most ~200 characters).

A robot description can hold a name, a tag or a value of millions of characters; a
message that quotes it whole is millions of characters too (a 900 MB link name once made
validate's report take 10.5 GB). ``shorten`` keeps any one quoted piece of input to about
``QUOTE_LIMIT`` characters, whatever the message is built of, so findings (text, json,
sarif and github alike) and one-line errors stay one readable line.
"""

from __future__ import annotations

import re

# Real names are far shorter: the corpus's longest name is 67 characters and its longest
# attribute value 119 (PR2's and osrf/vrx's expanded robots).
QUOTE_LIMIT = 200
# A whole message longer than this has quoted input with spaces in it (sensorkit's own
# words are a few hundred characters at most); its middle is cut.
MESSAGE_LIMIT = 2000
_HEAD = 120
_TAIL = 40

# A quoted piece ('...' or "...") or a run without spaces, longer than QUOTE_LIMIT. A run
# is only tried from its start (the look-behind), so the search is linear in the message.
# A quote opens only where no word character precedes it and closes only where none
# follows: the apostrophe of sensorkit's own prose ("ros_gz_image's image_bridge") is
# neither, so two of them never pair up around a stretch of the message's own words.
_Q = QUOTE_LIMIT
_LONG = re.compile(
    rf"(?<!\w)'[^'\n]{{{_Q},}}'(?!\w)|(?<!\w)\"[^\"\n]{{{_Q},}}\"(?!\w)|(?<!\S)\S{{{_Q + 1},}}"
)


def clip(text: str, limit: int = QUOTE_LIMIT) -> str:
    """``text`` itself when it has at most ``limit`` characters, else its start and end
    around a note of how many characters were left out."""
    if len(text) <= limit:
        return text
    head = max(limit * _HEAD // QUOTE_LIMIT, 1)
    tail = max(limit * _TAIL // QUOTE_LIMIT, 0)
    left_out = len(text) - head - tail
    return f"{text[:head]}…[{left_out} characters left out]…{text[len(text) - tail :]}"


def shorten(message: str) -> str:
    """``message`` with every long quoted piece or spaceless run clipped (``clip``), and
    the whole cut to about ``MESSAGE_LIMIT`` characters. Short messages come back as is."""
    if len(message) <= QUOTE_LIMIT:
        return message
    # Cut a huge message first: the pattern below costs up to QUOTE_LIMIT steps a character.
    out = _LONG.sub(lambda m: clip(m.group(0)), clip(message, 10 * MESSAGE_LIMIT))
    return clip(out, MESSAGE_LIMIT)


def plural(n: int, word: str, words: str | None = None) -> str:
    """``n`` and the noun in the number it takes: ``1 error``, ``0 errors``, ``2 files``
    (``words``: an irregular plural)."""
    return f"{n} {word}" if n == 1 else f"{n} {words or word + 's'}"
