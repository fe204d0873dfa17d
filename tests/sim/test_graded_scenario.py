"""Scripted scenarios under a graded hazard (issue 51): a step in an active ``wears k``
region may take up to k levels from a leg in use (``degrade: {L1: 2}``), not fail it."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.core.spec import load
from gaitc.diagnostics import ScenarioError
from gaitc.sim.domain import Domain
from gaitc.sim.map_view import _legend
from gaitc.sim.monitor import Monitor
from gaitc.sim.run import Run
from gaitc.sim.scenario import ScriptedEnvironment, parse_scenario
from gaitc.sim.simulator import simulate
from gaitc.sim.strategy import strategy_from_controller
from gaitc.solver.synthesis import synthesize

#: The hazard on b may stay on; the robot must cross it eastwards with L1 (health 4).
GRADED = """\
legs L1, L2 health 4
gait east uses L1 moves east
gait west uses L2 moves west
grid 1 x 3 cells a, b, c
cache a
hazard sand: b wears 2
start a
visit a, c infinitely often
"""
#: With a failing hazard a leg per gait is lost in b, so each way has two gaits.
FAILING = """\
legs L1..L3 health 4
gait east uses L1 moves east
gait hop uses L2 moves east
gait west uses L3 moves west
gait back uses L2 moves west
grid 1 x 3 cells a, b, c
cache a
hazard sand: b
start a
visit a, c infinitely often
"""


class Corridor:
    """A controller for the corridor and scripted runs against it."""

    def __init__(self, folder: Path, text: str) -> None:
        path = folder / "corridor.gait"
        path.write_text(text, encoding="utf-8")
        loaded = load(str(path))
        assert loaded.model is not None
        self.model = loaded.model
        controller = synthesize(loaded.gr1)
        assert controller is not None
        self.strategy = strategy_from_controller(controller, loaded.gr1)
        self.domain = Domain(self.model, "onehot")
        self.monitor = Monitor(loaded.gr1)

    def run(self, text: str) -> Run:
        scenario = parse_scenario(text, self.model, "s.yaml")
        env = ScriptedEnvironment(scenario, self.strategy.inputs)
        return simulate(self.strategy, self.domain, self.monitor, env, 50)

    def into_b(self) -> tuple[int, str, str]:
        """The index of the first state in b, entered eastwards with the hazard on, the
        gait that entered and its leg."""
        probe = self.run("start: {hazard: sand}\nsteps:\n" + "  - {}\n" * 12)
        at = next(i for i, s in enumerate(probe.steps) if s.region == "b")
        gait = probe.steps[at].gait
        return at, gait, self.model.gait(gait).legs[0]


@pytest.fixture(scope="module")
def graded(tmp_path_factory: pytest.TempPathFactory) -> Corridor:
    return Corridor(tmp_path_factory.mktemp("graded"), GRADED)


@pytest.fixture(scope="module")
def failing(tmp_path_factory: pytest.TempPathFactory) -> Corridor:
    return Corridor(tmp_path_factory.mktemp("failing"), FAILING)


def _script(before: int, step: str) -> str:
    return "start: {hazard: sand}\nsteps:\n" + "  - {}\n" * before + f"  - {step}\n"


def test_a_step_in_the_graded_hazard_may_take_two_levels(graded: Corridor) -> None:
    at, gait, _ = graded.into_b()
    assert gait == "east"
    run = graded.run(_script(at, "{degrade: {L1: 2}}"))
    assert run.error is None, run.error
    assert run.steps[at + 1].level("L1") == 2
    assert "L1" in run.steps[at].degraded  # two levels lost, the leg still works


def test_a_graded_hazard_does_not_fail_the_leg(graded: Corridor) -> None:
    at, _, _ = graded.into_b()
    run = graded.run(_script(at, "{fail: L1}"))
    assert isinstance(run.error, ScenarioError)
    assert "eq. 3.9 graded (eq. 3.5 with up to 2 levels): hazard sand active in b under " \
           "east: leg L1 may lose up to 2 levels" in run.error.message


def test_a_failing_hazard_refuses_a_wear_of_two_levels(failing: Corridor) -> None:
    at, gait, leg = failing.into_b()
    assert failing.run(_script(at, f"{{fail: {leg}}}")).error is None
    run = failing.run(_script(at, f"{{degrade: {{{leg}: 2}}}}"))
    assert isinstance(run.error, ScenarioError)
    assert f"eq. 3.9: hazard sand active in b under {gait} fails leg {leg}" in run.error.message


def test_degrade_by_levels_is_checked_on_loading(graded: Corridor) -> None:
    scenario = parse_scenario("steps:\n  - degrade: {L1: 2, L2: 1}\n  - degrade: [L1]\n",
                              graded.model, "s.yaml")
    assert [s.describe() for s in scenario.steps] == [
        "degrade L1 by 2 levels, degrade L2", "degrade L1"]
    for text, where, message in [
        ("steps:\n  - degrade: {L1: 0}\n", "s.yaml:2:19",
         "leg 'L1' must lose a whole number of levels, at least 1"),
        ("steps:\n  - degrade: {L1: two}\n", "s.yaml:2:19",
         "leg 'L1' must lose a whole number of levels, at least 1"),
        ("steps:\n  - degrade: {L1: 1, L1: 2}\n", "s.yaml:2:22",
         "leg 'L1' is listed twice under 'degrade'"),
    ]:
        with pytest.raises(ScenarioError) as info:
            parse_scenario(text, graded.model, "s.yaml")
        assert (str(info.value.span), info.value.message) == (where, message)


def test_losing_more_levels_than_left_is_a_scenario_error(graded: Corridor) -> None:
    run = graded.run("steps:\n  - degrade: {L1: 4}\n")
    assert isinstance(run.error, ScenarioError)
    assert run.error.message.startswith("leg 'L1' is at level 4 and cannot lose 4 levels")


def test_the_map_legend_says_what_each_hazard_does(graded: Corridor, failing: Corridor) -> None:
    assert "hazard set sand: wears the legs by up to 2 levels" in _legend(graded.model, False)
    assert "hazard set sand: fails the legs" in _legend(failing.model, False)
