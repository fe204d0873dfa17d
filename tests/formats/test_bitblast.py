"""Tests of bit-blasting integers the way SLUGS's converter does (gaitc/ir/bitblast.py)."""

from __future__ import annotations

import itertools
import random
from pathlib import Path

import pytest
from dd import cudd
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.ir.bitblast import bitblast, range_constraint
from gaitc.ir.bits import (
    bit_count,
    decode_bits,
    decode_valuation,
    encode_bits,
    integer_bits,
    split_bit_name,
)
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
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
    Term,
    Var,
    Xor,
    walk,
)
from gaitc.ir.spec import Clause, GR1Spec, Variable
from slugs_bridge.slugsin import emit_formula, emit_slugsin, parse_prefix, parse_slugsin
from slugs_bridge.structured import parse_structuredslugs

DATA = Path(__file__).parents[1] / "data" / "slugs_examples"
STRUCTURED = sorted([*DATA.glob("*.structuredslugs"), *DATA.glob("*.structureslugs")])


def bit_valuation(variables: list[Variable], values: dict[str, int]) -> dict[str, bool]:
    out: dict[str, bool] = {}
    for var in variables:
        for primed in (False, True):
            key = var.name + ("'" if primed else "")
            out.update(encode_bits(var, values[key], primed))
    return out


def test_bit_names_follow_slugs() -> None:
    assert integer_bits(Variable("b", 0, 10)) == ["b@0.0.10", "b@1", "b@2", "b@3"]
    assert integer_bits(Variable("c", 2, 8)) == ["c@0.2.8", "c@1", "c@2"]
    assert integer_bits(Variable("d", 0, 1)) == ["d@0.0.1"]
    assert integer_bits(Variable("e", 0, 8)) == ["e@0.0.8", "e@1", "e@2", "e@3"]
    assert integer_bits(Variable("f", 5, 5)) == ["f@0.5.5"]  # SLUGS: none; gaitc: one, fixed
    assert integer_bits(Variable("g")) == ["g"]
    assert bit_count(Variable("h", 3, 107)) == 7


def test_split_bit_name() -> None:
    assert split_bit_name("b@0.0.10") == ("b", 0)
    assert split_bit_name("b@3") == ("b", 3)
    assert split_bit_name("plain") is None
    assert split_bit_name("x@y") is None


def test_encode_decode_round_trip() -> None:
    var = Variable("level", 3, 107)
    for value in (3, 4, 50, 107):
        bits = encode_bits(var, value)
        assert decode_bits(var, bits) == value
        primed = encode_bits(var, value, primed=True)
        assert decode_bits(var, primed, primed=True) == value
    assert encode_bits(var, 4) == {f"level@{i}" if i else "level@0.3.107": i == 0
                                   for i in range(7)}
    with pytest.raises(ValueError, match="outside"):
        encode_bits(var, 108)
    both = {**encode_bits(var, 9), "flag": 1}
    assert decode_valuation([var, Variable("flag")], both) == {"level": 9, "flag": True}


def test_range_constraints_are_slugs_lines() -> None:
    b = range_constraint(Variable("b", 0, 10), primed=False)
    c = range_constraint(Variable("c", 2, 8), primed=True)
    assert b is not None and c is not None
    assert emit_formula(b) == "| ! b@3 & ! b@2 | ! b@1 | ! b@0.0.10 0"
    assert emit_formula(c) == "| ! c@2' | ! c@1' | ! c@0.2.8' 0"
    assert range_constraint(Variable("p", 0, 7), primed=False) is None
    q = range_constraint(Variable("q", 4, 4), primed=False)
    assert q is not None and emit_formula(q) == "| ! q@0.4.4 0"


@pytest.mark.parametrize(("low", "high"), [(0, 10), (2, 8), (3, 5), (-3, 2), (0, 2)])
def test_range_constraint_admits_exactly_the_range(low: int, high: int) -> None:
    var = Variable("v", low, high)
    limit = range_constraint(var, primed=False)
    assert limit is not None
    bits = integer_bits(var)
    for pattern in itertools.product((0, 1), repeat=len(bits)):
        valuation = dict(zip(bits, pattern, strict=True))
        assert evaluate(limit, valuation) == (low <= decode_bits(var, valuation) <= high)


