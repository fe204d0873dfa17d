"""Well-separation (:mod:`gaitc.analysis.separation`, after Maoz and Ringert, FSE 2016).

Every answer is checked here without the analysis's BDDs: the environment's winning region
is solved again by enumerating states (a generalized Büchi game for the environment, each
step judged by :class:`gaitc.sim.monitor.Monitor`) on tiny random Boolean specs
(hypothesis) and on the .gait specs of tests/data/separation/; the forcing play is replayed
under the monitor; the preferred controllers are checked against the property they claim
by the independent verifier and by enumerating their nodes.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from pathlib import Path

import pytest
from games import clauses, tiny_specs
from hypothesis import HealthCheck, example, given, settings

import gaitc
from gaitc.analysis.separation import (
    Broken,
    Finding,
    Separation,
    _forcing,
    environment_winning,
    separation,
    stay_separated,
)
from gaitc.cli import main
from gaitc.ir.controller import Controller
from gaitc.ir.formula import Not, Var
from gaitc.ir.spec import GR1Spec, Semantics, Variable
from gaitc.sim.domain import Domain, State
from gaitc.sim.monitor import Monitor
from gaitc.solver.symbolic import Options, SymbolicSpec
from ltlcompiler.encoding import EncodingName
from ltlcompiler.model import NO_GAIT

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "separation"
EXAMPLES = sorted((ROOT / "gaitc" / "examples").glob("*.gait"))
#: What the analysis found for every shipped spec: all well-separated (the thesis's robots
#: A and B included), in both encodings.
SHIPPED_WELL_SEPARATED = {path.stem: True for path in EXAMPLES}

Values = tuple[int, ...]


# ---------------------------------------------------------------- an explicit reference
def explicit_environment_winning(monitor: Monitor, states: Sequence[Values],
                                 inputs: Sequence[Values], outputs: Sequence[Values]
                                 ) -> set[Values]:
    """νZ. ∧_i μY. EPre((J_i ∧ Z') ∨ Y') by enumeration, EPre(T) holding at s when some
    input keeps every env_trans clause and every output answer keeping sys_trans lands in
    T; ``states`` must hold every successor that keeps sys_trans."""
    n_live = len(monitor.spec.env_liveness)
    goals = list(range(n_live)) or [-1]

    def env_ok(s: Values, x: Values) -> bool:
        return not monitor.check_step(s, x + outputs[0]).env_failed  # no primed outputs

    def epre(target: Callable[[Values, Values], bool]) -> set[Values]:
        return {s for s in states
                if any(env_ok(s, x) and all(monitor.check_step(s, x + y).sys_failed
                                            or target(s, x + y) for y in outputs)
                       for x in inputs)}

    def holds(i: int, s: Values, t: Values) -> bool:
        return i < 0 or i in monitor.check_step(s, t).env_live

    z = set(states)
    while True:
        new = set(z)
        for i in goals:
            y: set[Values] = set()
            while True:
                zz, yy = frozenset(z), frozenset(y)
                def target(s: Values, t: Values, i: int = i, zz: frozenset[Values] = zz,
                           yy: frozenset[Values] = yy) -> bool:
                    return (holds(i, s, t) and t in zz) or t in yy

                grown = epre(target) & new
                if grown == y:
                    break
                y = grown
            new &= y
        if new == z:
            return z
        z = new


def bdd_holds(sym: SymbolicSpec, region: object, names: Sequence[str], values: Values
              ) -> bool:
    """Whether the state ``values`` (Boolean variables ``names``) lies in BDD ``region``."""
    at = {n: bool(v) for n, v in zip(names, values, strict=True)}
    return bool(sym.bdd.let(at, region) == sym.bdd.true)  # type: ignore[arg-type]


def boolean_states(spec: GR1Spec) -> tuple[list[Values], list[Values], list[Values]]:
    n_in, n_out = len(spec.inputs), len(spec.outputs)
    xs = [tuple(x) for x in itertools.product((0, 1), repeat=n_in)]
    ys = [tuple(y) for y in itertools.product((0, 1), repeat=n_out)]
    return [x + y for x in xs for y in ys], xs, ys


# ---------------------------------------------------------------- tiny random specs
#: The environment's moves that let no robot answer leave a set must be chosen before the
#: robot's answer is (a play once looked at both at once).
AVOIDING = GR1Spec(inputs=(Variable("x0"),), outputs=(Variable("y0"),),
                   env_trans=clauses(Var("x0")), env_liveness=clauses(Not(Var("y0"))))


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(tiny_specs())
@example(AVOIDING)
def test_the_environments_winning_region_agrees_with_enumeration(spec: GR1Spec) -> None:
    sym = SymbolicSpec(spec, Options(care=False))
    winning = environment_winning(sym)
    monitor = Monitor(spec)
    states, xs, ys = boolean_states(spec)
    expected = explicit_environment_winning(monitor, states, xs, ys)
    names = [v.name for v in spec.variables()]
    got = {s for s in states if bdd_holds(sym, winning, names, s)}
    assert got == expected
    # the system's forcing rings cover exactly the rest (the dual fixpoint)
    _, forced = _forcing(sym, tuple(range(len(spec.env_liveness))), None)
    assert {s for s in states if bdd_holds(sym, forced, names, s)} == set(states) - expected
    # the verdict: every state of θe ∧ θs in W
    initial = [s for s in states if not monitor.check_initial(s)]
    found = separation(spec)
    assert found.well_separated == all(s in expected for s in initial)
    assert found.well_separated == (not found.findings)
    for finding in found.findings:
        replay(monitor, finding, expected)


def replay(monitor: Monitor, finding: Finding, winning: set[Values]) -> None:
    """The forcing play starts at an initial state outside ``winning``, keeps every
    guarantee and every safety assumption on its steps, and ends where the environment
    has no input keeping the named clauses (safety) or loops without the named □◇
    assumption ever holding (liveness)."""
    play = finding.play
    assert play.names == monitor.variables
    assert not monitor.check_initial(play.states[0])
    assert play.states[0] not in winning
    steps = list(itertools.pairwise(play.states))
    if play.loop_start is not None:
        steps.append((play.states[-1], play.states[play.loop_start]))
    for before, after in steps:
        checked = monitor.check_step(before, after)
        assert not checked.sys_failed and not checked.env_failed
    if finding.kind is Broken.LIVENESS:
        assert play.loop_start is not None and finding.assumptions
        for assumption in finding.assumptions:
            assert assumption.section == "env_liveness"
            for before, after in steps[play.loop_start:]:
                assert assumption.index not in monitor.check_step(before, after).env_live
        return
    assert play.loop_start is None
    core = {a.index for a in finding.assumptions}
    assert {a.section for a in finding.assumptions} <= {"env_trans"}
    inputs = list(itertools.product((0, 1), repeat=len(monitor.inputs)))

    def failed(x: tuple[int, ...], kept: set[int]) -> bool:
        return bool(kept & set(monitor.failed_assumptions(
            play.states[-1], dict(zip(monitor.inputs, x, strict=True)))))

    assert all(failed(x, core) for x in inputs)
    for dropped in core:  # minimal: without any one clause the environment has a move
        assert not all(failed(x, core - {dropped}) for x in inputs)


# ---------------------------------------------------------------- the flagged specs
def domain_states(spec: gaitc.Spec) -> tuple[Domain, list[Values], list[Values], list[Values]]:
    """Every state of a .gait spec's robot (regions, gaits, levels, hazard) as values in the
    monitor's order, and the input and output halves that occur."""
    assert spec.model is not None
    domain = Domain(spec.model, EncodingName.ONEHOT)
    monitor = Monitor(spec.gr1)
    gaits = sorted({*domain.gait_legs, NO_GAIT})
    levels = [range(1, domain.full[leg] + 1) for leg in domain.legs]
    hazards: list[str | None] = [None, *sorted(domain.hazard_regions)]
    states = []
    for region, gait, health, hazard in itertools.product(
            domain.regions, gaits, itertools.product(*levels), hazards):
        state = State(region, gait, tuple(zip(domain.legs, health, strict=True)), hazard)
        states.append(monitor.values(domain.encode(state)))
    n_in = len(monitor.inputs)
    xs = sorted({s[:n_in] for s in states})
    ys = sorted({s[n_in:] for s in states})
    return domain, states, xs, ys


@pytest.fixture(scope="module")
def flagged() -> dict[str, tuple[gaitc.Spec, Separation]]:
    out = {}
    for name in ("starved_region", "forced_hazard", "forced_goal"):
        spec = gaitc.load(DATA / f"{name}.gait")
        out[name] = (spec, separation(spec))
    return out


@pytest.mark.parametrize("name", ["starved_region", "forced_hazard"])
def test_lint_flags_the_assumption_and_a_forcing_strategy(name: str) -> None:
    path = DATA / f"{name}.gait"
    warnings = [d for d in gaitc.lint(path) if "not well-separated" in d.message]
    assert len(warnings) == 1
    (warning,) = warnings
    assert warning.severity == "warning" and warning.span is not None
    assert warning.span.file == str(path)
    if name == "starved_region":
        assert (warning.span.line, warning.span.column) == (16, 1)
        assert "'assumption (line 16): r3'" in warning.message
        assert warning.hint == ("from r1, the robot stays in r1 for ever: 'assumption "
                                "(line 16): r3' never holds again")
    else:
        assert (warning.span.line, warning.span.column) == (18, 1)
        assert "r2 -> next(blue)" in warning.message and "r2 -> next(!blue)" in warning.message
        assert warning.hint is not None
        assert warning.hint.startswith("from r0, the robot goes east to r1, then goes east "
                                       "to r2: there the environment has no move")


def test_the_forcing_plays_replay_under_the_monitor(
        flagged: dict[str, tuple[gaitc.Spec, Separation]]) -> None:
    """Each flagged spec's play, replayed (:func:`replay`) against the environment's
    winning region solved by enumerating the robot's states."""
    for name in ("starved_region", "forced_hazard"):
        spec, found = flagged[name]
        assert not found.well_separated
        (finding,) = found.findings
        assert finding.kind is (Broken.LIVENESS if name == "starved_region" else Broken.SAFETY)
        monitor = Monitor(spec.gr1)
        _, states, xs, ys = domain_states(spec)
        replay(monitor, finding, explicit_environment_winning(monitor, states, xs, ys))


def test_the_region_agrees_with_enumeration_on_the_flagged_specs(
        flagged: dict[str, tuple[gaitc.Spec, Separation]]) -> None:
    for name, (spec, _) in flagged.items():
        sym = SymbolicSpec(spec.gr1, Options(care=False))
        winning = environment_winning(sym)
        monitor = Monitor(spec.gr1)
        _, states, xs, ys = domain_states(spec)
        expected = explicit_environment_winning(monitor, states, xs, ys)
        got = {s for s in states if bdd_holds(sym, winning, monitor.variables, s)}
        assert got == expected, name


@pytest.mark.parametrize("semantics", list(Semantics))
def test_the_check_on_the_solvers_build_is_the_separate_analysis(
        flagged: dict[str, tuple[gaitc.Spec, Separation]], semantics: Semantics) -> None:
    """``gaitc check`` checks separation on the solver's own symbolic spec (its care set,
    whatever order the plan left it in); the answer is the analysis's on a build of its own,
    finding for finding, on the flagged specs, a well-separated example and two published
    instances (one decided early as unrealizable)."""
    published = Path(__file__).resolve().parent.parent / "data" / "published"
    specs = [spec for spec, _ in flagged.values()] + [
        gaitc.load(Path(__file__).resolve().parent.parent.parent / "specs"
                   / "thesis_robot_a.gait"),
        gaitc.load(published / "GyroLTL_595_GyroAspect_fixed.structuredslugs"),
        gaitc.load(published / "HumanoidLTL_458_Humanoid_fixed_unrealizable.structuredslugs")]
    for spec in specs:
        shared = gaitc.check(spec, semantics, separation=True).separation
        assert shared is not None
        alone = separation(spec)
        drop = ("seconds",)
        assert ({k: v for k, v in shared.to_json().items() if k not in drop}
                == {k: v for k, v in alone.to_json().items() if k not in drop}), spec.path


def test_forced_everywhere_under_both_semantics(
        flagged: dict[str, tuple[gaitc.Spec, Separation]]) -> None:
    """One start, which the robot can force from: the stronger case for both semantics."""
    for _, found in flagged.values():
        assert found.forced_everywhere == {Semantics.DEFAULT: True, Semantics.ROBOTICS: True}


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_every_shipped_spec_is_checked(path: Path) -> None:
    encodings = ("onehot", "binary") if path.stem not in (
        "centipede24_patrol", "radial12_patrol") else ("onehot",)
    for encoding in encodings:
        found = separation(gaitc.load(path, encoding))
        assert found.well_separated is SHIPPED_WELL_SEPARATED[path.stem], (path, encoding)
        assert not found.warnings()


# ---------------------------------------------------------------- synthesis prefers
def legal_input_everywhere(spec: gaitc.Spec, controller: Controller) -> bool:
    """Whether at every node of ``controller`` some input keeps every env_trans clause."""
    monitor = Monitor(spec.gr1)
    n_in = len(monitor.inputs)
    for node in range(len(controller.nodes)):
        here = monitor.values(controller.values(node))
        if not any(not monitor.failed_assumptions(here, dict(zip(monitor.inputs, x,
                                                                 strict=True)))
                   for x in itertools.product((0, 1), repeat=n_in)):
            return False
    return True


@pytest.mark.parametrize("semantics", ["default", "robotics"])
def test_synthesis_prefers_a_controller_that_never_blocks(semantics: str) -> None:
    spec = gaitc.load(DATA / "forced_hazard.gait")
    found = gaitc.synthesize(spec, semantics=semantics, form="explicit")
    assert found.verified
    assert found.separation is not None
    assert found.separation.startswith("the controller never forces the environment to "
                                       "break 'assumption (line 18)")
    assert isinstance(found.controller, Controller)
    assert legal_input_everywhere(spec, found.controller)


def test_synthesis_prefers_a_controller_that_does_not_rely_on_starving() -> None:
    """The preferred controller is proved by the verifier against the spec without the
    starved assumption: it does not need it."""
    spec = gaitc.load(DATA / "starved_region.gait")
    found = gaitc.synthesize(spec)
    assert found.verified and found.controller is not None
    assert found.separation is not None
    assert "does not rely on 'assumption (line 16): r3' failing" in found.separation
    text = (DATA / "starved_region.gait").read_text(encoding="utf-8")
    without = gaitc.parse(text.replace("assume always eventually r3\n", ""),
                          name=str(DATA / "starved_region.gait"))
    assert gaitc.verify(without, found.controller).ok


def test_synthesis_says_when_every_controller_relies_on_blocking() -> None:
    spec = gaitc.load(DATA / "forced_goal.gait")
    assert stay_separated(spec) is not None
    assert not gaitc.check(stay_separated(spec)[0]).realizable  # type: ignore[index]
    found = gaitc.synthesize(spec, form="explicit")
    assert found.verified and isinstance(found.controller, Controller)
    assert found.separation is not None
    assert found.separation.startswith("the controller may win by forcing the environment")
    assert not legal_input_everywhere(spec, found.controller)


def test_well_separated_specs_synthesize_as_before() -> None:
    found = gaitc.synthesize(gaitc.load(ROOT / "specs" / "patrol_2x2.gait"))
    assert found.separation is None and found.to_json()["separation"] is None
    assert stay_separated(gaitc.load(ROOT / "specs" / "patrol_2x2.gait")) is None


# ---------------------------------------------------------------- the command line
def test_check_and_synth_say_it(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = str(DATA / "starved_region.gait")
    assert main(["check", path]) == 0
    out, err = capsys.readouterr()
    assert out.startswith(f"{path}: realizable")
    assert err.startswith(f"{path}:16:1: warning: not well-separated")
    assert main(["synth", path, "-o", str(tmp_path / "c.json")]) == 0
    out, _ = capsys.readouterr()
    assert "  note: the controller does not rely on" in out
    assert main(["check", str(ROOT / "specs" / "patrol_2x2.gait")]) == 0
    assert "well-separated" not in capsys.readouterr().err


def test_a_notebook_shows_the_note() -> None:
    found = gaitc.synthesize(gaitc.load(DATA / "starved_region.gait"))
    assert "well-separation" in found._repr_html_()


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(tiny_specs())
def test_the_stricter_spec_keeps_the_environment_able(spec: GR1Spec) -> None:
    """From every state where the environment has a move at all, it can keep the stricter
    spec's (weakened) assumptions against every robot that keeps the stricter ρs (solved
    by enumeration); and synthesis writes a controller proved against the spec itself,
    which, when it says so, never leaves the environment without a move."""
    stricter = stay_separated(spec)
    if stricter is None:
        return
    strict, _ = stricter
    states, xs, ys = boolean_states(spec)
    plain = Monitor(spec)
    stuck = {s for s in states
             if all(plain.check_step(s, x + ys[0]).env_failed for x in xs)}
    able = explicit_environment_winning(Monitor(strict), states, xs, ys)
    assert set(states) - stuck <= able
    found = gaitc.synthesize(spec, form="explicit")
    if found.controller is None:
        return
    assert found.verified and found.separation is not None
    if found.separation.startswith("the controller may win"):
        return
    assert isinstance(found.controller, Controller)
    names = [v.name for v in spec.variables()]
    for node in range(len(found.controller.nodes)):
        values = found.controller.values(node)
        assert tuple(int(values[n]) for n in names) not in stuck
