"""Driving a robot (``gaitc drive``): a controller's gaits run as valve sequences on a board.

Each step reads the sensors, follows the controller and runs the chosen gait's valve
primitive (:mod:`gaitc.hw.driver`); the run is checked against the spec as a simulation's
is. The board is one of three backend objects a notebook builds:

- :class:`SimulatedBoard`: valves apply at once, sensor readings come from an environment
  (random, adversarial or a scenario) within the spec's assumptions;
- :class:`PhysicsBoard`: the same readings, but the chassis moves as the robot file's
  spring-damper model predicts (thesis 4.1.1), so the region is the one under the chassis;
- :class:`SerialBoard`: a real valve board on a serial port (protocol v2, docs/hardware.md),
  with waveguide health sensing (thesis 3.4.2).

A reading that breaks an assumption stops the drive, or is held, taken at worst, or
recovered from as ``simulate`` recovers (:class:`~gaitc.core.modes.ViolationPolicy`); on a
simulated board, ``violate`` makes its environment perform events whatever the assumptions
say (``"12:fail L5"``, as ``simulate --violate``).
"""

from __future__ import annotations

import html
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gaitc.api.simulation import (
    ENVIRONMENTS,
    EnvironmentLike,
    Session,
    environment,
    run_document,
    session,
)
from gaitc.api.solving import read_once, recorded_encoding
from gaitc.core.modes import BackendKind, EnvironmentKind, ViolationPolicy
from gaitc.core.spec import Spec, load
from gaitc.diagnostics import UsageError
from gaitc.forms.reader import ControllerFile
from gaitc.hw.backend import interrupt_on_signals
from gaitc.hw.driver import VIOLATION_POLICIES, Driver, bind_primitives, valve_count
from gaitc.hw.localisation import Localised, PoseStream, RegionMap
from gaitc.hw.physics import PhysicsRobot, centre, region_map
from gaitc.hw.saboteur import SurprisingRobot
from gaitc.hw.sensing import read_sensing
from gaitc.hw.serial_board import SerialValveBoard, parse_channels
from gaitc.hw.simulated import SimulatedRobot
from gaitc.ir.spec import Semantics
from gaitc.models.spring_damper.description import load_spring_damper
from gaitc.models.spring_damper.model import SpringDamperModel
from gaitc.search.primitives import resolve_primitive
from gaitc.sim.events import plan
from gaitc.sim.run import checked_steps
from gaitc.sim.scenario import ScriptedEnvironment
from gaitc.sim.terminal import step_table, summary_text, surprises_text
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from gaitc.gaitgraph.pairing import ValveSequence
    from gaitc.hw.backend import Backend
    from gaitc.ir.controller import Controller
    from gaitc.sim.environments import Environment
    from gaitc.sim.events import Event, Surprise
    from gaitc.sim.run import Run
    from gaitc.solver.progress import Progress

__all__ = ["VIOLATION_POLICIES", "Board", "Drive", "DriveOptions", "PhysicsBoard",
           "SerialBoard", "SimulatedBoard", "Tracker", "ViolationPolicy", "board_environment",
           "drive"]


@dataclass(frozen=True)
class SimulatedBoard:
    """The simulated robot: ``env`` is an :class:`~gaitc.sim.session.Opponent` (random with
    ``seed``, adversarial, or scripted with its scenario), its name (``scripted:FILE.yaml``),
    a :class:`~gaitc.sim.scenario.Scenario` or an environment."""

    env: EnvironmentLike = EnvironmentKind.RANDOM
    seed: int = 0
    name = BackendKind.SIM


@dataclass(frozen=True)
class PhysicsBoard:
    """The simulated robot's readings with the chassis moved by the spring-damper model of
    ``robot`` (default: the robot file the gaits' primitives name); regions are the polygons
    of ``map`` or grid cells of ``cell_size`` mm (100)."""

    robot: str | None = None
    map: str | None = None
    cell_size: float | None = None
    env: EnvironmentLike = EnvironmentKind.RANDOM
    seed: int = 0
    name = BackendKind.PHYSICS


