"""Environments that pick the robot's inputs: scripted (see scenario.py), random, adversarial.

At each step the environment sees the controller's node and the moves it offers (one per
distinct input valuation among the node's successors, Mealy semantics) and answers with a
:class:`Request`; the simulator follows it or, if the controller has no such successor,
stops and names the assumption the request breaks.
"""

from __future__ import annotations

import random
from abc import ABC, abstractmethod
from dataclasses import dataclass

from gaitsim.domain import Domain, Goal, State
from gaitsim.strategy import InputKey

INFINITY = 10**6


@dataclass(frozen=True)
class Move:
    """An input the controller accepts at a node, with the controller's answer to it."""

    inputs: InputKey
    node: int
    state: State


@dataclass(frozen=True)
class Situation:
    """What an environment sees before choosing the input of step ``step``."""

    step: int
    node: int | None  # None before the first state
    state: State | None
    moves: tuple[Move, ...]  # sorted by input values
    domain: Domain
    next_goal: Goal | None


@dataclass(frozen=True)
class Request:
    """The environment's choice: input values (in the strategy's input order) and its source."""

    inputs: InputKey
    what: str = ""  # human description, for messages
    span: object | None = None  # a Span when the request comes from a scenario file


class Environment(ABC):
    """Chooses the environment's inputs, step by step."""

    name = "environment"

    @abstractmethod
    def choose(self, situation: Situation) -> Request | None:
        """The next input, or ``None`` to end the run (a scenario that ran out of steps)."""


class RandomEnvironment(Environment):
    """Uniform among the distinct inputs the controller accepts; reproducible per seed."""

    def __init__(self, seed: int = 0) -> None:
        self.seed = seed
        self.rng = random.Random(seed)
        self.name = f"random --seed {seed}"

    def choose(self, situation: Situation) -> Request | None:
        if not situation.moves:
            return None
        move = situation.moves[self.rng.randrange(len(situation.moves))]
        return Request(move.inputs)


def levels_lost(before: State, after: State) -> int:
    """Health levels lost between two states, summed over legs."""
    now = dict(after.health)
    return sum(max(0, level - now.get(leg, level)) for leg, level in before.health)


def nearest_hazard(domain: Domain, region: str) -> str | None:
    """The hazard set with a region closest to ``region`` (declaration order breaks ties)."""
    best: tuple[int, int] | None = None
    name: str | None = None
    for order, (hazard, regions) in enumerate(domain.hazard_regions.items()):
        key = (domain.region_distance(region, regions), order)
        if regions and (best is None or key < best):
            best, name = key, hazard
    return name


class AdversarialEnvironment(Environment):
    """Hostile within the assumptions, greedily, one step ahead.

    Among the inputs the controller accepts it prefers, in this order: (1) the most health
    levels lost (every leg in use degrades, or fails in an active hazard); (2) the hazard set
    nearest the robot active; (3) the controller's answer farthest (in region transitions)
    from the goal the robot is heading for; ties go to the smallest input valuation.
    """

    name = "adversarial"

    def choose(self, situation: Situation) -> Request | None:
        if not situation.moves:
            return None
        here = situation.state
        domain = situation.domain
        region = here.region if here is not None else situation.moves[0].state.region
        wanted = nearest_hazard(domain, region)
        goal_regions = situation.next_goal.regions if situation.next_goal is not None else ()
        best: tuple[int, int, int] | None = None
        chosen = situation.moves[0]
        for move in situation.moves:
            lost = levels_lost(here, move.state) if here is not None else 0
            hazard = int(wanted is not None and move.state.hazard == wanted)
            far = domain.region_distance(move.state.region, goal_regions) if goal_regions else 0
            score = (lost, hazard, min(far, INFINITY))
            if best is None or score > best:
                best, chosen = score, move
        return Request(chosen.inputs)
