"""The adversarial environment plans (issue 13): over the whole controller it forces more
health loss than one step of look-ahead, and an unrealizable spec is played by its
counter-strategy."""

from __future__ import annotations

from pathlib import Path

import gaitc
from gaitc.sim.adversary import harm_table
from gaitc.sim.environments import AdversarialEnvironment
from gaitc.sim.run import Run
from gaitc.sim.strategy import Strategy
from gaitc.solver.symbolic import Options

ROOT = Path(__file__).resolve().parents[2]
HAZARD_PATROL = ROOT / "tests" / "data" / "hazard_patrol.gait"


def _lost(run: Run) -> int:
    return sum(max(0, level - b.level(leg)) for a, b in zip(run.steps, run.steps[1:],
                                                             strict=False)
               for leg, level in a.health)


def test_planning_forces_more_health_loss_than_one_step() -> None:
    """Against a controller that waits in its cache while the hazard is on (the strategy
    of the classic fixpoint, which may wait as long as the environment owes its liveness),
    the planner keeps the hazard on where it costs most."""
    spec = gaitc.load(HAZARD_PATROL)
    waiting = gaitc.synthesize(spec, options=Options(attractor=False), prefer="none")
    bound = gaitc.session(spec, waiting)
    assert bound is not None
    greedy = AdversarialEnvironment(plan=False)
    one_step = gaitc.simulate(bound, env=greedy, steps=400)
    planned = gaitc.simulate(bound, env=AdversarialEnvironment(), steps=400)
    assert planned.summary is not None and planned.summary.assumptions_held
    assert planned.summary.guarantees_held
    assert _lost(planned) > _lost(one_step) * 1.2


def test_the_harm_table_is_a_discounted_longest_path() -> None:
    bound = gaitc.session(gaitc.load(HAZARD_PATROL), prefer="none")
    assert bound is not None
    strategy: Strategy = bound.strategy
    states = [bound.domain.decode(strategy.valuation(n)) for n in range(len(strategy))]
    one = harm_table(strategy, bound.domain, states, horizon=1)
    two = harm_table(strategy, bound.domain, states, horizon=2)
    assert all(b >= a for a, b in zip(one, two, strict=True))
    assert max(one) >= 1.0  # some move costs a health level


def test_an_unrealizable_spec_is_played_by_its_counterstrategy() -> None:
    run = gaitc.simulate(ROOT / "specs" / "unrealizable_2x2.gait", env="adversarial", steps=8)
    assert run.environment.startswith("counter-strategy")
    assert run.summary is not None and run.summary.legs_failed
