"""The controller on ROS 2 (``gaitc ros``): a verified controller of a ``.gait`` spec as a
ROS 2 node (:mod:`gaitc.ros.node`), optionally with a simulated robot node beside it
(:mod:`gaitc.ros.robot`) and every topic recorded as MCAP; and any run written as MCAP with
the same topics (``simulate --mcap``).  Needs the ``ros`` extra (``pip install
'gaitc[ros]'``); without it each function raises a :class:`UsageError` that says so.
"""

from __future__ import annotations

import dataclasses
import threading
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gaitc.api.simulation import (
    DEFAULT_STEPS,
    EnvironmentLike,
    Session,
    environment,
    opponent,
    session,
)
from gaitc.api.solving import read_once, recorded_encoding
from gaitc.core.modes import ControllerKind, EnvironmentKind, Semantics, SurprisePolicy
from gaitc.core.spec import Spec, load
from gaitc.diagnostics import GaitcError, UsageError
from gaitc.forms.reader import ControllerFile
from gaitc.hw.backend import HardwareError
from gaitc.hw.driver import bind_primitives
from gaitc.ros.graph import Graph, wait_until
from gaitc.ros.node import ControllerNode, NodeOptions
from gaitc.ros.recorder import Recorder
from gaitc.ros.recording import Recording, write_run
from gaitc.ros.robot import RobotNode, RobotOptions
from gaitc.ros.topics import DIAGNOSTICS, GAIT, TOPICS, Flow, present, require
from gaitc.search.primitives import resolve_primitive
from gaitc.sim.events import plan
from gaitc.sim.monitor import Monitor
from gaitc.sim.replay import RunEnvironment
from gaitc.sim.run import checked_steps
from gaitc.sim.scenario import ScriptedEnvironment
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from gaitc.gaitgraph.pairing import ValveSequence
    from gaitc.ir.controller import Controller
    from gaitc.ros.node import NodeOptions
    from gaitc.sim.run import Run
    from gaitc.solver.progress import Progress

#: How long (s) the nodes of one command may take to see each other.
CONNECT = 15.0
#: The watchdog (s) beside a simulated robot: its copy of the controller solves the recovery
#: games of a surprise before it senses, which may take seconds.
SIM_WATCHDOG = 60.0

__all__ = ["SIM_WATCHDOG", "RosOptions", "RosRun", "SimulatedRobot", "record_run",
           "require_ros", "ros"]


@dataclass(frozen=True)
class SimulatedRobot:
    """The simulated robot node of ``gaitc ros --sim``: the environment it plays (as
    ``simulate --env``: random with ``seed``, adversarial, or scripted with its file), the
    events it performs whatever the assumptions say (``"12:fail L5"``), and the steps (50,
    or a scenario's or run file's length)."""

    env: EnvironmentLike = EnvironmentKind.RANDOM
    seed: int = 0
    violate: Sequence[str] = ()
    steps: int | None = None


@dataclass(frozen=True)
class RosOptions:
    """How :func:`ros` runs the node: after an input that breaks an assumption, recover or
    stop (``on_surprise``, with the recovery games' ``semantics``); the /diagnostics
    heartbeat ``rate`` (Hz), the ``watchdog`` (s without an observation; None: 2, or 60
    beside a simulated robot, whose copy of the controller solves the recovery games of a
    surprise before it senses) and the largest age
    of a stamp (``stale_after``, s); the steps to run without a simulated robot (None: until
    stopped); the ROS arguments (``-r gait:=/robot/gait``, ``-p watchdog:=5.0``); an MCAP
    file to ``record`` every topic into; the spec's ``encoding`` (default: the controller
    file's); the ``robot`` file the gaits' valve primitives are read from (default: the one
    each primitive names)."""

    on_surprise: SurprisePolicy | str = SurprisePolicy.RECOVER
    semantics: Semantics | str = Semantics.DEFAULT
    rate: float = 1.0
    watchdog: float | None = None
    stale_after: float = 1.0
    steps: int | None = None
    ros_args: Sequence[str] = ()
    record: str | Path | None = None
    encoding: EncodingName | str | None = None
    robot: str | Path | None = None


@dataclass
class RosRun:
    """What :func:`ros` ran: the controller node's run (None: the spec is unrealizable, or
    a signal stopped the node outside its wait for an observation), why it stopped, how
    often it vented, the bad observations it reported, the simulated robot's account, the
    recording and its message counts by topic."""

    spec: str
    run: Run | None
    full_health: dict[str, int] = field(default_factory=dict)
    stopped: str = ""
    vents: int = 0
    faults: tuple[str, ...] = ()
    interrupted: str = ""
    robot: str = ""
    recording: str | None = None
    recorded: dict[str, int] = field(default_factory=dict)
    robot_error: GaitcError | None = None


