"""Plays of a counter-strategy: the environment follows the automaton, the robot answers.

In a counter-strategy (``gaitc counter``, :mod:`gaitc.solver.counter`) each node fixes the
environment's next input and lists every answer of the robot that its guarantees allow; a
node without successors is a deadlock (the robot has no legal move). A play
(:class:`gaitc.sim.play.Play`) is a path through it: here a :data:`Chooser` picks the
robot's answers, the careful one of ``simulate --env adversarial``, of the player's
autopilot and (heading for a goal) of ``explain``, or a random one; the play's run is
checked step by step by the run monitor like any simulated run
(:func:`gaitc.sim.replay.replay`).
"""

from __future__ import annotations

import random
from collections.abc import Callable, Sequence
from dataclasses import replace

from gaitc.core.modes import EnvironmentKind
from gaitc.diagnostics import ControllerError, UsageError
from gaitc.ir.controller import Controller, ControllerKind
from gaitc.ir.spec import GR1Spec
from gaitc.sim.domain import Domain
from gaitc.sim.monitor import Monitor
from gaitc.sim.play import Play, deadlock_levels, goal_distance, missed_goals
from gaitc.sim.replay import replay
from gaitc.sim.run import Run
from gaitc.sim.simulator import Simulator
from gaitc.sim.strategy import Strategy

#: Picks the robot's answer: given the play so far (node ids) and the successors of its
#: last node, the index of the successor to take.
Chooser = Callable[[Sequence[int], Sequence[int]], int]


def careful_chooser(levels: Strategy | Sequence[int | None],
                    prefer: Callable[[int], tuple[int, ...]] | None = None) -> Chooser:
    """A robot that avoids the states from which a deadlock is forced and otherwise delays
    it (``levels``: :func:`~gaitc.sim.play.deadlock_levels`, or the counter-strategy to
    compute them of); among safe moves it takes the least by ``prefer`` (none for the first
    state), and among equals the states it has not seen (``--env adversarial`` of a
    counter-strategy: the environment plays its strategy, the robot its best)."""
    level = (deadlock_levels(levels.successors) if isinstance(levels, Strategy)
             else list(levels))

    def choose(path: Sequence[int], options: Sequence[int]) -> int:
        seen = set(path)

        def key(s: int) -> tuple[object, ...]:
            safe = level[s] is None
            rank = prefer(s) if safe and prefer is not None and path else ()
            return (not safe, -(level[s] or 0), rank, s in seen, s)

        keys = [key(s) for s in options]
        return keys.index(min(keys))

    return choose


def random_chooser(seed: int | random.Random) -> Chooser:
    """A robot that answers uniformly at random (reproducible with ``seed``, or drawing
    from the generator ``seed``)."""
    rng = seed if isinstance(seed, random.Random) else random.Random(seed)
    return lambda _path, options: rng.randrange(len(options))


def robot_chooser(how: EnvironmentKind, counter: Strategy, seed: int = 0
                  ) -> tuple[Chooser, str]:
    """How the robot answers a counter-strategy in a simulated counter-play, with the name a
    run records: uniformly at random (``seed``), or carefully (it avoids forced
    deadlocks, against the ``adversarial`` environment kind); a scripted play is replayed,
    not chosen, and is a :class:`UsageError` here."""
    if how == EnvironmentKind.RANDOM:
        return random_chooser(seed), f"counter-strategy, robot random --seed {seed}"
    if how == EnvironmentKind.ADVERSARIAL:
        return careful_chooser(counter), "counter-strategy, robot careful"
    raise UsageError("a counter-strategy is the environment: choose how the robot answers "
                     "with 'random', 'adversarial' (it avoids forced deadlocks), or replay a "
                     "play with 'scripted RUN.jsonl'")


def play_out(successors: Sequence[Sequence[int]], initial: Sequence[int], choose: Chooser,
             steps: int | None = None, until_loop: bool = False) -> Play:
    """The play in which the robot ``choose``s every state, the first among ``initial``:
    up to ``steps`` moves, ended early at a deadlock or, ``until_loop``, when it comes back
    to a state it has visited (the loop it closes)."""
    path = [initial[choose([], initial)]]
    seen = {path[0]: 0}
    while steps is None or len(path) <= steps:
        options = successors[path[-1]]
        if not options:
            return Play(tuple(path), deadlock=True)
        nxt = options[choose(path, options)]
        if until_loop and nxt in seen:
            return Play((*path, nxt), seen[nxt])
        seen.setdefault(nxt, len(path))
        path.append(nxt)
    return Play(tuple(path))


def choose_play(counter: Controller, spec: GR1Spec, goals: tuple[int, ...] = (),
                toward: Callable[[int], int] | None = None) -> Play:
    """The play in which the robot does its best against the counter-strategy (``explain``'s).

    Where it can, the robot avoids states from which the environment forces a deadlock and
    heads for the goals it is kept from: each move makes the most progress ``toward`` them
    (for a ``.gait`` spec, the region distance to the lost goal on the map), then toward the
    nearest node of the counter-strategy where one of ``goals`` holds, new nodes before
    nodes seen already. Where it cannot avoid a deadlock, it delays it as long as possible.
    The play ends at a deadlock or when it closes a loop: the robot tried, and the
    environment's answers brought it back.
    """
    successors = [node.trans for node in counter.nodes]
    distance = goal_distance(counter, spec, goals or tuple(range(len(spec.sys_liveness))))
    far = len(counter.nodes) + 1
    progress = toward if toward is not None else (lambda node: 0)
    careful = careful_chooser(deadlock_levels(successors),
                              lambda s: (distance.get(s, far), progress(s)))
    found = play_out(successors, counter.initial, careful, until_loop=True)
    if found.loop_start is None:
        return found
    return replace(found, missed=missed_goals(counter, spec, found.path[found.loop_start:]))


def play(strategy: Strategy, domain: Domain, monitor: Monitor, steps: int,
         choose: Chooser, spec_file: str = "", environment: str = "counter-strategy") -> Run:
    """The run of up to ``steps`` moves of the counter-strategy against a robot that
    ``choose``s; it stops early at a deadlock, where the robot has no legal move."""
    if strategy.kind != ControllerKind.COUNTERSTRATEGY:
        raise ControllerError("a counter-strategy play needs a counter-strategy", None)
    if not strategy.initial:
        raise ControllerError("the counter-strategy has no initial node", None)
    found = play_out(strategy.successors, strategy.initial, choose, steps)
    stopped = (f"step {len(found.path) - 1}: deadlock: the robot has no move that keeps its "
               "guarantees") if found.deadlock else None
    return replay(Simulator(strategy, domain, monitor), found.path, spec_file, environment,
                  stopped)
