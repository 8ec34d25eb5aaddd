"""``sensorkit lsp``: a language server for URDF/xacro robots, on stdio.

The layer between ``render`` and ``cli``; with ``cli`` the only one that speaks a protocol.
Bottom up:

- :mod:`~sensorkit.lsp.settings`: the engine's options for a document, from the settings
  file found upward from it (as the CLI reads it) and the client's initializationOptions;
- :mod:`~sensorkit.lsp.analysis`: validating a robot from the editor's unsaved buffers, and
  the one function every load goes through (:func:`~sensorkit.lsp.analysis.load`);
- :mod:`~sensorkit.lsp.documents`: which robots are open, what they include, and the
  diagnostics each file holds (findings land in the file that holds the element);
- :mod:`~sensorkit.lsp.convert`: findings as LSP diagnostics, text edits from byte diffs;
- :mod:`~sensorkit.lsp.hover`: what ``sensorkit topics`` says of a ``<sensor>``, as Markdown;
- :mod:`~sensorkit.lsp.fixes`: quick fixes, the fixers of ``validate --fix`` in memory;
- :mod:`~sensorkit.lsp.server`: the pygls server (the only module importing pygls).

pygls is an optional dependency (``pip install 'sensorkit-ros[lsp]'``); only
``sensorkit lsp`` imports this package, so the plain CLI never loads it.
"""
