"""Replaying a play or a run file against a controller or a counter-strategy, every step
checked by the run monitor.

:func:`replay` makes the :class:`~gaitc.sim.run.Run` of a play (the nodes of a
:class:`gaitc.sim.play.Play`, or of a play stepped by hand): each state decoded, each move
checked against the spec's clauses by :class:`~gaitc.sim.monitor.Monitor`.

A run file (``simulate --out``, ``explain --out``, a play saved by ``gaitc play``) records
every variable's value at every step. Against a controller, :class:`RunEnvironment` asks
for the recorded inputs of each step (``simulate --env scripted RUN.jsonl``);
:func:`recorded_play` replays both sides as recorded, every step checked against the spec
(a play of an unrealizable spec, such as ``explain``'s, which its environment plays from a
counter-strategy of the assumptions it needs); :func:`follow` finds the nodes of a
controller or counter-strategy that play a run file's steps again (``gaitc play --from``).
A run of another robot, or a step the controller cannot follow, is an error at the run
file's line.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import replace as replaced

from gaitc.diagnostics import ScenarioError, Span, UsageError
from gaitc.sim.domain import Domain
from gaitc.sim.environments import Environment, Request, Situation
from gaitc.sim.monitor import Monitor
from gaitc.sim.run import Run, Step
from gaitc.sim.simulator import Simulator, Verdicts
from gaitc.sim.strategy import Strategy

HINT = ("replay a run of this spec: one saved by 'gaitc play', 'gaitc simulate --out' or "
        "'gaitc explain --out'")


def replay(sim: Simulator, path: Sequence[int], spec_file: str = "", environment: str = "",
           stopped: str | None = None) -> Run:
    """The run that visits the nodes ``path`` of ``sim``'s controller in order, every step
    checked by its monitor (a counter-strategy's play, or a play chosen by hand);
    ``stopped`` says why it ended early."""
    run = Run(legs=sim.domain.legs, environment=environment, spec_file=spec_file,
              model=sim.domain.model)
    verdicts = Verdicts()
    previous: Step | None = None
    values = sim.strategy.values
    for index, node in enumerate(path):
        sim.observe(verdicts, index, None if previous is None else values[previous.node],
                    values[node])
        previous = sim.step(index, node, previous)
        run.add(previous)
    summary = sim.summarize(run, verdicts)
    run.summary = summary if stopped is None else replaced(summary, stopped=stopped)
    return run


def step_span(run: Run, index: int) -> Span:
    """Where step ``index`` of ``run`` is in its file."""
    line = run.lines[index] if index < len(run.lines) else 1
    return Span(run.file or "<run>", line, 1)


def check_robot(run: Run, legs: Sequence[str]) -> None:
    """A run of a robot with other legs is an error at the file's first line."""
    if tuple(run.legs) != tuple(legs):
        raise ScenarioError(
            f"the run is of a robot with legs {', '.join(run.legs) or '(none)'}, but this "
            f"spec's robot has {', '.join(legs)}", Span(run.file or "<run>", 1, 1), HINT)


def recorded(run: Run, index: int, names: Sequence[str]) -> tuple[int, ...]:
    """The values of ``names`` at step ``index`` of ``run``, in that order."""
    values = dict(run.steps[index].values)
    for name in names:
        if name not in values:
            raise ScenarioError(f"step {index} gives no value for '{name}': the run was "
                                "written for another spec", step_span(run, index), HINT)
    return tuple(values[name] for name in names)


class RunEnvironment(Environment):
    """The inputs of a run file, step by step; the run ends after its last step."""

    def __init__(self, run: Run, inputs: tuple[str, ...], legs: Sequence[str]) -> None:
        check_robot(run, legs)
        self.run = run
        self.inputs = inputs
        self.name = f"scripted {run.file or 'run'}"

    @property
    def length(self) -> int:
        """The number of moves the run makes (its steps after the first)."""
        return max(0, len(self.run.steps) - 1)

    def choose(self, situation: Situation) -> Request | None:
        index = situation.step
        if index >= len(self.run.steps):
            return None
        return Request(recorded(self.run, index, self.inputs), f"step {index} of the run",
                       step_span(self.run, index))


def last_step(run: Run, legs: Sequence[str], at: int | None) -> int:
    """The last step of ``run`` to play again: ``at``, by default its last; a run of
    another robot or a step it does not have is an error."""
    check_robot(run, legs)
    last = len(run.steps) - 1 if at is None else at
    if not 0 <= last < len(run.steps):
        raise UsageError(f"step {at} is not in {run.file or 'the run'}; it has steps "
                         f"0..{len(run.steps) - 1}")
    return last


def follow(run: Run, last: int, names: Sequence[str],
           options: Callable[[int | None], Sequence[int]], key: Callable[[int], tuple[int, ...]],
           refused: str) -> Iterator[int]:
    """The nodes that play steps ``0..last`` of ``run`` again, one at a time: at each step
    the first of the ``options`` after the node before (None at the first) whose ``key``
    is the run's values of ``names``; a step no option plays is an error at its line
    (``refused`` says why)."""
    node: int | None = None
    for index in range(last + 1):
        wanted = recorded(run, index, names)
        node = next((n for n in options(node) if key(n) == wanted), None)
        if node is None:
            raise ScenarioError(f"step {index} of the run cannot be played here: {refused}",
                                step_span(run, index),
                                "the run was played against another controller or spec")
        yield node


def recorded_play(run: Run, domain: Domain, monitor: Monitor, spec_file: str = "") -> Run:
    """``run``'s steps played again as recorded (both sides), decoded and checked by
    ``monitor`` step by step, as a simulated run is."""
    check_robot(run, domain.legs)
    inputs = monitor.inputs
    variables = inputs + tuple(v for v in monitor.variables if v not in inputs)
    values = tuple(recorded(run, i, variables) for i in range(len(run.steps)))
    count = len(values)
    path = Strategy(variables=variables, n_inputs=len(inputs), values=values,
                    successors=tuple((i + 1,) if i + 1 < count else () for i in range(count)),
                    ranks=(0,) * count, initial=(0,) if count else (), file=run.file)
    return replay(Simulator(path, domain, monitor), range(count), spec_file,
                  f"recorded {run.file or 'run'}")
