"""``sensorkit lsp``: the language server on stdin/stdout (see :mod:`sensorkit.lsp`).

pygls is optional (``pip install 'sensorkit[lsp]'``): without it the command says so in
one line and exits 2. Nothing here is imported by the other commands.
"""

from __future__ import annotations

import typer

from sensorkit.cli.options import Command, examples

EXAMPLES = examples(
    ("What an editor runs (it speaks the protocol on stdin/stdout)", "sensorkit lsp"),
    ("Check the server is installed: it starts, reads no request and ends", "sensorkit lsp -h"),
)


def lsp() -> None:
    """Start the language server on stdin/stdout for an editor: diagnostics as you type,
    quick fixes (the safe fixes of validate --fix) and hover on a <sensor>.

    Settings come from the sensorkit.toml (or the tool.sensorkit table of a
    pyproject.toml) found upward from each document, under the client's
    initializationOptions. The editor starts it; it prints nothing to a terminal.
    """
    import importlib.util

    if importlib.util.find_spec("pygls") is None:
        typer.echo(
            "sensorkit: lsp needs pygls, which is not installed: pip install 'sensorkit[lsp]'",
            err=True,
        )
        raise typer.Exit(2)
    from sensorkit.lsp.server import serve

    serve()


def register(app: typer.Typer) -> None:
    """Add ``lsp`` to ``app``."""
    app.command("lsp", cls=Command, epilog=EXAMPLES)(lsp)
