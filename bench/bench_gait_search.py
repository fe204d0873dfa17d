"""Benchmark of the chapter 5 gait searches (issue 16): time to a first gait, per edge update.

For the symmetric and asymmetric six-leg robots (24 chambers; 100 and 1,000 random valve
states plus the vented one) and the symmetric robot with 10,000 valve states: the chapter 2
search (Algorithm 1 toward the goal's direction) and A*, LPA*, D* Lite, MCTS toward the goal.  An
edge update is what the online loop does, one transition at a time: a transition of the
current gait not updated before gets its true motion on the simulated robot (20 % model
mismatch, seeded; no noise), then the gait is re-planned: A* from scratch, LPA* and D* Lite
by repair (D* Lite from the cycle's start, as the loop's plan at the start of a cycle),
MCTS by pruning and one rollout per pruned branch's parent.  The updates stop early when
every transition of the gait has been updated (the loop has converged).  Target: an LPA*
update under 10 ms (the thesis, 5.2.3: about 15 minutes).  Times are CPU time of this process
(``time.process_time``), so that other jobs on a shared machine count less.
The robot files that declare a chapter 4 model (radial8: spring-damper; silicone6:
active-passive) are searched on that model's gait graph (case ``radial8:model``), which is
what ``gaitc gaits`` and ``gaitc learn`` use for them by default (issue 36).
Run: ``.venv/bin/python bench/bench_gait_search.py [--quick] [--updates N] [--methods
lpa,dstar] [--cases asymmetric6:100,radial8:model]``.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gaitc.gaitgraph.cycles import synthesize
from gaitc.gaitgraph.graph import GaitGraph, random_states
from gaitc.gaitgraph.robot import load_robot
from gaitc.search.goal_search import start_pose
from gaitc.search.goals import Goal
from gaitc.search.planners import SearchLimitError, Settings
from gaitc.search.plans import GaitPlan
from gaitc.search.predictions import model_transitions
from gaitc.search.registry import goal_search
from gaitc.search.transitions import TransitionModel
from gaitc.search.walker import Mismatch, SimulatedWalker

ROBOTS = Path(__file__).resolve().parent.parent / "specs" / "robots"
GOAL = Goal(40.0, 0.0)
HEAD = (
    f"{'robot':<12} {'states':>6} {'poses':>6} {'edges':>8} {'method':<8} {'first s':>8} "
    f"{'work':>7} {'trans':>5} {'dx mm':>7} {'dy mm':>7} {'rot':>6} {'upd med ms':>10} "
    f"{'upd max ms':>10} {'upds':>4}"
)


def build(name: str, states: int) -> tuple[GaitGraph, float]:
    robot = load_robot(ROBOTS / f"{name}.yaml")
    graph = GaitGraph(robot)
    began = time.process_time()
    graph.add_states([0, *random_states(robot, np.random.default_rng(0), states - 1, {0})])
    return graph, time.process_time() - began


@dataclass(frozen=True)
class Case:
    """A searchable graph: its transitions, the rest pose and the sizes for the table."""

    robot: str
    model: TransitionModel
    start: int
    states: int
    poses: int


def kinematic_case(graph: GaitGraph) -> Case:
    return Case(graph.robot.name, TransitionModel.from_graph(graph), start_pose(graph),
                len(graph.states), len(graph))


def model_case(name: str) -> tuple[Case, float]:
    """The gait graph of the robot file's declared model (valve states with one open)."""
    began = time.process_time()
    found = model_transitions(ROBOTS / f"{name}.yaml")
    model = found.model
    case = Case(found.loaded.robot, model, found.start, model.poses, model.poses)
    return case, time.process_time() - began


def row(
    graph: Case,
    method: str,
    first: float,
    work: int,
    plan: tuple[int, float, float, float] | None,
    updates: list[float],
) -> str:
    size = f"{graph.robot:<12} {graph.states:>6} {graph.poses:>6} {len(graph.model):>8}"
    if plan is None:
        return f"{size} {method:<8} {first:8.2f} {work:>7}  no gait"
    n, x, y, th = plan
    upd = (
        f"{statistics.median(updates) * 1000:10.1f} {max(updates) * 1000:10.1f}"
        if updates
        else f"{'-':>10} {'-':>10}"
    )
    return f"{size} {method:<8} {first:8.3f} {work:>7} {n:>5} {x:7.1f} {y:7.1f} {th:6.1f} {upd}"


