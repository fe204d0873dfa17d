"""The sanity warnings of a realizable spec: vacuous goals and unused regions, gaits and
caches (:mod:`gaitc.analysis.sanity`).

The module stops its breadth-first search as soon as every goal is seen broken and every
region and gait seen reached; these tests find every reachable state first, with an image
written here (``exist`` then ``let``, not the module's ``and_exists``), and ask the same
questions of the whole set.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from packages import ROOT

import gaitc
from gaitc.analysis.sanity import unused_parts, vacuous_goals
from gaitc.solver.game import Game
from gaitc.solver.symbolic import BDDNode, SymbolicSpec
from ltlcompiler.encoding import make_encoding
from ltlcompiler.model import NO_GAIT

#: A 1 x 3 corridor with one gait per direction.  ``{goal}`` and ``{gaits}`` vary.
CORRIDOR = """\
legs L1..L2 health 3
{gaits}
grid 1 x 3 cells a, b, c
start a
visit b infinitely often
{goal}
"""
EAST = "gait east uses L1 moves east"
WEST = "gait west uses L2 moves west"


def _all_reachable(sym: SymbolicSpec, start: BDDNode, moves: BDDNode) -> BDDNode:
    """Every state reachable from ``start`` along ``moves``, the whole fixpoint."""
    pre = sym.pre_inputs | sym.pre_outputs
    rename = {p: b for b, p in sym.prime_map.items()}
    seen = start
    while True:
        successors = sym.bdd.let(rename, sym.bdd.exist(pre, seen & moves))
        if (successors & ~seen) == sym.bdd.false:
            return seen
        seen |= successors


def _reference(spec: gaitc.Spec) -> tuple[tuple[int, ...], dict[str, tuple[str, ...]]]:
    sym = SymbolicSpec(spec.gr1)
    moves = sym.env_trans & sym.sys_trans
    reach = _all_reachable(sym, sym.env_init & sym.sys_init, moves)
    steps = reach & moves
    vacuous = tuple(j for j, goal in enumerate(spec.gr1.sys_liveness)
                    if reach != sym.bdd.false
                    and (steps & ~sym.translate(goal.formula)) == sym.bdd.false)
    winning = Game(sym).solve().winning
    moves_in = moves & sym.prime(winning)
    reach_in = _all_reachable(sym, sym.env_init & sym.sys_init & winning, moves_in)
    assert spec.model is not None
    enc = make_encoding(spec.model, spec.robot_encoding)

    def never(states: BDDNode) -> bool:
        return bool((reach_in & states) == sym.bdd.false)

    regions = tuple(r.name for r in spec.model.regions
                    if never(sym.translate(enc.region(r.name))))
    gaits = tuple(g.name for g in spec.model.gaits
                  if g.name != NO_GAIT and never(sym.translate(enc.gait(g.name))))
    caches = tuple(c for c in spec.model.caches if c in regions)
    return vacuous, {"regions": regions, "gaits": gaits, "caches": caches}


def _found(spec: gaitc.Spec) -> tuple[tuple[int, ...], dict[str, tuple[str, ...]]]:
    assert spec.model is not None
    return (vacuous_goals(SymbolicSpec(spec.gr1)),
            unused_parts(SymbolicSpec(spec.gr1), spec.model, spec.robot_encoding))


SHIPPED = [p for p in sorted((ROOT / "specs").glob("*.gait"))
           if p.name not in {"radial12_patrol.gait", "centipede24_patrol.gait",
                             "unrealizable_2x2.gait", "thesis_robot_a_health2.gait"}]


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_the_early_stop_finds_what_the_whole_search_finds(path: Path) -> None:
    spec = gaitc.load(path)
    assert _found(spec) == _reference(spec)


@pytest.mark.parametrize(("gaits", "goal", "vacuous", "regions", "gait_names"), [
    # every goal asks something, every part is used
    (f"{EAST}\n{WEST}", "", (), (), ()),
    # a goal that holds wherever the robot is
    (f"{EAST}\n{WEST}", "guarantee always eventually (a | b | c)", (1,), (), ()),
    # without a gait west, a robot that walks on into c never sees b again: no winning
    # play enters c
    (EAST, "", (), ("c",), ()),
])
def test_small_corridors(tmp_path: Path, gaits: str, goal: str, vacuous: tuple[int, ...],
                         regions: tuple[str, ...], gait_names: tuple[str, ...]) -> None:
    path = tmp_path / "corridor.gait"
    path.write_text(CORRIDOR.format(gaits=gaits, goal=goal), encoding="utf-8")
    spec = gaitc.load(path)
    found = _found(spec)
    assert found == _reference(spec)
    assert found[0] == vacuous
    assert found[1]["regions"] == regions and found[1]["gaits"] == gait_names


def test_the_warnings_name_them(tmp_path: Path) -> None:
    path = tmp_path / "corridor.gait"
    path.write_text(CORRIDOR.format(gaits=f"{EAST}\n{WEST}",
                                    goal="guarantee always eventually (a | b | c)"),
                    encoding="utf-8")
    codes = [w.code for w in gaitc.explain(path, repairs=False).warnings]
    assert "vacuous-goal" in codes
