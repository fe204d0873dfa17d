"""The engine's plan (gaitc.solver.portfolio): the static order, then the configuration a
misfit names, every switch decided by counts.

The plan is tested with stand-in solvers (one that never finishes, one that fails, one
that misfits), and for real on the shipped specs: verdicts and controllers must not depend
on the configuration, and two runs of one spec take the same path. The child processes of
:func:`gaitc.diagnostics.processes.first_success` (a time limit, isolation, the language
server's jobs) are tested here too.
"""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path
from typing import Any
from unittest import mock

import pytest

import gaitc
from gaitc.diagnostics import SolverError, Span, SpecSyntaxError
from gaitc.diagnostics.processes import claim, first_success, to_parent
from gaitc.solver import game as game_module
from gaitc.solver import portfolio, synthesis
from gaitc.solver.game import Limits, OrderMisfit
from gaitc.solver.portfolio import DYNAMIC, SIFTED, STATIC, engine_options, solve_chosen
from gaitc.solver.symbolic import Options, SymbolicSpec
from gaitc.verifier.strategy import verify

ROOT = Path(__file__).resolve().parents[2]
SPECS = ["patrol_2x2", "unrealizable_2x2", "thesis_robot_b", "corridor_hazard"]


def test_a_misfit_builds_the_spec_again_in_the_configuration_it_names() -> None:
    seen: list[Options] = []

    def run(options: Options, limits: Limits) -> Options:
        seen.append(options)
        if options.reordering is False and not options.sift_build:
            raise OrderMisfit(dynamic=dynamic)
        return options

    for dynamic, engine in ((True, DYNAMIC), (False, SIFTED)):  # noqa: B007 (run reads it)
        seen.clear()
        answer, chosen = solve_chosen(run, Options(), Limits())
        assert chosen == engine and answer == engine_options(engine)
        assert [o.reordering for o in seen] == [False, engine == DYNAMIC]


def test_a_quick_spec_is_answered_by_the_static_order_alone() -> None:
    def run(options: Options, limits: Limits) -> tuple[bool | None, str]:
        return options.sift_build, options.order

    assert solve_chosen(run, Options(), Limits()) == ((False, "guards"), STATIC)


def test_a_failure_of_the_static_configuration_is_the_answer() -> None:
    """No second configuration runs after an error: the plan switches on counts only."""
    seen: list[Options] = []

    def static_fails(options: Options, limits: Limits) -> str:
        seen.append(options)
        raise MemoryError

    with pytest.raises(MemoryError):
        solve_chosen(static_fails, Options(), Limits())
    assert len(seen) == 1


def test_without_a_time_limit_the_plan_runs_in_this_process(
        monkeypatch: pytest.MonkeyPatch) -> None:
    def no_fork(*args: Any, **kwargs: Any) -> Any:
        raise AssertionError("the solver forked")

    seen: list[Options] = []

    def run(options: Options, limits: Limits) -> str:
        seen.append(options)  # in this process: a child's list would not come back
        return "answer"

    monkeypatch.setattr(portfolio, "first_success", no_fork)
    for bits in (portfolio.SMALL_BITS, portfolio.SMALL_BITS + 1, None):
        assert solve_chosen(run, Options(), Limits(), bits=bits) == ("answer", STATIC)
    assert [o.restart_misfit for o in seen] == [True, False, False]
    corpus_spec = gaitc.load(ROOT / "specs" / "patrol_2x2.gait", "binary").gr1
    assert synthesis.state_bits(corpus_spec) <= portfolio.SMALL_BITS
    assert synthesis.check(corpus_spec).engine == STATIC
    with pytest.raises(AssertionError, match="forked"):
        solve_chosen(run, Options(), Limits(timeout=5))


def test_an_explicit_choice_or_a_memory_budget_is_never_raced() -> None:
    seen: list[Options] = []

    def run(options: Options, limits: Limits) -> bool:
        seen.append(options)  # in this process: a racer's list would not come back
        return bool(options.reordering)

    assert solve_chosen(run, Options(reordering=True), Limits()) == (True, DYNAMIC)
    assert solve_chosen(run, Options(memory_mb=100), Limits()) == (False, STATIC)
    assert [o.reordering for o in seen] == [True, None]


