"""Tests for the lowering of a Model to GR(1) (thesis eqs. 3.3-3.9), both encodings."""

from __future__ import annotations

from collections.abc import Iterable

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.diagnostics import FormulaError, Span, SpecSemanticError
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
    And,
    Compare,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Next,
    Not,
    Or,
    Var,
)
from gaitc.ir.spec import SECTIONS, Clause, GR1Spec, Variable
from ltlcompiler.decoding import RobotState, encode
from ltlcompiler.lowering import lower
from ltlcompiler.model import (
    NO_GAIT,
    Gait,
    GaitKind,
    Hazard,
    Leg,
    Model,
    Region,
    Section,
    Transition,
    UserFormula,
)

ENCODINGS = ("onehot", "binary")


def _gait(name: str, *legs: str, kind: GaitKind = GaitKind.MOVE) -> Gait:
    return Gait(name, kind, tuple(legs))


def tiny_model() -> Model:
    """One leg with two health levels, two regions a <-> b joined by gait 'go'."""
    return Model(
        name="tiny", legs=(Leg("L1", 2, 2),),
        gaits=(_gait("go", "L1"), _gait(NO_GAIT, kind=GaitKind.NONE)),
        regions=(Region("a"), Region("b")),
        transitions=(Transition("a", "b", ("go",)), Transition("b", "a", ("go",))),
        caches=(), hazards=(), start="a",
        goals=(UserFormula(Section.LIVENESS, Var("b"), Span("t.gait", 9, 1)),),
        assumptions=(), guarantees=(),
    )


def corridor_model() -> Model:
    """a - b - c: east/west gaits, cache c, hazard 'hz' over b, a correction gait at a,
    and a permanently failed leg L3 used by gait 'west2'."""
    return Model(
        name="corridor",
        legs=(Leg("L1", 3, 3), Leg("L2", 2, 2), Leg("L3", 1, 1)),
        gaits=(_gait("east", "L1"), _gait("west", "L2"), _gait("west2", "L3"),
               _gait("fix", "L1", kind=GaitKind.CORRECTION), _gait(NO_GAIT, kind=GaitKind.NONE)),
        regions=(Region("a"), Region("b"), Region("c")),
        transitions=(
            Transition("a", "a", ("fix",)), Transition("a", "b", ("east",)),
            Transition("b", "a", ("west", "west2")), Transition("b", "c", ("east",)),
            Transition("c", "b", ("west", "west2")),
        ),
        caches=("c",), hazards=(Hazard("hz", ("b",)),), start="a",
        goals=(UserFormula(Section.LIVENESS, Var("c")),),
        assumptions=(), guarantees=(),
    )


def _formulas(clauses: Iterable[Clause]) -> list[Expr]:
    return [c.formula for c in clauses]


def v(name: str, primed: bool = False) -> Var:
    return Var(name, primed)


# ---------------------------------------------------------------- exact clause sets
def test_tiny_model_onehot_clauses_by_hand() -> None:
    spec = lower(tiny_model(), "onehot")
    h2, h1 = v("L1_h2"), v("L1_h1")
    h2n, h1n = v("L1_h2", True), v("L1_h1", True)
    assert spec.inputs == (Variable("L1_h2"), Variable("L1_h1"))
    assert spec.outputs == (Variable("a"), Variable("b"), Variable("go"), Variable(NO_GAIT))
    assert _formulas(spec.env_init) == [And((Or((h2, h1)), Not(And((h2, h1))))), h2]
    assert _formulas(spec.sys_init) == [
        And((Or((v("a"), v("b"))), Not(And((v("a"), v("b")))))),
        And((Or((v("go"), v(NO_GAIT))), Not(And((v("go"), v(NO_GAIT)))))),
        v("a"), v(NO_GAIT),
    ]
    assert _formulas(spec.env_trans) == [
        And((Or((h2n, h1n)), Not(And((h2n, h1n))))),
        Implies(v("go"), And((Implies(h2, Or((h2n, h1n))), Implies(h1, h1n)))),
        Implies(v(NO_GAIT), And((Iff(h2, h2n), Iff(h1, h1n)))),
    ]
    an, bn, gon, non = v("a", True), v("b", True), v("go", True), v(NO_GAIT, True)
    assert _formulas(spec.sys_trans) == [
        And((Or((an, bn)), Not(And((an, bn))))),
        And((Or((gon, non)), Not(And((gon, non))))),
        Implies(v("a"), Or((And((an, non)), And((bn, gon))))),
        Implies(v("b"), Or((And((an, gon)), And((bn, non))))),
        Implies(h1n, Not(gon)),
    ]
    assert spec.env_liveness == ()
    assert _formulas(spec.sys_liveness) == [v("b")]


