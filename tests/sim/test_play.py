"""The player (``gaitc play``, issue 39): the model, the terminal app driven headless, replay.

The terminal app runs under Textual's test pilot on an 80 x 24 screen, pressing the keys a
user would; the saved play is then replayed by ``gaitc simulate --env scripted`` and must
give the same steps. The legal moves are checked against the spec's clauses evaluated
directly (not through the controller or the run monitor), over random plays.
"""

from __future__ import annotations

import asyncio
import io
import itertools
import json
import os
import sys
from collections import deque
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import gaitc
from gaitc.cli import main
from gaitc.diagnostics import ControllerError, ScenarioError, UsageError
from gaitc.ir.evaluation import evaluate
from gaitc.play.player import Autopilot, Player, Role
from gaitc.sim.run import read_jsonl

ROOT = Path(__file__).resolve().parents[2]
SPECS = ROOT / "specs"
ROBOT_A = SPECS / "thesis_robot_a.gait"
CORRIDOR = SPECS / "corridor_hazard.gait"
UNREALIZABLE = SPECS / "unrealizable_2x2.gait"

textual = pytest.importorskip("textual")


@pytest.fixture(scope="module")
def robot_a() -> Player:
    return gaitc.player(ROBOT_A)


def _fresh(player: Player) -> Player:
    """A new play over the same session (the controller is synthesized once a module)."""
    return Player(player.session)


def _shape(steps: object) -> list[tuple[object, ...]]:
    return [(s.index, s.region, s.gait, s.health, s.hazard) for s in steps]  # type: ignore[attr-defined]


# ---------------------------------------------------------------------- the model
def test_the_first_moves_of_robot_a_are_told_in_the_robots_words(robot_a: Player) -> None:
    player = _fresh(robot_a)
    assert player.role is Role.ENVIRONMENT
    assert [c.words for c in player.choices()] == [
        "start at full health", "start with red on", "start with blue on"]
    player.choose("start at full health")
    words = [c.words for c in player.choices()]
    assert "nothing" in words and "switch blue on" in words
    assert all(c.answer for c in player.choices())


def test_undo_redo_and_jump_walk_the_same_play(robot_a: Player) -> None:
    player = _fresh(robot_a)
    player.choose(1)
    assert player.autoplay(10, Autopilot.RANDOM, seed=4) == 10
    before = _shape(player.steps)
    assert player.undo() and player.undo()
    assert player.step == 8 and player.length == 11
    assert player.redo() and player.step == 9
    player.jump(2)
    assert _shape(player.steps) == before[:3]
    player.jump(10)
    assert _shape(player.steps) == before
    with pytest.raises(UsageError, match="step 11 is not in this play"):
        player.jump(11)
    player.jump(3)
    player.choose(1)  # a new move forgets the undone ones
    assert player.length == 5


def test_a_move_that_is_not_legal_is_refused_with_the_legal_ones(robot_a: Player) -> None:
    player = _fresh(robot_a)
    player.choose(1)
    with pytest.raises(UsageError, match=r"'fail L9' is not a legal move here; the moves are: "
                       r"nothing; switch red on; switch blue on"):
        player.choose("fail L9")
    with pytest.raises(UsageError, match=r"there are 3 moves here; choose one of 1\.\.3"):
        player.choose(4)


def _legal_inputs(player: Player) -> set[tuple[int, ...]]:
    """Every input valuation the spec's assumptions allow from here, by brute force over
    the inputs' ranges, each clause evaluated on its own (initial clauses at the start)."""
    spec = player.session.spec.gr1
    names = player.strategy.inputs
    ranges = []
    for name in names:
        var = spec.variable(name)
        low = 0 if var is None or var.low is None else var.low
        high = 1 if var is None or var.high is None else var.high
        ranges.append(range(low, high + 1))
    here = player.path[-1] if player.path else None
    current = None if here is None else player.strategy.valuation(here)
    found = set()
    for values in itertools.product(*ranges):
        chosen = dict(zip(names, values, strict=True))
        if current is None:
            ok = all(evaluate(c.formula, chosen) for c in spec.env_init)
        else:
            valuation = dict(current) | {f"{n}'": v for n, v in chosen.items()}
            valuation |= {f"{n}'": v for n, v in current.items() if n not in chosen}
            ok = all(evaluate(c.formula, valuation) for c in spec.env_trans)
        if ok:
            found.add(values)
    return found


