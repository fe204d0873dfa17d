"""Runs that survive broken assumptions (issue 52): detected, recovered from, degraded.

Every answer of :mod:`gaitc.sim.recovery` is checked here by other means: the steps after a
surprise by a fresh :class:`~gaitc.sim.monitor.Monitor` (every guarantee holds from the
violation on, and the goals kept are visited again), and a ``degraded`` outcome by
re-solving, in this test, the game from the state the surprise left: the spec with its
initial conditions replaced by that state (θe: the observed inputs; θs: the moves ρs
allows from the state before) and only some goals, decided by the public
:func:`gaitc.check` under the default semantics, whose condition ∀x. θe → ∃y. θs ∧ W is
exactly "some move lands in the winning region".
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from itertools import combinations, product
from pathlib import Path

import pytest
from changed import agrees

import gaitc
from gaitc.api.simulation import session
from gaitc.cli import main
from gaitc.core.modes import Outcome, SurprisePolicy
from gaitc.ir.formula import Const, Expr, Not, Var, substitute
from gaitc.ir.spec import Clause, GR1Spec
from gaitc.sim.domain import State
from gaitc.sim.environments import RandomEnvironment
from gaitc.sim.events import Event, differences, parse_event, plan
from gaitc.sim.monitor import Monitor
from gaitc.sim.recovery import Fallback
from gaitc.sim.run import Run, Step, read_jsonl, save_run
from gaitc.sim.session import Session
from gaitc.sim.simulator import SurpriseOptions, simulate

ROOT = Path(__file__).resolve().parents[2]
ROBOT_A = ROOT / "gaitc" / "examples" / "thesis_robot_a.gait"
RADIAL8 = ROOT / "gaitc" / "examples" / "radial8_patrol.gait"
CORRIDOR = ROOT / "tests" / "data" / "surprises" / "corridor3.gait"
ONE_WAY = ROOT / "tests" / "data" / "surprises" / "one_way.gait"
AFTER = 40  # steps run after a surprise


@pytest.fixture(scope="module")
def robot_a() -> Session:
    bound = session(ROBOT_A)
    assert bound is not None
    return bound


@pytest.fixture(scope="module")
def radial8() -> Session:
    bound = session(RADIAL8)
    assert bound is not None
    return bound


@pytest.fixture(scope="module")
def corridor() -> Session:
    bound = session(CORRIDOR)
    assert bound is not None
    return bound


_FALLBACKS: dict[str, Fallback] = {}


def _run(bound: Session, events: Sequence[str], steps: int, seed: int = 1,
         policy: SurprisePolicy = SurprisePolicy.RECOVER) -> Run:
    """A random run (``seed``) with the planned ``events``; the games recovery solves are
    shared by every run of the spec."""
    shared = _FALLBACKS.setdefault(str(bound.spec.path),
                                   Fallback(bound.spec.gr1, bound.domain))
    options = SurpriseOptions(plan(events, bound.domain), policy, fallback=shared)
    return simulate(bound.strategy, bound.domain, bound.monitor, RandomEnvironment(seed),
                    steps, str(bound.spec.path), options)


def _values(bound: Session, run: Run, index: int) -> tuple[int, ...]:
    named = dict(run.steps[index].values)
    return tuple(named[v.name] for v in bound.spec.gr1.variables())


def _check_from(bound: Session, run: Run, start: int, goals: Sequence[str]) -> None:
    """From step ``start`` on, a fresh monitor finds every guarantee (ρs) kept on every
    move, every assumption kept after the surprise's own step, and each of ``goals``
    (labels) met again."""
    monitor = Monitor(bound.spec.gr1)
    for i in range(start, len(run.steps)):
        found = monitor.check_step(_values(bound, run, i - 1), _values(bound, run, i))
        assert found.sys_failed == (), f"step {i}: a guarantee broke after the surprise"
        if i > start:
            assert found.env_failed == (), f"step {i}: the environment broke ρe again"
    met = {g for s in run.steps[start:] for g in s.goals}
    assert set(goals) <= met, f"goals {set(goals) - met} not visited after step {start}"


def _unused_steps(bound: Session, leg: str, seed: int = 1, steps: int = 16) -> list[int]:
    """Steps k whose move starts from a state where ``leg`` is not in use, healthy, outside
    a cache (where eq. 3.6, not eq. 3.5, would be the assumption broken)."""
    plain = _run(bound, [], steps, seed)
    caches = bound.domain.model.caches
    return [k for k in range(1, len(plain.steps))
            if leg not in plain.steps[k - 1].legs_used and plain.steps[k - 1].level(leg) > 1
            and plain.steps[k - 1].region not in caches]


def _every_leg_failing_unused(bound: Session, picks: int) -> None:
    labels = [g.label for g in bound.domain.goals]
    for leg in bound.domain.legs:
        chosen = _unused_steps(bound, leg)[:picks]
        assert chosen, f"{leg} is in use at every step of the first run"
        for k in chosen:
            run = _run(bound, [f"{k}:fail {leg}"], k + AFTER)
            assert run.error is None and run.halted is None
            (surprise,) = run.surprises
            assert surprise.step == k and surprise.event == f"fail {leg}"
            assert surprise.assumption is not None
            assert surprise.assumption.startswith(f"{leg} failed while not in use (eq. 3.5")
            assert run.steps[k].level(leg) == 1
            if surprise.outcome == Outcome.RECOVERED:
                _check_from(bound, run, k, labels)
            else:  # a degraded run is checked against a re-solve in the tests below
                assert surprise.outcome == Outcome.DEGRADED
                _check_from(bound, run, k, [t.removeprefix("visit ")
                                            for t in surprise.kept])


def test_robot_a_goes_on_after_any_leg_fails_while_unused(robot_a: Session) -> None:
    _every_leg_failing_unused(robot_a, picks=3)


def test_eight_leg_robot_goes_on_after_any_leg_fails_while_unused(radial8: Session) -> None:
    _every_leg_failing_unused(radial8, picks=3)


def test_robot_a_recovers_from_a_lone_unused_failure(robot_a: Session) -> None:
    """Robot A has spare legs in every direction: one leg failing while unused leaves the
    state winning, so the outcome is 'recovered' and both goals are visited again."""
    k = _unused_steps(robot_a, "L5")[0]
    run = _run(robot_a, [f"{k}:fail L5"], k + AFTER)
    (surprise,) = run.surprises
    assert surprise.outcome == Outcome.RECOVERED
    assert surprise.note == "recovered: the state is still winning; every goal is pursued"
    assert surprise.words().startswith(f"step {k}: L5 failed while not in use (eq. 3.5")


def test_the_summary_names_a_surprise_failure_at_the_surprises_step(robot_a: Session) -> None:
    """Issue 60: after ``--violate "K:fail L5"`` the summary said "L5 (step K-1)", the step
    before, while the surprise list said step K. A leg worn by a gait is named at the move
    that wore it; one that failed while not in use, at the step it failed."""
    k = _unused_steps(robot_a, "L5")[0]
    run = _run(robot_a, [f"{k}:fail L5"], k + AFTER)
    assert run.summary is not None
    (surprise,) = run.surprises
    assert (surprise.step, "L5") in run.summary.legs_failed
    assert run.steps[k].level("L5") == 1 < run.steps[k - 1].level("L5")
    for index, leg in run.summary.legs_failed:  # worn by a move: named at that move
        if (index, leg) != (k, "L5"):
            assert leg in run.steps[index].legs_used


# ------------------------------------------------------------------ re-solving by hand
def _resolve(gr1: GR1Spec, before: dict[str, int], inputs: dict[str, int],
             kept: Sequence[int]) -> bool:
    """Whether some move from ``before`` with ``inputs`` lands in the winning region of the
    game with goals ``kept``: θe fixes the inputs, θs is ρs with the state before
    substituted, decided by gaitc.check (default semantics)."""
    assert not gr1.has_integers
    now: dict[tuple[str, bool], Expr] = {(name, False): Const(bool(value))
                                         for name, value in before.items()}
    unprime: dict[tuple[str, bool], Expr] = {(v.name, True): Var(v.name)
                                             for v in gr1.variables()}
    sys_init = tuple(Clause(substitute(substitute(c.formula, now), unprime))
                     for c in gr1.sys_trans)
    env_init = tuple(Clause(Var(name) if value else Not(Var(name)))
                     for name, value in inputs.items())
    variant = gr1.with_sections(env_init=env_init, sys_init=sys_init,
                                sys_liveness=tuple(gr1.sys_liveness[j] for j in kept))
    return bool(gaitc.check(variant).realizable)


def _expected_kept(gr1: GR1Spec, before: dict[str, int], inputs: dict[str, int]
                   ) -> tuple[int, ...]:
    every = tuple(range(len(gr1.sys_liveness)))
    for size in range(len(every), 0, -1):
        for kept in combinations(every, size):
            if _resolve(gr1, before, inputs, kept):
                return kept
    return ()


def _surprise_state(bound: Session, run: Run, k: int) -> tuple[dict[str, int], dict[str, int]]:
    """The state before step ``k`` and the inputs of step ``k`` (observed after the event)."""
    before = dict(run.steps[k - 1].values)
    after = dict(run.steps[k].values)
    return before, {v.name: after[v.name] for v in bound.spec.gr1.inputs}


def test_a_losing_surprise_degrades_to_exactly_the_goals_a_resolve_keeps(
        corridor: Session) -> None:
    k = _unused_steps(corridor, "L1")[0]
    run = _run(corridor, [f"{k}:fail L1"], k + AFTER)
    (surprise,) = run.surprises
    assert surprise.outcome == Outcome.DEGRADED
    gr1 = corridor.spec.gr1
    before, inputs = _surprise_state(corridor, run, k)
    expected = _expected_kept(gr1, before, inputs)
    assert expected and len(expected) < len(gr1.sys_liveness)
    titles = [f"visit {g.label}" for g in corridor.domain.goals]
    assert surprise.kept == tuple(titles[j] for j in expected)
    assert surprise.lost == tuple(t for j, t in enumerate(titles) if j not in expected)
    assert _resolve(gr1, before, inputs, tuple(range(len(gr1.sys_liveness)))) is False
    assert surprise.note == ("degraded: still pursuing visit w; visit e is out of reach after "
                             "L1 failed while not in use")
    _check_from(corridor, run, k, [titles[j].removeprefix("visit ") for j in expected])
    # and it keeps visiting them: w again and again, e never after
    later = [s.goals for s in run.steps[k + 1:]]
    assert sum("w" in g for g in later) >= 5 and not any("e" in g for g in later)


def test_recovered_surprises_agree_with_a_resolve(robot_a: Session) -> None:
    """Where the run says 'recovered', the hand-made game with every goal is winnable."""
    k = _unused_steps(robot_a, "L2")[0]
    run = _run(robot_a, [f"{k}:fail L2"], k + 3)
    (surprise,) = run.surprises
    before, inputs = _surprise_state(robot_a, run, k)
    every = tuple(range(len(robot_a.spec.gr1.sys_liveness)))
    assert (surprise.outcome == Outcome.RECOVERED) == _resolve(robot_a.spec.gr1, before, inputs,
                                                                every)


def test_no_goal_left_sends_the_robot_to_a_cache_to_stop() -> None:
    bound = session(ONE_WAY)
    assert bound is not None
    run = _run(bound, ["1:fail L1"], 20)
    (stop,) = run.surprises
    assert stop.outcome == Outcome.STOPPED and stop.kept == () and stop.lost == ("visit e",)
    assert stop.note == ("stopped: no goal is reachable after L1 failed while not in use; "
                         "heading for cache c to stop there")
    assert run.steps[-1].region == "c" and run.summary is not None
    assert run.halted == run.summary.stopped == f"stopped in cache c (step {len(run.steps) - 1})"
    _check_from(bound, run, 1, [])


def test_no_goal_and_no_cache_stops_the_robot_where_it_is() -> None:
    bound = session(ONE_WAY)
    assert bound is not None
    run = _run(bound, ["1:fail L1", "2:fail L2"], 20)
    assert [s.outcome for s in run.surprises] == [Outcome.STOPPED, Outcome.STOPPED]
    stop = run.surprises[1]
    assert stop.note.endswith("the robot stops where it is")
    assert len(run.steps) == 2 and run.halted == stop.note


def test_stop_policy_keeps_the_old_error(robot_a: Session) -> None:
    k = _unused_steps(robot_a, "L5")[0]
    run = _run(robot_a, [f"{k}:fail L5"], k + 5, policy=SurprisePolicy.STOP)
    assert run.error is not None and not run.surprises
    assert run.error.message.startswith(f"step {k} (fail L5): L5 failed while not in use "
                                        "(eq. 3.5, L5 declared on line 14): the environment "
                                        "breaks the assumption 'eq. 3.5")


def test_an_event_the_assumptions_allow_is_marked_allowed(robot_a: Session) -> None:
    plain = _run(robot_a, [], 12)
    k = next(k for k in range(1, 12) if plain.steps[k - 1].legs_used
             and plain.steps[k - 1].region not in robot_a.domain.model.caches
             and plain.steps[k - 1].level(plain.steps[k - 1].legs_used[0]) > 1)
    leg = plain.steps[k - 1].legs_used[0]
    run = _run(robot_a, [f"{k}:degrade {leg}"], k + 2)
    (surprise,) = run.surprises
    assert surprise.outcome == Outcome.ALLOWED and surprise.assumption is None


def test_violations_are_saved_and_read_back(corridor: Session, tmp_path: Path) -> None:
    k = _unused_steps(corridor, "L1")[0]
    run = _run(corridor, [f"{k}:fail L1"], k + 4)
    path = tmp_path / "run.jsonl"
    save_run(run, path)
    again = read_jsonl(path)
    assert again.surprises == run.surprises


def test_cli_json_lists_the_violations(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["simulate", str(CORRIDOR), "--steps", "8", "--seed", "1", "--violate",
                 "3:fail L1", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    (violation,) = data["violations"]
    assert set(violation) == {"step", "event", "assumption", "clause", "line", "outcome",
                              "goals_kept", "goals_lost", "note"}
    assert violation["step"] == 3 and violation["event"] == "fail L1"
    assert violation["line"].startswith(f"{CORRIDOR}:")


@pytest.mark.parametrize(("option", "message"), [
    ("3:fail L9", "--violate 'fail L9': unknown leg 'L9'; the robot's legs are L1, L2"),
    ("0:fail L1", "--violate '0:fail L1': write STEP:EVENT with STEP a step number from 1, "
                  "e.g. --violate '12:fail L5'"),
    ("3:explode L1", "--violate 'explode L1': not an event; write one of 'fail LEG', "
                     "'degrade LEG', 'degrade LEG by N', 'repair LEG', 'repair LEG to level N', "
                     "'switch HAZARD on', 'switch HAZARD off', or several joined by commas"),
    ("3:fail L1, repair L1", "--violate 'fail L1, repair L1': 'fail L1' and 'repair L1' both "
                             "change leg L1; give one of them"),
    ("3:fail L1,", "--violate 'fail L1,': an event is missing after a comma"),
    ("3:switch spill on", "--violate 'switch spill on': unknown hazard set 'spill'; the "
                          "spec's hazard sets are none (the spec declares no hazard)"),
    ("9:fail L1", "--violate '9:fail L1': the run has 4 steps, so step 9 never comes; give "
                  "--steps 9 or more"),
])
def test_bad_violate_options_are_usage_errors(option: str, message: str,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["simulate", str(CORRIDOR), "--steps", "4", "--violate", option])
    assert code == 2
    assert capsys.readouterr().err.strip() == f"gaitc: usage error: {message}"


# ------------------------------------------------------------- the event on an allowed move
CORRIDOR_HAZARD = ROOT / "gaitc" / "examples" / "corridor_hazard.gait"


def _agrees(event: Event, before: State, state: State) -> bool:
    """Whether ``state`` has what ``event`` performed at ``before`` names: its failed legs at
    level 1, a degraded leg ``k`` levels below its level before, its hazard on (or not)."""
    return agrees(event, dict(before.health), state)


def _state(step: Step) -> State:
    return State(step.region, step.gait, step.health, step.hazard)


@pytest.mark.parametrize("words", ["fail L1", "fail L3", "degrade L2", "switch spill on",
                                   "switch spill off"])
def test_an_event_is_laid_on_a_move_the_assumptions_allow(words: str) -> None:
    """At every step of a run of the corridor with a spill, the event performed there has
    what it names; it is ``allowed`` exactly when some input the assumptions allow has it
    (every input of the robot enumerated here, each checked by a fresh monitor); and when
    none has it, the input performed differs in no more than the event's own part from an
    input the assumptions allow (a spill switched on in the cache keeps the cache's reset)."""
    bound = session(CORRIDOR_HAZARD)
    assert bound is not None
    domain = bound.domain
    event = parse_event(words, domain)
    monitor = Monitor(bound.spec.gr1)
    inputs = {v.name for v in bound.spec.gr1.inputs}
    every = [State("", "", tuple(zip(domain.legs, levels, strict=True)), hazard)
             for levels in product(*(range(1, domain.full[leg] + 1) for leg in domain.legs))
             for hazard in (None, *domain.hazard_regions)]
    outcomes = set()
    for k in range(1, 13):
        run = _run(bound, [f"{k}:{words}"], k + 4)
        assert run.error is None
        (surprise,) = run.surprises
        before = _state(run.steps[k - 1])
        previous = _values(bound, run, k - 1)

        def allowed(state: State, previous: tuple[int, ...] = previous,
                    at: State = before) -> bool:
            placed = State(at.region, at.gait, state.health, state.hazard)  # inputs only
            named = {n: v for n, v in domain.encode(placed).items() if n in inputs}
            return not monitor.failed_assumptions(previous, named)

        possible = [s for s in every if _agrees(event, before, s) and allowed(s)]
        outcomes.add(surprise.outcome)
        assert (surprise.outcome == Outcome.ALLOWED) == bool(possible), (k, surprise)
        if surprise.outcome == Outcome.STOPPED and len(run.steps) == k:
            continue
        performed = _state(run.steps[k])
        assert _agrees(event, before, performed), (k, performed)
        if not possible:
            own = len(event.changes)
            nearest = min(differences(performed, s) for s in every if allowed(s))
            assert nearest <= own, (k, performed)
    assert Outcome.ALLOWED in outcomes or words.startswith(("fail", "degrade"))


# ------------------------------------------------------------------ several events at a step
def test_events_at_one_step_are_performed_together(robot_a: Session) -> None:
    """``fail L1, fail L4`` and two --violate options at one step are the same run; both
    legs are failed at that step, every leg's other level as a move the assumptions allow;
    and the run goes on under a fresh monitor with the goals it reports kept."""
    joined = _run(robot_a, ["5:fail L1, fail L4"], 5 + AFTER)
    apart = _run(robot_a, ["5:fail L1", "5:fail L4"], 5 + AFTER)
    assert [s.values for s in joined.steps] == [s.values for s in apart.steps]
    assert joined.steps[5].level("L1") == 1 and joined.steps[5].level("L4") == 1
    (surprise,) = joined.surprises
    assert surprise.event == "fail L1, fail L4" and apart.surprises[0].event == surprise.event
    assert surprise.outcome in (Outcome.RECOVERED, Outcome.DEGRADED, Outcome.ALLOWED)
    if surprise.outcome != Outcome.ALLOWED:
        assert surprise.assumption is not None and "L1 failed" in surprise.assumption
        assert "L4 failed" in surprise.assumption
    labels = [g.label for g in robot_a.domain.goals]
    kept = (labels if surprise.outcome != Outcome.DEGRADED
            else [t.removeprefix("visit ") for t in surprise.kept])
    _check_from(robot_a, joined, 6, kept)