def test_tiny_model_binary_clauses_by_hand() -> None:
    spec = lower(tiny_model(), "binary")

    def eq(name: str, k: int, primed: bool = False) -> Compare:
        return Compare("=", IntVar(name, primed), IntConst(k))

    assert spec.inputs == (Variable("L1", 1, 2),)
    assert spec.outputs == (Variable("region", 0, 1), Variable("gait", 0, 1))
    assert _formulas(spec.env_init) == [eq("L1", 2)]
    assert _formulas(spec.sys_init) == [eq("region", 0), eq("gait", 1)]
    keep = Compare("=", IntVar("L1", True), IntVar("L1"))
    assert _formulas(spec.env_trans) == [
        Implies(eq("gait", 0), Or((keep, And((eq("L1", 2), eq("L1", 1, True)))))),
        Implies(eq("gait", 1), keep),
    ]
    assert _formulas(spec.sys_trans) == [
        Implies(eq("region", 0), Or((And((eq("region", 0, True), eq("gait", 1, True))),
                                     And((eq("region", 1, True), eq("gait", 0, True)))))),
        Implies(eq("region", 1), Or((And((eq("region", 0, True), eq("gait", 0, True))),
                                     And((eq("region", 1, True), eq("gait", 1, True)))))),
        Implies(eq("L1", 1, True), Not(eq("gait", 0, True))),
    ]
    assert _formulas(spec.sys_liveness) == [eq("region", 1)]


def test_every_clause_names_its_rule() -> None:
    spec = lower(corridor_model(), "onehot")
    rules = [c.origin.rule for name in ("env_init", "sys_init", "env_trans", "sys_trans",
                                        "sys_liveness") for c in spec.section(name)
             if c.origin is not None]
    assert len(rules) == sum(len(spec.section(n)) for n in ("env_init", "sys_init", "env_trans",
                                                             "sys_trans", "sys_liveness"))
    assert "eq. 3.3: from b move to a by west|west2, move to c by east, or stay by noGait" in rules
    assert "eq. 3.3: from a turn in place by fix, move to b by east, or stay by noGait" in rules
    assert "eq. 3.4: leg L3 is failed for ever => gaits using L3 (west2) are off" in rules
    assert "eq. 3.6: cache c resets every leg" in rules
    assert "eq. 3.9: hazard hz active in b under east fails leg L1" in rules
    assert "eq. 3.5: fix degrades no leg: every leg keeps its health" in rules
    assert "init: start in a" in rules
    assert "mutex: exactly one region" in rules


def test_lowering_is_deterministic_and_encodings_differ() -> None:
    for enc in ENCODINGS:
        assert lower(corridor_model(), enc) == lower(corridor_model(), enc)
    assert lower(corridor_model(), "onehot") != lower(corridor_model(), "binary")


# ---------------------------------------------------------------- semantics on concrete states
def _state(region: str, gait: str, hazard: str | None = None, **health: int) -> RobotState:
    full = {"L1": 3, "L2": 2, "L3": 1}
    full.update(health)
    return RobotState(region, gait, tuple(sorted(full.items())), hazard)


def _holds(spec: GR1Spec, section: str, enc: str, now: RobotState, nxt: RobotState) -> bool:
    model = corridor_model()
    valuation = dict(encode(model, enc, now))
    valuation.update({k + "'": val for k, val in encode(model, enc, nxt).items()})
    return all(evaluate(c.formula, valuation) for c in spec.section(section))


@pytest.fixture(params=ENCODINGS)
def enc(request: pytest.FixtureRequest) -> str:
    return str(request.param)


def test_failed_leg_forbids_its_gaits(enc: str) -> None:
    spec = lower(corridor_model(), enc)
    now = _state("a", NO_GAIT)
    assert _holds(spec, "sys_trans", enc, now, _state("b", "east", L1=2))
    assert not _holds(spec, "sys_trans", enc, now, _state("b", "east", L1=1))
    assert not _holds(spec, "sys_trans", enc, _state("b", NO_GAIT), _state("a", "west2"))
    assert _holds(spec, "sys_trans", enc, _state("b", NO_GAIT), _state("a", "west"))