@pytest.fixture(scope="module")
def small_players() -> dict[str, Player]:
    return {name: gaitc.player(SPECS / f"{name}.gait")
            for name in ("patrol_2x2", "corridor_hazard", "shuttle_2leg")}


@settings(max_examples=25, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=st.sampled_from(["patrol_2x2", "corridor_hazard", "shuttle_2leg"]),
       picks=st.lists(st.integers(min_value=0, max_value=50), max_size=12))
def test_only_and_all_the_legal_moves_are_offered(small_players: dict[str, Player], name: str,
                                                  picks: list[int]) -> None:
    player = _fresh(small_players[name])
    for pick in [*picks, 0]:
        offered = {player.strategy.input_key(c.node) for c in player.choices()}
        assert offered == _legal_inputs(player), (name, player.path)
        assert len({c.words for c in player.choices()}) == len(player.choices())
        player.choose(1 + pick % len(player.choices()))


def test_the_robot_role_offers_every_answer_and_says_why_it_loses() -> None:
    player = gaitc.player(UNREALIZABLE)
    assert player.role is Role.ROBOT
    player.choose(1)
    counter = player.strategy
    assert [c.node for c in player.choices()] == list(counter.successors[player.path[-1]])
    assert all(c.why for c in player.choices())
    assert player.pending() == "nothing"
    # the strongest robot holds out, yet the goals are never all met again: re-checked on
    # the run by the monitor, not trusted from the reasons
    player.autoplay(12)
    run = player.run()
    visits = dict(run.summary.goal_visits)
    assert run.summary.guarantees_held and min(visits.values()) <= 1


def test_a_dead_end_is_reported_and_ends_the_choices() -> None:
    player = gaitc.player(UNREALIZABLE)
    for _ in range(40):
        if player.over is not None:
            break
        dooming = [c for c in player.choices() if c.loses_in is not None]
        player.choose((min(dooming, key=lambda c: c.loses_in or 0) if dooming
                       else player.choices()[0]).number)
    if player.over is not None:
        assert "dead end" in player.over and player.choices() == ()


def test_a_realizable_spec_has_no_robot_role() -> None:
    with pytest.raises(UsageError, match="is realizable: the environment has no winning"):
        gaitc.player(SPECS / "patrol_2x2.gait", against=True)


def test_a_controller_of_another_spec_is_refused(tmp_path: Path) -> None:
    other = tmp_path / "other.json"
    assert main(["synth", str(SPECS / "patrol_2x2.gait"), "-o", str(other)]) == 0
    with pytest.raises(ControllerError, match="controller does not belong to this spec"):
        gaitc.player(ROBOT_A, other)


def test_a_run_of_another_robot_is_an_error_at_its_file(tmp_path: Path) -> None:
    run = tmp_path / "other.run.jsonl"
    assert main(["simulate", str(SPECS / "patrol_2x2.gait"), "--steps", "3", "--out",
                 str(run)]) == 0
    with pytest.raises(ScenarioError) as caught:
        gaitc.player(ROBOT_A, start=run)
    assert caught.value.span is not None and caught.value.span.file == str(run)
    assert caught.value.message == (
        "the run is of a robot with legs L1, L2, L3, L4, but this spec's robot has L1, L2, "
        "L3, L4, L5, L6, L7, L8")


def test_a_play_resumes_from_any_step_of_a_run(robot_a: Player, tmp_path: Path) -> None:
    player = _fresh(robot_a)
    player.choose(1)
    player.autoplay(8, Autopilot.RANDOM, seed=2)
    file = tmp_path / "p.run.jsonl"
    player.save(file)
    resumed = gaitc.player(ROBOT_A, start=file, at=5)
    assert _shape(resumed.steps) == _shape(player.steps[:6])
    with pytest.raises(UsageError, match="step 9 is not in"):
        gaitc.player(ROBOT_A, start=file, at=9)


def test_explains_play_is_a_start_for_the_robot_role(tmp_path: Path) -> None:
    """explain plays the environment from a counter-strategy of the freedoms it needs, so
    its play leaves the whole spec's counter-strategy at step 3 here; the player resumes it
    against explain's, at every step, and simulate replays it as recorded."""
    out = tmp_path / "explain.run.jsonl"
    main(["explain", str(UNREALIZABLE), "--no-repairs", "--out", str(out)])
    play = read_jsonl(out)
    for at in range(len(play.steps)):
        player = gaitc.player(UNREALIZABLE, start=out, at=at)
        assert _shape(player.steps) == _shape(play.steps[:at + 1])
        assert player.role is Role.ROBOT and player.choices()
    again = gaitc.simulate(UNREALIZABLE, env=f"scripted:{out}")
    assert _shape(again.steps) == _shape(play.steps)
    assert again.summary is not None and again.summary.assumptions_held


