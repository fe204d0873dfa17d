"""The ``drive`` command: run a controller's gaits on a valve board (simulated or serial).

The work lives in :func:`gaitc.drive` (:mod:`gaitc.api.driving`); this module builds the
board and :class:`~gaitc.api.driving.DriveOptions` from the options and prints the run.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import gaitc
from gaitc.api.driving import VIOLATION_POLICIES
from gaitc.api.modes import BackendKind, EncodingName
from gaitc.api.simulation import CHANGE_EXAMPLES, run_document
from gaitc.cli.commands.arguments import add_prefer, positive_seconds, run_file, semantics_of
from gaitc.cli.commands.simulating import add_json, opponent_of, report_run, settle_environment
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.reporting import document, print_json
from gaitc.cli.status import progress_display
from gaitc.diagnostics import UsageError

EPILOG = """backends:
  --backend sim      a simulated robot (default): valves apply instantly, sensor readings come
                     from --env (random, adversarial or a scripted scenario), within the
                     spec's assumptions
  --backend physics  the simulated robot's sensor readings, but the chassis moves as the
                     robot file's spring-damper model predicts (docs/models.md): each valve
                     state is held for the model's control period, the region is the one
                     under the chassis (--cell-size mm squares, default 100, or --map), so
                     a gait that does not get far enough breaks the spec
  --backend serial   a valve board on --port (a device such as /dev/ttyUSB0, or
                     socket://HOST:PORT) speaking the gaitc line protocol v2
                     (docs/hardware.md); every valve is vented on exit, on any error, on
                     Ctrl-C, SIGTERM and SIGHUP; a heartbeat keeps the board's watchdog fed
                     while valves are open (try it with 'gaitc firmware simulate')

"""
EPILOG += exit_code_help({
    ExitCode.OK: "the run finished (or was interrupted with Ctrl-C) and the spec held along it",
    ExitCode.USER: "an input file is wrong, a gait has no valve primitive, the board failed, "
    "the sensors broke an assumption, or the controller broke a guarantee",
    ExitCode.UNREALIZABLE: "the spec is unrealizable (when no CONTROLLER is given)",
}, codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE, ExitCode.UNREALIZABLE))


def register(sub: Any) -> None:
    p = sub.add_parser(
        "drive",
        help="run a controller's gaits on a valve board",
        description="Drive the robot of the .gait SPEC with CONTROLLER (JSON from 'gaitc synth'; "
        "without it, synthesize one first): each step reads the sensors, follows the "
        "controller and runs the chosen gait's valve sequence on the board.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER", nargs="?")
    p.add_argument("--backend", choices=BackendKind.values(), default=BackendKind.SIM.value,
                   help="sim (default), physics or serial")
    p.add_argument("--robot", metavar="ROBOT.yaml",
                   help="physics backend: the robot file with the model (default: the one "
                   "the gaits' primitives name)")
    p.add_argument("--port", metavar="URL", help="serial port or pyserial URL (serial backend)")
    p.add_argument("--baud", type=int, default=115200, metavar="N", help="baud rate (115200)")
    p.add_argument("--timeout", type=positive_seconds, default=1.0, metavar="S",
                   help="seconds to wait for each board answer (1)")
    p.add_argument("--channels", metavar="LIST",
                   help="board channel of each robot valve, e.g. 7,6,5,4,3,2,1,0 "
                   "(default: valve i on channel i)")
    p.add_argument("--steps", type=int, metavar="N",
                   help="steps to run (20; a scenario's length when scripted)")
    p.add_argument("--step-delay", type=float, metavar="S",
                   help="seconds between valve states (0 for sim, 0.5 for serial)")
    p.add_argument("--cycles", type=int, default=1, metavar="N",
                   help="times each gait's valve sequence is repeated per step (1)")
    p.add_argument("--env", nargs="+", metavar="KIND",
                   help="sim backend: random (default) | adversarial | scripted FILE.yaml")
    p.add_argument("--seed", type=int, help="seed of the random environment (default 0)")
    p.add_argument("--out", metavar="FILE", type=run_file,
                   help="save the run as .jsonl or .csv")
    p.add_argument("--on-violation", choices=VIOLATION_POLICIES,
                   help="a reading that breaks the spec's assumptions: stop the run (the "
                   "default), hold the levels the controller had, take the worst levels the "
                   "assumptions allow, or recover as simulate does (go on from the state "
                   "sensed, with fewer goals or to a cache if need be; the default with "
                   "--violate)")
    p.add_argument("--violate", action="append", default=[], metavar="STEP:EVENT",
                   help="sim and physics backends: at step STEP the simulated robot's "
                   f"environment performs EVENT whatever the assumptions say: "
                   f"{CHANGE_EXAMPLES}, or several joined by commas (repeatable; events of "
                   "one step happen together; docs/how-to/surprises.md)")
    p.add_argument("--pose", metavar="URL",
                   help="take the region from a tracker's pose stream: udp://HOST:PORT "
                   "(listen) or tcp://HOST:PORT (connect), JSON {\"x\": .., \"y\": ..}")
    p.add_argument("--map", metavar="FILE", help="--pose: region polygons (YAML)")
    p.add_argument("--cell-size", type=float, metavar="S",
                   help="--pose without --map: the side of a grid cell (1)")
    p.add_argument("--sensing", metavar="FILE",
                   help="serial backend: waveguide thresholds per leg (from 'gaitc calibrate')")
    p.add_argument("--encoding", choices=EncodingName.values(),
                   help="encoding of the spec (default: the one recorded in the controller)")
    p.add_argument("--robotics-semantics", action="store_true",
                   help="semantics when synthesizing on the fly")
    p.add_argument("--quiet", action="store_true", help="print only the summary")
    add_json(p)
    add_prefer(p, "without CONTROLLER: ")
    p.set_defaults(run=run_drive)


def _check_options(args: argparse.Namespace) -> None:
    """The checks only the command line needs: options given to a board that takes none."""
    settle_environment(args, real_sensors=args.backend == BackendKind.SERIAL)
    if args.backend == BackendKind.SERIAL and args.env:
        raise UsageError("--env chooses the simulated robot's environment; the serial "
                         "backend reads real sensors")
    physics = args.backend == BackendKind.PHYSICS
    if (args.map or args.cell_size is not None) and not args.pose and not physics:
        raise UsageError("--map and --cell-size place the poses of --pose or --backend physics")
    if args.robot and not physics:
        raise UsageError("--robot is for --backend physics")
    if args.backend != BackendKind.SERIAL and (args.port or args.channels or args.sensing):
        raise UsageError("--port, --channels and --sensing are for --backend serial")


def board_of(args: argparse.Namespace) -> Any:
    """The board ``--backend`` names, with its options."""
    from gaitc.api.driving import PhysicsBoard, SerialBoard, SimulatedBoard

    if args.backend == BackendKind.SERIAL:
        return SerialBoard(args.port or "", args.baud, args.timeout, args.channels,
                           args.sensing)
    env, seed = opponent_of(args), args.seed or 0
    if args.backend == BackendKind.PHYSICS:
        return PhysicsBoard(args.robot, None if args.pose else args.map,
                            None if args.pose else args.cell_size, env, seed)
    return SimulatedBoard(env, seed)


def options_of(args: argparse.Namespace) -> Any:
    from gaitc.api.driving import DriveOptions, Tracker

    tracker = (Tracker(args.pose, args.map, args.cell_size, args.timeout) if args.pose
               else None)
    return DriveOptions(
        steps=args.steps, step_delay=args.step_delay, cycles=args.cycles,
        on_violation=args.on_violation, violate=args.violate, tracker=tracker,
        encoding=args.encoding,
        semantics=semantics_of(args), prefer=args.prefer)


def run_drive(args: argparse.Namespace) -> int:
    _check_options(args)
    board, options = board_of(args), options_of(args)
    live = (None if args.quiet or args.json or args.backend in ("sim", "physics")
            else _print_flush)
    with progress_display() as progress:
        driven = gaitc.drive(args.spec, args.controller, board, options, progress, live)
    if driven.run is None:
        print(f"{args.spec}: unrealizable: no controller to drive", file=sys.stderr)
        if args.json:
            print_json(document("drive", {**run_document(args.spec, None, None, None, False),
                                          "backend": args.backend, "violations": [],
                                          "substituted": []}))
        return ExitCode.UNREALIZABLE
    if args.json:
        extra = {"backend": args.backend, "substituted": list(driven.violations)}
        return report_run(driven.run, driven.full_health, driven.board, args.quiet,
                          out=args.out, as_json=True, extra=extra, command="drive")
    if driven.violations and live is None:
        print(f"readings that broke an assumption ({args.on_violation}): "
              f"{len(driven.violations)}")
        for note in driven.violations:
            print(f"  {note}")
    try:
        return report_run(driven.run, driven.full_health, driven.board, args.quiet,
                          out=args.out)
    finally:
        if driven.poses:  # the physics backend's poses, also for a run that broke the spec
            print(driven.poses_text(args.quiet))


def _print_flush(line: str) -> None:
    print(line, flush=True)
