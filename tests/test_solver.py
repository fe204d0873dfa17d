"""Tests of the embedded BDD solver (solver/symbolic.py, game.py, synthesis.py).

The property test compares it with an explicit-state GR(1) game solver written here from
the definitions (sets of states, no BDDs), on random tiny specifications.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from diagnostics import FormulaError, SolverError
from gr1.evaluation import evaluate
from gr1.formula import (
    Add,
    And,
    Compare,
    Const,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Not,
    Or,
    Var,
    Xor,
)
from gr1.spec import SEMANTICS, Clause, GR1Spec, Variable
from solver import synthesis
from solver.game import Game
from solver.ordering import group_members, invariant_clauses, variable_order
from solver.strategy import holds, smallest
from solver.symbolic import Options, SymbolicSpec
from verifier.counterstrategy import verify_counterstrategy
from verifier.strategy import verify


def clauses(*formulas: Expr) -> tuple[Clause, ...]:
    return tuple(Clause(f) for f in formulas)


def v(name: str, primed: bool = False) -> Var:
    return Var(name, primed)


# ---------------------------------------------------------------- an explicit reference solver
State = tuple[int, ...]


def _valuation(names: list[str], pre: State, post: State | None = None) -> dict[str, int]:
    out = dict(zip(names, pre, strict=True))
    if post is not None:
        out.update({n + "'": b for n, b in zip(names, post, strict=True)})
    return out


def explicit_realizable(spec: GR1Spec, semantics: str) -> bool:
    """Solve the GR(1) game by enumerating states (Boolean specs only)."""
    ins = [x.name for x in spec.inputs]
    outs = [y.name for y in spec.outputs]
    names = ins + outs
    states = [tuple(s) for s in itertools.product((0, 1), repeat=len(names))]
    xs = list(itertools.product((0, 1), repeat=len(ins)))
    ys = list(itertools.product((0, 1), repeat=len(outs)))

    def holds(section: tuple[Clause, ...], pre: State, post: State | None = None) -> bool:
        val = _valuation(names, pre, post)
        return all(evaluate(c.formula, val) for c in section)

    env_ok = {
        (s, x): holds(spec.env_trans, s, x + ys[0]) for s in states for x in xs
    }  # ρe may not read primed outputs in these tests
    sys_ok = {(s, t): holds(spec.sys_trans, s, t) for s in states for t in states}
    env_goals = [c.formula for c in spec.env_liveness] or [Const(True)]
    sys_goals = [c.formula for c in spec.sys_liveness] or [Const(True)]

    def goal(f: Expr, s: State, t: State) -> bool:
        return evaluate(f, _valuation(names, s, t))

    def cpre(target: object) -> set[State]:
        # ∀x'. ρe → ∃y'. ρs ∧ target(s, t)
        out = set()
        for s in states:
            if all(
                not env_ok[(s, x)] or any(sys_ok[(s, x + y)] and target(s, x + y) for y in ys)  # type: ignore[operator]
                for x in xs
            ):
                out.add(s)
        return out

    z: set[State] = set(states)
    while True:
        new_z = set(states)
        for sg in sys_goals:
            y_set: set[State] = set()
            while True:
                new_y = set(y_set)
                for eg in env_goals:
                    x_set = set(states)
                    while True:
                        zz, yy, xx = frozenset(z), frozenset(y_set), frozenset(x_set)
                        nxt = cpre(
                            lambda s, t, zz=zz, yy=yy, xx=xx, sg=sg, eg=eg: (
                                (goal(sg, s, t) and t in zz)
                                or t in yy
                                or (not goal(eg, s, t) and t in xx)
                            )
                        )
                        if nxt == x_set:
                            break
                        x_set = nxt
                    new_y |= x_set
                if new_y == y_set:
                    break
                y_set = new_y
            new_z &= y_set
        if new_z == z:
            break
        z = new_z
    for x in xs:
        starts = [x + y for y in ys]
        if not holds(spec.env_init, starts[0]):
            continue
        good = [s for s in starts if holds(spec.sys_init, s) and s in z]
        if semantics == "default" and not good:
            return False
        if semantics == "robotics" and any(holds(spec.sys_init, s) and s not in z for s in starts):
            return False
    return True


# ---------------------------------------------------------------- random tiny specs
def formulas(names: list[str], depth: int) -> st.SearchStrategy[Expr]:
    leaves = st.sampled_from(
        [Var(n.rstrip("'"), n.endswith("'")) for n in names] + [Const(True), Const(False)]
    )

    def grow(children: st.SearchStrategy[Expr]) -> st.SearchStrategy[Expr]:
        pair = st.tuples(children, children)
        return st.one_of(
            st.builds(Not, children),
            pair.map(lambda p: And(p)),
            pair.map(lambda p: Or(p)),
            pair.map(lambda p: Xor(*p)),
            pair.map(lambda p: Iff(*p)),
            pair.map(lambda p: Implies(*p)),
        )

    return st.recursive(leaves, grow, max_leaves=depth)


@st.composite
def tiny_specs(draw: st.DrawFn) -> GR1Spec:
    n_in = draw(st.integers(1, 2))
    n_out = draw(st.integers(1, 2))
    ins = [f"x{k}" for k in range(n_in)]
    outs = [f"y{k}" for k in range(n_out)]
    pre = ins + outs
    env_post = pre + [n + "'" for n in ins]
    all_post = env_post + [n + "'" for n in outs]

    def some(names: list[str], most: int) -> tuple[Clause, ...]:
        return clauses(*draw(st.lists(formulas(names, 5), max_size=most)))

    return GR1Spec(
        inputs=tuple(Variable(n) for n in ins),
        outputs=tuple(Variable(n) for n in outs),
        env_init=some(ins, 1),
        sys_init=some(pre, 1),
        env_trans=some(env_post, 1),
        sys_trans=some(all_post, 2),
        env_liveness=some(env_post, 2),
        sys_liveness=some(all_post, 2),
    )


def _exactly_one(names: list[str], primed: bool) -> Expr:
    some = Or(tuple(Var(n, primed) for n in names))
    pairs = [
        Not(And((Var(a, primed), Var(b, primed)))) for a, b in itertools.combinations(names, 2)
    ]
    return And((some, *pairs))


@st.composite
def one_hot_specs(draw: st.DrawFn) -> GR1Spec:
    """Random specs over a one-hot input pair and a one-hot output triple, as the .gait
    lowering writes them: mutexes in ρe/ρs over primed variables (invariants, a care set),
    in θe/θs only sometimes (then initial states lie outside the invariant)."""
    ins, outs = ["a", "b"], ["p", "q", "r"]
    pre = ins + outs
    all_post = pre + [n + "'" for n in pre]
    env_post = [*pre, "a'", "b'"]

    def some(names: list[str], most: int) -> tuple[Clause, ...]:
        return clauses(*draw(st.lists(formulas(names, 6), max_size=most)))

    mutex_init = draw(st.booleans())
    env_init = clauses(_exactly_one(ins, False)) if mutex_init else ()
    sys_init = clauses(_exactly_one(outs, False)) if mutex_init else ()
    return GR1Spec(
        inputs=tuple(Variable(n) for n in ins),
        outputs=tuple(Variable(n) for n in outs),
        env_init=env_init + some(ins, 1),
        sys_init=sys_init + some(pre, 1),
        env_trans=clauses(_exactly_one(ins, True)) + some(env_post, 1),
        sys_trans=clauses(_exactly_one(outs, True)) + some(all_post, 2),
        env_liveness=some(env_post, 2),
        sys_liveness=some(all_post, 2),
    )


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
    ],
    ids=["plain", "clustered", "reordering", "reorder-once", "no-care"],
)
@settings(max_examples=25, deadline=None)
@given(spec=st.one_of(tiny_specs(), one_hot_specs()))
def test_every_tuning_option_gives_the_same_winning_region(spec: GR1Spec, options: Options) -> None:
    # Each solver is exact on its care set: compare wherever both claim exactness.
    base = SymbolicSpec(spec)
    other = SymbolicSpec(spec, options)
    w1 = Game(base).solve().winning
    w2 = Game(other).solve().winning
    names = list(base.input_bits + base.output_bits)
    for bits in itertools.product((False, True), repeat=len(names)):
        point = dict(zip(names, bits, strict=True))
        if _holds(base, base.care, point) and _holds(other, other.care, point):
            assert _holds(base, w1, point) == _holds(other, w2, point), point


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


def test_progress_reports_iterations() -> None:
    seen: list[str] = []
    synthesis.check(SEMANTICS_DIFFERENCE, progress=seen.append)
    assert seen and all("Z round" in line for line in seen)


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


def test_building_the_relations_checks_the_deadline() -> None:
    def stop() -> None:
        raise SolverError("synthesis stopped after the time limit of 0 s")

    with pytest.raises(SolverError, match="time limit"):
        SymbolicSpec(ONE_HOT_TASK, deadline=stop)
    calls: list[int] = []
    SymbolicSpec(ONE_HOT_TASK, deadline=lambda: calls.append(1))
    assert len(calls) >= 2  # at least once per clause that is not an invariant


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
    from gr1.formula import Or, Var
    from gr1.spec import Clause, GR1Spec, Variable

    base = GR1Spec(inputs=(Variable("a"),), outputs=(Variable("y"),))
    spec = base.with_sections(env_trans=(Clause(Or((Var("a"), Var("y", True)))),))
    for run in (synthesis.check, synthesis.synthesize, synthesis.counterstrategy):
        with pytest.raises(FormulaError, match="next-state output 'y'' cannot appear"):
            run(spec)
