""" "Did you mean": rank candidate names by the words they share, then by spelling.

``difflib.get_close_matches`` ranks by character overlap, which favours short common
names: asked for a missing ``gnss_link`` beside ``gnss_antenna_link`` and ``base_link``
it answers ``base_link``. Names in robot descriptions are built from words
(``front_camera_optical_frame``), so a shared distinctive word counts far more than a
shared ``_link`` suffix.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable
from functools import lru_cache

# Words nearly every frame name carries: sharing one says little.
GENERIC = frozenset({"link", "frame", "joint", "optical", "sensor", "base"})
_SPLIT = re.compile(r"[_\-/.\s:]+|(?<=[a-z0-9])(?=[A-Z])")


def words(name: str) -> list[str]:
    return [w.lower() for w in _SPLIT.split(name) if w]


def score(name: str, candidate: str) -> float:
    """Higher is closer: distinctive shared words, then shared generic words, then spelling."""
    a, b = words(name), words(candidate)
    shared = set(a) & set(b)
    distinctive = len(shared - GENERIC)
    generic = len(shared & GENERIC)
    # A suffix match on whole words (``gnss_link`` ends like ``antenna_gnss_link``) helps.
    tail = 0
    for x, y in zip(reversed(a), reversed(b), strict=False):
        if x != y:
            break
        tail += 1
    ratio = difflib.SequenceMatcher(None, name.lower(), candidate.lower()).ratio()
    return 3.0 * distinctive + 0.5 * generic + 0.25 * tail + ratio


@lru_cache(maxsize=1 << 18)
def _profile(name: str) -> tuple[frozenset[str], str, dict[str, int]]:
    """A name's words, lower-case spelling and letter counts (for :func:`closest`)."""
    low = name.lower()
    counts: dict[str, int] = {}
    for ch in low:
        counts[ch] = counts.get(ch, 0) + 1
    return frozenset(words(name)), low, counts


def closest(name: str, candidates: Iterable[str], n: int = 1) -> list[str]:
    """Up to ``n`` candidates that plausibly are what ``name`` meant, best first.

    A candidate qualifies by a shared distinctive word or a spelling ratio of 0.7; the
    ratio is computed only where its upper bounds reach 0.7 (difflib's real_quick_ratio
    and quick_ratio: lengths, then letters in common), so a robot of 100,000 links answers
    in a fraction of the time, with the same answer.
    """
    pool = [c for c in dict.fromkeys(candidates) if c and c != name]
    scored = []
    mine, low, counts = _profile(name)
    la = len(low)
    for c in pool:
        theirs, clow, ccounts = _profile(c)
        if not (mine & theirs) - GENERIC:
            total = la + len(clow)
            if 2.0 * min(la, len(clow)) / total < 0.7:
                continue
            common = 0
            for ch, k in counts.items():
                m = ccounts.get(ch)
                if m:
                    common += k if k < m else m
            if 2.0 * common / total < 0.7:
                continue
            if difflib.SequenceMatcher(None, low, clow).ratio() < 0.7:
                continue
        scored.append((score(name, c), c))
    scored.sort(key=lambda t: (-t[0], t[1]))
    return [c for _, c in scored[:n]]
