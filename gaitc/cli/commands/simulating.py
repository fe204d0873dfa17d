"""The ``simulate`` command: run a controller against an environment, print and save the run.

The work lives in :func:`gaitc.simulate` (:mod:`gaitc.api.simulation`, over :mod:`gaitc.sim`);
this module parses options, calls it and prints the step table and summary.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Mapping
from typing import Any

from gaitc.api.modes import EncodingName, EnvironmentKind
from gaitc.api.runs import Run, checked_steps
from gaitc.api.simulation import (
    CHANGE_EXAMPLES,
    ENVIRONMENTS,
    Opponent,
    SurprisePolicy,
    run_document,
    simulate_spec,
)
from gaitc.cli.commands.arguments import (
    add_prefer,
    mcap_file,
    probability,
    run_file,
    semantics_of,
)
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.reporting import document, exit_code_of, print_json
from gaitc.cli.status import progress_display
from gaitc.diagnostics import UsageError, render_error

EPILOG = """environments:
  --env random [--seed N]   uniform among the inputs the controller accepts (default, seed 0)
  --env adversarial         plans over the controller for the most health lost and the
                            farthest from the next goal (docs/simulation.md); for an
                            unrealizable spec without CONTROLLER, plays its counter-strategy
  --env scripted FILE.yaml  a scenario: per step the hazard and the legs that degrade/fail
  --env scripted RUN.jsonl  the inputs of a run file (gaitc play, simulate --out), again
  --env stochastic [--rates RATES.yaml] [--wear P] [--seed N]
                            drawn from the rates 'gaitc chances' reads (a leg's wear chance
                            a move, hazards switching); unrated wear is always taken
A counter-strategy (from 'gaitc counter') is the environment itself; --env random,
adversarial or scripted RUN.jsonl then says how the robot answers (adversarial: it avoids
forced deadlocks; a run file: as the run did).

