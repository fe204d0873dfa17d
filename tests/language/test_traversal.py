"""The iterative traversal (gaitc/ir/traversal.py) and the folds built on it agree with brute force.

Each function that used to recurse over formulas (evaluation, simplification, priming,
the solver's and the verifier's BDD translations, the run monitor, bit-blasting) is checked
against a plain recursive reference or a truth table, on random formulas and on the same
formulas wrapped thousands of levels deep.
"""

from __future__ import annotations

import itertools
import sys
from collections.abc import Callable

from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.ir.bitblast import bitblast
from gaitc.ir.bits import encode_bits
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
    COMPARE_OPS,
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
    atoms,
    prime,
    simplify,
)
from gaitc.ir.spec import Clause, GR1Spec, Origin, Variable
from gaitc.ir.traversal import Node, Text, fold, height, join_text, rebuild, separated
from gaitc.sim.monitor import compile_formula
from gaitc.solver.ordering import AtomCache
from gaitc.solver.symbolic import SymbolicSpec
from gaitc.verifier.logic import Logic

NAMES = ("a", "b", "c")
KEYS = [*NAMES, *(n + "'" for n in NAMES)]
ALL = [dict(zip(KEYS, bits, strict=True)) for bits in itertools.product((0, 1), repeat=6)]
WRAP = 3000  # levels added around a random formula: beyond the recursion limit
SOME = ALL[::21]  # the valuations deep formulas are evaluated on
SPEC = GR1Spec(inputs=(Variable("a"), Variable("b")), outputs=(Variable("c"),))


def formulas() -> st.SearchStrategy[Expr]:
    leaves: st.SearchStrategy[Expr] = st.one_of(
        st.builds(Const, st.booleans()), st.builds(Var, st.sampled_from(NAMES), st.booleans())
    )

    def extend(inner: st.SearchStrategy[Expr]) -> st.SearchStrategy[Expr]:
        return st.one_of(
            st.builds(Not, inner),
            st.builds(And, st.lists(inner, max_size=4).map(tuple)),
            st.builds(Or, st.lists(inner, max_size=4).map(tuple)),
            st.builds(Xor, inner, inner),
            st.builds(Iff, inner, inner),
            st.builds(Implies, inner, inner),
        )

    return st.recursive(leaves, extend, max_leaves=12)


def reference(expr: Expr, v: dict[str, int]) -> bool:
    """The textbook recursive semantics (only for shallow formulas)."""
    if isinstance(expr, Const):
        return expr.value
    if isinstance(expr, Var):
        return bool(v[expr.name + "'" * expr.primed])
    if isinstance(expr, Not):
        return not reference(expr.arg, v)
    if isinstance(expr, And):
        return all(reference(a, v) for a in expr.args)
    if isinstance(expr, Or):
        return any(reference(a, v) for a in expr.args)
    assert isinstance(expr, (Xor, Iff, Implies))
    left, right = reference(expr.left, v), reference(expr.right, v)
    if isinstance(expr, Xor):
        return left != right
    return left == right if isinstance(expr, Iff) else (not left) or right


def deepened(expr: Expr, levels: int = WRAP) -> Expr:
    """``expr`` under ``levels`` double negations and implications from true: same meaning."""
    for k in range(levels):
        expr = Not(Not(expr)) if k % 2 else Implies(Const(True), expr)
    return expr


def truth_table(fn: Callable[[dict[str, int]], bool]) -> list[bool]:
    return [fn(v) for v in ALL]


@settings(max_examples=200, deadline=None)
@given(formulas())
def test_evaluation_agrees_with_the_recursive_semantics(f: Expr) -> None:
    assert truth_table(lambda v: evaluate(f, v)) == truth_table(lambda v: reference(f, v))


@settings(max_examples=40, deadline=None)
@given(formulas())
def test_evaluation_of_deep_formulas(f: Expr) -> None:
    deep = deepened(f)
    assert [evaluate(deep, v) for v in SOME] == [reference(f, v) for v in SOME]


@settings(max_examples=40, deadline=None)
@given(formulas())
def test_simplify_is_idempotent_and_keeps_truth_values_of_deep_formulas(f: Expr) -> None:
    g = simplify(deepened(f))
    assert simplify(g) == g
    assert g == simplify(f)
    assert height(g) <= height(f)
    assert truth_table(lambda v: evaluate(g, v)) == truth_table(lambda v: reference(f, v))
    assert height(deepened(f)) > sys.getrecursionlimit()


@settings(max_examples=40, deadline=None)
@given(formulas())
def test_bdd_translations_agree_with_the_truth_table(f: Expr) -> None:
    expected = truth_table(lambda v: reference(f, v))
    deep = deepened(f)
    sym = SymbolicSpec(SPEC)
    solver_bdd = sym.translate(deep)
    logic = Logic(SPEC)
    verifier_bdd = logic.translate(deep)
    for v, value in zip(ALL, expected, strict=True):
        point = {k: bool(b) for k, b in v.items()}
        assert (sym.bdd.let(point, solver_bdd) == sym.bdd.true) == value
        assert logic.holds(verifier_bdd, point) == value