def test_spec_layout_matches_the_converter() -> None:
    spec = GR1Spec(
        inputs=(Variable("a"), Variable("n", 0, 5), Variable("z")),
        outputs=(Variable("m", 1, 4), Variable("k", 0, 2)),
        sys_trans=(Clause(Compare("=", IntVar("m", True), IntVar("n"))),),
    )
    out = bitblast(spec)
    assert [v.name for v in out.inputs] == ["a", "n@0.0.5", "n@1", "n@2", "z"]
    assert [v.name for v in out.outputs] == ["m@0.1.4", "m@1", "k@0.0.2", "k@1"]
    assert not out.has_integers
    # n (6 values in 3 bits) is limited by env clauses; m (4 values) needs none; k does.
    assert [emit_formula(c.formula) for c in out.env_init] == ["| ! n@2 | ! n@1 & ! n@0.0.5 0"]
    assert [emit_formula(c.formula) for c in out.env_trans] == [
        "| ! n@2' | ! n@1' & ! n@0.0.5' 0"
    ]
    assert [emit_formula(c.formula) for c in out.sys_init] == ["| ! k@1 | ! k@0.0.2 0"]
    assert len(out.sys_trans) == 2  # the user's clause first, then k's limit
    origin = out.sys_trans[1].origin
    assert origin is not None and origin.rule == "range of integer output k: 0 <= k' <= 2"
    text = emit_slugsin(out)
    assert parse_slugsin(text, "x") == parse_slugsin(emit_slugsin(out), "y")


def test_boolean_spec_is_returned_unchanged() -> None:
    spec = GR1Spec(inputs=(Variable("a"),), sys_liveness=(Clause(Or((Var("a"), Var("a")))),))
    assert bitblast(spec) is spec


def test_sharing_keeps_adders_small() -> None:
    # x + y + z = w over 8-bit integers: a tree would repeat carries exponentially.
    names = ["x", "y", "z", "w"]
    variables = tuple(Variable(n, 0, 255) for n in names)
    total: Term = Add(IntVar("x"), Add(IntVar("y"), IntVar("z")))
    spec = GR1Spec(outputs=variables, sys_init=(Clause(Compare("=", total, IntVar("w"))),))
    formula = bitblast(spec).sys_init[0].formula
    assert sum(1 for _ in walk(formula)) < 400
    assert len(emit_formula(formula)) < 6000


# ---------------------------------------------------------------- semantics (hypothesis)
RANGES = st.tuples(st.integers(-4, 6), st.integers(0, 9)).map(lambda t: (t[0], t[0] + t[1]))


@st.composite
def comparisons(draw: st.DrawFn) -> tuple[list[Variable], Compare]:
    count = draw(st.integers(1, 3))
    variables = [Variable(f"v{i}", *draw(RANGES)) for i in range(count)]

    def term(depth: int) -> Term:
        choice = draw(st.integers(0, 2 if depth < 3 else 1))
        if choice == 0:
            return IntConst(draw(st.integers(0, 12)))
        if choice == 1:
            var = draw(st.sampled_from(variables))
            return IntVar(var.name, draw(st.booleans()))
        return Add(term(depth + 1), term(depth + 1))

    op = draw(st.sampled_from(["=", "!=", "<", "<=", ">", ">="]))
    return variables, Compare(op, term(0), term(0))


@settings(max_examples=150, deadline=None)
@given(comparisons(), st.randoms(use_true_random=False))
def test_bitblasted_comparison_agrees_with_integers(
    case: tuple[list[Variable], Compare], rnd: random.Random
) -> None:
    variables, compare = case
    spec = GR1Spec(outputs=tuple(variables), sys_trans=(Clause(compare),))
    blasted = bitblast(spec).sys_trans[0].formula
    for _ in range(25):
        values = {}
        for var in variables:
            assert var.low is not None and var.high is not None
            values[var.name] = rnd.randint(var.low, var.high)
            values[var.name + "'"] = rnd.randint(var.low, var.high)
        assert evaluate(blasted, bit_valuation(variables, values)) == evaluate(compare, values)


