"""The controller loop on a valve board: sense, follow the controller, run the gait's valves.

Turn order as in the lowering (Mealy, thesis eqs. 3.3-3.9): the sensed health levels and
hazard are the environment's next input; the controller's successor with that input names
the next region and the gait that gets there, whose valve sequence (chapter 2) is then run.
The loop is gaitsim's Simulator with the sensors playing the environment, so a hardware run
is checked by the monitor and saved like a simulated one (``gaitc render map --run``).

A reading that breaks an assumption stops the run, is replaced by an allowed input
(``hold``, ``worst``), or is recovered from as ``simulate`` recovers from a surprise
(``recover``: :mod:`gaitc.sim.recovery`, after Ehlers and Topcu, HSCC 2014): the drive
goes on with the fallback strategy, with every goal, fewer, or towards a cache, and the run
lists the surprise (``violations``) as ``simulate --violate`` does.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Protocol

from gaitc.core.modes import SurprisePolicy, ViolationPolicy
from gaitc.diagnostics import SpecSemanticError
from gaitc.gaitgraph.pairing import (
    Resolver,
    ValveSequence,
    idle_fired,
    resolve_primitive,
)
from gaitc.hw.backend import (
    Backend,
    HardwareError,
    Interrupted,
    SensorReading,
    where,
)
from gaitc.hw.localisation import Miss, RegionMap, deviation
from gaitc.hw.simulated import ScenarioFinished
from gaitc.ir.spec import Semantics
from gaitc.sim.domain import Domain, State
from gaitc.sim.environments import Environment, Move, Request, Situation
from gaitc.sim.events import ALLOWED_NOTE, Event, Surprise
from gaitc.sim.monitor import Monitor
from gaitc.sim.run import Run
from gaitc.sim.simulator import Simulator, SurpriseOptions
from gaitc.sim.strategy import InputKey, StrategyView
from ltlcompiler.model import GaitKind, Model

#: The policies, as ``--on-violation`` names them.
VIOLATION_POLICIES = ViolationPolicy.values()


class Follower(Protocol):
    """A simulated robot that follows the driver's controller (after a recovery, the
    fallback strategy) and performs planned events (``drive --violate``)."""

    def situate(self, situation: Situation) -> None:
        """The driver's situation before the next reading."""

    def performed(self, step: int) -> Event | None:
        """The planned event performed for the reading of step ``step``, if any."""


@dataclass(frozen=True)
class Executed:
    """The valve states run for the gait of one step of the run."""

    step: int
    gait: str
    valves: tuple[str, ...]


def bind_primitives(model: Model, spec_dir: str,
                    resolve: Resolver | None = None) -> dict[str, ValveSequence]:
    """The valve sequence of every gait but noGait; all must exist and have one valve count.
    ``resolve`` turns a primitive into valves (by default the kinematic graph's pairing;
    ``gaitc drive`` passes :func:`gaitc.search.primitives.resolve_primitive`).

    Raises :class:`SpecSemanticError` listing the gaits without a primitive.
    """
    legs = [leg.name for leg in model.legs]
    gaits = [g for g in model.gaits if g.kind is not GaitKind.NONE]
    missing = [g for g in gaits if g.primitive is None]
    if missing:
        names = ", ".join(g.name for g in missing)
        raise SpecSemanticError(
            f"cannot drive the robot: {len(missing)} gait(s) have no valve primitive: {names}",
            missing[0].span,
            "bind one to each gait: 'gaitc lint --primitives' suggests the valves of each, "
            'or name a robot file with primitive "ROBOT.yaml" direction +x')
    bound = {g.name: (resolve or resolve_primitive)(g, spec_dir, legs) for g in gaits}
    for g in gaits:  # the board must fire only the legs the health reasoning wears
        wrong = idle_fired(g, bound[g.name])
        if wrong is not None:
            span = g.primitive.span if g.primitive is not None and g.primitive.span else g.span
            raise SpecSemanticError(f"cannot drive the robot: {wrong[0]}", span, wrong[1])
    counts = {len(seq.states[0]) for seq in bound.values() if seq.states}
    if len(counts) > 1:
        detail = ", ".join(f"{name}: {len(seq.states[0])}" for name, seq in sorted(bound.items())
                           if seq.states)
        raise SpecSemanticError(
            f"the gaits' primitives drive different numbers of valves ({detail})",
            gaits[0].span, "every primitive must address the same valve board")
    return bound


