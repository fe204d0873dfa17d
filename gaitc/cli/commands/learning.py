"""``gaitc learn``: a gait learned online toward a displacement (thesis chapter 5), and the
goal options it shares with ``gaitc gaits --method astar|lpa|dstar|mcts``.

The work lives in :func:`gaitc.learn` (:mod:`gaitc.api.learning`); this module turns the
options into :class:`~gaitc.api.learning.LearnOptions` and prints the loop as it runs.
"""

from __future__ import annotations

import argparse
from typing import Any

from gaitc.cli.commands.arguments import output_file
from gaitc.cli.exitcodes import ExitCode, exit_code_help


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
    from gaitc.api.modes import BackendKind, SearchMethod

    p.add_argument("robot", metavar="ROBOT.yaml")
    p.add_argument(
        "--method", default=SearchMethod.LPA.value,
        choices=[m.value for m in SearchMethod if m.is_global],
        help="the chapter 5 search (default lpa)")
    p.add_argument(
        "--backend",
        default=BackendKind.SIM.value,
        metavar="|".join(BackendKind.values()),
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


def search_of(args: argparse.Namespace) -> Any:
    """The :class:`~gaitc.api.gaits.GlobalSearch` of the goal options."""
    from gaitc.api.gaits import GlobalSearch

    return GlobalSearch(goal=args.goal, tolerance=args.tolerance, cell=args.cell,
                        budget=args.budget, iterations=args.iterations, horizon=args.horizon)


def run_learn(args: argparse.Namespace) -> int:
    import gaitc
    from gaitc.api.learning import LearnOptions
    from gaitc.api.modes import SearchMethod

    options = LearnOptions(
        method=SearchMethod.parse(args.method), backend=args.backend, predictions=args.predictions,
        max_open=args.max_open, seed=args.seed, max_states=args.max_states,
        mismatch=args.mismatch, noise=args.noise, model_mismatch=args.model_mismatch,
        infeasible=args.infeasible, grow=args.grow, max_iterations=args.max_iterations,
        verify=args.verify, search=search_of(args))
    learned = gaitc.learn(args.robot, options, progress=None if args.quiet else _print_flush)
    print(learned.learned.summary())
    if args.log:
        learned.save_log(args.log)
    if args.svg:
        learned.draw(args.svg)
        print(f"wrote {args.svg}")
    for note in learned.notes:
        print(note)
    return 0 if learned.converged else 1


def _print_flush(line: str) -> None:
    print(line, flush=True)
