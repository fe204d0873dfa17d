"""The independent controller verifier: correct controllers pass, corrupted ones are caught."""

from __future__ import annotations

import random
from dataclasses import replace
from pathlib import Path

import pytest

from gaitc.diagnostics import Span
from gaitc.ir.controller import Controller, ControllerNode, integers_of
from gaitc.ir.formula import FALSE, Compare, Iff, IntVar, Not, Or, Var
from gaitc.ir.spec import Clause, GR1Spec, Origin, Variable
from gaitc.verifier.counterstrategy import verify_counterstrategy
from gaitc.verifier.strategy import verify
from slugs_bridge.slugsin import parse_slugsin

DATA = Path(__file__).resolve().parents[1] / "data"
r, g = Var("r"), Var("g")


def grant_spec() -> GR1Spec:
    """g must copy r at every step (and initially); r recurs; g recurs."""
    return GR1Spec(
        inputs=(Variable("r"),),
        outputs=(Variable("g"),),
        sys_init=(Clause(Iff(g, r), Origin("grant starts like request")),),
        sys_trans=(Clause(Iff(Var("g", True), Var("r", True)), Origin("grant follows request")),),
        env_liveness=(Clause(r, Origin("requests recur")),),
        sys_liveness=(Clause(g, Origin("grants recur")),),
    )


def free_spec() -> GR1Spec:
    """No safety at all: the system must grant infinitely often if requests recur."""
    return GR1Spec(
        inputs=(Variable("r"),),
        outputs=(Variable("g"),),
        env_liveness=(Clause(r, Origin("requests recur")),),
        sys_liveness=(Clause(g, Origin("grants recur")),),
    )


def automaton(
    nodes: list[tuple[tuple[int, ...], tuple[int, ...]]],
    initial: tuple[int, ...],
    variables: tuple[str, ...] = ("r", "g"),
    kind: str = "strategy",
) -> Controller:
    return Controller(
        variables=variables,
        inputs=("r",),
        outputs=("g",),
        nodes=tuple(ControllerNode(0, state, trans) for state, trans in nodes),
        initial=initial,
        kind=kind,
    )


GOOD = [((0, 0), (0, 1)), ((1, 1), (0, 1))]


@pytest.mark.parametrize("semantics", ["default", "robotics"])
def test_hand_made_controller_passes(semantics: str) -> None:
    report = verify(grant_spec(), automaton(GOOD, (0, 1)), semantics)
    assert report.ok, report.problems
    assert (report.nodes, report.edges) == (2, 4)
    assert report.sccs >= 1
    assert "ok" in report.summary()


def test_missing_successor_for_an_allowed_input() -> None:
    report = verify(grant_spec(), automaton([((0, 0), (0,)), ((1, 1), (0, 1))], (0, 1)))
    assert report.problems == (
        "node 0: environment input {r=1} is allowed by the assumptions but has no successor",
    )


def test_successor_violating_the_guarantees() -> None:
    nodes = [((0, 0), (0, 2)), ((1, 1), (0, 1)), ((1, 0), (0, 1))]
    report = verify(grant_spec(), automaton(nodes, (0, 1)))
    assert not report.ok
    assert report.problems[0] == (
        "edge 0 -> 2: the system's move violates sys_trans clause #1 'grant follows request' "
        "(next: {r=1, g=0})"
    )


def test_cycle_that_starves_a_goal() -> None:
    never_grant = [((0, 0), (0, 1)), ((1, 0), (0, 1))]
    report = verify(free_spec(), automaton(never_grant, (0, 1)))
    assert report.problems == (
        "nodes [0, 1] (2 nodes): a cycle through them satisfies every environment liveness "
        "assumption infinitely often but never satisfies sys_liveness clause #1 'grants recur'",
    )


def test_unfair_cycle_may_starve_a_goal() -> None:
    # Granting only after a request: the r=0 self-loop starves g but is not fair.
    lazy = [((0, 0), (0, 1)), ((1, 1), (0, 1))]
    assert verify(free_spec(), automaton(lazy, (0, 1))).ok


def test_missing_initial_node_under_each_semantics() -> None:
    spec, ctrl = grant_spec(), automaton(GOOD, (0,))
    assert verify(spec, ctrl, "default").problems == (
        "no initial node for environment input {r=1} allowed by the assumptions (default "
        "semantics: some initial node must have these inputs and satisfy sys_init)",
    )
    assert verify(spec, ctrl, "robotics").problems == (
        "no initial node for initial state {r=1, g=1} allowed by the assumptions (robotics "
        "semantics: every state allowed by env_init and sys_init must be covered)",
    )


def test_default_semantics_needs_one_start_per_input_robotics_needs_all_states() -> None:
    spec = free_spec()
    one_per_input = automaton([((0, 1), (0, 1)), ((1, 1), (0, 1))], (0, 1))
    assert verify(spec, one_per_input, "default").ok
    robotics = verify(spec, one_per_input, "robotics")
    assert len(robotics.problems) == 1
    assert "initial state" in robotics.problems[0] and "(and 1 more)" in robotics.problems[0]