def valve_count(primitives: Mapping[str, ValveSequence], default: int) -> int:
    """The number of valves the primitives address (``default`` when there are none)."""
    for seq in primitives.values():
        if seq.states:
            return len(seq.states[0])
    return default


class Driver:
    """Runs a controller on a backend, one sensed input and one gait per step."""

    def __init__(self, strategy: StrategyView, domain: Domain, monitor: Monitor,
                 primitives: Mapping[str, ValveSequence], backend: Backend,
                 *, step_delay: float = 0.0, cycles: int = 1,
                 progress: Callable[[str], None] | None = None,
                 on_violation: ViolationPolicy | str = ViolationPolicy.STOP,
                 semantics: Semantics = Semantics.DEFAULT,
                 follower: Follower | None = None) -> None:
        self.simulator = Simulator(strategy, domain, monitor)
        self.domain = domain
        self.primitives = dict(primitives)
        self.backend = backend
        self.step_delay = step_delay
        self.cycles = cycles
        self.progress = progress
        self.executed: list[Executed] = []
        self.interrupted = False
        self.interruption = ""  # Ctrl-C, SIGTERM or SIGHUP
        self.on_violation = ViolationPolicy.parse(on_violation, "--on-violation")
        self.semantics = semantics  # of the games a recovery solves
        self.follower = follower
        self.violations: list[str] = []  # readings held or taken at worst, as handled
        self.substituted: set[int] = set()  # the steps of those readings
        self.no_gait = next(g.name for g in domain.model.gaits if g.kind is GaitKind.NONE)
        self._ran_up_to = -1  # index of the last step whose gait was run
        self._left = domain.model.start  # the region the last gait set out from

    def run(self, steps: int, spec_file: str = "") -> Run:
        """Open the backend, drive up to ``steps`` steps, vent and close; return the run."""
        sensed = SensedEnvironment(self)
        with self.backend:
            try:
                self.backend.vent()
                surprises = (SurpriseOptions(policy=SurprisePolicy.RECOVER,
                                             semantics=self.semantics)
                             if self.on_violation is ViolationPolicy.RECOVER else None)
                run = self.simulator.run(sensed, steps, spec_file, surprises)
                self._allowed(run)
                if run.error is None and not self.interrupted and run.steps:
                    last = run.steps[-1]
                    if last.index > self._ran_up_to:
                        self.execute(last.index, last.gait)
            except KeyboardInterrupt as stop:
                self.interruption = interruption_name(stop)
                self.backend.vent()
                raise
        if self.interrupted and run.summary is not None:
            run.summary = dataclasses.replace(
                run.summary,
                stopped=f"interrupted ({self.interruption}); {self.backend.safety_note()}")
        return run

    def _allowed(self, run: Run) -> None:
        """Add to ``run`` the events the follower performed that broke no assumption (the
        others are surprises the run recorded), in step order."""
        if self.follower is None:
            return
        recorded = {s.step for s in run.surprises}
        for index in range(1, len(run.steps)):
            event = self.follower.performed(index)
            if event is not None and index not in recorded and index not in self.substituted:
                run.surprises.append(Surprise(index, event.words, None, note=ALLOWED_NOTE))
        run.surprises.sort(key=lambda s: s.step)

    def execute(self, step: int, gait: str) -> None:
        """Run the valve sequence of ``gait`` (noGait: vent) and log it."""
        if gait == self.no_gait:
            states: tuple[str, ...] = (self.backend.vented,)
        else:
            seq = self.primitives.get(gait)
            if seq is None:
                raise HardwareError(f"gait {gait} has no valve primitive; cannot run it",
                                    where(self.backend.name))
            states = seq.states * self.cycles
        if self.progress is not None:
            self.progress(f"step {step}: {gait}: {' '.join(states)}")
        for valves in states:
            self.backend.apply(valves)
            self.backend.wait(self.step_delay)
        if "1" in states[-1]:  # no valve stays open outside its gait's step; the actuators
            self.backend.vent()  # relax before the sensors are read
            self.backend.wait(self.step_delay)
        self.executed.append(Executed(step, gait, states))
        self._ran_up_to = step

    def moving_legs(self, gait: str) -> tuple[str, ...]:
        """The legs ``gait`` may degrade (eq. 3.5): a move gait's legs; none for the others."""
        found = next((g for g in self.domain.model.gaits if g.name == gait), None)
        return found.legs if found is not None and found.kind is GaitKind.MOVE else ()

    def sensed_input(self, reading: SensorReading, here: State | None) -> Request:
        """The environment input that ``reading`` stands for, after checking it."""
        domain = self.domain
        legs = tuple(leg for leg, _ in reading.health)
        if legs != domain.legs:
            raise HardwareError(f"the sensors report legs {', '.join(legs)} but the spec has "
                                f"{', '.join(domain.legs)}", where(self.backend.name))
        for leg, level in reading.health:
            if not 1 <= level <= domain.full[leg]:
                raise HardwareError(f"the sensors report health level {level} for leg {leg}, "
                                    f"outside 1..{domain.full[leg]}", where(self.backend.name),
                                    "check the waveguide thresholds of the board")
        if reading.hazard is not None and reading.hazard not in domain.hazard_regions:
            raise HardwareError(f"the sensors report an unknown hazard '{reading.hazard}'",
                                where(self.backend.name))
        expected = domain.model.start if here is None else here.region
        if reading.region is not None and reading.region != expected:
            raise self._off_course(reading.region, expected, here)
        self._left = expected
        gait = self.no_gait if here is None else here.gait
        values = domain.encode(State(expected, gait, reading.health, reading.hazard))
        inputs: InputKey = tuple(int(values[name]) for name in self.simulator.strategy.inputs)
        return Request(inputs, describe(reading, here))

    def _off_course(self, found: str, expected: str, here: State | None) -> HardwareError:
        """The error for a reading in another region than the controller expects, at the
        step's gait in the spec (at the start, at its ``start``): a gait that did not move the
        robot, one that went the wrong way (its motion against the move, in degrees, and its
        primitive), one that went the right way but fell short or too far, or one that
        drifted sideways into a neighbour of the region expected
        (:func:`gaitc.hw.localisation.deviation`)."""
        model = self.domain.model
        step = max(self._ran_up_to, 0)
        after = "at the start" if here is None else f"after gait {here.gait}"
        head = (f"step {step}: localisation reports region {found} but the controller expects "
                f"{expected} {after}")
        tail = "stopped with all valves vented"
        gait = None if here is None else next((g for g in model.gaits if g.name == here.gait),
                                              None)
        span = (model.start_span if gait is None else gait.span) or where(self.backend.name)
        if here is None:
            return HardwareError(
                f"{head}: the robot is not in the region the spec starts it in; {tail}", span,
                f"put the robot in {expected} before the run, or check the localisation map")
        course = self.backend.course(self._left, expected)
        if course is None:
            physics = self.backend.name.startswith("physics")
            return HardwareError(
                f"{head}: the gait did not get there; {tail}", span,
                "on the physics backend a gait moves the robot only as far as the model "
                "predicts per cycle: repeat each gait with --cycles N or shrink the regions "
                "with --cell-size MM (docs/models.md)" if physics
                else "check the gait's valve sequence and the localisation map")
        regions = getattr(self.backend, "regions", None)
        if isinstance(regions, RegionMap) and {found, expected} <= regions.polygons.keys():
            (fx, fy), (ex, ey) = regions.centre(found), regions.centre(expected)
            reached = (fx - ex, fy - ey)
        else:  # as if the gait set out from the centre of its region
            reached = (course.moved[0] - course.wanted[0], course.moved[1] - course.wanted[1])
        off = deviation(course, reached)
        mx, my = course.moved
        moved = (f"moved the chassis {math.hypot(mx, my):.1f} mm ({_compass(mx, 'east', 'west')}"
                 f", {_compass(my, 'north', 'south')})")
        track = f"{off.along:.1f} mm along the {off.length:.1f} mm from {self._left} to {expected}"
        aside = (f"{abs(off.across):.1f} mm {off.side} of that line" if off.side
                 else "not off that line")
        into = found + (f", {off.beside} of {expected}" if off.beside else "")
        seq = self.primitives.get(here.gait)
        primitive = ("" if seq is None else
                     f"; its primitive ({seq.source}) runs {', '.join(seq.states)}")
        if off.miss is Miss.STILL:
            return HardwareError(
                f"{head}: gait {here.gait} did not move the robot: the chassis moved "
                f"{math.hypot(mx, my):.1f} mm of the {off.length:.1f} mm from {self._left} to "
                f"{expected}{primitive}; {tail}", span,
                "check that the primitive opens the valves of the gait's legs, and that the "
                "legs still work (a leg at health level 1 does not move)")
        if off.miss is Miss.WRONG_WAY:
            toward = f"toward {math.degrees(math.atan2(my, mx)):.0f} deg"
            wanted = math.degrees(math.atan2(course.wanted[1], course.wanted[0]))
            return HardwareError(
                f"{head}: gait {here.gait} went the wrong way: it {moved}, {toward}, but "
                f"{expected} lies toward {wanted:.0f} deg from {self._left}, a direction "
                f"error of {off.error:.0f} deg{primitive}; {tail}", span,
                "check the primitive: a valve wired to another leg, or legs fired in "
                "another order, sends the robot elsewhere ('gaitc gaits ROBOT --direction D' "
                "predicts each direction's valve sequence)")
        if off.miss is Miss.DRIFTED:
            return HardwareError(
                f"{head}: gait {here.gait} drifted: it {moved}, {track}, enough to reach "
                f"{expected}, but {aside} (a direction error of {off.error:.0f} deg), which "
                f"put it in {into}; {tail}", span,
                "the gait's motion has a sideways part that carried the robot out of the "
                "region: choose a primitive closer to the move ('gaitc gaits ROBOT "
                "--direction D' ranks each direction's valve sequences), or give the regions "
                "room across the move (--cell-size MM, or a --map)")
        if off.miss is Miss.SHORT:
            return HardwareError(
                f"{head}: gait {here.gait} went the right way (a direction error of "
                f"{off.error:.0f} deg) but not far enough: it {moved}, {track} and {aside}, "
                f"so it fell short and is in {into}; {tail}", span,
                "a gait moves the robot only as far as its cycle does: repeat each gait with "
                "--cycles N or shrink the regions with --cell-size MM (docs/models.md)")
        return HardwareError(
            f"{head}: gait {here.gait} went the right way (a direction error of "
            f"{off.error:.0f} deg) but too far: it {moved}, {track} and {aside}, so it "
            f"passed {expected} and is in {into}; {tail}", span,
            "each step runs the gait's cycle --cycles times: run fewer cycles or grow the "
            "regions with --cell-size MM (docs/models.md)")