def check_examples_equivalent(original: GR1Spec, blasted: GR1Spec, seed: int) -> None:
    rnd = random.Random(seed)
    variables = list(original.variables())
    for section in ("env_init", "sys_init", "env_trans", "sys_trans", "env_liveness",
                    "sys_liveness"):
        user = blasted.section(section)[: len(original.section(section))]
        for before, after in zip(original.section(section), user, strict=True):
            for _ in range(40):
                values: dict[str, int] = {}
                for var in variables:
                    low, high = (var.low, var.high) if var.is_integer else (0, 1)
                    assert low is not None and high is not None
                    values[var.name] = rnd.randint(low, high)
                    values[var.name + "'"] = rnd.randint(low, high)
                bits: dict[str, int | bool] = dict(values)
                for var in variables:
                    if var.is_integer:
                        bits.update(bit_valuation([var], values))
                assert evaluate(before.formula, values) == evaluate(after.formula, bits)


@pytest.mark.parametrize("path", STRUCTURED, ids=lambda p: p.name)
def test_examples_bitblast_to_equivalent_slugsin(path: Path) -> None:
    original = parse_structuredslugs(path.read_text(encoding="utf-8"), str(path))
    blasted = bitblast(original)
    again = parse_slugsin(emit_slugsin(blasted), "blasted.slugsin")
    assert [v.name for v in again.variables()] == [v.name for v in blasted.variables()]
    check_examples_equivalent(original, again, seed=len(path.name))


def test_deep_formulas_do_not_overflow() -> None:
    deep: Expr = Compare("<", IntVar("n"), IntConst(3))
    for _ in range(5000):
        deep = Not(deep)
    spec = GR1Spec(outputs=(Variable("n", 0, 7),), sys_init=(Clause(deep),))
    out = bitblast(spec).sys_init[0].formula
    for n in range(8):
        assert evaluate_iteratively(out, encode_bits(Variable("n", 0, 7), n)) == (n < 3)


def evaluate_iteratively(expr: Expr, valuation: dict[str, bool]) -> bool:
    negations = 0
    while isinstance(expr, Not):
        negations += 1
        expr = expr.arg
    return evaluate(expr, valuation) != (negations % 2 == 1)


def test_one_value_range_becomes_a_constant() -> None:
    spec = GR1Spec(
        outputs=(Variable("k", 4, 4), Variable("n", 0, 7)),
        sys_init=(Clause(Compare("=", IntVar("n"), Add(IntVar("k"), IntConst(1)))),),
    )
    out = bitblast(spec)
    assert [v.name for v in out.outputs] == ["k@0.4.4", "n@0.0.7", "n@1", "n@2"]
    assert [emit_formula(c.formula) for c in out.sys_init[1:]] == ["| ! k@0.4.4 0"]
    formula: Expr = out.sys_init[0].formula
    for n in range(8):
        bits = {**encode_bits(Variable("n", 0, 7), n), **encode_bits(Variable("k", 4, 4), 4)}
        assert evaluate(formula, bits) == (n == 5)