@settings(max_examples=40, deadline=None)
@given(formulas())
def test_the_monitor_agrees_with_evaluation(f: Expr) -> None:
    check = compile_formula(f, NAMES)
    assert [check([v[k] for k in KEYS]) for v in ALL] == truth_table(lambda v: reference(f, v))
    check = compile_formula(deepened(f), NAMES)  # too deep for Python's compiler
    assert [check([v[k] for k in KEYS]) for v in SOME] == [reference(f, v) for v in SOME]


@settings(max_examples=40, deadline=None)
@given(formulas(), st.sampled_from(COMPARE_OPS), st.integers(0, 6), st.booleans())
def test_bitblasting_comparisons_under_deep_formulas(
    f: Expr, op: str, k: int, plus: bool
) -> None:
    x = IntVar("x")
    left = Add(x, IntConst(1)) if plus else x
    formula = deepened(And((f, Compare(op, left, IntConst(k)))), 50)
    spec = GR1Spec(inputs=(Variable("a"), Variable("b"), Variable("c"), Variable("x", 2, 6)),
                   sys_init=(Clause(formula, Origin("deep")),))
    lowered = bitblast(spec).sys_init[0].formula
    for v in SOME:
        for value in range(2, 7):
            bits = encode_bits(spec.inputs[3], value)
            assert evaluate(lowered, {**v, **bits}) == evaluate(formula, {**v, "x": value})


@settings(max_examples=40, deadline=None)
@given(formulas())
def test_prime_of_a_deep_formula_shifts_the_valuation(f: Expr) -> None:
    current = rebuild(f, lambda n: Var(n.name) if isinstance(n, Var) else None)
    shifted = prime(deepened(current))
    for v in SOME:
        later = {n + "'": v[n] for n in NAMES}
        assert evaluate(shifted, later) == reference(current, v)


# ---------------------------------------------------------------- the traversal itself
def test_fold_calls_children_in_pre_order_and_combine_in_post_order() -> None:
    a, b = Var("a"), Var("b")
    shared = And((a, b))
    negated, xor = Not(shared), Xor(a, Const(True))
    root = Or((negated, shared, xor))
    entered: list[Node] = []
    left: list[Node] = []

    def children(node: Node) -> tuple[Node, ...]:
        entered.append(node)
        return node.children()

    def combine(node: Node, kids: list[int]) -> int:
        left.append(node)
        return 1 + sum(kids)

    assert fold(root, combine, children) == 1 + 4 + 3 + 3  # shared nodes: one value
    assert [id(n) for n in entered] == [id(n) for n in (root, negated, shared, a, b, xor,
                                                          xor.right)]
    assert [id(n) for n in left] == [id(n) for n in (a, b, shared, negated, xor.right, xor,
                                                       root)]


def test_fold_shares_its_memo_and_skips_pruned_subtrees() -> None:
    deep = deepened(Var("a"), 5000)
    memo: dict[int, tuple[Node, int]] = {}
    depth = fold(deep, lambda _, kids: 1 + max(kids, default=0), memo=memo)
    assert depth == height(deep) == 7501
    assert fold(deep, lambda _, kids: -1, memo=memo) == depth  # answered from the memo
    assert fold(deep, lambda node, kids: len(kids), lambda node: ()) == 0


def test_rebuild_keeps_spans_and_leaves_and_stops_at_replacements() -> None:
    a = Var("a")
    f = And((a, Not(Var("b"))))
    g = rebuild(f, lambda n: Const(False) if isinstance(n, Not) else None)
    assert g == And((a, Const(False))) and g.args[0] is a
    assert rebuild(a, lambda n: None) is a
    assert Not(a).with_children([Var("z")]) == Not(Var("z"))


def test_text_ropes_join_in_order() -> None:
    rope = ("(", separated(" & ", ["a", ("!", "b"), "c"]), ")")
    assert join_text(rope) == "(a & !b & c)"
    assert join_text(separated(", ", [])) == ""
    deep: Text = "x"
    for _ in range(WRAP):
        deep = ("!", deep)
    assert join_text(deep) == "!" * WRAP + "x"


def _reference_atoms(expr: Node) -> set[tuple[str, bool]]:
    """The variables of a shallow formula, by plain recursion."""
    if isinstance(expr, (Var, IntVar)):
        return {(expr.name, expr.primed)}
    return set().union(*(_reference_atoms(c) for c in expr.children()))


@settings(max_examples=60, deadline=None)
@given(formulas())
def test_atoms_and_the_shared_atom_cache_agree_with_recursion_on_deep_formulas(f: Expr) -> None:
    expected = _reference_atoms(f)
    assert atoms(f) == expected
    deep = deepened(f)  # implications from true, thousands deep: the cache must not recurse
    cache = AtomCache()
    assert cache(deep) == atoms(deep) == expected
    assert cache(deep) is cache(deep)  # asked again: the same set, not walked anew
    if isinstance(f, Implies):
        assert cache(f) == atoms(f.left) | atoms(f.right)
