"""Replaying a run file: the recorded moves of one side, played again step by step.

A run file (``simulate --out``, ``explain --out``, a play saved by ``gaitc play``) records
every variable's value at every step. Against a controller, :class:`RunEnvironment` asks
for the recorded inputs of each step (``simulate --env scripted RUN.jsonl``); against a
counter-strategy, :func:`run_chooser` picks the recorded answer of the robot. A run of
another robot, or a step the controller cannot follow, is an error at the run file's line.
"""

from __future__ import annotations

from collections.abc import Sequence

from gaitc.diagnostics import ScenarioError, Span
from gaitc.sim.counterplay import Chooser
from gaitc.sim.environments import Environment, Request, Situation
from gaitc.sim.run import Run
from gaitc.sim.view import StrategyView

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


def run_chooser(run: Run, strategy: StrategyView, legs: Sequence[str]) -> Chooser:
    """A robot that answers a counter-strategy as ``run`` did, step by step."""
    check_robot(run, legs)

    def choose(path: Sequence[int], options: Sequence[int]) -> int:
        index = len(path)
        wanted = recorded(run, index, strategy.variables)
        for k, node in enumerate(options):
            if strategy.values[node] == wanted:
                return k
        raise ScenarioError(f"step {index} of the run cannot be played here: the "
                            "counter-strategy has no such move", step_span(run, index),
                            "the run was played against another counter-strategy or spec")

    return choose
