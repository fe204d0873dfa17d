"""Tests of the readable LTL text (slugs_bridge/ltltext.py)."""

from __future__ import annotations

from pathlib import Path

from diagnostics import Span
from gr1.formula import And, Compare, IntConst, IntVar, Not, Or, Var
from gr1.spec import Clause, GR1Spec, Origin, Variable
from slugs_bridge.ltltext import emit_ltl
from slugs_bridge.slugsin import parse_slugsin

DATA = Path(__file__).parent / "data"


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
