"""The controller as a ROS 2 node: each observation (``leg_health``, ``hazards``) is the
environment's input of a step, the controller's answer is published as the gait, the target
region and the valve pattern, and the node's state goes to ``/diagnostics``.

The loop is the simulator's (:class:`~gaitc.sim.simulator.Simulator`) with the robot's
messages playing the environment, as ``drive`` runs it with the board's sensors
(:mod:`gaitc.hw.driver`): the run monitor checks every step, and an input that breaks an
assumption is recovered from or stops the run as ``simulate --on-surprise`` says
(:mod:`gaitc.sim.recovery`).  A bad observation (an unknown leg, a level out of range, a
stale stamp), a silent robot (the watchdog) and SIGINT/SIGTERM/SIGHUP each stop the node
with every valve vented: the gait becomes the spec's no-gait and the valves all close.
"""

from __future__ import annotations

import contextlib
import queue
import signal
import sys
import threading
import time
from collections import Counter
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field, replace
from types import FrameType
from typing import TYPE_CHECKING, Any

from gaitc.core.modes import SurprisePolicy
from gaitc.diagnostics import UsageError
from gaitc.hw.backend import HardwareError, Interrupted
from gaitc.ir.spec import Semantics
from gaitc.ros.observation import Intake, Reading
from gaitc.ros.recording import end_reason
from gaitc.ros.topics import (
    DIAGNOSTICS,
    GAIT,
    HAZARDS,
    LEG_HEALTH,
    OK,
    REGION,
    VALVES,
    Status,
    diagnostics_message,
    qos,
    step_status,
    stop_status,
    text_message,
    valve_pattern,
)
from gaitc.sim.domain import Domain, State
from gaitc.sim.environments import Environment, Request, Situation
from gaitc.sim.monitor import Monitor
from gaitc.sim.recovery import Entry, Fallback
from gaitc.sim.run import Run
from gaitc.sim.simulator import Simulator, SurpriseOptions, Verdicts
from gaitc.solver.progress import goal_titles
from ltlcompiler.model import GaitKind

if TYPE_CHECKING:
    from collections.abc import Sequence

    from gaitc.gaitgraph.pairing import ValveSequence
    from gaitc.ros.graph import Graph
    from gaitc.sim.strategy import StrategyView

#: How often (s) the run loop looks at the clock while waiting for an observation.
POLL = 0.02


@dataclass(frozen=True)
class NodeOptions:
    """How the controller node runs (each is also a ROS parameter of the node, so ``--ros-args
    -p watchdog:=5.0`` overrides it): after an input that breaks an assumption, recover or
    stop (``on_surprise``) with the recovery games' ``semantics``; the /diagnostics heartbeat
    ``rate`` (Hz; 0 publishes on every step only); the ``watchdog`` (s without an
    observation, once the first came, before stopping; counted from the last command when
    the node took longer to answer); the largest age of an observation's
    stamp (``stale_after``, s); the ``steps`` to run (None: until stopped); the node's name."""

    on_surprise: SurprisePolicy = SurprisePolicy.RECOVER
    semantics: Semantics = Semantics.DEFAULT
    rate: float = 1.0
    watchdog: float = 2.0
    stale_after: float = 1.0
    steps: int | None = None
    name: str = "gaitc_controller"

    def checked(self) -> NodeOptions:
        """These options, or a :class:`UsageError` naming the first that is out of range."""
        for what, value in (("rate", self.rate), ("watchdog", self.watchdog),
                            ("stale_after", self.stale_after)):
            bound = "at least 0" if what == "rate" else "positive"
            if not value >= 0 or (what != "rate" and value == 0):
                raise UsageError(f"the {what} must be {bound} (got {value})")
        return self


@dataclass
class Games(Fallback):
    """The recovery games of a run (:class:`~gaitc.sim.recovery.Fallback`), noting the entry
    each surprise made (the goals kept) by the thread that met it, so that the simulated
    robot's copy of the controller and the node, stepping in turn, solve each game once."""

    entries: dict[int, list[Entry]] = field(default_factory=dict)

    def enter(self, before: Sequence[int], inputs: Mapping[str, int], pursuing: int = 0,
              caches: bool = True) -> Entry:
        entry = super().enter(before, inputs, pursuing, caches)
        self.entries.setdefault(threading.get_ident(), []).append(entry)
        return entry


