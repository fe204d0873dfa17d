"""Formulas nested 10,000 levels deep through every reader and writer of slugs_bridge.

Python's recursion limit is 1,000 frames, so any recursive step on the way (writer,
parser, ``next`` pushing, the renaming, equality) would raise RecursionError here.
"""

from __future__ import annotations

from collections.abc import Callable

import pytest

from gaitc.api.compiling import emit
from gaitc.ir.bitblast import bitblast
from gaitc.ir.formula import (
    Add,
    And,
    Compare,
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
from gaitc.ir.spec import Clause, GR1Spec, Variable
from slugs_bridge.infix import parse_infix
from slugs_bridge.infixtext import emit_infix
from slugs_bridge.ltltext import parse_ltl
from slugs_bridge.prefixform import prefix_form, prefix_spec
from slugs_bridge.slugsin import emit_formula, parse_prefix, parse_slugsin
from slugs_bridge.structured import parse_structuredslugs

# slow: formulas 10,000 levels deep through every reader and writer, about a minute in all
# (docs/background/testing.md)
pytestmark = pytest.mark.slow

DEPTH = 10_000
a, b, c = Var("a"), Var("b", True), Var("X")  # 'X' is renamed in the infix formats


def nested(step: Callable[[Expr, int], Expr], leaf: Expr = a) -> Expr:
    out = leaf
    for i in range(DEPTH):
        out = step(out, i)
    return out


def deep_sum() -> Expr:
    term: Add | IntVar = IntVar("n")
    for i in range(DEPTH):
        term = Add(term, IntConst(i % 3)) if i % 2 else Add(IntVar("n", True), term)
    return Compare("<=", term, IntConst(7))


SHAPES: dict[str, Expr] = {
    "not": nested(lambda e, i: Not(e)),
    "implies-right": nested(lambda e, i: Implies(b if i % 2 else c, e)),
    "implies-left": nested(lambda e, i: Implies(e, c)),
    "iff-xor": nested(lambda e, i: (Iff if i % 2 else Xor)(e, b) if i % 3 else Xor(c, e)),
    "and-or": nested(lambda e, i: (And if i % 2 else Or)((c, e, b))),
    "not-and": nested(lambda e, i: Not(And((e, c))) if i % 2 else Or((e, Not(b)))),
    "sum": deep_sum(),
}


def spec_of(formula: Expr) -> GR1Spec:
    return GR1Spec(inputs=(Variable("a"), Variable("n", 0, 3)),
                   outputs=(Variable("b"), Variable("X")), sys_trans=(Clause(formula),),
                   name="deep")


@pytest.mark.parametrize("shape", SHAPES)
def test_structuredslugs_and_ltl_round_trip(shape: str) -> None:
    spec = spec_of(SHAPES[shape])
    for fmt, parse in (("structuredslugs", parse_structuredslugs), ("ltl", parse_ltl)):
        text = emit(spec, fmt)
        assert "$" not in text  # written in infix, not in the prefix fallback
        assert parse(text, f"deep.{fmt}") == spec


@pytest.mark.parametrize("shape", [s for s in SHAPES if s != "sum"])
def test_slugsin_round_trips(shape: str) -> None:
    spec = spec_of(SHAPES[shape])
    again = parse_slugsin(emit(spec, "slugsin"), "deep.slugsin")
    assert again == prefix_spec(bitblast(spec))
    line = emit_formula(SHAPES[shape])
    assert parse_prefix(line, "x", 1, {"a", "b", "X"}) == prefix_form(SHAPES[shape])


def test_the_infix_reader_takes_deep_brackets_and_prefix_operators() -> None:
    booleans, integers = {"a", "b"}, {"n": Variable("n", 0, 3)}
    read = lambda text: parse_infix(text, "deep", 1, booleans, integers)  # noqa: E731
    assert read("(" * DEPTH + "a" + ")" * DEPTH) == a
    assert read("[" * DEPTH + "a" + "]" * DEPTH) == a
    assert read("!" * DEPTH + "a") == nested(lambda e, i: Not(e))
    assert read("next" + "(" * DEPTH + "a & b" + ")" * DEPTH) == And((Var("a", True), b))
    assert read("(" * DEPTH + "n + 1" + ")" * DEPTH + " = 2") == Compare(
        "=", Add(IntVar("n"), IntConst(1)), IntConst(2))
    chain = " -> (".join(["a"] * (DEPTH + 1)) + ")" * DEPTH
    assert read(chain) == nested(lambda e, i: Implies(a, e))
    right_sum: Add | IntVar = IntVar("n")
    for _ in range(DEPTH - 1):
        right_sum = Add(IntVar("n"), right_sum)
    assert read(" + ".join(["n"] * DEPTH) + " > 1") == Compare(">", right_sum, IntConst(1))


def test_writers_take_deep_formulas() -> None:
    text = emit_infix(SHAPES["not"])
    assert text == "!" * DEPTH + "a"
    assert emit_formula(SHAPES["not"]) == "! " * DEPTH + "a"
    assert emit_infix(SHAPES["implies-left"]).startswith("a -> X -> X")
