"""Which findings ``--fix`` fixes: the ``[*]`` of validate's text output, as ruff marks them.

:func:`fixability` asks each finding's fixer for its fix on the report as validated (the
model still alive), once, as the first round of :func:`sensorkit.fix.apply.plan_file`
does: a finding is ``safe`` when its fixer returns a safe fix that edits only files of
the package being validated, ``unsafe`` when the fix needs ``--unsafe-fixes``, and
unmarked when there is no fixer, the fixer refuses, or the fix would edit another
package. The fixes are not applied, so a fix that ``--fix`` then leaves out because it
would add an error (rare: it is validated in memory first) is still marked.
"""

from __future__ import annotations

from sensorkit.fix.apply import Files, _candidates, edit_scope
from sensorkit.lint.engine import FileReport, Options

__all__ = ["fixability"]


def fixability(report: FileReport, options: Options) -> dict[int, str]:
    """The indexes in ``report.findings`` of the fixable findings -> ``safe``/``unsafe``."""
    if report.robot is None or report.target is None or not report.findings:
        return {}
    files = Files({}, dict(options.overlay))
    fixes, _notes = _candidates(report, options, files, True, edit_scope(report.path), None)
    index = {id(f): i for i, f in enumerate(report.findings)}
    out: dict[int, str] = {}
    for fix in fixes:
        i = index.get(id(fix.finding))
        if i is not None:
            out[i] = "safe" if fix.safe else out.get(i, "unsafe")
    return out
