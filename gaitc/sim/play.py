"""The model of a play: the nodes an automaton visits, how the play ends, what each node
means to the robot.

A play is a path through a controller (the user or an environment picks the inputs, the
controller answers) or through a counter-strategy (the environment's automaton fixes the
inputs, the robot picks among the answers its guarantees allow). Its steps, with both
players' moves, the goals reached and the run monitor's verdicts, are the
:class:`gaitc.sim.run.Run` that :func:`gaitc.sim.replay.replay` makes of its path. Every
play comes from here: ``explain``'s (:func:`gaitc.sim.counterplay.choose_play`), a
counter-play of ``simulate`` (:func:`gaitc.sim.counterplay.play`) and one played by hand
(:class:`gaitc.play.player.Player`); who chooses the robot's moves is in
:mod:`gaitc.sim.counterplay`, replaying and checking a play or a run file in
:mod:`gaitc.sim.replay`.
"""

from __future__ import annotations

import itertools
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass, field

import networkx as nx

from gaitc.ir.controller import Controller
from gaitc.ir.evaluation import evaluate
from gaitc.ir.spec import GR1Spec
from gaitc.sim.domain import Domain, Goal, State
from gaitc.sim.strategy import Strategy


@dataclass(frozen=True)
class Play:
    """The automaton nodes ``path`` visited in order, and how the play ends: at a
    ``deadlock`` (the side to move has no legal move at its last node), by closing a loop
    (its last node is the one at ``loop_start``, and ``missed`` lists the goals,
    ``sys_liveness`` indices, met on no move of the loop), or neither (it was cut short)."""

    path: tuple[int, ...]
    loop_start: int | None = None
    missed: tuple[int, ...] = ()
    deadlock: bool = False


def pursued(goals: Sequence[Goal], index: int, reached: Sequence[str]) -> int:
    """The goal pursued after a step that reaches ``reached`` when goal ``index`` was: the
    goals are taken in turn, and one step may meet several of them in a row."""
    for _ in goals:
        if goals[index].label not in reached:
            break
        index = (index + 1) % len(goals)
    return index


def deadlock_levels(successors: Sequence[Sequence[int]]) -> list[int | None]:
    """Per node, in how many steps the environment forces a deadlock however the robot
    answers (None: the robot can avoid deadlocks for ever from there); the attractor of
    the nodes without successors, computed backwards."""
    preds: list[list[int]] = [[] for _ in successors]
    for n, succ in enumerate(successors):
        for s in succ:
            preds[s].append(n)
    left = [len(succ) for succ in successors]
    level: list[int | None] = [0 if not succ else None for succ in successors]
    queue = deque(n for n, succ in enumerate(successors) if not succ)
    while queue:
        s = queue.popleft()
        for n in preds[s]:
            left[n] -= 1
            if left[n] == 0 and level[n] is None:
                level[n] = 1 + max(level[x] or 0 for x in successors[n])
                queue.append(n)
    return level


def goal_distance(counter: Controller, spec: GR1Spec, goals: tuple[int, ...]
                  ) -> dict[int, int]:
    """Steps from each node of ``counter`` to the nearest node where one of ``goals``
    (``sys_liveness`` indices) holds."""
    nodes = counter.nodes
    preds: list[list[int]] = [[] for _ in nodes]
    for n, node in enumerate(nodes):
        for s in node.trans:
            preds[s].append(n)
    distance: dict[int, int] = {}
    queue: deque[int] = deque()
    for n in range(len(nodes)):
        values = dict(counter.values(n))
        valuation = {**values, **{f"{k}'": v for k, v in values.items()}}
        if any(evaluate(spec.sys_liveness[j].formula, valuation) for j in goals):
            distance[n] = 0
            queue.append(n)
    while queue:
        s = queue.popleft()
        for n in preds[s]:
            if n not in distance:
                distance[n] = distance[s] + 1
                queue.append(n)
    return distance


def missed_goals(counter: Controller, spec: GR1Spec, loop: Sequence[int]) -> tuple[int, ...]:
    """Goals (``sys_liveness`` indices) that hold on no move of ``loop`` (nodes of
    ``counter``, its first node repeated at its end)."""
    missed = []
    for j, clause in enumerate(spec.sys_liveness):
        met = False
        for a, b in itertools.pairwise(loop):
            valuation = dict(counter.values(a))
            valuation.update({f"{k}'": v for k, v in counter.values(b).items()})
            if evaluate(clause.formula, valuation):
                met = True
                break
        if not met:
            missed.append(j)
    return tuple(missed)


@dataclass
class Losses:
    """Why each node of a counter-strategy is lost for the robot: a dead end the
    environment forces within ``level[node]`` steps, a goal it can no longer reach, or the
    goal every loop from there misses (``states``: each node decoded)."""

    strategy: Strategy
    states: list[State]
    domain: Domain
    level: list[int | None] = field(init=False)
    _why: dict[int, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.level = deadlock_levels(self.strategy.successors)
        self._meets = [set(self.domain.goals_reached(s)) for s in self.states]
        self._loops: tuple[frozenset[int], ...] | None = None

    def why(self, node: int) -> str:
        found = self._why.get(node)
        if found is None:
            found = self._explain(node)
            self._why[node] = found
        return found

    def _explain(self, node: int) -> str:
        level = self.level[node]
        if level == 0:
            return "a dead end: no move of the robot keeps its guarantees after it"
        if level is not None:
            return f"the environment forces a dead end within {level} steps"
        labels = [g.label for g in self.domain.goals]
        reach = self._reachable(node)
        met = set().union(*(self._meets[n] for n in reach))
        lost = [g for g in labels if g not in met]
        if lost:
            return f"{', '.join(lost)} can never be reached again"
        gaps: set[str] = set()
        for loop in self._safe_loops():
            if loop & reach:
                covered = set().union(*(self._meets[n] for n in loop))
                gaps.update(g for g in labels if g not in covered)
        missed = [g for g in labels if g in gaps]
        if missed:
            return (f"every loop from here misses {' or '.join(missed)}: the environment "
                    "keeps it away")
        return "the environment wins on every play from here"

    def _reachable(self, node: int) -> set[int]:
        seen, todo = {node}, [node]
        while todo:
            for succ in self.strategy.successors[todo.pop()]:
                if succ not in seen:
                    seen.add(succ)
                    todo.append(succ)
        return seen

    def _safe_loops(self) -> tuple[frozenset[int], ...]:
        """The strongly connected sets of nodes without a forced dead end that hold a loop."""
        if self._loops is None:

            graph = nx.DiGraph()
            safe = [n for n, lv in enumerate(self.level) if lv is None]
            graph.add_nodes_from(safe)
            graph.add_edges_from((n, s) for n in safe for s in self.strategy.successors[n]
                                 if self.level[s] is None)
            self._loops = tuple(frozenset(c) for c in nx.strongly_connected_components(graph)
                                if len(c) > 1 or any(graph.has_edge(n, n) for n in c))
        return self._loops
