"""Prove a refactoring changes no output: run the CLI over every robot the tests and the
corpus hold and write what it prints (stdout, stderr, exit status) to one folder; run it
again after the change into another folder and compare.

    python tests/tools/same_output.py write /tmp/before
    ... change the code ...
    python tests/tools/same_output.py write /tmp/after
    python tests/tools/same_output.py compare /tmp/before /tmp/after

What runs, each in text and JSON under every target: ``validate`` on every URDF/xacro
robot of the project (tests/ and examples/, each file on its own, as a user would call
it) and on the labelled robots of the corpus run lists with their args, packages and
bridges; ``topics`` and ``intrinsics`` on the project's robots. Then ``validate`` on every
URDF/xacro file of ../shared/corpus, partials included, in one call per format. Paths are
printed as given, relative to the project root, so the two runs must use the same
checkout folder.
"""

from __future__ import annotations

import hashlib
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "corpus"
TARGETS = ("auto", "classic", "ros1", "fortress", "harmonic", "jetty")
SUFFIXES = (".urdf", ".xacro")


def _files(top: Path) -> list[str]:
    if not top.is_dir():
        return []
    return sorted(
        str(p.relative_to(ROOT)) if p.is_relative_to(ROOT) else str(p)
        for p in top.rglob("*")
        if p.is_file() and p.name.endswith(SUFFIXES)
    )


def _own() -> list[str]:
    out: list[str] = []
    for d in ("tests/robots", "tests/edit_robots", "tests/render_robots", "tests/corpus_wrappers", "examples"):
        out += _files(ROOT / d)
    return out


def _corpus() -> list[str]:
    return [str(Path("..") / "shared" / "corpus" / p.relative_to(SHARED)) for p in map(Path, _files(SHARED))]


def _listed() -> list[tuple[str, list[str]]]:
    """(name, extra argv) for each labelled robot of the run lists."""
    out = []
    lists = [(SHARED, ROOT / "tests" / "corpus" / "robots.yaml"), (SHARED / "realworld", ROOT / "tests" / "realworld" / "robots.yaml")]
    for corpus, listing in lists:
        if not listing.is_file():
            continue
        for e in yaml.safe_load(listing.read_text()) or []:
            path = corpus / e["file"]
            if e["file"].startswith("../corpus_wrappers/"):
                path = ROOT / "tests" / e["file"][3:]
            argv = [str(path)]
            for k, v in (e.get("args") or {}).items():
                argv += ["--arg", f"{k}:={v}"]
            for name, folder in (e.get("packages") or {}).items():
                argv += ["--package-path", f"{name}={corpus / folder}"]
            argv += ["--package-path", str(SHARED), "--package-path", str(SHARED / "realworld")]
            for b in e.get("bridge") or []:
                argv += ["--bridge", str(corpus / b)]
            key = hashlib.sha1(" ".join(argv).encode()).hexdigest()[:10]
            out.append((f"listed-{Path(e['file']).name}-{key}", argv))
    return out


def _jobs() -> list[tuple[str, list[str]]]:
    jobs: list[tuple[str, list[str]]] = []
    everything = _own()
    for fmt in ("text", "json"):
        jobs.append((f"corpus-all-{fmt}", ["validate", "--jobs", "2", "--format", fmt, *_corpus()]))
    for t in TARGETS:
        for fmt in ("text", "json"):
            for f in everything:
                key = hashlib.sha1(f.encode()).hexdigest()[:10]
                jobs.append((f"validate-{t}-{fmt}-{Path(f).name}-{key}", ["validate", "--target", t, "--format", fmt, f]))
            for name, argv in _listed():
                jobs.append((f"{name}-{t}-{fmt}", ["validate", "--target", t, "--format", fmt, *argv]))
        for f in _own():
            key = hashlib.sha1(f.encode()).hexdigest()[:10]
            jobs.append((f"topics-{t}-{Path(f).name}-{key}", ["topics", "--target", t, "--format", "json", f]))
            jobs.append((f"topics-{t}-text-{Path(f).name}-{key}", ["topics", "--target", t, f]))
            jobs.append((f"intrinsics-{t}-{Path(f).name}-{key}", ["intrinsics", "--target", t, f]))
    return jobs


def _run(job: tuple[str, list[str]], out: Path) -> None:
    name, argv = job
    p = subprocess.run([sys.executable, "-m", "sensorkit", *argv], cwd=ROOT, capture_output=True, timeout=300, stdin=subprocess.DEVNULL, check=False)
    (out / name).write_bytes(b"$ " + " ".join(argv).encode() + b"\n" + p.stdout + b"\n--- stderr\n" + p.stderr + f"\n--- exit {p.returncode}\n".encode())


def write(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    jobs = _jobs()
    with ThreadPoolExecutor(int(sys.argv[3]) if len(sys.argv) > 3 else 2) as pool:
        list(pool.map(lambda j: _run(j, out), jobs))
    print(f"{len(jobs)} runs written to {out}")


def compare(a: Path, b: Path) -> int:
    names = sorted({p.name for p in a.iterdir()} | {p.name for p in b.iterdir()})
    differ = [n for n in names if not (a / n).is_file() or not (b / n).is_file() or (a / n).read_bytes() != (b / n).read_bytes()]
    for n in differ[:20]:
        print("differs:", n)
    print(f"{len(names) - len(differ)} of {len(names)} runs identical")
    return 1 if differ else 0


if __name__ == "__main__":
    if sys.argv[1] == "write":
        write(Path(sys.argv[2]))
    else:
        sys.exit(compare(Path(sys.argv[2]), Path(sys.argv[3])))
