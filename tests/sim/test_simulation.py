"""Simulation: decoding, environments within the assumptions, the run checker, run files, CLI."""

from __future__ import annotations

import dataclasses
import itertools
import json
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.cli import main
from gaitc.core.spec import load
from gaitc.diagnostics import ControllerError
from gaitc.ir.controller import Controller, controller_to_json
from gaitc.ir.evaluation import evaluate
from gaitc.sim.domain import Domain, State
from gaitc.sim.environments import AdversarialEnvironment, RandomEnvironment, Request, Situation
from gaitc.sim.monitor import Monitor, compile_formula
from gaitc.sim.run import read_jsonl, write_csv, write_jsonl
from gaitc.sim.simulator import simulate
from gaitc.sim.strategy import Strategy, strategy_from_controller
from gaitc.solver.synthesis import synthesize

ROOT = Path(__file__).resolve().parents[2]
PATROL = ROOT / "specs" / "patrol_2x2.gait"
HAZARD_PATROL = (ROOT / "tests" / "data" / "hazard_patrol.gait").read_text(encoding="utf-8")


@dataclasses.dataclass
class Setup:
    path: str
    controller: Controller
    strategy: Strategy
    domain: Domain
    monitor: Monitor


def _setup(path: str, encoding: str = "onehot") -> Setup:
    loaded = load(path, encoding)
    assert loaded.model is not None
    controller = synthesize(loaded.gr1)
    assert controller is not None
    return Setup(path, controller, strategy_from_controller(controller, loaded.gr1),
                 Domain(loaded.model, encoding), Monitor(loaded.gr1))


@pytest.fixture(scope="module")
def patrol() -> Setup:
    return _setup(str(PATROL))


@pytest.fixture(scope="module")
def hazard_path(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("spec") / "hazard_patrol.gait"
    path.write_text(HAZARD_PATROL, encoding="utf-8")
    return str(path)


@pytest.fixture(scope="module")
def hazard(hazard_path: str) -> Setup:
    return _setup(hazard_path)


# ---------------------------------------------------------------- decoding
def test_decoding_hand_checked_onehot_state(patrol: Setup) -> None:
    values = {"nw": 0, "ne": 0, "sw": 1, "se": 0, "north": 0, "south": 1, "east": 0,
              "west": 0, "noGait": 0, "L1_h1": 0, "L1_h2": 1, "L2_h1": 1, "L2_h2": 0,
              "L3_h1": 0, "L3_h2": 1, "L4_h1": 0, "L4_h2": 1}
    assert patrol.domain.decode(values) == State(
        "sw", "south", (("L1", 2), ("L2", 1), ("L3", 2), ("L4", 2)), None)


def test_decoding_hand_checked_binary_state(hazard_path: str) -> None:
    loaded = load(hazard_path, "binary")
    assert loaded.model is not None
    domain = Domain(loaded.model, "binary")
    # regions nw, ne, sw, se = 0..3; gaits in declaration order, noGait last = 8
    values = {"region": 3, "gait": 4, "hazard": 1, "L1": 3, "L2": 2, "L3": 1}
    assert domain.decode(values) == State("se", "east_b", (("L1", 3), ("L2", 2), ("L3", 1)),
                                          "h")
    assert domain.encode(domain.decode(values)) == values


def test_initial_controller_state_is_the_declared_start(patrol: Setup, hazard: Setup) -> None:
    for setup, start, full in ((patrol, "nw", 2), (hazard, "nw", 3)):
        for node in setup.strategy.initial:
            state = setup.domain.decode(setup.strategy.valuation(node))
            assert (state.region, state.gait) == (start, "noGait")
            assert all(level == full for _, level in state.health)


# ---------------------------------------------------------------- environments
def _assert_within_assumptions(setup: Setup, run_steps: list, env_name: str) -> None:
    monitor = setup.monitor
    assert monitor.check_initial(monitor.values(dict(run_steps[0].values))) == []
    for before, after in itertools.pairwise(run_steps):
        check = monitor.check_step(monitor.values(dict(before.values)),
                                   monitor.values(dict(after.values)))
        assert check.env_failed == (), f"{env_name} broke an assumption at step {after.index}"
        assert check.sys_failed == (), f"controller broke a guarantee at step {after.index}"


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(min_value=0, max_value=10**9))
def test_random_environment_stays_within_the_assumptions(hazard: Setup, seed: int) -> None:
    run = simulate(hazard.strategy, hazard.domain, hazard.monitor, RandomEnvironment(seed), 60)
    assert run.error is None and run.summary is not None
    assert run.summary.assumptions_held and run.summary.guarantees_held
    assert len(run.steps) == 61
    _assert_within_assumptions(hazard, run.steps, "random")


