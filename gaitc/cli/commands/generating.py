"""``gaitc codegen``: a compact controller as C for a host (``c``) or the valve board (``avr``).

A thin wrapper over :func:`gaitc.generate`; the controller is proved against the spec first
and an AVR image that does not fit the ATmega328P is refused with its sizes.
"""

from __future__ import annotations

import argparse
from typing import Any

import gaitc
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.reporting import document, print_json

EPILOG = """examples:
  gaitc synth specs/thesis_robot_a.gait --compact -o a.compact.json
  gaitc codegen specs/thesis_robot_a.gait a.compact.json --target c -o gen/
  gaitc codegen specs/thesis_robot_a.gait a.compact.json --target avr -o board/

"""


def register(sub: Any) -> None:
    p = sub.add_parser(
        "codegen", help="generate C from a compact controller, for a host or the valve board",
        description="Write the controller as self-contained C (fixed tables, no heap): "
        "gaitc_controller.h and .c. --target c also builds gaitc-run, the controller behind "
        "a line protocol on standard input; --target avr links it into the valve-board "
        "firmware (gaitboard.elf, gaitboard.hex), reports flash and RAM against the "
        "ATmega328P's and refuses an image that does not fit. The controller (compact, or "
        "symbolic and compacted here) is proved against SPEC first.",
        epilog=EPILOG + exit_code_help({ExitCode.USER: "the controller is malformed, belongs "
                                        "to another spec, or does not fit the board"},
                                       codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE)),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER",
                   help="a compact (synth --compact) or symbolic (synth --symbolic) controller")
    p.add_argument("--target", required=True, choices=[str(t) for t in gaitc.Target],
                   help="c: a host (no size limit); avr: the valve board's firmware")
    p.add_argument("-o", "--out", required=True, metavar="DIR", help="output folder")
    p.add_argument("--no-monitor", action="store_true",
                   help="leave the assumption monitor out (smaller tables): a board running "
                   "alone then checks only that the levels it grades are in range, not that "
                   "they are moves the spec's assumptions allow")
    p.add_argument("--recover", action="store_true",
                   help="add recovery and fallback tables: on a broken assumption "
                   "the controller recovers, degrades to fewer goals or stops, instead of "
                   "venting; the recovering controller is built from SPEC and proved, and "
                   "written instead of CONTROLLER; on the board, fallbacks that do not fit "
                   "its flash are dropped and the surprises it then stops on are listed")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.set_defaults(run=run_codegen)


def run_codegen(args: argparse.Namespace) -> int:
    built = gaitc.generate(args.spec, args.controller, args.target, args.out,
                           monitor=not args.no_monitor, recover=args.recover)
    if args.json:
        print_json(document("codegen", {"file": args.spec, "controller": args.controller,
                                        **built.to_json()}))
        return ExitCode.OK
    names = ", ".join(p.name for p in built.files)
    program = f"; built {built.program}" if built.program is not None else ""
    print(f"wrote {names} to {args.out}{program}")
    print(f"size: {built.summary()}")
    return ExitCode.OK
