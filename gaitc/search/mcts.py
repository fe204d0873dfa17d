"""Monte Carlo Tree Search over control histories (thesis 5.2.4, Algorithm 3).

A tree node is a control history from the start pose with the continuous chassis state it
leads to (pose, x, y, heading).  Selection follows UCB1 (Auer, Cesa-Bianchi and Fischer
2002): mean reward + c·sqrt(ln N_parent / N_child); expansion adds one untried transition;
a playout walks random transitions that can still return to the start pose within the
horizon, then home, and scores each cycle it closes by its displacement toward the goal.
When the robot reveals that a transition moves otherwise than predicted, every branch
through it is pruned and new rollouts start from the branches' parents (Algorithm 3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from gaitc.search.goals import Goal
from gaitc.search.transitions import Step, TransitionModel, compose


@dataclass(eq=False)
class TreeNode:
    """One control history: the transition from its parent and the state it reaches."""

    pose: int
    x: float
    y: float
    heading: float
    depth: int
    parent: TreeNode | None
    edge: int  # -1 at the root
    untried: list[int]
    children: dict[int, TreeNode] = field(default_factory=dict)
    visits: int = 0
    reward: float = 0.0
    pruned: bool = False

    def history(self) -> list[int]:
        out: list[int] = []
        node: TreeNode | None = self
        while node is not None and node.edge >= 0:
            out.append(node.edge)
            node = node.parent
        return out[::-1]


@dataclass(frozen=True)
class Candidate:
    """A closed cycle some rollout found, with its predicted displacement and reward."""

    edges: tuple[int, ...]
    x: float
    y: float
    heading: float
    reward: float
    reached: bool


class MonteCarloPlanner:
    """The MCTS of Algorithm 3 from ``start``; deterministic for a given ``seed``."""

    def __init__(
        self,
        model: TransitionModel,
        start: int,
        goal: Goal,
        horizon: int = 12,
        seed: int = 0,
        exploration: float = math.sqrt(2),
    ) -> None:
        self.model, self.start, self.goal = model, start, goal
        self.horizon, self.exploration = horizon, exploration
        self.rng = np.random.default_rng(seed)
        self.hops = model.hops_to(start)
        self.root = self._node(start, 0.0, 0.0, 0.0, 0, None, -1)
        self.by_edge: dict[int, list[TreeNode]] = {}
        self.candidates: dict[tuple[int, ...], Candidate] = {}
        self.with_edge: dict[int, set[tuple[int, ...]]] = {}  # candidates through an edge
        self.iterations = 0
        self.pruned = 0

    def _node(
        self, pose: int, x: float, y: float, h: float, depth: int, parent: TreeNode | None, e: int
    ) -> TreeNode:
        room = self.horizon - depth - 1
        rows = np.arange(int(self.model.offsets[pose]), int(self.model.offsets[pose + 1]))
        dst = self.model.dst[rows]
        ok = self.model.alive[rows] & (self.hops[dst] >= 0) & (self.hops[dst] <= room)
        untried = [int(r) for r in self.rng.permutation(rows[ok])]
        return TreeNode(
            pose=pose,
            x=x,
            y=y,
            heading=h,
            depth=depth,
            parent=parent,
            edge=e,
            untried=untried,
        )

    def score(self, x: float, y: float, heading: float, length: int) -> float:
        """Reward in [0, 1]: progress toward the goal, less heading error and length."""
        far, turn = self.goal.error(x, y, heading)
        span = max(math.hypot(self.goal.dx, self.goal.dy), self.goal.tolerance)
        value = 1.0 - far / span - turn / 180.0 - 0.01 * length / self.horizon
        return min(1.0, max(0.0, value))

    # -- one iteration -----------------------------------------------------------------
    def run(self, iterations: int) -> Candidate | None:
        """``iterations`` rounds of selection, expansion, playout and backup; the best
        cycle found so far."""
        for _ in range(iterations):
            self.iterate(self.root)
        return self.best()

    def iterate(self, start: TreeNode) -> None:
        node = start
        while not node.untried and node.children and node.depth < self.horizon:
            node = self._select(node)
        if node.untried and node.depth < self.horizon:
            node = self._expand(node)
        value = self._playout(node)
        self.iterations += 1
        climb: TreeNode | None = node
        while climb is not None:
            climb.visits += 1
            climb.reward += value
            climb = climb.parent

    def _select(self, node: TreeNode) -> TreeNode:
        log_n = math.log(max(node.visits, 1))
        ordered = sorted(node.children)
        best, best_value = node.children[ordered[0]], -math.inf
        for e in ordered:
            child = node.children[e]
            mean = child.reward / child.visits if child.visits else 0.0
            bonus = self.exploration * math.sqrt(log_n / child.visits) if child.visits else math.inf
            if mean + bonus > best_value:
                best, best_value = child, mean + bonus
        return best

    def _expand(self, node: TreeNode) -> TreeNode:
        e = node.untried.pop()
        x, y, h = compose(node.x, node.y, node.heading, self.model.step(e))
        child = self._node(int(self.model.dst[e]), x, y, h, node.depth + 1, node, e)
        node.children[e] = child
        self.by_edge.setdefault(e, []).append(child)
        return child

    def _playout(self, node: TreeNode) -> float:
        """Random transitions that keep the start pose within reach, then the best cycle."""
        m = self.model
        edges = node.history()
        pose, x, y, h = node.pose, node.x, node.y, node.heading
        best = self._close(edges, x, y, h) if pose == self.start and edges else 0.0
        for depth in range(node.depth, self.horizon):
            room = self.horizon - depth - 1
            rows = np.arange(int(m.offsets[pose]), int(m.offsets[pose + 1]))
            dst = m.dst[rows]
            ok = m.alive[rows] & (self.hops[dst] >= 0) & (self.hops[dst] <= room)
            choices = rows[ok]
            if not len(choices):
                break
            e = int(choices[self.rng.integers(len(choices))])
            x, y, h = compose(x, y, h, m.step(e))
            edges.append(e)
            pose = int(m.dst[e])
            if pose == self.start:
                best = max(best, self._close(edges, x, y, h))
        return best

    def _close(self, edges: list[int], x: float, y: float, h: float) -> float:
        value = self.score(x, y, h, len(edges))
        key = tuple(edges)
        if key not in self.candidates:
            self.candidates[key] = Candidate(key, x, y, h, value, self.goal.reached(x, y, h))
            for e in set(key):
                self.with_edge.setdefault(e, set()).add(key)
        return value

    def best(self) -> Candidate | None:
        """The cycle to run: within the goal's tolerance and shortest if any, else the one
        with the best reward (ties: fewer transitions, then the edge numbers)."""
        if not self.candidates:
            return None
        return min(
            self.candidates.values(),
            key=lambda c: (not c.reached, len(c.edges) if c.reached else 0, -c.reward, c.edges),
        )

    # -- what the robot revealed ---------------------------------------------------------
    def observe(self, edge: int, step: Step | None, rollouts: int = 1, prune: bool = True) -> int:
        """Set transition ``edge`` to the motion the robot made (``None``: it could not make
        it) and re-score the cycles through it; with ``prune`` (the motion differs), cut every
        branch through it and run ``rollouts`` new rollouts from each cut branch's parent.
        Returns the branches pruned."""
        if step is None:
            self.model.remove(edge)
            self.hops = self.model.hops_to(self.start)
        else:
            self.model.set_motion(edge, step)
        parents = self._prune(edge, again=step is not None) if prune else []
        self.pruned += len(parents)
        self._rescore(edge)
        for parent in parents:
            if parent.pruned:  # cut off later in the same pass, under another branch
                continue
            for _ in range(rollouts):
                self.iterate(parent)
        return len(parents)

    def _prune(self, edge: int, again: bool) -> list[TreeNode]:
        """Cut every live branch entered through ``edge``, taking its visits and rewards off
        its ancestors; ``again`` puts the transition back among its parent's untried ones."""
        parents: list[TreeNode] = []
        for child in self.by_edge.pop(edge, []):
            parent = child.parent
            if parent is None or child.pruned:
                continue  # already cut off with an ancestor
            del parent.children[edge]
            for node in self._subtree(child):
                node.pruned = True
            climb: TreeNode | None = parent
            while climb is not None:
                climb.visits -= child.visits
                climb.reward -= child.reward
                climb = climb.parent
            if again:
                parent.untried.append(edge)
            parents.append(parent)
        return parents

    @staticmethod
    def _subtree(node: TreeNode) -> list[TreeNode]:
        out, stack = [], [node]
        while stack:
            top = stack.pop()
            out.append(top)
            stack.extend(top.children.values())
        return out

    def _rescore(self, edge: int) -> None:
        """Recompute the displacement and reward of every cycle through ``edge``."""
        m = self.model
        for key in sorted(self.with_edge.get(edge, ())):
            if not m.alive[edge]:
                self.candidates.pop(key, None)
                continue
            x = y = h = 0.0
            for e in key:
                x, y, h = compose(x, y, h, m.step(e))
            value = self.score(x, y, h, len(key))
            self.candidates[key] = Candidate(key, x, y, h, value, self.goal.reached(x, y, h))
        if not m.alive[edge]:
            self.with_edge.pop(edge, None)
