"""sensorkit's fast xacro (sensorkit.loading.xacro_fast, issue 37) gives what xacro's own
command line gives, byte for byte, on every file of the corpus.

The corpus's files as tests/test_corpus.py enumerates them (its repositories' .urdf and
.xacro files, and every .urdf and .xacro file of the real-world set), each without args,
and each real-world robot of tests/realworld/robots.yaml with its args. xacro's command
line runs once per job, as users run it (its entry point in a process forked per job from
one that imported xacro: tests/xacro_cli_forks.py; a sample runs the script itself too);
the fast side (tests/xacro_peer.py) runs every job in one process, so its caches carry over
from file to file as in the language server.
The jobs xacro fails on must fail alike (status, and the same error words on stderr).
"""

from __future__ import annotations

import json
import os
import random
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import pytest
import yaml
from conftest import CORPUS, REALWORLD, ROOT, corpus_package_paths, needs_corpus
from xacro_peer import setup

from sensorkit.loading import xacro_expand, xacro_fast
from sensorkit.loading.packages import PackageResolver
from sensorkit.loading.xacro_expand import ExpandOutcome, expand

pytestmark = needs_corpus

XACRO = str(Path(sys.executable).parent / "xacro")
PEER = Path(__file__).resolve().parent / "xacro_peer.py"
FORKS = Path(__file__).resolve().parent / "xacro_cli_forks.py"


def _files() -> list[Path]:
    if not CORPUS.is_dir():
        return []
    own = [
        p
        for p in CORPUS.rglob("*")
        if p.suffix in (".urdf", ".xacro") and REALWORLD not in p.parents
    ]
    real = [p for p in REALWORLD.rglob("*") if p.suffix in (".urdf", ".xacro")]
    return sorted(own) + sorted(real)


def _robots() -> list[tuple[Path, dict[str, str]]]:
    entries = yaml.safe_load((ROOT / "tests/realworld/robots.yaml").read_text()) or []
    out = []
    for e in entries:
        path = REALWORLD / e["file"]
        if e.get("pending") or not path.is_file() or not path.name.endswith(".xacro"):
            continue
        out.append((path, {k: str(v) for k, v in (e.get("args") or {}).items()}))
    return out


def _jobs() -> list[list[str]]:
    jobs = [[str(p)] for p in _files()]
    jobs += [[str(p), *(f"{k}:={v}" for k, v in args.items())] for p, args in _robots() if args]
    return jobs


def _cli(argv: list[str], env: dict[str, str], cwd: Path) -> dict[str, Any]:
    run = subprocess.run(
        [XACRO, *argv], env=env, cwd=cwd, capture_output=True, text=True, timeout=120, check=False
    )
    return {"code": run.returncode, "out": run.stdout, "err": run.stderr}


def test_the_installed_xacro_is_one_xacro_fast_was_tested_with() -> None:
    assert xacro_fast.supported()
    assert Path(XACRO).is_file()