# ---------------------------------------------------------------------- the terminal app
def _screen(app: object) -> str:
    """The app's screen as plain text (what a terminal of its size shows)."""
    from rich.console import Console

    console = Console(width=80, height=24, file=io.StringIO(), force_terminal=True,
                      color_system=None, record=True)
    console.print(app.screen._compositor.render_update(full=True))  # type: ignore[attr-defined]
    return console.export_text()


def _path_to_failures(player: Player, wanted: int = 2) -> list[int]:
    """Moves (choice numbers) from here to a state with ``wanted`` failed legs, breadth
    first over the controller's nodes."""
    start = player.path[-1]
    seen = {start: (None, 0)}
    queue = deque([start])
    sim = player._sim
    while queue:
        node = queue.popleft()
        if sum(level == 1 for _, level in sim.state(node).health) >= wanted:
            moves: list[int] = []
            while seen[node][0] is not None:
                parent, number = seen[node]
                moves.append(number)
                node = parent  # type: ignore[assignment]
            return moves[::-1]
        for number, move in enumerate(sim.moves(node), 1):
            if move.node not in seen and len(seen) < 10**5:
                seen[move.node] = (node, number)
                queue.append(move.node)
    return []


async def _press_choice(pilot: object, app: object, number: int) -> None:
    """Play move ``number`` as a user does: its digit, or the arrows and enter."""
    if number <= 9:
        await pilot.press(str(number))  # type: ignore[attr-defined]
        return
    await pilot.press(*(["down"] * (number - 1)), "enter")  # type: ignore[attr-defined]


def _session(spec: Path, out: Path, fail_legs: bool) -> tuple[str, list[str], Player]:
    """The scripted session of the issue, keys only: (fail two legs), switch a hazard,
    undo, let the adversary play 20 steps, save."""
    from gaitc.play.terminal import PlayApp

    player = gaitc.player(spec)
    app = PlayApp(player)
    screens: list[str] = []

    async def script() -> None:
        async with app.run_test(size=(80, 24)) as pilot:
            await pilot.press("1")
            if fail_legs:
                for number in _path_to_failures(player):
                    await _press_choice(pilot, app, number)
                assert sum(level == 1 for _, level in player.state.health) >= 2
            switch = next(c for c in player.choices() if c.words.startswith("switch"))
            await _press_choice(pilot, app, switch.number)
            assert player.state.hazard is not None
            screens.append(_screen(app))
            await pilot.press("u")
            screens.append(str(player.step + 1))  # the states before the pilot
            await pilot.press("a")
            await pilot.press(*"20", "enter")
            await pilot.press("s")
            await pilot.press(*str(out), "enter")
            await pilot.pause()
            screens.append(_screen(app))
            await pilot.press("question_mark")
            await pilot.pause()
            screens.append(_screen(app))
            await pilot.press("escape")
            await pilot.press("q")

    asyncio.run(script())
    return app.saved or "", screens, player


