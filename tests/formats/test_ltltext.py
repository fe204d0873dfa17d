"""Tests of the readable LTL text, its writer and its reader (slugs_bridge/ltltext.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.diagnostics import SlugsFormatError, Span
from gaitc.ir.formula import Add, And, Compare, Const, IntConst, IntVar, Not, Or, Var
from gaitc.ir.spec import Clause, GR1Spec, Origin, Variable
from slugs_bridge.formats import load_spec_file
from slugs_bridge.ltltext import emit_ltl, parse_ltl
from slugs_bridge.slugsin import parse_slugsin

DATA = Path(__file__).parents[1] / "data"


def test_layout_operators_and_origins() -> None:
    where = Span("robot.gait", 12, 3)
    spec = GR1Spec(
        inputs=(Variable("hurt"),),
        outputs=(Variable("gait", 0, 3), Variable("move")),
        env_init=(Clause(Not(Var("hurt")), Origin("initial health", where)),),
        sys_trans=(
            Clause(Or((Not(Var("hurt", True)), Var("move", True))), Origin("eq. 3.5")),
            Clause(Compare("<=", IntVar("gait", True), IntConst(2))),
        ),
        sys_liveness=(Clause(And((Var("move"), Var("hurt")))),),
        name="demo",
    )
    assert emit_ltl(spec) == (
        "# GR(1) specification of demo in LTL: G = always, F = eventually, X = next state\n"
        "# inputs (environment): hurt\n"
        "# outputs (system): gait in 0..3, move\n"
        "(  # assumptions (environment)\n"
        "    !hurt  # initial health (robot.gait:12:3)\n"
        ")\n"
        "->\n"
        "(  # guarantees (system)\n"
        "    G (!X hurt | X move)  # eq. 3.5\n"
        "  & G (X gait <= 2)\n"
        "  & G F (move & hurt)\n"
        ")\n"
    )


def test_empty_sides_are_true_and_output_is_deterministic() -> None:
    spec = GR1Spec(outputs=(Variable("y"),), sys_init=(Clause(Var("y")),))
    text = emit_ltl(spec)
    assert "(  # assumptions (environment)\n    TRUE\n)" in text
    assert emit_ltl(spec) == text
    assert "# inputs (environment): (none)" in text


def test_every_clause_of_a_file_gets_one_line() -> None:
    path = DATA / "slugs_examples" / "firefighting.slugsin"
    spec = parse_slugsin(path.read_text(encoding="utf-8"), str(path))
    text = emit_ltl(spec)
    clauses = sum(len(spec.section(s)) for s in (
        "env_init", "sys_init", "env_trans", "sys_trans", "env_liveness", "sys_liveness"))
    conjunct_lines = [ln for ln in text.splitlines() if f"({path}:" in ln]
    assert len(conjunct_lines) == clauses
    assert all("slugsin [" in ln for ln in conjunct_lines)


# ---------------------------------------------------------------- the reader
SLUGS_FILES = sorted([*DATA.glob("slugs_examples/*.slugsin"), *DATA.glob("slugs_examples/*.txt"),
                      *DATA.glob("slugs_examples/*.structuredslugs")])


def test_the_reader_gives_back_the_spec() -> None:
    where = Span("robot.gait", 12, 3)
    spec = GR1Spec(
        inputs=(Variable("hurt"), Variable("k", -2, 2)),
        outputs=(Variable("gait", 0, 3), Variable("move")),
        env_init=(Clause(Not(Var("hurt")), Origin("initial health", where)),),
        env_trans=(Clause(Compare("=", IntVar("k", True), Add(IntVar("k"), IntConst(1)))),),
        sys_trans=(Clause(Or((Not(Var("hurt", True)), Var("move", True))), Origin("eq. 3.5")),),
        sys_liveness=(Clause(And((Var("move"), Var("hurt", True)))),),
    )
    text = emit_ltl(spec)
    assert "G (X k = k + 1)" in text  # X binds to the atom: k' = k + 1, not (k = k + 1)'
    again = parse_ltl(text, "demo.ltl")
    assert again == spec
    assert again.env_init[0].origin == Origin("ltl [ENV_INIT]", Span("demo.ltl", 5, 5))


@pytest.mark.parametrize("path", SLUGS_FILES, ids=lambda p: p.name)
def test_every_slugs_example_round_trips_through_ltl(path: Path) -> None:
    spec = load_spec_file(str(path))
    assert parse_ltl(emit_ltl(spec), "again.ltl") == spec


def test_a_single_true_clause_is_not_an_empty_side() -> None:
    one = GR1Spec(outputs=(Variable("y"),), sys_init=(Clause(Const(True)),))
    assert "(  # guarantees (system)\n    (TRUE)\n)" in emit_ltl(one)
    assert parse_ltl(emit_ltl(one), "x.ltl") == one
    first = GR1Spec(outputs=(Variable("y"),), sys_init=(Clause(Const(True)), Clause(Var("y"))))
    assert "    TRUE\n  & y\n" in emit_ltl(first)
    assert parse_ltl(emit_ltl(first), "x.ltl") == first
    empty = GR1Spec(outputs=(Variable("y"),))
    assert parse_ltl(emit_ltl(empty), "x.ltl") == empty


def test_huge_trees_are_written_as_slugsin_lines() -> None:
    parts = ["a"] + [f"^ ? {i} ? {i}" for i in range(30)]  # 2**30 leaves as a tree
    spec = parse_slugsin("[INPUT]\na\n[SYS_LIVENESS]\n$ 31 " + " ".join(parts) + "\n", "dag")
    text = emit_ltl(spec)
    assert len(text) < 1000 and "\n    G F (slugsin: $ 30 ^ a a ^ ? 0 ? 0 " in text
    assert parse_ltl(text, "dag.ltl") == spec


LTL_ERRORS = [
    ("# outputs (system): y\n(\n    y\n)\n->\n(\n    TRUE\n)\n", 1, 1,
     "the LTL text has no '# inputs (environment):' comment declaring its inputs"),
    ("# inputs (environment): y\n# outputs (system): (none)\n(\n  y\n)\n", 3, 1,
     "this is not the LTL text gaitc writes: expected '(' conjuncts ')' '->' '(' "
     "conjuncts ')'"),
    ("# inputs (environment): a\n# outputs (system): y\n(\n    a\n    a\n)\n->\n(\n    TRUE\n)\n",
     5, 5, "a conjunct after the first must start with '& '"),
    ("# inputs (environment): a\n# outputs (system): y\n(\n    a\n  & G (a & zz)\n)\n->\n(\n"
     "    TRUE\n)\n", 5, 12, "unknown variable 'zz'; declare it under [INPUT] or [OUTPUT]"),
    ("# inputs (environment): a\n# outputs (system): y\n(\n    G F (slugsin: & a ?)\n)\n->\n(\n"
     "    TRUE\n)\n", 4, 23, "missing operand: '?' must be followed by a buffer element number, "
     "but the line ends here"),
    ("# inputs (environment): X\n# outputs (system): y\n(\n    TRUE\n)\n->\n(\n    TRUE\n)\n",
     1, 25, "'X' cannot be a variable name in LTL text"),
    ("# inputs (environment): k in 1...3\n# outputs (system): y\n", 1, 25,
     "bad integer range 'k in 1...3': write name in MIN..MAX"),
    ("# inputs (environment): a\n# outputs (system): y\n(\n    TRUE\n)\n->\n(\n    X a\n)\n",
     8, 7, "next-state variable 'a'' cannot appear in [SYS_INIT]: initial conditions "
     "constrain the first state only"),
]


@pytest.mark.parametrize(("text", "line", "column", "message"), LTL_ERRORS)
def test_reader_errors_are_positioned(text: str, line: int, column: int, message: str) -> None:
    with pytest.raises(SlugsFormatError) as info:
        parse_ltl(text, "bad.ltl")
    assert info.value.message == message
    assert info.value.span is not None
    assert (info.value.span.line, info.value.span.column) == (line, column)


SEED_LTL = emit_ltl(GR1Spec(
    inputs=(Variable("a"), Variable("k", 0, 3)), outputs=(Variable("G"), Variable("y")),
    env_trans=(Clause(Compare("<=", IntVar("k", True), IntConst(2))),),
    sys_trans=(Clause(Or((Not(Var("G", True)), Var("y")))),),
    sys_liveness=(Clause(And((Var("y"), Var("a", True)))),),
))
LTL_PIECES = ["&", "|", "!", "X", "G", "F", "(", ")", "->", "#", "in", "..", ",", "\n", " ",
              "TRUE", "k", "G_", "slugsin: ", "$ 1", "? 0", '"', "{", "é"]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(st.integers(0, len(SEED_LTL)), st.sampled_from(LTL_PIECES),
                          st.integers(0, 3)), max_size=6))
def test_mutated_ltl_raises_only_format_errors(edits: list[tuple[int, str, int]]) -> None:
    text = SEED_LTL
    for position, piece, cut in edits:
        text = text[:position] + piece + text[position + cut:]
    try:
        spec = parse_ltl(text, "fuzz.ltl")
    except SlugsFormatError as err:
        assert err.span is not None and err.span.file == "fuzz.ltl"
        return
    assert parse_ltl(emit_ltl(spec), "again.ltl") == spec