@dataclass(frozen=True)
class SerialBoard:
    """A valve board on ``port`` (a device or a pyserial URL such as ``socket://HOST:PORT``)
    at ``baud``, waiting ``timeout`` s for each answer; ``channels`` maps robot valves to
    board channels (``"7,6,5,4"``), ``sensing`` is a thresholds file of ``gaitc calibrate``."""

    port: str
    baud: int = 115200
    timeout: float = 1.0
    channels: str | None = None
    sensing: str | None = None
    name = BackendKind.SERIAL


Board = SimulatedBoard | PhysicsBoard | SerialBoard


@dataclass(frozen=True)
class Tracker:
    """A tracker's pose stream giving the region (``udp://HOST:PORT`` to listen,
    ``tcp://HOST:PORT`` to connect; JSON ``{"x": .., "y": ..}``), placed by the polygons of
    ``map`` or grid cells of ``cell_size`` (1)."""

    url: str
    map: str | None = None
    cell_size: float | None = None
    timeout: float = 1.0


@dataclass(frozen=True)
class DriveOptions:
    """How :func:`drive` runs: ``steps`` (20, or a scenario's length), seconds between valve
    states (0 simulated, 0.5 serial), ``cycles`` of each gait per step, what a reading that
    breaks an assumption does (:class:`ViolationPolicy`; by default stop, or recover when
    there are events to ``violate``), the events a simulated board's environment performs
    whatever the assumptions say (``"12:fail L5"``), an optional pose ``tracker``, and for
    a controller synthesized on the fly its ``encoding``, ``semantics`` (also that of the
    games a recovery solves) and move preferences ``prefer``."""

    steps: int | None = None
    step_delay: float | None = None
    cycles: int = 1
    on_violation: ViolationPolicy | str | None = None
    violate: Sequence[str] = ()
    tracker: Tracker | None = None
    encoding: EncodingName | str | None = None
    semantics: Semantics | str = Semantics.DEFAULT
    prefer: str | Sequence[str] | None = None


@dataclass
class Drive:
    """A drive: the run (None when the spec is unrealizable and no controller was given),
    the readings that broke an assumption and were held or taken at worst (``violations``,
    as notes; a recovered one is a surprise of the run, :attr:`surprises`), the backend's
    name and, for the physics board, the chassis pose at each reading."""

    spec: str
    board: str
    run: Run | None
    full_health: dict[str, int] = field(default_factory=dict)
    violations: tuple[str, ...] = ()
    poses: tuple[Any, ...] = ()

    @property
    def realizable(self) -> bool:
        return self.run is not None

    @property
    def surprises(self) -> tuple[Surprise, ...]:
        """The events of the run that broke an assumption (or were performed by
        ``violate``), each with what became of the run, as ``simulate`` lists them."""
        return () if self.run is None else tuple(self.run.surprises)

    def poses_text(self, quiet: bool = False) -> str:
        """The chassis pose the physics model gave at each reading (the last one if quiet)."""
        lines = ["chassis pose at each reading (mm, deg; region under the chassis):"]
        for p in self.poses if not quiet else self.poses[-1:]:
            lines.append(f"  {p.reading:>3}  x {p.pose.x:8.1f}  y {p.pose.y:8.1f}  "
                         f"heading {math.degrees(p.pose.theta):7.2f}  "
                         f"{p.region or 'outside the map'}")
        return "\n".join(lines)

    def __str__(self) -> str:
        if self.run is None:
            return f"{self.spec}: unrealizable: no controller to drive"

        parts = [step_table(self.run, self.full_health, False)]
        if self.run.summary is not None:
            parts.append(summary_text(self.run.summary, self.board, False))
        if self.run.surprises:

            parts.append(surprises_text(self.run.surprises))
        if self.poses:
            parts.append(self.poses_text())
        return "\n\n".join(parts)

    def _repr_html_(self) -> str:
        return f"<pre>{html.escape(str(self))}</pre>"

    def to_json(self) -> dict[str, Any]:
        return {**run_document(self.spec, self.run, self.board, None, self.realizable),
                "backend": self.board, "substituted": list(self.violations)}


