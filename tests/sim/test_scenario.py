"""Scripted scenarios: YAML checked with file:line:col errors; each step checked against ρe."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.core.spec import load
from gaitc.diagnostics import ScenarioError
from gaitc.ir.controller import controller_to_json
from gaitc.sim.domain import Domain
from gaitc.sim.monitor import Monitor
from gaitc.sim.run import Run
from gaitc.sim.scenario import ScriptedEnvironment, load_scenario, parse_scenario
from gaitc.sim.simulator import simulate
from gaitc.sim.strategy import Strategy, strategy_from_controller
from gaitc.solver.synthesis import synthesize
from ltlcompiler.model import Model

SPEC = (Path(__file__).resolve().parents[1] / "data" / "hazard_patrol.gait").read_text(
    encoding="utf-8"
)


class World:
    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self.spec_path = folder / "patrol.gait"
        self.spec_path.write_text(SPEC, encoding="utf-8")
        loaded = load(str(self.spec_path))
        assert loaded.model is not None
        self.model: Model = loaded.model
        controller = synthesize(loaded.gr1)
        assert controller is not None
        self.controller_path = folder / "patrol.json"
        self.controller_path.write_text(controller_to_json(controller), encoding="utf-8")
        self.strategy: Strategy = strategy_from_controller(controller, loaded.gr1)
        self.domain = Domain(self.model, "onehot")
        self.monitor = Monitor(loaded.gr1)

    def scenario_file(self, text: str, name: str = "s.yaml") -> Path:
        path = self.folder / name
        path.write_text(text, encoding="utf-8")
        return path

    def run(self, text: str, name: str = "s.yaml") -> Run:
        scenario = load_scenario(self.scenario_file(text, name), self.model)
        env = ScriptedEnvironment(scenario, self.strategy.inputs)
        return simulate(self.strategy, self.domain, self.monitor, env, 100)


@pytest.fixture(scope="module")
def world(tmp_path_factory: pytest.TempPathFactory) -> World:
    return World(tmp_path_factory.mktemp("scenario"))


def _error(world: World, text: str) -> ScenarioError:
    with pytest.raises(ScenarioError) as info:
        parse_scenario(text, world.model, "s.yaml")
    return info.value


# ---------------------------------------------------------------- checked on loading
@pytest.mark.parametrize(("text", "where", "message"), [
    ("steps:\n  - degrade: [L9]\n", "s.yaml:2:15",
     "unknown leg 'L9'; the robot's legs are L1, L2, L3"),
    ("steps:\n  - hazard: fire\n", "s.yaml:2:13",
     "unknown hazard set 'fire'; use one of h, or none"),
    ("steps:\n  - health: {L2: 4}\n", "s.yaml:2:18", "leg 'L2' has levels 1..3, not 4"),
    ("steps:\n  - health: {L2: two}\n", "s.yaml:2:18",
     "the level of leg 'L2' must be an integer"),
    ("steps:\n  - {}\n  - degrad: [L1]\n", "s.yaml:3:5",
     "unknown key 'degrad' in step 2; expected one of hazard, degrade, fail, health, note"),
    ("steps:\n  - degrade: [L1, L1]\n", "s.yaml:2:19", "leg 'L1' is listed twice under 'degrade'"),
    ("steps:\n  - degrade: [L1]\n    fail: [L1]\n", "s.yaml:2:5",
     "step 1 says two things about leg 'L1'"),
    ("steps: 3\n", "s.yaml:1:8", "'steps' must be a list, one item per step"),
    ("start: {hazard: h}\n", "s.yaml:1:1", "scenario needs a 'steps' list"),
    ("", "s.yaml:1:1", "scenario is empty; it needs a 'steps' list"),
    ("steps:\n  - [\n", "s.yaml:2:6",  # the end of the last line, not a line after it
     "scenario is not valid YAML: expected the node content, but found '<stream end>'"),
    ("start: {degrade: [L1]}\nsteps: []\n", "s.yaml:1:9",
     "unknown key 'degrade' in 'start'; expected one of hazard, health, note"),
])
def test_scenario_errors_on_loading(world: World, text: str, where: str, message: str) -> None:
    err = _error(world, text)
    assert (str(err.span), err.message) == (where, message)


def test_a_valid_scenario_loads_every_step(world: World) -> None:
    scenario = parse_scenario("start: {hazard: none}\nsteps:\n  - {}\n  - hazard: h\n"
                              "  - degrade: L1\n    note: hello\n  -\n", world.model, "s.yaml")
    assert len(scenario.steps) == 4
    assert [s.describe() for s in scenario.steps] == [
        "no change", "hazard h", "degrade L1", "no change"]
    assert [s.span.line for s in scenario.steps] == [3, 4, 5, 7]


# ---------------------------------------------------------------- checked against ρe
def test_scenario_steps_drive_the_run(world: World) -> None:
    first = world.run("steps:\n  - {}\n")
    gait = first.steps[1].gait
    legs = world.domain.legs_used(gait)
    assert legs, "the controller moves on its first step"
    text = "steps:\n  - {}\n  - hazard: h\n    degrade: [" + ", ".join(legs) + "]\n  - {}\n"
    run = world.run(text)
    assert run.error is None and run.summary is not None
    assert len(run.steps) == 4  # the start and three scripted steps
    assert run.steps[2].hazard == "h" and run.steps[3].hazard == "h"
    for leg in legs:
        assert run.steps[2].level(leg) == 2
        assert leg in run.steps[1].degraded  # marked on the move whose gait wore it out
    assert run.summary.assumptions_held and run.summary.guarantees_held


def _rule(world: World, equation: str, word: str) -> str:
    """The origin rule of the one ρe clause of ``equation`` that mentions ``word``."""
    rules = [c.origin.rule for c in world.monitor.spec.env_trans if c.origin is not None
             and c.origin.rule.startswith(equation) and f" {word} " in c.origin.rule + " "]
    assert len(rules) == 1, rules
    return rules[0]


def _line(world: World, equation: str, word: str) -> int:
    """The source line of the clause :func:`_rule` finds."""
    for c in world.monitor.spec.env_trans:
        if c.origin is not None and c.origin.rule == _rule(world, equation, word):
            assert c.origin.span is not None
            return c.origin.span.line
    raise AssertionError(word)


def test_degrading_a_leg_not_in_use_names_the_assumption(world: World) -> None:
    gait = world.run("steps:\n  - {}\n").steps[1].gait
    idle = next(leg for leg in world.domain.legs if leg not in world.domain.legs_used(gait))
    run = world.run(f"steps:\n  - {{}}\n  - degrade: [{idle}]\n", "idle.yaml")
    assert len(run.steps) == 2 and isinstance(run.error, ScenarioError)
    assert str(run.error.span) == f"{world.folder / 'idle.yaml'}:3:5"
    assert run.error.message == (
        f"step 2 (degrade {idle}): {idle} lost a level while not in use (eq. 3.5, line "
        f"{_line(world, 'eq. 3.5', gait)}): the environment breaks the assumption "
        f"'{_rule(world, 'eq. 3.5', gait)}'; the controller has no successor for this input")


def test_skipping_a_level_names_the_assumption(world: World) -> None:
    gait = world.run("steps:\n  - {}\n").steps[1].gait
    leg = world.domain.legs_used(gait)[0]
    run = world.run(f"steps:\n  - {{}}\n  - health: {{{leg}: 1}}\n")
    assert isinstance(run.error, ScenarioError)
    assert run.error.message == (
        f"step 2 ({leg} at level 1): {leg} dropped 2 levels in one move and failed (eq. 3.5, "
        f"line {_line(world, 'eq. 3.5', gait)}): the environment breaks the assumption "
        f"'{_rule(world, 'eq. 3.5', gait)}'; the controller has no successor for this input")


def test_degrading_in_a_cache_names_the_cache_assumption(world: World) -> None:
    run = world.run("steps:\n  - degrade: [L1]\n")  # step 1 leaves the cache nw
    assert isinstance(run.error, ScenarioError)
    assert run.error.message == (
        f"step 1 (degrade L1): L1 lost a level in cache nw (eq. 3.6, line "
        f"{_line(world, 'eq. 3.6', 'nw')}): the environment breaks the assumption "
        f"'{_rule(world, 'eq. 3.6', 'nw')}'; the controller has no successor for this input")


def test_degrading_a_failed_leg_is_refused(world: World) -> None:
    gait = world.run("steps:\n  - {}\n").steps[1].gait
    leg = world.domain.legs_used(gait)[0]
    run = world.run(f"steps:\n  - {{}}\n  - degrade: [{leg}]\n  - degrade: [{leg}]\n"
                    f"  - degrade: [{leg}]\n")
    assert isinstance(run.error, ScenarioError)
    assert run.error.message in (
        f"leg '{leg}' has already failed (level 1) and cannot degrade further",
        # or the controller stopped using it, so eq. 3.5 forbids the step
        *(f"step {k} (degrade {leg}): {leg} {what} (eq. 3.5, line "
          f"{_line(world, 'eq. 3.5', g)}): the environment breaks the assumption "
          f"'{_rule(world, 'eq. 3.5', g)}'; the controller has no successor for this input"
          for k in (3, 4) for g in world.domain.gait_legs if g != "noGait"
          for what in ("lost a level while not in use", "failed while not in use")))


def test_wrong_initial_health_is_refused(world: World) -> None:
    run = world.run("start: {health: {L1: 2}}\nsteps: []\n")
    assert run.steps == [] and run.error is not None
    assert run.error.message == ("step 0 (L1 at level 2): no initial state of the controller "
                                 "has these inputs; the initial assumptions may forbid them")


def test_cli_scripted_error_points_into_the_scenario(world: World,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    path = world.scenario_file("steps:\n  - degrade: [L1]\n", "cli.yaml")
    code = main(["simulate", str(world.spec_path), str(world.controller_path),
                 "--env", "scripted", str(path), "--on-surprise", "stop"])
    err = capsys.readouterr().err
    assert code == 1
    assert err.startswith(f"{path}:2:5: error: step 1 (degrade L1): L1 lost a level in cache "
                          f"nw (eq. 3.6, line {_line(world, 'eq. 3.6', 'nw')}): the "
                          f"environment breaks the assumption '{_rule(world, 'eq. 3.6', 'nw')}'")
    assert "    - degrade: [L1]\n" in err


def test_cli_scripted_surprise_is_recovered_from_by_default(
        world: World, capsys: pytest.CaptureFixture[str]) -> None:
    """Without --on-surprise stop, the step that breaks eq. 3.6 is a surprise the run goes
    on from (issue 52), listed with the assumption in the robot's words."""
    path = world.scenario_file("steps:\n  - degrade: [L1]\n  - {}\n", "cli2.yaml")
    code = main(["simulate", str(world.spec_path), str(world.controller_path),
                 "--env", "scripted", str(path), "--quiet"])
    out = capsys.readouterr().out
    assert code == 0
    assert "surprises:\n  step 1: L1 lost a level in cache nw (eq. 3.6" in out
    assert "recovered" in out or "degraded" in out or "stopped" in out
