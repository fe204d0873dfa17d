"""The models ``gaitc`` knows by name, and the searches and runs built on them.

This is the one place a new model is registered: :data:`MODELS` maps the name the command
line takes (``--model``, ``--backend physics``) to a loader from a robot file, and
:func:`chosen_model` decides which one a search uses: the model the robot file declares,
unless the caller names one or asks for the kinematic graph (:data:`KINEMATIC`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gaitc.diagnostics import UsageError
from gaitc.gaitgraph.robot import MODEL_SECTIONS, Robot
from gaitc.models.active_passive.model import loaded_model
from gaitc.models.gait_graph import ModelGait, ModelGraph, build_graph, find_gaits, valve_states
from gaitc.models.motion import LoadedModel
from gaitc.models.spring_damper.description import load_spring_damper
from gaitc.models.spring_damper.model import SpringDamperModel


def _spring_damper(path: str | Path) -> LoadedModel:
    robot = load_spring_damper(path)
    model = SpringDamperModel(robot)
    rest = model.rest_state([(False,) * robot.valve_count])
    reach = rest.feet[0, :, :2] - rest.position[0, :2]
    length = 2000.0 * float(max(math.hypot(float(x), float(y)) for x, y in reach))
    legs = tuple(
        limb.name for limb in sorted(robot.limbs, key=lambda x: x.valves) for _ in limb.valves
    )
    return LoadedModel(model, robot.name, legs, robot.period, length)


def _active_passive(path: str | Path) -> LoadedModel:
    return loaded_model(path)


MODELS: dict[str, Callable[[str | Path], LoadedModel]] = {
    "spring-damper": _spring_damper,  # thesis 4.1.1
    "active-passive": _active_passive,  # thesis 4.1.2
}


#: ``--model kinematic``: the frictionless gait graph of chapter 2, whatever the file declares.
KINEMATIC = "kinematic"
#: What ``--model`` takes.
MODEL_CHOICES = (KINEMATIC, *sorted(MODELS))
assert set(MODELS) == set(MODEL_SECTIONS.values()), "a model section without a loader"


def chosen_model(robot: Robot, requested: str | None) -> str | None:
    """The chapter 4 model a search of ``robot`` uses (None: the kinematic graph).

    ``requested`` None lets the robot file decide (its first declared model, else the
    kinematic graph); :data:`KINEMATIC` asks for the kinematic graph; a model's name asks
    for that model, which the file must declare (its reader says where it is missing).
    """
    if requested is None:
        return robot.models[0] if robot.models else None
    if requested == KINEMATIC:
        return None
    if requested not in MODELS:
        raise UsageError(f"unknown model {requested!r}; use one of {', '.join(MODEL_CHOICES)}")
    return requested  # a file without it: the model's reader says so, with the position


def sampled_states(count: int, max_open: int, limit: int, seed: int) -> list[tuple[bool, ...]]:
    """At most ``limit`` valve states of ``count`` valves with at most ``max_open`` open:
    all of them when they are few enough, else the vented state and a seeded random sample
    of the others (the model's counterpart of thesis 2.5.1's random valve states)."""
    every = valve_states(count, max_open)
    if len(every) <= limit:
        return every
    rng = np.random.default_rng(seed)
    chosen = sorted(rng.choice(np.arange(1, len(every)), size=limit - 1, replace=False).tolist())
    return [every[0], *(every[i] for i in chosen)]


def load_model(name: str, path: str | Path) -> LoadedModel:
    """The model ``name`` of the robot file ``path`` (a KeyError for an unknown name)."""
    return MODELS[name](path)


@dataclass(frozen=True)
class ModelSearch:
    """What ``gaitc gaits --model`` found."""

    loaded: LoadedModel
    graph: ModelGraph
    gaits: list[ModelGait]


def search_gaits(
    loaded: LoadedModel, direction: tuple[float, float], max_open: int = 1,
    states: list[tuple[bool, ...]] | None = None,
) -> ModelSearch:
    """Build the model's gait graph over valve states with at most ``max_open`` valves open
    (or over ``states``; thesis 4.2.2) and search it for gaits towards ``direction`` (a
    body-frame unit vector)."""
    if states is None:
        states = valve_states(len(loaded.valve_legs), max_open)
    graph = build_graph(loaded.model, states, loaded.period)
    return ModelSearch(loaded, graph, find_gaits(graph, direction, loaded.body_length))
