"""The ``ros`` command: a verified controller as a ROS 2 node, optionally with a simulated
robot node beside it and every topic recorded as MCAP.

The work lives in :func:`gaitc.ros` (:mod:`gaitc.api.ros`, over :mod:`gaitc.ros`); this
module parses options, calls it and prints the run as ``simulate`` does.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from gaitc.api.modes import EncodingName
from gaitc.cli.commands.arguments import (
    mcap_file,
    positive_seconds,
    seconds_or_zero,
    semantics_of,
)
from gaitc.cli.commands.simulating import (
    add_json,
    add_surprises,
    opponent_of,
    report_run,
    settle_environment,
)
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.status import progress_display
from gaitc.diagnostics import UsageError

EPILOG = """The node (default name gaitc_controller) subscribes to leg_health
(sensor_msgs/JointState: leg names, health levels) and hazards (sensor_msgs/JointState:
hazard sets, 1 on / 0 off, the same stamp), and publishes gait, target_region and valves
(std_msgs/String) and /diagnostics (diagnostic_msgs/DiagnosticArray).  A bad observation (an
unknown leg, a level out of range, a stale stamp), the watchdog and SIGINT/SIGTERM stop it
with every valve vented.  ROS arguments go last: --ros-args -r gait:=/robot/gait -p
watchdog:=5.0 (docs/how-to/ros.md has the topic table).

--sim runs a simulated robot node beside it, over the topics, against --env as simulate
does (random with --seed, adversarial, scripted FILE), for --steps steps (50), performing
each --violate event whatever the assumptions say.

"""
EPILOG += exit_code_help({
    ExitCode.OK: "the run finished (or a signal stopped it) and the spec held along it",
    ExitCode.USER: "an input file is wrong, a bad observation or the watchdog stopped the "
    "node, an input broke an assumption under --on-surprise stop, or the controller broke "
    "a guarantee",
    ExitCode.USAGE: "the command line is wrong, or the ros extra is not installed "
    "(pip install 'gaitc[ros]')",
    ExitCode.UNREALIZABLE: "the spec is unrealizable (when no CONTROLLER is given)",
}, codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE, ExitCode.UNREALIZABLE))


def register(sub: Any) -> None:
    p = sub.add_parser(
        "ros",
        help="run a controller as a ROS 2 node",
        description="Run CONTROLLER (from 'gaitc synth'; without it, synthesize one first) of "
        "the .gait SPEC as a ROS 2 node: each observation of the legs' health and the hazards "
        "is a step's input, the gait, target region and valve pattern are its answer, and "
        "every step is checked against the spec.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER", nargs="?")
    p.add_argument("--sim", action="store_true",
                   help="run a simulated robot node beside the controller node")
    p.add_argument("--env", nargs="+", metavar="KIND",
                   help="--sim: random (default) | adversarial | scripted FILE")
    p.add_argument("--seed", type=int, help="--sim: seed of the random environment (0)")
    p.add_argument("--steps", type=int, metavar="N",
                   help="steps to run (--sim: 50, or a scenario's length; else until stopped)")
    p.add_argument("--robot", metavar="ROBOT.yaml",
                   help="the robot file the gaits' valve primitives are read from (default: "
                   "the one each primitive names)")
    p.add_argument("--record", metavar="RUN.mcap", type=mcap_file,
                   help="record every topic to an MCAP file (ROS 2 encoding)")
    p.add_argument("--rate", type=seconds_or_zero, default=1.0, metavar="HZ",
                   help="/diagnostics heartbeat (1 Hz; 0: on every step only)")
    p.add_argument("--watchdog", type=positive_seconds, metavar="S",
                   help="stop, vented, when no observation came for S seconds (2; with --sim "
                   "60, as the simulated robot solves recovery games before it senses)")
    p.add_argument("--stale-after", type=positive_seconds, default=1.0, metavar="S",
                   help="an observation stamped more than S seconds ago is bad (1)")
    p.add_argument("--encoding", choices=EncodingName.values(),
                   help="encoding of the spec (default: the one recorded in the controller)")
    p.add_argument("--robotics-semantics", action="store_true",
                   help="semantics when synthesizing on the fly")
    p.add_argument("--quiet", action="store_true", help="print only the summary")
    add_surprises(p)
    add_json(p)
    p.add_argument("--ros-args", nargs=argparse.REMAINDER, default=[], metavar="ARG",
                   help="ROS 2 arguments, last on the line: remaps (-r FROM:=TO), "
                   "parameters (-p NAME:=VALUE), --log-level")
    p.set_defaults(run=run_ros)


def _check(args: argparse.Namespace) -> None:
    if not args.sim and (args.env or args.seed is not None or args.violate):
        raise UsageError("--env, --seed and --violate are for the simulated robot: add --sim")
    if args.sim:
        settle_environment(args)


def run_ros(args: argparse.Namespace) -> int:
    from gaitc.api.ros import RosOptions, SimulatedRobot, ros

    _check(args)
    robot = (SimulatedRobot(opponent_of(args), args.seed or 0, tuple(args.violate),
                            args.steps) if args.sim else None)
    options = RosOptions(on_surprise=args.on_surprise, semantics=semantics_of(args),
                         rate=args.rate, watchdog=args.watchdog, stale_after=args.stale_after,
                         steps=None if args.sim else args.steps,
                         ros_args=tuple(args.ros_args), record=args.record,
                         encoding=args.encoding, robot=args.robot)
    with progress_display() as progress:
        ran = ros(args.spec, args.controller, options, robot, progress)
    if ran.run is None:
        if ran.interrupted:
            print(f"interrupted ({ran.interrupted}); every valve vented", file=sys.stderr)
            return ExitCode.OK
        print(f"{args.spec}: {ran.stopped}", file=sys.stderr)
        return ExitCode.UNREALIZABLE
    if not args.json:
        if ran.robot:
            print(f"simulated robot: {ran.robot}")
        if ran.recording is not None:
            counts = ", ".join(f"{t} {n}" for t, n in sorted(ran.recorded.items()))
            print(f"recorded {ran.recording}: {counts}")
        print(f"node: {ran.stopped}")
    extra = {"stopped": ran.stopped, "vents": ran.vents, "faults": list(ran.faults),
             "robot": ran.robot, "recording": ran.recording, "recorded": ran.recorded}
    code = report_run(ran.run, ran.full_health, ran.run.environment, args.quiet, out=None,
                      as_json=args.json, extra=extra, command="ros")
    if ran.robot_error is not None:
        raise ran.robot_error
    return code
