"""xacro's own command line, once per job, without paying the interpreter's start-up each time.

Run as a program (``python tests/xacro_cli_forks.py < jobs.json``, in the environment of
``xacro_peer.setup``): this process imports xacro once and, for each job (an argv list),
forks a child that runs what the installed ``xacro`` script runs (``sys.exit(xacro.main())``
with ``sys.argv = ["xacro", *argv]``), its stdout and stderr going to files. The parent never
runs xacro, so every child starts from the state of a freshly imported xacro, as the command
line does; only the interpreter's start-up and the import are shared. The answer is one JSON
list of ``{"code", "out", "err"}``, as ``subprocess.run`` of the script gives them.

tests/test_xacro_fast.py compares sensorkit's fast xacro with these answers on the whole
corpus (~575 jobs): forking saves ~0.15 s of start-up per job.
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
import traceback
from pathlib import Path
from typing import Any


def _child(argv: list[str], out: Path, err: Path) -> None:
    """In the forked child: xacro's script, stdout and stderr into files; never returns."""
    code = 1
    try:
        with open(out, "wb") as fo, open(err, "wb") as fe:
            os.dup2(fo.fileno(), 1)
            os.dup2(fe.fileno(), 2)
        from xacro import main

        sys.argv = ["xacro", *argv]
        try:
            code = _exit_code(main())
        except SystemExit as exc:
            code = _exit_code(exc.code)
        except BaseException:
            traceback.print_exc()  # what the interpreter prints for an uncaught exception
            code = 1
    finally:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        finally:
            os._exit(code)


def _exit_code(value: Any) -> int:
    """What ``sys.exit(value)`` makes of a value: None 0, an int itself, else printed and 1."""
    if value is None:
        return 0
    if isinstance(value, int):
        return value
    print(value, file=sys.stderr)
    return 1


def run(jobs: list[list[str]]) -> list[dict[str, Any]]:
    import xacro  # noqa: F401  (imported once, before any fork)

    answers = []
    with tempfile.TemporaryDirectory() as tmp:
        out, err = Path(tmp, "out"), Path(tmp, "err")
        for argv in jobs:
            sys.stdout.flush()
            sys.stderr.flush()
            pid = os.fork()
            if pid == 0:
                _child(argv, out, err)
            _pid, status = os.waitpid(pid, 0)
            answers.append(
                {
                    "code": os.waitstatus_to_exitcode(status),
                    "out": out.read_bytes().decode(errors="replace"),
                    "err": err.read_bytes().decode(errors="replace"),
                }
            )
    return answers


if __name__ == "__main__":
    json.dump(run(json.load(sys.stdin)), sys.stdout)