class ControllerNode:
    """A controller of a ``.gait`` spec as a ROS 2 node in ``graph``.

    ``primitives`` are the gaits' valve sequences (None: the spec binds no valves, and the
    node publishes no valve pattern); ``spec_file`` and ``controller_file`` are the node's
    read-only parameters ``spec`` and ``controller``."""

    def __init__(self, graph: Graph, strategy: StrategyView, domain: Domain, monitor: Monitor,
                 primitives: Mapping[str, ValveSequence] | None, options: NodeOptions, *,
                 spec_file: str = "", controller_file: str = "") -> None:
        # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
        from rclpy.node import Node

        self.graph = graph
        self.strategy, self.domain, self.monitor = strategy, domain, monitor
        self.primitives = None if primitives is None else dict(primitives)
        self.spec_file = spec_file
        self.node = Node(options.name, context=graph.context)
        self.options = self._parameters(options, spec_file, controller_file)
        self.no_gait = next(g.name for g in domain.model.gaits if g.kind is GaitKind.NONE)
        self.valve_count = 0 if not self.primitives else next(
            (len(s.states[0]) for s in self.primitives.values() if s.states), 0)
        self.titles = goal_titles(monitor.spec)
        self.intake = Intake(domain.full, tuple(domain.hazard_regions), self.options.stale_after)
        node = self.node
        self.publishers = {t.name: node.create_publisher(t.message_class, t.name, qos(t))
                           for t in (GAIT, REGION, DIAGNOSTICS)}
        if self.primitives:
            self.publishers[VALVES.name] = node.create_publisher(VALVES.message_class,
                                                                 VALVES.name, qos(VALVES))
        self.subscriptions = [node.create_subscription(LEG_HEALTH.message_class,
                                                       LEG_HEALTH.name, self.on_health,
                                                       qos(LEG_HEALTH))]
        if domain.hazard_regions:
            self.subscriptions.append(node.create_subscription(
                HAZARDS.message_class, HAZARDS.name, self.on_hazards, qos(HAZARDS)))
        self._inbox: queue.Queue[Reading | HardwareError | Interrupted] = queue.Queue()
        self._lock = threading.RLock()
        self.vents = 0  # times every valve was vented
        self.taken = 0  # observation messages handled
        self.faults: list[str] = []  # the bad observations, in words
        self.interrupted = ""  # the signal that stopped the node
        self.received: float | None = None  # monotonic time of the last observation
        self.commanded = 0.0  # monotonic time of the last command
        self.status = Status(OK, "waiting for the first observation",
                             (("step", "-"),))
        self.sent: Counter[str] = Counter()  # messages published, by topic
        self.stopped = False
        self.games = Games(monitor.spec, domain, self.options.semantics)
        self._runner: int | None = None  # the thread that runs the node's loop
        self._told = 0  # the surprises logged
        if self.options.rate > 0:
            node.create_timer(1.0 / self.options.rate, self._heartbeat)
        graph.add(node)
        listened = ", ".join(s.topic_name for s in self.subscriptions)
        node.get_logger().info(f"ready: waiting for observations on {listened}")

    # -- parameters --------------------------------------------------------------------

    def _parameters(self, options: NodeOptions, spec_file: str, controller_file: str
                    ) -> NodeOptions:
        """Declare the node's parameters with ``options`` as defaults and read them back
        (``--ros-args -p name:=value`` overrides a default)."""
        # lazy: the ros extra may be missing; gaitc ros then names the extra
        from rcl_interfaces.msg import ParameterDescriptor

        # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
        from rclpy.exceptions import ParameterException

        node = self.node

        def declare(name: str, value: Any, description: str, read_only: bool = False) -> Any:
            try:
                found = node.declare_parameter(name, value, ParameterDescriptor(
                    description=description, read_only=read_only)).value
            except ParameterException as err:  # a -p NAME:=VALUE of the wrong type
                raise UsageError(f"parameter {name}: {err}") from None
            if type(found) is not type(value):
                raise UsageError(f"parameter {name}: expected a {type(value).__name__}, got "
                                 f"{found!r}")
            return found

        declare("spec", spec_file, "the .gait spec the controller was synthesized for", True)
        declare("controller", controller_file or "<synthesized>", "the controller file", True)
        policy = declare("on_surprise", options.on_surprise.value,
                         "after an input that breaks an assumption: recover or stop")
        return replace(
            options,
            on_surprise=SurprisePolicy.parse(policy, "parameter on_surprise"),
            rate=declare("rate", float(options.rate), "/diagnostics heartbeat (Hz; 0: none)"),
            watchdog=declare("watchdog", float(options.watchdog),
                             "seconds without an observation before stopping"),
            stale_after=declare("stale_after", float(options.stale_after),
                                "largest age of an observation's stamp (s)"),
        ).checked()

    # -- observations --------------------------------------------------------------------

    def on_health(self, message: Any) -> None:
        """A ``leg_health`` message (the subscription's callback)."""
        self._take(self.intake.health, message)

    def on_hazards(self, message: Any) -> None:
        """A ``hazards`` message (the subscription's callback)."""
        self._take(self.intake.hazards, message)

    def _take(self, read: Any, message: Any) -> None:
        self.taken += 1
        try:
            reading = read(message, time.time_ns())
        except HardwareError as err:
            self.fault(err)
            return
        if reading is not None:
            self.received = time.monotonic()
            self._inbox.put(reading)

    def fault(self, err: HardwareError) -> None:
        """A bad observation: report it, vent every valve, and stop the run."""
        self.faults.append(err.message)
        self.vent(f"bad observation: {err.message}; stopped with every valve vented")
        self._inbox.put(err)

    def interrupt(self, name: str) -> None:
        """A signal: vent at once, then stop the run."""
        self.interrupted = name
        self.vent(f"interrupted ({name}); stopped with every valve vented")
        self._inbox.put(Interrupted(name))

    # -- commands --------------------------------------------------------------------------

    def _publish(self, topic: str, text: str) -> None:
        self.publishers[topic].publish(text_message(text))
        self.sent[topic] += 1

    def vent(self, reason: str) -> None:
        """Stop the robot: the no-gait, every valve closed, the reason on /diagnostics."""
        with self._lock:
            self.stopped = True
            self._publish(GAIT.name, self.no_gait)
            if VALVES.name in self.publishers:
                self._publish(VALVES.name, "0" * self.valve_count)
            self.vents += 1
            self.status = stop_status(reason, *self._goals())
            self._diagnose()

    def command(self, index: int, state: State, verdicts: Verdicts) -> None:
        """Publish step ``index``: the target region, the gait, its valves, the verdict."""
        with self._lock:
            if self.stopped:
                return
            self._publish(REGION.name, state.region)
            self._publish(GAIT.name, state.gait)
            if VALVES.name in self.publishers:
                self._publish(VALVES.name, valve_pattern(self.primitives, state.gait,
                                                         self.valve_count))
            self.commanded = time.monotonic()
            entries = self._entries()
            if len(entries) > self._told:  # a surprise since the last step: say it in words
                self._told = len(entries)
                kept, lost = self._goals()
                self.node.get_logger().warning(
                    f"step {index}: the observation broke an assumption; "
                    f"{entries[-1].outcome.value}: pursuing {', '.join(kept) or 'no goal'}"
                    + (f"; out of reach: {', '.join(lost)}" if lost else ""))
            self.status = step_status(index, state.region, state.gait,
                                      [v.describe() for v in verdicts.violations],
                                      [e.outcome.value for e in entries], *self._goals())
            self._diagnose()

    def _goals(self) -> tuple[list[str], list[str]]:
        """The goals kept and lost (all kept until a surprise gives some up)."""
        entries = self._entries()
        kept = entries[-1].kept if entries else range(len(self.titles))
        return ([self.titles[j] for j in kept],
                [t for j, t in enumerate(self.titles) if j not in kept])

    def _entries(self) -> list[Entry]:
        """The node's own recoveries (the games may be shared with a simulated robot)."""
        return [] if self._runner is None else self.games.entries.get(self._runner, [])

    def _diagnose(self) -> None:
        self.publishers[DIAGNOSTICS.name].publish(
            diagnostics_message(self.status, self.spec_file, time.time_ns()))
        self.sent[DIAGNOSTICS.name] += 1

    def _heartbeat(self) -> None:
        with self._lock:
            self._diagnose()

    # -- the run ---------------------------------------------------------------------------

    def request(self, reading: Reading, here: State | None) -> Request:
        """The environment input ``reading`` stands for at ``here`` (None: the start)."""
        domain = self.domain
        region = domain.model.start if here is None else here.region
        gait = self.no_gait if here is None else here.gait
        values = domain.encode(State(region, gait, reading.health, reading.hazard))
        inputs = tuple(int(values[name]) for name in self.strategy.inputs)
        before = dict(here.health) if here is not None else {}
        changed = [f"{leg} {before[leg]}→{level}" for leg, level in reading.health
                   if leg in before and before[leg] != level]
        what = (f"observed {', '.join(changed) if changed else 'no health change'}; "
                f"{'hazard ' + reading.hazard if reading.hazard else 'no hazard'}")
        return Request(inputs, what)

    def run(self) -> Run | None:
        """Follow the controller until ``steps`` are done, a fault, the watchdog or a signal
        stops it; every valve is vented at the end. None when a signal stopped it outside
        the wait for an observation (the run is then lost, the valves vented)."""
        opts = self.options
        self._runner = threading.get_ident()
        surprises = SurpriseOptions(policy=opts.on_surprise, semantics=opts.semantics,
                                    fallback=self.games)
        simulator = _Following(self, self.strategy, self.domain, self.monitor)
        steps = sys.maxsize - 1 if opts.steps is None else opts.steps
        try:
            run = simulator.run(_Observed(self), steps, self.spec_file, surprises)
        except KeyboardInterrupt as stop:
            if not self.interrupted:
                self.interrupt(stop.name if isinstance(stop, Interrupted) else "SIGINT")
            return None
        self._finish(run)
        return run

    def _finish(self, run: Run) -> None:
        if self.interrupted:
            if run.summary is not None:
                run.summary = replace(run.summary, stopped=f"interrupted ({self.interrupted}); "
                                      "every valve vented")
            return
        if run.error is not None and isinstance(run.error, HardwareError) and \
                run.error.message in self.faults:
            return  # vented when the bad observation (or the watchdog) came
        self.vent(end_reason(run))

    @contextlib.contextmanager
    def signals(self) -> Iterator[None]:
        """While inside (in the main thread), SIGINT, SIGTERM and SIGHUP vent at once and
        stop the run."""
        if threading.current_thread() is not threading.main_thread():
            yield
            return

        def stop(signum: int, frame: FrameType | None) -> None:
            name = signal.Signals(signum).name
            if not self.interrupted:
                self.interrupt(name)
            raise Interrupted(name)

        # an ignored SIGINT (a background job's) stays ignored, as gaitc leaves it elsewhere
        caught = [sig for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
                  if sig != signal.SIGINT or signal.getsignal(sig) is not signal.SIG_IGN]
        kept = {sig: signal.signal(sig, stop) for sig in caught}
        try:
            yield
        finally:
            for sig, handler in kept.items():
                signal.signal(sig, handler)


