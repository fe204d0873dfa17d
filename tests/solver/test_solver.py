"""Tests of the embedded BDD solver (gaitc/solver/symbolic.py, game.py, synthesis.py) against an
explicit-state reference solver (tests/games.py) on random tiny specs, and of its
strategy-extraction helpers. Semantics, basics and the variable order: test_solver_basics.py.
"""

from __future__ import annotations

import itertools
from typing import Any
from unittest import mock

import pytest
from games import explicit_realizable, formulas, one_hot_specs, tiny_specs
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gaitc.diagnostics import FormulaError
from gaitc.ir.bddwalk import Cofactors
from gaitc.ir.bddwalk import holds_at as holds
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
    Expr,
    Or,
    Var,
)
from gaitc.ir.spec import SEMANTICS, Clause, GR1Spec, Variable
from gaitc.solver import game as game_module
from gaitc.solver import synthesis
from gaitc.solver.canonical import smallest
from gaitc.solver.game import Game
from gaitc.solver.portfolio import SIFTED, engine_options
from gaitc.solver.symbolic import Options, SymbolicSpec
from gaitc.verifier.counterstrategy import verify_counterstrategy
from gaitc.verifier.strategy import verify


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(tiny_specs())
def test_bdd_solver_agrees_with_explicit_solver(spec: GR1Spec) -> None:
    for semantics in ("default", "robotics"):
        expected = explicit_realizable(spec, semantics)
        assert synthesis.check(spec, semantics).realizable == expected, semantics


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(one_hot_specs())
def test_care_set_solver_agrees_with_explicit_solver_on_one_hot_specs(spec: GR1Spec) -> None:
    sym = SymbolicSpec(spec)
    assert sym.invariant != sym.bdd.true  # the mutexes are found as invariants
    for semantics in ("default", "robotics"):
        expected = explicit_realizable(spec, semantics)
        assert synthesis.check(spec, semantics).realizable == expected, semantics
        unmasked = synthesis.check(spec, semantics, options=Options(care=False))
        assert unmasked.realizable == expected, semantics


def _holds(sym: SymbolicSpec, u: object, point: dict[str, bool]) -> bool:
    return bool(sym.bdd.let(point, u) == sym.bdd.true)


@pytest.mark.parametrize(
    "options",
    [
        Options(order="declaration", partitioned=False, recycle=False, care=False),
        Options(order="occurrence", partitioned=True, recycle=True, cluster_limit=1),
        Options(reordering=True),
        Options(reorder_once=True, order="declaration"),
        Options(care=False, recycle=False),
        engine_options(SIFTED),
        Options(sift_build=True, care=False, order="occurrence"),
        Options(sift_above=0),  # every build starts again, sifting
        Options(sift_above=None, sift_blowup=0),  # every static build is sifted once built
    ],
    ids=["plain", "clustered", "reordering", "reorder-once", "no-care", "race-second",
         "sift-build", "sift-restart", "sift-settle"],
)
@settings(max_examples=25, deadline=None)
@given(spec=st.one_of(tiny_specs(), one_hot_specs()))
def test_every_tuning_option_gives_the_same_winning_region(spec: GR1Spec, options: Options) -> None:
    base = SymbolicSpec(spec)  # each solver is exact on its care set
    other = SymbolicSpec(spec, options)
    _same_where_both_exact(base, Game(base).solve().winning,
                           other, Game(other).solve().winning)


@settings(max_examples=25, deadline=None)
@given(spec=st.one_of(tiny_specs(), one_hot_specs()))
def test_a_restarted_build_that_sifts_again_in_the_game_gives_the_same_winning_region(
        spec: GR1Spec) -> None:
    """The restart's second sifting (Game.resume_sifting), forced at the first step."""
    base = SymbolicSpec(spec)
    other = SymbolicSpec(spec, Options(sift_above=0))  # restarts if it has ρ clauses
    with mock.patch.object(game_module, "RESIFT_WORK", -1):
        game = Game(other)
        w2 = game.solve().winning
    if other.restarted and game.stats.x_iterations:
        assert game.stats.resumed_sifting
    assert other.bdd.configure()["reordering"] is False  # the sifting ended with the game
    _same_where_both_exact(base, Game(base).solve().winning, other, w2)