def _loaded(spec: Spec | str | Path, controller: Controller | str | Path | ControllerFile | None,
            encoding: EncodingName | str | None) -> Spec:
    """``spec`` loaded with ``encoding``, else the one the controller file records."""
    if isinstance(spec, Spec):
        return spec
    recorded = (recorded_encoding(controller)
                if isinstance(controller, (str, Path, ControllerFile)) else None)
    return load(spec, encoding or recorded or EncodingName.ONEHOT)


def _primitives(checked: Spec, robot_file: str | Path | None = None
                ) -> dict[str, ValveSequence] | None:
    """The gaits' valve sequences when the spec binds any (then all must be bound, as
    ``drive`` needs), else None; a primitive that names a robot file reads ``robot_file``
    instead when one is given."""


    model = checked.robot
    if not any(g.primitive is not None for g in model.gaits):
        if robot_file is not None:
            raise UsageError(f"--robot {robot_file}: no gait of '{checked.path}' binds a "
                             "valve primitive, so no robot file is read")
        return None
    if robot_file is None:
        return bind_primitives(model, str(Path(checked.path).parent), resolve_primitive)
    chosen = Path(robot_file).resolve()
    if not chosen.is_file():
        raise UsageError(f"--robot {robot_file}: no such robot file")

    def resolve(gait: Any, spec_dir: str, legs: Sequence[str] | None = None) -> ValveSequence:
        prim = gait.primitive
        if prim is not None and prim.robot is not None:
            gait = dataclasses.replace(gait, primitive=dataclasses.replace(
                prim, robot=str(chosen)))
        return resolve_primitive(gait, spec_dir, legs)

    return bind_primitives(model, str(Path(checked.path).parent), resolve)


def ros(spec: Spec | str | Path,
        controller: Controller | str | Path | ControllerFile | None = None,
        options: RosOptions | None = None, robot: SimulatedRobot | None = None,
        progress: Progress | None = None) -> RosRun:
    """Run ``controller`` (synthesized first when None) of the ``.gait`` ``spec`` as a ROS 2
    node until its steps are done, a bad observation, the watchdog or a signal stops it
    (every valve vented then); with ``robot``, a simulated robot node beside it plays the
    environment over the topics for the robot's steps.  Every topic goes to
    ``options.record`` (MCAP) when given."""

    require_ros()
    opts = options or RosOptions()
    policy = SurprisePolicy.parse(opts.on_surprise, "--on-surprise")
    semantics = Semantics.parse(opts.semantics)
    controller = read_once(controller)
    checked = _loaded(spec, controller, opts.encoding)
    if checked.model is None:
        raise UsageError(f"'{checked.path}': 'gaitc ros' needs a .gait spec, which says what "
                         "the variables mean (legs, hazards, gaits, regions)")
    primitives = _primitives(checked, opts.robot)  # before synthesis: a wrong file fails fast
    bound = session(checked, controller, semantics=semantics)
    if bound is None:
        return RosRun(checked.path, None, stopped="unrealizable: no controller to run")
    if bound.strategy.kind == ControllerKind.COUNTERSTRATEGY:
        raise UsageError("CONTROLLER is a counter-strategy (the environment's strategy, from "
                         "'gaitc counter'); 'gaitc ros' runs a controller of the robot")
    steps = opts.steps
    planned: dict[int, Any] = {}
    chosen = None
    if robot is not None:

        chosen, steps = _robot_environment(robot, bound)
        planned = plan(robot.violate, bound.domain)
        late = sorted(k for k in planned if k > steps)
        if late:
            raise UsageError(f"--violate '{late[0]}:{planned[late[0]].words}': the run has "
                             f"{steps} steps, so step {late[0]} never comes; give --steps "
                             f"{late[-1]} or more")
    elif steps is not None:
        checked_steps(steps, "--steps")
    watchdog = opts.watchdog if opts.watchdog is not None else (
        SIM_WATCHDOG if chosen is not None else NodeOptions.watchdog)
    node_options = NodeOptions(on_surprise=policy, semantics=semantics, rate=opts.rate,
                               watchdog=watchdog, stale_after=opts.stale_after,
                               steps=steps).checked()
    return _run_graph(_Plan(checked, bound, primitives, node_options, chosen, planned,
                            str(controller) if isinstance(controller, (str, Path)) else ""),
                      opts)


def _robot_environment(robot: SimulatedRobot, bound: Session) -> tuple[Any, int]:
    """The simulated robot's environment and the steps it plays (as ``simulate``'s)."""

    chosen = environment(opponent(robot.env), bound, robot.seed)
    steps = robot.steps
    if steps is None:
        steps = (len(chosen.scenario.steps) if isinstance(chosen, ScriptedEnvironment)
                 else chosen.length if isinstance(chosen, RunEnvironment) else DEFAULT_STEPS)
    return chosen, checked_steps(steps, "--steps")