def test_fast_xacro_is_byte_identical_to_xacros_command_line(tmp_path: Path) -> None:
    jobs = _jobs()
    assert len(jobs) > 400
    env = setup(tmp_path, list(corpus_package_paths()))
    fast = _run_peer(jobs, env, tmp_path, timeout=1200)
    with ThreadPoolExecutor(2) as pool:  # xacro's main, forked once per job: two halves
        halves = list(
            pool.map(lambda half: _cli_forks(half, env, tmp_path), (jobs[::2], jobs[1::2]))
        )
    peer: list[dict[str, Any]] = [{}] * len(jobs)
    peer[::2], peer[1::2] = halves
    # The forks are xacro's command line: the script itself gives the same on a sample,
    # failing jobs included.
    failing = [i for i, p in enumerate(peer) if p["code"] != 0][:3]
    sample = sorted({*range(0, len(jobs), len(jobs) // 8), *failing})
    for i in sample:
        assert _cli(jobs[i], env, tmp_path) == peer[i], jobs[i]
    differ = []
    for argv, ours, theirs in zip(jobs, fast, peer, strict=True):
        same = ours["code"] == theirs["code"] and ours["out"] == theirs["out"]
        if theirs["code"] != 0:
            same = same and ours["err"].strip() == theirs["err"].strip()
        if not same:
            differ.append(
                (
                    argv,
                    ours["how"],
                    ours["code"],
                    theirs["code"],
                    ours["err"][-300:],
                    theirs["err"][-300:],
                )
            )
    assert not differ, differ[:5]
    expanded = [f for f in fast if f["code"] == 0]
    bounded = [f for f in expanded if f["how"] == "bounded"]
    # The test is not vacuous: most of the corpus expands, and in this process.
    assert len(expanded) > 300 and len(bounded) >= 0.95 * len(expanded), (
        len(expanded),
        len(bounded),
    )


@pytest.mark.parametrize(
    ("path", "args"), _robots(), ids=[str(p.relative_to(REALWORLD)) for p, _a in _robots()]
)
def test_in_process_expansion_equals_the_forked_childs(
    path: Path, args: dict[str, str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """What sensorkit reads (stamped with source lines, what the expansion read) is the
    same whether the robot was expanded here or in the forked child with xacro's eval."""
    resolver = PackageResolver.from_options(corpus_package_paths()).for_file(path)
    real = xacro_expand._expand_here
    answers: list[object] = []
    # The in-process answer is kept aside and None returned: the forked child expands too.
    monkeypatch.setattr(xacro_expand, "_expand_here", lambda *a: answers.append(real(*a)))
    child = expand(path, args, resolver)
    (here,) = answers
    assert isinstance(here, ExpandOutcome)
    assert here.error_kind == child.error_kind and here.message == child.message
    assert here.xml == child.xml
    assert here.files == child.files and here.includes == child.includes
    assert here.deps == child.deps


EDITED = [  # robots edited at random in the edit loop below (top file, its args)
    (
        "turtlebot__turtlebot4/turtlebot4_description/urdf/standard/turtlebot4.urdf.xacro",
        ["gazebo:=ignition"],
    ),
    ("husarion__rosbot_ros/rosbot_description/urdf/rosbot.urdf.xacro", ["use_sim:=true"]),
    ("PR2__pr2_common/pr2_description/robots/pr2.urdf.xacro", []),
]
NUMBER = re.compile(r'(?<=")(-?\d+\.\d+)(?=")')


def _mirror(repo: Path, into: Path) -> Path:
    """``repo`` rebuilt under ``into`` from symlinks, so that one file can be replaced."""
    for folder, _dirs, names in os.walk(repo):
        here = into / Path(folder).relative_to(repo)
        here.mkdir(parents=True, exist_ok=True)
        for name in names:
            (here / name).symlink_to(Path(folder) / name)
    return into


def _edits(text: str, rng: random.Random, n: int) -> list[str]:
    """``n`` successive edits of ``text``, as a user types them: a number changed, a
    comment added or removed."""
    out = []
    for _ in range(n):
        numbers = list(NUMBER.finditer(text))
        if numbers and rng.random() < 0.7:
            m = rng.choice(numbers)
            value = f"{float(m.group(1)) + rng.choice([-1, 1]) * rng.randint(1, 9) / 100:.3f}"
            text = text[: m.start()] + value + text[m.end() :]
        elif "<!-- edit -->" in text:
            text = text.replace("<!-- edit -->\n", "", 1)
        else:
            at = text.rfind("</robot>")
            text = text[:at] + "<!-- edit -->\n" + text[at:]
        out.append(text)
    return out


def test_successive_edits_in_one_process_equal_cold_runs(tmp_path: Path) -> None:
    """As in the language server: one process expands edit after edit of the same robots
    (its caches warm), each result byte-identical to xacro's command line run cold."""
    rng = random.Random(37)
    env = setup(tmp_path / "env", list(corpus_package_paths()))
    jobs: list[list[str]] = []
    for k, (rel, args) in enumerate(EDITED):
        top = REALWORLD / rel
        repo = REALWORLD / Path(rel).parts[0]
        for i, text in enumerate(_edits(top.read_text(), rng, 4)):
            mirror = _mirror(repo, tmp_path / f"r{k}e{i}")
            edited = mirror / Path(rel).relative_to(Path(rel).parts[0])
            edited.unlink()
            edited.write_text(text)
            jobs.append([str(edited), *args])
    fast = _run_peer(jobs, env, tmp_path, timeout=600)
    for argv, ours in zip(jobs, fast, strict=True):
        theirs = _cli(argv, env, tmp_path)
        assert theirs["code"] == 0, theirs["err"][-500:]
        assert (ours["code"], ours["how"]) == (0, "bounded"), ours["err"][-500:]
        assert ours["out"] == theirs["out"], argv


KEPT = [  # robots the kept results are checked on: args to switch, the edits in turn
    (
        "turtlebot__turtlebot4/turtlebot4_description/urdf/standard/turtlebot4.urdf.xacro",
        {"gazebo": ["ignition", "classic"]},
        ["top", "include", "arg", "include"],
    ),
    (
        "husarion__rosbot_ros/rosbot_description/urdf/rosbot.urdf.xacro",
        {"use_sim": ["true", "false"]},
        ["include", "arg", "top", "include"],
    ),
    ("PR2__pr2_common/pr2_description/robots/pr2.urdf.xacro", {}, ["include"]),
]


def _edit(text: str, rng: random.Random) -> str:
    """One edit as a user types it: a number changed (anywhere, a property's value too),
    or a comment added or removed (at the end, in a file whose root is not a robot)."""
    if "</robot>" not in text:
        return text + "<!-- edit -->\n" if rng.random() < 0.5 else text + " "
    return _edits(text, rng, 1)[0]


@pytest.mark.parametrize(("rel", "switch", "edits"), KEPT, ids=[Path(k[0]).name for k in KEPT])
def test_kept_includes_give_what_a_cold_expansion_gives(
    rel: str, switch: dict[str, list[str]], edits: list[str]
) -> None:
    """The language server keeps each include's and macro call's result
    (xacro_fast.keep_includes) and replays it where nothing it read changed. Over edits
    of the top file, of the files it includes (as open buffers) and of the args, in turn
    (what each changes drawn at random), every expansion with the kept results equals a
    cold one (no kept results) exactly: the XML with its line stamps,
    the files and includes, and everything the expansion read. The cold in-process
    expansion is xacro's command line's output byte for byte (the tests above)."""
    top = REALWORLD / rel
    resolver = PackageResolver.from_options(corpus_package_paths())
    rng = random.Random(rel)
    args = {k: v[0] for k, v in switch.items()}
    texts: dict[str, str] = {}
    files: list[str] = []
    kinds = []
    memo = xacro_fast.keep_includes()
    try:
        for step, kind in enumerate(["open", *edits]):
            if kind == "top":
                texts[str(top)] = _edit(texts.get(str(top), top.read_text()), rng)
            elif kind == "include":
                assert len(files) > 1
                name = rng.choice(files[1:])
                texts[name] = _edit(texts.get(name, Path(name).read_text()), rng)
            elif kind == "arg":
                name = rng.choice(sorted(switch))
                args[name] = rng.choice([v for v in switch[name] if v != args[name]])
            kinds.append(kind)
            overlay = {k: v.encode() for k, v in texts.items()}
            assert memo is not None
            xacro_fast._MEMO = memo
            kept = _expand_in_process(top, args, resolver, overlay)
            xacro_fast._MEMO = None
            cold = _expand_in_process(top, args, resolver, overlay)
            assert cold.error_kind is None, cold.message
            assert (kept.error_kind, kept.message) == (cold.error_kind, cold.message)
            assert kept.xml == cold.xml, (step, kinds)
            assert (kept.files, kept.includes) == (cold.files, cold.includes)
            assert kept.deps == cold.deps
            files = cold.files
        assert memo.replayed > 0 and memo.expanded > 0, (memo.replayed, memo.expanded)
        # includes and macro calls were both kept (the test is not vacuous)
        assert {k.kind for kept in memo.kept.values() for k in kept} == {"include", "macro"}
    finally:
        xacro_fast.keep_includes(False)


@pytest.mark.parametrize(("places", "budget", "replays"), [(2, 10**6, True), (64, -1, False)])
def test_a_store_too_small_keeps_what_it_has_and_a_spent_budget_expands_as_xacro(
    places: int, budget: int, replays: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A robot with more includes and calls than the store holds still replays what the
    store kept (results are not pushed out, one by one, just before they are needed); past
    the comparing budget of one expansion, xacro expands the rest. Either way the result is
    a cold expansion's."""
    from sensorkit.loading import kept_includes

    monkeypatch.setattr(kept_includes, "MAX_INCLUDES", places)
    monkeypatch.setattr(kept_includes, "RUN_BUDGET", budget)
    top = REALWORLD / KEPT[1][0]
    resolver = PackageResolver.from_options(corpus_package_paths())
    args = {"use_sim": "true"}
    overlay = {str(top): top.read_bytes() + b"<!-- edited -->"}
    cold = _expand_in_process(top, args, resolver, overlay)
    memo = xacro_fast.keep_includes()
    try:
        for _ in range(2):
            kept = _expand_in_process(top, args, resolver, overlay)
            assert (kept.xml, kept.files, kept.deps) == (cold.xml, cold.files, cold.deps)
        assert memo is not None and len(memo.kept) <= places
        assert (memo.replayed > 0) is replays, (memo.replayed, memo.expanded)
    finally:
        xacro_fast.keep_includes(False)


def _expand_in_process(
    top: Path, args: dict[str, str], resolver: PackageResolver, overlay: dict[str, bytes]
) -> ExpandOutcome:
    return xacro_expand.expand_in_process(
        top, dict(args), resolver.for_file(top), overlay=overlay, bounded=60.0
    )


LEXED = [
    "plain", "${a}", "x ${a*2} y", "$(arg n)_link", "$${kept}", "$$(kept)", "${a} ${b}$(find p)",
    "${'}'}", "", "$", "${unclosed", "$(unclosed", "a $ b",
]  # fmt: skip


@pytest.mark.parametrize("text", LEXED)
def test_the_cached_lexer_gives_xacros_tokens_and_errors(text: str) -> None:
    """Each text lexed twice by the cached lexer (made, then replayed) gives the tokens
    xacro's own lexer gives, and a text xacro cannot lex fails with xacro's own error."""
    import xacro

    def tokens(cls: Any) -> list[Any] | str:
        lexer = cls(xacro.LEXER)
        try:
            lexer.lex(text)
            out = []
            while lexer.peek():
                out.append(lexer.next())
        except xacro.XacroException as exc:
            return str(exc)
        return out

    cached = xacro_fast.lexer_class(xacro.QuickLexer)
    xacro_fast._TOKENS.pop(text, None)
    expected = tokens(xacro.QuickLexer)
    assert tokens(cached) == expected  # made
    assert tokens(cached) == expected  # replayed
    assert (text in xacro_fast._TOKENS) == (not isinstance(expected, str))


def _cli_forks(jobs: list[list[str]], env: dict[str, str], cwd: Path) -> list[Any]:
    """xacro's command line on each of ``jobs``, forked from one process (FORKS)."""
    return _driver(FORKS, jobs, env, cwd, timeout=1200)


def _run_peer(jobs: list[list[str]], env: dict[str, str], cwd: Path, timeout: int) -> list[Any]:
    """The in-process expansions of ``jobs`` by one driver process (PEER), caches warm
    across them, as JSON."""
    return _driver(PEER, jobs, env, cwd, timeout)


def _driver(script: Path, jobs: list[list[str]], env: dict[str, str], cwd: Path, timeout: int) -> list[Any]:
    """The JSON answers of ``script`` run once on the JSON list ``jobs``."""
    run = subprocess.run(
        [sys.executable, str(script)],
        input=json.dumps(jobs),
        env=env,
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    return list(json.loads(run.stdout))