def test_the_time_limit_holds_through_one_long_call() -> None:
    def never(options: Options, limits: Limits) -> None:
        time.sleep(60)  # never checks its own time limit

    started = time.monotonic()
    with pytest.raises(SolverError, match="time limit of 1 s"):
        solve_chosen(never, Options(), Limits(timeout=1))
    assert time.monotonic() - started < 2.5


def test_an_error_of_the_static_configuration_is_raised() -> None:
    def broken(options: Options, limits: Limits) -> None:
        raise SolverError(f"failed with sift_build={options.sift_build}")

    with pytest.raises(SolverError, match="failed with sift_build=False"):
        solve_chosen(broken, Options(), Limits())


@pytest.mark.parametrize("name", SPECS)
def test_verdicts_and_controllers_do_not_depend_on_the_configuration(name: str) -> None:
    gr1 = gaitc.load(ROOT / "specs" / f"{name}.gait", "binary").gr1
    alone = synthesis.check(gr1).realizable
    for engine in (STATIC, SIFTED, DYNAMIC):
        assert synthesis.check(gr1, options=engine_options(engine)).realizable == alone
    limited = synthesis.check(gr1, timeout=60)  # the plan in a child process
    assert limited.realizable == alone and limited.engine == STATIC
    controller = synthesis.synthesize(gr1)
    assert (controller is not None) == alone
    if controller is not None:
        assert verify(gr1, controller).ok


def _decide_in_a_daemon(queue: Any) -> None:
    gr1 = gaitc.load(ROOT / "specs" / "patrol_2x2.gait").gr1
    result = synthesis.check(gr1)
    queue.put((result.realizable, result.engine))


def test_a_daemonic_worker_solves_in_itself() -> None:
    """Daemonic processes (bench/fuzz.py's workers) may not have children: the solver then
    runs the plan in the worker itself instead of failing."""
    import multiprocessing

    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    worker = context.Process(target=_decide_in_a_daemon, args=(queue,), daemon=True)
    worker.start()
    answer = queue.get(timeout=60)
    worker.join(timeout=60)
    assert answer == (True, STATIC)
    assert worker.exitcode == 0


@pytest.mark.parametrize("name", ["patrol_2x2", "corridor_hazard", "thesis_robot_b"])
@pytest.mark.parametrize("semantics", ["default", "robotics"])
def test_every_configuration_writes_the_same_controller_byte_for_byte(
        name: str, semantics: str) -> None:
    """Moves are chosen in the static order whatever the BDD order, so the file a user gets
    does not depend on which configuration the plan chose."""
    from gaitc.ir.bddfile import SymbolicController
    from gaitc.ir.controller import controller_to_json
    from gaitc.sim.environments import RandomEnvironment

    spec = gaitc.load(ROOT / "specs" / f"{name}.gait", "binary")
    texts, runs = [], []
    for engine in (STATIC, SIFTED, DYNAMIC):
        found = synthesis.synthesize(spec.gr1, semantics, options=engine_options(engine))
        assert found is not None
        texts.append(controller_to_json(found))
        sym = synthesis.synthesize_controller(spec.gr1, semantics,
                                              options=engine_options(engine), form="symbolic")
        assert isinstance(sym, SymbolicController)
        run = gaitc.simulate(spec, sym, env=RandomEnvironment(3), steps=200)
        runs.append([step.values for step in run.steps])
    assert texts[0] == texts[1] == texts[2]
    assert runs[0] == runs[1] == runs[2]  # the symbolic runtime chooses in the same order too