class _Following(Simulator):
    """The simulator whose every checked step is published as the node's command."""

    def __init__(self, owner: ControllerNode, strategy: StrategyView, domain: Domain,
                 monitor: Monitor) -> None:
        super().__init__(strategy, domain, monitor)
        self.owner = owner
        self._decoded: dict[tuple[int, ...], State] = {}

    def observe(self, verdicts: Verdicts, index: int, before: tuple[int, ...] | None,
                values: tuple[int, ...]) -> None:
        super().observe(verdicts, index, before, values)
        state = self._decoded.get(values)
        if state is None:
            state = self.domain.decode(dict(zip(self.monitor.variables, values, strict=True)))
            self._decoded[values] = state
        self.owner.command(index, state, verdicts)


class _Observed(Environment):
    """The environment as the robot's messages tell it: waits for the next reading."""

    name = "ROS 2 topics"

    def __init__(self, owner: ControllerNode) -> None:
        self.owner = owner

    def choose(self, situation: Situation) -> Request | None:
        owner = self.owner
        inbox = owner._inbox
        watchdog = owner.options.watchdog
        try:
            while True:
                try:
                    item = inbox.get(timeout=POLL)
                except queue.Empty:
                    # the robot's silence counts from its last observation, or from the
                    # last command when the node took longer to answer than the robot
                    if owner.received is not None and time.monotonic() - max(
                            owner.received, owner.commanded) > watchdog:
                        owner.vent(f"watchdog: no observation for {watchdog:g} s; stopped "
                                   "with every valve vented")
                        owner.faults.append(f"watchdog: no observation for {watchdog:g} s")
                        raise HardwareError(owner.faults[-1]) from None
                    continue
                if isinstance(item, Interrupted):
                    return None
                if isinstance(item, HardwareError):
                    raise item
                return owner.request(item, situation.state)
        except KeyboardInterrupt as stop:  # a signal while waiting: already vented
            if not owner.interrupted:
                owner.interrupt(stop.name if isinstance(stop, Interrupted) else "SIGINT")
            return None