def test_initial_node_violating_sys_init() -> None:
    nodes = [((0, 1), (1, 2)), ((1, 1), (1, 2)), ((0, 0), (1, 2))]
    report = verify(grant_spec(), automaton(nodes, (0, 1)))
    assert report.problems[0] == (
        "initial node 0: its state {r=0, g=1} violates sys_init clause #1 "
        "'grant starts like request'"
    )


def test_wrong_variable_list() -> None:
    report = verify(grant_spec(), automaton(GOOD, (0, 1), variables=("g", "r")))
    assert report.problems == (
        "controller does not belong to this spec: it lists the spec's variables in another "
        "order: ['g', 'r'] instead of ['r', 'g'] (inputs first, then outputs)",
    )


def test_kind_mismatch_is_reported() -> None:
    counter = automaton(GOOD, (0, 1), kind="counterstrategy")
    assert verify(grant_spec(), counter).problems == (
        "the controller is a counterstrategy, not a strategy for the system",
    )
    assert not verify_counterstrategy(grant_spec(), automaton(GOOD, (0, 1))).ok


def test_input_breaking_the_assumptions_is_only_a_note() -> None:
    spec = replace(
        grant_spec(), env_trans=(Clause(Or((Not(r), Not(Var("r", True)))), Origin("no repeat")),)
    )
    report = verify(spec, automaton(GOOD, (0, 1)))
    assert report.ok, report.problems
    assert report.notes == (
        "edge 1 -> 1: the input violates env_trans clause #1 'no repeat' (next: {r=1}); "
        "harmless, the environment broke its assumptions there",
    )


def test_a_move_on_an_input_the_assumptions_forbid_may_break_the_guarantees() -> None:
    """Issue 60: a correct controller with an extra edge on an input ρe forbids was
    rejected for breaking ρs on that edge, which the note called harmless: once the
    environment breaks its assumptions the play is the system's, whatever it does. The
    extra edge 1 -> 2 repeats the request (forbidden) and answers it with no grant."""
    spec = replace(
        grant_spec(), env_trans=(Clause(Or((Not(r), Not(Var("r", True)))), Origin("no repeat")),)
    )
    nodes = [((0, 0), (0, 1)), ((1, 1), (0, 2)), ((1, 0), (0, 1))]
    report = verify(spec, automaton(nodes, (0, 1)))
    assert report.ok, report.problems
    assert report.notes == tuple(
        f"edge {a} -> {b}: the input violates env_trans clause #1 'no repeat' (next: {{r=1}}); "
        "harmless, the environment broke its assumptions there" for a, b in ((1, 2), (2, 1)))
    # the same move on an input the assumptions allow is still refused
    assert not verify(grant_spec(), automaton(nodes, (0, 1))).ok


def test_unsatisfiable_assumptions_need_no_successors() -> None:
    spec = replace(grant_spec(), env_trans=(Clause(FALSE),))
    report = verify(spec, automaton([((0, 0), ()), ((1, 1), ())], (0, 1)))
    assert report.ok, report.problems


# ---------------------------------------------------------------- counter-strategies
def deadlock_spec() -> GR1Spec:
    text = (DATA / "slugs_examples" / "semantics_diference.slugsin").read_text(encoding="utf-8")
    return parse_slugsin(text, "semantics_diference.slugsin")


def counter(nodes: list[tuple[tuple[int, ...], tuple[int, ...]]], initial: tuple[int, ...]) -> (
    Controller
):
    return Controller(
        variables=("person", "bit0"), inputs=("person",), outputs=("bit0",),
        nodes=tuple(ControllerNode(0, state, trans) for state, trans in nodes),
        initial=initial, kind="counterstrategy", semantics="robotics",
    )


def test_counterstrategy_with_system_deadlock_passes() -> None:
    ctrl = counter([((0, 0), (2,)), ((1, 0), (2,)), ((0, 0), ())], (0, 1))
    report = verify_counterstrategy(deadlock_spec(), ctrl, "robotics")
    assert report.ok, report.problems


def test_counterstrategy_must_start_where_the_system_may() -> None:
    # Under the default semantics the system starts with bit0=1 and wins from there.
    ctrl = counter([((0, 1), (1,)), ((1, 1), (0,))], (0,))
    report = verify_counterstrategy(deadlock_spec(), ctrl, "default")
    assert not report.ok
    assert any("every system goal infinitely often" in p or "never satisfies" in p
               for p in report.problems), report.problems


def test_counterstrategy_missing_system_answer() -> None:
    spec = free_spec()
    # The environment never requests; the system answer g'=1 is missing.
    ctrl = Controller(
        variables=("r", "g"), inputs=("r",), outputs=("g",),
        nodes=(ControllerNode(0, (0, 0), (0,)),), initial=(0,), kind="counterstrategy",
    )
    problems = verify_counterstrategy(spec, ctrl, "robotics").problems
    assert "node 0: system answer {g=1} to input {r=0} is allowed by the guarantees but has no "\
        "successor" in problems
    assert any("never satisfies env_liveness clause #1 'requests recur'" in p for p in problems)


