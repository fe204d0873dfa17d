"""Where the searches' predicted motions come from: the chapter 2 kinematic gait graph, or
the gait graph of a chapter 4 model (thesis 4.2.2) where the robot file has one.

The model graph's poses are valve states (each at its steady state), every ordered pair of
them a transition with the body-frame motion the model simulates for one control period;
:func:`model_transitions` turns it into the :class:`TransitionModel` the searches take.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import yaml

from gaitc.models.catalogue import load_model
from gaitc.models.gait_graph import ModelGraph, build_graph, valve_states, valve_text
from gaitc.models.motion import LoadedModel
from gaitc.search.transitions import TransitionModel

PREDICTIONS = ("kinematic", "model")
MODEL = "spring-damper"  # the one chapter 4 model a robot file can carry so far


def has_model(path: str | Path) -> bool:
    """Whether the robot file has a ``model: spring_damper:`` section (read loosely; the
    model's own reader reports what is wrong with it)."""
    try:
        data = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, yaml.YAMLError):
        return False
    section = data.get("model") if isinstance(data, dict) else None
    return isinstance(section, dict) and "spring_damper" in section


@dataclass(frozen=True)
class ModelPredictions:
    """A chapter 4 model, its gait graph and that graph as searchable transitions."""

    loaded: LoadedModel
    graph: ModelGraph
    model: TransitionModel
    start: int  # the all-vented valve state


def model_transitions(path: str | Path, max_open: int = 1) -> ModelPredictions:
    """The spring-damper gait graph of the robot file over valve states with at most
    ``max_open`` valves open, as a :class:`TransitionModel` (mm, degrees; no slip)."""
    loaded = load_model(MODEL, path)
    states = valve_states(len(loaded.valve_legs), max_open)
    graph = build_graph(loaded.model, states, loaded.period)
    index = {s: i for i, s in enumerate(graph.states)}
    pairs = sorted(graph.motion)
    src = np.array([index[a] for a, _ in pairs], np.int64)
    dst = np.array([index[b] for _, b in pairs], np.int64)
    motion = [graph.motion[p] for p in pairs]
    model = TransitionModel(

        poses=len(states),
        src=src,
        dst=dst,
        dx=np.array([m.x for m in motion]),
        dy=np.array([m.y for m in motion]),
        rot=np.array([math.degrees(m.theta) for m in motion]),
        slip=np.zeros(len(pairs)),
        labels=[valve_text(s) for s in graph.states],
    )
    model.groups = _groups(loaded.valve_legs)
    return ModelPredictions(loaded, graph, model, index[(False,) * len(loaded.valve_legs)])


def _groups(legs: tuple[str, ...]) -> tuple[int, ...]:
    """Valves per leg, in valve order (consecutive valves of one leg form a group)."""
    out: list[int] = []
    for i, leg in enumerate(legs):
        if i and legs[i - 1] == leg:
            out[-1] += 1
        else:
            out.append(1)
    return tuple(out)
