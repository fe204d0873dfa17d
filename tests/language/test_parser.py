"""Parser tests: every .gait construct becomes the expected syntax tree (spans ignored)."""

from __future__ import annotations

import pytest

from gaitc.diagnostics import FormulaError, SpecSyntaxError
from gaitc.ir import formula as f
from ltlcompiler import syntax as s
from ltlcompiler.parser import parse


def one(text: str) -> s.Statement:
    statements = parse(text, "t.gait").statements
    assert len(statements) == 1
    return statements[0]


def formula(text: str) -> f.Expr:
    st = one(f"guarantee {text}")
    assert isinstance(st, s.GuaranteeDecl)
    return st.formula


N = s.Name
V = f.Var


def test_robot_and_comments() -> None:
    assert one('# a comment\nrobot "thesis robot A"  # trailing\n') == s.RobotDecl("thesis robot A")


def test_legs_range_and_single() -> None:
    assert one("legs L1..L8 health 3") == s.LegsDecl((s.NameRange(N("L1"), N("L8")),), 3)
    assert one("leg L2 health 2") == s.LegsDecl((N("L2"),), 2)
    assert one("legs A, B..B3 health 1") == s.LegsDecl((N("A"), s.NameRange(N("B"), N("B3"))), 1)


def test_gait_with_direction_and_valves() -> None:
    st = one("gait north_a uses L1, L5 moves north valves 10001000, 00001000")
    assert st == s.GaitDecl(
        N("north_a"),
        False,
        (N("L1"), N("L5")),
        directions=(s.Direction("north"),),
        primitive=s.ValvesPrimitive((N("10001000"), N("00001000"))),
    )


def test_gait_with_transitions_and_cells() -> None:
    st = one("gait hop uses L2 moves r1 -> r2, (1, 2) -> r3")
    assert isinstance(st, s.GaitDecl)
    assert st.transitions == (
        s.Arrow(N("r1"), N("r2")),
        s.Arrow(s.Cell(1, 2), N("r3")),
    )
    assert st.directions == ()


def test_gait_several_directions() -> None:
    st = one("gait diag uses L1 moves north, east")
    assert isinstance(st, s.GaitDecl)
    assert [d.name for d in st.directions] == ["north", "east"]


def test_correction_gait_and_bare_gait() -> None:
    assert one("correction gait adjust") == s.GaitDecl(N("adjust"), True, None)
    assert one("gait g uses L1") == s.GaitDecl(N("g"), False, (N("L1"),))


def test_robot_primitive() -> None:
    st = one('gait e uses L3 moves east primitive "robots/radial8.yaml" direction +x method reset')
    assert isinstance(st, s.GaitDecl)
    assert st.primitive == s.RobotPrimitive("robots/radial8.yaml", "+x", N("reset"))
    bare = one('gait e uses L3 primitive "r.yaml"')
    assert isinstance(bare, s.GaitDecl)
    assert bare.primitive == s.RobotPrimitive("r.yaml", None, None)


def test_grid_block_region() -> None:
    assert one("grid 4 x 5 cells r0..r19") == s.GridDecl(4, 5, (s.NameRange(N("r0"), N("r19")),))
    assert one("grid 2x3") == s.GridDecl(2, 3, None)
    assert one("block r7, (2, 3)") == s.BlockDecl((N("r7"), s.Cell(2, 3)))
    assert one("region dock, hall") == s.RegionDecl((N("dock"), N("hall")))
    assert one("regions a..a2") == s.RegionDecl((s.NameRange(N("a"), N("a2")),))


def test_edges() -> None:
    assert one("edge dock -> hall by north_a, hop") == s.EdgeDecl(
        N("dock"), N("hall"), False, gaits=(N("north_a"), N("hop"))
    )
    assert one("edge hall <-> lab east") == s.EdgeDecl(
        N("hall"), N("lab"), True, direction=s.Direction("east")
    )


def test_task_statements() -> None:
    assert one("cache r3, (0, 1)") == s.CacheDecl((N("r3"), s.Cell(0, 1)))
    assert one("hazard blue: r7, r9") == s.HazardDecl(N("blue"), (N("r7"), N("r9")))
    assert one("hazard empty:") == s.HazardDecl(N("empty"), ())
    assert one("start r12") == s.StartDecl(N("r12"), ())
    assert one("start r12 with L1 = 2, L3..L4 = 1") == s.StartDecl(
        N("r12"),
        (s.HealthInit(N("L1"), 2), s.HealthInit(s.NameRange(N("L3"), N("L4")), 1)),
    )
    assert one("visit r11, r12 infinitely often") == s.VisitDecl((N("r11"), N("r12")))


