"""Plays of a counter-strategy: the environment follows the automaton, the robot answers.

In a counter-strategy (``gaitc counter``, :mod:`gaitc.solver.counter`) each node fixes the
environment's next input and lists every answer of the robot that its guarantees allow; a
node without successors is a deadlock (the robot has no legal move). A play is a path
through it, checked step by step by the run monitor like any simulated run.
"""

from __future__ import annotations

import random
from collections import deque
from collections.abc import Callable, Sequence

from gaitc.diagnostics import ControllerError
from gaitc.sim.domain import Domain
from gaitc.sim.monitor import Monitor
from gaitc.sim.run import Run
from gaitc.sim.simulator import Simulator
from gaitc.sim.strategy import Strategy

#: Picks the robot's answer: given the play so far (node ids) and the successors of its
#: last node, the index of the successor to take.
Chooser = Callable[[Sequence[int], Sequence[int]], int]


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


def careful_chooser(strategy: Strategy) -> Chooser:
    """A robot that avoids the states from which a deadlock is forced and otherwise delays
    it; among equals it prefers states it has not seen (``--env adversarial`` of a
    counter-strategy: the environment plays its strategy, the robot its best)."""
    level = deadlock_levels(strategy.successors)

    def choose(path: Sequence[int], options: Sequence[int]) -> int:
        seen = set(path)
        keys = [(level[s] is not None, -(level[s] or 0), s in seen, s) for s in options]
        return keys.index(min(keys))

    return choose


def random_chooser(seed: int) -> Chooser:
    """A robot that answers uniformly at random (reproducible with ``seed``)."""
    rng = random.Random(seed)
    return lambda _path, options: rng.randrange(len(options))


def path_run(strategy: Strategy, domain: Domain, monitor: Monitor, path: Sequence[int],
             spec_file: str = "", environment: str = "counter-strategy",
             stopped: str | None = None) -> Run:
    """The run that visits the counter-strategy nodes ``path``, checked by ``monitor``."""
    if strategy.kind != "counterstrategy":
        raise ControllerError("a counter-strategy play needs a counter-strategy", None)
    return Simulator(strategy, domain, monitor).replay(path, spec_file, environment, stopped)


def play(strategy: Strategy, domain: Domain, monitor: Monitor, steps: int,
         choose: Chooser, spec_file: str = "", environment: str = "counter-strategy") -> Run:
    """Up to ``steps`` moves of the counter-strategy against a robot that ``choose``s; the
    run stops early at a deadlock, where the robot has no legal move."""
    if not strategy.initial:
        raise ControllerError("the counter-strategy has no initial node", None)
    path = [strategy.initial[choose([], strategy.initial)]]
    stopped = None
    while len(path) <= steps:
        options = strategy.successors[path[-1]]
        if not options:
            stopped = (f"step {len(path) - 1}: deadlock: the robot has no move that keeps "
                       "its guarantees")
            break
        path.append(options[choose(path, options)])
    return path_run(strategy, domain, monitor, path, spec_file, environment, stopped)