def test_random_environment_is_deterministic_per_seed(hazard: Setup) -> None:
    def text(seed: int) -> str:
        return write_jsonl(simulate(hazard.strategy, hazard.domain, hazard.monitor,
                                    RandomEnvironment(seed), 40))

    assert text(7) == text(7)
    assert len({text(seed) for seed in range(6)}) > 1


@pytest.mark.parametrize("name", ["patrol", "hazard"])
def test_adversarial_environment_stays_within_the_assumptions_and_hurts(
        name: str, request: pytest.FixtureRequest) -> None:
    setup: Setup = request.getfixturevalue(name)
    run = simulate(setup.strategy, setup.domain, setup.monitor, AdversarialEnvironment(), 80)
    assert run.error is None and run.summary is not None
    assert run.summary.assumptions_held and run.summary.guarantees_held
    _assert_within_assumptions(setup, run.steps, "adversarial")
    caches = set(setup.domain.model.caches)
    for before, after in zip(run.steps, run.steps[1:], strict=False):
        if before.region in caches:
            continue
        for leg in before.legs_used:  # every leg in use loses a level if it still can
            if before.level(leg) > 1:
                assert after.level(leg) < before.level(leg), (before, after)
    random_losses = sum(len(s.degraded) + len(s.failed) for s in simulate(
        setup.strategy, setup.domain, setup.monitor, RandomEnvironment(0), 80).steps)
    assert len(run.summary.legs_failed) + len(run.summary.legs_degraded) >= random_losses


def test_adversarial_environment_activates_the_nearest_hazard(hazard: Setup) -> None:
    run = simulate(hazard.strategy, hazard.domain, hazard.monitor,
                   AdversarialEnvironment(plan=False), 30)
    active = [s.hazard == "h" for s in run.steps[1:]]
    # the only set is on, except when fairness (□◇ !h) makes the adversary switch it off
    assert sum(active) >= 0.7 * len(active)
    assert not any(not a and not b for a, b in itertools.pairwise(active))
    off = sum(s.hazard != "h" for s in run.steps)  # at every step, the first one too
    assert run.summary is not None and dict(run.summary.env_liveness) == {
        "assumption (line 17): !h": off}


def test_summary_counts_goals_caches_and_failures(patrol: Setup) -> None:
    run = simulate(patrol.strategy, patrol.domain, patrol.monitor, AdversarialEnvironment(), 12)
    summary = run.summary
    assert summary is not None
    visits = dict(summary.goal_visits)
    assert visits == {"sw": sum(s.region == "sw" for s in run.steps),
                      "se": sum(s.region == "se" for s in run.steps)}
    assert dict(summary.cache_visits) == {"ne": sum(s.region == "ne" for s in run.steps)}
    assert list(summary.legs_failed) == [(s.index, leg) for s in run.steps for leg in s.failed]
    assert summary.legs_failed, "the adversary fails legs of two-level robots"


