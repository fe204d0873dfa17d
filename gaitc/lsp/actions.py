"""Code actions: quick fixes of unknown names, and ``explain``'s verified repairs.

A quick fix of an unknown leg, gait or region replaces it with the closest declared names
of the right kind that are valid there (difflib; a blocked cell is no region to name, noGait
labels no edge), and an unknown leg may be declared instead (``leg A6 health 3``, after the
last ``legs`` statement, with the other legs' health). Each fix is checked before it is
offered: the edited text is checked again (:func:`ltlcompiler.frontend.model_from_text`)
and the fix is dropped when the checker still refuses the place it edits. Other errors
keep the fix of their "did you mean" hint (a misspelt keyword).

A repair is an edit of the whole file that :mod:`gaitc.analysis.repairs` has verified by
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

from gaitc.diagnostics import GaitcError, Span
from gaitc.lsp.analysis import Analysis, Finding
from gaitc.lsp.index import Index, Kind
from ltlcompiler import syntax as s
from ltlcompiler.model import NO_GAIT

_SUGGESTION = re.compile(r"did you mean '([^']+)'\?")
#: The checker's errors for a name it does not know: the kind, the name, where.
_UNKNOWN = (re.compile(r"unknown (leg|gait|region|name) '([^']+)' ([^;]*);"),
            re.compile(r"health\((\w+)\) needs (a leg), but '\w+' is not declared"))
CLOSEST = 3  # replacements offered for one unknown name
CUTOFF = 0.5  # the least difflib ratio of a replacement (A6 -> L6 is 0.5)
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


@dataclass(frozen=True)
class TextEdit:
    """Replace 0-based ``line``, characters ``column..end`` (exclusive), with ``text``."""

    line: int
    column: int
    end: int
    text: str


@dataclass(frozen=True)
class Fix:
    """A quick fix of one error: its title and its edits of the document."""

    title: str
    edits: tuple[TextEdit, ...]
    name: str  # the name it writes


def apply(text: str, edits: tuple[TextEdit, ...]) -> str:
    """``text`` with ``edits`` (on distinct places) made."""
    lines = text.split("\n")
    for e in sorted(edits, key=lambda e: (e.line, e.column), reverse=True):
        lines[e.line] = lines[e.line][:e.column] + e.text + lines[e.line][e.end:]
    return "\n".join(lines)


def unknown_name(finding: Finding) -> tuple[str, str, str] | None:
    """The kind (``leg``, ``gait``, ``region`` or ``name`` in a formula), the name and the
    place (``in cache``...) of an error about an undeclared name; None for another."""
    for pattern in _UNKNOWN:
        match = pattern.match(finding.message)
        if match is not None:
            if pattern is _UNKNOWN[1]:
                return "leg", match.group(1), "in health"
            return match.group(1), match.group(2), match.group(3)
    return None


def _candidates(index: Index, kind: str, place: str) -> list[str]:
    """The declared names of ``kind`` that the checker accepts in ``place``."""
    if kind == "leg":
        return index.of_kind(Kind.LEG)
    if kind == "gait":
        return [g for g in index.of_kind(Kind.GAIT) if g != NO_GAIT or place != "in edge"]
    if kind == "region":
        return list(index.cells.values()) if place == "in block" else index.free_regions()
    return [*index.free_regions(), *index.of_kind(Kind.GAIT), NO_GAIT,
            *index.of_kind(Kind.HAZARD)]


def quick_fixes(analysis: Analysis, finding: Finding) -> list[Fix]:
    """The fixes of an unknown name that the checker accepts, closest name first."""
    unknown = unknown_name(finding)
    span = finding.span
    if unknown is None or analysis.index is None or analysis.stale_tree or span is None:
        return []
    kind, name, place = unknown
    lines = analysis.text.split("\n")
    line, column = span.line - 1, span.column - 1
    found: list[Fix] = []
    if 0 <= line < len(lines) and lines[line][column:column + len(name)] == name:
        close = difflib.get_close_matches(name, _candidates(analysis.index, kind, place),
                                          n=CLOSEST, cutoff=CUTOFF)
        found += [Fix(f"Change to '{other}'",
                      (TextEdit(line, column, column + len(name), other),), other)
                  for other in close]
    if kind == "leg":
        found += _declare_leg(analysis, name)
    return [fix for fix in found if _accepted(analysis, finding, fix)]


def _declare_leg(analysis: Analysis, name: str) -> list[Fix]:
    """``leg NAME health N`` on a line after the last ``legs`` statement, N the other legs'
    health (the last statement's when they differ)."""
    if analysis.tree is None:
        return []
    decls = [st for st in analysis.tree.statements if isinstance(st, s.LegsDecl)]
    if not decls or decls[-1].span is None:
        return []
    last = decls[-1]
    assert last.span is not None
    healths = set(analysis.index.health.values()) if analysis.index is not None else set()
    health = healths.pop() if len(healths) == 1 else last.health
    end = (last.span.end_line or last.span.line) - 1
    at = len(analysis.text.split("\n")[end])
    return [Fix(f"Declare leg {name} health {health}",
                (TextEdit(end, at, at, f"\nleg {name} health {health}"),), name)]


def _accepted(analysis: Analysis, finding: Finding, fix: Fix) -> bool:
    """Whether the checker accepts the place ``fix`` edits: the edited text checks, or its
    first error is another one, elsewhere, that does not name what the fix wrote (the
    rest of the file may have errors of its own, but the fix must not make one: a leg
    then listed twice, a second goal)."""
    from ltlcompiler.frontend import model_from_text

    try:
        model_from_text(apply(analysis.text, fix.edits), analysis.path)
    except GaitcError as err:
        if re.search(rf"\b{re.escape(fix.name)}\b", err.message.split(";")[0]):
            return False
        return err.message != finding.message and not _same_place(err.span, finding.span,
                                                                   fix)
    except RecursionError:
        return False
    return True


def _same_place(new: Span | None, old: Span | None, fix: Fix) -> bool:
    """Whether ``new`` (in the edited text) is where ``old`` was before ``fix``."""
    if new is None or old is None:
        return new is old
    shift = sum(e.text.count("\n") for e in fix.edits if e.line < old.line - 1)
    return (new.line, new.column) == (old.line + shift, old.column)


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