def test_statements_need_no_separator() -> None:
    spec = parse("legs L1 health 2 gait g uses L1 moves east grid 1 x 2 start r0", "t.gait")
    assert [type(st).__name__ for st in spec.statements] == [
        "LegsDecl", "GaitDecl", "GridDecl", "StartDecl",
    ]


def test_keywords_are_contextual() -> None:
    assert one("region edge, x, cells") == s.RegionDecl((N("edge"), N("x"), N("cells")))


def test_formula_precedence() -> None:
    a, b, c = V("a"), V("b"), V("c")
    assert formula("a & b | c") == f.Or((f.And((a, b)), c))
    assert formula("a | b & c") == f.Or((a, f.And((b, c))))
    assert formula("a -> b -> c") == f.Implies(a, f.Implies(b, c))
    assert formula("a <-> b -> c") == f.Iff(a, f.Implies(b, c))
    assert formula("a ^ b & c") == f.Xor(a, f.And((b, c)))
    assert formula("a & b & c") == f.And((a, b, c))
    assert formula("!a & b") == f.And((f.Not(a), b))
    assert formula("next a & b") == f.And((f.Next(a), b))
    assert formula("next(a & b)") == f.Next(f.And((a, b)))


def test_formula_word_operators() -> None:
    assert formula("not a and b or c xor d") == formula("!a & b | c ^ d")


def test_formula_temporal_prefix_covers_the_rest() -> None:
    assert formula("always eventually !a & !b") == f.Always(
        f.Eventually(f.And((f.Not(V("a")), f.Not(V("b")))))
    )
    assert formula("always (a -> next(b))") == f.Always(f.Implies(V("a"), f.Next(V("b"))))


def test_formula_atoms() -> None:
    assert formula("true | false") == f.Or((f.TRUE, f.FALSE))
    assert formula("health(L1) >= 2") == f.Compare(">=", f.IntVar("L1"), f.IntConst(2))
    assert formula("failed(L1)") == f.Compare("=", f.IntVar("L1"), f.IntConst(1))
    for op in f.COMPARE_OPS:
        assert formula(f"health(L2) {op} 3") == f.Compare(op, f.IntVar("L2"), f.IntConst(3))


def test_spans() -> None:
    st = parse("\n  gait g uses L1 moves east", "t.gait").statements[0]
    assert isinstance(st, s.GaitDecl)
    assert st.span is not None and (st.span.line, st.span.column) == (2, 3)
    assert st.name.span is not None and (st.name.span.line, st.name.span.column) == (2, 8)
    assert st.name.span.end_column == 8
    assert st.name.span.file == "t.gait"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("legs L1 3", "2:9: unexpected number '3'; expected ',', '..' or 'health'"),
        ("grid 2 x", "2:9: unexpected end of file; expected a number"),
        ("guarantee (a", "2:11: '(' is never closed; add a matching ')'"),
        ("guarantee a)", "2:12: ')' has no matching '('; remove it or add '('"),
        ("region a$", "2:9: unexpected character '$': names use letters, digits and '_', "
         "comments start with '#'"),
        ("hazard : a", "2:8: unexpected ':'; expected a name"),
    ],
)
def test_syntax_errors(text: str, message: str) -> None:
    with pytest.raises(SpecSyntaxError) as info:
        parse("\n" + text, "t.gait")
    err = info.value
    assert err.span is not None
    assert f"{err.span.line}:{err.span.column}: {err.message}" == message


def test_temporal_words_inside_formulas_are_gr1_errors() -> None:
    with pytest.raises(FormulaError, match="'always' may only start an assume or guarantee"):
        parse("guarantee a & always b", "t.gait")
    with pytest.raises(FormulaError, match="'until' is outside GR\\(1\\)"):
        parse("assume a until b", "t.gait")


def test_every_example_in_the_language_reference_parses() -> None:
    from pathlib import Path

    from ltlcompiler.frontend import model_from_text

    doc = (Path(__file__).resolve().parents[2] / "docs" / "language.md").read_text("utf-8")
    blocks = doc.split("```gait\n")[1:]
    assert len(blocks) >= 8
    for block in blocks:
        parse(block.split("```")[0], "language.md")
    model, _ = model_from_text(blocks[0].split("```")[0], "language.md")
    assert model.start == "r12" and len(model.regions) == 20
