"""Learning a gait on a robot (``gaitc learn``): plan in the global frame, run, measure,
repair the plan, until every transition of the gait has been executed.

Thesis chapter 5, Algorithms 2 and 3: the first plan comes from the chapter 4 model's gait
graph (or the chapter 2 graph), each measured transition updates the search (LPA* repairs,
MCTS prunes), and the loop ends when the gait's every transition was executed
(:func:`gaitc.search.online.learn_gait`). The backend is the simulated robot with a seeded
mismatch, or the robot file's spring-damper model.
"""

from __future__ import annotations

import html
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gaitc.api.gaits import GlobalSearch
from gaitc.core.modes import BackendKind, SearchMethod
from gaitc.diagnostics import UsageError
from gaitc.diagnostics.files import write_atomically
from gaitc.search.online import learn_gait
from gaitc.search.registry import goal_search
from gaitc.search.walker import Mismatch

if TYPE_CHECKING:
    from gaitc.search.goals import Goal
    from gaitc.search.online import Learned


#: Where :func:`learn` runs its gaits (the backends of ``drive``; the serial board cannot
#: learn, for it measures no displacement).
LearningBackend = BackendKind


@dataclass(frozen=True)
class LearnOptions:
    """How :func:`learn` searches and what it runs on.

    ``method`` is a chapter 5 search (:class:`SearchMethod` astar, lpa, dstar or mcts, a
    :class:`~gaitc.search.registry.GoalSearch` in the registry); ``predictions`` where the
    predicted motions come from (``model``, the default when the robot file has one, or
    ``kinematic``), with valve states of at most ``max_open`` open valves; the simulated
    robot's ``mismatch`` (relative error of its transitions), ``noise`` (mm and degrees per
    execution) and ``infeasible`` share of transitions; the physics backend's
    ``model_mismatch`` (limb stiffness and friction scaled within 1 +- F); ``grow`` adds
    valve states when removals leave no gait; ``max_iterations`` of the loop and ``verify``
    cycles of the final gait.
    """

    method: SearchMethod | str = SearchMethod.LPA
    backend: LearningBackend | str = LearningBackend.SIM
    predictions: str | None = None
    max_open: int = 1
    seed: int = 0
    max_states: int = 10_000
    mismatch: float = 0.2
    noise: float = 0.2
    model_mismatch: float = 0.0
    infeasible: float = 0.0
    grow: bool = False
    max_iterations: int = 40
    verify: int = 5
    search: GlobalSearch = field(default_factory=GlobalSearch)


@dataclass(frozen=True)
class Learning:
    """What :func:`learn` found: the loop's record and the goal it aimed at."""

    learned: Learned
    goal: Goal

    @property
    def converged(self) -> bool:
        """The loop converged and the learned gait was executed."""
        return self.learned.converged and self.learned.error is not None

    @property
    def notes(self) -> tuple[str, ...]:
        error = self.learned.error
        if error is not None and error[0] > self.goal.tolerance:
            return (f"the executed displacement misses the goal's tolerance "
                    f"({self.goal.tolerance:g} mm): the measurements are noisy; raise "
                    "--verify or loosen --tolerance",)
        return ()

    def __str__(self) -> str:
        return "\n".join([self.learned.summary(), *self.notes])

    def _repr_html_(self) -> str:
        return self.learned._repr_svg_() + f"<pre>{html.escape(str(self))}</pre>"

    def to_json(self) -> dict[str, Any]:
        data: dict[str, Any] = json.loads(self.learned.to_json())
        return data

    def save_log(self, path: str | Path) -> None:
        """Every iteration as JSON."""
        write_atomically(path, self.learned.to_json())

    def draw(self, path: str | Path) -> None:
        """The search and the runs as one SVG file."""
        write_atomically(path, self.learned._repr_svg_())


def learn(robot: str | Path, options: LearnOptions | None = None,
          progress: Callable[[str], None] | None = None) -> Learning:
    """Learn a gait of the robot file ``robot`` toward ``options.search.goal`` (see the
    module's docstring); ``progress`` receives one line per iteration."""
    opts = options or LearnOptions()
    method = goal_search(opts.method).method
    backend = _backend(opts.backend)
    if opts.mismatch < 0 or opts.noise < 0 or not 0 <= opts.infeasible < 1:
        raise UsageError(
            "--mismatch and --noise must not be negative, --infeasible must lie in [0, 1)")
    if opts.max_iterations < 1 or opts.verify < 1:
        raise UsageError("--max-iterations and --verify must be at least 1")
    if opts.max_states < 1:
        raise UsageError("--max-states must be at least 1")
    goal, settings = opts.search.target(method), opts.search.settings(opts.seed)
    mismatch = Mismatch(opts.mismatch, opts.noise, opts.infeasible, opts.seed,
                        opts.model_mismatch)
    learned = learn_gait(
        robot=str(robot),
        goal=goal,
        method=method,
        mismatch=mismatch,
        settings=settings,
        max_states=opts.max_states,
        max_iterations=opts.max_iterations,
        verify=opts.verify,
        progress=progress,
        backend=backend,
        predictions=opts.predictions,
        max_open=opts.max_open,
        grow=opts.grow,
    )
    return Learning(learned, goal)


def _backend(value: LearningBackend | str) -> LearningBackend:
    if value not in BackendKind.values():
        raise UsageError(f"unknown backend {value!r}; use sim or physics")
    backend = BackendKind.parse(value)
    if backend is LearningBackend.SERIAL:
        raise UsageError(
            "--backend serial is not available for learning: the valve board reports no "
            "displacement of a transition (the chapter 4 EKF is not in gaitc); use --backend "
            "sim or physics")
    return backend
