"""The chapter 5 online loop (gaitc.search.online) on the simulated walker, and the CLI."""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from gaitc.cli import main
from gaitc.search import Mismatch, Settings, learn_gait, plan_gait
from gaitc.search.goals import Goal
from gaitc.search.online import NoGaitError, learn
from gaitc.search.planners import HybridPlanner, TreePlanner
from gaitc.search.transitions import TransitionModel
from gaitc.search.walker import SimulatedWalker

ROBOT = str(Path(__file__).resolve().parents[2] / "specs" / "robots" / "symmetric6.yaml")
FINE = Settings(cell=1.0, cell_angle=1.0)

# pose 0 is the start; the planner believes 0 -> 1 -> 0 walks 30 mm, but the real robot
# only makes 20 of them; 0 -> 2 -> 3 -> 0 (30 mm in three steps) is what really works
EDGES = [
    (0, 1, 15.0, 0.0),
    (1, 0, 15.0, 0.0),
    (0, 2, 10.0, 0.0),
    (2, 3, 10.0, 0.0),
    (3, 0, 10.0, 0.0),
]


def toy() -> TransitionModel:
    src, dst, dx, dy = (np.array(c) for c in zip(*EDGES, strict=True))
    z = np.zeros(len(EDGES))
    return TransitionModel(4, src, dst, dx, dy, z, z, labels=["000", "100", "010", "001"])


@pytest.mark.parametrize("method", ["astar", "lpa", "mcts"])
def test_the_loop_drops_the_gait_the_robot_cannot_make(method: str) -> None:
    model = toy()
    goal = Goal(30.0, 0.0, 0.0, 2.0, 2.0)
    walker = SimulatedWalker(model.copy(), 0, 3, ("L1", "L2", "L3"), Mismatch(0.0, 0.0))
    for a, b in ((0, 1), (1, 0)):  # 0 -> 1 -> 0 really walks 20 mm
        walker.true_dx[model.find(a, b)] = 10.0
    settings = Settings(cell=1.0, cell_angle=1.0, horizon=4, iterations=200)
    planner = (
        TreePlanner(model, "toy", 0, goal, settings)
        if method == "mcts"
        else HybridPlanner(model, "toy", 0, goal, settings, method)
    )
    result = learn(planner, walker, verify=3)
    assert len(result.iterations[0].edges) == 2  # the predicted short cut
    assert result.converged and result.final is not None
    assert [(int(model.src[e]), int(model.dst[e])) for e in result.final.edges] == [
        (0, 2),
        (2, 3),
        (3, 0),
    ]
    assert result.executed is not None and math.isclose(result.executed[0], 30.0)
    assert result.iterations[0].changed == 2


@pytest.mark.parametrize("method", ["lpa", "mcts"])
def test_learning_on_the_mismatched_symmetric_robot_converges(method: str) -> None:
    # stated tolerance: the goal's 5 mm, plus 3 mm for lattice snapping and 0.2 mm noise
    result = learn_gait(ROBOT, "40,0", method, Mismatch(0.2, 0.2, 0.0, 2), FINE)
    assert result.converged
    assert result.error is not None and result.error[0] <= 8.0 and result.error[1] <= 5.0
    assert result.final is not None
    assert all(len(it.edges) == it.completed for it in result.iterations)


def test_learning_survives_transitions_the_robot_cannot_make() -> None:
    result = learn_gait(ROBOT, "40,0", "lpa", Mismatch(0.1, 0.1, 0.1, 3))
    assert sum(it.failed is not None for it in result.iterations) == 3
    assert all(it.executed is None for it in result.iterations if it.failed is not None)
    assert result.converged and result.error is not None


def test_the_log_is_the_same_bytes_for_the_same_seed() -> None:
    a = learn_gait(ROBOT, "40,0", "mcts", Mismatch(0.2, 0.2, 0.0, 2))
    b = learn_gait(ROBOT, "40,0", "mcts", Mismatch(0.2, 0.2, 0.0, 2))
    assert a.to_json() == b.to_json()
    log = json.loads(a.to_json())
    assert log["iterations"][0]["index"] == 1 and log["converged"] == a.converged


def test_plans_display_themselves() -> None:
    plan = plan_gait(ROBOT, "40,0", "astar")
    assert plan is not None and plan.reached
    text = repr(plan)
    assert text.startswith("astar gait for symmetric6: goal (40 mm, 0 mm, 0 deg)")
    assert "per cycle:" in text.splitlines()[-1]
    svg = ET.fromstring(plan._repr_svg_())
    assert svg.tag.endswith("svg") and len(svg) > len(plan.steps)
    doc = json.loads(plan.to_json())
    assert doc["valves"][0] == "0" * 24 and len(doc["transitions"]) == len(plan.steps)


