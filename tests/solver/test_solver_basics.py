"""Tests of the embedded solver's semantics, basic games, limits and variable order."""

from __future__ import annotations

import itertools
from collections.abc import Iterator

import pytest
from games import clauses, one_hot_specs, tiny_specs, v
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.diagnostics import FormulaError, SolverError
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
    Add,
    And,
    Compare,
    Const,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Not,
    Or,
    Var,
    Xor,
)
from gaitc.ir.spec import SEMANTICS, GR1Spec, Variable
from gaitc.solver import synthesis
from gaitc.solver.game import Game
from gaitc.solver.ordering import group_members, invariant_clauses, variable_order
from gaitc.solver.progress import Stage
from gaitc.solver.symbolic import Options, SymbolicSpec

# ---------------------------------------------------------------- semantics and basics
SEMANTICS_DIFFERENCE = GR1Spec(
    inputs=(Variable("person"),),
    outputs=(Variable("bit0"),),
    sys_trans=clauses(v("bit0")),
    env_liveness=clauses(v("person"), Not(v("person"))),
)


def test_initial_semantics_differ_as_in_slugs() -> None:
    # The system may start with bit0 = 1 (default) but not every start is winning (robotics).
    assert synthesis.check(SEMANTICS_DIFFERENCE, "default").realizable
    assert not synthesis.check(SEMANTICS_DIFFERENCE, "robotics").realizable


def test_environment_deadlock_makes_the_system_win() -> None:
    spec = GR1Spec(
        inputs=(Variable("a"),),
        outputs=(Variable("b"),),
        env_trans=clauses(Const(False)),
        sys_liveness=clauses(Const(False)),
    )
    assert synthesis.check(spec).realizable


def test_goal_is_a_transition_predicate() -> None:
    # The goal "b changes" needs primes; the system can toggle b every step.
    toggle = Xor(v("b"), v("b", True))
    spec = GR1Spec(outputs=(Variable("b"),), sys_liveness=clauses(toggle))
    assert synthesis.check(spec).realizable
    frozen = GR1Spec(
        outputs=(Variable("b"),),
        sys_trans=clauses(Iff(v("b"), v("b", True))),
        sys_liveness=clauses(toggle),
    )
    assert not synthesis.check(frozen).realizable


def test_unsatisfiable_liveness_is_unrealizable_unless_the_environment_fails() -> None:
    spec = GR1Spec(
        inputs=(Variable("a"),), outputs=(Variable("b"),), sys_liveness=clauses(Const(False))
    )
    assert not synthesis.check(spec).realizable
    fair = spec.with_sections(env_liveness=clauses(Const(False)))
    assert synthesis.check(fair).realizable


def _points(
    names: list[str], lows: dict[str, int], sizes: dict[str, int]
) -> Iterator[dict[str, int]]:
    for values in itertools.product(*(range(lows[n], lows[n] + sizes[n]) for n in names)):
        yield dict(zip(names, values, strict=True))


@pytest.mark.parametrize("op", ["=", "!=", "<", "<=", ">", ">="])
@pytest.mark.parametrize(
    ("left", "right"),
    [
        (IntVar("p"), IntConst(3)),
        (IntVar("p"), IntVar("q")),
        (Add(IntVar("p"), IntConst(2)), IntVar("q")),
        (Add(IntVar("p"), IntVar("q")), IntConst(7)),
        (IntVar("q"), Add(IntVar("p"), IntConst(-1))),
    ],
)
def test_integer_comparisons_match_evaluate(op: str, left: IntVar, right: IntVar) -> None:
    spec = GR1Spec(outputs=(Variable("p", -2, 4), Variable("q", 1, 6)))
    sym = SymbolicSpec(spec)
    formula = Compare(op, left, right)
    u = sym.translate(formula)
    for point in _points(["p", "q"], {"p": -2, "q": 1}, {"p": 7, "q": 6}):
        bits = {}
        for name, value in point.items():
            var = spec.variable(name)
            assert var is not None and var.low is not None
            for k, bit in enumerate(sym.var_bits[name]):
                bits[bit] = bool((value - var.low) >> k & 1)
        assert (sym.bdd.let(bits, u) == sym.bdd.true) == evaluate(formula, point), point


def test_range_constraints_exclude_values_outside_the_domain() -> None:
    # r in 0..4 has 3 bits; values 5..7 are forbidden for the system, so "r = 6"
    # can never be reached, while "r = 4" can.
    r = Variable("r", 0, 4)
    reach_six = GR1Spec(outputs=(r,), sys_liveness=clauses(Compare("=", IntVar("r"), IntConst(6))))
    reach_four = GR1Spec(outputs=(r,), sys_liveness=clauses(Compare("=", IntVar("r"), IntConst(4))))
    assert not synthesis.check(reach_six).realizable
    assert synthesis.check(reach_four).realizable


