"""The explicit Markov model of a ``.gait`` spec under rates: the spec's state space as an MDP
(the robot's moves allowed by ρs are the choices, the environment's next inputs are drawn by
:class:`gaitc.sim.rates.StepLaw`), or as a Markov chain under one controller.

A state is what the robot sees before it moves: its region and the gait that brought it
there, the legs' levels and the active hazard the environment has just chosen (SLUGS's Mealy
turn order, :func:`ltlcompiler.lowering.lower`), and the next goal of the patrol (a patrol
visits the goals of eq. 3.7 in their order, counted from the first state, as a GR(1)
controller's rank is).  State 0 is the start, before the environment's first move; the
robot's t-th move is the model's step t + 1.  Every input the
spec's physics allow is explored (chance 0 too), so a scheduler covers them all.  The arrays
are handed to Storm by :mod:`gaitc.analysis.chances` (Kwiatkowska, Norman and Parker,
"Stochastic model checking", SFM 2007, for the product with a counter and the bounded
properties).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gaitc.diagnostics import SpecSemanticError, UsageError
from gaitc.ir.formula import Var
from gaitc.ir.roles import UserClause
from gaitc.ir.spec import GR1Spec
from gaitc.sim.domain import Domain, State
from gaitc.sim.rates import Outcome, StepLaw
from gaitc.sim.view import StrategyView
from ltlcompiler.model import NO_GAIT, Model

#: (region, levels, hazard, the next goal of the patrol); the number of goals means "a patrol
#: was completed on entering this state", and the next one starts at the first goal.  The gait
#: that brought the robot in is left out: its wear is already in the levels, and the robot's
#: next moves and the environment's next draw do not read it (the goals are read on entry).
Key = tuple[str, tuple[int, ...], str | None, int]


#: The most states the explicit model is built to (about 1 KB each with its choices).
MAX_STATES = 2_000_000


def _level_combinations(model: Model) -> int:
    count = 1
    for leg in model.legs:
        count *= leg.health
    return count


def user_trans_clauses(spec: GR1Spec) -> int:
    """How many user-written safety clauses (assume/guarantee always ...) the spec has."""
    return sum(1 for section in ("env_trans", "sys_trans") for c in spec.section(section)
               if c.origin is not None and isinstance(c.origin.role, UserClause))


@dataclass
class Arrays:
    """A sparse model: row ``r`` of state ``row_state[r]`` moves to ``cols[e]`` with
    ``vals[e]`` for the entries ``starts[r] <= e < starts[r + 1]``; ``breaks[e]`` marks a
    move beyond the spec's assumptions."""

    groups: list[int]  # first row of each state
    starts: list[int]
    cols: list[int]
    vals: list[float]
    breaks: list[bool]

    def numpy(self) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float64],
                             NDArray[np.bool_]]:
        starts = np.asarray(self.starts, dtype=np.int64)
        rows = np.repeat(np.arange(len(starts) - 1, dtype=np.int64), np.diff(starts))
        return rows, np.asarray(self.cols, dtype=np.int64), \
            np.asarray(self.vals, dtype=np.float64), np.asarray(self.breaks, dtype=bool)


class Progress:
    """The goals of a patrol in the order of the spec's liveness guarantees (as a GR(1)
    controller's rank cycles through them): the index of the next goal, and the number of
    goals meaning "a patrol was completed on entering this state" (the next one starts at
    the first goal)."""

    def __init__(self, domain: Domain) -> None:
        self.domain = domain
        self.labels = tuple(g.label for g in domain.goals)
        self.index = {label: i for i, label in enumerate(self.labels)}
        self.full = len(self.labels)
        self._memo: dict[State, frozenset[int]] = {}
        # a goal that is a region is read from the region alone (most goals: eq. 3.7)
        self._regions: dict[str, frozenset[int]] | None = None
        if all(g.label in domain.regions and g.formula == Var(g.label) for g in domain.goals):
            self._regions = {r: frozenset(i for i, label in enumerate(self.labels) if label == r)
                             for r in domain.regions}

    def reached(self, state: State) -> frozenset[int]:
        if self._regions is not None:
            return self._regions[state.region]
        found = self._memo.get(state)
        if found is None:
            found = frozenset(self.index[label] for label in self.domain.goals_reached(state))
            self._memo[state] = found
        return found

    def step(self, mask: int, state: State) -> int:
        """The next goal after entering ``state`` (:attr:`full`: a patrol completed)."""
        goal = 0 if mask == self.full else mask
        reached = self.reached(state)
        while goal < self.full and goal in reached:
            goal += 1
        return goal