def drive(spec: Spec | str | Path,
          controller: Controller | str | Path | ControllerFile | None = None,
          board: Board | None = None, options: DriveOptions | None = None,
          progress: Progress | None = None,
          live: Callable[[str], None] | None = None) -> Drive:
    """Drive the robot of the ``.gait`` ``spec`` with ``controller`` (synthesized first when
    None) on ``board`` (a :class:`SimulatedBoard` by default). ``live`` receives a line per
    valve state as it runs; ``progress`` the synthesis stages. Every valve is vented at the
    end, on any error and on Ctrl-C, SIGTERM and SIGHUP."""
    chosen = board if board is not None else SimulatedBoard()
    opts = options or DriveOptions()
    _check(chosen, opts)
    controller = read_once(controller)
    recorded = (recorded_encoding(controller)
                if isinstance(controller, (str, Path, ControllerFile)) else None)
    encoding = opts.encoding or recorded or EncodingName.ONEHOT
    checked = spec if isinstance(spec, Spec) else load(spec, encoding)
    if checked.model is None:
        raise UsageError(f"'{checked.path}': driving needs a .gait spec, which binds gaits to "
                         "valve primitives")
    primitives = bind_primitives(checked.model, str(Path(checked.path).parent),
                                 resolve_primitive)
    bound = session(checked, controller, semantics=opts.semantics, prefer=opts.prefer,
                    progress=progress)
    if bound is None:
        return Drive(checked.path, chosen.name, None)
    planned = _planned(chosen, opts, bound)
    policy = _policy(opts)
    backend, steps = _backend(chosen, opts, bound, checked.path, primitives,
                              planned if planned or policy is ViolationPolicy.RECOVER else None)
    if opts.tracker is not None:
        backend = _localised(opts.tracker, backend, bound)
    delay = opts.step_delay if opts.step_delay is not None else (
        0.5 if isinstance(chosen, SerialBoard) else 0.0)
    driver = Driver(
        strategy=bound.strategy,
        domain=bound.domain,
        monitor=bound.monitor,
        primitives=primitives,
        backend=backend,
        step_delay=delay,
        cycles=opts.cycles,
        progress=live,
        on_violation=policy,
        semantics=Semantics.parse(opts.semantics),
        follower=_follower(backend),
    )
    with interrupt_on_signals():  # SIGTERM and SIGHUP vent and keep the run, as Ctrl-C does
        run = driver.run(steps, checked.path)
    return Drive(checked.path, backend.name, run, dict(bound.domain.full),
                 tuple(driver.violations), tuple(getattr(backend, "placed", None) or ()))


def _policy(opts: DriveOptions) -> ViolationPolicy:
    """The policy for a reading that breaks an assumption: the one given, else recover
    when events are to be performed, else stop."""
    if opts.on_violation is not None:
        return ViolationPolicy.parse(opts.on_violation, "--on-violation")
    return ViolationPolicy.RECOVER if opts.violate else ViolationPolicy.STOP


def _planned(board: Board, opts: DriveOptions, bound: Session) -> dict[int, Event]:
    """The events ``violate`` plans, by step; only a simulated board performs them."""
    if not opts.violate:
        return {}
    if isinstance(board, SerialBoard):
        raise UsageError("--violate makes the simulated robot's environment perform an "
                         "event; a serial board's sensors report what happens (use --backend "
                         "sim or physics)")
    if opts.tracker is not None:
        raise UsageError("--violate changes the simulated robot's readings; with --pose the "
                         "region comes from a tracker")

    return plan(opts.violate, bound.domain)


def _follower(backend: Backend) -> Any:
    """The surprising simulated robot inside ``backend`` (a physics board wraps it), or
    None."""
    inner: Any = backend
    while inner is not None and not isinstance(inner, SurprisingRobot):
        inner = getattr(inner, "inner", None)
    return inner


