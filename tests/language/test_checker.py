"""Checker tests: hand-checked Models for a 2 x 2 grid and a tiny explicit map, plus details."""

from __future__ import annotations

from typing import get_args

import pytest

from gaitc.diagnostics import FormulaError, SpecSemanticError
from gaitc.ir import formula as f
from ltlcompiler.frontend import model_from_text
from ltlcompiler.model import (
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

GRID = """
robot "tiny"
legs L1..L2 health 2
leg L3 health 3
gait n uses L1 moves north
gait s uses L1 moves south
gait e uses L2, L3 moves east
gait w uses L3, L2 moves west
correction gait adjust
grid 2 x 2 cells nw, ne, sw, se
cache ne
hazard lava: sw
start nw with L3 = 2
visit se infinitely often
assume always eventually !lava
assume always (lava -> next(failed(L1) | !lava))
guarantee always (nw -> next(!sw))
guarantee !lava
"""

EXPLICIT = """
legs L1 health 2
gait hop uses L1 moves dock -> hall
gait fwd uses L1 moves east
correction gait turn moves hall -> hall
region dock, hall, lab
edge hall <-> lab east
edge lab -> dock by hop
start dock
visit lab infinitely often
"""


def test_grid_model_by_hand() -> None:
    model, warnings = model_from_text(GRID, "grid.gait")
    # 'guarantee !lava' names a hazard only: the robot cannot make it hold
    assert [(w.message, w.span.line if w.span else None) for w in warnings] == [
        ("this guarantee names only what the environment chooses (hazards, leg health), so "
         "the robot cannot make it hold: the spec is unrealizable unless the assumptions "
         "already force it", 18)]
    assert model.name == "tiny"
    assert model.legs == (Leg("L1", 2, 2), Leg("L2", 2, 2), Leg("L3", 3, 2))
    assert model.gaits == (
        Gait("n", GaitKind.MOVE, ("L1",)),
        Gait("s", GaitKind.MOVE, ("L1",)),
        Gait("e", GaitKind.MOVE, ("L2", "L3")),
        Gait("w", GaitKind.MOVE, ("L2", "L3")),  # sorted in leg declaration order
        Gait("adjust", GaitKind.CORRECTION, ()),
        Gait("noGait", GaitKind.NONE, ()),
    )
    assert model.regions == (
        Region("nw", 0, 0), Region("ne", 0, 1), Region("sw", 1, 0), Region("se", 1, 1),
    )
    stay = ("adjust", "noGait")
    assert model.transitions == (
        Transition("nw", "nw", stay),
        Transition("nw", "ne", ("e",)),
        Transition("nw", "sw", ("s",)),
        Transition("ne", "nw", ("w",)),
        Transition("ne", "ne", stay),
        Transition("ne", "se", ("s",)),
        Transition("sw", "nw", ("n",)),
        Transition("sw", "sw", stay),
        Transition("sw", "se", ("e",)),
        Transition("se", "ne", ("n",)),
        Transition("se", "sw", ("w",)),
        Transition("se", "se", stay),
    )
    assert model.caches == ("ne",)
    assert model.hazards == (Hazard("lava", ("sw",)),)
    assert model.start == "nw"
    assert model.grid == (2, 2)
    assert model.goals == (UserFormula(Section.LIVENESS, f.Var("se")),)
    lava, sw = f.Var("lava"), f.Var("sw")
    failed_l1 = f.Compare("=", f.IntVar("L1"), f.IntConst(1))
    assert model.assumptions == (
        UserFormula(Section.LIVENESS, f.Not(lava)),
        UserFormula(Section.TRANS, f.Implies(lava, f.Next(f.Or((failed_l1, f.Not(lava)))))),
    )
    assert model.guarantees == (
        UserFormula(Section.TRANS, f.Implies(f.Var("nw"), f.Next(f.Not(sw)))),
        UserFormula(Section.INIT, f.Not(lava)),
    )
    assert model.gaits_using("L3") == ("e", "w")


def test_explicit_model_by_hand() -> None:
    model, warnings = model_from_text(EXPLICIT, "map.gait")
    assert model.regions == (Region("dock"), Region("hall"), Region("lab"))
    assert model.grid is None
    assert model.transitions == (
        Transition("dock", "dock", ("noGait",)),
        Transition("dock", "hall", ("hop",)),
        Transition("hall", "hall", ("turn", "noGait")),
        Transition("hall", "lab", ("fwd",)),
        Transition("lab", "dock", ("hop",)),
        Transition("lab", "lab", ("noGait",)),
    )
    assert [w.message for w in warnings] == [
        "no gait moves west, so edge lab -> hall is never usable"
    ]
    assert warnings[0].span is not None and warnings[0].span.line == 7
    assert model.hazards == () and model.caches == ()
    assert model.legs == (Leg("L1", 2, 2),)


def test_default_cell_names_and_blocks() -> None:
    text = """
    legs L1 health 2
    gait e uses L1 moves east
    gait s uses L1 moves south
    grid 2 x 3
    block r1, (1, 2)
    start r0
    """
    model, _ = model_from_text(text, "b.gait")
    assert [r.name for r in model.regions] == ["r0", "r2", "r3", "r4"]
    moves = {(t.source, t.target) for t in model.transitions if t.source != t.target}
    # r0 -> r1 is blocked; r2 -> r5 is blocked; r3 -> r4 (east), r0 -> r3, r2? no south from r2
    assert moves == {("r0", "r3"), ("r3", "r4")}


def test_leading_zero_ranges_keep_width() -> None:
    model, _ = model_from_text(
        "legs L08..L10 health 2 gait g uses L09 moves east grid 1 x 2 start r0", "z.gait"
    )
    assert [leg.name for leg in model.legs] == ["L08", "L09", "L10"]


def test_primitive_binding() -> None:
    text = (
        'legs L1 health 2 gait g uses L1 moves east primitive "robots/r.yaml" direction -y '
        "method full gait h uses L1 moves east valves 1, 0 grid 1 x 2 start r0"
    )
    model, _ = model_from_text(text, "p.gait")
    g, h = model.gait("g").primitive, model.gait("h").primitive
    assert g is not None and (g.robot, g.direction, g.method, g.valves) == (
        "robots/r.yaml", "-y", "full", (),
    )
    assert h is not None and h.valves == ("1", "0") and h.robot is None


def test_edge_direction_and_grid_cells_mix() -> None:
    text = """
    legs L1 health 2
    gait n uses L1 moves north
    gait s uses L1 moves south
    grid 1 x 1 cells yard
    region shed
    edge yard <-> shed north
    start yard
    """
    model, warnings = model_from_text(text, "m.gait")
    moves = {(t.source, t.target, t.gaits) for t in model.transitions if t.source != t.target}
    assert moves == {("yard", "shed", ("n",)), ("shed", "yard", ("s",))}
    assert warnings == []


def test_assumption_may_use_next_of_environment_variables_only() -> None:
    base = "legs L1 health 3 gait g uses L1 moves east grid 1 x 2 hazard h: r1 start r0 "
    model, _ = model_from_text(base + "assume always (g -> next(health(L1) >= 2 | h))", "a")
    assert model.assumptions[0].section is Section.TRANS
    with pytest.raises(FormulaError, match=r"next\(r1\)"):
        model_from_text(base + "assume always next(r1)", "a")
    model, _ = model_from_text(base + "guarantee always next(r1 & g)", "a")
    assert model.guarantees[0].formula == f.Next(f.And((f.Var("r1"), f.Var("g"))))


def test_nogait_is_a_formula_atom() -> None:
    model, _ = model_from_text(
        "legs L1 health 2 gait g uses L1 moves east grid 1 x 2 start r0 "
        "guarantee always eventually noGait",
        "n",
    )
    assert model.guarantees == (UserFormula(Section.LIVENESS, f.Var("noGait")),)


def test_deterministic() -> None:
    first, w1 = model_from_text(GRID, "grid.gait")
    second, w2 = model_from_text(GRID, "grid.gait")
    assert first == second and w1 == w2
    assert repr(first) == repr(second)
    assert isinstance(first, Model)


def test_order_of_statements_does_not_matter_for_names() -> None:
    text = "start r0 grid 1 x 2 gait g uses L1 moves east legs L1 health 2 cache r1"
    model, _ = model_from_text(text, "o.gait")
    assert model.start == "r0" and model.caches == ("r1",)


def test_error_points_at_the_offending_name() -> None:
    with pytest.raises(SpecSemanticError) as info:
        model_from_text("legs L1 health 2\ngait g uses L1, L1x moves east grid 1 x 2 start r0", "e")
    assert info.value.span is not None
    assert (info.value.span.line, info.value.span.column) == (2, 17)
    assert info.value.hint == "did you mean 'L1'?"


# ------------------------------------------------------------ statement dispatch (issue 49)
def _statement_matches(path: str) -> list[tuple[set[str], bool]]:
    """Each ``match`` of ``path`` whose cases name statement classes (``s.LegsDecl()``):
    the classes it names, and whether its last case is ``case _: unreachable(...)``."""
    import ast
    from pathlib import Path

    from ltlcompiler import syntax as s

    kinds = {kind.__name__ for kind in get_args(s.Statement)}
    tree = ast.parse((Path(__file__).resolve().parents[2] / path).read_text())
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Match):
            continue
        named = {n.cls.attr for case in node.cases for n in ast.walk(case.pattern)
                 if isinstance(n, ast.MatchClass) and isinstance(n.cls, ast.Attribute)}
        if not named & kinds:
            continue
        last = node.cases[-1]
        closed = (isinstance(last.pattern, ast.MatchAs) and last.pattern.pattern is None
                  and isinstance(last.body[0], ast.Expr)
                  and isinstance(last.body[0].value, ast.Call)
                  and isinstance(last.body[0].value.func, ast.Name)
                  and last.body[0].value.func.id == "unreachable")
        found.append((named, closed))
    return found


def test_statement_is_every_statement_class_of_the_syntax() -> None:
    import dataclasses

    from ltlcompiler import syntax as s

    declared = {name for name, value in vars(s).items()
                if dataclasses.is_dataclass(value) and name.endswith("Decl")}
    assert {kind.__name__ for kind in get_args(s.Statement)} == declared


@pytest.mark.parametrize("path", ["ltlcompiler/checker.py", "gaitc/lsp/index.py"])
def test_statements_are_dispatched_by_one_exhaustive_match(path: str) -> None:
    """The checker and the editor's index each sort statements in one ``match`` that names
    every kind of ``Statement`` and ends in ``unreachable`` (so mypy reports a new kind),
    and no ``isinstance`` test on a statement is left."""
    from pathlib import Path

    from ltlcompiler import syntax as s

    kinds = {kind.__name__ for kind in get_args(s.Statement)}
    matches = _statement_matches(path)
    assert any(named == kinds and closed for named, closed in matches), matches
    assert all(closed for _, closed in matches)
    text = (Path(__file__).resolve().parents[2] / path).read_text()
    assert not [k for k in kinds if f"isinstance(st, s.{k})" in text]
