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

from gaitc.gaitgraph.robot import load_robot
from gaitc.models.catalogue import chosen_model, load_model
from gaitc.models.gait_graph import ModelGraph, build_graph, valve_states, valve_text
from gaitc.models.motion import LoadedModel
from gaitc.search.transitions import TransitionModel

PREDICTIONS = ("kinematic", "model")


def has_model(path: str | Path) -> bool:
    """Whether the robot file declares a chapter 4 model (read by the robot file's own
    reader, so a broken file is reported with its position)."""
    return bool(load_robot(path).models)


@dataclass(frozen=True)
class ModelPredictions:
    """A chapter 4 model, its gait graph and that graph as searchable transitions."""

    loaded: LoadedModel
    graph: ModelGraph
    model: TransitionModel
    start: int  # the all-vented valve state


def model_transitions(path: str | Path, max_open: int = 1, model: str | None = None,
                      states: list[tuple[bool, ...]] | None = None) -> ModelPredictions:
    """The gait graph of the robot file's chapter 4 model (``model``, by default the one the
    file declares first) over valve states with at most ``max_open`` valves open (or the
    given ``states``, the vented one among them), as a :class:`TransitionModel` (mm,
    degrees; no slip)."""
    # a file that declares no model: the spring-damper reader says so, at the position
    name = model or chosen_model(load_robot(path), None) or "spring-damper"
    loaded = load_model(name, path)
    if states is None:
        states = valve_states(len(loaded.valve_legs), max_open)
    graph = build_graph(loaded.model, states, loaded.period)
    index = {s: i for i, s in enumerate(graph.states)}
    return ModelPredictions(loaded, graph, graph_transitions(graph, loaded.valve_legs),
                            index[(False,) * len(loaded.valve_legs)])


def graph_transitions(graph: ModelGraph, valve_legs: tuple[str, ...]) -> TransitionModel:
    """A model's gait graph as a :class:`TransitionModel`: one pose per valve state, in the
    graph's order (mm, degrees; no slip)."""
    index = {s: i for i, s in enumerate(graph.states)}
    pairs = sorted(graph.motion)
    motion = [graph.motion[p] for p in pairs]
    transitions = TransitionModel(
        poses=len(graph.states),
        src=np.array([index[a] for a, _ in pairs], np.int64),
        dst=np.array([index[b] for _, b in pairs], np.int64),
        dx=np.array([m.x for m in motion]),
        dy=np.array([m.y for m in motion]),
        rot=np.array([math.degrees(m.theta) for m in motion]),
        slip=np.zeros(len(pairs)),
        labels=[valve_text(s) for s in graph.states],
    )
    transitions.groups = _groups(valve_legs)
    return transitions


def _groups(legs: tuple[str, ...]) -> tuple[int, ...]:
    """Valves per leg, in valve order (consecutive valves of one leg form a group)."""
    out: list[int] = []
    for i, leg in enumerate(legs):
        if i and legs[i - 1] == leg:
            out[-1] += 1
        else:
            out.append(1)
    return tuple(out)