def _check(board: Board, opts: DriveOptions) -> None:
    if opts.steps is not None:
        checked_steps(opts.steps, "--steps")
    if opts.cycles < 1:
        raise UsageError("--cycles must be at least 1")
    if opts.step_delay is not None and opts.step_delay < 0:
        raise UsageError("--step-delay must not be negative")
    if opts.on_violation is not None and opts.on_violation not in VIOLATION_POLICIES:
        raise UsageError(f"unknown --on-violation {opts.on_violation!r}; use one of "
                         f"{', '.join(VIOLATION_POLICIES)}")
    if isinstance(board, SerialBoard) and not board.port:
        raise UsageError("--backend serial needs --port URL (e.g. /dev/ttyUSB0 or "
                         "socket://localhost:7000)")
    for place in (board, opts.tracker):
        if isinstance(place, (PhysicsBoard, Tracker)):
            if place.map and place.cell_size is not None:
                raise UsageError("give --map or --cell-size, not both")
            if place.cell_size is not None and not place.cell_size > 0:
                raise UsageError("--cell-size must be positive")
    if opts.tracker is not None and isinstance(board, PhysicsBoard):
        raise UsageError("--pose reads a tracker; --backend physics computes the pose")


def board_environment(board: SimulatedBoard | PhysicsBoard, bound: Session) -> Environment:
    """The environment a simulated board's readings come from."""
    env = board.env
    if isinstance(env, str) and env not in ENVIRONMENTS and not env.startswith("scripted:"):
        raise UsageError(f"unknown environment '{env}'; use one of {', '.join(ENVIRONMENTS)}")
    return environment(env, bound, board.seed)


def _backend(board: Board, opts: DriveOptions, bound: Session, spec_path: str,
             primitives: dict[str, ValveSequence],
             planned: Mapping[int, Event] | None = None) -> tuple[Backend, int]:
    """The backend of ``board`` and the steps to drive; with ``planned`` (None: no
    surprise to meet), a simulated robot that follows the driver and performs them."""
    valves = valve_count(primitives, len(bound.domain.legs))
    steps: int = 20 if opts.steps is None else opts.steps
    if isinstance(board, SerialBoard):

        channels = parse_channels(board.channels) if board.channels else None
        calibration = read_sensing(board.sensing) if board.sensing else None
        return SerialValveBoard(board.port, valves, bound.domain.legs, board.baud,
                                timeout=board.timeout, channels=channels,
                                levels=bound.domain.full, calibration=calibration), steps

    chosen = board_environment(board, bound)
    if isinstance(chosen, ScriptedEnvironment) and opts.steps is None:
        steps = len(chosen.scenario.steps)
    if planned is not None:

        robot: SimulatedRobot = SurprisingRobot(bound.strategy, bound.domain, bound.monitor,
                                                chosen, valves, planned)
    else:
        robot = SimulatedRobot(bound.strategy, bound.domain, bound.monitor, chosen, valves)
    if isinstance(board, PhysicsBoard):
        return _physics(board, bound, robot, spec_path), steps
    return robot, steps


def _physics(board: PhysicsBoard, bound: Session, robot: Any, spec_path: str) -> Backend:
    model = bound.domain.model
    path = board.robot or next((str(Path(spec_path).parent / g.primitive.robot)
                                for g in model.gaits
                                if g.primitive is not None and g.primitive.robot), None)
    if path is None:
        raise UsageError("--backend physics needs --robot ROBOT.yaml: no gait's primitive "
                         "names a robot file")
    described = load_spring_damper(path)
    if described.valve_count != robot.valve_count:
        raise UsageError(f"robot file {path} has {described.valve_count} valves but the gaits' "
                         f"primitives drive {robot.valve_count}")
    regions = (RegionMap.from_file(board.map, bound.domain.regions) if board.map
               else region_map(model, board.cell_size or 100.0))
    if model.start not in regions.polygons:
        raise UsageError(f"the map places no start region {model.start}")
    return PhysicsRobot(robot, SpringDamperModel(described), regions,
                        centre(regions, model.start), described.period)


def _localised(tracker: Tracker, backend: Backend, bound: Session) -> Backend:
    model = bound.domain.model
    regions = (RegionMap.from_file(tracker.map, bound.domain.regions) if tracker.map
               else RegionMap.from_grid(model, tracker.cell_size or 1.0))
    return Localised(backend, PoseStream(tracker.url, tracker.timeout), regions)
