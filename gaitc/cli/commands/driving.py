"""The ``drive`` command: run a controller's gaits on a valve board (simulated or serial).

The work lives in :mod:`gaitc.hw` (backends, driver loop); this module parses options, binds
the gaits to their valve primitives, picks the backend and prints the run.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import gaitc
from gaitc.api.simulation import Session
from gaitc.api.solving import recorded_encoding
from gaitc.cli.commands.arguments import add_prefer, positive_seconds, run_file
from gaitc.cli.commands.simulating import add_json, environment_of, report_run, settle_environment
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.reporting import document, print_json, run_json
from gaitc.cli.status import progress_display
from gaitc.diagnostics import UsageError
from gaitc.hw.backend import Backend, interrupt_on_signals
from gaitc.hw.driver import VIOLATION_POLICIES
from gaitc.sim.environments import Environment
from gaitc.sim.scenario import ScriptedEnvironment
from ltlcompiler.encoding import ENCODINGS

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
    p.add_argument("--backend", choices=("sim", "physics", "serial"), default="sim",
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
    p.add_argument("--on-violation", choices=VIOLATION_POLICIES, default="stop",
                   help="a reading that breaks the spec's assumptions: stop the run (default), "
                   "hold the levels the controller had, or take the worst levels the "
                   "assumptions allow")
    p.add_argument("--pose", metavar="URL",
                   help="take the region from a tracker's pose stream: udp://HOST:PORT "
                   "(listen) or tcp://HOST:PORT (connect), JSON {\"x\": .., \"y\": ..}")
    p.add_argument("--map", metavar="FILE", help="--pose: region polygons (YAML)")
    p.add_argument("--cell-size", type=float, metavar="S",
                   help="--pose without --map: the side of a grid cell (1)")
    p.add_argument("--sensing", metavar="FILE",
                   help="serial backend: waveguide thresholds per leg (from 'gaitc calibrate')")
    p.add_argument("--encoding", choices=ENCODINGS,
                   help="encoding of the spec (default: the one recorded in the controller)")
    p.add_argument("--robotics-semantics", action="store_true",
                   help="semantics when synthesizing on the fly")
    p.add_argument("--quiet", action="store_true", help="print only the summary")
    add_json(p)
    add_prefer(p, "without CONTROLLER: ")
    p.set_defaults(run=run_drive)


def _check_options(args: argparse.Namespace) -> None:
    settle_environment(args, real_sensors=args.backend == "serial")
    if args.steps is not None and args.steps < 0:
        raise UsageError("--steps must not be negative")
    if args.cycles < 1:
        raise UsageError("--cycles must be at least 1")
    if args.step_delay is not None and args.step_delay < 0:
        raise UsageError("--step-delay must not be negative")
    if args.backend == "serial":
        if not args.port:
            raise UsageError("--backend serial needs --port URL (e.g. /dev/ttyUSB0 or "
                             "socket://localhost:7000)")
        if args.env:
            raise UsageError("--env chooses the simulated robot's environment; the serial "
                             "backend reads real sensors")
    if (args.map or args.cell_size is not None) and not args.pose and args.backend != "physics":
        raise UsageError("--map and --cell-size place the poses of --pose or --backend physics")
    if args.robot and args.backend != "physics":
        raise UsageError("--robot is for --backend physics")
    if args.map and args.cell_size is not None:
        raise UsageError("give --map or --cell-size, not both")
    if args.cell_size is not None and not args.cell_size > 0:
        raise UsageError("--cell-size must be positive")
    if args.backend != "serial" and (args.port or args.channels or args.sensing):
        raise UsageError("--port, --channels and --sensing are for --backend serial")


def _environment(args: argparse.Namespace, bound: Session) -> tuple[Environment, int | None]:
    chosen = environment_of(args, bound)
    scripted = chosen.scenario.steps if isinstance(chosen, ScriptedEnvironment) else None
    return chosen, None if scripted is None else len(scripted)


def _backend(args: argparse.Namespace, loaded: Session, valves: int) -> tuple[Backend, int]:
    steps: int = 20 if args.steps is None else args.steps
    if args.backend == "serial":
        from gaitc.hw.sensing import read_sensing
        from gaitc.hw.serial_board import SerialValveBoard, parse_channels

        channels = parse_channels(args.channels) if args.channels else None
        calibration = read_sensing(args.sensing) if args.sensing else None
        return SerialValveBoard(args.port, valves, loaded.domain.legs, args.baud, args.timeout,
                                channels=channels, levels=loaded.domain.full,
                                calibration=calibration), steps
    from gaitc.hw.simulated import SimulatedRobot

    environment, scripted = _environment(args, loaded)
    if scripted is not None and args.steps is None:
        steps = scripted
    robot = SimulatedRobot(loaded.strategy, loaded.domain, loaded.monitor, environment, valves)
    if args.backend == "physics":
        return _physics(args, loaded, robot), steps
    return robot, steps


def _physics(args: argparse.Namespace, loaded: Session, robot: Any) -> Backend:
    from gaitc.hw.localisation import RegionMap
    from gaitc.hw.physics import PhysicsRobot, centre, region_map
    from gaitc.models.description import load_spring_damper
    from gaitc.models.spring_damper import SpringDamperModel

    model = loaded.domain.model
    path = args.robot or next((str(Path(args.spec).parent / g.primitive.robot)
                               for g in model.gaits
                               if g.primitive is not None and g.primitive.robot), None)
    if path is None:
        raise UsageError("--backend physics needs --robot ROBOT.yaml: no gait's primitive "
                         "names a robot file")
    described = load_spring_damper(path)
    if described.valve_count != robot.valve_count:
        raise UsageError(f"robot file {path} has {described.valve_count} valves but the gaits' "
                         f"primitives drive {robot.valve_count}")
    regions = (RegionMap.from_file(args.map, loaded.domain.regions) if args.map
               else region_map(model, args.cell_size or 100.0))
    if model.start not in regions.polygons:
        raise UsageError(f"the map places no start region {model.start}")
    return PhysicsRobot(robot, SpringDamperModel(described), regions,
                        centre(regions, model.start), described.period)


def _localised(args: argparse.Namespace, backend: Backend, loaded: Session) -> Backend:
    from gaitc.hw.localisation import Localised, PoseStream, RegionMap

    model = loaded.domain.model
    regions = (RegionMap.from_file(args.map, loaded.domain.regions) if args.map
               else RegionMap.from_grid(model, args.cell_size or 1.0))
    return Localised(backend, PoseStream(args.pose, args.timeout), regions)


def run_drive(args: argparse.Namespace) -> int:
    from gaitc.hw.driver import Driver, bind_primitives, valve_count

    _check_options(args)
    encoding = args.encoding or (recorded_encoding(args.controller) if args.controller
                                 else None) or "onehot"
    checked = gaitc.load(args.spec, encoding)
    if checked.model is None:
        raise UsageError(f"'{args.spec}': driving needs a .gait spec, which binds gaits to "
                         "valve primitives")
    primitives = bind_primitives(checked.model, str(Path(args.spec).parent))
    semantics = "robotics" if args.robotics_semantics else "default"
    with progress_display() as progress:
        loaded = gaitc.session(checked, args.controller, semantics=semantics,
                               prefer=args.prefer, progress=progress)
    if loaded is None:
        print(f"{args.spec}: unrealizable: no controller to drive", file=sys.stderr)
        if args.json:
            print_json(document("drive", {**run_json(args.spec, None, None, None, False),
                                          "backend": args.backend, "violations": []}))
        return ExitCode.UNREALIZABLE
    backend, steps = _backend(args, loaded, valve_count(primitives, len(loaded.domain.legs)))
    if args.pose:
        if args.backend == "physics":
            raise UsageError("--pose reads a tracker; --backend physics computes the pose")
        backend = _localised(args, backend, loaded)
    delay = args.step_delay if args.step_delay is not None else (
        0.5 if args.backend == "serial" else 0.0)
    live = (None if args.quiet or args.json or args.backend in ("sim", "physics")
            else _print_flush)
    driver = Driver(loaded.strategy, loaded.domain, loaded.monitor, primitives, backend,
                    delay, args.cycles, live, args.on_violation)
    with interrupt_on_signals():  # SIGTERM and SIGHUP vent and keep the run, as Ctrl-C does
        run = driver.run(steps, args.spec)
    if args.json:
        extra = {"backend": args.backend, "violations": list(driver.violations)}
        return report_run(run, dict(loaded.domain.full), backend.name, args.quiet, args.out,
                          True, extra, command="drive")
    if driver.violations and live is None:
        print(f"readings that broke an assumption ({args.on_violation}): "
              f"{len(driver.violations)}")
        for note in driver.violations:
            print(f"  {note}")
    try:
        return report_run(run, dict(loaded.domain.full), backend.name, args.quiet, args.out)
    finally:
        placed = getattr(backend, "placed", None)
        if placed:  # the physics backend's poses, also for a run that broke the spec
            _print_poses(placed, args.quiet)


def _print_poses(placed: list[Any], quiet: bool) -> None:
    """The chassis pose the physics model gave at each sensor reading."""
    import math

    print("chassis pose at each reading (mm, deg; region under the chassis):")
    for p in placed if not quiet else placed[-1:]:
        print(f"  {p.reading:>3}  x {p.pose.x:8.1f}  y {p.pose.y:8.1f}  "
              f"heading {math.degrees(p.pose.theta):7.2f}  {p.region or 'outside the map'}")


def _print_flush(line: str) -> None:
    print(line, flush=True)