def chapter2(graph: GaitGraph) -> str:
    began = time.process_time()
    direction = (GOAL.dx / math.hypot(GOAL.dx, GOAL.dy), GOAL.dy / math.hypot(GOAL.dx, GOAL.dy))
    gaits = synthesize(graph, direction)
    seconds = time.process_time() - began
    if not gaits:
        return row(graph, "chapter2", seconds, 0, None, [])
    g = gaits[0]
    plan = (len(g.poses), g.displacement[0], g.displacement[1], g.rotation)
    return row(kinematic_case(graph), "chapter2", seconds, len(gaits), plan, [])


def chapter5(graph: Case, method: str, updates: int) -> str:
    model = graph.model.copy()
    settings = Settings(budget=400_000)
    planner = goal_search(method).planner(model, graph.robot, graph.start, GOAL, settings)
    began = time.process_time()
    try:
        plan = planner.plan(explored=False)
    except SearchLimitError:
        return f"{graph.robot:<12} {method:<8} spent {settings.budget} expansions"
    first = time.process_time() - began
    if plan is None:
        return row(graph, method, first, planner.expanded, None, [])
    summary = (len(plan.steps), *plan.displacement)
    work = planner.expanded
    rng = np.random.default_rng(7)
    truth = SimulatedWalker(model.copy(), graph.start, 1, (), Mismatch(0.2, 0.0, 0.0, 7))
    times: list[float] = []
    done: set[int] = set()
    current: GaitPlan | None = plan
    for _ in range(updates):
        todo = [] if current is None else [e for e in current.edges if e not in done]
        if not todo:
            break
        edge = todo[int(rng.integers(len(todo)))]
        done.add(edge)
        began = time.process_time()
        planner.observe(edge, truth.true_step(edge), True)
        try:
            current = planner.plan(explored=False)
        except SearchLimitError:
            tail = f" {len(times):>4} (update {len(times) + 1} spent {settings.budget} expansions)"
            return row(graph, method, first, work, summary, times) + tail
        times.append(time.process_time() - began)
    return row(graph, method, first, work, summary, times) + f" {len(times):>4}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the 10,000-state graph")
    parser.add_argument("--updates", type=int, default=20, help="edge updates per method at most")
    parser.add_argument(
        "--methods",
        default="chapter2,astar,lpa,mcts",
        help="comma-separated methods (dstar too; slow beyond the 100-state graphs)",
    )
    parser.add_argument("--cases", help="comma-separated ROBOT:STATES, e.g. asymmetric6:100")
    args = parser.parse_args()
    cases: list[tuple[str, str]] = [
        ("symmetric6", "100"), ("asymmetric6", "100"), ("symmetric6", "1000"),
        ("asymmetric6", "1000"), ("radial8", "model"), ("silicone6", "model")]
    if not args.quick:
        cases.append(("symmetric6", "10000"))
    if args.cases:
        cases = [(c.split(":")[0], c.split(":")[1]) for c in args.cases.split(",")]
    methods = args.methods.split(",")
    print(
        f"goal {GOAL} within {GOAL.tolerance:g} mm, {GOAL.angle_tolerance:g} deg; cells 2 mm, "
        f"2 deg; at most {args.updates} edge updates per method (upds: how many); CPU times"
    )
    print("work: lattice expansions (A*, LPA*, D* Lite), MCTS iterations, chapter 2: gaits ranked")
    print(HEAD)
    for name, states in cases:
        if states == "model":
            case, seconds = model_case(name)
            print(f"# {name}, its declared model's gait graph: built in {seconds:.1f} s",
                  flush=True)
        else:
            graph, seconds = build(name, int(states))
            case = kinematic_case(graph)
            print(f"# {name}, {states} valve states: gait graph built in {seconds:.1f} s",
                  flush=True)
            if "chapter2" in methods:
                print(chapter2(graph), flush=True)
        for method in ("astar", "lpa", "dstar", "mcts"):
            if method in methods:
                print(chapter5(case, method, args.updates), flush=True)
    print("target: LPA* edge update < 10 ms (thesis 5.2.3: about 15 minutes)")


if __name__ == "__main__":
    main()
