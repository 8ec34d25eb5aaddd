"""``sensorkit lsp``: the language server on stdin/stdout (see :mod:`sensorkit.lsp`).

pygls is optional (the ``lsp`` extra of the ``sensorkit-ros`` distribution): without it the
command says so in one line and exits 2. Typed in a terminal (stdin a tty), it says that it
waits for an editor, and one Ctrl-C ends it at once (pygls' reader thread would otherwise
hold the process for a second one). Nothing here is imported by the other commands.
"""

from __future__ import annotations

import typer

from sensorkit.cli.options import Command, examples

EXAMPLES = examples(
    ("What an editor runs (it speaks the protocol on stdin/stdout)", "sensorkit lsp"),
    ("Check the server is installed: it starts, reads no request and ends", "sensorkit lsp -h"),
)


# How to add pygls, for each way of installing sensorkit: the distribution's own name (the
# PyPI project `sensorkit` is another one), a clone, and pipx.
INSTALL_LSP = (
    "pip install 'sensorkit-ros[lsp]' (from a clone: pip install './sensorkit[lsp]'; "
    "with pipx: pipx inject sensorkit-ros pygls)"
)


def lsp() -> None:
    """Start the language server on stdin/stdout for an editor: diagnostics as you type,
    quick fixes (the safe fixes of validate --fix) and hover on a <sensor>.

    Settings come from the sensorkit.toml (or the tool.sensorkit table of a
    pyproject.toml) found upward from each document, under the client's
    initializationOptions. The editor starts it; typed in a terminal, it says that it
    waits for an editor, and Ctrl-C ends it.
    """
    import importlib.util
    import os
    import signal
    import sys

    if importlib.util.find_spec("pygls") is None:
        typer.echo(
            f"sensorkit: lsp needs pygls, which is not installed: {INSTALL_LSP}",
            err=True,
        )
        raise typer.Exit(2)
    if sys.stdin.isatty():
        # The handler first: a Ctrl-C typed as soon as the words appear must end it.
        signal.signal(signal.SIGINT, lambda _sig, _frame: os._exit(130))
        typer.echo(
            "sensorkit lsp: a language server, waiting for an editor to speak LSP on "
            "stdin/stdout (the README's Editor section says how to start it from yours); "
            "Ctrl-C ends it",
            err=True,
        )
    from sensorkit.lsp.server import serve

    serve()


def register(app: typer.Typer) -> None:
    """Add ``lsp`` to ``app``."""
    app.command("lsp", cls=Command, epilog=EXAMPLES)(lsp)
