"""How much harm the environment can still do from each controller node: the adversary's
plan, looked ahead over the whole controller instead of one step.

A controller is a Mealy machine, so once the environment picks an input the robot's answer
is fixed: planning against it is a one-player search over the controller graph.  The
table is finite-horizon discounted value iteration (Bellman):
``harm_{k+1}(n) = max over successors s of gain(n, s) + γ · harm_k(s)``, with gain the
health levels lost on the move plus a small weight for the distance of ``s`` from the goal
its node pursues, so the adversary steers towards the states closest to losing a leg and
farthest from the next goal.
"""

from __future__ import annotations

from collections.abc import Sequence

from gaitc.sim.domain import Domain, State
from gaitc.sim.strategy import Strategy

HORIZON = 12
DISCOUNT = 0.85
DISTANCE_WEIGHT = 0.05  # a level lost outweighs twenty regions of detour


def _lost(before: State, after: State) -> int:
    now = dict(after.health)
    return sum(max(0, level - now.get(leg, level)) for leg, level in before.health)


def harm_table(strategy: Strategy, domain: Domain, states: Sequence[State],
               horizon: int = HORIZON, discount: float = DISCOUNT) -> list[float]:
    """Per node, the discounted harm the environment can force from it (see the module)."""
    goals = domain.goals
    far = []
    for node, state in enumerate(states):
        goal = goals[strategy.ranks[node] % len(goals)] if goals else None
        distance = domain.region_distance(state.region, goal.regions) if goal and \
            goal.regions else 0
        far.append(DISTANCE_WEIGHT * min(distance, 100))
    gain = [[_lost(states[n], states[s]) + far[s] for s in strategy.successors[n]]
            for n in range(len(states))]
    harm = [0.0] * len(states)
    for _ in range(horizon):
        harm = [max((g + discount * harm[s] for g, s in zip(gains, succ, strict=True)),
                    default=0.0)
                for gains, succ in zip(gain, strategy.successors, strict=True)]
    return harm