@settings(max_examples=25, deadline=None)
@given(spec=st.one_of(tiny_specs(), one_hot_specs()))
def test_a_static_order_that_sifts_once_its_images_blow_up_gives_the_same_winning_region(
        spec: GR1Spec) -> None:
    """The blow-up rule of Game._order_misfits (not restarted), forced at the first step."""
    base = SymbolicSpec(spec)
    other = SymbolicSpec(spec, Options(sift_above=None, sift_blowup=None))  # never refits
    with mock.patch.object(game_module, "RESIFT_NODES", -1), \
            mock.patch.object(game_module, "RESIFT_BLOWUP", -1):
        game = Game(other)
        w2 = game.solve().winning
    assert not other.refitted
    if game.stats.x_iterations:
        assert game.stats.resumed_sifting
    assert other.bdd.configure()["reordering"] is False  # the sifting ended with the game
    _same_where_both_exact(base, Game(base).solve().winning, other, w2)


def _same_where_both_exact(base: SymbolicSpec, w1: Any, other: SymbolicSpec, w2: Any) -> None:
    """Two winning regions of one spec agree on every state both solvers are exact on."""
    names = list(base.input_bits + base.output_bits)
    for bits in itertools.product((False, True), repeat=len(names)):
        point = dict(zip(names, bits, strict=True))
        if _holds(base, base.care, point) and _holds(other, other.care, point):
            assert _holds(base, w1, point) == _holds(other, w2, point), point


# ---------------------------------------------------------------- extraction helpers
@settings(max_examples=40, deadline=None)
@given(formula=formulas(["a", "b", "c", "d"], 8))
def test_walking_helpers_agree_with_cofactors(formula: Expr) -> None:
    spec = GR1Spec(outputs=tuple(Variable(n) for n in "abcd"))
    sym = SymbolicSpec(spec, Options(order="declaration"))
    u = sym.translate(formula)
    names = list("abcd")
    models = []
    for bits in itertools.product((0, 1), repeat=4):
        point = dict(zip(names, map(bool, bits), strict=True))
        assert holds(u, point) == evaluate(formula, point)
        if evaluate(formula, point):
            models.append(bits)
    # with the declaration order the BDD order is a, b, c, d: the smallest model
    assert smallest(sym, u, names) == (min(models) if models else None)


@settings(max_examples=40, deadline=None)
@given(formula=formulas(["a", "b", "c", "d"], 8), fixed=st.sets(st.sampled_from("abcd")),
       limit=st.integers(1, 4))
def test_remembered_cofactors_are_the_cofactors(formula: Expr, fixed: set[str],
                                                limit: int) -> None:
    """gaitc.ir.bddwalk.Cofactors against dd's own cofactor at every assignment to ``fixed``,
    twice over (the second time from its memory, or after it forgot at ``limit``)."""
    spec = GR1Spec(outputs=tuple(Variable(n) for n in "abcd"))
    sym = SymbolicSpec(spec, Options(order="declaration"))
    u = sym.translate(formula)
    remembered = Cofactors(sym.bdd, u, fixed, limit=limit)
    names = sorted(fixed)
    for _ in range(2):
        for bits in itertools.product((False, True), repeat=len(names)):
            point = dict(zip(names, bits, strict=True))
            assert remembered.at(point | {"other": True}) == sym.bdd.let(point, u)
    assert len(remembered.known) <= limit


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(spec=one_hot_specs(), semantics=st.sampled_from(SEMANTICS))
def test_automata_from_the_care_set_game_pass_the_verifier(spec: GR1Spec, semantics: str) -> None:
    controller = synthesis.synthesize(spec, semantics)
    if controller is not None:
        assert verify(spec, controller, semantics).ok
        return
    counter = synthesis.counterstrategy(spec, semantics)
    assert counter is not None
    assert verify_counterstrategy(spec, counter, semantics).ok


def test_solver_rejects_next_state_outputs_in_env_trans() -> None:
    """As SLUGS does; built through the API, such a spec must not reach the fixpoint.

    (Primed outputs in env_liveness are accepted, as SLUGS does: fastslow_ICRA uses them.)
    """
    from gaitc.ir.spec import GR1Spec, Variable

    base = GR1Spec(inputs=(Variable("a"),), outputs=(Variable("y"),))
    spec = base.with_sections(env_trans=(Clause(Or((Var("a"), Var("y", True)))),))
    for run in (synthesis.check, synthesis.synthesize, synthesis.counterstrategy):
        with pytest.raises(FormulaError, match="next-state output 'y'' cannot appear"):
            run(spec)
