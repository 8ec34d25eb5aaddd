"""Edit-to-diagnostics latency of `sensorkit lsp` on turtlebot4 through a real editor
client, a headless Neovim (issue 37: the server's time is bench_lsp.py's; this is what
a user of an editor waits).

Run by hand (never in the test suite): `.venv/bin/python benchmarks/bench_editor.py`.
Needs Neovim 0.7 or newer (`apt-get install -y neovim`; Debian 12 ships 0.7.2).

The same robot, initializationOptions and edits as bench_lsp.py (imported from it):
turtlebot4's standard robot with ``gazebo:=ignition`` and the corpus as package path,
each edit adding a comment line at the end of the buffer or removing it. Neovim starts
the server itself (``vim.lsp.start_client`` + ``vim.lsp.buf_attach_client``, which 0.7
has; ``vim.lsp.start`` came in 0.8) on the robot's buffer, and a Lua script written to a
temporary folder makes each edit a real buffer change (``nvim_buf_set_lines``), so
Neovim's own change tracking sends the didChange (full text: the server asks for full
sync). Neovim's ``textDocument/publishDiagnostics`` handler is wrapped: after Neovim has
stored the diagnostics (``vim.diagnostic``), the time is taken, and an edit ends when
the diagnostics of the buffer's new version (its changedtick) are in. Wall time is
``vim.loop.hrtime()`` from just before the change to then.

Neovim debounces didChange: ``flags.debounce_text_changes`` is 150 ms when not given
in 0.7.2 (Debian 12's /usr/share/nvim/runtime/lua/vim/lsp.lua:337; its :help says nil
means none), shortened by the time since the last flush. The edits here run with it at
0 (``--debounce``), so the change is sent at once; ``--default-debounce`` adds sessions
with the flag left out. The script checks that each text Neovim sent is bench_lsp's.

The server's CPU per edit is utime+stime of the server and its reaped children from
``/proc/PID/stat``, read before the change and after the diagnostics (the pid is
``client.rpc.pid``); Lua reads the file, this script parses it as bench_lsp does.
``--with-lsp`` runs bench_lsp's bare protocol client in the same rounds (the same
edits, warm-up included), alternating with Neovim, for client latency against server
time. Prints median, p90, max, the load average before and after each session, and one
JSON line of everything.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_lsp import (
    EDIT,
    REALWORLD,
    ROBOT,
    ROOT,
    TICK,
    edited,
    pct,
    robot_options,
    run_client,
    stat_cpu,
)

LUA = r"""
local cfg = vim.fn.json_decode(table.concat(vim.fn.readfile(os.getenv('SENSORKIT_BENCH_CFG')), '\n'))
local out = { edits = {}, sha = {} }
local hrtime = vim.loop.hrtime

local function stat(pid)
  local f = io.open('/proc/' .. pid .. '/stat', 'r')
  if not f then return nil end
  local s = f:read('*a')
  f:close()
  return s
end

