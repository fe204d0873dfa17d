"""The gait tools called the way a user calls them (issue 36): the robot file's model is
searched by default, a graph that cannot move the robot is said at once with its reason, the
lattice searches meet the goal's tolerance, and what they answer is re-checked here from the
transitions themselves (not trusted)."""

from __future__ import annotations

import itertools
import json
import math
import time
from pathlib import Path

import networkx as nx
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import gaitc
from gaitc.cli import main
from gaitc.gaitgraph.displacement import stillness
from gaitc.gaitgraph.robot import load_robot
from gaitc.search.goals import Goal
from gaitc.search.transitions import Step, compose

ROBOTS = Path(__file__).parents[2] / "specs" / "robots"
RADIAL8, SILICONE6 = str(ROBOTS / "radial8.yaml"), str(ROBOTS / "silicone6.yaml")
ASYMMETRIC6 = str(ROBOTS / "asymmetric6.yaml")
UNIT = {"+x": (1.0, 0.0), "-x": (-1.0, 0.0), "+y": (0.0, 1.0), "-y": (0.0, -1.0)}


def test_robot_files_name_their_models() -> None:
    assert load_robot(RADIAL8).models == ("spring-damper",)
    assert load_robot(SILICONE6).models == ("active-passive",)
    assert load_robot(ASYMMETRIC6).models == ()


#: silicone6 cannot walk sideways: its best cycle towards ±y goes 61 degrees off (6.2 mm
#: along x for 3.4 mm along y), so no gait is offered there (issue 60)
SIDEWAYS = {(SILICONE6, "+y"), (SILICONE6, "-y")}


@pytest.mark.parametrize("robot", [RADIAL8, SILICONE6])
@pytest.mark.parametrize("direction", sorted(UNIT))
def test_the_robot_files_model_is_searched_by_default(robot: str, direction: str) -> None:
    found = gaitc.gaits(robot, gaitc.GaitOptions(direction))
    if (robot, direction) in SIDEWAYS:
        assert not found.found
        assert found.hints == (
            f"no cycle of the active-passive model's 42 simulated transitions goes within 30 "
            f"degrees of {direction}; more open valves (--max-open) give the search more "
            "valve states",)
        return
    assert found.found, str(found)
    doc = found.to_json()
    assert doc["model"] == load_robot(robot).models[0]
    # the best gait's displacement, recomposed from its transitions, goes the way asked
    first = doc["gaits"][0]
    x = y = heading = 0.0
    for t in first["transitions"]:
        x, y, heading = compose(x, y, heading, Step(t["dx"], t["dy"], t["rotation"]))
    ux, uy = UNIT[direction]
    along, lateral = x * ux + y * uy, -x * uy + y * ux
    assert along > 2.0
    assert math.degrees(math.atan2(abs(lateral), along)) <= 30.0  # the way the map means
    assert (x, y) == pytest.approx(tuple(first["displacement"]), abs=0.01)


def test_kinematic_is_asked_for_by_name_and_the_reason_names_the_model(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["gaits", RADIAL8, "--model", "kinematic", "--direction", "+x"]) == 1
    captured = capsys.readouterr()
    assert "no gait towards +x found" in captured.out
    assert ("no cycle of the kinematic gait graph's 7768 transitions goes within 30 degrees "
            "of +x; drop --model kinematic to search the robot file's spring-damper model"
            ) in captured.err


def test_a_global_search_on_a_motionless_graph_is_answered_without_searching(
    capsys: pytest.CaptureFixture[str],
) -> None:
    began = time.perf_counter()
    code = main(["gaits", RADIAL8, "--model", "kinematic", "--method", "mcts", "--goal", "0,40"])
    seconds = time.perf_counter() - began
    out = capsys.readouterr().out
    assert code == 1
    assert ("robot radial8: no gait toward (0 mm, 40 mm, 0 deg) found (kinematic): no cycle "
            "of the kinematic gait graph through the rest pose moves the chassis") in out
    assert seconds < 60  # the graph is built, but no search runs (15 s of MCTS before)


def test_mcts_searches_the_model_by_default() -> None:
    found = gaitc.gaits(RADIAL8, gaitc.GaitOptions(method="mcts",
                                                   search=gaitc.GlobalSearch(goal="0,40")))
    assert found.found, str(found)
    doc = found.to_json()
    assert doc["model"] == "spring-damper" and doc["reached"]