def test_cli_gaits_lpa_and_learn(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "plan.json"
    assert main(["gaits", ROBOT, "--method", "lpa", "--goal", "40,0", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert text.startswith(
        "robot symmetric6: 24 chambers, kinematic gait graph, method lpa, 100 valve states")
    assert json.loads(out.read_text())["method"] == "lpa"
    log, svg = tmp_path / "log.json", tmp_path / "run.svg"
    code = main(
        [
            "learn",
            ROBOT,
            "--goal",
            "40,0",
            "--method",
            "mcts",
            "--seed",
            "2",
            "--log",
            str(log),
            "--svg",
            str(svg),
        ]
    )
    text = capsys.readouterr().out
    assert code == 0, text
    assert text.splitlines()[0].startswith("iteration 1: ")
    assert "converged" in text
    assert json.loads(log.read_text())["converged"] is True
    ET.fromstring(svg.read_text())


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (
            ["gaits", ROBOT, "--method", "lpa"],
            "--method lpa needs --goal DX,DY[,DTHETA] (mm, degrees)",
        ),
        (
            ["gaits", ROBOT, "--method", "astar", "--goal", "40"],
            "--goal: expected 2 to 3 comma-separated numbers, got '40'",
        ),
        (
            ["gaits", ROBOT, "--method", "astar", "--goal", "40,y"],
            "--goal: 'y' is not a number (in '40,y')",
        ),
        (
            ["gaits", ROBOT, "--method", "mcts", "--goal", "40,0,200"],
            "--goal: the rotation 200 deg must lie strictly between -180 and 180",
        ),
        (
            ["gaits", ROBOT, "--method", "lpa", "--goal", "1,1"],
            "--goal (1 mm, 1 mm, 0 deg) is within the tolerance of standing still; a gait must "
            "move",
        ),
        (
            ["gaits", ROBOT, "--goal", "40,0"],
            "--goal is for --method astar, lpa, dstar or mcts; the chapter 2 search (--method "
            "chapter2) takes --direction",
        ),
        (
            ["gaits", ROBOT, "--method", "lpa", "--goal", "40,0", "--cell", "2,7"],
            "--cell: the angle 7 deg must divide 360",
        ),
        (
            ["gaits", ROBOT, "--method", "lpa", "--goal", "40,0", "--tolerance", "-1"],
            "--tolerance: must be positive, got '-1'",
        ),
        (
            ["learn", ROBOT, "--goal", "40,0", "--method", "bfs"],
            "argument --method: invalid choice: 'bfs' (choose from 'astar', 'lpa', 'dstar', "
            "'mcts')",
        ),
        (
            ["learn", ROBOT, "--goal", "40,0", "--backend", "serial"],
            "--backend serial is not available for learning: the valve board reports no "
            "displacement of a transition (the chapter 4 EKF is not in gaitc); use --backend "
            "sim or physics",
        ),
        (
            ["learn", ROBOT, "--goal", "40,0", "--backend", "usb"],
            "unknown backend 'usb'; use sim or physics",
        ),
        (
            ["learn", ROBOT, "--goal", "40,0", "--infeasible", "1"],
            "--mismatch and --noise must not be negative, --infeasible must lie in [0, 1)",
        ),
    ],
)
def test_bad_input_is_a_usage_error(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err == f"gaitc: usage error: {message}\n"


def test_an_exhausted_budget_is_a_solver_error(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["gaits", ROBOT, "--method", "astar", "--goal", "400,0", "--budget", "5"])
    assert code == 4
    err = capsys.readouterr().err
    assert ("no gait for goal (400 mm, 0 mm, 0 deg) within 5 node expansions per search and "
            "10 in all, over 1000 valve states (astar)") in err
    assert "Traceback" not in err


def test_the_loop_says_why_it_stopped() -> None:
    model = toy()
    goal = Goal(30.0, 0.0, 0.0, 2.0, 2.0)
    walker = SimulatedWalker(model.copy(), 0, 3, ("L1", "L2", "L3"), Mismatch(0.0, 0.0))
    for a, b in ((0, 1), (1, 0)):
        walker.true_dx[model.find(a, b)] = 10.0
    planner = HybridPlanner(model, "toy", 0, goal, Settings(cell=1.0, cell_angle=1.0))
    result = learn(planner, walker, max_iterations=1)
    assert not result.converged and result.stopped == "iteration limit"
    assert result.summary().startswith("lpa: did not converge (iteration limit) after 1 iter")
    assert json.loads(result.to_json())["stopped"] == "iteration limit"


def test_learning_without_a_first_gait_is_an_error() -> None:
    model = toy()
    goal = Goal(0.0, 30.0, 0.0, 2.0, 2.0)  # every cycle of the toy graph walks along x
    walker = SimulatedWalker(model.copy(), 0, 3, ("L1", "L2", "L3"), Mismatch(0.0, 0.0))
    planner = HybridPlanner(model, "toy", 0, goal, Settings(cell=1.0, cell_angle=1.0))
    with pytest.raises(NoGaitError, match=r"no gait for goal \(0 mm, 30 mm, 0 deg\)"):
        learn(planner, walker)


def test_the_chapter_2_search_is_the_default_and_unchanged(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["gaits", ROBOT]) == 0
    default = capsys.readouterr().out
    assert main(["gaits", ROBOT, "--method", "chapter2"]) == 0
    assert capsys.readouterr().out == default
    assert default.startswith("robot symmetric6: 24 chambers, method random, 100 valve states")
