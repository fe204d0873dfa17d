"""Deciding, as the facade offers it: whether a controller exists for a spec given as a
path, a loaded spec or its IR (:func:`check`).

The work is :mod:`gaitc.forms.decision`'s; this module converts the arguments.  It is all
``gaitc check`` loads of the solving side: controllers, their forms and their proofs are
:mod:`gaitc.api.solving`'s.
"""

from __future__ import annotations

from gaitc.core.spec import SpecLike, resolve
from gaitc.forms.decision import SOLVERS, SolverName, Verdict, decide
from gaitc.ir.spec import Semantics
from gaitc.solver.progress import Progress
from gaitc.solver.symbolic import Options

__all__ = ["SOLVERS", "SolverName", "Verdict", "check"]


def check(spec: SpecLike, semantics: Semantics | str = Semantics.DEFAULT, solver: str = "embedded",
          timeout: float | None = None, slugs: str | None = None,
          options: Options | None = None, progress: Progress | None = None, *,
          separation: bool = False) -> Verdict:
    """Decide whether a controller exists for ``spec`` (:func:`gaitc.forms.decision.decide`).

    ``semantics`` is ``default`` or ``robotics`` (:data:`gaitc.ir.spec.SEMANTICS`), ``solver``
    ``embedded`` or ``slugs`` (then ``slugs`` names the binary, else ``$SLUGS`` or PATH).
    With ``separation`` the embedded solver also checks, on the same build, that the spec
    is well-separated (:func:`gaitc.separation`), in the verdict's ``.separation``.
    Raises :class:`~gaitc.diagnostics.SolverError` when the solver cannot finish.
    """
    return decide(resolve(spec), semantics, solver, timeout, slugs, options, progress,
                  separation=separation)
