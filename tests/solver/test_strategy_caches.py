"""The explicit extraction's remembered answers (gaitc/solver/strategy.py, and
``MovePreferences.choose`` in gaitc/solver/preferences.py) change no move.

Each spec's controller is extracted twice, with the default move preferences: as shipped,
and with every cofactor and every preferred choice computed afresh from the whole state,
as the extraction did before it kept them by the bits each reads.  The two must be the
same automaton, node for node.  A cache keyed by too few bits must not pass: with every
key emptied the controllers differ.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from gaitc.core.spec import load
from gaitc.ir.bddwalk import Cofactors
from gaitc.ir.controller import Controller
from gaitc.ir.spec import Semantics
from gaitc.solver import strategy
from gaitc.solver.game import Game
from gaitc.solver.preferences import PREFERENCES, MovePreferences
from gaitc.solver.symbolic import BDDNode, SymbolicSpec
from ltlcompiler.costs import model_costs
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from dd.cudd import BDD

EXAMPLES = Path(strategy.__file__).resolve().parents[1] / "examples"
SPECS = ["corridor_hazard", "patrol_2x2", "thesis_robot_a"]


class _Afresh(Cofactors):
    """Every cofactor computed from all the variables ``fixed`` at each call."""

    def __init__(self, bdd: BDD, u: BDDNode, fixed: Collection[str], limit: int = 0) -> None:
        super().__init__(bdd, u, fixed, limit)
        self.fixed = tuple(fixed)

    def at(self, values: Mapping[str, bool]) -> BDDNode:
        return self.bdd.let({n: values[n] for n in self.fixed}, self.u)


class _Blind(Cofactors):
    """A wrong cache: every state shares one key, so the first cofactor is kept for all."""

    def __init__(self, bdd: BDD, u: BDDNode, fixed: Collection[str],
                 limit: int = 100_000) -> None:
        super().__init__(bdd, u, fixed, limit)
        self.key = lambda _: ()


def _extract(name: str, cofactors: type[Cofactors] | None = None) -> Controller:
    spec = load(str(EXAMPLES / f"{name}.gait"))
    assert spec.model is not None
    sym = SymbolicSpec(spec.gr1)
    game = Game(sym)
    result = game.solve(keep_layers=True)
    assert game.initially_winning(result.winning, Semantics.DEFAULT)
    costs = model_costs(spec.model, EncodingName(spec.encoding or "onehot"))
    prefer = MovePreferences(sym, result, costs, PREFERENCES)
    if cofactors is None:
        return strategy.extract_strategy(sym, result, Semantics.DEFAULT, prefer=prefer)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(strategy, "Cofactors", cofactors)
        patch.setattr(strategy, "remembered", lambda compute: compute)
        if cofactors is _Afresh:
            patch.setattr(prefer, "choose", prefer._choose)
        return strategy.extract_strategy(sym, result, Semantics.DEFAULT, prefer=prefer)


@pytest.mark.parametrize("name", SPECS)
def test_remembered_cofactors_give_the_same_controller(name: str) -> None:
    kept = _extract(name)
    afresh = _extract(name, _Afresh)
    assert len(kept.nodes) > 10
    assert (kept.nodes, kept.initial) == (afresh.nodes, afresh.initial)


def test_a_cache_keyed_by_too_few_bits_changes_the_controller() -> None:
    kept = _extract("corridor_hazard")
    blind = _extract("corridor_hazard", _Blind)
    assert (kept.nodes, kept.initial) != (blind.nodes, blind.initial)


def test_a_choice_remembered_without_the_state_changes_the_controller() -> None:
    kept = _extract("thesis_robot_a")
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(MovePreferences, "_reads", lambda self, goal: lambda at: ())
        blind = _extract("thesis_robot_a")
    assert (kept.nodes, kept.initial) != (blind.nodes, blind.initial)
