"""Linting: every check gaitc makes of a ``.gait`` spec without solving it.

The checker's warnings, lowering in both encodings (which catches names that clash once
encoded), and the pairing of gaits with their valve primitives (:mod:`gaitgraph.pairing`).
"""

from __future__ import annotations

from pathlib import Path

from diagnostics import Diagnostic, UsageError
from gaitc.loading import Spec, load
from ltlcompiler.encoding import ENCODINGS


def lint(spec: Spec | str | Path, primitives: bool = False) -> tuple[Diagnostic, ...]:
    """The warnings (and primitive errors) of a ``.gait`` spec; a path is read as ``.gait``.

    Gaits without a valve primitive are reported when ``primitives`` is set or once any
    gait of the spec binds one. Errors in the spec itself raise, as :func:`gaitc.load` does.
    """
    from ltlcompiler.lowering import lower

    if not isinstance(spec, Spec):
        spec = load(spec, kind=".gait")
    model = spec.model
    if model is None:
        raise UsageError(f"'{spec.path}': lint checks .gait specs")
    for encoding in ENCODINGS:
        if encoding != spec.encoding:
            lower(model, encoding)
    diagnostics = list(spec.diagnostics)
    if primitives or any(g.primitive is not None for g in model.gaits):
        from gaitgraph.pairing import check_gaits

        folder = str(Path(spec.path).resolve().parent)
        diagnostics += check_gaits(model.gaits, folder, legs=[leg.name for leg in model.legs])
    return tuple(diagnostics)
