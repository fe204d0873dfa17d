"""The engine on large integer maps (issue 37): the attractor start of μY, and a transition
relation built without holding every clause product at once.

The attractor (gaitc.solver.game.Game._attractor) is a warm start of each goal's least
fixpoint: the winning region must be the same with it and without it, on random games
(checked against the explicit-state reference solver too) and on the gridworlds, and every
controller it yields must pass the independent verifier.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import pytest
from games import explicit_realizable, one_hot_specs, tiny_specs
from hypothesis import given, settings
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from bench.families.gridworld import evasion_text, gridworld_text  # noqa: E402
from gaitc.core.spec import parse  # noqa: E402
from gaitc.ir.spec import SEMANTICS, GR1Spec, Semantics  # noqa: E402
from gaitc.solver import synthesis  # noqa: E402
from gaitc.solver.game import Game, GameResult  # noqa: E402
from gaitc.solver.symbolic import PENDING_NODES, Options, SymbolicSpec  # noqa: E402
from gaitc.verifier.strategy import verify  # noqa: E402

# slow: large maps, about 20 s in all (docs/background/testing.md)
pytestmark = pytest.mark.slow


def _winning(spec: GR1Spec, attractor: bool) -> tuple[SymbolicSpec, Game, GameResult]:
    sym = SymbolicSpec(spec, Options(reordering=False, attractor=attractor))
    game = Game(sym)
    return sym, game, game.solve()


@settings(max_examples=150, deadline=None)
@given(spec=st.one_of(tiny_specs(), one_hot_specs()), semantics=st.sampled_from(SEMANTICS))
def test_the_attractor_start_keeps_the_winning_region(spec: GR1Spec, semantics: Semantics) -> None:
    """Same winning region (as a set of states: the two managers are different, so the
    regions are compared by their satisfying assignments), same verdict as the explicit
    reference solver."""
    regions = []
    for attractor in (False, True):
        sym, game, result = _winning(spec, attractor)
        bits = sym.input_bits + sym.output_bits
        region = result.winning
        regions.append(sorted(tuple(sorted(a.items()))
                              for a in sym.bdd.pick_iter(region, care_vars=set(bits))))
        verdict = game.initially_winning(region, semantics)
    assert regions[0] == regions[1]
    assert verdict == explicit_realizable(spec, semantics)


@settings(max_examples=60, deadline=None)
@given(spec=st.one_of(tiny_specs(), one_hot_specs()), semantics=st.sampled_from(SEMANTICS))
def test_every_controller_of_the_attractor_start_verifies(spec: GR1Spec,
                                                          semantics: Semantics) -> None:
    controller = synthesis.synthesize(spec, semantics, options=Options(reordering=False))
    if controller is not None:
        assert verify(spec, controller, semantics).ok


def test_a_gridworld_goal_is_decided_by_its_attractor() -> None:
    """The obstacle's liveness takes the X fixpoints 16 steps a ring; the attractor needs
    one CPre a ring and already holds every state, so no X fixpoint runs."""
    spec = parse(gridworld_text(6), "grid.structuredslugs").gr1
    _, _, quick = _winning(spec, True)
    _, _, classic = _winning(spec, False)
    assert quick.stats.x_iterations == quick.stats.y_iterations
    assert classic.stats.x_iterations > 10 * quick.stats.x_iterations
    controller = synthesis.synthesize(spec, Semantics.DEFAULT, options=Options(reordering=False))
    assert controller is not None
    assert verify(spec, controller, Semantics.DEFAULT).ok


def test_an_evasion_grid_is_realizable_either_way() -> None:
    spec = parse(evasion_text(8, 8), "evasion.structuredslugs").gr1
    for attractor in (False, True):
        _, game, result = _winning(spec, attractor)
        assert game.initially_winning(result.winning, Semantics.DEFAULT)


def test_the_relation_is_built_without_every_clause_product_alive() -> None:
    """The 512 x 512 gridworld's ρs is about 1,400 nodes; its 1,025 clause products, each
    as large as the 64 obstacle-cell invariants under them, were all alive at once (about
    430,000 live nodes at the peak); joined once they hold PENDING_NODES nodes, the peak
    stays under two and a half times that."""
    spec = parse(gridworld_text(9), "grid.structuredslugs").gr1
    sym = SymbolicSpec(spec, Options(reordering=False))
    with warnings.catch_warnings():  # dd warns that the unrelated 'mem' field changed unit
        warnings.simplefilter("ignore")
        peak = int(sym.bdd.statistics()["peak_live_nodes"])
    assert peak < 2.5 * PENDING_NODES
