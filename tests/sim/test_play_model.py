"""The one model of a play (gaitc.sim.play), its choosers (gaitc.sim.counterplay) and its
replay under the run monitor (gaitc.sim.replay), shared by explain, simulate and the player."""

from __future__ import annotations

from pathlib import Path

import pytest

import gaitc
from gaitc.diagnostics import ScenarioError
from gaitc.sim.counterplay import careful_chooser, play_out, random_chooser
from gaitc.sim.play import Play, deadlock_levels
from gaitc.sim.replay import follow, replay
from gaitc.sim.run import Run

ROOT = Path(__file__).resolve().parents[2]
UNREALIZABLE = ROOT / "specs" / "unrealizable_2x2.gait"

# 0 -> 1 | 2; 1 -> 3 (a deadlock); 2 -> 0 | 2; 3 has no move
GRAPH: tuple[tuple[int, ...], ...] = ((1, 2), (3,), (0, 2), ())


def test_deadlock_levels_count_the_steps_to_a_forced_deadlock() -> None:
    assert deadlock_levels(GRAPH) == [None, 1, None, 0]


def test_the_careful_robot_avoids_forced_deadlocks_and_prefers_new_states() -> None:
    careful = careful_chooser(deadlock_levels(GRAPH))
    assert careful([0], GRAPH[0]) == 1  # node 2: node 1 forces a deadlock
    assert careful([0, 2], GRAPH[2]) == 0  # node 0 and 2 both seen: the lower
    assert careful([2], GRAPH[2]) == 0  # node 0 is new


def test_a_preference_orders_only_the_safe_moves_and_not_the_start() -> None:
    careful = careful_chooser(deadlock_levels(GRAPH), lambda s: (-s,))
    assert careful([], (0, 2)) == 0  # the start: safety, then the lowest node
    assert careful([0], (1, 2)) == 1  # node 1 is unsafe whatever the preference
    assert careful([2], (0, 2)) == 1  # among safe moves, the preferred one


def test_a_play_ends_at_a_deadlock_a_loop_or_its_length() -> None:
    first = lambda _path, _options: 0  # noqa: E731
    assert play_out(GRAPH, (0,), first) == Play((0, 1, 3), deadlock=True)
    careful = careful_chooser(deadlock_levels(GRAPH))
    assert play_out(GRAPH, (0,), careful, until_loop=True) == Play((0, 2, 0), 0)
    assert play_out(GRAPH, (0,), careful, steps=3) == Play((0, 2, 0, 2))
    assert play_out(GRAPH, (0, 2), random_chooser(1), steps=0).path in ((0,), (2,))


def _told(run: Run) -> list[tuple[object, ...]]:
    return [(s.region, s.gait, s.health, s.hazard, s.goals, s.values) for s in run.steps]


def test_explains_play_resumed_by_the_player_is_the_same_play() -> None:
    """explain's play, saved as a run, is played again by hand step for step, and the
    player's play replays to the same checked run."""
    why = gaitc.explain(UNREALIZABLE, repairs=False)
    assert why.play is not None and why.run is not None
    player = gaitc.player(UNREALIZABLE, start=why.run)
    assert player.play.path == player.path and len(player.path) == len(why.play.path)
    again = player.run()
    assert _told(again) == _told(why.run)
    assert again.summary is not None and why.run.summary is not None
    assert again.summary.guarantees_held == why.run.summary.guarantees_held


def test_the_players_run_is_the_replay_of_its_play() -> None:
    player = gaitc.player(UNREALIZABLE)
    player.autoplay(8)
    replayed = replay(player._sim, player.play.path, player.session.spec.path,
                      player.run().environment, player.over)
    assert _told(replayed) == _told(player.run())
    assert replayed.summary == player.run().summary
    assert player.play.deadlock == (player.over is not None)


def test_follow_names_the_step_no_move_plays() -> None:
    player = gaitc.player(UNREALIZABLE)
    player.autoplay(3)
    run = player.run()
    run.file, run.lines = "r.jsonl", [2, 3, 4, 5]
    strategy = player.strategy
    nodes = list(follow(run, len(run.steps) - 1, strategy.variables,
                        lambda n: strategy.initial if n is None else strategy.successors[n],
                        lambda n: strategy.values[n], "no such move"))
    assert nodes == list(player.path)
    with pytest.raises(ScenarioError, match="step 0 of the run cannot be played here: no") as e:
        list(follow(run, 0, strategy.variables, lambda n: (), lambda n: (), "no such move"))
    assert e.value.span is not None and e.value.span.line == 2