"""
EPILOG += exit_code_help({
    ExitCode.OK: "the run finished and the spec held along it",
    ExitCode.USER: "an input file is wrong, a scenario step breaks an assumption, or the "
    "controller broke a guarantee along the run",
    ExitCode.UNREALIZABLE: "the spec is unrealizable (when no CONTROLLER is given)",
}, codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE, ExitCode.UNREALIZABLE))


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
    p.add_argument("--env", nargs="+", metavar="KIND", default=[EnvironmentKind.RANDOM.value],
                   help="scripted FILE.yaml | scripted RUN.jsonl | random | adversarial "
                   "(default random)")
    p.add_argument("--seed", type=int,
                   help="seed of the random or stochastic environment (default 0)")
    p.add_argument("--rates", metavar="RATES.yaml",
                   help="the stochastic environment's chances (docs/how-to/chances.md)")
    p.add_argument("--wear", type=probability, metavar="P",
                   help="the stochastic environment: every leg in use loses a level with "
                        "chance P a move")
    p.add_argument("--steps", type=int, metavar="N",
                   help="number of steps (default 50; a scenario's length when scripted)")
    p.add_argument("--out", metavar="FILE", type=run_file,
                   help="save the run as .jsonl or .csv")
    p.add_argument("--mcap", metavar="RUN.mcap", type=mcap_file,
                   help="also write the run as MCAP with the topics of 'gaitc ros' (one step "
                   "a second; needs the ros extra; docs/how-to/ros.md)")
    p.add_argument("--encoding", choices=EncodingName.values(),
                   help="encoding of the spec (default: the one recorded in the controller)")
    p.add_argument("--robotics-semantics", action="store_true",
                   help="semantics when synthesizing on the fly")
    p.add_argument("--quiet", action="store_true", help="print only the summary")
    add_surprises(p)
    add_json(p)
    add_prefer(p, "without CONTROLLER: ")
    p.set_defaults(run=run_simulate)


def add_surprises(p: argparse.ArgumentParser) -> None:
    """``--violate`` and ``--on-surprise``: events the environment performs whatever the
    assumptions say, and what the controller does after an input that breaks them."""
    p.add_argument("--violate", action="append", default=[], metavar="STEP:EVENT",
                   help="at step STEP the environment performs EVENT whatever the assumptions "
                   f"say: {CHANGE_EXAMPLES}, or several joined by commas (repeatable; "
                   "events of one step happen together; docs/how-to/surprises.md)")
    p.add_argument("--on-surprise", choices=SurprisePolicy.values(),
                   default=SurprisePolicy.RECOVER.value,
                   help="after an input that breaks an assumption: recover (go on from the "
                   "state reached, with fewer goals or to a cache if need be; the default) or "
                   "stop with an error")


def add_json(p: argparse.ArgumentParser) -> None:
    """``--json`` of ``simulate`` and ``drive``: the run as one object (docs/json.md)."""
    p.add_argument("--json", action="store_true",
                   help="print the run (steps, summary, error) as one JSON object instead "
                   "of the table (docs/json.md)")


def settle_environment(args: argparse.Namespace, real_sensors: bool = False) -> None:
    """Give CONTROLLER back from ``--env`` (whose ``nargs='+'`` also takes the positional
    after it: ``SPEC --env random CONTROLLER``; a .yaml word stays a misplaced scenario), and
    refuse a ``--seed`` nothing uses."""
    kind, *rest = args.env or [EnvironmentKind.RANDOM.value]
    wanted = 1 if kind == EnvironmentKind.SCRIPTED else 0
    taken = rest[-1] if len(rest) == wanted + 1 else ""
    if args.controller is None and taken and not taken.endswith(
            (".yaml", ".yml", ".jsonl")):
        args.controller = rest[-1]
        args.env = args.env[:-1]
    if args.seed is not None and real_sensors:
        raise UsageError("--seed seeds the simulated random environment; the serial backend "
                         "reads real sensors")
    if args.seed is not None and kind not in (EnvironmentKind.RANDOM,
                                              EnvironmentKind.STOCHASTIC):
        raise UsageError(f"--seed seeds the random environment; --env {kind} uses no random "
                         "numbers (drop --seed, or use --env random)")


def opponent_of(args: argparse.Namespace) -> Opponent:
    """The environment ``--env`` names (with its scenario or run file for ``scripted``)."""
    kind, *rest = args.env or [EnvironmentKind.RANDOM.value]
    if kind not in ENVIRONMENTS:
        raise UsageError(f"unknown environment '{kind}'; use one of {', '.join(ENVIRONMENTS)}")
    if kind == EnvironmentKind.SCRIPTED:
        if len(rest) != 1:
            raise UsageError("--env scripted needs one scenario or run file: --env scripted "
                             "FILE.yaml or --env scripted RUN.jsonl")
        return Opponent(EnvironmentKind.SCRIPTED, rest[0])
    if rest:
        raise UsageError(f"--env {kind} takes no file (got '{rest[0]}')")
    rates, wear = getattr(args, "rates", None), getattr(args, "wear", None)
    if kind == EnvironmentKind.STOCHASTIC:
        return Opponent(EnvironmentKind.STOCHASTIC, rates=rates, wear=wear)
    if rates is not None or wear is not None:
        raise UsageError("--rates and --wear give the chances of the stochastic environment: "
                         "use --env stochastic")
    return Opponent(EnvironmentKind.parse(kind))


def run_simulate(args: argparse.Namespace) -> int:
    if args.steps is not None:
        checked_steps(args.steps, "--steps")
    settle_environment(args)
    if args.mcap:
        from gaitc.api.ros import require_ros

        require_ros()  # before the run, not after it
    with progress_display() as progress:
        played = simulate_spec(args.spec, args.controller, opponent_of(args), args.steps,
                               args.seed or 0, encoding=args.encoding,
                               semantics=semantics_of(args), prefer=args.prefer,
                               progress=progress, violate=args.violate,
                               on_surprise=args.on_surprise)
    if played.run is None:
        print(f"{args.spec}: unrealizable: no controller to simulate", file=sys.stderr)
        if args.json:
            print_json(document("simulate", run_document(args.spec, None, None, None, False)))
        return ExitCode.UNREALIZABLE
    if args.mcap:
        from gaitc.api.ros import record_run

        assert played.spec is not None  # a run was played, so its spec was loaded
        record_run(played.run, played.spec, args.mcap)
    return report_run(played.run, played.full_health, played.run.environment, args.quiet,
                      out=args.out, as_json=args.json, realizable=played.realizable)


def report_run(
    run: Run, full_health: Mapping[str, int], source: str, quiet: bool, *, out: str | None,
    as_json: bool = False, extra: Mapping[str, Any] | None = None, realizable: bool = True,
    command: str = "simulate",
) -> int:
    """Print ``run``'s step table and summary, save it to ``out``, return the exit code.

    A run stopped by a broken assumption raises its error; a run along which the controller
    broke a guarantee (with every assumption kept) is a user error (exit 1).  With
    ``as_json`` one object is printed instead (with ``extra``'s keys), holding the error
    that stopped the run, and the exit code is returned rather than the error raised.
    """
    from gaitc.api.runs import save_run, step_table, summary_text, surprises_text, use_colour

    if as_json:
        if out:
            save_run(run, out)
        print_json(document(command, {**run_document(run.spec_file, run, source, out, realizable),
                                      **(extra or {})}))
        if run.error is not None:
            print(render_error(run.error), file=sys.stderr)
            return exit_code_of(run.error)
        return ExitCode.USER if _broke_guarantee(run) else ExitCode.OK
    colour = use_colour(sys.stdout)
    if not quiet:
        print(step_table(run, dict(full_health), colour))
        print()
    if run.summary is not None:
        print(summary_text(run.summary, source, colour))
    if run.surprises:
        print(surprises_text(run.surprises))
    if out:
        save_run(run, out)
    if run.error is not None:
        sys.stdout.flush()
        raise run.error
    return ExitCode.USER if _broke_guarantee(run) else ExitCode.OK


def _broke_guarantee(run: Run) -> bool:
    """Whether the controller broke a guarantee with every assumption kept (said on stderr)."""
    summary = run.summary
    if summary is not None and summary.assumptions_held and not summary.guarantees_held:
        print("gaitc: error: the controller broke a guarantee along this run (see above)",
              file=sys.stderr)
        return True
    return False
