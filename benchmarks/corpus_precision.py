"""Precision of ``sensorkit validate`` on the labelled real-world corpora.

Runs validate on every robot in tests/corpus/robots.yaml and tests/realworld/robots.yaml,
whose files are in ../shared/corpus (as tests/labelled.py does), and prints, per corpus and per rule, how many findings are
labelled true and false, and the precision; then, per severity, how many are labelled defect,
minor or false (issue 23: at least 95 % of errors must be defects). ``--skeleton`` prints label lines for
findings that have none yet, to be judged by a person and pasted into labels.yaml.

Run: ``.venv/bin/python benchmarks/corpus_precision.py [--skeleton]``.
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from labelled import live, robots, run, skeleton, table


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--skeleton", action="store_true", help="print label lines for unlabelled findings")
    ns = ap.parse_args()
    per_rule: dict[str, Counter[str]] = {}
    per_corpus: dict[str, Counter[str]] = {}
    per_severity: dict[str, Counter[str]] = {}
    crashes = 0
    for robot in robots():
        if robot.pending and not robot.present:
            continue  # listed in wanted.yaml, not fetched into ../shared/corpus yet
        out = run(robot)
        if out.error:
            crashes += 1
            print(f"ERROR {robot.id}: {out.error}", file=sys.stderr)
            continue
        known = live(table(robot))
        todo = skeleton(out, known)
        if ns.skeleton and todo:
            print(f"- robot: {robot.key}\n  findings:\n{todo}")
        for key, count in out.keys.items():
            lab = known.get(key)
            verdict = "unlabelled" if lab is None else "true" if lab.get("verdict") is True else "false"
            per_rule.setdefault(key[0], Counter())[verdict] += count
            per_corpus.setdefault(robot.corpus.name, Counter())[verdict] += count
            severity = out.messages[key].split(":", 1)[0]
            impact = "false" if verdict == "false" else (lab or {}).get("impact", "unlabelled")
            per_severity.setdefault(severity, Counter())[impact] += count
    if ns.skeleton:
        return 0
    total: Counter[str] = Counter()
    print(f"{'':12} {'true':>5} {'false':>5} {'unlab':>5}  precision")
    for name, c in sorted(per_corpus.items()):
        total.update(c)
        print(f"{name:12} {c['true']:5} {c['false']:5} {c['unlabelled']:5}  {_p(c)}")
    print(f"{'all':12} {total['true']:5} {total['false']:5} {total['unlabelled']:5}  {_p(total)}")
    print(f"robots: {len(robots())}, could not be validated: {crashes}\n")
    for rule, c in sorted(per_rule.items()):
        print(f"{rule:12} {c['true']:5} {c['false']:5} {c['unlabelled']:5}  {_p(c)}")
    # Severity is a promise: the share of each severity's findings that change what the robot
    # does (labelled defect), against minor (true, harmless) and false.
    print(f"\n{'severity':12} {'defect':>6} {'minor':>6} {'false':>6}  defects")
    for sev in ("error", "warning", "info"):
        c = per_severity.get(sev, Counter())
        n = sum(c.values())
        share = f"{100 * c['defect'] / n:.1f} %" if n else "-"
        print(f"{sev:12} {c['defect']:6} {c['minor']:6} {c['false']:6}  {share}")
    return 0


def _p(c: Counter[str]) -> str:
    judged = c["true"] + c["false"]
    return f"{100 * c['true'] / judged:.1f} %" if judged else "-"


if __name__ == "__main__":
    raise SystemExit(main())