# ---------------------------------------------------------------- against SLUGS's own output
# The structured example of SLUGS's doc/input_formats.md and the slugsin text its
# converter printed for it (formulas only; that converter also repeated the unprimed
# range limits in the trans sections, which hold anyway on in-range states).
DOC_STRUCTURED = """[INPUT]
a
b:0...10
[OUTPUT]
c:2...8
d
[ENV_INIT]
! a
b = 1
[SYS_INIT]
d
c = 4
[ENV_TRANS]
a -> (a' <-> ! a)
b' = b + 1
[SYS_TRANS]
d -> (c' = 3)
[ENV_LIVENESS]
! a | (b = 3)
[SYS_LIVENESS]
d
c = 2
"""
DOC_CONVERTED = {
    "env_init": [
        "! a",
        "$ 1 & ! b@3 & ! b@2 & ! b@1 & ! ^ b@0.0.10 1 1",
        "| ! b@3 & ! b@2 | ! b@1 | ! b@0.0.10 0",
    ],
    "sys_init": [
        "d",
        "$ 7 ^ 0 c@0.2.8 & 0 c@0.2.8 ^ ^ 1 c@1 ? 1 | | & 1 c@1 & ? 1 1 & ? 1 c@1 ^ c@2 ? 3 "
        "& c@2 ? 3 & ! ? 5 & ! ^ ? 4 1 & ! ^ ? 2 0 & ! ^ ? 0 0 1",
        "| ! c@2 | ! c@1 | ! c@0.2.8 0",
    ],
    "env_trans": [
        "| ! a | & ! a' ! ! a & a' ! a",
        "$ 9 ^ 1 b@0.0.10 & 1 b@0.0.10 ^ b@1 ? 1 & b@1 ? 1 ^ b@2 ? 3 & b@2 ? 3 ^ b@3 ? 5 "
        "& b@3 ? 5 & ! ? 7 & ! ^ b@3' ? 6 & ! ^ b@2' ? 4 & ! ^ b@1' ? 2 & ! ^ b@0.0.10' ? 0 1",
        "| ! b@3 & ! b@2 | ! b@1 | ! b@0.0.10 0",
        "| ! b@3' & ! b@2' | ! b@1' | ! b@0.0.10' 0",
    ],
    "sys_trans": [
        "| ! d $ 7 ^ 0 c@0.2.8' & 0 c@0.2.8' ^ ^ 1 c@1' ? 1 | | & 1 c@1' & ? 1 1 & ? 1 c@1' "
        "^ c@2' ? 3 & c@2' ? 3 & ! ? 5 & ! ? 4 & ! ^ ? 2 1 & ! ^ ? 0 1 1",
        "| ! c@2 | ! c@1 | ! c@0.2.8 0",
        "| ! c@2' | ! c@1' | ! c@0.2.8' 0",
    ],
    "env_liveness": ["| ! a $ 1 & ! b@3 & ! b@2 & ! ^ b@1 1 & ! ^ b@0.0.10 1 1"],
    "sys_liveness": [
        "d",
        "$ 7 ^ 0 c@0.2.8 & 0 c@0.2.8 ^ ^ 1 c@1 ? 1 | | & 1 c@1 & ? 1 1 & ? 1 c@1 ^ c@2 ? 3 "
        "& c@2 ? 3 & ! ? 5 & ! ? 4 & ! ^ ? 2 1 & ! ^ ? 0 0 1",
    ],
}


def to_bdd(
    expr: Expr, manager: cudd.BDD, memo: dict[int, tuple[Expr, cudd.Function]]
) -> cudd.Function:
    # The memo keeps each node alive, so its id cannot be reused by a later formula.
    if id(expr) in memo:
        return memo[id(expr)][1]
    if isinstance(expr, Const):
        out = manager.true if expr.value else manager.false
    elif isinstance(expr, Var):
        out = manager.var(expr.name + ("'" if expr.primed else ""))
    elif isinstance(expr, Not):
        out = ~to_bdd(expr.arg, manager, memo)
    elif isinstance(expr, (And, Or)):
        parts = [to_bdd(a, manager, memo) for a in expr.args]
        out = manager.true if isinstance(expr, And) else manager.false
        for p in parts:
            out = (out & p) if isinstance(expr, And) else (out | p)
    elif isinstance(expr, (Xor, Iff, Implies)):
        left, right = to_bdd(expr.left, manager, memo), to_bdd(expr.right, manager, memo)
        if isinstance(expr, Implies):
            out = ~left | right
        else:
            out = manager.apply("xor" if isinstance(expr, Xor) else "<=>", left, right)
    else:
        raise AssertionError(f"unexpected node {expr!r}")
    memo[id(expr)] = (expr, out)
    return out


def test_bitblast_agrees_with_slugs_converter_output() -> None:
    spec = parse_structuredslugs(DOC_STRUCTURED, "doc.structuredslugs")
    ours = bitblast(spec)
    assert [v.name for v in ours.inputs] == ["a", "b@0.0.10", "b@1", "b@2", "b@3"]
    assert [v.name for v in ours.outputs] == ["c@0.2.8", "c@1", "c@2", "d"]
    declared = {v.name for v in ours.variables()}
    manager = cudd.BDD()
    manager.declare(*sorted(declared | {n + "'" for n in declared}))
    memo: dict[int, tuple[Expr, cudd.Function]] = {}
    in_range = manager.true
    for var in spec.variables():
        if var.is_integer:
            limit = range_constraint(var, primed=False)
            assert limit is not None
            in_range &= to_bdd(limit, manager, memo)
    for section, lines in DOC_CONVERTED.items():
        theirs = manager.true
        for number, line in enumerate(lines, start=1):
            theirs &= to_bdd(parse_prefix(line, "doc", number, declared), manager, memo)
        mine = manager.true
        for clause in ours.section(section):
            mine &= to_bdd(clause.formula, manager, memo)
        assert (mine & in_range) == (theirs & in_range), section
        if section.endswith("init") or section.endswith("liveness"):
            assert mine == theirs, section