@dataclass(frozen=True)
class _Plan:
    """What :func:`ros` runs: the spec and its session, the gaits' valves, the node's
    options, the simulated robot's environment and planned events (None: no robot), the
    controller file's name."""

    checked: Spec
    bound: Session
    primitives: dict[str, ValveSequence] | None
    node: NodeOptions
    chosen: Any
    planned: dict[int, Any]
    controller: str


def _run_graph(plan: _Plan, opts: RosOptions) -> RosRun:






    checked, bound, primitives, chosen = plan.checked, plan.bound, plan.primitives, plan.chosen
    steps = plan.node.steps
    domain = bound.domain
    topics = present(TOPICS, bool(domain.hazard_regions), primitives is not None)
    recording = Recording(opts.record) if opts.record is not None else None
    result = RosRun(checked.path, None, dict(bound.domain.full),
                    recording=None if opts.record is None else str(opts.record))
    try:
        with Graph(opts.ros_args) as graph:
            recorder = Recorder(graph, topics, recording) if recording is not None else None
            node = ControllerNode(graph, bound.strategy, domain, bound.monitor, primitives,
                                  plan.node, spec_file=checked.path,
                                  controller_file=plan.controller)
            thread = None
            robot_node = None
            if chosen is not None:
                robot_node = RobotNode(graph, bound.strategy, domain, bound.monitor, chosen,
                                       RobotOptions(plan.planned, node.games,
                                                    node.options.on_surprise,
                                                    node.options.semantics,
                                                    wait=node.options.watchdog),
                                       checked.path)
            # every publisher and subscriber of this command matched before the first
            # message (a real robot's may come later), so that the recording misses none
            ours = [t for t in topics if robot_node is not None
                    or t.flow is not Flow.OBSERVATION]
            wanted = {node.node.resolve_topic_name(t.name): 1 for t in ours}
            readers = _readers(node, robot_node, recording is not None)
            if not wait_until(lambda: (recorder is None or recorder.connected(wanted)) and all(
                    p.get_subscription_count() >= n for p, n in readers), CONNECT):
                raise HardwareError(f"the nodes of this command did not see each other in "
                                    f"{CONNECT:g} s")
            if robot_node is not None:
                assert steps is not None
                thread = _start(robot_node, steps, result)
            with node.signals():
                result.run = node.run()
            if thread is not None:
                thread.join(timeout=node.options.watchdog + 1.0)
            if robot_node is not None:
                result.robot = robot_node.note
            if recorder is not None:
                expected = {node.node.resolve_topic_name(t): n for t, n in node.sent.items()}
                if robot_node is not None:
                    for topic, count in robot_node.sent.items():
                        resolved = node.node.resolve_topic_name(topic)
                        expected[resolved] = expected.get(resolved, 0) + count
                recorder.settle(expected)
                result.recorded = dict(recording.counts) if recording is not None else {}
            result.vents, result.faults = node.vents, tuple(node.faults)
            result.interrupted = node.interrupted
            result.stopped = node.status.message
    finally:
        if recording is not None:
            recording.close()
    return result


def _readers(node: Any, robot: Any, recorded: bool) -> list[tuple[Any, int]]:
    """Each publisher of the command's nodes and how many of its subscribers it must see:
    the recorder's, the robot's (gait, /diagnostics) and the node's (the observations)."""

    found = [(publisher, int(recorded) + int(robot is not None
                                             and topic in (GAIT.name, DIAGNOSTICS.name)))
             for topic, publisher in node.publishers.items()]
    if robot is not None:
        found += [(publisher, 1 + int(recorded)) for publisher in (robot.health, robot.hazards)
                  if publisher is not None]
    return found


def _start(robot: Any, steps: int, result: RosRun) -> threading.Thread:
    def play() -> None:
        try:
            robot.run(steps)
        except GaitcError as err:
            result.robot_error = err
            robot.note = f"the simulated robot stopped: {err.message}"

    thread = threading.Thread(target=play, name="gaitc-sim-robot", daemon=True)
    thread.start()
    return thread


def require_ros() -> None:
    """A :class:`UsageError` naming the ``ros`` extra when ROS 2 or mcap is missing."""

    require()


def record_run(run: Run, spec: Spec | Session | str | Path, path: str | Path,
               controller: str | Path | None = None, period: float = 1.0, *,
               encoding: EncodingName | str | None = None) -> dict[str, int]:
    """Write ``run`` (of ``spec``; a path is loaded with ``encoding``, else the one the
    ``controller`` file records) to the MCAP file ``path`` with the topics and messages
    ``gaitc ros`` publishes, step k at (k + 1) * ``period`` s (so the same run gives the
    same file); returns the messages written by topic."""

    require_ros()
    if isinstance(spec, Session):
        checked = spec.spec
    elif isinstance(spec, Spec):
        checked = spec
    else:
        checked = load(spec, encoding or (recorded_encoding(controller) if controller
                                          is not None else None) or EncodingName.ONEHOT)
    return write_run(run, checked.robot, Monitor(checked.gr1), _primitives(checked),
                     checked.path, path, period)
