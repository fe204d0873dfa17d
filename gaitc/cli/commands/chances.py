"""``gaitc chances``: how likely the robot is to finish its patrols under rates
(:func:`gaitc.api.chances.chances`, Storm on the spec's MDP); ``--out`` writes the controller
that does best in expectation, ``--json`` prints one object."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from gaitc.api.modes import EncodingName
from gaitc.cli.commands.arguments import output_file, positive_count, probability
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.reporting import document, print_json

EPILOG = exit_code_help({
    ExitCode.OK: "the chances were computed",
}, codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE))


def register(sub: Any) -> None:
    p = sub.add_parser(
        "chances", help="how likely the robot is to finish its patrols, under rates (Storm)",
        description="For a .gait SPEC (realizable or not) and the chances of the environment's "
        "moves (a rates file, --wear): the best chance any controller has of reaching each goal "
        "and of completing k patrols within N steps, the expected patrols, the controller that "
        "does best in expectation (--out) and, with a CONTROLLER, that controller's chances and "
        "how long its assumptions hold. Needs the 'chances' extra (stormpy).",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER", nargs="?")
    p.add_argument("--rates", metavar="RATES.yaml",
                   help="the chances of wear, sudden failures and hazards (docs/how-to/"
                        "chances.md); unrated wear is the worst case")
    p.add_argument("--wear", type=probability, metavar="P",
                   help="every leg in use loses a level with chance P a move (over the file)")
    p.add_argument("--steps", type=positive_count, default=500, metavar="N",
                   help="the horizon in steps (default 500)")
    p.add_argument("--patrols", type=positive_count, default=10, metavar="K",
                   help="count patrols up to K (default 10)")
    p.add_argument("--max-states", type=positive_count, default=2_000_000, metavar="N",
                   help="stop, saying what is needed, when the explicit model passes N states "
                        "(default 2,000,000; about 1 KB a state)")
    p.add_argument("--out", metavar="FILE", type=output_file,
                   help="write the best controller in expectation (an explicit controller)")
    p.add_argument("--plot", metavar="FILE", type=output_file,
                   help="draw the chance of at least k patrols against k (.svg; .png with "
                        "matplotlib)")
    p.add_argument("--sensitivity", action="store_true",
                   help="also what one more health level on each leg, or a cache on each free "
                        "cell, buys (one model each: slow on big robots)")
    p.add_argument("--encoding", choices=EncodingName.values(), default=EncodingName.ONEHOT.value,
                   help="the encoding of the leg levels (as the CONTROLLER was synthesized)")
    p.add_argument("--json", action="store_true", help="print one JSON object (docs/json.md)")
    p.set_defaults(run=run_chances)


def run_chances(args: argparse.Namespace) -> int:
    import gaitc
    from gaitc.api.chances import ChancesOptions, chances, save_best

    answer = chances(gaitc.load(args.spec, args.encoding), args.controller, rates=args.rates,
                     wear=args.wear,
                     options=ChancesOptions(args.steps, args.patrols, args.max_states),
                     write=args.out is not None or args.plot is not None,
                     sensitivity=args.sensitivity)
    if args.out is not None:
        save_best(answer, args.out)
    if args.plot is not None:
        answer.plot(args.plot)
    if args.json:
        print_json(document("chances", {**answer.to_json(), "output": args.out,
                                        "plot": args.plot}))
    else:
        print(answer)
        if args.out is not None:
            print(f"wrote the best controller in expectation to {args.out}", file=sys.stderr)
    return ExitCode.OK
