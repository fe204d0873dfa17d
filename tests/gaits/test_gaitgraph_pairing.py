"""Robot files (validation with positions) and pairing of spec gaits with primitives."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.diagnostics import Span
from gaitc.gaitgraph.pairing import check_gaits, resolve_primitive
from gaitc.gaitgraph.robot import RobotFileError, load_robot, parse_robot
from ltlcompiler.model import Gait, GaitKind, Primitive

ROBOTS = Path(__file__).resolve().parents[2] / "specs" / "robots"
GOOD = """robot: tiny
chassis: {mass: 10}
legs:
  - {name: A, mount: [10, 0, 0], length: 50, chambers: [{curvature: 0.01}]}
  - {name: B, mount: [-10, 5, 0], length: 50, chambers: [{curvature: 0.01}]}
  - {name: C, mount: [-10, -5, 0], length: 50, chambers: [{curvature: 0.01}]}
"""


def test_all_shipped_robots_load() -> None:
    counts = {p.stem: load_robot(p).valve_count for p in ROBOTS.glob("*.yaml")}
    assert counts == {"symmetric6": 24, "asymmetric6": 24, "radial8": 8, "silicone6": 6}
    assert len(load_robot(ROBOTS / "radial8.yaml").gaits) == 12


@pytest.mark.parametrize(
    ("text", "line", "token", "words"),
    [
        (GOOD.replace("mass: 10", "mass: ten"), 2, "ten", "chassis mass must be a number"),
        (GOOD.replace("length: 50, ch", "lenght: 50, ch", 1), 4, "lenght", "unknown key 'lenght'"),
        (GOOD.replace("chassis: {mass: 10}\n", ""), 1, "robot", "no 'chassis' section"),
        (
            GOOD + "gaits:\n  - {name: g, legs: [A], direction: +x, valves: ['12']}\n",
            8,
            "'12'",
            "must have 3 digits",
        ),
        (
            GOOD + "gaits:\n  - {name: g, legs: [Z], direction: +x, valves: ['100']}\n",
            8,
            "Z",
            "unknown leg 'Z'",
        ),
    ],
)
def test_robot_file_errors_have_positions(text: str, line: int, token: str, words: str) -> None:
    with pytest.raises(RobotFileError) as info:
        parse_robot(text, "r.yaml")
    err = info.value
    assert words in err.message
    lines = text.splitlines()
    assert err.span == Span("r.yaml", line, lines[line - 1].index(token) + 1)


def test_a_robot_file_cut_short_has_its_error_on_its_last_line() -> None:
    with pytest.raises(RobotFileError, match="not valid YAML") as info:
        parse_robot("robot: [unclosed\n", "r.yaml")
    assert info.value.span == Span("r.yaml", 1, 17)  # past the end of line 1, not line 2


def _gait(name: str, legs: tuple[str, ...], prim: Primitive | None) -> Gait:
    return Gait(name, GaitKind.MOVE, legs, None, prim)


def test_inline_valves_one_per_leg_in_declaration_order() -> None:
    legs = ("L1", "L2", "L3", "L4")
    ok = _gait("a", ("L1", "L3"), Primitive(valves=("1000", "0010")))
    bad = _gait("b", ("L1", "L2"), Primitive(valves=("1000", "0001")))
    missing = _gait("c", ("L4",), None)
    diags = check_gaits([ok, bad, missing], ".", legs)
    assert [(d.severity, d.message.split(" ")[1]) for d in diags] == [
        ("error", "b"),
        ("warning", "c"),
    ]
    assert "pressurises L1, L4" in diags[0].message
    assert resolve_primitive(ok, ".", legs).pressurised_legs() == ("L1", "L3")


def test_robot_file_primitives(tmp_path: Path) -> None:
    spec_dir = str(ROBOTS.parent)
    stored = _gait("north", ("L6", "L8"), Primitive(robot="robots/radial8.yaml", direction="+y"))
    seq = resolve_primitive(stored, spec_dir)
    assert seq.source == "robot file gait north_L6_L8" and seq.pressurised_legs() == ("L6", "L8")
    wrong = _gait("east", ("L1", "L2"), Primitive(robot="robots/radial8.yaml", direction="+x"))
    inline = _gait("x", ("L1",), Primitive(valves=("10000000",), robot="robots/radial8.yaml"))
    lost = _gait("y", ("L1",), Primitive(robot="nowhere.yaml", direction="+x"))
    diags = check_gaits([stored, wrong, inline, lost], spec_dir)
    assert [d.message.split(" ")[1].rstrip(":") for d in diags] == ["east", "y"]
    assert all(d.severity == "error" for d in diags)
    assert "not found" in diags[1].message


def test_the_gait_search_of_a_primitive_is_bounded(monkeypatch: pytest.MonkeyPatch) -> None:
    """Fuzzing found a robot without a gait on which lint's search ran for over 100 s: the
    search of a primitive adds at most PAIRING_STATES valve states, and says so."""
    import gaitc.gaitgraph.search as search_module
    from gaitc.diagnostics import SpecSemanticError
    from gaitc.gaitgraph import pairing
    from gaitc.gaitgraph.graph import GaitGraph

    asked: list[int] = []

    def bounded(robot: object, direction: object, method: str, seed: int,
                max_states: int = 10_000) -> search_module.SearchResult:
        asked.append(max_states)
        return search_module.SearchResult(method, GaitGraph(robot), [], max_states, True)  # type: ignore[arg-type]

    monkeypatch.setattr(pairing, "search", bounded)  # the search pairing imported
    searched = _gait("north", ("L1", "L2"), Primitive(robot="robots/radial8.yaml",
                                                      direction="+y", method="reset"))
    with pytest.raises(SpecSemanticError, match=f"within {pairing.PAIRING_STATES} valve states"):
        resolve_primitive(searched, str(ROBOTS.parent))
    assert asked == [pairing.PAIRING_STATES]


def test_a_correction_gait_may_pressurise_no_leg() -> None:
    """Issue 60: a correction gait wears no leg (thesis 3.4.1), yet one whose valves fired
    a leg passed lint."""
    legs = ("L1", "L2", "L3", "L4")
    firing = Gait("adjust", GaitKind.CORRECTION, (), None, Primitive(valves=("0100",)))
    quiet = Gait("settle", GaitKind.CORRECTION, (), None, Primitive(valves=("0000",)))
    diags = check_gaits([firing, quiet], ".", legs)
    assert [(d.severity, d.message) for d in diags] == [
        ("error", "correction gait adjust wears no leg, but its primitive (inline) "
                  "pressurises L2")]
    assert diags[0].hint is not None and "thesis 3.4.1" in diags[0].hint
