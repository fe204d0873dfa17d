"""Formulas nested far deeper than Python's recursion limit (issue 8).

A guarantee 10,000 levels deep used to end in a RecursionError (exit 70, internal error);
now every stage is a fold (:mod:`gaitc.ir.traversal`) and such specs parse, compile, solve,
synthesize, verify and simulate.  Formulas deeper than the parser's documented limit are
refused with a positioned error.  The tree-shaped writers of :mod:`slugs_bridge`
(structuredslugs, and the LTL text of integer formulas) still recurse: those cases are
expected failures until that branch lands.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.cli.commands.compiling import compile_text
from gaitc.core.spec import load
from gaitc.diagnostics import FormulaError
from gaitc.ir.bitblast import bitblast
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
    And,
    Compare,
    Expr,
    Implies,
    IntConst,
    IntVar,
    Next,
    Not,
    Var,
    atoms,
    prime,
    push_next,
    simplify,
    substitute,
)
from gaitc.ir.spec import Clause, GR1Spec, Origin, Variable
from gaitc.ir.traversal import height
from gaitc.sim.monitor import compile_formula
from gaitc.solver.synthesis import check, synthesize
from gaitc.verifier.strategy import verify
from ltlcompiler import parse_tree
from ltlcompiler.frontend import parse_text

ROOT = Path(__file__).resolve().parents[2]
PATROL = (ROOT / "specs" / "patrol_2x2.gait").read_text(encoding="utf-8")
DEPTH = 10_000
FORMULAS = {  # each means "the robot is in nw"
    "not": "!" * DEPTH + "nw",
    "and": " & ".join(["nw"] * DEPTH),
    "implies": "true -> " * (DEPTH - 1) + "nw",
    "parentheses": "(" * DEPTH + "nw" + ")" * DEPTH,
    "next": "next " + "!" * DEPTH + "nw",
}
FORMATS = ("structuredslugs", "slugsin", "ltl")
ENCODINGS = ("onehot", "binary")


def test_the_depth_is_far_beyond_the_recursion_limit() -> None:
    assert 5 * sys.getrecursionlimit() < DEPTH


def _spec_file(tmp_path: Path, guarantee: str, name: str = "deep.gait") -> Path:
    path = tmp_path / name
    path.write_text(f"{PATROL}guarantee always {guarantee}\n", encoding="utf-8")
    return path


def _cases() -> list[object]:
    cases: list[object] = []
    for kind in FORMULAS:
        for encoding in ENCODINGS:
            for fmt in FORMATS:
                cases.append(pytest.param(kind, encoding, fmt, id=f"{kind}-{encoding}-{fmt}"))
    return cases


@pytest.mark.parametrize(("kind", "encoding", "fmt"), _cases())
def test_deep_guarantees_compile_end_to_end(
    tmp_path: Path, kind: str, encoding: str, fmt: str
) -> None:
    text, warnings = compile_text(str(_spec_file(tmp_path, FORMULAS[kind])), fmt, encoding)
    assert not warnings
    assert "guarantee (line 24)" in text


@pytest.mark.parametrize("encoding", ENCODINGS)
@pytest.mark.parametrize("kind", sorted(FORMULAS))
def test_the_compiled_guarantee_means_what_it_says(
    tmp_path: Path, kind: str, encoding: str
) -> None:
    spec = load(_spec_file(tmp_path, FORMULAS[kind]), encoding).gr1
    formula = spec.sys_trans[-1].formula
    primed = kind == "next"
    key = ("nw" if encoding == "onehot" else "region") + ("'" if primed else "")
    inside, outside = (1, 0) if encoding == "onehot" else (0, 1)
    assert atoms(formula) == {(key.rstrip("'"), primed)}
    assert evaluate(formula, {key: inside}) is True
    assert evaluate(formula, {key: outside}) is False
    blasted = bitblast(spec).sys_trans[len(spec.sys_trans) - 1].formula  # before the ranges
    bits = {"nw": 1} if encoding == "onehot" else {"region@0.0.3": 0, "region@1": 0}
    assert evaluate(blasted, {bit + "'" * primed: value for bit, value in bits.items()})


def test_nested_next_is_refused_with_a_position(tmp_path: Path) -> None:
    path = _spec_file(tmp_path, "next " * DEPTH + "nw")
    with pytest.raises(FormulaError, match="'next' inside 'next'") as err:
        load(path)
    assert err.value.span is not None and (err.value.span.line, err.value.span.column) == (24, 23)


@pytest.mark.parametrize("encoding", ENCODINGS)
def test_a_deep_spec_is_solved_synthesized_and_verified(tmp_path: Path, encoding: str) -> None:
    realizable = load(_spec_file(tmp_path, "!" * DEPTH + "(nw | !nw)"), encoding).gr1
    assert check(realizable).realizable
    controller = synthesize(realizable)
    assert controller is not None and verify(realizable, controller).ok
    never_sw = load(_spec_file(tmp_path, "!" * DEPTH + "!sw", "never.gait"), encoding).gr1
    assert not check(never_sw).realizable


# ---------------------------------------------------------------- the CLI never exits 70
@pytest.mark.parametrize("kind", sorted(FORMULAS))
def test_lint_accepts_deep_guarantees(tmp_path: Path, kind: str) -> None:
    assert main(["lint", str(_spec_file(tmp_path, FORMULAS[kind]))]) == 0


@pytest.mark.parametrize(
    ("guarantee", "message"),
    [
        ("next " * DEPTH + "nw", "'next' inside 'next'"),
        ("!" * DEPTH + "zz", "unknown name 'zz'"),
        ("!" * DEPTH, "unexpected end of file"),
        (" & ".join(["nw"] * DEPTH) + " &", "unexpected end of file"),
        (" -> ".join(["nw"] * DEPTH) + " -> ->", "unexpected '->'"),
        ("(" * DEPTH + "nw", "is never closed"),
        ("!" * DEPTH + "(nw until ne)", "'until' is outside GR(1)"),
    ],
    ids=["nested-next", "unknown-name", "no-atom", "dangling-and", "double-arrow", "unclosed",
         "until"],
)
def test_lint_reports_errors_in_deep_guarantees(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], guarantee: str, message: str
) -> None:
    assert main(["lint", str(_spec_file(tmp_path, guarantee))]) == 1
    first = capsys.readouterr().err.splitlines()[0]
    assert first.startswith(f"{tmp_path / 'deep.gait'}:24:") and message in first


def test_compile_writes_a_deep_spec(tmp_path: Path) -> None:
    out = tmp_path / "deep.slugsin"
    assert main(["compile", str(_spec_file(tmp_path, FORMULAS["implies"])), "-o", str(out)]) == 0
    assert out.read_text(encoding="utf-8").count("| ! 1") == DEPTH - 1


# ---------------------------------------------------------------- the nesting limit
def test_the_limit_is_documented_and_at_least_ten_thousand() -> None:
    assert parse_tree.MAX_NESTING >= DEPTH
    assert f"{parse_tree.MAX_NESTING:,}" in (ROOT / "docs" / "language.md").read_text("utf-8")


def test_a_formula_beyond_the_limit_is_refused_where_it_crosses_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(parse_tree, "MAX_NESTING", 50)
    text = PATROL + "guarantee " + "!" * 49 + "nw\n"  # 50 levels: accepted
    assert parse_text(text, "s.gait").statements[-1].formula is not None
    with pytest.raises(FormulaError) as err:
        parse_text(PATROL + "guarantee always nw & " + "!" * 60 + "ne\n", "s.gait")
    assert err.value.message == "formula nested 63 levels deep; the limit is 50"
    assert err.value.span is not None
    assert (err.value.span.line, err.value.span.column) == (24, 23 + 48)  # the 50th '!'


def test_the_real_limit_is_enforced(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    limit = parse_tree.MAX_NESTING
    assert main(["lint", str(_spec_file(tmp_path, "!" * limit + "nw"))]) == 1
    assert f"formula nested {limit + 2} levels deep; the limit is {limit}" in (
        capsys.readouterr().err)


# ---------------------------------------------------------------- the IR functions
def _deep_not(core: Expr, depth: int = DEPTH) -> Expr:
    for _ in range(depth):
        core = Not(core)
    return core


def _deep_implies(depth: int = DEPTH) -> Expr:
    formula: Expr = Var("b")
    for k in range(depth):
        formula = Implies(Var("a", k % 2 == 1), formula)
    return formula


def test_ir_functions_handle_deep_formulas() -> None:
    a, b = Var("a"), Var("b")
    deep = _deep_not(And((a, b)))
    assert height(deep) == DEPTH + 2
    assert evaluate(deep, {"a": 1, "b": 1}) is True
    assert simplify(deep) == And((a, b))
    assert simplify(_deep_not(a, DEPTH + 1)) == Not(a)
    primed = prime(deep)
    assert atoms(primed) == {("a", True), ("b", True)}
    assert push_next(Next(deep)) == primed
    swapped = substitute(deep, {("a", False): Not(b)})
    assert evaluate(swapped, {"b": 1}) is False
    chain = _deep_implies()
    assert evaluate(chain, {"a": 1, "a'": 1, "b": 0}) is False
    assert evaluate(chain, {"a": 1, "a'": 0, "b": 0}) is True


def test_bitblast_and_monitor_handle_deep_formulas() -> None:
    formula = _deep_not(Compare("<", IntVar("x"), IntConst(3)))
    spec = GR1Spec(outputs=(Variable("x", 0, 5),), sys_init=(Clause(formula, Origin("deep")),))
    blasted = bitblast(spec)
    lowered = blasted.sys_init[0].formula
    for x in range(6):
        bits = {"x@0.0.5": x & 1, "x@1": x >> 1 & 1, "x@2": x >> 2 & 1}
        assert evaluate(lowered, bits) == (x < 3)
        check_x = compile_formula(formula, ["x"])
        assert check_x([x, 0]) == (x < 3) == evaluate(formula, {"x": x})
