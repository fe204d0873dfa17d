"""The ``play`` command: step through a controller or a counter-strategy by hand.

The work lives in :func:`gaitc.player` (:mod:`gaitc.api.playing`, over :mod:`gaitc.play`);
this module parses options and runs the terminal app of :mod:`gaitc.play.terminal`.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import Any

from gaitc.api.modes import EncodingName
from gaitc.cli.commands.arguments import run_file, semantics_of
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.keys import Quit, quit_key
from gaitc.cli.status import progress_display
from gaitc.diagnostics import UsageError

EPILOG = """keys (? in the player lists them):
  1-9 or enter  play a move           u / r  undo / redo       g  go to a step
  a / n         the strongest / a random pilot plays N steps   s  save   q  quit (saves)
For a realizable spec you play the environment (which legs degrade or fail, which hazard
is on) and the controller answers; for an unrealizable one, or with --against, you play
the robot against the environment's counter-strategy, and each move says why it loses.
Playing the environment, the moves marked ! break an assumption (a leg failing while not
in use, a hazard where none may be): the controller recovers as after 'simulate --violate'
(every goal, fewer goals, or stopped at a cache) and the log below the moves says how.
A saved play is drawn by 'gaitc render map SPEC --run FILE' and replayed by
'gaitc simulate SPEC --env scripted FILE'.

"""
EPILOG += exit_code_help({
    ExitCode.OK: "the player was closed",
    ExitCode.USER: "an input file is wrong (a controller or run file of another spec)",
}, codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE))


def register(sub: Any) -> None:
    p = sub.add_parser(
        "play",
        help="step through a controller or counter-strategy by hand",
        description="Play the environment against CONTROLLER (synthesized when left out) for "
        "the .gait SPEC in a terminal app: choose which legs degrade or fail and which hazard "
        "is on, and see the controller answer on the map. For an unrealizable spec, play the "
        "robot against the environment's counter-strategy.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER", nargs="?")
    p.add_argument("--against", action="store_true",
                   help="play the robot against the environment's counter-strategy (the "
                   "default for an unrealizable spec)")
    p.add_argument("--from", dest="start", metavar="RUN.jsonl",
                   help="start from a run file (a saved play, simulate --out, explain --out)")
    p.add_argument("--at", type=int, metavar="STEP",
                   help="the step of the --from run to start from (default: its last)")
    p.add_argument("--out", metavar="FILE", type=run_file,
                   help="where the play is saved on quitting (default SPEC-NAME.play.jsonl "
                   "here); s in the player saves anywhere")
    p.add_argument("--seed", type=int, default=0, help="seed of the random pilot (default 0)")
    p.add_argument("--no-color", action="store_true", help="draw without colour (as NO_COLOR)")
    p.add_argument("--encoding", choices=EncodingName.values())
    p.add_argument("--robotics-semantics", action="store_true",
                   help="the initial state is chosen by the robot too (SLUGS's option)")
    p.set_defaults(run=run_play)


def run_play(args: argparse.Namespace) -> int:
    import gaitc

    if args.at is not None and args.start is None:
        raise UsageError("--at picks a step of the run given with --from")
    if not (sys.stdin.isatty() and sys.stdout.isatty()):
        raise UsageError("'gaitc play' needs a terminal; from a script or a notebook use "
                         "gaitc.player(SPEC) (or gaitc.player_widget), or replay a run with "
                         "'gaitc simulate SPEC --env scripted RUN.jsonl'")
    try:
        with quit_key() as watched, progress_display(note="q quits" if watched else "") \
                as progress:
            player = gaitc.player(args.spec, args.controller, against=args.against or None,
                                  start=args.start, at=args.at, encoding=args.encoding,
                                  semantics=semantics_of(args), progress=progress)
    except Quit:
        print(f"{args.spec}: quit before the play began; nothing to save", file=sys.stderr)
        return ExitCode.OK
    if args.no_color:
        os.environ["NO_COLOR"] = "1"
    from gaitc.play.terminal import play_in_terminal

    out = args.out or f"{Path(args.spec).stem}.play.jsonl"
    saved = play_in_terminal(player, out, args.seed)
    if saved is not None:
        print(f"{args.spec}: {player.played_words()} saved to {saved}")
    return ExitCode.OK