class SpecModel:
    """The MDP of a model under a law: states as :data:`Key`, the robot's moves as choices."""

    def __init__(self, model: Model, domain: Domain, law: StepLaw,
                 max_states: int = MAX_STATES) -> None:
        self.model = model
        self.domain = domain
        self.law = law
        self.max_states = max_states
        self.progress = Progress(domain)
        if not self.progress.labels:
            raise SpecSemanticError("the spec has no goal: there is no patrol to count",
                                    None)
        self.legs = tuple(leg.name for leg in model.legs)
        self.moves: dict[str, list[tuple[str, str, tuple[int, ...]]]] = {
            r.name: [] for r in model.regions}
        leg_index = {leg: i for i, leg in enumerate(self.legs)}
        for t in model.transitions:
            for gait in t.gaits:
                needs = tuple(leg_index[leg] for leg in model.gait(gait).legs)
                self.moves[t.source].append((t.target, gait, needs))
        for region in model.regions:  # noGait stays everywhere (lowering's eq. 3.3)
            if not any(g == NO_GAIT and r == region.name for r, g, _ in self.moves[region.name]):
                self.moves[region.name].append((region.name, NO_GAIT, ()))
        start = State(model.start, NO_GAIT,
                      tuple((leg.name, leg.initial) for leg in model.legs), None)
        self.start = start
        self.keys: list[Key | None] = [None]  # state 0: the start, before the first input
        self.index: dict[Key, int] = {}
        self.actions: list[tuple[str, str]] = []  # per row: the move (region, gait)
        self.arrays = Arrays([0], [0], [], [], [])
        self._build()

    def _key(self, state: State, outcome: Outcome, mask: int) -> Key:
        return (state.region, outcome.levels, outcome.hazard, mask)

    def _add_row(self, targets: list[tuple[Key, Outcome]], queue: deque[Key]) -> None:
        a = self.arrays
        for key, outcome in targets:
            found = self.index.get(key)
            if found is None:
                found = len(self.keys)
                if found >= self.max_states:
                    raise UsageError(
                        f"the spec's explicit model passed {self.max_states:,} states (one per "
                        "region, leg levels, active hazard and next goal; this robot has "
                        f"{_level_combinations(self.model):,} combinations of leg levels): "
                        "gaitc chances would need Storm's symbolic engine, which it does not "
                        "drive yet; ask about a robot with fewer legs or levels, or raise "
                        "the limit (ChancesOptions.max_states) if memory allows, about "
                        "1 KB a state")
                self.index[key] = found
                self.keys.append(key)
                queue.append(key)
            if outcome.chance > 0.0:
                a.cols.append(found)
                a.vals.append(outcome.chance)
                a.breaks.append(outcome.breaks)
        a.starts.append(len(a.cols))

    def _build(self) -> None:
        queue: deque[Key] = deque()
        law, progress = self.law, self.progress
        self.actions.append((self.start.region, self.start.gait))
        first = progress.step(0, self.start)  # the start counts, as in a GR(1) controller
        self._add_row([(self._key(self.start, o, first), o) for o in law.outcomes(self.start)],
                      queue)
        while queue:
            key = queue.popleft()
            self.arrays.groups.append(len(self.arrays.starts) - 1)
            region, levels, hazard, mask = key
            health = tuple(zip(self.legs, levels, strict=True))
            for target, gait, needs in self.moves[region]:
                if any(levels[i] <= 1 for i in needs):
                    continue  # eq. 3.4: a gait with a failed leg is off
                entered = State(target, gait, health, hazard)
                nxt = progress.step(mask, entered)
                self.actions.append((target, gait))
                self._add_row([(self._key(entered, o, nxt), o) for o in law.outcomes(entered)],
                              queue)

    @property
    def size(self) -> int:
        return len(self.keys)

    def full_states(self) -> NDArray[np.bool_]:
        """The states entered by completing a patrol."""
        full = self.progress.full
        return np.array([k is not None and k[3] == full for k in self.keys], dtype=bool)

    def at_goal(self, goal: int) -> NDArray[np.bool_] | None:
        """The states in goal ``goal``'s region (None for a goal that is not a region: the
        states leave out the gait a goal formula may read)."""
        label = self.progress.labels[goal]
        if label not in self.domain.regions:
            return None
        return np.array([k is not None and k[0] == label for k in self.keys], dtype=bool)