# ---------------------------------------------------------------- the run checker
def _corrupt(controller: Controller, node: int, region: str) -> Controller:
    """Move ``node`` to ``region`` without changing anything else (breaks eq. 3.3)."""
    regions = ("nw", "ne", "sw", "se")
    state = list(controller.nodes[node].state)
    for name in regions:
        state[controller.variables.index(name)] = int(name == region)
    nodes = list(controller.nodes)
    nodes[node] = dataclasses.replace(nodes[node], state=tuple(state))
    return dataclasses.replace(controller, nodes=tuple(nodes))


def _diagonal(setup: Setup, node: int) -> str:
    here = setup.domain.decode(setup.strategy.valuation(node)).region
    return {"nw": "se", "se": "nw", "ne": "sw", "sw": "ne"}[here]


def test_monitor_catches_a_corrupted_controller(patrol: Setup) -> None:
    spec = load(str(PATROL)).gr1
    first = patrol.strategy.initial[0]
    victim = patrol.strategy.successors[first][0]
    bad = strategy_from_controller(_corrupt(patrol.controller, victim, _diagonal(patrol, first)),
                                   spec)
    run = simulate(bad, patrol.domain, Monitor(spec), RandomEnvironment(0), 5)
    assert run.summary is not None
    assert run.summary.assumptions_held and not run.summary.guarantees_held
    assert run.summary.violations[0].startswith("step 1: guarantee violated: eq. 3.3: from nw")


