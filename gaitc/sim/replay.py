"""Replaying a run file: the recorded moves of one side, played again step by step.

A run file (``simulate --out``, ``explain --out``, a play saved by ``gaitc play``) records
every variable's value at every step. Against a controller, :class:`RunEnvironment` asks
for the recorded inputs of each step (``simulate --env scripted RUN.jsonl``);
:func:`recorded_play` replays both sides as recorded, every step checked against the spec
(a play of an unrealizable spec, such as ``explain``'s, which its environment plays from a
counter-strategy of the assumptions it needs). A run of another robot, or a step the
controller cannot follow, is an error at the run file's line.
"""

from __future__ import annotations

from collections.abc import Sequence

from gaitc.diagnostics import ScenarioError, Span
from gaitc.sim.domain import Domain
from gaitc.sim.environments import Environment, Request, Situation
from gaitc.sim.monitor import Monitor
from gaitc.sim.run import Run

HINT = ("replay a run of this spec: one saved by 'gaitc play', 'gaitc simulate --out' or "
        "'gaitc explain --out'")


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


def recorded_play(run: Run, domain: Domain, monitor: Monitor, spec_file: str = "") -> Run:
    """``run``'s steps played again as recorded (both sides), decoded and checked by
    ``monitor`` step by step, as a simulated run is."""
    from gaitc.sim.simulator import Simulator
    from gaitc.sim.strategy import Strategy

    check_robot(run, domain.legs)
    inputs = monitor.inputs
    variables = inputs + tuple(v for v in monitor.variables if v not in inputs)
    values = tuple(recorded(run, i, variables) for i in range(len(run.steps)))
    count = len(values)
    path = Strategy(variables=variables, n_inputs=len(inputs), values=values,
                    successors=tuple((i + 1,) if i + 1 < count else () for i in range(count)),
                    ranks=(0,) * count, initial=(0,) if count else (), file=run.file)
    return Simulator(path, domain, monitor).replay(range(count), spec_file,
                                                    f"recorded {run.file or 'run'}")
