"""One gait search (issue 49): the registry of search methods, and the ``.gait`` ``primitive``
clause searching a robot file's declared model as ``gaitc gaits`` does.

The must-show: for every shipped robot file with a ``model:`` section, every direction its
model moves and the legs of the gaits found that way, the primitive clause of a gait that
``uses`` those legs and ``gaitc.gaits(..., GaitOptions(direction, legs=...))`` give the same
valve sequence.
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

import gaitc
from gaitc.core.modes import SearchMethod
from gaitc.diagnostics import SpecSemanticError
from gaitc.gaitgraph.robot import Robot, RobotFileError, load_robot
from gaitc.search.primitives import resolve_primitive
from gaitc.search.registry import ENTRIES, SEARCHES, DirectionSearch, GoalSearch, goal_search

ROOT = Path(__file__).resolve().parents[2]
DIRECTIONS = ("+x", "-x", "+y", "-y")
#: Where robot files ship: the package's examples (``specs/`` links there) and the tutorial.
SHIPPED = (ROOT / "gaitc" / "examples" / "robots", ROOT / "docs" / "tutorial")


def _robots_with_models() -> list[Path]:
    found = []
    for folder in SHIPPED:
        for path in sorted(folder.glob("*.yaml")):
            try:
                robot = load_robot(path)
            except RobotFileError:  # a YAML file that is not a robot file
                continue
            if robot.models:
                found.append(path)
    return found


MODELLED = _robots_with_models()
#: The active-passive model simulates slowly: silicone6's case takes about 40 s.
CASES = [pytest.param(p, marks=pytest.mark.slow) if p.name == "silicone6.yaml" else p
         for p in MODELLED]


def test_every_search_method_has_exactly_one_entry() -> None:
    counts = Counter(e.method for e in ENTRIES)
    assert set(counts) == set(SearchMethod)
    assert all(n == 1 for n in counts.values()), counts
    assert set(SEARCHES) == set(SearchMethod)
    for method, entry in SEARCHES.items():
        assert entry.toward_goal == method.is_global
        assert isinstance(entry, GoalSearch if method.is_global else DirectionSearch)


def test_the_entries_declare_what_the_online_loop_asks() -> None:
    """D* Lite is known by its declared capability, not by an attribute of its planner."""
    assert [e.method for e in ENTRIES if e.replans_from_anywhere] == [SearchMethod.DSTAR]
    assert {e.method for e in ENTRIES if e.learns} == {m for m in SearchMethod if m.is_global}
    with pytest.raises(gaitc.UsageError, match="--method full searches toward a direction"):
        goal_search("full")


def test_the_shipped_modelled_robots_are_found() -> None:
    names = {p.name for p in MODELLED}
    assert {"radial8.yaml", "silicone6.yaml"} <= names


def _leg_orders(found: gaitc.api.gaits.GaitSearch, loaded: Robot,
                direction: str) -> list[tuple[str, ...]]:
    """The legs of the gaits ``gaitc gaits`` found toward ``direction`` (the first three),
    each in the order it pressurises them, and of the robot file's gaits that way (in their
    stored order, which the primitive clause prefers)."""
    assert isinstance(found, gaitc.api.gaits.ModelGaits)
    legs = found.found_search.loaded.valve_legs
    orders: list[tuple[str, ...]] = []
    for gait in found.found_search.gaits[:3]:
        fired = tuple(dict.fromkeys(leg for s in gait.states
                                    for leg, on in zip(legs, s, strict=True) if on))
        stored = [g for g in loaded.gaits
                  if g.direction == direction and set(g.legs) == set(fired)]
        order = tuple(stored[0].legs) if stored else fired
        if order not in orders:
            orders.append(order)
    orders += [tuple(g.legs) for g in loaded.gaits
               if g.direction == direction and tuple(g.legs) not in orders]
    return orders


def _primitive(tmp_path: Path, robot: Path, loaded: Robot, legs: tuple[str, ...],
               direction: str, lint: bool = True) -> tuple[tuple[str, ...], str]:
    """The valves and source the clause of a gait using ``legs`` resolves to."""
    declared = "\n".join(f"leg {leg.name} health 2" for leg in loaded.legs)
    text = (f'robot "r"\n{declared}\n'
            f'gait g uses {", ".join(legs)} moves a -> b, b -> a '
            f'primitive "{robot}" direction {direction}\n'
            "region a, b\nstart a\nvisit b infinitely often\n")
    spec = gaitc.parse(text, name=str(tmp_path / "g.gait"))
    assert spec.model is not None
    if lint:  # gaitc lint resolves the clause as gaitc drive and the language server do
        assert not [d for d in gaitc.lint(spec) if d.severity == "error"]
    order = [leg.name for leg in spec.model.legs]
    seq = resolve_primitive(spec.model.gaits[0], str(tmp_path), order)
    return seq.states, seq.source


@pytest.mark.parametrize("robot", CASES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_the_primitive_clause_finds_what_gaitc_gaits_finds(robot: Path, tmp_path: Path) -> None:
    loaded = load_robot(robot)
    searched = {d: gaitc.gaits(robot, gaitc.GaitOptions(d)) for d in DIRECTIONS}
    moving = [d for d, found in searched.items() if found.found]
    assert moving, f"{robot.name}'s model moves in no direction"
    checked = 0
    for direction in moving:
        for k, legs in enumerate(_leg_orders(searched[direction], loaded, direction)):
            by_gaits = gaitc.gaits(robot, gaitc.GaitOptions(direction, legs=legs))
            assert by_gaits.found, (robot.name, direction, legs)
            expected = tuple(by_gaits.to_json()["gaits"][0]["valves"])
            states, source = _primitive(tmp_path, robot, loaded, legs, direction, lint=k == 0)
            assert states == expected, (robot.name, direction, legs, source)
            checked += 1
    assert checked >= len(moving)


def test_a_model_without_stored_gaits_answers_the_clause(tmp_path: Path) -> None:
    """The issue's case: a robot file with a model and no stored gaits, whose clause found
    "no reset gait towards +x" in the kinematic graph."""
    text = (ROOT / "gaitc" / "examples" / "robots" / "radial8.yaml").read_text(encoding="utf-8")
    head, _, rest = text.partition("gaits:\n")
    rest = rest[rest.index("\nmodel:") + 1:]
    robot = tmp_path / "starfish.yaml"
    robot.write_text(head + rest, encoding="utf-8")
    loaded = load_robot(robot)
    assert not loaded.gaits and loaded.models == ("spring-damper",)
    states, source = _primitive(tmp_path, robot, loaded, ("L6", "L4"), "+x")
    assert source == "synthesised (spring-damper model, +x)"
    assert states == ("00000100", "00010000")
    found = gaitc.gaits(robot, gaitc.GaitOptions("+x", legs=("L6", "L4")))
    assert tuple(found.to_json()["gaits"][0]["valves"]) == states


def test_legs_that_cannot_move_that_way_are_told_which_do(tmp_path: Path) -> None:
    robot = ROOT / "gaitc" / "examples" / "robots" / "radial8.yaml"
    text = ('robot "r"\nlegs L1..L8 health 2\n'
            f'gait g uses L1, L2 moves a -> b, b -> a primitive "{robot}" direction +x\n'
            "region a, b\nstart a\nvisit b infinitely often\n")
    spec = gaitc.parse(text, name=str(tmp_path / "g.gait"))
    assert spec.model is not None
    message = ("gait g: no gait of legs L1, L2 moves towards +x in "
               f"{robot}'s spring-damper model; legs L6, L4 do")
    with pytest.raises(SpecSemanticError) as info:
        resolve_primitive(spec.model.gaits[0], str(tmp_path))
    assert info.value.message == message
    assert "let the gait use legs L6, L4" in (info.value.hint or "")
    errors = [d for d in gaitc.lint(spec) if d.severity == "error"]
    assert [d.message for d in errors] == [message]
    found = gaitc.gaits(robot, gaitc.GaitOptions("+x", legs=("L1", "L2")))
    assert not found.found
    assert found.hints == ("no gait of legs L1, L2 moves towards +x in the spring-damper "
                           "model; legs L6, L4 do",)


def test_legs_restrict_only_a_model(tmp_path: Path) -> None:
    symmetric = ROOT / "specs" / "robots" / "symmetric6.yaml"
    with pytest.raises(gaitc.UsageError, match="--legs restricts a chapter 4 model"):
        gaitc.gaits(symmetric, gaitc.GaitOptions("+x", legs=("L1",)))
    radial = ROOT / "specs" / "robots" / "radial8.yaml"
    with pytest.raises(gaitc.UsageError, match="robot radial8 has no leg L9"):
        gaitc.gaits(radial, gaitc.GaitOptions("+x", legs=("L1", "L9")))
