"""The models ``gaitc`` knows by name, and the searches and runs built on them.

This is the one place a new model is registered: :data:`MODELS` maps the name the command
line takes (``--model``, ``--backend physics``) to a loader from a robot file.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from gaitc.models.gait_graph import ModelGait, ModelGraph, build_graph, find_gaits, valve_states
from gaitc.models.motion import LoadedModel


def _spring_damper(path: str | Path) -> LoadedModel:
    from gaitc.models.spring_damper.description import load_spring_damper
    from gaitc.models.spring_damper.model import SpringDamperModel

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
    from gaitc.models.active_passive.model import loaded_model

    return loaded_model(path)


MODELS: dict[str, Callable[[str | Path], LoadedModel]] = {
    "spring-damper": _spring_damper,  # thesis 4.1.1
    "active-passive": _active_passive,  # thesis 4.1.2
}


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
    loaded: LoadedModel, direction: tuple[float, float], max_open: int = 1
) -> ModelSearch:
    """Build the model's gait graph over valve states with at most ``max_open`` valves open
    (thesis 4.2.2) and search it for gaits towards ``direction`` (a body-frame unit vector)."""
    states = valve_states(len(loaded.valve_legs), max_open)
    graph = build_graph(loaded.model, states, loaded.period)
    return ModelSearch(loaded, graph, find_gaits(graph, direction, loaded.body_length))
