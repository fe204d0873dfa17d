"""One analysis of a ``.gait`` document: its syntax tree, model, index and diagnostics.

The stages are the compiler's (:func:`gaitc.parse`: parse, check, lower to GR(1)) and
``gaitc lint``'s warnings, so the editor shows the messages and spans of the command line.
:func:`analyse` is the fast part, run at every edit: a file that stops parsing keeps the
index of its last good tree, so hover and completion keep working while a statement is
half written. :func:`primitive_findings` is the slow part (the gait search behind valve
primitives), run after it in the background. Neither raises: a failure inside gaitc is a
finding too, so a document always gets its diagnostics.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gaitc.diagnostics import Diagnostic, GaitcError, Span
from gaitc.lsp.index import Index
from ltlcompiler import syntax as s
from ltlcompiler.model import Model


@dataclass(frozen=True)
class Finding:
    """A diagnostic in the document: an error (the first the compiler meets) or a warning."""

    message: str
    span: Span | None
    severity: str  # "error" or "warning"
    hint: str | None = None


@dataclass
class Analysis:
    """What one version of a document says."""

    text: str
    path: str
    tree: s.SpecFile | None = None  # the last syntax tree that parsed
    model: Model | None = None  # None while the file has an error
    index: Index | None = None
    findings: list[Finding] = field(default_factory=list)
    stale_tree: bool = False  # the tree and index are of an earlier version

    @property
    def errors(self) -> list[Finding]:
        return [f for f in self.findings if f.severity == "error"]


def _finding(err: GaitcError | Diagnostic, severity: str) -> Finding:
    return Finding(err.message, err.span, severity, err.hint)


def internal_error(err: BaseException, path: str, doing: str) -> Finding:
    """The finding of a failure inside gaitc while ``doing`` something to the file at
    ``path``: an error at its first character, for the editor to show as it shows the
    others."""
    return Finding(f"gaitc failed while {doing}: internal error: {type(err).__name__}: {err}",
                   Span(path, 1, 1), "error",
                   "this is a bug in gaitc, not in your file; please report it")


def analyse(text: str, path: str, previous: Analysis | None = None) -> Analysis:
    """Parse, check and lower ``text`` (spans name ``path``); keep ``previous``'s tree and
    index when ``text`` does not parse. Any failure inside gaitc becomes an error finding
    (:func:`internal_error`), with ``previous``'s tree and index kept as for a file that
    does not parse."""
    try:
        return _analyse(text, path, previous)
    except Exception as err:  # a bug in gaitc must not leave the document without answers
        found = Analysis(text, path, findings=[internal_error(err, path, "analysing the file")])
        if previous is not None and previous.tree is not None:
            found.tree, found.index, found.stale_tree = previous.tree, previous.index, True
        return found


def _analyse(text: str, path: str, previous: Analysis | None) -> Analysis:
    from gaitc.api.loading import parse
    from ltlcompiler.frontend import parse_text

    found = Analysis(text, path)
    try:
        found.tree = parse_text(text, path)
    except GaitcError as err:
        found.findings.append(_finding(err, "error"))
    except RecursionError:
        found.findings.append(Finding("the file nests too deeply to read", Span(path, 1, 1),
                                      "error"))
    if found.tree is not None:
        found.index = Index(found.tree)
        try:
            spec = parse(text, path)
        except GaitcError as err:
            found.findings.append(_finding(err, "error"))
        except RecursionError:
            found.findings.append(Finding("the file nests too deeply to read",
                                          Span(path, 1, 1), "error"))
        else:
            found.model = spec.model
            found.findings.extend(_finding(d, d.severity) for d in spec.diagnostics)
            found.findings.extend(_other_encodings(found.model, spec.encoding))
    elif previous is not None and previous.tree is not None:
        found.tree, found.index, found.stale_tree = previous.tree, previous.index, True
    return found


#: Primitive findings by what they depend on (the gaits, their moves, the legs, the robot
#: files' modification times): an edit elsewhere in the file does not search again.
_PRIMITIVES: dict[object, list[Finding]] = {}
_KEPT = 16


def _other_encodings(model: Model | None, done: object) -> list[Finding]:
    """The errors of lowering with the encodings ``gaitc lint`` also tries."""
    from ltlcompiler.encoding import ENCODINGS
    from ltlcompiler.lowering import lower

    if model is None:
        return []
    for encoding in ENCODINGS:
        if encoding != done:
            try:
                lower(model, encoding)
            except GaitcError as err:
                return [_finding(err, "error")]
    return []


def primitive_findings(analysis: Analysis) -> list[Finding]:
    """The warnings and errors of the valve primitives (``gaitc lint``'s primitive check),
    for a document whose model checked; slow for gaits bound to a robot file, so the
    result is kept for the next analysis of an unchanged set of gaits."""
    model = analysis.model
    if model is None or not any(g.primitive is not None for g in model.gaits):
        return []
    from pathlib import Path

    from gaitc.api.compiling import gait_moves
    from gaitc.search.primitives import check_gaits

    moves = gait_moves(model)
    folder = Path(analysis.path).resolve().parent
    legs = [leg.name for leg in model.legs]
    robots = sorted({g.primitive.robot for g in model.gaits
                     if g.primitive is not None and g.primitive.robot})
    stamps = []
    for robot in robots:
        try:
            stamps.append((robot, (folder / robot).stat().st_mtime_ns))
        except OSError:
            stamps.append((robot, -1))
    key = (str(folder), model.gaits, tuple(sorted(moves.items())), tuple(legs), tuple(stamps))
    found = _PRIMITIVES.get(key)
    if found is None:
        try:
            found = [_finding(d, d.severity)
                     for d in check_gaits(model.gaits, str(folder), legs=legs, moves=moves)]
        except GaitcError as err:
            found = [_finding(err, "error")]
        except Exception as err:  # a bug in the search: said once, not searched again
            found = [internal_error(err, analysis.path, "checking the valve primitives")]
        if len(_PRIMITIVES) >= _KEPT:
            _PRIMITIVES.pop(next(iter(_PRIMITIVES)))
        _PRIMITIVES[key] = found
    return list(found)
