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
- :func:`simulate`: a run of a controller against an environment, checked against the spec.

The command line (:mod:`gaitc.cli`) is a thin layer over these functions.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from gaitc.emission import FORMATS, emit
    from gaitc.explaining import explain
    from gaitc.linting import lint
    from gaitc.loading import Spec, load, parse
    from gaitc.resilient import resilience
    from gaitc.simulation import Session, session, simulate
    from gaitc.solving import (
        SOLVERS,
        Synthesis,
        Verdict,
        check,
        counterstrategy,
        synthesize,
        verify,
    )

#: Where each public name lives; modules load on first use, so ``gaitc --help`` and a
#: Ctrl-C at start-up do not wait for the solver, the parser and the gait graph to import.
_HOMES = {
    "FORMATS": "gaitc.emission", "emit": "gaitc.emission", "explain": "gaitc.explaining",
    "lint": "gaitc.linting", "Spec": "gaitc.loading", "load": "gaitc.loading",
    "parse": "gaitc.loading", "resilience": "gaitc.resilient", "Session": "gaitc.simulation",
    "session": "gaitc.simulation", "simulate": "gaitc.simulation", "SOLVERS": "gaitc.solving",
    "Synthesis": "gaitc.solving", "Verdict": "gaitc.solving", "check": "gaitc.solving",
    "counterstrategy": "gaitc.solving", "synthesize": "gaitc.solving",
    "verify": "gaitc.solving",
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
    "Session",
    "Spec",
    "Synthesis",
    "Verdict",
    "check",
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
