"""Controller states in the robot's terms: decoding with a cache, goals, distances on the map.

Wraps ``ltlcompiler.decoding`` (decode/encode of region, gait, leg health, hazard; thesis
section 3.3) and evaluates the model's goal formulas (eq. 3.7) on decoded states.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from gaitc.diagnostics import ControllerError, Span
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import Always, Eventually, Expr, Or, Var, atoms, has_primes, push_next
from ltlcompiler.decoding import RobotState, decode, encode
from ltlcompiler.encoding import EncodingName
from ltlcompiler.model import Model

if TYPE_CHECKING:
    from gaitc.sim.view import StrategyView


@dataclass(frozen=True)
class State:
    """A decoded controller state."""

    region: str
    gait: str
    health: tuple[tuple[str, int], ...]  # (leg, level) in leg order
    hazard: str | None

    def level(self, leg: str) -> int:
        for name, level in self.health:
            if name == leg:
                return level
        raise KeyError(leg)


@dataclass(frozen=True)
class Goal:
    """A goal of the model (□◇ formula) with a short label and the regions it names."""

    label: str
    formula: Expr
    regions: tuple[str, ...]


def _strip(expr: Expr) -> Expr:
    while isinstance(expr, (Always, Eventually)):
        expr = expr.arg
    return expr


def _label(expr: Expr, index: int) -> str:
    if isinstance(expr, Var) and not expr.primed:
        return expr.name
    if isinstance(expr, Or) and all(isinstance(a, Var) for a in expr.args):
        return "|".join(a.name for a in expr.args if isinstance(a, Var))
    return f"goal{index + 1}"


def model_goals(model: Model) -> tuple[Goal, ...]:
    """The model's goals (in the order of the spec's liveness guarantees) with labels."""
    regions = [r.name for r in model.regions]
    out = []
    for i, g in enumerate(model.goals):
        formula = _strip(g.formula)
        names = atoms(formula)
        out.append(Goal(_label(formula, i), push_next(formula),
                        tuple(r for r in regions if (r, False) in names or (r, True) in names)))
    return tuple(out)


class Domain:
    """A model plus an encoding: decodes valuations and answers questions about the map."""

    def __init__(self, model: Model, encoding: EncodingName) -> None:
        self.model = model
        self.encoding = encoding
        self.legs: tuple[str, ...] = tuple(leg.name for leg in model.legs)
        self.full: dict[str, int] = {leg.name: leg.health for leg in model.legs}
        self.regions: tuple[str, ...] = tuple(r.name for r in model.regions)
        self.gait_legs: dict[str, tuple[str, ...]] = {g.name: g.legs for g in model.gaits}
        self.hazard_regions: dict[str, tuple[str, ...]] = {
            h.name: h.regions for h in model.hazards
        }
        self.goals = model_goals(model)
        self._primed_goals = any(has_primes(g.formula) for g in self.goals)
        self._reached: dict[tuple[State, State | None], tuple[str, ...]] = {}
        self.distance = _distances(self.regions, [(t.source, t.target)
                                                  for t in model.transitions])

    def decode(self, values: Mapping[str, int]) -> State:
        """The domain state of spec-level ``values`` (by ``ltlcompiler.decoding.decode``)."""
        robot = decode(self.model, self.encoding, values)
        return State(robot.region, robot.gait, robot.health, robot.hazard)

    def node_state(self, strategy: StrategyView, node: int) -> State:
        """The domain state of node ``node`` of a controller; a node whose values are no
        state of the spec (two regions at once, no gait) is an error naming the controller's
        file and the node, as ``gaitc verify`` would."""
        try:
            return self.decode(strategy.valuation(node))
        except ControllerError as err:
            raise ControllerError(
                f"node {node} of the controller: {err.message}",
                Span(strategy.file or "<controller>", 1, 1),
                "the controller was edited or belongs to another spec: check it with "
                "'gaitc verify SPEC CONTROLLER', or synthesize it again") from None

    def encode(self, state: State) -> dict[str, int]:
        """Spec-level values of ``state`` (by ``ltlcompiler.decoding.encode``)."""
        robot = RobotState(state.region, state.gait, state.health, state.hazard)
        return encode(self.model, self.encoding, robot)

    def valuation(self, state: State, primed: bool = False) -> dict[str, int]:
        """The model-namespace valuation of ``state`` (regions, gaits, hazards, leg levels)."""
        suffix = "'" if primed else ""
        out = {r + suffix: int(r == state.region) for r in self.regions}
        out.update({g + suffix: int(g == state.gait) for g in self.gait_legs})
        out.update({h + suffix: int(h == state.hazard) for h in self.hazard_regions})
        out.update({leg + suffix: level for leg, level in state.health})
        return out

    def goals_reached(self, state: State, previous: State | None = None) -> tuple[str, ...]:
        """Labels of the goals that ``state`` satisfies (primed goals read ``previous`` too)."""
        key = (state, previous if self._primed_goals else None)
        found = self._reached.get(key)
        if found is None:
            found = self._goals_reached(state, previous)
            self._reached[key] = found
        return found

    def _goals_reached(self, state: State, previous: State | None) -> tuple[str, ...]:
        reached = []
        for goal in self.goals:
            if goal.label in self.regions and goal.formula == Var(goal.label):
                if state.region == goal.label:
                    reached.append(goal.label)
                continue
            if has_primes(goal.formula):
                before = previous if previous is not None else state
                valuation = self.valuation(before) | self.valuation(state, primed=True)
            else:
                valuation = self.valuation(state)
            try:
                if evaluate(goal.formula, valuation):
                    reached.append(goal.label)
            except KeyError:
                continue
        return tuple(reached)

    def legs_used(self, gait: str) -> tuple[str, ...]:
        return self.gait_legs.get(gait, ())

    def region_distance(self, source: str, targets: Sequence[str]) -> int:
        """Fewest region transitions from ``source`` to any of ``targets`` (large if none)."""
        row = self.distance.get(source, {})
        return min((row.get(t, 10**6) for t in targets), default=10**6)


def _distances(
    regions: Sequence[str], edges: Sequence[tuple[str, str]]
) -> dict[str, dict[str, int]]:
    """All-pairs shortest path lengths by breadth-first search on the region graph τ."""
    succ: dict[str, list[str]] = {r: [] for r in regions}
    for a, b in edges:
        if a != b and a in succ:
            succ[a].append(b)
    out: dict[str, dict[str, int]] = {}
    for source in regions:
        dist = {source: 0}
        queue = deque([source])
        while queue:
            here = queue.popleft()
            for there in succ[here]:
                if there not in dist:
                    dist[there] = dist[here] + 1
                    queue.append(there)
        out[source] = dist
    return out
