"""Simulation: a controller of a ``.gait`` spec run against an environment, step by step.

A :class:`Session` binds a spec, its controller (read from a file, or synthesized), the
domain decoding of :mod:`gaitc.sim.domain` and the run monitor of :mod:`gaitc.sim.monitor`;
:func:`simulate` runs it against a random, adversarial or scripted environment and returns
a :class:`gaitc.sim.run.Run` checked against every assumption and guarantee.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Final

from gaitc.api.solving import Synthesis, recorded_encoding, synthesize
from gaitc.core.spec import Spec, load
from gaitc.diagnostics import UsageError
from gaitc.forms.reader import load_runtime, runtime
from gaitc.ir.bddfile import SymbolicController
from gaitc.ir.controller import Controller
from gaitc.ir.spec import Semantics
from gaitc.sim.domain import Domain
from gaitc.sim.environments import AdversarialEnvironment, Environment, RandomEnvironment
from gaitc.sim.monitor import Monitor
from gaitc.sim.strategy import StrategyView, explicit
from gaitc.solver.progress import Progress
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from gaitc.sim.run import Run
    from gaitc.sim.scenario import Scenario
    from ltlcompiler.model import Model

#: The environments :func:`simulate` and ``gaitc simulate --env`` know by name.
ENVIRONMENTS: Final = ("scripted", "random", "adversarial")
DEFAULT_STEPS: Final = 50


@dataclass(frozen=True)
class Session:
    """A ``.gait`` spec with its model, a controller adapted to it, and the run checker."""

    spec: Spec
    model: Model = field(repr=False)
    strategy: StrategyView = field(repr=False)
    domain: Domain = field(repr=False)
    monitor: Monitor = field(repr=False)

    @property
    def full_health(self) -> dict[str, int]:
        """Each leg's number of health levels (the table's reference for marks)."""
        return {leg.name: leg.health for leg in self.model.legs}

    def __repr__(self) -> str:
        return (f"<gaitc.Session {self.spec.path!r}: controller of {len(self.strategy)} "
                f"nodes, {len(self.model.legs)} legs>")


def session(spec: Spec | str | Path,
            controller: Controller | SymbolicController | Synthesis | str | Path | None = None,
            encoding: EncodingName | str | None = None,
            semantics: Semantics | str = Semantics.DEFAULT,
            prefer: str | Sequence[str] | None = None,
            progress: Progress | None = None) -> Session | None:
    """Bind ``spec`` (a ``.gait`` :class:`Spec` or path) to ``controller`` (an automaton, a
    :class:`Synthesis` or a controller file); synthesize one when ``controller`` is None
    (with the move preferences ``prefer``, telling ``progress``; see
    :func:`gaitc.synthesize`).

    A path is loaded with ``encoding``, else the encoding the controller file records, else
    onehot. Returns None when no controller was given and the spec is unrealizable.
    ``prefer`` with a given controller is a :class:`UsageError`: its moves are chosen already.
    """
    if prefer is not None and controller is not None:
        raise UsageError("--prefer orders the moves of a controller synthesized here, but "
                         "CONTROLLER was synthesized already; give --prefer to the 'gaitc "
                         "synth' that writes it, or leave out CONTROLLER")
    if not isinstance(spec, Spec):
        if encoding is None and isinstance(controller, (str, Path)):
            encoding = recorded_encoding(controller)
        spec = load(spec, encoding or EncodingName.ONEHOT)
    if spec.model is None:
        raise UsageError(f"'{spec.path}': simulating, driving and drawing a controller need "
                         "a .gait spec, which says what the variables mean (regions, gaits, "
                         "legs); for this spec 'gaitc synth' writes a controller and 'gaitc "
                         "verify' checks it")
    if isinstance(controller, (str, Path)):
        strategy = load_runtime(controller, spec)
    else:
        if controller is None:
            controller = synthesize(spec, semantics, verify=False, prefer=prefer,
                                    progress=progress)
        automaton = controller.controller if isinstance(controller, Synthesis) else controller
        if automaton is None:
            return None
        strategy = runtime(automaton, spec, "<synthesized>")
    domain = Domain(spec.model, spec.encoding or EncodingName.ONEHOT)
    return Session(spec, spec.model, strategy, domain, Monitor(spec.gr1))


def counter_session(spec: Spec | str | Path, semantics: Semantics | str = Semantics.DEFAULT,
                    progress: Progress | None = None) -> Session | None:
    """``spec`` bound to its counter-strategy (the environment's winning strategy), for the
    adversarial environment of an unrealizable spec; None when the spec is realizable."""
    from gaitc.api.solving import counterstrategy

    loaded = spec if isinstance(spec, Spec) else load(spec, EncodingName.ONEHOT)
    found = counterstrategy(loaded, semantics, verify=False, progress=progress)
    return None if found.controller is None else session(loaded, found, None, semantics)


def environment(kind: str | Scenario | Environment, bound: Session, seed: int = 0
                ) -> Environment:
    """The environment named ``kind`` (:data:`ENVIRONMENTS`; ``scripted`` needs a scenario
    object or a path ``scripted:FILE.yaml``), or ``kind`` itself when it already is one."""
    from gaitc.sim.scenario import Scenario, ScriptedEnvironment, load_scenario

    if isinstance(kind, Environment):
        return kind
    if isinstance(kind, Scenario):
        return ScriptedEnvironment(kind, bound.strategy.inputs)
    if kind == "random":
        return RandomEnvironment(seed)
    if kind == "adversarial":
        return AdversarialEnvironment()
    if kind.startswith("scripted:"):
        file = kind.removeprefix("scripted:")
        if is_run_file(file):
            from gaitc.sim.replay import RunEnvironment
            from gaitc.sim.run import read_jsonl

            return RunEnvironment(read_jsonl(file), bound.strategy.inputs, bound.domain.legs)
        scenario = load_scenario(file, bound.model)
        return ScriptedEnvironment(scenario, bound.strategy.inputs)
    raise UsageError(f"unknown environment '{kind}'; use random, adversarial, a scenario or "
                     "'scripted:FILE.yaml'")


def is_run_file(path: str | Path) -> bool:
    """Whether a scripted environment's file is a run file (``.jsonl``, ``.json``) rather
    than a scenario (``.yaml``)."""
    return Path(path).suffix.lower() in (".jsonl", ".json")


def _recorded(spec: Spec | str | Path, file: str, steps: int | None) -> Run:
    """A run file of an unrealizable spec played again as recorded, checked step by step
    (no controller exists to answer it; see :func:`gaitc.sim.replay.recorded_play`)."""
    from gaitc.sim.replay import recorded_play
    from gaitc.sim.run import read_jsonl

    loaded = spec if isinstance(spec, Spec) else load(spec, EncodingName.ONEHOT)
    if loaded.model is None:
        raise UsageError(f"'{loaded.path}': replaying a run needs a .gait spec")
    recorded = read_jsonl(file)
    if steps is not None:
        recorded.steps = recorded.steps[:steps + 1]
    domain = Domain(loaded.model, loaded.encoding or EncodingName.ONEHOT)
    return recorded_play(recorded, domain, Monitor(loaded.gr1), loaded.path)


def _counter_play(bound: Session, env: object, steps: int | None, seed: int) -> Run:
    """A counter-strategy plays the environment; ``env`` says how the robot answers:
    ``random`` (with ``seed``) or ``adversarial`` (it avoids forced deadlocks); with
    ``scripted:RUN.jsonl`` both sides play as the run file did (a play of an unrealizable
    spec: ``gaitc play``'s, or ``explain``'s, whose environment may come from a
    counter-strategy of fewer freedoms), every step checked against the spec."""
    from gaitc.sim.counterplay import careful_chooser, play, random_chooser

    if isinstance(env, str) and env.startswith("scripted:") and is_run_file(env[9:]):
        return _recorded(bound.spec, env[9:], steps)
    counter = explicit(bound.strategy, "a counter-play")
    if env == "random":
        choose, name = random_chooser(seed), f"counter-strategy, robot random --seed {seed}"
    elif env == "adversarial":
        choose, name = careful_chooser(counter), "counter-strategy, robot careful"
    else:
        raise UsageError("a counter-strategy is the environment: choose how the robot answers "
                         "with 'random', 'adversarial' (it avoids forced deadlocks), or "
                         "replay a play with 'scripted RUN.jsonl'")
    count = DEFAULT_STEPS if steps is None else steps
    if count < 0:
        raise UsageError("the number of steps must not be negative")
    return play(counter, bound.domain, bound.monitor, count, choose, bound.spec.path, name)


def simulate(spec: Spec | Session | str | Path,
             controller: Controller | SymbolicController | Synthesis | str | Path | None = None,
             env: str | Scenario | Environment = "random", steps: int | None = None,
             seed: int = 0, semantics: Semantics | str = Semantics.DEFAULT,
             prefer: str | Sequence[str] | None = None) -> Run:
    """Run ``controller`` (synthesized when None) for ``spec`` against ``env`` for ``steps``
    steps (default 50, or the scenario's length) and check every step against the spec.

    A counter-strategy (``gaitc counter``) plays the environment itself; ``env`` then says
    how the robot answers (``random`` or ``adversarial``).  ``prefer``: the move
    preferences of a controller synthesized here (:func:`gaitc.synthesize`).

    >>> import gaitc
    >>> run = gaitc.simulate("specs/patrol_2x2.gait", env="adversarial", steps=6)
    >>> run.summary.guarantees_held, len(run.steps)
    (True, 7)
    """
    from gaitc.sim.replay import RunEnvironment
    from gaitc.sim.scenario import ScriptedEnvironment
    from gaitc.sim.simulator import simulate as run_simulation

    bound = spec if isinstance(spec, Session) else session(spec, controller, None, semantics,
                                                           prefer)
    if bound is None and isinstance(env, str) and env.startswith("scripted:") and \
            is_run_file(env[9:]) and not isinstance(spec, Session):
        return _recorded(spec, env[9:], steps)
    if bound is None and env == "adversarial" and not isinstance(spec, Session):
        bound = counter_session(spec, semantics)
    if bound is None:
        path = spec.path if isinstance(spec, Spec) else str(spec)
        raise UsageError(f"'{path}' is unrealizable: there is no controller to simulate")
    if bound.strategy.kind == "counterstrategy":
        return _counter_play(bound, env, steps, seed)
    chosen = environment(env, bound, seed)
    if steps is None:
        steps = (len(chosen.scenario.steps) if isinstance(chosen, ScriptedEnvironment)
                 else chosen.length if isinstance(chosen, RunEnvironment) else DEFAULT_STEPS)
    if steps < 0:
        raise UsageError("the number of steps must not be negative")
    return run_simulation(bound.strategy, bound.domain, bound.monitor, chosen, steps,
                          bound.spec.path)


def run_document(file: str, run: Run | None, environment: str | None, output: str | None,
                 realizable: bool = True) -> dict[str, Any]:
    """A run as ``simulate --json`` and ``drive --json`` print it (docs/json.md): the run
    (:meth:`Run.to_json`), the environment that played it, the file it was saved to, the
    error that stopped it. ``run`` is None when an unrealizable spec left nothing to run."""
    body: dict[str, Any] = {"legs": [], "steps": [], "summary": None}
    if run is not None:
        body.update(run.to_json())
        body.pop("spec")  # the same as "file"
    stopped = None if run is None or run.error is None else run.error.to_json()
    return {**body, "file": file, "environment": environment, "realizable": realizable,
            "output": output, "error": stopped}