class ControllerChain:
    """The Markov chain of one controller under a law: (node, goals visited) states, state 0
    the start; an input the controller has no answer to (it breaks the assumptions) leads to
    the absorbing state 1, "off the controller"."""

    def __init__(self, strategy: StrategyView, domain: Domain, law: StepLaw) -> None:
        self.strategy = strategy
        self.domain = domain
        self.law = law
        self.progress = Progress(domain)
        self.keys: list[tuple[int, int] | None] = [None, None]
        self.index: dict[tuple[int, int], int] = {}
        self.arrays = Arrays([0, 1], [0], [], [], [])
        self._states: dict[int, State] = {}
        self._build()

    def node_state(self, node: int) -> State:
        found = self._states.get(node)
        if found is None:
            found = self.domain.node_state(self.strategy, node)
            self._states[node] = found
        return found

    def _input_key(self, state: State, outcome: Outcome) -> tuple[int, ...]:
        values = self.domain.encode(State(state.region, state.gait, outcome.health,
                                          outcome.hazard))
        return tuple(values[name] for name in self.strategy.inputs)

    def _row(self, state: State, mask: int | None, options: dict[tuple[int, ...], int],
             outcomes: tuple[Outcome, ...], queue: deque[tuple[int, int]]) -> None:
        a = self.arrays
        off = 0.0
        for outcome in outcomes:
            if outcome.chance <= 0.0:
                continue
            node = options.get(self._input_key(state, outcome))
            if node is None:
                off += outcome.chance
                continue
            key = (node, self.progress.step(0 if mask is None else mask, self.node_state(node)))
            found = self.index.get(key)
            if found is None:
                found = len(self.keys)
                self.index[key] = found
                self.keys.append(key)
                queue.append(key)
            a.cols.append(found)
            a.vals.append(outcome.chance)
            a.breaks.append(outcome.breaks)
        if off > 0.0:
            a.cols.append(1)
            a.vals.append(off)
            a.breaks.append(True)
        a.starts.append(len(a.cols))

    def _build(self) -> None:
        queue: deque[tuple[int, int]] = deque()
        start = State(self.domain.model.start, NO_GAIT,
                      tuple((leg.name, leg.initial) for leg in self.domain.model.legs), None)
        first = Outcome(1.0, tuple(lv for _, lv in start.health), None,
                        legs=tuple(leg for leg, _ in start.health))  # hazards start off
        self._row(start, None, self.strategy.initial_options(), (first,), queue)
        self.arrays.cols.append(1)  # state 1 stays off the controller
        self.arrays.vals.append(1.0)
        self.arrays.breaks.append(False)
        self.arrays.starts.append(len(self.arrays.cols))
        while queue:
            node, mask = queue.popleft()
            self.arrays.groups.append(len(self.arrays.starts) - 1)
            here = self.node_state(node)
            self._row(here, mask, self.strategy.options(node), self.law.outcomes(here), queue)

    @property
    def size(self) -> int:
        return len(self.keys)

    def full_states(self) -> NDArray[np.bool_]:
        full = self.progress.full
        return np.array([k is not None and k[1] == full for k in self.keys], dtype=bool)

    def at_goal(self, goal: int) -> NDArray[np.bool_] | None:
        """The states whose node reaches goal ``goal``."""
        return np.array([k is not None and goal in self.progress.reached(self.node_state(k[0]))
                         for k in self.keys], dtype=bool)
