"""gaitc chances: Storm's numbers against closed forms worked out by hand and against Monte
Carlo runs of ``simulate --env stochastic``; the rates file's errors (issue 63)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from gaitc.diagnostics import RatesError
from gaitc.sim.rates import load_rates

stormpy = pytest.importorskip(
    "stormpy", reason="needs Storm's binding: pip install 'gaitc[chances]' (scripts/setup.sh)")

#: The corridor a - b - c (tests/data/chances/corridor.gait): east uses L1, west uses L2,
#: both of health 2 (one move to failure), the cache in a; the patrol is c, then a.
CORRIDOR = (Path(__file__).resolve().parents[1] / "data" / "chances"
            / "corridor.gait").read_text(encoding="utf-8")
P, Q = 0.1, 0.2  # L1's and L2's chance of losing a level on a move
RATES = f"wear:\n  legs: {{L1: {P}, L2: {Q}}}\n"


@pytest.fixture
def corridor(tmp_path: Path) -> tuple[Path, Path]:
    spec = tmp_path / "corridor.gait"
    spec.write_text(CORRIDOR)
    rates = tmp_path / "rates.yaml"
    rates.write_text(RATES)
    return spec, rates


def test_closed_forms(corridor: tuple[Path, Path]) -> None:
    """By hand: a -> b wears L1 with chance p; b -> c needs it.  c -> b wears L2 with chance q;
    b -> a needs it, and a failed L2 leaves the robot in b for ever.  A failed L1 in b sends
    the robot back to the cache (L2 is not worn entering a cache) to try again.

    - goal c within 2 moves: 1 - p
    - one patrol within 4 moves: (1 - p)(1 - q)
    - one patrol within 6 moves: (1 - p)(1 - q) + p (1 - p)(1 - q)
    """
    from gaitc.api.chances import ChancesOptions, chances

    spec, rates = corridor
    two = chances(spec, rates=rates, options=ChancesOptions(steps=2, patrols=1), write=False)
    assert two.best.goals["c"] == pytest.approx(1 - P, abs=1e-6)
    four = chances(spec, rates=rates, options=ChancesOptions(steps=4, patrols=2), write=False)
    assert four.best.patrols[0] == pytest.approx((1 - P) * (1 - Q), abs=1e-6)
    assert four.best.patrols[1] == pytest.approx(0.0, abs=1e-12)
    six = chances(spec, rates=rates, options=ChancesOptions(steps=6, patrols=1))
    want = (1 - P) * (1 - Q) * (1 + P)
    assert six.best.patrols[0] == pytest.approx(want, abs=1e-6)
    assert six.written is not None
    assert six.written.patrols[0] == pytest.approx(want, abs=1e-6)


def test_written_controller_verifies_and_agrees_with_monte_carlo(
        corridor: tuple[Path, Path], tmp_path: Path) -> None:
    """The written controller keeps every safety guarantee (the verifier), and 400 runs of
    it against the stochastic environment agree with Storm within the 99.9% interval."""
    import gaitc
    from gaitc.api.chances import ChancesOptions, chances, save_best
    from gaitc.api.simulation import session, simulate
    from gaitc.core.modes import EnvironmentKind
    from gaitc.sim.session import Opponent

    spec, rates = corridor
    answer = chances(spec, rates=rates, options=ChancesOptions(steps=10, patrols=2))
    out = tmp_path / "best.json"
    save_best(answer, out)
    report = gaitc.verify(str(spec), str(out))
    assert not [p for p in report.problems if "edge" in p or "no successor" in p], report.problems
    assert answer.written is not None
    bound = session(str(spec), str(out))
    env = Opponent(EnvironmentKind.STOCHASTIC, rates=str(rates))
    runs = 400
    hits = [0, 0]
    for seed in range(runs):
        run = simulate(bound, env=env, steps=10, seed=seed)
        done = run.patrols()
        hits[0] += done >= 1
        hits[1] += done >= 2
    for k in (0, 1):
        p = answer.written.patrols[k]
        width = 3.29 * math.sqrt(max(p * (1 - p), 1e-4) / runs)
        assert abs(hits[k] / runs - p) <= width, (k, hits[k] / runs, p)


def test_rates_errors_name_the_place(tmp_path: Path) -> None:
    import gaitc

    spec = tmp_path / "corridor.gait"
    spec.write_text(CORRIDOR)
    model = gaitc.load(str(spec)).robot
    bad = tmp_path / "bad.yaml"
    bad.write_text("wear:\n  legs: {L9: 0.1}\n")
    with pytest.raises(RatesError, match="unknown leg 'L9'") as err:
        load_rates(bad, model)
    assert err.value.span is not None and (err.value.span.line, err.value.span.column) == (2, 10)
    bad.write_text("wear: 1.5\n")
    with pytest.raises(RatesError, match="outside \\[0, 1\\]") as err:
        load_rates(bad, model)
    assert err.value.span is not None and err.value.span.line == 1


# One leg for both ways, three levels; a hazard in b fails it (eq. 3.9), or wears it by up to
# two levels when graded.  The robot sees the hazard before it moves (SLUGS's turn order).
SHUTTLE = """robot "one-leg shuttle"
legs L1 health 3
gait east uses L1 moves east
gait west uses L1 moves west
grid 1 x 2 cells a, b
cache a
hazard h: b{wears}
start a
visit b, a infinitely often
"""


def _spec(tmp_path: Path, text: str, rates: str) -> tuple[Path, Path]:
    spec = tmp_path / "shuttle.gait"
    spec.write_text(text)
    file = tmp_path / "rates.yaml"
    file.write_text(rates)
    return spec, file


def test_hazard_switching_closed_form(tmp_path: Path) -> None:
    """The robot waits in the cache a until h is off, then goes to b and back (entering b
    while h is on would fail L1 for good).  h starts off and is on at the first step with
    chance on = α, then switches off with chance off = β a step:

    - one patrol within 2 moves: 1 - α
    - within 3: 1 - α + α β
    - within 4: 1 - α + α β + α (1 - β) β
    """
    from gaitc.api.chances import ChancesOptions, chances

    a, b = 0.3, 0.4
    spec, rates = _spec(tmp_path, SHUTTLE.format(wears=""),
                        f"wear: 0.1\nhazards:\n  h: {{on: {a}, off: {b}}}\n")
    for steps, want in ((2, 1 - a), (3, 1 - a + a * b), (4, 1 - a + a * b + a * (1 - b) * b)):
        got = chances(spec, rates=rates, options=ChancesOptions(steps, 1), write=False)
        assert got.best.patrols[0] == pytest.approx(want, abs=1e-6), steps


def test_graded_hazard_closed_form(tmp_path: Path) -> None:
    """h is on from the first step for ever: the robot must enter b with h on, where L1
    loses one level with chance w1 and two (down to failed: stuck in b) with chance w2."""
    from gaitc.api.chances import ChancesOptions, chances

    w1, w2 = 0.25, 0.15
    spec, rates = _spec(tmp_path, SHUTTLE.format(wears=" wears 2"),
                        f"hazards:\n  h: {{on: 1, off: 0, wears: [{w1}, {w2}]}}\n")
    got = chances(spec, rates=rates, options=ChancesOptions(10, 1), write=False)
    assert got.best.patrols[0] == pytest.approx(1 - w2, abs=1e-6)
    assert got.best.goals["b"] == pytest.approx(1.0, abs=1e-9)


def test_unrated_hazard_is_named(tmp_path: Path) -> None:
    from gaitc.api.chances import chances

    spec, rates = _spec(tmp_path, SHUTTLE.format(wears=""), "wear: 0.1\n")
    with pytest.raises(RatesError, match="hazard set h has no switching chances"):
        chances(spec, rates=rates, write=False)


def test_assumptions_hold_as_often_as_monte_carlo_says(tmp_path: Path) -> None:
    """A realizable corridor with three levels a leg and sudden failures: Storm's chance
    that no input breaks the assumptions within 30 steps against 300 stochastic runs of the
    synthesized controller that stop at the first broken assumption."""
    import gaitc
    from gaitc.api.chances import ChancesOptions, chances
    from gaitc.api.simulation import session, simulate
    from gaitc.core.modes import EnvironmentKind
    from gaitc.sim.session import Opponent

    spec, rates = _spec(tmp_path, CORRIDOR.replace("health 2", "health 3"),
                        "wear: 0.2\nfail: 0.02\n")
    controller = tmp_path / "ctrl.json"
    gaitc.synthesize(gaitc.load(str(spec))).save(controller)
    steps = 30
    answer = chances(spec, controller, rates=rates, options=ChancesOptions(steps, 2),
                     write=False)
    assert answer.assumptions is not None and answer.given is not None
    p = answer.assumptions.hold
    assert 0.05 < p < 0.95  # the check below can fail both ways
    bound = session(str(spec), str(controller))
    env = Opponent(EnvironmentKind.STOCHASTIC, rates=str(rates))
    runs = 300
    held = sum(simulate(bound, env=env, steps=steps, seed=s, on_surprise="stop").error is None
               for s in range(runs))
    assert abs(held / runs - p) <= 3.29 * math.sqrt(p * (1 - p) / runs), (held / runs, p)


def test_answers_are_cached_by_spec_and_rates(corridor: tuple[Path, Path],
                                              tmp_path: Path) -> None:
    from gaitc.api.chances import ChancesOptions, chances

    spec, rates = corridor
    first = chances(spec, rates=rates, options=ChancesOptions(6, 1))
    again = chances(spec, rates=rates, options=ChancesOptions(6, 1))
    assert set(again.seconds) == {"cache"} and "model" in first.seconds
    assert again.best == first.best and again.written == first.written
    assert again.controller == first.controller
    other = chances(spec, rates=rates, options=ChancesOptions(4, 1))
    assert "model" in other.seconds  # another question: computed
    assert other.best.patrols != first.best.patrols


def test_sensitivity_closed_forms(corridor: tuple[Path, Path]) -> None:
    """One patrol within 4 moves, (1 - p)(1 - q) now.  One more level on L1 spares the walk
    to c: 1 - q (gain p (1 - q)); on L2, the walk back: 1 - p (gain (1 - p) q); a cache in b
    spares both: 1 (gain 1 - (1 - p)(1 - q)); a cache in c changes nothing."""
    from gaitc.api.chances import ChancesOptions, chances

    spec, rates = corridor
    got = chances(spec, rates=rates, options=ChancesOptions(4, 1), write=False,
                  sensitivity=True)
    gains = {g.change: g.gain for g in got.sensitivity}
    now = (1 - P) * (1 - Q)
    assert gains == pytest.approx({"a cache in b": 1 - now, "one more health level on L2":
                                   (1 - P) * Q, "one more health level on L1": P * (1 - Q),
                                   "a cache in c": 0.0}, abs=1e-6)
    assert [g.change for g in got.sensitivity][:3] == [
        "a cache in b", "one more health level on L2", "one more health level on L1"]