# ---------------------------------------------------------------- embedded solver strategies
def corpus_specs(step: int) -> list[Path]:
    files = sorted((DATA / "gr1_corpus").glob("*.slugsin"))
    return files[::step]


@pytest.mark.parametrize("path", corpus_specs(5), ids=lambda p: p.stem)
def test_embedded_solver_controllers_pass(path: Path) -> None:
    synthesis = pytest.importorskip("gaitc.solver.synthesis")
    spec = parse_slugsin(path.read_text(encoding="utf-8"), str(path))
    for semantics in ("default", "robotics"):
        ctrl = synthesis.synthesize(spec, semantics)
        if ctrl is not None:
            report = verify(spec, ctrl, semantics)
            assert report.ok, (semantics, report.problems)
            _corrupted_transition_is_caught(spec, ctrl, semantics, random.Random(path.stem))
        else:
            cs = synthesis.counterstrategy(spec, semantics)
            assert cs is not None
            report = verify_counterstrategy(spec, cs, semantics)
            assert report.ok, (semantics, report.problems)


def _corrupted_transition_is_caught(
    spec: GR1Spec, ctrl: Controller, semantics: str, rng: random.Random
) -> None:
    """Drop one successor whose input no sibling repeats: the verifier must name that node."""
    inputs = len(ctrl.inputs)
    candidates = []
    for k, node in enumerate(ctrl.nodes):
        seen = [ctrl.nodes[t].state[:inputs] for t in node.trans]
        candidates += [(k, t) for t in node.trans if seen.count(ctrl.nodes[t].state[:inputs]) == 1]
    if not candidates:
        return
    k, t = rng.choice(candidates)
    nodes = list(ctrl.nodes)
    nodes[k] = replace(nodes[k], trans=tuple(x for x in nodes[k].trans if x != t))
    report = verify(spec, replace(ctrl, nodes=tuple(nodes)), semantics)
    if report.ok:  # only possible if the dropped edge's input broke ρe (a harmless edge)
        assert any(f"edge {k} -> {t}:" in n for n in verify(spec, ctrl, semantics).notes)
    else:
        assert any(p.startswith(f"node {k}: environment input") for p in report.problems)


# ---------------------------------------------------------------- integer variables
def integer_spec() -> GR1Spec:
    """y must copy x (both 0..2, so each has an unused bit pattern)."""
    return GR1Spec(
        inputs=(Variable("x", 0, 2),),
        outputs=(Variable("y", 0, 2),),
        sys_trans=(Clause(Compare("=", IntVar("y", True), IntVar("x", True)), Origin("copy")),),
    )


def integer_controller(values: list[tuple[int, int]], trans: list[tuple[int, ...]]) -> Controller:
    bits = ("x@0.0.2", "x@1", "y@0.0.2", "y@1")
    nodes = tuple(ControllerNode(0, (x & 1, x >> 1, y & 1, y >> 1), t)
                  for (x, y), t in zip(values, trans, strict=True))
    return Controller(variables=bits, inputs=bits[:2], outputs=bits[2:], nodes=nodes,
                      initial=tuple(range(len(nodes))),
                      integers=integers_of(bits, frozenset(bits[:2])))


def test_integer_spec_is_bit_blasted_and_messages_decode_integers() -> None:
    pytest.importorskip("gaitc.ir.bitblast")
    spec, every = integer_spec(), (0, 1, 2)
    good = integer_controller([(0, 0), (1, 1), (2, 2)], [every] * 3)
    assert verify(spec, good).ok, verify(spec, good).problems
    missing = integer_controller([(0, 0), (1, 1), (2, 2)], [(0, 1)] * 3)
    assert "node 0: environment input {x=2} is allowed by the assumptions but has no successor" \
        in verify(spec, missing).problems
    wrong = integer_controller([(0, 0), (1, 1), (2, 1)], [every] * 3)
    assert any(p.startswith("edge 0 -> 2: the system's move violates sys_trans clause #1 "
                            "'copy' (next: {x=2, y=1})") for p in verify(spec, wrong).problems)


def test_problem_names_the_source_line_of_the_violated_clause() -> None:
    where = Span("robot.gait", 12, 5)
    spec = replace(grant_spec(), sys_trans=(
        Clause(Iff(Var("g", True), Var("r", True)), Origin("eq. 3.5 grant", where)),))
    nodes = [((0, 0), (0, 2)), ((1, 1), (0, 1)), ((1, 0), (0, 1))]
    assert verify(spec, automaton(nodes, (0, 1))).problems[0] == (
        "edge 0 -> 2: the system's move violates sys_trans clause #1 'eq. 3.5 grant' "
        "(robot.gait:12:5) (next: {r=1, g=0})"
    )