def _compass(value: float, positive: str, negative: str) -> str:
    return f"{abs(value):.1f} mm {positive if value >= 0 else negative}"


def substitute(moves: Sequence[Move], reading: SensorReading, here: State | None,
               policy: ViolationPolicy) -> Move:
    """The accepted input that stands for a reading which breaks an assumption: ``hold``
    keeps the levels the controller had (closest to them, then to the reading); ``worst``
    takes the lowest levels the assumptions allow (then closest to the reading).  The
    sensed hazard is kept when an accepted input has it."""
    sensed = dict(reading.health)
    before = dict(here.health) if here is not None else sensed

    def distance(move: Move, to: Mapping[str, int]) -> int:
        return sum(abs(level - to[leg]) for leg, level in move.state.health)

    def rank(move: Move) -> tuple[int, int, int, InputKey]:
        other_hazard = int(move.state.hazard != reading.hazard)
        first = (distance(move, before) if policy is ViolationPolicy.HOLD
                 else sum(level for _, level in move.state.health))
        return other_hazard, first, distance(move, sensed), move.inputs

    return min(moves, key=rank)


def describe(reading: SensorReading, here: State | None) -> str:
    """A short account of a reading, for messages: the legs that changed and the hazard."""
    before = dict(here.health) if here is not None else {}
    changed = [f"{leg} {before[leg]}→{level}" for leg, level in reading.health
               if leg in before and before[leg] != level]
    parts = [f"sensed {', '.join(changed) if changed else 'no health change'}"]
    parts.append(f"hazard {reading.hazard}" if reading.hazard else "no hazard")
    return "; ".join(parts)


