"""The issue's question on robot A with two health levels (unrealizable), run in the suite
only with ``GAITC_SLOW_TESTS=1`` (minutes): Storm's chances of 1, 5 and 10 patrols, the
controller it writes, and 2,000 Monte Carlo runs of that controller within the 99.9%
interval (six comparisons).
``bench/bench_chances.py`` runs the 10,000-run version and prints the table."""

from __future__ import annotations

import math
import os
from pathlib import Path

import pytest

stormpy = pytest.importorskip(
    "stormpy", reason="needs Storm's binding: pip install 'gaitc[chances]' (scripts/setup.sh)")

ROOT = Path(__file__).resolve().parents[2]
SLOW = os.environ.get("GAITC_SLOW_TESTS") == "1"


@pytest.mark.slow
@pytest.mark.skipif(not SLOW, reason="a minute of Storm and 2,000 runs; set GAITC_SLOW_TESTS=1")
@pytest.mark.parametrize(("steps", "wear"), [(500, None), (80, 0.4)])
def test_robot_a_patrols_agree_with_monte_carlo(steps: int, wear: float | None,
                                                tmp_path: Path) -> None:
    import gaitc
    from gaitc.api.chances import ChancesOptions, chances, save_best
    from gaitc.api.simulation import session, simulate
    from gaitc.core.modes import EnvironmentKind
    from gaitc.sim.session import Opponent

    spec = ROOT / "specs" / "thesis_robot_a_health2.gait"
    rates = ROOT / "docs" / "how-to" / "robot_a_rates.yaml"
    answer = chances(spec, rates=rates, wear=wear, options=ChancesOptions(steps, 10))
    assert answer.written is not None
    for k in (1, 5, 10):
        assert answer.written.patrols[k - 1] <= answer.best.patrols[k - 1] + 1e-9
    out = tmp_path / "best.json"
    save_best(answer, out)
    report = gaitc.verify(str(spec), str(out))
    assert not [p for p in report.problems if "edge" in p or "no successor" in p]
    bound = session(str(spec), str(out))
    env = Opponent(EnvironmentKind.STOCHASTIC, rates=str(rates), wear=wear)
    runs = 2000
    counts = [simulate(bound, env=env, steps=steps, seed=s).patrols() for s in range(runs)]
    for k in (1, 5, 10):
        p = answer.written.patrols[k - 1]
        seen = sum(c >= k for c in counts) / runs
        width = 3.29 * math.sqrt(max(p * (1 - p), 0.25 / runs) / runs)  # 99.9%: six checks
        assert abs(seen - p) <= width, (k, seen, p)