def test_gaits_move_only_along_their_edges(enc: str) -> None:
    spec = lower(corridor_model(), enc)
    now = _state("a", NO_GAIT)
    assert not _holds(spec, "sys_trans", enc, now, _state("c", "east"))  # not adjacent
    assert not _holds(spec, "sys_trans", enc, now, _state("b", "west"))  # wrong direction
    assert not _holds(spec, "sys_trans", enc, now, _state("b", NO_GAIT))  # noGait stays
    assert _holds(spec, "sys_trans", enc, now, _state("a", NO_GAIT))
    assert _holds(spec, "sys_trans", enc, now, _state("a", "fix"))
    assert not _holds(spec, "sys_trans", enc, _state("b", NO_GAIT), _state("b", "fix"))


def test_used_legs_lose_at_most_one_level_others_keep(enc: str) -> None:
    spec = lower(corridor_model(), enc)
    now = _state("b", "east")
    assert _holds(spec, "env_trans", enc, now, _state("b", "east", L1=3))
    assert _holds(spec, "env_trans", enc, now, _state("b", "east", L1=2))
    assert not _holds(spec, "env_trans", enc, now, _state("b", "east", L1=1))
    assert not _holds(spec, "env_trans", enc, now, _state("b", "east", L2=1))
    assert not _holds(spec, "env_trans", enc, _state("b", "east", L1=2),
                      _state("b", "east", L1=3))


def test_nogait_and_correction_keep_health(enc: str) -> None:
    spec = lower(corridor_model(), enc)
    for gait in (NO_GAIT, "fix"):
        now = _state("a", gait, L1=2)
        assert _holds(spec, "env_trans", enc, now, _state("a", gait, L1=2))
        assert not _holds(spec, "env_trans", enc, now, _state("a", gait, L1=1))


def test_cache_resets_every_leg(enc: str) -> None:
    spec = lower(corridor_model(), enc)
    now = _state("c", "east", L1=1, L2=1)
    assert _holds(spec, "env_trans", enc, now, _state("c", "east"))
    assert not _holds(spec, "env_trans", enc, now, _state("c", "east", L2=1))


def test_active_hazard_fails_the_legs_of_the_gait_in_use(enc: str) -> None:
    spec = lower(corridor_model(), enc)
    now = _state("b", "east", hazard="hz")
    assert _holds(spec, "env_trans", enc, now, _state("b", "east", L1=1))
    assert not _holds(spec, "env_trans", enc, now, _state("b", "east", L1=2))
    assert not _holds(spec, "env_trans", enc, now, _state("b", "east", L1=1, L2=1))
    # the hazard only covers b: in a it does nothing
    assert _holds(spec, "env_trans", enc, _state("a", "west", hazard="hz"),
                  _state("a", "west", L2=2))


def test_initial_state(enc: str) -> None:
    spec = lower(corridor_model(), enc)
    model = corridor_model()

    def init_ok(state: RobotState) -> bool:
        values = encode(model, enc, state)
        return all(evaluate(c.formula, values) for c in spec.env_init + spec.sys_init)

    assert init_ok(_state("a", NO_GAIT))
    assert init_ok(_state("a", NO_GAIT, hazard="hz"))
    assert not init_ok(_state("b", NO_GAIT))
    assert not init_ok(_state("a", "east"))
    assert not init_ok(_state("a", NO_GAIT, L1=2))


# ---------------------------------------------------------------- user formulas
def _with(model: Model, **kw: tuple[UserFormula, ...]) -> Model:
    from dataclasses import replace

    return replace(model, **kw)  # type: ignore[arg-type]


def test_user_formulas_are_translated_per_encoding(enc: str) -> None:
    never_b_with_weak_l1 = UserFormula(
        Section.TRANS, Implies(Next(Var("b")), Compare(">", IntVar("L1", True), IntConst(2))))
    hz_off = UserFormula(Section.LIVENESS, Not(Var("hz")))
    model = _with(corridor_model(), guarantees=(never_b_with_weak_l1,), assumptions=(hz_off,))
    spec = lower(model, enc)
    guard = spec.sys_trans[-1].formula
    assert spec.env_liveness[-1].origin is not None
    values = dict(encode(model, enc, _state("a", NO_GAIT)))
    for level, ok in ((3, True), (2, False), (1, False)):
        nxt = encode(model, enc, _state("b", "east", L1=level))
        values.update({k + "'": val for k, val in nxt.items()})
        assert evaluate(guard, values) is ok
    off = encode(model, enc, _state("a", NO_GAIT, hazard=None))
    on = encode(model, enc, _state("a", NO_GAIT, hazard="hz"))
    assert evaluate(spec.env_liveness[-1].formula, off)
    assert not evaluate(spec.env_liveness[-1].formula, on)


