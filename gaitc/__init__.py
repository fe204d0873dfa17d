"""gaitc: a specification compiler and GR(1) synthesizer for walking soft robots.

The public API, one function per stage; each returns an object that shows itself in a
notebook (see ``docs/api.md``):

- :func:`load` / :func:`parse`: a ``.gait``, ``.slugsin`` or ``.structuredslugs`` file or
  text becomes a :class:`Spec` (the GR(1) IR, plus the robot model and source map for
  ``.gait``);
- :func:`lint`: the warnings of a ``.gait`` spec and the check of its valve primitives;
- :func:`emit`: the spec as structuredslugs, slugsin or LTL text, exactly as
  ``gaitc compile`` writes it;
- :func:`check`: a :class:`Verdict`; :func:`synthesize` and :func:`counterstrategy`: a
  :class:`Synthesis` holding an automaton that :func:`verify` has proved;
- :func:`explain`: why a spec is unrealizable (kind, core, the environment's freedoms, a
  play, verified repairs), or the sanity checks of a realizable one;
- :func:`resilience`: which leg failures, health levels, caches and hazards a task
  tolerates or needs;
- :func:`simulate`: a run of a controller against an environment, checked against the spec;
- :func:`copy_examples`: the example robots and specs shipped in the package, copied out.

Every error a user can cause is a :class:`GaitcError` with a source span, and also the
builtin exception it means: a missing file is a :class:`FileNotFoundError`, a bad value a
:class:`ValueError`, a solver that cannot finish a :class:`RuntimeError`.

The command line (:mod:`gaitc.cli`) is a thin layer over these functions.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from gaitc.api.emission import FORMATS, emit
    from gaitc.api.examples import copy_examples
    from gaitc.api.explaining import explain
    from gaitc.api.linting import lint
    from gaitc.api.loading import Spec, load, parse
    from gaitc.api.resilient import resilience
    from gaitc.api.simulation import Session, session, simulate
    from gaitc.api.solving import (
        SOLVERS,
        Synthesis,
        Verdict,
        check,
        counterstrategy,
        synthesize,
        verify,
    )
    from gaitc.diagnostics import (
        ControllerError,
        FileAccessError,
        FormulaError,
        GaitcError,
        MissingFileError,
        ScenarioError,
        SlugsFormatError,
        SolverError,
        Span,
        SpecSemanticError,
        SpecSyntaxError,
        UsageError,
    )

#: Where each public name lives; modules load on first use, so ``gaitc --help`` and a
#: Ctrl-C at start-up do not wait for the solver, the parser and the gait graph to import.
_HOMES = {
    "FORMATS": "gaitc.api.emission", "emit": "gaitc.api.emission",
    "explain": "gaitc.api.explaining", "lint": "gaitc.api.linting",
    "Spec": "gaitc.api.loading", "load": "gaitc.api.loading", "parse": "gaitc.api.loading",
    "resilience": "gaitc.api.resilient", "Session": "gaitc.api.simulation",
    "session": "gaitc.api.simulation", "simulate": "gaitc.api.simulation",
    "SOLVERS": "gaitc.api.solving", "Synthesis": "gaitc.api.solving",
    "Verdict": "gaitc.api.solving", "check": "gaitc.api.solving",
    "counterstrategy": "gaitc.api.solving", "synthesize": "gaitc.api.solving",
    "verify": "gaitc.api.solving",
    "copy_examples": "gaitc.api.examples",
    "GaitcError": "gaitc.diagnostics", "UsageError": "gaitc.diagnostics",
    "FileAccessError": "gaitc.diagnostics", "MissingFileError": "gaitc.diagnostics",
    "SpecSyntaxError": "gaitc.diagnostics", "SpecSemanticError": "gaitc.diagnostics",
    "FormulaError": "gaitc.diagnostics", "SlugsFormatError": "gaitc.diagnostics",
    "ControllerError": "gaitc.diagnostics", "SolverError": "gaitc.diagnostics",
    "ScenarioError": "gaitc.diagnostics", "Span": "gaitc.diagnostics",
}


def __getattr__(name: str) -> Any:
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module 'gaitc' has no attribute {name!r}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted([*globals(), *_HOMES])


__version__ = "0.1.0"

__all__ = [
    "FORMATS",
    "SOLVERS",
    "ControllerError",
    "FileAccessError",
    "FormulaError",
    "GaitcError",
    "MissingFileError",
    "ScenarioError",
    "Session",
    "SlugsFormatError",
    "SolverError",
    "Span",
    "Spec",
    "SpecSemanticError",
    "SpecSyntaxError",
    "Synthesis",
    "UsageError",
    "Verdict",
    "check",
    "copy_examples",
    "counterstrategy",
    "emit",
    "explain",
    "lint",
    "load",
    "parse",
    "resilience",
    "session",
    "simulate",
    "synthesize",
    "verify",
]