def test_unknown_variable_is_a_formula_error() -> None:
    spec = GR1Spec(outputs=(Variable("b"),), sys_trans=clauses(v("ghost")))
    with pytest.raises(FormulaError, match="unknown variable 'ghost'"):
        synthesis.check(spec)


def test_timeout_stops_with_a_solver_error() -> None:
    with pytest.raises(SolverError, match="time limit"):
        synthesis.check(SEMANTICS_DIFFERENCE, timeout=-1.0)


def test_progress_reports_the_stages_in_words() -> None:
    seen: list[Stage] = []
    synthesis.check(SEMANTICS_DIFFERENCE, progress=seen.append)
    assert seen[0].words == "building the transition relation"
    rounds = [s for s in seen if s.words.startswith("solving the game: round ")]
    assert rounds and all("BDD" not in s.words for s in seen)
    assert any("live BDD nodes" in s.detail for s in rounds)


def test_check_stops_once_the_initial_states_are_lost() -> None:
    spec = GR1Spec(
        inputs=(Variable("a"),), outputs=(Variable("b"),), sys_liveness=clauses(Const(False))
    )
    full = Game(SymbolicSpec(spec)).solve()
    early = Game(SymbolicSpec(spec)).solve(stop_if_lost="default")
    assert early.decided_early and not full.decided_early
    assert early.stats.z_iterations < full.stats.z_iterations


@settings(max_examples=30, deadline=None)
@given(spec=st.one_of(tiny_specs(), one_hot_specs()), semantics=st.sampled_from(SEMANTICS))
def test_stopping_early_never_changes_the_verdict(spec: GR1Spec, semantics: str) -> None:
    full = Game(SymbolicSpec(spec))
    early = Game(SymbolicSpec(spec))
    result = early.solve(stop_if_lost=semantics)
    expected = full.initially_winning(full.solve().winning, semantics)
    assert early.initially_winning(result.winning, semantics) == expected
    assert not (result.decided_early and expected)


# ---------------------------------------------------------------- variable order
ONE_HOT_TASK = GR1Spec(
    inputs=(Variable("h_hi"), Variable("h_lo"), Variable("hazard")),
    outputs=(Variable("at_a"), Variable("at_b"), Variable("go")),
    env_trans=clauses(
        Or((Var("h_hi", True), Var("h_lo", True))),
        Implies(And((v("go"), v("hazard"), v("at_b"))), Var("h_lo", True)),
    ),
    sys_trans=clauses(
        Not(And((Var("at_a", True), Var("at_b", True)))),
        Implies(v("at_a"), Or((Var("at_a", True), Var("go", True)))),
        Implies(Var("h_lo", True), Not(Var("go", True))),
    ),
)


def test_invariants_are_the_clauses_over_next_state_variables_only() -> None:
    env, sys = invariant_clauses(ONE_HOT_TASK)
    assert [c.formula for c in env] == [ONE_HOT_TASK.env_trans[0].formula]
    assert [c.formula for c in sys] == [
        ONE_HOT_TASK.sys_trans[0].formula,
        ONE_HOT_TASK.sys_trans[2].formula,
    ]
    # The last one mixes an input and an output: an invariant, but no mutex group.
    assert group_members(ONE_HOT_TASK) == [["h_hi", "h_lo"], ["at_a", "at_b"]]


def test_guards_come_before_the_variables_they_constrain() -> None:
    names = [v.name for v in variable_order(ONE_HOT_TASK, "guards")]
    # Scores (guarded clauses minus constraining ones): at_* +1 (guards the env clause; its
    # own move has it on both sides), hazard +1, health -1 +1 = 0, go +1 -2 = -1.  Ties go
    # by first occurrence (ρs is read first), and each mutex group stays together.
    assert names == ["at_a", "at_b", "hazard", "h_hi", "h_lo", "go"]
    declared = [v.name for v in variable_order(ONE_HOT_TASK, "declaration")]
    assert declared == ["h_hi", "h_lo", "hazard", "at_a", "at_b", "go"]
    with pytest.raises(ValueError, match="unknown variable order"):
        variable_order(ONE_HOT_TASK, "random")


def test_care_set_contains_the_initial_states_and_the_invariant() -> None:
    sym = SymbolicSpec(ONE_HOT_TASK)
    both_places = sym.bdd.add_expr("at_a & at_b")
    assert sym.invariant & both_places == sym.bdd.false
    assert sym.care & both_places != sym.bdd.false  # θ allows it, so it stays exact there
    plain = SymbolicSpec(ONE_HOT_TASK, Options(care=False))
    assert plain.care == plain.bdd.true


def test_building_the_relations_checks_the_deadline() -> None:
    def stop() -> None:
        raise SolverError("synthesis stopped after the time limit of 0 s")

    with pytest.raises(SolverError, match="time limit"):
        SymbolicSpec(ONE_HOT_TASK, deadline=stop)
    calls: list[int] = []
    SymbolicSpec(ONE_HOT_TASK, deadline=lambda: calls.append(1))
    assert len(calls) >= 2  # at least once per clause that is not an invariant