def test_assumption_on_next_robot_move_is_rejected() -> None:
    bad = UserFormula(Section.TRANS, Next(Var("b")), Span("t.gait", 4, 8))
    with pytest.raises(FormulaError, match="environment moves first") as err:
        lower(_with(corridor_model(), assumptions=(bad,)))
    assert err.value.span == Span("t.gait", 4, 8)


def test_unknown_name_in_formula_is_rejected() -> None:
    bad = UserFormula(Section.INIT, Var("nowhere", span=Span("t.gait", 2, 3)))
    with pytest.raises(FormulaError, match="unknown name 'nowhere'"):
        lower(_with(corridor_model(), guarantees=(bad,)), "binary")


def test_generated_name_collision_is_reported_at_the_user_name() -> None:
    from dataclasses import replace

    model = tiny_model()
    clash = replace(model, regions=(Region("a"), Region("L1_h2", span=Span("t.gait", 3, 8))),
                    transitions=(), goals=())
    with pytest.raises(SpecSemanticError, match="'L1_h2' clashes") as err:
        lower(clash, "onehot")
    assert err.value.span == Span("t.gait", 3, 8)
    lower(clash, "binary")  # no clash there


# ---------------------------------------------------------------- the encodings agree
def _states(model: Model) -> st.SearchStrategy[RobotState]:
    def level(leg: Leg) -> st.SearchStrategy[tuple[str, int]]:
        return st.tuples(st.just(leg.name), st.integers(1, leg.health))

    health = st.tuples(*(level(leg) for leg in model.legs))
    return st.builds(RobotState, st.sampled_from([r.name for r in model.regions]),
                     st.sampled_from([g.name for g in model.gaits]), health,
                     st.sampled_from([None, *(h.name for h in model.hazards)]))


def _rich_model() -> Model:
    l1, l2 = IntVar("L1"), IntVar("L2", True)
    return _with(
        corridor_model(),
        assumptions=(UserFormula(Section.TRANS, Implies(Var("hz"), Next(Not(Var("hz"))))),
                     UserFormula(Section.LIVENESS, Compare("<=", l1, IntConst(2)))),
        guarantees=(UserFormula(Section.TRANS, Implies(
            Compare(">", l2, IntConst(1)), Or((Next(Var("a")), Compare("!=", l1, l2))))),),
    )


@settings(max_examples=150, deadline=None)
@given(_states(_rich_model()), _states(_rich_model()))
def test_onehot_and_binary_mean_the_same(now: RobotState, nxt: RobotState) -> None:
    model = _rich_model()
    verdicts = []
    for enc in ENCODINGS:
        spec = LOWERED[enc]
        values = dict(encode(model, enc, now))
        values.update({k + "'": val for k, val in encode(model, enc, nxt).items()})
        verdicts.append({name: all(evaluate(c.formula, values) for c in spec.section(name))
                         for name in SECTIONS})
    assert verdicts[0] == verdicts[1]


LOWERED = {enc: lower(_rich_model(), enc) for enc in ENCODINGS}


def test_binary_reserved_names_and_nogait_edges_are_rejected() -> None:
    from dataclasses import replace

    model = tiny_model()
    leg = Leg("gait", 2, 2, span=Span("t.gait", 4, 5))
    clash = replace(model, legs=(leg,), gaits=(_gait("go", "gait"), model.gaits[1]))
    with pytest.raises(SpecSemanticError, match="'gait' clashes") as err:
        lower(clash, "binary")
    assert err.value.span == Span("t.gait", 4, 5)
    lower(clash, "onehot")
    sneaky = replace(model, transitions=(Transition("a", "b", (NO_GAIT,), Span("t.gait", 6, 1)),))
    with pytest.raises(SpecSemanticError, match="noGait cannot move the robot from a to b"):
        lower(sneaky)