def test_cli_exits_1_on_a_corrupted_controller(patrol: Setup, tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    first = patrol.strategy.initial[0]
    victim = patrol.strategy.successors[first][0]
    path = tmp_path / "bad.json"
    path.write_text(controller_to_json(_corrupt(patrol.controller, victim,
                                                _diagonal(patrol, first))), encoding="utf-8")
    assert main(["simulate", str(PATROL), str(path), "--steps", "4", "--quiet"]) == 1
    captured = capsys.readouterr()
    assert "guarantees:      VIOLATED" in captured.out
    assert "the controller broke a guarantee" in captured.err


def test_dead_end_stops_the_run_with_a_message(patrol: Setup) -> None:
    first = patrol.strategy.initial[0]
    succ = list(patrol.strategy.successors)
    succ[first] = ()
    broken = dataclasses.replace(patrol.strategy, successors=tuple(succ), _options={})
    run = simulate(broken, patrol.domain, patrol.monitor, RandomEnvironment(0), 5)
    assert len(run.steps) == 1
    assert isinstance(run.error, ControllerError)
    assert run.error.message == (f"step 1: controller node {first} has no successor (a dead "
                                 "end); the controller is not a winning strategy for this spec")


def test_request_outside_the_assumptions_names_the_assumption(patrol: Setup) -> None:
    class Breaker(RandomEnvironment):
        def choose(self, situation: Situation) -> Request | None:
            if situation.step < 2:
                return super().choose(situation)
            # every leg failed at once: eq. 3.5 lets at most the legs in use lose one level
            return Request(tuple(0 if n.endswith("_h2") else 1 for n in
                                 patrol.strategy.inputs), "all legs fail")

    run = simulate(patrol.strategy, patrol.domain, patrol.monitor, Breaker(0), 5)
    assert len(run.steps) == 2 and run.error is not None
    message = run.error.message
    assert message.startswith("step 2 (all legs fail): L1 failed while not in use, ")
    assert ": the environment breaks the assumption 'eq. 3." in message


@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_compiled_clauses_agree_with_evaluate(hazard: Setup, data: st.DataObject) -> None:
    spec = hazard.monitor.spec
    names = hazard.monitor.variables
    bits = data.draw(st.lists(st.integers(0, 1), min_size=2 * len(names),
                              max_size=2 * len(names)))
    valuation = {n: bits[i] for i, n in enumerate(names)}
    valuation.update({n + "'": bits[len(names) + i] for i, n in enumerate(names)})
    for clause in spec.env_trans + spec.sys_trans + spec.sys_liveness:
        fn = compile_formula(clause.formula, names)
        assert fn(bits) == evaluate(clause.formula, valuation)


# ---------------------------------------------------------------- run files and the CLI
def test_jsonl_round_trip_and_csv(hazard: Setup) -> None:
    run = simulate(hazard.strategy, hazard.domain, hazard.monitor, RandomEnvironment(3), 15)
    text = write_jsonl(run)
    lines = [json.loads(line) for line in text.splitlines()]
    assert [x["kind"] for x in lines] == ["run"] + ["step"] * 16 + ["summary"]
    path = Path(hazard.path).with_suffix(".jsonl")
    path.write_text(text, encoding="utf-8")
    back = read_jsonl(path)
    assert back.steps == run.steps and back.legs == ("L1", "L2", "L3")
    rows = write_csv(run).splitlines()
    assert rows[0] == ("step,node,region,gait,legs_used,health_L1,health_L2,health_L3,"
                       "hazard,goals,degraded,failed,repaired")
    assert len(rows) == 17


def test_cli_simulate_synthesizes_prints_and_saves(tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run.jsonl"
    code = main(["simulate", str(PATROL), "--env", "adversarial", "--steps", "6",
                 "--out", str(out)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    header = captured.out.splitlines()[0].split()
    assert header == ["step", "region", "gait", "legs", "used", "L1", "L2", "L3", "L4",
                      "hazard", "goal"]
    assert "\x1b[" not in captured.out  # no colour when stdout is not a terminal
    assert "assumptions:     held at every step" in captured.out
    assert len(out.read_text(encoding="utf-8").splitlines()) == 1 + 7 + 1


@pytest.mark.parametrize(("argv", "message"), [
    (["--env", "scripted"], "--env scripted needs one scenario or run file: --env scripted "
     "FILE.yaml or --env scripted RUN.jsonl"),
    (["--env", "chaotic"], "unknown environment 'chaotic'; use one of scripted, random, "
                           "adversarial, stochastic"),
    (["--env", "random", "x.yaml"], "--env random takes no file (got 'x.yaml')"),
])
def test_cli_usage_errors(argv: list[str], message: str,
                          capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["simulate", str(PATROL), *argv]) == 2
    assert capsys.readouterr().err.strip() == f"gaitc: usage error: {message}"


def test_cli_rejects_a_controller_of_another_spec(hazard: Setup, tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "other.json"
    path.write_text(controller_to_json(hazard.controller), encoding="utf-8")
    assert main(["simulate", str(PATROL), str(path)]) == 1
    assert "does not" in capsys.readouterr().err


def test_step_table_colours_health_only_when_asked(patrol: Setup) -> None:
    from gaitc.sim.terminal import step_table, summary_text

    run = simulate(patrol.strategy, patrol.domain, patrol.monitor, AdversarialEnvironment(), 6)
    full = {leg: 2 for leg in patrol.domain.legs}
    plain = step_table(run, full, colour=False)
    coloured = step_table(run, full, colour=True)
    assert "\x1b[" not in plain
    assert "\x1b[34m\x1b[1m2!" in coloured  # a leg in use that this step's gait fails
    assert "\x1b[31m1 " in coloured  # failed legs in red
    assert "\x1b[34m" in coloured  # healthy legs in blue
    failed = next(s for s in run.steps if s.failed)
    leg = failed.failed[0]
    row = plain.splitlines()[failed.index + 1].split()
    assert row[0] == str(failed.index) and f"{failed.level(leg)}!" in row
    assert leg in failed.legs_used  # marked on the row whose gait used it
    after = plain.splitlines()[failed.index + 2].split()
    assert run.steps[failed.index + 1].level(leg) == 1 and after[0] == str(failed.index + 1)
    assert run.summary is not None
    text = summary_text(run.summary, "adversarial")
    assert "legs failed:" in text and "(none)" not in text.split("legs failed:")[1].splitlines()[0]