class SensedEnvironment(Environment):
    """The environment as the sensors see it: runs the last gait, then reads its outcome."""

    name = "hardware"

    def __init__(self, driver: Driver) -> None:
        self.driver = driver
        self.name = f"hardware ({driver.backend.name})"

    def choose(self, situation: Situation) -> Request | None:
        driver = self.driver
        state = situation.state
        if driver.follower is not None:
            driver.follower.situate(situation)
        try:
            if state is not None:
                driver.execute(situation.step - 1, state.gait)
                driver.backend.step_context(driver.moving_legs(state.gait),
                                            state.region in driver.domain.model.caches)
            reading = driver.backend.read_sensors()
        except ScenarioFinished:
            return None
        except KeyboardInterrupt as stop:
            driver.interrupted = True
            driver.interruption = interruption_name(stop)
            driver.backend.vent()
            return None
        request = driver.sensed_input(reading, state)
        event = None if driver.follower is None else driver.follower.performed(situation.step)
        if event is not None:  # the simulated robot performed a planned event: its words
            request = Request(request.inputs, event.words)
        moves = {m.inputs: m for m in situation.moves}
        move = moves.get(request.inputs)
        if move is None and driver.on_violation is ViolationPolicy.RECOVER:
            if driver.progress is not None and situation.values is not None and \
                    driver.simulator.monitor.failed_assumptions(
                        situation.values, dict(zip(driver.simulator.strategy.inputs,
                                                   request.inputs, strict=True))):
                driver.progress(f"step {situation.step}: {request.what} breaks an assumption; "
                                "recover: the controller goes on from the state sensed")
            return request  # the simulator recovers from it (or refuses what breaks nothing)
        if move is None and driver.on_violation is not ViolationPolicy.STOP and situation.moves:
            move = substitute(situation.moves, reading, state, driver.on_violation)
            used = ", ".join(f"{leg} {level}" for leg, level in move.state.health)
            note = (f"step {situation.step}: {request.what} breaks an assumption; "
                    f"{driver.on_violation}: taken as {used}, hazard "
                    f"{move.state.hazard or 'none'}")
            driver.violations.append(note)
            driver.substituted.add(situation.step)
            if driver.progress is not None:
                driver.progress(note)
            request = Request(move.inputs, f"{request.what} ({driver.on_violation}: {used})")
        if move is not None:
            driver.backend.accepted(move)
        return request


def interruption_name(stop: KeyboardInterrupt) -> str:
    """How a run was interrupted: ``Ctrl-C``, ``SIGTERM`` or ``SIGHUP``."""
    return stop.name if isinstance(stop, Interrupted) else "Ctrl-C"


def applied_states(executed: Sequence[Executed]) -> list[str]:
    """Every valve state run, in order (flattens :attr:`Driver.executed`)."""
    return [valves for entry in executed for valves in entry.valves]
