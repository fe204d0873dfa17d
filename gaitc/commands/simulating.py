"""The ``simulate`` command: run a controller against an environment, print and save the run.

The work lives in :mod:`gaitsim` (simulator, environments, scenarios, monitor); this module
parses options, loads the spec and controller (or synthesizes one) and prints the results.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from diagnostics import ControllerError, UsageError
from gaitc.exitcodes import EXIT_OK, EXIT_UNREALIZABLE, EXIT_USER
from gaitc.loading import Spec, load
from gaitsim.domain import Domain
from gaitsim.environments import AdversarialEnvironment, Environment, RandomEnvironment
from gaitsim.monitor import Monitor
from gaitsim.run import Run
from gaitsim.strategy import Strategy, load_strategy, strategy_from_controller
from ltlcompiler.encoding import ENCODINGS
from ltlcompiler.model import Model

ENVIRONMENTS = ("scripted", "random", "adversarial")
EPILOG = """environments:
  --env random [--seed N]   uniform among the inputs the controller accepts (default, seed 0)
  --env adversarial         degrades every leg in use, activates the nearest hazard set,
                            keeps the robot from its next goal (docs/simulation.md)
  --env scripted FILE.yaml  a scenario: per step the hazard and the legs that degrade/fail

exit codes:
  0  the run finished and the spec held along it
  1  an input file is wrong, a scenario step breaks an assumption, or the controller broke
     a guarantee along the run
  2  the command line is wrong
  3  the spec is unrealizable (when no CONTROLLER is given)
"""


@dataclass(frozen=True)
class Loaded:
    """A .gait spec with its model, a controller adapted to it, and the run checker."""

    spec: Spec
    model: Model
    strategy: Strategy
    domain: Domain
    monitor: Monitor


def _recorded_encoding(controller: str) -> str | None:
    try:
        data = json.loads(Path(controller).read_text(encoding="utf-8"))
        encoding = data["gaitc"]["source"]["encoding"]
    except (OSError, ValueError, KeyError, TypeError):
        return None
    return str(encoding) if encoding in ENCODINGS else None


def load_session(spec_path: str, controller: str | None, encoding: str | None = None,
                 semantics: str = "default") -> Loaded | None:
    """Load ``spec_path`` (a .gait file) and its controller; synthesize one if not given.

    Returns None when no controller was given and the spec is unrealizable.
    """
    if encoding is None:
        encoding = (_recorded_encoding(controller) if controller else None) or "onehot"
    loaded = load(spec_path, encoding)
    if loaded.model is None:
        raise UsageError(f"'{spec_path}': simulation and maps need a .gait spec, which says "
                         "what the variables mean (regions, gaits, legs)")
    if controller is not None:
        strategy = load_strategy(controller, loaded.gr1)
    else:
        from solver.synthesis import synthesize

        found = synthesize(loaded.gr1, semantics)
        if found is None:
            return None
        strategy = strategy_from_controller(found, loaded.gr1, "<synthesized>")
    if strategy.kind != "strategy":
        raise ControllerError("this is a counter-strategy; simulate a controller written by "
                              "'gaitc synth'", None)
    domain = Domain(loaded.model, encoding)
    return Loaded(loaded, loaded.model, strategy, domain, Monitor(loaded.gr1))


def register(sub: Any) -> None:
    p = sub.add_parser(
        "simulate",
        help="run a controller against an environment",
        description="Simulate CONTROLLER (JSON from 'gaitc synth' or SLUGS) for the .gait SPEC "
        "and print each step in domain terms; without CONTROLLER, synthesize one first. Every "
        "step is checked against the spec's assumptions and guarantees.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER", nargs="?")
    p.add_argument("--env", nargs="+", metavar="KIND", default=["random"],
                   help="scripted FILE.yaml | random | adversarial (default random)")
    p.add_argument("--seed", type=int, default=0, help="seed of the random environment")
    p.add_argument("--steps", type=int, metavar="N",
                   help="number of steps (default 50; a scenario's length when scripted)")
    p.add_argument("--out", metavar="FILE", help="save the run as .jsonl or .csv")
    p.add_argument("--encoding", choices=ENCODINGS,
                   help="encoding of the spec (default: the one recorded in the controller)")
    p.add_argument("--robotics-semantics", action="store_true",
                   help="semantics when synthesizing on the fly")
    p.add_argument("--quiet", action="store_true", help="print only the summary")
    p.set_defaults(run=run_simulate)


def _environment(args: argparse.Namespace, loaded: Loaded) -> tuple[Environment, int]:
    kind, *rest = args.env
    if kind not in ENVIRONMENTS:
        raise UsageError(f"unknown environment '{kind}'; use one of {', '.join(ENVIRONMENTS)}")
    steps = 50 if args.steps is None else args.steps
    if steps < 0:
        raise UsageError("--steps must not be negative")
    if kind == "scripted":
        if len(rest) != 1:
            raise UsageError("--env scripted needs one scenario file: --env scripted FILE.yaml")
        from gaitsim.scenario import ScriptedEnvironment, load_scenario

        scenario = load_scenario(rest[0], loaded.model)
        if args.steps is None:
            steps = len(scenario.steps)
        return ScriptedEnvironment(scenario, loaded.strategy.inputs), steps
    if rest:
        raise UsageError(f"--env {kind} takes no file (got '{rest[0]}')")
    if kind == "random":
        return RandomEnvironment(args.seed), steps
    return AdversarialEnvironment(), steps


def run_simulate(args: argparse.Namespace) -> int:
    from gaitsim.simulator import simulate

    semantics = "robotics" if args.robotics_semantics else "default"
    loaded = load_session(args.spec, args.controller, args.encoding, semantics)
    if loaded is None:
        print(f"{args.spec}: unrealizable: no controller to simulate", file=sys.stderr)
        return EXIT_UNREALIZABLE
    environment, steps = _environment(args, loaded)
    run = simulate(loaded.strategy, loaded.domain, loaded.monitor, environment, steps,
                   args.spec)
    full = {leg.name: leg.health for leg in loaded.model.legs}
    return report_run(run, full, environment.name, args.quiet, args.out)


def report_run(
    run: Run, full_health: Mapping[str, int], source: str, quiet: bool, out: str | None
) -> int:
    """Print ``run``'s step table and summary, save it to ``out``, return the exit code.

    A run stopped by a broken assumption raises its error; a run along which the controller
    broke a guarantee (with every assumption kept) is a user error (exit 1).
    """
    from gaitsim.run import save_run
    from gaitsim.terminal import step_table, summary_text, use_colour

    colour = use_colour(sys.stdout)
    if not quiet:
        print(step_table(run, dict(full_health), colour))
        print()
    if run.summary is not None:
        print(summary_text(run.summary, source, colour))
    if out:
        save_run(run, out)
    if run.error is not None:
        sys.stdout.flush()
        raise run.error
    summary = run.summary
    if summary is not None and summary.assumptions_held and not summary.guarantees_held:
        print("gaitc: error: the controller broke a guarantee along this run (see above)",
              file=sys.stderr)
        return EXIT_USER
    return EXIT_OK