@pytest.mark.parametrize("spec, fail_legs", [(CORRIDOR, True), (ROBOT_A, False)])
def test_a_scripted_session_replays_with_simulate(spec: Path, fail_legs: bool, tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "session.run.jsonl"
    saved, screens, player = _session(spec, out, fail_legs)
    assert saved == str(out)
    played = read_jsonl(out)
    assert played.environment == "played by hand (environment)"
    switched, before, after, keys = screens
    assert player.step == len(played.steps) - 1 == int(before) + 20 - 1
    assert "switch" in switched  # the hazard switched, before the undo
    assert f"saved {len(played.steps)} steps to" in after
    assert "you play the environment" in after
    assert "the strongest pilot plays N steps" in keys
    if fail_legs:
        assert any(sum(level == 1 for _, level in s.health) >= 2 for s in played.steps)
    else:  # robot A's controller never lets a leg fail: no legal move fails one
        assert all(level > 1 for s in played.steps for _, level in s.health)
    capsys.readouterr()
    json_out = tmp_path / "replay.run.jsonl"
    code = main(["simulate", str(spec), "--env", "scripted", str(out), "--out", str(json_out)])
    assert code == 0
    replay = read_jsonl(json_out)
    assert _shape(replay.steps) == _shape(played.steps)
    assert read_jsonl(json_out).steps[-1].values == played.steps[-1].values


def test_the_robot_role_in_the_terminal_and_its_replay(tmp_path: Path) -> None:
    from gaitc.play.terminal import PlayApp

    player = gaitc.player(UNREALIZABLE)
    app = PlayApp(player, tmp_path / "lost.run.jsonl")
    shown: list[str] = []

    async def script() -> None:
        async with app.run_test(size=(80, 24)) as pilot:
            await pilot.press("1", "2")
            await pilot.pause()
            shown.append(_screen(app))
            await pilot.press("a", "5", "enter", "q")

    asyncio.run(script())
    assert "you play the robot" in shown[0]
    assert "the environment: degrade L1; your move as the robot" in shown[0]
    assert "can never be reached again" in shown[0]
    out = tmp_path / "lost.run.jsonl"
    played = read_jsonl(out)
    assert len(played.steps) == 2 + 5
    replay = tmp_path / "replay.run.jsonl"
    assert main(["simulate", str(UNREALIZABLE), "--env", "scripted", str(out), "--out",
                 str(replay)]) == 0
    assert _shape(read_jsonl(replay).steps) == _shape(played.steps)


def test_the_screen_reads_without_colour(monkeypatch: pytest.MonkeyPatch) -> None:
    from gaitc.play.terminal import PlayApp

    monkeypatch.setenv("NO_COLOR", "1")
    player = gaitc.player(ROBOT_A)
    app = PlayApp(player)
    shown: list[str] = []

    async def script() -> None:
        async with app.run_test(size=(80, 24)) as pilot:
            await pilot.press("3")
            await pilot.pause()
            shown.append(_screen(app))
            shown.append(app.export_screenshot())

    asyncio.run(script())
    text, svg = shown
    assert "@r12*" in text and "r9!" in text and "r3+" in text and "r2~" in text
    assert "~ hazard region (! when on)" in text
    assert app.no_color  # Textual's monochrome filter: every colour drawn is a grey
    import re

    frame = {"ff5f57", "febc2e", "28c840", "c5c8c6"}  # the screenshot's window and text
    colours = {c.lower() for c in re.findall(r"#([0-9a-fA-F]{6})\b", svg)} - frame
    assert colours and all(c[0:2] == c[2:4] == c[4:6] for c in colours), colours


TINY_KEYS = ("pageup", "pagedown", "home", "end", "up", "down", "pageup", "enter", "2",
             "question_mark", "escape", "u", "r", "g", "escape", "tab", "shift+tab", "ctrl+p",
             "pagedown", "pageup")


@pytest.mark.parametrize("size", [(20, 3), (1, 1), (80, 2), (12, 40)])
def test_a_tiny_terminal_takes_every_key_and_the_play_is_saved(
        small_players: dict[str, Player], tmp_path: Path, size: tuple[int, int]) -> None:
    """Issue 48: PageUp on a 20 x 3 screen died inside Textual (KeyError) and the play was
    lost; on any screen every key works (a page is one move when the list has no room)."""
    from gaitc.play.terminal import PlayApp

    player = _fresh(small_players["patrol_2x2"])
    out = tmp_path / "tiny.run.jsonl"
    app = PlayApp(player, out)

    async def script(pilot: object) -> None:
        await pilot.press("1", *TINY_KEYS)  # type: ignore[attr-defined]
        played.append(player.step + 1)
        await pilot.press("q")  # type: ignore[attr-defined]

    played: list[int] = []
    assert app.play(headless=True, size=size, auto_pilot=script) == str(out)
    assert app.return_code == 0 and played[0] >= 3
    assert len(read_jsonl(out).steps) == played[0] == player.step + 1


def test_a_play_is_saved_when_the_app_ends_without_q(small_players: dict[str, Player],
                                                     tmp_path: Path) -> None:
    from gaitc.play.terminal import PlayApp

    player = _fresh(small_players["patrol_2x2"])
    out = tmp_path / "quit.run.jsonl"
    app = PlayApp(player, out)

    async def script(pilot: object) -> None:
        await pilot.press("1", "1", "ctrl+q")  # type: ignore[attr-defined]  # Textual's quit

    assert app.play(headless=True, size=(80, 24), auto_pilot=script) == str(out)
    assert len(read_jsonl(out).steps) == 2


def test_an_error_inside_the_app_saves_the_play_and_is_not_a_clean_exit(
        small_players: dict[str, Player], tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    from gaitc.play.terminal import PlayApp, PlayCrash

    player = _fresh(small_players["patrol_2x2"])
    out = tmp_path / "crash.run.jsonl"
    app = PlayApp(player, out)

    def broken() -> bool:
        raise KeyError(0)  # stands for any bug inside the app, as Textual's KeyError was

    monkeypatch.setattr(player, "undo", broken)

    async def script(pilot: object) -> None:
        await pilot.press("1", "1", "1", "u")  # type: ignore[attr-defined]

    with pytest.raises(PlayCrash) as crash:
        app.play(headless=True, size=(80, 24), auto_pilot=script)
    # three states are two steps, as the saved run's summary counts them (issue 60)
    assert str(crash.value) == (f"the player stopped on an error of its own; a play of 2 "
                                f"steps is saved in {out}")
    assert app.return_code == 1 and len(read_jsonl(out).steps) == 3
    capsys.readouterr()


def test_play_needs_a_terminal(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["play", str(ROBOT_A)]) == 2
    assert "'gaitc play' needs a terminal" in capsys.readouterr().err


def test_a_run_file_without_an_input_is_an_error_at_its_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    player = gaitc.player(SPECS / "patrol_2x2.gait")
    player.choose(1)
    player.autoplay(4, Autopilot.RANDOM, seed=1)
    out = tmp_path / "p.run.jsonl"
    player.save(out)
    lines = out.read_text().splitlines()
    step = json.loads(lines[3])
    step["values"] = {k: v for k, v in step["values"].items() if k != "L1_h2"}
    lines[3] = json.dumps(step)
    out.write_text("\n".join(lines) + "\n")
    run = gaitc.simulate(SPECS / "patrol_2x2.gait", env=f"scripted:{out}")
    assert isinstance(run.error, ScenarioError) and len(run.steps) == 2
    capsys.readouterr()
    assert main(["simulate", str(SPECS / "patrol_2x2.gait"), "--env", "scripted",
                 str(out)]) == 1
    err = capsys.readouterr().err
    assert f"{out}:4:1: error: step 2 gives no value for 'L1_h2': the run was written for " \
           "another spec" in err
    with pytest.raises(ScenarioError, match="step 2 gives no value for 'L1_h2'"):
        gaitc.player(SPECS / "patrol_2x2.gait", start=out)


def test_the_words_of_each_kind_of_move() -> None:
    from gaitc.play.words import distinguished, environment_words, robot_words
    from gaitc.sim.domain import State

    full = {"L1": 3, "L2": 3, "L3": 3}
    here = State("r1", "north", (("L1", 3), ("L2", 2), ("L3", 1)), None)
    moved = State("r2", "east", (("L1", 2), ("L2", 1), ("L3", 3)), "spill")
    assert environment_words(here, moved, full) == \
        "switch spill on, degrade L1, fail L2, repair L3"
    assert environment_words(moved, here, full) == \
        "switch spill off, repair L1, repair L2 to level 2, fail L3"
    assert environment_words(State("r1", "x", (("L4", 5),), None),
                             State("r1", "x", (("L4", 3),), None), {"L4": 5}) == \
        "degrade L4 by 2"
    assert environment_words(here, here, full) == "nothing"
    assert environment_words(None, here, full) == "start with L2 at level 2, L3 at level 1"
    assert environment_words(None, State("r1", "noGait", (("L1", 3),), "a"), full) == \
        "start with a on"
    other = State("r1", "north", here.health, "acid")
    assert environment_words(moved, other, full).startswith("switch spill off, switch acid on")
    assert robot_words(here, moved) == "east to r2"
    assert robot_words(here, State("r1", "noGait", here.health, None)) == "stay in r1"
    assert robot_words(None, State("r1", "noGait", here.health, None)) == "start in r1"
    assert distinguished(["nothing", "nothing", "fail L1"],
                         [{"x": 0, "y": 1}, {"x": 1, "y": 1}, {"x": 0, "y": 0}]) == \
        ["nothing (x=0)", "nothing (x=1)", "fail L1"]


@pytest.mark.graphviz
def test_render_map_draws_a_saved_play(robot_a: Player, tmp_path: Path) -> None:
    player = _fresh(robot_a)
    player.choose(1)
    player.autoplay(6)
    run = tmp_path / "p.run.jsonl"
    player.save(run)
    picture = tmp_path / "p.svg"
    assert main(["render", "map", str(ROBOT_A), "--run", str(run), "-o", str(picture)]) == 0
    svg = picture.read_text()
    assert svg.startswith("<?xml") or "<svg" in svg
    assert all(s.region in svg for s in player.steps)


def test_the_robot_role_offers_exactly_the_answers_the_guarantees_allow() -> None:
    """Each robot move offered is an answer to the environment's fixed input that every
    safety guarantee allows, and every such answer is offered (brute force over the
    outputs, each clause evaluated on its own)."""
    player = gaitc.player(UNREALIZABLE)
    spec = player.session.spec.gr1
    outputs = [v.name for v in spec.outputs]
    checked = 0
    for _ in range(8):
        if player.over is not None:
            break
        offered = {player.strategy.values[c.node] for c in player.choices()}
        if player.path:
            current = player.strategy.valuation(player.path[-1])
            fixed = player.strategy.input_key(player.choices()[0].node)
            allowed = set()
            for values in itertools.product((0, 1), repeat=len(outputs)):
                nxt = dict(zip(player.strategy.inputs, fixed, strict=True))
                nxt |= dict(zip(outputs, values, strict=True))
                valuation = dict(current) | {f"{n}'": v for n, v in nxt.items()}
                if all(evaluate(c.formula, valuation) for c in spec.sys_trans):
                    allowed.add(tuple(nxt[n] for n in player.strategy.variables))
            assert offered == allowed
            checked += 1
        player.choose(1 + len(player.path) % len(player.choices()))
    assert checked >= 3


@pytest.mark.parametrize("key", ["a", "n"])
def test_a_pilot_asked_for_too_many_steps_refuses_at_once(key: str) -> None:
    """10**7 steps kept the app busy for minutes (issue 48's fuzzing): more than MAX_AUTO
    steps are refused with the limit, nothing is played, and a count within it plays."""
    import time

    from gaitc.play.terminal import MAX_AUTO, PlayApp

    player = gaitc.player(CORRIDOR)
    app = PlayApp(player)
    said: list[str] = []

    async def script() -> None:
        async with app.run_test(size=(80, 24)) as pilot:
            await pilot.press("1")
            before = player.step
            started = time.monotonic()
            await pilot.press(key, *str(10**7), "enter")
            await pilot.pause()
            assert time.monotonic() - started < 10
            assert player.step == before
            said.append(app.message)
            await pilot.press(key, *"3", "enter")
            await pilot.pause()
            said.append(app.message)
            await pilot.press("q", "q")

    asyncio.run(script())
    assert f"at most {MAX_AUTO} steps" in said[0]
    assert "pilot played" in said[1]


@pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs a pseudo-terminal")
def test_q_quits_while_the_controller_is_being_synthesized() -> None:
    """Issue 59: ``q`` works at once, before the player has opened. The hexapod's controller
    takes seconds to synthesize, so an answer naming the quit came from the preparation,
    and the key costs this test only the start-up."""
    pexpect = pytest.importorskip("pexpect")
    spec = ROOT / "tests" / "data" / "play" / "hexapod_warehouse.gait"
    child = pexpect.spawn(sys.executable, ["-m", "gaitc", "play", str(spec)], cwd=str(ROOT),
                          encoding="utf-8", timeout=120, dimensions=(24, 120))
    child.expect("q quits")
    child.send("q")
    child.expect(pexpect.EOF)
    child.close()
    assert "quit before the play began; nothing to save" in child.before
    assert child.exitstatus == 0
    assert not (ROOT / "hexapod_warehouse.play.jsonl").exists()


def test_a_play_counts_its_steps_as_its_run_file_does(tmp_path: Path) -> None:
    """Issue 60: the player said "a play of 2 steps" of a file that holds one step (two
    states). A play's steps are counted as ``simulate --steps`` and the run's summary
    count them: the moves after the first state."""
    player = gaitc.player(SPECS / "patrol_2x2.gait")
    player.autoplay(1)
    assert player.played_words() == "a play of 0 steps"
    player.autoplay(1)
    assert player.played_words() == "a play of 1 step"
    run = player.save(tmp_path / "two.jsonl")
    assert len(read_jsonl(tmp_path / "two.jsonl").steps) == 2 == len(run.steps)
    player.autoplay(3)
    assert player.played_words() == "a play of 4 steps"
