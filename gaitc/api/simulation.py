"""Simulation: a controller of a ``.gait`` spec run against an environment, step by step.

A :class:`~gaitc.sim.session.Session` binds a spec, its controller (read from a file, or
synthesized), the domain decoding of :mod:`gaitc.sim.domain` and the run monitor of
:mod:`gaitc.sim.monitor`; :func:`simulate` runs it against a random, adversarial or
scripted environment and returns a :class:`gaitc.sim.run.Run` checked against every
assumption and guarantee.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Final, TypeAlias

from gaitc.api.solving import Synthesis, counterstrategy, read_once, recorded_encoding, synthesize
from gaitc.core.changes import EXAMPLES as CHANGE_EXAMPLES
from gaitc.core.modes import EnvironmentKind, Semantics, SurprisePolicy
from gaitc.core.spec import Spec, load
from gaitc.diagnostics import UsageError
from gaitc.forms.reader import ControllerFile, load_runtime, runtime
from gaitc.ir.bddfile import SymbolicController
from gaitc.ir.controller import Controller, ControllerKind
from gaitc.sim.counterplay import play, robot_chooser
from gaitc.sim.domain import Domain
from gaitc.sim.environments import Environment
from gaitc.sim.events import plan
from gaitc.sim.monitor import Monitor
from gaitc.sim.replay import RunEnvironment, recorded_play
from gaitc.sim.run import checked_steps, read_jsonl
from gaitc.sim.scenario import Scenario, ScriptedEnvironment
from gaitc.sim.session import Opponent, Session, is_run_file
from gaitc.sim.session import environment as build_environment
from gaitc.sim.simulator import SurpriseOptions
from gaitc.sim.simulator import simulate as run_simulation
from gaitc.sim.strategy import explicit
from gaitc.solver.progress import Progress
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from gaitc.sim.run import Run
    from gaitc.sim.scenario import Scenario
    from gaitc.sim.simulator import SurpriseOptions

__all__ = ["CHANGE_EXAMPLES", "DEFAULT_STEPS", "ENVIRONMENTS", "ControllerLike",
           "EnvironmentLike", "Opponent", "Session", "Simulation", "SurprisePolicy",
           "counter_session", "environment", "is_run_file", "opponent", "run_document",
           "session", "simulate", "simulate_spec"]

#: The environments :func:`simulate` and ``gaitc simulate --env`` know by name.
ENVIRONMENTS: Final = EnvironmentKind.values()
DEFAULT_STEPS: Final = 50
#: What the facade takes as an environment: a typed :class:`Opponent`, a name of
#: :class:`EnvironmentKind` (or ``scripted:FILE``), a scenario or an environment object.
EnvironmentLike: TypeAlias = "Opponent | EnvironmentKind | str | Scenario | Environment"
#: What the facade takes as a controller: one in memory (any form, or a synthesis), or a
#: controller file, given by its path or read already (read once either way).
ControllerLike: TypeAlias = (
    "Controller | SymbolicController | Synthesis | str | Path | ControllerFile")


def session(spec: Spec | str | Path,
            controller: ControllerLike | None = None,
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
    _check_prefer(controller, prefer)
    controller = read_once(controller)
    spec = _load(spec, controller, encoding)
    if spec.model is None:
        raise UsageError(f"'{spec.path}': simulating, driving and drawing a controller need "
                         "a .gait spec, which says what the variables mean (regions, gaits, "
                         "legs); for this spec 'gaitc synth' writes a controller and 'gaitc "
                         "verify' checks it")
    if isinstance(controller, (str, Path, ControllerFile)):
        strategy = load_runtime(controller, spec)
    else:
        if controller is None:
            controller = synthesize(spec, semantics, verify=False, prefer=prefer,
                                    progress=progress)
        automaton = controller.controller if isinstance(controller, Synthesis) else controller
        if automaton is None:
            return None
        strategy = runtime(automaton, spec, "<synthesized>")
    return Session.bind(spec, strategy)


def _check_prefer(controller: object, prefer: object) -> None:
    if prefer is not None and controller is not None:
        raise UsageError("--prefer orders the moves of a controller synthesized here, but "
                         "CONTROLLER was synthesized already; give --prefer to the 'gaitc "
                         "synth' that writes it, or leave out CONTROLLER")


def _load(spec: Spec | str | Path, controller: object, encoding: EncodingName | str | None
          ) -> Spec:
    """``spec`` loaded with ``encoding``, else the one a controller file records, else
    onehot."""
    if isinstance(spec, Spec):
        return spec
    if encoding is None and isinstance(controller, (str, Path, ControllerFile)):
        encoding = recorded_encoding(controller)
    return load(spec, encoding or EncodingName.ONEHOT)


def counter_session(spec: Spec | str | Path, semantics: Semantics | str = Semantics.DEFAULT,
                    progress: Progress | None = None) -> Session | None:
    """``spec`` bound to its counter-strategy (the environment's winning strategy), for the
    adversarial environment of an unrealizable spec; None when the spec is realizable."""
    loaded = spec if isinstance(spec, Spec) else load(spec, EncodingName.ONEHOT)
    found = counterstrategy(loaded, semantics, verify=False, progress=progress)
    return None if found.controller is None else session(loaded, found, None, semantics)


def opponent(env: EnvironmentLike) -> Opponent | Scenario | Environment:
    """``env`` as a typed value: an object stays as it is, a name becomes an
    :class:`Opponent` (a :class:`UsageError` names the accepted ones)."""
    if isinstance(env, (Opponent, Scenario, Environment)):
        return env
    return Opponent.parse(env)


def environment(kind: EnvironmentLike, bound: Session, seed: int = 0) -> Environment:
    """The environment ``kind`` names for ``bound`` (:func:`gaitc.sim.session.environment`)."""
    return build_environment(opponent(kind), bound, seed)


def _recorded(spec: Spec | str | Path, file: str, steps: int | None) -> Run:
    """A run file of an unrealizable spec played again as recorded, checked step by step
    (no controller exists to answer it; see :func:`gaitc.sim.replay.recorded_play`)."""
    loaded = spec if isinstance(spec, Spec) else load(spec, EncodingName.ONEHOT)
    if loaded.model is None:
        raise UsageError(f"'{loaded.path}': replaying a run needs a .gait spec")
    recorded = read_jsonl(file)
    if steps is not None:
        recorded.steps = recorded.steps[:steps + 1]
    domain = Domain(loaded.model, loaded.encoding or EncodingName.ONEHOT)
    return recorded_play(recorded, domain, Monitor(loaded.gr1), loaded.path)


def _counter_play(bound: Session, env: Opponent | Scenario | Environment, steps: int | None,
                  seed: int) -> Run:
    """A counter-strategy plays the environment; ``env`` says how the robot answers:
    ``random`` (with ``seed``) or ``adversarial`` (it avoids forced deadlocks); with
    ``scripted:RUN.jsonl`` both sides play as the run file did (a play of an unrealizable
    spec: ``gaitc play``'s, or ``explain``'s, whose environment may come from a
    counter-strategy of fewer freedoms), every step checked against the spec."""
    if isinstance(env, Opponent) and env.replays_run:
        assert env.file is not None
        return _recorded(bound.spec, env.file, steps)
    counter = explicit(bound.strategy, "a counter-play")
    kind = env.kind if isinstance(env, Opponent) else EnvironmentKind.SCRIPTED
    choose, name = robot_chooser(kind, counter, seed)
    count = checked_steps(DEFAULT_STEPS if steps is None else steps)
    return play(counter, bound.domain, bound.monitor, count, choose, bound.spec.path, name)


@dataclass(frozen=True)
class Simulation:
    """What :func:`simulate_spec` ran: the run (None when the spec is unrealizable and no
    counter-strategy or recorded play stands in), whether a controller of the spec played
    it (False: a counter-strategy, a recorded play of an unrealizable spec, or nothing),
    each leg's number of health levels (the step table's reference) and the spec it was
    loaded as (so a caller that records or draws the run does not load it again)."""

    run: Run | None
    realizable: bool
    full_health: dict[str, int] = field(default_factory=dict)
    spec: Spec | None = field(default=None, compare=False)

    @property
    def environment(self) -> str | None:
        """Who played the environment, in words (None when nothing ran)."""
        return None if self.run is None else self.run.environment


def simulate_spec(spec: Spec | Session | str | Path,
                  controller: ControllerLike | None = None,
                  env: EnvironmentLike = EnvironmentKind.RANDOM,
                  steps: int | None = None, seed: int = 0, *,
                  encoding: EncodingName | str | None = None,
                  semantics: Semantics | str = Semantics.DEFAULT,
                  prefer: str | Sequence[str] | None = None,
                  progress: Progress | None = None,
                  violate: Sequence[str] = (),
                  on_surprise: SurprisePolicy | str = SurprisePolicy.RECOVER) -> Simulation:
    """:func:`simulate`, deciding what plays when ``spec`` is unrealizable instead of
    refusing: ``spec`` is loaded once (with ``encoding``, else the one ``controller``
    records, else onehot) and bound to ``controller`` (synthesized when None, telling
    ``progress``). Without a controller, the environment's counter-strategy plays an
    unrealizable spec against the careful robot for ``env`` adversarial, a run file
    (``scripted RUN.jsonl``) is played again as recorded, and otherwise nothing runs (the
    answer's ``run`` is None).

    ``violate`` lists events to perform whatever the assumptions say (``"12:fail L5"``,
    in the player's move words, :mod:`gaitc.sim.events`); ``on_surprise`` says whether
    a controller recovers from an input that breaks an assumption (the default, by
    :mod:`gaitc.sim.recovery`) or stops with an error.  The run's ``surprises`` list each
    event with what became of the run."""
    if isinstance(spec, Session):
        bound: Session | None = spec
        loaded = spec.spec
    else:
        _check_prefer(controller, prefer)
        controller = read_once(controller)
        loaded = _load(spec, controller, encoding)
        bound = session(loaded, controller, None, semantics, prefer, progress)
    chosen_env = opponent(env)
    if bound is None:
        if isinstance(chosen_env, Opponent) and chosen_env.replays_run:
            assert chosen_env.file is not None
            run = _recorded(loaded, chosen_env.file, steps)
            return Simulation(run, False, {leg.name: leg.health for leg in loaded.robot.legs},
                              loaded)
        if isinstance(chosen_env, Opponent) and chosen_env.kind == EnvironmentKind.ADVERSARIAL:
            bound = counter_session(loaded, semantics, progress)
        if bound is None:
            return Simulation(None, False, spec=loaded)
    if bound.strategy.kind == ControllerKind.COUNTERSTRATEGY and not violate:
        return Simulation(_counter_play(bound, chosen_env, steps, seed), False,
                          bound.full_health, loaded)
    if violate and bound.strategy.kind == ControllerKind.COUNTERSTRATEGY:
        raise UsageError("--violate makes the environment break its assumptions against a "
                         "controller; this spec is unrealizable and its counter-strategy "
                         "plays the environment")

    surprises = SurpriseOptions(plan(violate, bound.domain),
                                SurprisePolicy.parse(on_surprise, "--on-surprise"),
                                Semantics.parse(semantics))
    return Simulation(_controller_play(bound, chosen_env, steps, seed, surprises), True,
                      bound.full_health, loaded)


def _controller_play(bound: Session, env: Opponent | Scenario | Environment,
                     steps: int | None, seed: int, surprises: SurpriseOptions | None = None
                     ) -> Run:
    """A controller of the spec against ``env`` for ``steps`` steps (default 50, or the
    scenario's or run file's length)."""
    chosen = build_environment(env, bound, seed)
    if steps is None:
        steps = (len(chosen.scenario.steps) if isinstance(chosen, ScriptedEnvironment)
                 else chosen.length if isinstance(chosen, RunEnvironment) else DEFAULT_STEPS)
    checked_steps(steps)
    late = sorted(k for k in (surprises.planned if surprises is not None else {}) if k > steps)
    if late:
        assert surprises is not None
        raise UsageError(f"--violate '{late[0]}:{surprises.planned[late[0]].words}': the run "
                         f"has {steps} steps, so step {late[0]} never comes; give --steps "
                         f"{late[-1]} or more")
    return run_simulation(bound.strategy, bound.domain, bound.monitor, chosen, steps,
                          bound.spec.path, surprises)


def simulate(spec: Spec | Session | str | Path,
             controller: ControllerLike | None = None,
             env: EnvironmentLike = EnvironmentKind.RANDOM, steps: int | None = None,
             seed: int = 0, semantics: Semantics | str = Semantics.DEFAULT,
             prefer: str | Sequence[str] | None = None, *, violate: Sequence[str] = (),
             on_surprise: SurprisePolicy | str = SurprisePolicy.RECOVER) -> Run:
    """Run ``controller`` (synthesized when None) for ``spec`` against ``env`` for ``steps``
    steps (default 50, or the scenario's length) and check every step against the spec.

    A counter-strategy (``gaitc counter``) plays the environment itself; ``env`` then says
    how the robot answers (``random`` or ``adversarial``).  ``prefer``: the move
    preferences of a controller synthesized here (:func:`gaitc.synthesize`).  An
    unrealizable spec is a :class:`UsageError`, unless :func:`simulate_spec` has something
    else play it.

    >>> import gaitc
    >>> run = gaitc.simulate("specs/patrol_2x2.gait", env="adversarial", steps=6)
    >>> run.summary.guarantees_held, len(run.steps)
    (True, 7)
    """
    played = simulate_spec(spec, controller, env, steps, seed, semantics=semantics,
                           prefer=prefer, violate=violate, on_surprise=on_surprise)
    if played.run is None:
        path = spec.spec.path if isinstance(spec, Session) else (
            spec.path if isinstance(spec, Spec) else str(spec))
        raise UsageError(f"'{path}' is unrealizable: there is no controller to simulate")
    return played.run


def run_document(file: str, run: Run | None, environment: str | None, output: str | None,
                 realizable: bool = True) -> dict[str, Any]:
    """A run as ``simulate --json`` and ``drive --json`` print it (docs/json.md): the run
    (:meth:`Run.to_json`), the environment that played it, the file it was saved to, the
    error that stopped it. ``run`` is None when an unrealizable spec left nothing to run."""
    body: dict[str, Any] = {"legs": [], "steps": [], "violations": [], "summary": None,
                            "patrols": 0}
    if run is not None:
        body.update(run.to_json())
        body.pop("spec")  # the same as "file"
        body["patrols"] = run.patrols()
    stopped = None if run is None or run.error is None else run.error.to_json()
    return {**body, "file": file, "environment": environment, "realizable": realizable,
            "output": output, "error": stopped}
