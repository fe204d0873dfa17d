"""``gaitc gaits --method astar|lpa|dstar|mcts`` and ``gaitc learn``: gait synthesis in the global
frame and its online refinement (thesis chapter 5), over :mod:`gaitc.search`."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gaitc.cli.commands.arguments import output_file
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.diagnostics import UsageError
from gaitc.diagnostics.files import write_atomically

if TYPE_CHECKING:
    from gaitc.search.plans import GaitPlan

BACKENDS = ("sim", "physics", "serial")


def goal_arguments(p: argparse.ArgumentParser) -> None:
    """The goal and the chapter 5 search options (shared by ``gaits`` and ``learn``)."""
    p.add_argument(
        "--goal",
        metavar="DX,DY[,DTHETA]",
        help="displacement per cycle in mm and degrees (astar, lpa, dstar, mcts)",
    )
    p.add_argument(
        "--tolerance",
        metavar="MM[,DEG]",
        help="how close to the goal counts as reached (5 mm, 5 deg)",
    )
    p.add_argument("--cell", metavar="MM[,DEG]", help="lattice cell of astar/lpa (2 mm, 2 deg)")
    p.add_argument(
        "--budget",
        type=int,
        default=200_000,
        metavar="N",
        help="node expansions per astar/lpa search (200000)",
    )
    p.add_argument(
        "--iterations", type=int, default=2000, metavar="N", help="MCTS iterations (2000)"
    )
    p.add_argument(
        "--horizon",
        type=int,
        default=12,
        metavar="N",
        help="MCTS: longest cycle in transitions (12)",
    )


def register(sub: Any) -> None:
    p = sub.add_parser(
        "learn",
        help="learn a gait toward a displacement on a robot, refining the model online",
        description="Synthesize a gait for ROBOT.yaml toward --goal (thesis chapter 5), run it on "
        "the backend, feed the measured displacement of every transition back into the search "
        "(LPA* repairs, MCTS prunes) and repeat until every transition of the gait has been "
        "executed (Algorithms 2 and 3).",
        epilog=exit_code_help(
            {
                ExitCode.OK: "the loop converged: every transition of the gait was executed",
                ExitCode.USER: "the robot file is wrong, the graph has no first gait, or the "
                "loop did not converge (no gait left, a later search spent its budget, the "
                "iteration limit)",
                ExitCode.SOLVER: "the first search spent --budget node expansions",
            },
            codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE, ExitCode.SOLVER),
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("robot", metavar="ROBOT.yaml")
    p.add_argument(
        "--method", default="lpa", metavar="astar|lpa|dstar|mcts", help="the search (default lpa)"
    )
    p.add_argument(
        "--backend",
        default="sim",
        metavar="sim|physics|serial",
        help="sim: the simulated robot with --mismatch and --noise; physics: the robot "
        "file's spring-damper model (chapter 4), with --noise on each measurement",
    )
    p.add_argument(
        "--predictions",
        metavar="kinematic|model",
        help="where the search's predicted motions come from: the chapter 4 model's gait "
        "graph (the default when the robot file has a model) or the chapter 2 graph",
    )
    p.add_argument(
        "--max-open",
        type=int,
        default=1,
        metavar="N",
        help="model predictions: valve states with at most N valves open (1)",
    )
    p.add_argument("--seed", type=int, default=0, help="seed of the graph, MCTS and the robot")
    p.add_argument("--max-states", type=int, default=10_000, help="valve states to try at most")
    p.add_argument(
        "--mismatch",
        type=float,
        default=0.2,
        metavar="F",
        help="sim: relative error of the true transitions (0.2)",
    )
    p.add_argument(
        "--noise",
        type=float,
        default=0.2,
        metavar="SD",
        help="sim: per-execution noise, mm and deg (0.2)",
    )
    p.add_argument(
        "--model-mismatch",
        type=float,
        default=0.0,
        metavar="F",
        help="physics: execute with each limb's stiffness and friction scaled by seeded "
        "factors in [1-F, 1+F] (0)",
    )
    p.add_argument(
        "--infeasible",
        type=float,
        default=0.0,
        metavar="P",
        help="sim: share of transitions the robot cannot make (0)",
    )
    p.add_argument(
        "--grow",
        action="store_true",
        help="sim, kinematic predictions: when removals leave no gait, add the next 100 "
        "random valve states (up to --max-states) instead of stopping",
    )
    p.add_argument("--max-iterations", type=int, default=40, metavar="N")
    p.add_argument(
        "--verify",
        type=int,
        default=5,
        metavar="N",
        help="cycles the learned gait is run at the end (5)",
    )
    p.add_argument("--log", metavar="FILE.json", type=output_file,
                   help="write every iteration as JSON")
    p.add_argument("--svg", metavar="FILE.svg", help="draw the search and the runs")
    p.add_argument("--quiet", action="store_true", help="print only the summary")
    goal_arguments(p)
    p.set_defaults(run=run_learn)


def _pair(text: str, option: str, default_angle: float) -> tuple[float, float]:
    from gaitc.search.goals import numbers

    values = numbers(text, option, 1, 2)
    if any(v <= 0 for v in values):
        raise UsageError(f"{option}: must be positive, got {text!r}")
    return values[0], values[1] if len(values) == 2 else default_angle


def settings_of(args: argparse.Namespace) -> Any:
    from gaitc.search.planners import Settings

    for name in ("budget", "iterations", "horizon", "max_states"):
        if getattr(args, name) < 1:
            raise UsageError(f"--{name.replace('_', '-')} must be at least 1")
    cell, angle = _pair(args.cell, "--cell", 2.0) if args.cell else (2.0, 2.0)
    if abs(360.0 / angle - round(360.0 / angle)) > 1e-9:
        raise UsageError(f"--cell: the angle {angle:g} deg must divide 360")
    return Settings(
        cell,
        angle,
        budget=args.budget,
        iterations=args.iterations,
        horizon=args.horizon,
        seed=args.seed,
    )


def goal_of(args: argparse.Namespace) -> Any:
    from gaitc.search.goals import parse_goal

    if args.goal is None:
        raise UsageError(f"--method {args.method} needs --goal DX,DY[,DTHETA] (mm, degrees)")
    return parse_goal(args.goal, args.tolerance)


def run_global(args: argparse.Namespace) -> int:
    """``gaitc gaits --method astar|lpa|dstar|mcts``: one gait toward ``--goal``."""
    from gaitc.gaitgraph.robot import load_robot
    from gaitc.search.api import plan_gait

    goal, settings = goal_of(args), settings_of(args)
    robot = load_robot(args.robot)
    plan = plan_gait(robot, goal, args.method, settings, args.max_states)
    if getattr(args, "json", False):
        return _plan_json(args, robot.name, plan)
    if plan is None:
        print(f"robot {robot.name}: no gait toward {goal} found")
        return 1
    states, poses, edges = plan.graph
    print(
        f"robot {robot.name}: {robot.valve_count} chambers, method {args.method}, "
        f"{states} valve states, {poses} poses, {edges} transitions"
    )
    print(plan.table())
    if not plan.reached and args.method == "mcts":
        print(
            f"the best cycle found misses the goal's tolerance ({goal.tolerance:g} mm, "
            f"{goal.angle_tolerance:g} deg); more --iterations or a longer --horizon may help"
        )
    elif not plan.reached:
        print(
            f"the route reaches the goal's cells, but its continuous displacement misses the "
            f"tolerance ({goal.tolerance:g} mm, {goal.angle_tolerance:g} deg): every "
            "transition is propagated from a cell centre; a finer --cell helps"
        )
    if args.output:
        write_atomically(args.output, plan.to_json())
    if args.svg:
        Path(args.svg).mkdir(parents=True, exist_ok=True)
        path = Path(args.svg) / "gait-search.svg"
        write_atomically(str(path), plan._repr_svg_())
        print(f"wrote {path}")
    return 0 if plan.reached else 1


def _plan_json(args: argparse.Namespace, robot: str, plan: GaitPlan | None) -> int:
    """``gaits --method astar|lpa|dstar|mcts --json``: the same files, the plan as one object."""
    from gaitc.cli.reporting import document, print_json

    written = []
    if plan is not None and args.output:
        write_atomically(args.output, plan.to_json())
        written.append(args.output)
    if plan is not None and args.svg:
        Path(args.svg).mkdir(parents=True, exist_ok=True)
        path = Path(args.svg) / "gait-search.svg"
        write_atomically(str(path), plan._repr_svg_())
        written.append(str(path))
    states, poses, edges = plan.graph if plan is not None else (None, None, None)
    print_json(document("gaits", {
        "robot": robot, "method": args.method, "found": plan is not None,
        "reached": plan is not None and plan.reached, "valve_states": states, "poses": poses,
        "transitions": edges, "plan": None if plan is None else plan.to_dict(),
        "written": written}))
    return 0 if plan is not None and plan.reached else 1


def run_learn(args: argparse.Namespace) -> int:
    from gaitc.search.api import check_method
    from gaitc.search.online import learn_gait
    from gaitc.search.walker import Mismatch

    check_method(args.method)
    if args.backend not in BACKENDS:
        raise UsageError(f"unknown backend {args.backend!r}; use sim or physics")
    if args.backend == "serial":
        raise UsageError(
            "--backend serial is not available for learning: the valve board reports no "
            "displacement of a transition (the chapter 4 EKF is not in gaitc); use --backend "
            "sim or physics"
        )
    if args.mismatch < 0 or args.noise < 0 or not 0 <= args.infeasible < 1:
        raise UsageError(
            "--mismatch and --noise must not be negative, --infeasible must lie in [0, 1)"
        )
    if args.max_iterations < 1 or args.verify < 1:
        raise UsageError("--max-iterations and --verify must be at least 1")
    goal, settings = goal_of(args), settings_of(args)
    mismatch = Mismatch(args.mismatch, args.noise, args.infeasible, args.seed, args.model_mismatch)
    progress = None if args.quiet else _print_flush
    result = learn_gait(
        args.robot,
        goal,
        args.method,
        mismatch,
        settings,
        args.max_states,
        args.max_iterations,
        args.verify,
        progress,
        args.backend,
        args.predictions,
        args.max_open,
        args.grow,
    )
    print(result.summary())
    if args.log:
        write_atomically(args.log, result.to_json())
    if args.svg:
        write_atomically(args.svg, result._repr_svg_())
        print(f"wrote {args.svg}")
    error = result.error
    if error is not None and error[0] > goal.tolerance:
        print(
            f"the executed displacement misses the goal's tolerance ({goal.tolerance:g} mm): "
            "the measurements are noisy; raise --verify or loosen --tolerance"
        )
    return 0 if result.converged and error is not None else 1


def _print_flush(line: str) -> None:
    print(line, flush=True)