def test_reset_on_a_model_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["gaits", RADIAL8, "--method", "reset"]) == 2
    assert "add --model kinematic" in capsys.readouterr().err


@pytest.mark.parametrize("method", ["astar", "lpa", "mcts"])
@pytest.mark.parametrize("goal", ["60,0", "42.4,42.4", "0,60"])
def test_global_searches_meet_the_default_tolerance(method: str, goal: str) -> None:
    found = gaitc.gaits(ASYMMETRIC6, gaitc.GaitOptions(
        method=method, search=gaitc.GlobalSearch(goal=goal)))
    assert found.found, str(found)
    plan = found.plan  # type: ignore[union-attr]
    assert plan is not None
    # recompose the cycle from the steps it reports: it must close at the goal
    x = y = heading = 0.0
    for step in plan.steps:
        x, y, heading = compose(x, y, heading, Step(step.dx, step.dy, step.rotation))
    dx, dy = (float(v) for v in goal.split(","))
    assert Goal(dx, dy).reached(x, y, heading)
    assert plan.steps[-1].valves == plan.start_valves


def test_a_budget_too_small_for_every_batch_reports_the_whole_search(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["gaits", ASYMMETRIC6, "--method", "astar", "--goal", "0,60",
                 "--budget", "20", "--max-states", "300"]) == 4
    assert ("no gait for goal (0 mm, 60 mm, 0 deg) within 20 node expansions per search and "
            "30 in all, over 300 valve states (astar)") in capsys.readouterr().err


# -- the motion check, against brute force -------------------------------------------------

Edge = tuple[int, int, float, float, float]


def _cycles_move(poses: int, edges: list[Edge]) -> set[int]:
    """Poses on a simple cycle whose composed motion is not the identity (brute force)."""
    g = nx.DiGraph()
    g.add_nodes_from(range(poses))
    motion = {}
    for a, b, dx, dy, rot in edges:
        g.add_edge(a, b)
        motion[(a, b)] = Step(dx, dy, rot)
    out: set[int] = set()
    for cycle in nx.simple_cycles(g):
        x = y = h = 0.0
        for a, b in itertools.pairwise([*cycle, cycle[0]]):
            x, y, h = compose(x, y, h, motion[(a, b)])
        if math.hypot(x, y) > 0.05 or abs((h + 180.0) % 360.0 - 180.0) > 0.05:
            out.update(cycle)
    return out


def _still(poses: int, edges: list[Edge]) -> frozenset[int]:
    cols = list(zip(*edges, strict=True)) if edges else [(), (), (), (), ()]
    return stillness(poses, *cols).moving_poses


_motions = st.tuples(st.sampled_from([0.0, 3.0, -2.0]), st.sampled_from([0.0, 1.5]),
                     st.sampled_from([0.0, 0.0, 30.0]))


@settings(max_examples=60, deadline=None)
@given(st.integers(2, 5), st.data())
def test_stillness_agrees_with_every_simple_cycle(poses: int, data: st.DataObject) -> None:
    pairs = data.draw(st.lists(st.tuples(st.integers(0, poses - 1), st.integers(0, poses - 1))
                               .filter(lambda p: p[0] != p[1]), unique=True, max_size=10))
    edges = [(a, b, *data.draw(_motions)) for a, b in pairs]
    moving = _still(poses, edges)
    brute = _cycles_move(poses, edges)
    # a moving cycle's poses are all in the moving components; a still component has none
    assert brute <= moving
    assert bool(brute) == bool(moving)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(-50, 50), st.floats(-50, 50), st.floats(-90, 90)),
                min_size=2, max_size=6), st.data())
def test_motions_between_placements_never_move(places: list[tuple[float, float, float]],
                                               data: st.DataObject) -> None:
    """Edges that take one placement to another compose to the identity around any cycle."""
    n = len(places)
    pairs = data.draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1))
                               .filter(lambda p: p[0] != p[1]), unique=True, max_size=12))
    edges = []
    for a, b in pairs:
        (xa, ya, ha), (xb, yb, hb) = places[a], places[b]
        c, s = math.cos(math.radians(ha)), math.sin(math.radians(ha))
        dx, dy = xb - xa, yb - ya
        edges.append((a, b, c * dx + s * dy, -s * dx + c * dy, hb - ha))
    assert _still(n, edges) == frozenset()


def test_json_of_a_global_search_names_the_graph(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["gaits", RADIAL8, "--method", "lpa", "--goal", "40,0", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["model"] == "spring-damper" and doc["reason"] is None and doc["reached"]