def test_a_static_build_too_large_for_its_order_starts_again_sifting(tmp_path: Path) -> None:
    """The AMBA arbiter's relation passes SIFT_TRIGGER nodes a bit in the guards order, so
    the build starts again with CUDD sifting; robot A's stays far below and keeps the static
    order. Both answer as the other configurations do."""
    from bench.families.amba import amba_text
    from gaitc.solver.game import Game
    from gaitc.solver.options import SIFT_TRIGGER
    from gaitc.solver.symbolic import SymbolicSpec
    from slugs_bridge.formats import load_spec_file

    path = tmp_path / "amba2.structuredslugs"
    path.write_text(amba_text(2), encoding="utf-8")
    amba = load_spec_file(str(path))
    robot_a = gaitc.load(ROOT / "specs" / "thesis_robot_a.gait").gr1
    for gr1, sifts in ((amba, True), (robot_a, False)):
        sym = SymbolicSpec(gr1, Options(reordering=False))
        assert sym.sifted_build is sifts
        bits = len(sym.input_bits) + len(sym.output_bits)
        assert sym.sys_trans.dag_size <= SIFT_TRIGGER * bits  # after sifting too
        never = SymbolicSpec(gr1, Options(reordering=False, sift_above=None))
        assert never.sifted_build is False
        pinned = SymbolicSpec(gr1, Options(reordering=False, first=(gr1.inputs[0].name,)))
        assert pinned.sifted_build is False  # an order pinned on purpose (analysis) is kept
        game, plain = Game(sym), Game(never)
        won, plain_won = game.solve().winning, plain.solve().winning
        assert sym.restarted is sifts
        original = Game.resume_sifting
        with mock.patch.object(game_module, "RESIFT_WORK", -1), \
                mock.patch.object(Game, "resume_sifting", autospec=True,
                                  side_effect=original) as resumed:  # sift again at once
            again = SymbolicSpec(gr1, Options(reordering=False))
            resifted = Game(again)
            again_won = resifted.solve().winning
        assert resumed.called is sifts
        assert again.bdd.configure()["reordering"] is False  # for its game only
        forced = [mock.patch.object(game_module, name, -1.0)
                  for name in ("RESIFT_WORK", "SMALL_WORK", "RESIFT_NODES", "RESIFT_BLOWUP",
                               "MISFIT_WORK", "MISFIT_RATIO")]
        for patch in forced:
            patch.start()
        try:
            Game(pinned).solve()  # every misfit rule forced: a pinned order still stays
        finally:
            for patch in forced:
                patch.stop()
        assert not pinned.bdd.configure()["reordering"]
        for semantics in ("default", "robotics"):
            assert (game.initially_winning(won, semantics)
                    == plain.initially_winning(plain_won, semantics)
                    == resifted.initially_winning(again_won, semantics))


def test_a_static_build_far_larger_than_its_clauses_is_sifted_once_built(tmp_path: Path) -> None:
    """AMBA with two masters in the SYNTCOMP bit encoding stays under SIFT_TRIGGER, but its
    ρs comes out 20 times the nodes of its clauses in the guards order: it is sifted once
    (``settled``), to a smaller ρs and the same winning region; robot A is left alone."""
    from bench.families.amba_bits import amba_bits_text
    from gaitc.solver.game import Game
    from gaitc.solver.options import SIFT_BLOWUP
    from gaitc.solver.symbolic import SymbolicSpec
    from slugs_bridge.formats import load_spec_file

    path = tmp_path / "amba_bits2.structuredslugs"
    path.write_text(amba_bits_text(2), encoding="utf-8")
    amba = load_spec_file(str(path))
    robot_a = gaitc.load(ROOT / "specs" / "thesis_robot_a.gait").gr1
    for gr1, sifts in ((amba, True), (robot_a, False)):
        sym = SymbolicSpec(gr1, engine_options(STATIC))
        fixed = SymbolicSpec(gr1, Options(reordering=False, sift_blowup=None))
        assert (sym.settled, sym.refitted, sym.restarted) == (sifts, sifts, False)
        assert not fixed.settled and not fixed.refitted
        if sifts:
            assert fixed.sys_trans.dag_size > SIFT_BLOWUP * fixed._sys_parts
            assert sym.sys_trans.dag_size < fixed.sys_trans.dag_size / 4
        pinned = SymbolicSpec(gr1, Options(reordering=False, first=(gr1.inputs[0].name,)))
        assert not pinned.settled  # an order pinned on purpose is kept
        game, plain = Game(sym), Game(fixed)
        won, plain_won = game.solve().winning, plain.solve().winning
        for semantics in ("default", "robotics"):
            assert game.initially_winning(won, semantics) == plain.initially_winning(
                plain_won, semantics)