local function bench()
  vim.cmd('edit ' .. vim.fn.fnameescape(cfg.robot))
  local buf = vim.api.nvim_get_current_buf()
  local uri = vim.uri_from_bufnr(buf)
  local last = nil  -- the newest publishDiagnostics of this buffer, when Neovim had it
  local seen = {}
  local flags = {}
  if cfg.debounce ~= vim.NIL then flags.debounce_text_changes = cfg.debounce end
  local t_start = hrtime()
  local id = vim.lsp.start_client({
    name = 'sensorkit',
    cmd = cfg.cmd,
    cmd_cwd = cfg.cwd,
    root_dir = cfg.root,
    init_options = cfg.options,
    flags = flags,
    get_language_id = function() return 'xml' end,
    handlers = {
      ['textDocument/publishDiagnostics'] = function(err, result, ctx, config)
        vim.lsp.diagnostic.on_publish_diagnostics(err, result, ctx, config)
        if result.uri == uri then
          last = { version = result.version, t = hrtime(), n = #result.diagnostics }
        elseif #seen < 20 then
          table.insert(seen, result.uri)
        end
      end,
    },
  })
  if not id then error('start_client failed') end
  if not vim.lsp.buf_attach_client(buf, id) then error('buf_attach_client failed') end
  local client = vim.lsp.get_client_by_id(id)
  out.pid = client.rpc.pid
  local function wait_for(version, ms)
    local ok = vim.wait(ms, function() return last ~= nil and last.version == version end, 2)
    if not ok then
      error(string.format('no diagnostics for version %s in %d ms (last %s, other uris %s)',
        tostring(version), ms, vim.inspect(last), vim.inspect(seen)))
    end
    return last
  end
  -- didOpen goes out once the server has answered initialize, as version 0 (lsp.lua:539)
  local opened = wait_for(0, 120000)
  out.open_ms = (opened.t - t_start) / 1e6
  out.open_n = opened.n
  out.sync = client.resolved_capabilities.text_document_did_change
  for i = 0, cfg.warmup + cfg.edits - 1 do
    if cfg.pause_ms > 0 then vim.wait(cfg.pause_ms) end
    local before, mine = stat(out.pid), stat('self')
    local t0 = hrtime()
    if i % 2 == 0 then
      vim.api.nvim_buf_set_lines(buf, -1, -1, false, { string.format(cfg.edit, i) })
    else
      vim.api.nvim_buf_set_lines(buf, -2, -1, false, {})
    end
    local got = wait_for(vim.lsp.util.buf_versions[buf], 60000)
    local after, mine_after = stat(out.pid), stat('self')
    -- what the server was sent: the buffer's lines, each ended by a newline ('eol')
    local sent = table.concat(vim.api.nvim_buf_get_lines(buf, 0, -1, true), '\n') .. '\n'
    table.insert(out.sha, vim.fn.sha256(sent))
    if i >= cfg.warmup then
      table.insert(out.edits, { ms = (got.t - t0) / 1e6, before = before, after = after,
        nvim_before = mine, nvim_after = mine_after })
    end
  end
  out.nvim = vim.version()
  client.stop()
  vim.wait(5000, function() return client.is_stopped() end, 10)
end

local ok, err = pcall(bench)
if not ok then out.error = tostring(err) end
vim.fn.writefile({ vim.fn.json_encode(out) }, cfg.result)
vim.cmd(ok and 'qall!' or 'cquit!')
"""


def nvim_version(nvim: str) -> str:
    out = subprocess.run([nvim, "--version"], capture_output=True, text=True, check=True).stdout
    return out.splitlines()[0]


def run_nvim(
    nvim: str,
    robot: Path,
    options: dict[str, object],
    edits: int,
    warmup: int,
    debounce: int | None,
    pause_ms: int,
) -> dict[str, Any]:
    """One cold Neovim and server: open ``robot``, the warm-up edits, the counted edits."""
    with tempfile.TemporaryDirectory(prefix="bench_editor.") as tmp:
        folder = Path(tmp)
        (folder / "bench.lua").write_text(LUA)
        cfg = {
            "robot": str(robot),
            "cmd": [sys.executable, "-m", "sensorkit", "lsp"],
            "cwd": str(ROOT),
            "root": str(robot.parent),
            "options": options,
            "debounce": debounce,
            "edit": EDIT.replace("{}", "%d"),
            "edits": edits,
            "warmup": warmup,
            "pause_ms": pause_ms,
            "result": str(folder / "result.json"),
        }
        (folder / "cfg.json").write_text(json.dumps(cfg))
        env = {**os.environ, "SENSORKIT_BENCH_CFG": str(folder / "cfg.json")}
        cmd = [
            nvim,
            "--headless",
            "-n",
            "-i",
            "NONE",
            "-u",
            "NONE",
            "-c",
            f"luafile {folder / 'bench.lua'}",
        ]
        try:
            proc = subprocess.run(
                cmd,
                check=False,
                env=env,
                cwd=folder,
                capture_output=True,
                text=True,
                timeout=180 + 70 * (edits + warmup),
            )
        except subprocess.TimeoutExpired:
            sys.exit("bench_editor: Neovim did not finish in time")
        result = folder / "result.json"
        if not result.is_file():
            sys.exit(
                f"bench_editor: Neovim wrote no result (status {proc.returncode}): "
                f"{proc.stderr.strip()[-500:]}"
            )
        out: dict[str, Any] = json.loads(result.read_text())
    if "error" in out:
        sys.exit(f"bench_editor: {out['error']}")
    out["cpu_ms"] = [(stat_cpu(e["after"]) - stat_cpu(e["before"])) * 1000 for e in out["edits"]]
    out["nvim_cpu_ms"] = [
        (stat_cpu(e["nvim_after"]) - stat_cpu(e["nvim_before"])) * 1000 for e in out["edits"]
    ]
    out["wall_ms"] = [e["ms"] for e in out.pop("edits")]
    text = robot.read_text()
    want = [hashlib.sha256(edited(text, i).encode()).hexdigest() for i in range(edits + warmup)]
    if out.pop("sha") != want:
        sys.exit("bench_editor: Neovim's buffer is not bench_lsp's edited text")
    return out


MEASURES = ("wall_ms", "cpu_ms", "nvim_cpu_ms")


def summary(values: list[float]) -> dict[str, float]:
    return {
        "median": round(statistics.median(values), 1),
        "p90": round(pct(values, 0.9), 1),
        "max": round(max(values), 1),
    }


def show(name: str, s: dict[str, Any], load: tuple[float, float]) -> None:
    w, c = summary(s["wall_ms"]), summary(s["cpu_ms"])
    line = (
        f"  {name}: wall median {w['median']:.0f} ms, p90 {w['p90']:.0f}, max {w['max']:.0f}"
        f" | server CPU median {c['median']:.0f} ms, p90 {c['p90']:.0f}, max {c['max']:.0f}"
    )
    if s.get("nvim_cpu_ms"):
        line += f" | Neovim CPU median {statistics.median(s['nvim_cpu_ms']):.0f} ms"
    print(f"{line} | load {load[0]:.2f} -> {load[1]:.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--edits", type=int, default=20)
    ap.add_argument("--warmup", type=int, default=1, help="edits made first, not counted")
    ap.add_argument("--rounds", type=int, default=1, help="cold sessions of each kind")
    ap.add_argument("--robot", type=Path, default=REALWORLD / ROBOT)
    ap.add_argument(
        "--arg", action="append", help="NAME:=VALUE (default for turtlebot4: gazebo:=ignition)"
    )
    ap.add_argument(
        "--debounce",
        type=int,
        default=0,
        help="Neovim's flags.debounce_text_changes, ms (default 0)",
    )
    ap.add_argument(
        "--default-debounce",
        action="store_true",
        help="also a Neovim session with the flag left out (150 ms in 0.7.2)",
    )
    ap.add_argument(
        "--pause", type=int, default=0, help="ms between one edit's diagnostics and the next edit"
    )
    ap.add_argument(
        "--with-lsp",
        action="store_true",
        help="also bench_lsp's bare protocol client in the same rounds",
    )
    ap.add_argument("--nvim", default=os.environ.get("NVIM_BIN", "nvim"))
    a = ap.parse_args()
    sys.stdout.reconfigure(line_buffering=True)  # type: ignore[union-attr]
    nvim = shutil.which(a.nvim)
    if nvim is None:
        print(
            f"bench_editor: no Neovim ({a.nvim}) on PATH; install it, e.g. "
            "`apt-get install -y neovim` (Debian 12: 0.7.2), or name it with --nvim",
            file=sys.stderr,
        )
        sys.exit(2)
    if not a.robot.is_file():
        sys.exit(f"bench_editor: no robot at {a.robot}")
    args, options = robot_options(a.robot, a.arg)
    version = nvim_version(nvim)
    kinds: list[tuple[str, int | None]] = [(f"nvim debounce {a.debounce}", a.debounce)]
    if a.default_debounce:
        kinds.append(("nvim debounce default", None))
    if a.with_lsp:
        kinds.append(("bench_lsp client", -1))
    print(
        f"{version}; {a.robot.name} (args {args}); {a.warmup} warm-up + {a.edits} edits "
        f"per session, {a.rounds} round(s); server CPU in clock ticks of {1000 / TICK:.0f} ms"
    )
    sessions: list[dict[str, Any]] = []
    for r in range(a.rounds):
        order = kinds if r % 2 == 0 else kinds[::-1]
        for name, debounce in order:
            load0 = os.getloadavg()[0]
            if debounce == -1:
                opened, first, wall, cpu, _ = run_client(a.robot, options, a.edits, a.warmup)
                s: dict[str, Any] = {
                    "open_ms": opened * 1000,
                    "open_n": first,
                    "wall_ms": [w * 1000 for w in wall],
                    "cpu_ms": [c * 1000 for c in cpu],
                }
            else:
                s = run_nvim(nvim, a.robot, options, a.edits, a.warmup, debounce, a.pause)
            load = (load0, os.getloadavg()[0])
            s.update(kind=name, round=r, load=[round(x, 2) for x in load])
            sessions.append(s)
            show(f"round {r} {name}", s, load)
    print("all rounds, per kind (every counted edit):")
    record: dict[str, Any] = {
        "bench": "bench_editor",
        "nvim": version,
        "robot": a.robot.name,
        "args": args,
        "edits": a.edits,
        "warmup": a.warmup,
        "rounds": a.rounds,
        "pause_ms": a.pause,
        "tick_ms": 1000 / TICK,
        "kinds": {},
    }
    for name, _ in kinds:
        mine = [s for s in sessions if s["kind"] == name]
        every = {k: [x for s in mine for x in s.get(k, [])] for k in MEASURES}
        loads = [x for s in mine for x in s["load"]]
        show(name, every, (min(loads), max(loads)))
        record["kinds"][name] = {
            "wall_ms": summary(every["wall_ms"]),
            "server_cpu_ms": summary(every["cpu_ms"]),
            "nvim_cpu_ms": summary(every["nvim_cpu_ms"]) if every["nvim_cpu_ms"] else None,
            "open_ms": [round(s["open_ms"]) for s in mine],
            "load": [min(loads), max(loads)],
            "sync": mine[0].get("sync"),
        }
    print(json.dumps(record))


if __name__ == "__main__":
    main()
