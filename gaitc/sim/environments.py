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

from gaitc.ir.formula import has_primes
from gaitc.sim.adversary import DISCOUNT, harm_table
from gaitc.sim.domain import Domain, Goal, State
from gaitc.sim.monitor import Monitor
from gaitc.sim.rates import StepLaw
from gaitc.sim.strategy import InputKey, Strategy

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
    monitor: Monitor | None = None
    values: tuple[int, ...] | None = None  # spec-level values of ``node``
    successor_values: tuple[tuple[int, ...], ...] = ()  # of each move's node
    strategy: Strategy | None = None  # the whole controller, for environments that plan


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


class StochasticEnvironment(Environment):
    """Draws each next input from the rates (:class:`gaitc.sim.rates.StepLaw`, the law
    ``gaitc chances`` gives Storm); every hazard set starts off.  An input the controller
    has no answer to (a sudden failure beyond eq. 3.5) is still requested: the run then
    stops, naming the assumption it breaks."""

    def __init__(self, law: StepLaw, seed: int = 0) -> None:
        self.law = law
        self.seed = seed
        self.rng = random.Random(seed)
        self.name = f"stochastic --seed {seed}"

    def choose(self, situation: Situation) -> Request | None:
        domain = situation.domain
        here = situation.state
        if here is None:
            start = tuple((leg.name, leg.initial) for leg in domain.model.legs)
            wanted = State(domain.model.start, "noGait", start, None)
            what = "start"
        else:
            outcomes = [o for o in self.law.outcomes(here) if o.chance > 0.0]
            pick = self.rng.random()
            chosen = outcomes[-1]
            for outcome in outcomes:
                pick -= outcome.chance
                if pick < 0.0:
                    chosen = outcome
                    break
            wanted = State(here.region, here.gait, chosen.health, chosen.hazard)
            what = "a sudden failure" if chosen.breaks else "drawn from the rates"
        for move in situation.moves:
            if move.state.health == wanted.health and move.state.hazard == wanted.hazard:
                return Request(move.inputs, what)
        values = domain.encode(wanted)
        names = situation.strategy.inputs if situation.strategy is not None else \
            situation.monitor.inputs if situation.monitor is not None else ()
        if not names:
            return None
        return Request(tuple(values[name] for name in names), what)


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
    """Hostile within the assumptions, planning over the whole controller.

    Given the controller (``Situation.strategy``), it takes the move with the most harm it
    can force from there (:func:`gaitc.sim.adversary.harm_table`: health levels lost over the
    next steps, discounted, and distance from the next goal).  Ties, and every choice when
    it cannot see the controller, go to the one-step order: (1) the most health levels
    lost (every leg in use degrades, and in an active hazard fails or loses as many levels
    as the hazard wears); (2) the hazard set nearest the robot active; (3) the
    controller's answer farthest (in region transitions) from the goal the robot is
    heading for; then the smallest input valuation.
    It stays fair: when a □◇ assumption has waited ``patience`` steps, only moves that
    satisfy it are considered (the assumptions' liveness part, in turn).
    """

    name = "adversarial"

    def __init__(self, patience: int = 3, plan: bool = True) -> None:
        self.patience = patience
        self.plan = plan  # False: the one-step order alone
        self.pending = 0
        self.waiting = 0
        self._harm: tuple[Strategy, list[float]] | None = None

    def _harm_of(self, situation: Situation) -> list[float] | None:
        strategy = situation.strategy
        if strategy is None or not self.plan:
            return None
        if self._harm is None or self._harm[0] is not strategy:
            domain = situation.domain
            states = [domain.node_state(strategy, n) for n in range(len(strategy))]
            self._harm = (strategy, harm_table(strategy, domain, states))
        return self._harm[1]

    def _fair(self, situation: Situation) -> tuple[tuple[Move, ...], list[bool]]:
        monitor, here = situation.monitor, situation.values
        if monitor is None or here is None or not monitor.spec.env_liveness:
            return situation.moves, [False] * len(situation.moves)
        self.pending %= len(monitor.spec.env_liveness)
        # an unprimed □◇ clause is about the state the move leads to; a primed one about the move
        primed = has_primes(monitor.spec.env_liveness[self.pending].formula)
        meets = [self.pending in monitor.check_step(here if primed else nxt, nxt).env_live
                 for nxt in situation.successor_values]
        if self.waiting >= self.patience and any(meets):
            kept = tuple(m for m, ok in zip(situation.moves, meets, strict=True) if ok)
            return kept, [True] * len(kept)
        return situation.moves, meets

    def choose(self, situation: Situation) -> Request | None:
        if not situation.moves:
            return None
        moves, meets = self._fair(situation)
        chosen = self._worst(situation, moves)
        if meets[moves.index(chosen)]:
            self.pending, self.waiting = self.pending + 1, 0
        elif situation.values is not None:
            self.waiting += 1
        return Request(chosen.inputs)

    def _worst(self, situation: Situation, moves: tuple[Move, ...]) -> Move:
        here = situation.state
        domain = situation.domain
        region = here.region if here is not None else moves[0].state.region
        wanted = nearest_hazard(domain, region)
        goal_regions = situation.next_goal.regions if situation.next_goal is not None else ()
        harm = self._harm_of(situation)
        best: tuple[float, int, int, int] | None = None
        chosen = moves[0]
        for move in moves:
            lost = levels_lost(here, move.state) if here is not None else 0
            hazard = int(wanted is not None and move.state.hazard == wanted)
            far = domain.region_distance(move.state.region, goal_regions) if goal_regions else 0
            planned = 0.0 if harm is None else round(lost + DISCOUNT * harm[move.node], 6)
            score = (planned, lost, hazard, min(far, INFINITY))
            if best is None or score > best:
                best, chosen = score, move
        return chosen
