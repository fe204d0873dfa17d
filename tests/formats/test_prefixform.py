"""What slugsin keeps of a formula (slugs_bridge/prefixform.py), against the writer and reader."""

from __future__ import annotations

import itertools

from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import And, Const, Expr, Iff, Implies, Not, Or, Var, Xor
from slugs_bridge.prefixform import prefix_form
from slugs_bridge.shapes import prefix_exact
from slugs_bridge.slugsin import emit_formula, parse_prefix

LEAVES = [Var("a"), Var("b", True), Var("c"), Const(True), Const(False)]


@st.composite
def dags(draw: st.DrawFn) -> Expr:
    """A formula whose nodes may be shared: each new node picks operands among earlier ones."""
    pool: list[Expr] = list(LEAVES)
    for _ in range(draw(st.integers(1, 14))):
        pick = st.sampled_from(pool)
        kind = draw(st.sampled_from(["not", "and", "or", "xor", "iff", "implies"]))
        if kind == "not":
            pool.append(Not(draw(pick)))
        elif kind in ("and", "or"):
            args = tuple(draw(st.lists(pick, max_size=4)))
            pool.append((And if kind == "and" else Or)(args))
        else:
            pool.append({"xor": Xor, "iff": Iff, "implies": Implies}[kind](draw(pick), draw(pick)))
    return pool[-1]


def equivalent(f: Expr, g: Expr) -> bool:
    names = ["a", "b'", "c"]
    return all(
        evaluate(f, dict(zip(names, values, strict=True)))
        == evaluate(g, dict(zip(names, values, strict=True)))
        for values in itertools.product((False, True), repeat=3)
    )


@settings(max_examples=400, deadline=None)
@given(dags())
def test_prefix_form_is_what_the_reader_gives_back(f: Expr) -> None:
    form = prefix_form(f)
    again = parse_prefix(emit_formula(f), "x", 1, {"a", "b", "c"})
    assert again == form
    assert equivalent(form, f)
    assert emit_formula(form) == emit_formula(again)
    if prefix_exact(f):
        assert form == f


def test_examples() -> None:
    a, b, c = Var("a"), Var("b"), Var("c")
    assert prefix_form(Iff(a, b)) == Not(Xor(a, b))
    assert prefix_form(Implies(a, Or((b, c)))) == Or((Not(a), b, c))
    assert prefix_form(Or((c, Implies(a, b)))) == Or((c, Not(a), b))
    assert prefix_form(And(())) == Const(True)
    shared = Implies(a, b)
    assert prefix_form(Or((shared, shared))) == Or((Or((Not(a), b)),) * 2)  # '? 0' stays apart
