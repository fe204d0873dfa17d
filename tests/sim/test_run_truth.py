"""Runs tell the truth (issue 13): a degradation is marked on the move and gait that caused
it, in the step list, the map, the health timeline and the run file; the summary's goal
visits and its □◇ counts use one definition of "held on a step"."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.core.spec import load
from gaitc.sim.domain import Domain
from gaitc.sim.environments import AdversarialEnvironment, RandomEnvironment
from gaitc.sim.map_view import map_view
from gaitc.sim.monitor import Monitor
from gaitc.sim.run import Run, read_jsonl, write_jsonl
from gaitc.sim.simulator import simulate
from gaitc.sim.strategy import strategy_from_controller
from gaitc.solver.synthesis import synthesize

ROOT = Path(__file__).resolve().parents[2]
HAZARD_PATROL = ROOT / "tests" / "data" / "hazard_patrol.gait"
PATROL = ROOT / "specs" / "patrol_2x2.gait"


def _run(path: Path, adversarial: bool, steps: int = 40, seed: int = 0) -> Run:
    loaded = load(str(path))
    assert loaded.model is not None
    controller = synthesize(loaded.gr1)
    assert controller is not None
    strategy = strategy_from_controller(controller, loaded.gr1)
    env = AdversarialEnvironment() if adversarial else RandomEnvironment(seed)
    return simulate(strategy, Domain(loaded.model, "onehot"), Monitor(loaded.gr1), env, steps)


@pytest.fixture(scope="module")
def hazard_run() -> Run:
    return _run(HAZARD_PATROL, adversarial=True)


def test_a_failure_is_marked_on_the_step_whose_gait_used_the_leg(hazard_run: Run) -> None:
    marked = [s for s in hazard_run.steps if s.failed or s.degraded]
    assert marked, "the adversary wears legs out"
    for s in marked:
        after = hazard_run.steps[s.index + 1]
        for leg in s.failed + s.degraded:
            assert leg in s.legs_used, f"step {s.index}: {leg} marked but not in use"
            assert after.level(leg) < s.level(leg)
        for leg in s.failed:
            assert after.level(leg) == 1
    for before, after in zip(hazard_run.steps, hazard_run.steps[1:], strict=False):
        dropped = {leg for leg, level in before.health if after.level(leg) < level}
        assert dropped == set(before.failed + before.degraded)


def test_the_map_and_timeline_mark_the_causing_move(hazard_run: Run) -> None:
    assert hazard_run.model is not None
    dot = map_view(hazard_run.model, hazard_run, max_steps=40).graph.to_string()
    for s in hazard_run.steps[1:]:
        if s.failed:
            assert f"{s.index}✗" in dot  # the edge into step s: the move made with s's gait
    # in the timeline a ✗ sits only in a cell with the in-use frame
    for cell in dot.split("<TD")[1:]:
        if ">✗</TD>" in cell:
            assert 'BORDER="3"' in cell


def test_the_run_file_keeps_the_causing_step(hazard_run: Run, tmp_path: Path) -> None:
    path = tmp_path / "run.jsonl"
    path.write_text(write_jsonl(hazard_run), encoding="utf-8")
    again = read_jsonl(path)
    assert [s.failed for s in again.steps] == [s.failed for s in hazard_run.steps]
    assert hazard_run.summary is not None
    for index, leg in hazard_run.summary.legs_failed:
        assert leg in hazard_run.steps[index].legs_used


@pytest.mark.parametrize("adversarial", [False, True])
def test_goal_visits_and_liveness_counts_agree(adversarial: bool) -> None:
    for path in (PATROL, HAZARD_PATROL):
        run = _run(path, adversarial, steps=25, seed=3)
        assert run.summary is not None
        visits = dict(run.summary.goal_visits)
        held = dict(run.summary.sys_liveness)
        assert len(visits) == len(held) > 0
        for (goal, count), (rule, times) in zip(visits.items(), held.items(), strict=True):
            assert goal in rule and count == times, (path.name, goal, count, rule, times)
        assert sum(visits.values()) == sum(len(s.goals) for s in run.steps)


def test_busy_or_two_way_map_edges_list_their_steps_in_a_side_table(hazard_run: Run) -> None:
    assert hazard_run.model is not None
    dot = map_view(hazard_run.model, hazard_run, max_steps=40).graph.to_string()
    pairs: dict[tuple[str, str], list[int]] = {}
    for a, b in zip(hazard_run.steps[:41], hazard_run.steps[1:41], strict=False):
        pairs.setdefault((a.region, b.region), []).append(b.index)
    busy = [k for k, v in pairs.items() if len(v) > 2 or (k[0] != k[1] and (k[1], k[0]) in pairs)]
    assert busy, "the patrol walks some edge often"
    assert "moves (steps)" in dot and ("headlabel=A," in dot or 'headlabel="A"' in dot)
    for src, dst in busy:  # no step list on the edge itself, which would overlap
        for line in dot.splitlines():
            if line.strip().startswith(f"{src} -> {dst} "):
                assert "headlabel=" in line and " label=" not in line
