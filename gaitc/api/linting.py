"""Linting: every check gaitc makes of a spec without solving it.

For a ``.gait`` spec the checker's warnings, lowering in both encodings (which catches
names that clash once encoded), and the pairing of gaits with their valve primitives
(:mod:`gaitc.gaitgraph.pairing`); a ``.slugsin``, ``.structuredslugs`` or ``.ltl`` spec is
read (every syntax and type error with its span) and has no further checks.
"""

from __future__ import annotations

from pathlib import Path

from gaitc.api.loading import Spec, load, reader_of
from gaitc.diagnostics import Diagnostic
from ltlcompiler.encoding import ENCODINGS


def lint(spec: Spec | str | Path, primitives: bool = False) -> tuple[Diagnostic, ...]:
    """The warnings (and primitive errors) of a spec; a path is read as ``.gait`` unless its
    suffix names another format (:func:`gaitc.api.loading.reader_of`).

    Gaits without a valve primitive are reported when ``primitives`` is set or once any
    gait of the spec binds one. Errors in the spec itself raise, as :func:`gaitc.load` does.
    """
    from ltlcompiler.lowering import lower

    if not isinstance(spec, Spec):
        spec = load(spec, kind=reader_of(str(spec)))
    model = spec.model
    if model is None:
        return tuple(spec.diagnostics)
    for encoding in ENCODINGS:
        if encoding != spec.encoding:
            lower(model, encoding)
    diagnostics = list(spec.diagnostics)
    if primitives or any(g.primitive is not None for g in model.gaits):
        from gaitc.gaitgraph.pairing import check_gaits

        folder = str(Path(spec.path).resolve().parent)
        diagnostics += check_gaits(model.gaits, folder, legs=[leg.name for leg in model.legs])
    return tuple(diagnostics)
