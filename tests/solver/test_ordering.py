"""The static variable order's placement of per-member variables, and the BDD manager's start.

gaitc/solver/ordering.py puts the environment's fair integers (a map's obstacle) above the
robot's integer position when the system's goals are over integers, and a variable that
belongs to one member of a mutex group (a lift's call button to its floor, an arbiter's
request to its grant) right below that member; a member many variables lean on, or a group
of two, moves nothing.  The verdicts under the
new order are compared with the explicit-state solver in tests/solver/test_vmcai_families.py.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from bench.families.amba import amba_text  # noqa: E402
from bench.families.gridworld import evasion_text, gridworld_text  # noqa: E402
from bench.families.vmcai import arbiter_text, lift_text  # noqa: E402
from gaitc.api.deciding import check  # noqa: E402
from gaitc.core.spec import parse  # noqa: E402
from gaitc.ir.manager import INITIAL_CACHE_SLOTS, manager  # noqa: E402
from gaitc.ir.spec import GR1Spec  # noqa: E402
from gaitc.solver.ordering import group_members, variable_order  # noqa: E402
from gaitc.solver.symbolic import Options  # noqa: E402


def _spec(text: str) -> GR1Spec:
    return parse(text, "order.structuredslugs").gr1


def _order(text: str) -> list[str]:
    return [v.name for v in variable_order(_spec(text), "guards")]


def test_a_lift_button_sits_below_its_floor() -> None:
    assert _order(lift_text(4)) == ["f0", "b0", "f1", "b1", "f2", "b2", "f3", "b3"]


def test_an_arbiter_request_sits_below_its_grant() -> None:
    assert _order(arbiter_text(12))[:6] == ["g0", "r0", "g1", "r1", "g2", "r2"]
    assert len(_order(arbiter_text(12))) == 24


def test_an_integer_obstacle_goes_above_the_robots_position() -> None:
    """The guard scores alone put the position first (every move clause is guarded by it);
    the obstacle that the environment's liveness brings home goes on top."""
    assert _order(gridworld_text(5)) == ["ox0", "oy0", "x", "y"]
    assert _order(gridworld_text(5, obstacles=2)) == ["ox0", "oy0", "ox1", "oy1", "x", "y"]
    # the evasion grid's moves stay where the guards put them, below the obstacle
    assert _order(evasion_text(8, 8)) == ["mox0", "moy0", "left", "right", "up", "down",
                                          "x", "y"]


def test_boolean_obstacles_and_boolean_goals_move_nothing() -> None:
    """A one-hot obstacle (a Boolean per cell) stays below the position; an integer that
    the environment must bring back is not lifted when the system's goals are Boolean."""
    names = _order(gridworld_text(5, encoding="onehot"))
    assert names[:2] == ["x", "y"]
    base = ("[INPUT]\nh:0...3\n[OUTPUT]\ng\nk:0...3\n[ENV_TRANS]\ng -> h' = h\n"
            "[SYS_TRANS]\ng -> k' = k\n[ENV_LIVENESS]\nh = 0\n[SYS_LIVENESS]\n")
    assert _order(base + "g\n") == ["g", "k", "h"]  # the guard scores' order
    assert _order(base + "k = 3\n") == ["h", "g", "k"]  # an integer goal: h goes on top


@pytest.mark.parametrize("text", [gridworld_text(5), evasion_text(8, 8)],
                         ids=["gridworld", "evasion"])
def test_the_lifted_order_keeps_the_verdict(text: str) -> None:
    """Both orders decide the map the same way (realizable: the boxes lie off the way)."""
    spec = _spec(text)
    lifted = check(spec, options=Options(reordering=False))
    declared = check(spec, options=Options(reordering=False, order="declaration"))
    assert lifted.realizable and declared.realizable


def test_a_group_of_two_keeps_its_partners_where_they_were() -> None:
    # two floors: the group is too small to tell a pairing from a coincidence
    assert _order(lift_text(2)) == ["f0", "f1", "b0", "b1"]


def test_a_hub_member_moves_nothing() -> None:
    """AMBA's hready, hburst and hmastlock all lean on ``start``; they stay where the guard
    scores put them, and so does every other variable."""
    names = _order(amba_text(4))
    assert ["start", "stateG2"] in group_members(_spec(amba_text(4)))
    assert names[names.index("start") + 1] == "stateG2"
    assert names.index("hready") < names.index("start")


def test_without_a_one_to_one_pairing_the_group_stays_whole() -> None:
    """One extra button tied to floor 0 as well makes floor 0 a member with two partners:
    the whole pairing is dropped, not just that member's."""
    text = lift_text(4).replace("[INPUT]\n", "[INPUT]\nextra\n").replace(
        "[ENV_TRANS]\n", "[ENV_TRANS]\n(extra & f0) -> extra'\n(extra & !f0) -> !extra'\n")
    names = _order(text)
    assert names[:4] == ["f0", "f1", "f2", "f3"]


@pytest.mark.parametrize("budget", [None, 64 << 20])
def test_a_new_manager_starts_small_with_reordering_off(budget: int | None) -> None:
    bdd = manager(budget)
    settings = bdd.configure()
    assert settings["reordering"] is False
    if budget is not None:
        assert settings["max_memory"] == budget
    bdd.declare("x", "y")
    assert bdd.add_expr("x & y") != bdd.false
    assert INITIAL_CACHE_SLOTS < 262_144
