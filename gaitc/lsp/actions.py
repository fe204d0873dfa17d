"""Code actions: the compiler's "did you mean" fixes, and ``explain``'s verified repairs.

A fix replaces the misspelt name an error points at with the name its hint suggests. A
repair is an edit of the whole file that :mod:`gaitc.analysis.repairs` has verified by
solving the edited spec again (thesis chapter 3's game); finding them takes seconds, so
the editor asks for them with a command (run off the request loop by
:mod:`gaitc.lsp.jobs`) and they are offered as edits afterwards, as the smallest line
changes that turn the document into the repaired text.
"""

from __future__ import annotations

import contextlib
import difflib
import importlib
import re
from collections.abc import Callable
from dataclasses import dataclass

from gaitc.lsp.analysis import Finding

_SUGGESTION = re.compile(r"did you mean '([^']+)'\?")
#: The modules :func:`find_repairs` imports (with theirs), imported in the server before
#: its child is forked (:mod:`gaitc.lsp.jobs`): a child must import nothing, for another
#: thread of the server may hold the import lock of that very module as it forks.
#: ``tests/lsp/test_lsp_robustness.py`` checks that the list is complete.
REPAIR_IMPORTS = (
    "gaitc", "gaitc.api", "gaitc.api.loading", "gaitc.api.answers", "gaitc.api.isolation",
    "gaitc.analysis.explanation", "gaitc.analysis.repairs", "gaitc.solver.synthesis",
    "gaitc.solver.portfolio", "gaitc.solver.counter", "gaitc.solver.strategy",
    "gaitc.solver.preferences", "gaitc.solver.symbolic_strategy", "gaitc.ir.bddfile",
    "gaitc.ir.quotient", "gaitc.ir.evaluation", "gaitc.sim.counterplay", "gaitc.ir.cuddlib",
    "ltlcompiler.frontend", "ltlcompiler.decoding", "ltlcompiler.parser",
    "multiprocessing.popen_fork", "ctypes",
)  # fmt: skip


@dataclass(frozen=True)
class LineEdit:
    """Replace 0-based lines ``start..end`` (exclusive) with ``lines``."""

    start: int
    end: int
    lines: tuple[str, ...]


@dataclass(frozen=True)
class RepairEdit:
    """A verified repair as edits of the document it was found for."""

    title: str
    edits: tuple[LineEdit, ...]


def suggestion(finding: Finding) -> str | None:
    """The name a finding's "did you mean" hint suggests (None without one)."""
    for text in (finding.hint or "", finding.message):
        match = _SUGGESTION.search(text)
        if match is not None:
            return match.group(1)
    return None


def line_edits(old: str, new: str) -> tuple[LineEdit, ...]:
    """The fewest line replacements that turn ``old`` into ``new`` (difflib's opcodes)."""
    a, b = old.split("\n"), new.split("\n")
    matcher = difflib.SequenceMatcher(a=a, b=b, autojunk=False)
    return tuple(LineEdit(i1, i2, tuple(b[j1:j2]))
                 for tag, i1, i2, j1, j2 in matcher.get_opcodes() if tag != "equal")


def preload_repairs() -> None:
    """Import :data:`REPAIR_IMPORTS` (those that exist here) in this process."""
    for name in REPAIR_IMPORTS:
        with contextlib.suppress(ImportError):  # an optional one, or another platform's
            importlib.import_module(name)


def find_repairs(text: str, path: str, timeout: float,
                 report: Callable[[str], None] | None = None) -> tuple[str, list[RepairEdit]]:
    """Solve ``text``; for an unrealizable spec, its verified repairs as edits. Returns a
    sentence for the user and the repairs; ``report`` is told each stage as it starts."""
    import gaitc
    from gaitc.diagnostics import GaitcError

    tell = report or (lambda words: None)
    try:
        tell("reading the spec")
        spec = gaitc.parse(text, path)
        tell("solving the spec, then verifying each candidate repair")
        why = gaitc.explain(spec, timeout=timeout, repairs=True)
    except GaitcError as err:
        return f"gaitc could not look for repairs: {err.message}", []
    if why.realizable:
        return "the spec is realizable: there is nothing to repair", []
    found = [RepairEdit(f"Repair: {r.change} (verified realizable)", line_edits(text, r.text))
             for r in why.repairs]
    if not found:
        tried = ", ".join(why.repairs_tried) or "none"
        return f"no single repair makes the spec realizable (tried: {tried})", []
    return (f"{len(found)} verified repair{'s' * (len(found) != 1)} found: apply one from the "
            "code actions (the light bulb)"), found
