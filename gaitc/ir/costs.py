"""Move costs: named criteria that rank a controller's allowed moves (issue 13).

A criterion's cost of a move is the sum of the weights of its terms that hold on the move;
a term is a formula over the current state and the next inputs and outputs (primed), as in
a transition clause.  The domain (:mod:`ltlcompiler.costs`) writes them; the solver
(:mod:`gaitc.solver.preferences`) picks, among the moves its strategy allows, the cheapest.  The
neighbouring idea is SLUGS's cost-annotated specifications (``--twoDimensionalCost``).
"""

from __future__ import annotations

from dataclasses import dataclass

from gaitc.ir.formula import Expr


@dataclass(frozen=True)
class Cost:
    """One criterion: ``name``, what it means, and its weighted terms (weights >= 1)."""

    name: str
    meaning: str
    terms: tuple[tuple[int, Expr], ...] = ()
    labels: tuple[str, ...] = ()  # what each term is, in progress words (may be empty)

    def __post_init__(self) -> None:
        if any(weight < 1 for weight, _ in self.terms):
            raise ValueError(f"cost {self.name!r}: every weight must be at least 1")
        if self.labels and len(self.labels) != len(self.terms):
            raise ValueError(f"cost {self.name!r}: one label a term, or none")
