"""Property tests of the formula IR (gaitc/ir/formula.py): simplify, next, evaluate."""

from __future__ import annotations

import itertools

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.diagnostics import FormulaError, Span
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
    FALSE,
    TRUE,
    Add,
    Always,
    And,
    Compare,
    Const,
    Eventually,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Next,
    Not,
    Or,
    Var,
    Xor,
    atoms,
    conj,
    disj,
    has_primes,
    prime,
    push_next,
    simplify,
    substitute,
    walk,
)

NAMES = ("a", "b", "c")


def formulas(primes: bool = True, nexts: bool = False) -> st.SearchStrategy[Expr]:
    leaves: st.SearchStrategy[Expr] = st.one_of(
        st.builds(Const, st.booleans()),
        st.builds(Var, st.sampled_from(NAMES), st.booleans() if primes else st.just(False)),
    )

    def extend(inner: st.SearchStrategy[Expr]) -> st.SearchStrategy[Expr]:
        options = [
            st.builds(Not, inner),
            st.builds(And, st.lists(inner, min_size=0, max_size=4).map(tuple)),
            st.builds(Or, st.lists(inner, min_size=0, max_size=4).map(tuple)),
            st.builds(Xor, inner, inner),
            st.builds(Iff, inner, inner),
            st.builds(Implies, inner, inner),
        ]
        if nexts:
            options.append(st.builds(Next, inner))
        return st.one_of(*options)

    return st.recursive(leaves, extend, max_leaves=12)


def valuations() -> list[dict[str, int]]:
    keys = [*NAMES, *(n + "'" for n in NAMES)]
    return [dict(zip(keys, bits, strict=True)) for bits in itertools.product((0, 1), repeat=6)]


ALL = valuations()


@settings(max_examples=300, deadline=None)
@given(formulas())
def test_simplify_keeps_truth_values(f: Expr) -> None:
    g = simplify(f)
    for v in ALL:
        assert evaluate(g, v) == evaluate(f, v)


@settings(max_examples=200, deadline=None)
@given(formulas())
def test_simplify_removes_constants_unless_constant(f: Expr) -> None:
    g = simplify(f)
    if isinstance(g, Const):
        return
    for node in walk(g):
        if isinstance(node, (And, Or)):
            assert not any(isinstance(x, Const) for x in node.args)
            assert len(node.args) >= 2
            assert len(set(node.args)) == len(node.args)
        if isinstance(node, Not):
            assert not isinstance(node.arg, (Not, Const))


@settings(max_examples=200, deadline=None)
@given(formulas(primes=False))
def test_prime_shifts_the_valuation(f: Expr) -> None:
    g = prime(f)
    assert all(p for _, p in atoms(g))
    assert atoms(g) == {(n, True) for n, _ in atoms(f)}
    for v in ALL[::3]:
        shifted = {n + "'": v[n] for n in NAMES}
        assert evaluate(g, shifted) == evaluate(f, v)


@settings(max_examples=200, deadline=None)
@given(formulas(primes=False, nexts=True))
def test_push_next_removes_next_or_rejects_nesting(f: Expr) -> None:
    nested = any(
        isinstance(n, Next) and any(isinstance(m, Next) for m in walk(n.arg)) for n in walk(f)
    )
    if nested:
        with pytest.raises(FormulaError):
            push_next(f)
        return
    g = push_next(f)
    assert not any(isinstance(n, Next) for n in walk(g))
    assert has_primes(g) == any(isinstance(n, Next) and atoms(n.arg) for n in walk(f))


def test_push_next_examples() -> None:
    a, b = Var("a"), Var("b")
    assert push_next(And((a, Next(Or((a, Not(b))))))) == And(
        (a, Or((Var("a", True), Not(Var("b", True)))))
    )
    assert push_next(Next(Compare("=", IntVar("n"), Add(IntVar("m"), IntConst(1))))) == Compare(
        "=", IntVar("n", True), Add(IntVar("m", True), IntConst(1))
    )
    with pytest.raises(FormulaError, match="already a next-state value"):
        push_next(Next(Var("a", True)))
    with pytest.raises(FormulaError, match="'next' inside 'next'"):
        push_next(Next(Not(Next(a))))
    with pytest.raises(FormulaError, match="'always' cannot appear"):
        push_next(And((a, Always(b))))
    with pytest.raises(FormulaError, match="'eventually' cannot appear"):
        push_next(Eventually(b))


@settings(max_examples=200, deadline=None)
@given(formulas(), formulas(primes=False))
def test_substitute_agrees_with_evaluation(f: Expr, g: Expr) -> None:
    h = substitute(f, {("a", False): g})
    assert ("a", False) not in atoms(h) or ("a", False) in atoms(g)
    for v in ALL[::5]:
        replaced = dict(v, a=int(evaluate(g, v)))
        assert evaluate(h, v) == evaluate(f, replaced)


def test_conj_and_disj() -> None:
    a = Var("a")
    assert conj([]) == TRUE and disj([]) == FALSE
    assert conj([a]) is a and disj([a]) is a
    assert conj([a, Not(a)]) == And((a, Not(a)))
    assert disj([a, FALSE]) == Or((a, FALSE))


def test_equality_ignores_spans_and_hash_is_structural() -> None:
    here = Span("f", 1, 2)
    there = Span("g", 3, 4)
    x = And((Var("a", span=here), Not(Var("b"))), span=here)
    y = And((Var("a", span=there), Not(Var("b", span=there))))
    assert x == y and hash(x) == hash(y)
    assert x != And((Var("a", True), Not(Var("b"))))
    assert Var("a") != IntVar("a")


@pytest.mark.parametrize(
    ("op", "expected"),
    [("=", False), ("!=", True), ("<", True), ("<=", True), (">", False), (">=", False)],
)
def test_evaluate_comparisons(op: str, expected: bool) -> None:
    f = Compare(op, Add(IntVar("n"), IntConst(2)), IntVar("m", True))
    assert evaluate(f, {"n": 3, "m'": 6}) == expected


def test_evaluate_rejects_temporal_operators() -> None:
    with pytest.raises(FormulaError):
        evaluate(Always(Var("a")), {"a": 1})
