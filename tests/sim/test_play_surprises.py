"""The player's "break an assumption" moves (issue 52): offered, performed through the
recovery, the play going on with the fallback strategy, saved and resumed.

Nothing the player says is trusted: the moves offered are checked against the spec's
clauses evaluated one by one (no legal move agrees with an offered event, and the inputs
performed for it break a clause of ρe; every other event agrees with a legal move), the
surprise is compared with the one ``simulate --violate`` records for the same event at the
same state, a ``degraded`` outcome against a re-solve of the game from the state the
surprise left (made here with :func:`gaitc.decide`), and the steps after it by a fresh run
monitor.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from itertools import combinations
from pathlib import Path

import pytest
from changed import agrees, hazard_named, legs_named
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import gaitc
from gaitc.core.modes import Outcome, Role
from gaitc.diagnostics import UsageError
from gaitc.forms.decision import decide
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import Const, Expr, Not, Var, substitute
from gaitc.ir.spec import Clause
from gaitc.play.player import Player
from gaitc.sim.domain import State
from gaitc.sim.events import parse_event
from gaitc.sim.jumps import forced
from gaitc.sim.monitor import Monitor
from gaitc.sim.replay import RunEnvironment
from gaitc.sim.run import read_jsonl
from gaitc.sim.simulator import SurpriseOptions, simulate

ROOT = Path(__file__).resolve().parents[2]
CORRIDOR = ROOT / "tests" / "data" / "surprises" / "corridor3.gait"
CORRIDOR4 = ROOT / "tests" / "data" / "play" / "corridor4.gait"
ROBOT_A = ROOT / "specs" / "thesis_robot_a.gait"

DEGRADED_NOTE = ("degraded: still pursuing visit w; visit e is out of reach after L1 failed "
                 "while not in use")


@pytest.fixture(scope="module")
def corridor() -> Player:
    return gaitc.player(CORRIDOR)


@pytest.fixture(scope="module")
def robot_a() -> Player:
    return gaitc.player(ROBOT_A)


def _fresh(player: Player) -> Player:
    return Player(player.session)


def _at_w(player: Player) -> Player:
    """The corridor play at step 1: in w, gait west, so L1 is not in use."""
    played = _fresh(player)
    played.choose("start at full health")
    played.choose("nothing")
    assert played.state is not None and played.state.region == "w"
    return played


def _agrees(player: Player, words: str, state: State) -> bool:
    """Whether ``state`` has what the event ``words`` performed at the play's last state
    names: its failed legs at level 1, a degraded leg ``k`` levels below its level now, its
    hazard on (or not on)."""
    event = parse_event(words, player.domain)
    now = dict(player._played[-1].sim.state(player.path[-1]).health)
    return agrees(event, now, state)


def _possible(player: Player, words: str) -> bool:
    """Whether some legal move at the play's last state agrees with the event ``words``:
    a verified controller accepts every input ρe allows, so an event no legal move agrees
    with is one the assumptions forbid whatever else the environment does."""
    sim = player._played[-1].sim
    return any(_agrees(player, words, m.state) for m in sim.moves(player.path[-1]))


def _forbidden(player: Player, inputs: Sequence[int]) -> bool:
    """Whether ``inputs`` at the play's last state break a clause of ρe, each clause
    evaluated on its own (not through the controller or the run monitor)."""
    sim = player._played[-1].sim
    current = sim.strategy.valuation(player.path[-1])
    after = dict(zip(sim.strategy.inputs, inputs, strict=True))
    valuation = dict(current) | {f"{n}'": int(after.get(n, current[n])) for n in current}
    return not all(evaluate(c.formula, valuation) for c in player.session.spec.gr1.env_trans)


def _impossible(player: Player, words: str) -> bool:
    """The event ``words`` as a break must be: no legal move agrees with it, and the inputs
    the player performs for it agree with it and break a clause of ρe."""
    sim = player._played[-1].sim
    node = player.path[-1]
    request = forced(sim, node, parse_event(words, player.domain))
    state = player.domain.decode(sim.strategy.valuation(node)
                                 | dict(zip(sim.strategy.inputs, request.inputs, strict=True)))
    return (not _possible(player, words) and _agrees(player, words, state)
            and _forbidden(player, request.inputs))


# ---------------------------------------------------------------------- the moves offered
def test_the_moves_that_break_an_assumption_are_listed_after_the_legal_ones(
        corridor: Player) -> None:
    player = _at_w(corridor)
    legal = player.choices()
    assert [c.words for c in legal] == ["degrade L2", "nothing"]
    breaks = player.breaks()
    assert [(c.number, c.words, c.breaks) for c in breaks] == [
        (3, "fail L1", "L1 failed while not in use (eq. 3.5, line 10)"),
        (4, "degrade L1", "L1 lost a level while not in use (eq. 3.5, line 10)"),
        (5, "fail L2", "L2 dropped 2 levels in one move and failed (eq. 3.5, line 10)"),
    ]
    assert breaks[0].answer == ("the controller recovers if it can: every goal, fewer goals, "
                                "or it stops")
    # no legal move agrees with any of them, and each breaks a clause; a legal move agrees
    assert all(_impossible(player, c.words) for c in breaks)
    assert _possible(player, "degrade L2")  # the legal move ('nothing' is no event)
    # before the first state nothing can be broken (the initial assumptions decide it)
    assert _fresh(corridor).breaks() == ()


def test_choose_plays_only_legal_moves_and_breaking_only_breaking_ones(
        corridor: Player) -> None:
    player = _at_w(corridor)
    with pytest.raises(UsageError, match=r"there are 2 moves here; choose one of 1\.\.2"):
        player.choose(3)
    with pytest.raises(UsageError, match=r"there are 3 moves here; choose one of 3\.\.5"):
        player.break_assumption(2)
    with pytest.raises(UsageError, match="'degrade L2' breaks no assumption here; play it "
                                         "among the legal moves"):
        player.break_assumption("degrade L2")
    with pytest.raises(UsageError, match="break an assumption 'fail L9': unknown leg 'L9'"):
        player.break_assumption("fail L9")


def test_every_state_offers_exactly_the_forbidden_events(robot_a: Player) -> None:
    """Along a random play of robot A, each candidate event (a leg failing or losing a
    level, a hazard switched) that changes the state is offered as a break exactly when
    no legal move gives it and the clauses forbid it."""
    player = _fresh(robot_a)
    player.choose(1)
    player.autoplay(6, "random", seed=3)
    sim = player._played[-1].sim
    node = player.path[-1]
    state = sim.state(node)
    offered = {c.words for c in player.breaks()}
    for leg, level in state.health:
        for words in (f"fail {leg}", f"degrade {leg}"):
            event = parse_event(words, player.domain)
            if event.apply(state, player.domain) == state:
                assert words not in offered
                continue
            if words in offered:
                assert _impossible(player, words), words
            elif not (words.startswith("degrade") and level == 2):  # same as 'fail'
                assert _possible(player, words), words


# ---------------------------------------------------------------------- performing one
def _resolve(player: Player, before: dict[str, int], inputs: dict[str, int],
             kept: Sequence[int]) -> bool:
    """Whether some move from ``before`` with ``inputs`` wins the game with goals ``kept``:
    θe fixes the inputs, θs is ρs with the state before substituted (gaitc.decide)."""
    gr1 = player.session.spec.gr1
    now: dict[tuple[str, bool], Expr] = {(n, False): Const(bool(v)) for n, v in before.items()}
    unprime: dict[tuple[str, bool], Expr] = {(v.name, True): Var(v.name)
                                             for v in gr1.variables()}
    sys_init = tuple(Clause(substitute(substitute(c.formula, now), unprime))
                     for c in gr1.sys_trans)
    env_init = tuple(Clause(Var(n) if v else Not(Var(n))) for n, v in inputs.items())
    variant = gr1.with_sections(env_init=env_init, sys_init=sys_init,
                                sys_liveness=tuple(gr1.sys_liveness[j] for j in kept))
    return decide(variant).realizable


def test_failing_an_unused_leg_degrades_to_the_goals_a_resolve_keeps(corridor: Player) -> None:
    player = _at_w(corridor)
    step = player.break_assumption("fail L1")
    (surprise,) = player.surprises
    assert surprise.outcome == Outcome.DEGRADED and surprise.note == DEGRADED_NOTE
    assert surprise.words() == ("step 2: L1 failed while not in use (eq. 3.5, line 10); "
                                + DEGRADED_NOTE)
    assert step.index == 2 and step.level("L1") == 1 and player.goal == "w"
    # the re-solve: the state before, the inputs after the event
    before = dict(player.steps[1].values)
    inputs = {v.name: dict(step.values)[v.name] for v in player.session.spec.gr1.inputs}
    goals = len(player.session.spec.gr1.sys_liveness)
    kept = next(k for size in range(goals, 0, -1) for k in combinations(range(goals), size)
                if _resolve(player, before, inputs, k))
    assert tuple(f"visit {player.domain.goals[j].label}" for j in kept) == surprise.kept
    # the play goes on with the fallback strategy: w again and again, e never
    assert player.autoplay(12) == 12
    monitor = Monitor(player.session.spec.gr1)
    names = [v.name for v in player.session.spec.gr1.variables()]
    values = [tuple(dict(s.values)[n] for n in names) for s in player.steps]
    for i in range(3, len(values)):
        found = monitor.check_step(values[i - 1], values[i])
        assert found.sys_failed == () and found.env_failed == ()
    later = [s.goals for s in player.steps[3:]]
    assert sum("w" in g for g in later) >= 3 and not any("e" in g for g in later)


def test_the_surprise_is_the_one_simulate_records_for_the_same_event(
        corridor: Player, tmp_path: Path) -> None:
    player = _at_w(corridor)
    player.save(tmp_path / "before.run.jsonl")
    player.break_assumption("fail L1")
    run = read_jsonl(tmp_path / "before.run.jsonl")
    session = player.session
    simulated = simulate(session.strategy, session.domain, session.monitor,
                         RunEnvironment(run, session.strategy.inputs, session.domain.legs),
                         2, str(session.spec.path),
                         SurpriseOptions({2: parse_event("fail L1", session.domain)}))
    assert simulated.surprises == list(player.surprises)
    assert simulated.steps[2].values == player.steps[2].values


def test_robot_a_recovers_and_keeps_every_goal(robot_a: Player) -> None:
    player = _fresh(robot_a)
    player.choose(1)
    player.autoplay(3, "random", seed=1)
    player.break_assumption("fail L1")
    (surprise,) = player.surprises
    assert surprise.outcome == Outcome.RECOVERED
    assert surprise.words() == ("step 4: L1 failed while not in use (eq. 3.5, line 34); "
                                "recovered: the state is still winning; every goal is pursued")
    assert player.autoplay(30) == 30
    assert {"r11", "r12"} <= {g for s in player.steps[5:] for g in s.goals}


def test_no_goal_left_stops_the_play_and_undo_takes_it_back() -> None:
    """In the four-cell corridor, L1 failing on the way west and then L2 failing leave the
    robot in m with no goal it can reach and no cache it can reach: it stops there."""
    player = gaitc.player(CORRIDOR4)
    player.choose(1)
    for _ in range(6):
        player.choose("nothing")
    assert player.state is not None and (player.state.region, player.state.gait) == ("m",
                                                                                    "west")
    player.break_assumption("fail L1")
    here = player.step
    step = player.break_assumption("fail L2")
    stop = player.surprises[-1]
    assert stop.outcome == Outcome.STOPPED and stop.kept == () and step.index == here
    assert stop.note == ("stopped: no goal is reachable after L2 failed while not in use; "
                         "the robot stops where it is")
    assert player.over == f"step {here + 1}: {stop.note}"
    assert player.choices() == () and player.breaks() == ()
    assert player.autoplay(5) == 0
    with pytest.raises(UsageError, match="stopped: no goal is reachable"):
        player.choose(1)
    run = player.run()
    assert run.summary is not None and run.summary.stopped == player.over
    assert run.halted == player.over and len(run.steps) == here + 1
    assert player.undo() and player.over is None and player.step == here
    assert len(player.surprises) == 1 and player.choices()


def test_a_saved_play_carries_its_violations_and_resumes(corridor: Player,
                                                          tmp_path: Path) -> None:
    player = _at_w(corridor)
    player.break_assumption("fail L1")
    player.autoplay(5)
    out = tmp_path / "play.run.jsonl"
    saved = player.save(out)
    lines = out.read_text(encoding="utf-8").splitlines()
    assert sum('"kind": "violation"' in line for line in lines) == 1
    again = read_jsonl(out)
    assert again.surprises == list(player.surprises) == saved.surprises
    resumed = gaitc.player(CORRIDOR, start=out)
    assert resumed.role is Role.ENVIRONMENT
    assert resumed.steps == player.steps and resumed.surprises == player.surprises
    assert resumed.goal == player.goal
    at = gaitc.player(CORRIDOR, start=out, at=1)
    assert at.step == 1 and at.surprises == ()
    # simulate replays the saved inputs, recovers at the same step, the same way
    replayed = gaitc.simulate(CORRIDOR, env=f"scripted:{out}")
    assert [s.values for s in replayed.steps] == [s.values for s in player.steps]
    (again_surprise,) = replayed.surprises
    assert again_surprise.event == "step 2 of the run"  # the replay knows the inputs only
    assert replace(again_surprise, event="fail L1") == player.surprises[0]


# ---------------------------------------------------------------------- the terminal app
def test_the_terminal_breaks_an_assumption_and_the_play_goes_on(corridor: Player,
                                                                 tmp_path: Path) -> None:
    pytest.importorskip("textual")
    from textual.widgets import Static

    from gaitc.play.terminal import PlayApp

    player = _fresh(corridor)
    out = tmp_path / "surprise.run.jsonl"
    app = PlayApp(player, out)
    seen: dict[str, str] = {}

    async def script(pilot: object) -> None:
        await pilot.press("1", "1")  # type: ignore[attr-defined]  # start, then 'nothing'
        await pilot.pause()  # type: ignore[attr-defined]
        seen["moves"] = "\n".join(str(o.prompt) for o in app.query_one("#moves")._options)  # type: ignore[attr-defined]
        await pilot.press("down", "down")  # type: ignore[attr-defined]  # over the heading
        seen["answer"] = str(app.query_one("#answer", Static).render())
        await pilot.press("3")  # type: ignore[attr-defined]  # fail L1: breaks eq. 3.5
        await pilot.pause()  # type: ignore[attr-defined]
        seen["log"] = str(app.query_one("#log", Static).render())
        seen["state"] = str(app.query_one("#state", Static).render())
        await pilot.press("a", "6", "enter")  # type: ignore[attr-defined]
        await pilot.pause()  # type: ignore[attr-defined]
        seen["after"] = str(player.step)
        await pilot.press("q")  # type: ignore[attr-defined]

    assert app.play(headless=True, size=(80, 24), auto_pilot=script) == str(out)
    assert "break an assumption (! the controller recovers if it can):" in seen["moves"]
    assert " 3 fail L1  ! L1 failed while not in use (eq. 3.5, line 10)" in seen["moves"]
    assert seen["answer"] == ("→ the controller recovers if it can: every goal, fewer goals, "
                              "or it stops")
    assert seen["log"] == ("surprise: step 2: L1 failed while not in use (eq. 3.5, line 10); "
                           + DEGRADED_NOTE)
    assert "broke an assumption with move 3 (fail L1): degraded; now in w" in seen["state"]
    assert "next goal: w" in seen["state"]
    assert seen["after"] == "8"  # the pilot played on: 6 steps after step 2
    played = read_jsonl(out)
    assert len(played.steps) == 9 and [s.outcome for s in played.surprises] == [
        Outcome.DEGRADED]
    assert played.surprises[0].step == 2 and played.surprises[0].event == "fail L1"


def test_the_notebook_widget_offers_the_breaks_and_logs_the_surprise() -> None:
    pytest.importorskip("ipywidgets")
    widget = gaitc.player_widget(CORRIDOR)
    widget.buttons[0].click()  # start at full health
    widget.buttons[-1].click()  # nothing: in w, gait west
    assert [b.description for b in widget.break_buttons] == [
        "3. ! fail L1", "4. ! degrade L1", "5. ! fail L2"]
    widget.break_buttons[0].click()
    assert widget.log.value == ("surprise: step 2: L1 failed while not in use (eq. 3.5, line "
                                "10); " + DEGRADED_NOTE)
    widget.count.value = 4
    widget.strongest_button.click()
    assert widget.player.step == 6 and widget.player.goal == "w"


def test_a_hazard_the_assumptions_forbid_can_be_switched_on(small: dict[str, Player]) -> None:
    player = _fresh(small["corridor_spill"])
    player.choose("start at full health")  # in the cache c, where no spill may appear
    spill = next(c for c in player.breaks() if c.words == "switch spill on")
    assert spill.breaks == ("hazard spill switched on ('assumption (line 35): c -> "
                            "!next(spill)', line 35)")
    assert _impossible(player, "switch spill on")
    step = player.break_assumption(spill.number)
    assert step.hazard == "spill" and player.surprises[-1].outcome == Outcome.RECOVERED
    assert player.autoplay(6) == 6


# ---------------------------------------------------------------------- over random plays
SMALL = {name: ROOT / "specs" / f"{name}.gait" for name in ("patrol_2x2", "shuttle_2leg",
                                                            "corridor_hazard")}
SMALL["corridor_spill"] = ROOT / "tests" / "data" / "play" / "corridor_spill.gait"


@pytest.fixture(scope="module")
def small() -> dict[str, Player]:
    return {name: gaitc.player(path) for name, path in SMALL.items()}


def _expected_breaks(player: Player) -> list[str]:
    """The candidate events in order (each leg failing, then losing a level; each hazard
    switched on, then off) that change the state and that no legal move agrees with; of
    events asking the same of the state (``degrade L`` at level 2 is ``fail L``) the first
    only."""
    sim = player._played[-1].sim
    state = sim.state(player.path[-1])
    words = [f"{how} {leg}" for leg in player.domain.legs for how in ("fail", "degrade")]
    words += [f"switch {h} {how}" for h in player.domain.hazard_regions for how in ("on", "off")]
    seen: set[tuple[object, ...]] = set()
    out = []
    for text in words:
        event = parse_event(text, player.domain)
        after = event.apply(state, player.domain)
        if after == state:
            continue
        asked = (after.health if legs_named(event) else None,
                 after.hazard if hazard_named(event) else None)
        if asked in seen or _possible(player, text):
            continue
        seen.add(asked)
        assert _impossible(player, text)
        out.append(text)
    return out


@settings(max_examples=20, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=st.sampled_from(sorted(SMALL)),
       picks=st.lists(st.integers(min_value=0, max_value=50), min_size=1, max_size=8),
       pick=st.integers(min_value=0, max_value=50))
def test_over_random_plays_the_breaks_are_the_forbidden_events_and_the_play_goes_on(
        small: dict[str, Player], name: str, picks: list[int], pick: int) -> None:
    player = _fresh(small[name])
    for number in picks:
        if not player.choices():
            break
        player.choose(1 + number % len(player.choices()))
        assert [c.words for c in player.breaks()] == _expected_breaks(player), player.path
    breaks = player.breaks()
    if not breaks:
        return
    chosen = breaks[pick % len(breaks)]
    start = player.step
    player.break_assumption(chosen.number)
    surprise = player.surprises[-1]
    assert surprise.step == start + 1 and surprise.event == chosen.words
    assert surprise.assumption == chosen.breaks
    player.autoplay(8, "random", seed=pick)
    monitor = Monitor(player.session.spec.gr1)
    names = [v.name for v in player.session.spec.gr1.variables()]
    values = [tuple(dict(s.values)[n] for n in names) for s in player.steps]
    for i in range(start + 1, len(values)):  # ρs on every move from the surprise on
        found = monitor.check_step(values[i - 1], values[i])
        assert found.sys_failed == (), (name, i)
        assert found.env_failed == () or i == start + 1, (name, i)