def test_a_game_whose_steps_work_too_hard_for_its_sets_is_built_again_sifting(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The rule of MISFIT_RATIO, forced by thresholds of zero: the static game stops with a
    dynamic misfit, the plan answers sifting throughout, and the winning region is the
    same; a refitted build (GenBuf) or an order pinned on purpose is never judged."""
    from bench.families.genbuf import genbuf_text
    from slugs_bridge.formats import load_spec_file

    path = tmp_path / "genbuf4.structuredslugs"
    path.write_text(genbuf_text(4), encoding="utf-8")
    genbuf = load_spec_file(str(path))
    robot_b = gaitc.load(ROOT / "specs" / "thesis_robot_b.gait", "binary").gr1
    monkeypatch.setattr(game_module, "MISFIT_WORK", 0)
    monkeypatch.setattr(game_module, "MISFIT_RATIO", 0.0)
    static = SymbolicSpec(robot_b, replace(engine_options(STATIC), rebuild_misfit=True))
    assert not static.refitted
    with pytest.raises(OrderMisfit) as raised:
        game_module.Game(static).solve()
    assert raised.value.dynamic
    verdict = synthesis.check(robot_b)
    assert verdict.realizable and verdict.engine == DYNAMIC
    game_module.Game(SymbolicSpec(robot_b, engine_options(STATIC))).solve()  # not asked to
    pinned = SymbolicSpec(robot_b, Options(reordering=False, rebuild_misfit=True,
                                           first=(robot_b.inputs[0].name,)))
    game_module.Game(pinned).solve()  # no misfit: the order was chosen on purpose
    refitted = SymbolicSpec(genbuf, replace(engine_options(STATIC), rebuild_misfit=True))
    assert refitted.refitted
    assert game_module.Game(refitted).solve().winning is not None


def test_the_sifting_a_misfit_turns_on_ends_with_its_game(monkeypatch: pytest.MonkeyPatch
                                                           ) -> None:
    """A misfit turns CUDD's sifting on for the rest of its game only: left on, the
    manager was sifted whole, the kept layers too, inside whatever operation of the
    extraction next passed its threshold (radial12's synth: 9 s became 165 s).  Forced
    here: every step of robot B's static game is judged a misfit."""
    robot_b = gaitc.load(ROOT / "specs" / "thesis_robot_b.gait", "binary").gr1
    sym = SymbolicSpec(robot_b, engine_options(STATIC))
    game = game_module.Game(sym)
    resumed: list[bool] = []
    original = game.resume_sifting

    def resume() -> None:
        resumed.append(sym.bdd.configure()["reordering"])
        original()

    monkeypatch.setattr(game, "_order_misfits", lambda *_: game_module._SIFT)
    monkeypatch.setattr(game, "resume_sifting", resume)
    result = game.solve(keep_layers=True)
    assert resumed and resumed[0] is False, "the static game turned sifting on"
    assert sym.bdd.configure()["reordering"] is False
    assert result.winning == game_module.Game(sym).solve().winning  # sifted, same region


@pytest.mark.parametrize("name", ["thesis_robot_a", "corridor_hazard"])
def test_the_plan_takes_the_same_path_on_every_run(name: str) -> None:
    """No decision depends on time: two runs, here and in a child, count the same steps."""
    gr1 = gaitc.load(ROOT / "specs" / f"{name}.gait").gr1
    first, second = synthesis.check(gr1), synthesis.check(gr1, timeout=120)
    assert first.engine == second.engine
    assert ((first.stats.z_iterations, first.stats.y_iterations, first.stats.x_iterations)
            == (second.stats.z_iterations, second.stats.y_iterations,
                second.stats.x_iterations))


def _claims_then(answer: str, seconds: float, fail: bool = False) -> Any:
    def work() -> str:
        to_parent("before the claim")
        claim()
        time.sleep(seconds)
        to_parent(f"{answer} after the claim")
        if fail:
            raise SolverError("the claimant failed")
        return answer

    return work


def _answers_after(seconds: float) -> Any:
    def work() -> str:
        time.sleep(seconds)
        to_parent("the other")
        return "other"

    return work


def test_a_claim_makes_the_claimants_answer_the_races() -> None:
    """Without the claim the other child, done after 0.2 s, would win; its messages and
    its answer are dropped, and the claimant's are kept."""
    heard: list[str] = []
    started, cpu = time.monotonic(), time.process_time()
    index, outcome = first_success([_answers_after(0.2), _claims_then("mine", 1.0)],
                                   relay=heard.append)
    assert (index, outcome) == (1, ("ok", "mine"))
    assert time.monotonic() - started >= 1.0
    assert time.process_time() - cpu < 0.5  # the parent waits on the pipe, it does not spin
    assert "mine after the claim" in heard and "the other" not in heard


def test_a_claimant_that_fails_is_the_answer_even_if_the_other_would_have_won() -> None:
    index, outcome = first_success([_claims_then("mine", 0.3, fail=True),
                                    _answers_after(0.1)])
    assert index == 0 and outcome[0] == "raise"
    assert "the claimant failed" in str(outcome[1])


def test_a_claim_before_the_head_start_ends_starts_no_second_child(tmp_path: Path) -> None:
    marker = tmp_path / "started"

    def second() -> str:
        marker.write_text("yes", encoding="utf-8")
        return "other"

    index, outcome = first_success([_claims_then("mine", 0.5), second], delays=(0.0, 0.2))
    assert (index, outcome) == (0, ("ok", "mine"))
    assert not marker.exists()


def test_claim_outside_a_child_does_nothing() -> None:
    claim()  # no parent to tell


MISFIT = ROOT / "tests" / "data" / "misfit"


@pytest.mark.parametrize("name,semantics", [("compare_0076", "default"),
                                            ("compare_0135", "robotics")])
def test_a_small_spec_whose_guards_order_misfits_is_built_again_sifted(
        name: str, semantics: str) -> None:
    """18 state bits, so no race: in the guards order one goal's J ∧ Z' has a million
    nodes, and sifting that manager in place took 15 s; built sifted, it solves at once.
    SLUGS says both are realizable."""
    spec = gaitc.load(MISFIT / f"{name}.structuredslugs").gr1
    assert synthesis.state_bits(spec) <= portfolio.SMALL_BITS
    verdict = synthesis.check(spec, semantics)
    assert verdict.realizable and verdict.engine == SIFTED
    controller = synthesis.synthesize(spec, semantics)
    assert controller is not None and verify(spec, controller, semantics).ok


def test_a_game_asked_to_restart_stops_at_a_misfit_step() -> None:
    spec = gaitc.load(MISFIT / "compare_0076.structuredslugs").gr1
    sym = SymbolicSpec(spec, Options(reordering=False, restart_misfit=True))
    with pytest.raises(OrderMisfit):
        game_module.Game(sym).solve()


def _raises_with_a_module() -> object:
    import json

    err = SpecSyntaxError("bad byte", Span("spec.gait", 3, 7))
    err.__dict__["parser_state"] = json  # what cannot be pickled (a module)
    raise err


def test_a_child_error_that_does_not_pickle_still_reaches_the_parent_as_itself() -> None:
    _, outcome = first_success([_raises_with_a_module])
    assert outcome[0] == "raise"
    err = outcome[1]
    assert isinstance(err, SpecSyntaxError) and "bad byte" in str(err)
    assert "parser_state" not in vars(err)
