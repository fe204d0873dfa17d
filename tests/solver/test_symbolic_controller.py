"""Symbolic controllers: file format, runtime, independent verifier, and the commands.

The runtime must make the explicit controller's moves (runs are compared step by step), the
verifier must accept every synthesized controller and reject broken ones (mutants built
from the solver's own BDDs), and malformed files get positioned messages.
"""

from __future__ import annotations

import itertools
import json
import re
from pathlib import Path
from typing import Any

import dd.cudd as cudd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import gaitc
from gaitc.cli import main
from gaitc.diagnostics import ControllerError, UsageError
from gaitc.ir.bddfile import (
    SymbolicController,
    materialize,
    node_table,
    symbolic_from_dict,
    symbolic_to_json,
)
from gaitc.ir.evaluation import evaluate
from gaitc.sim.domain import Domain
from gaitc.sim.environments import AdversarialEnvironment, Environment, RandomEnvironment
from gaitc.sim.monitor import Monitor
from gaitc.sim.simulator import Simulator
from gaitc.sim.strategy import strategy_from_controller
from gaitc.sim.symbolic_view import SymbolicStrategy
from gaitc.solver import synthesis
from gaitc.solver.game import Game, goal_strategies
from gaitc.solver.symbolic import SymbolicSpec
from gaitc.verifier.symbolic import verify_symbolic

SPECS = Path(__file__).parents[2] / "specs"
SMALL = ["patrol_2x2", "corridor_hazard", "correction_edges", "radial8_patrol",
         "thesis_robot_b"]


def _symbolic(name: str, semantics: str = "default") -> tuple[gaitc.Spec, SymbolicController]:
    spec = gaitc.load(SPECS / f"{name}.gait")
    found = synthesis.synthesize_controller(spec.gr1, semantics, form="symbolic")
    assert isinstance(found, SymbolicController)
    return spec, found


# ---------------------------------------------------------------- file format
@pytest.mark.parametrize("name", SMALL)
def test_the_file_round_trips_and_rebuilds_the_same_functions(name: str) -> None:
    spec, ctrl = _symbolic(name)
    text = symbolic_to_json(ctrl)
    assert text == symbolic_to_json(symbolic_from_dict(json.loads(text)))  # deterministic
    assert symbolic_from_dict(json.loads(text)) == ctrl
    sym = SymbolicSpec(spec.gr1)
    again = materialize(sym.bdd, ctrl)
    assert again["env_trans"] == sym.env_trans
    assert again["goals"] == list(sym.sys_live)


_EXPR = st.recursive(
    st.sampled_from(["a", "b", "c", "d", "e", "TRUE", "FALSE"]),
    lambda inner: st.one_of(
        st.tuples(st.just("!"), inner).map(lambda t: f"!({t[1]})"),
        st.tuples(inner, st.sampled_from(["&", "|", "^", "->"]), inner).map(
            lambda t: f"({t[0]} {t[1]} {t[2]})")),
    max_leaves=14)


@settings(max_examples=150, deadline=None)
@given(st.lists(_EXPR, min_size=1, max_size=4), st.permutations(list("abcde")))
def test_node_tables_rebuild_every_function_in_any_order(exprs: list[str],
                                                         order: list[str]) -> None:
    """Brute force over all assignments, in a manager declared in another order."""
    source = cudd.BDD()
    source.declare(*"abcde")
    roots = [source.add_expr(e) for e in exprs]
    names, nodes, refs = node_table(source, {"goals": roots, "strategies": roots,
                                             **{k: roots[0] for k in
                                                ("winning", "env_init", "sys_init",
                                                 "env_trans")}})
    ctrl = SymbolicController(("a", "b"), ("c", "d", "e"), names, nodes, refs)
    target = cudd.BDD()
    target.declare(*order)
    rebuilt = materialize(target, ctrl)["goals"]
    for values in itertools.product([False, True], repeat=5):
        point = dict(zip("abcde", values, strict=True))
        for u, v in zip(roots, rebuilt, strict=True):
            assert source.let(point, u) == (source.true if target.let(point, v) ==
                                             target.true else source.false)


def _file(tmp_path: Path, edit: Any) -> Path:
    _, ctrl = _symbolic("patrol_2x2")
    data = json.loads(symbolic_to_json(ctrl))
    edit(data)
    path = tmp_path / "broken.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


BROKEN = [
    (lambda d: d["gaitc"].update(version=9),
     "this symbolic controller file is format version 9, written by a newer gaitc; this gaitc "
     "reads versions up to 1"),
    (lambda d: d["nodes"].__setitem__(0, [0, 5, 1]),
     "BDD node 0: reference 5 is not an earlier node"),
    (lambda d: d["nodes"].__setitem__(0, [999, 0, 1]),
     "BDD node 0: variable 999 is not in 'order'"),
    (lambda d: d["nodes"].__setitem__(0, [0, 1, 1]),
     "BDD node 0 has equal children (not reduced)"),
    (lambda d: d["roots"].pop("winning"), "'roots.winning' must be a reference into 'nodes'"),
    (lambda d: d["roots"]["goals"].append(0),
     "'roots.goals' and 'roots.strategies' must have one entry per goal each"),
    (lambda d: d["order"].append("nobody"),
     "'order' names ['nobody'], which is no input or output bit (primed or not)"),
]


@pytest.mark.parametrize(("edit", "message"), BROKEN)
def test_malformed_files_get_exact_messages(tmp_path: Path, edit: Any, message: str,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    path = _file(tmp_path, edit)
    assert main(["verify", str(SPECS / "patrol_2x2.gait"), str(path)]) == 1
    assert f"{path}:1:1: error: {message}" in capsys.readouterr().err


# ---------------------------------------------------------------- runtime
def _run(strategy: Any, spec: gaitc.Spec, env: Environment, steps: int) -> Any:
    assert spec.model is not None
    sim = Simulator(strategy, Domain(spec.model, "onehot"), Monitor(spec.gr1))
    return sim.run(env, steps)


@pytest.mark.parametrize("name", ["patrol_2x2", "radial8_patrol", "thesis_robot_a"])
@pytest.mark.parametrize("semantics", ["default", "robotics"])
def test_a_symbolic_run_makes_the_explicit_controllers_moves(name: str, semantics: str) -> None:
    spec, ctrl = _symbolic(name, semantics)
    explicit = synthesis.synthesize(spec.gr1, semantics)
    assert explicit is not None
    # the planning adversary plans over explicit controllers only: its one-step rules here
    for make in (lambda: RandomEnvironment(7), lambda: AdversarialEnvironment(plan=False)):
        a = _run(SymbolicStrategy(ctrl, spec.gr1), spec, make(), 400)
        b = _run(strategy_from_controller(explicit, spec.gr1), spec, make(), 400)
        assert a.error is None and a.summary.guarantees_held
        assert [s.values for s in a.steps] == [s.values for s in b.steps]


def test_a_controller_of_another_spec_is_refused() -> None:
    _, ctrl = _symbolic("patrol_2x2")
    other = gaitc.load(SPECS / "corridor_hazard.gait")
    with pytest.raises(ControllerError, match="does not belong to this spec"):
        SymbolicStrategy(ctrl, other.gr1)


# ---------------------------------------------------------------- verifier
@pytest.mark.parametrize("name", SMALL)
@pytest.mark.parametrize("semantics", ["default", "robotics"])
def test_the_verifier_accepts_every_synthesized_controller(name: str, semantics: str) -> None:
    spec, ctrl = _symbolic(name, semantics)
    report = verify_symbolic(spec.gr1, ctrl)
    assert report.ok, report.problems
    assert report.symbolic and report.nodes > 0


def _mutant(name: str, change: str) -> tuple[gaitc.Spec, SymbolicController]:
    """A controller whose roots are the solver's, with one part broken."""
    spec = gaitc.load(SPECS / f"{name}.gait")
    sym = SymbolicSpec(spec.gr1)
    result = Game(sym).solve(keep_layers=True)
    strategies = goal_strategies(sym, result)
    roots: dict[str, Any] = {"winning": result.winning, "env_init": sym.env_init,
                             "sys_init": sym.sys_init, "env_trans": sym.env_trans,
                             "goals": list(sym.sys_live), "strategies": strategies}
    if change == "stay safe, never progress":
        roots["strategies"] = [sym.sys_trans & sym.prime(result.winning)] * len(strategies)
    elif change == "any move":
        roots["strategies"] = [sym.bdd.true] * len(strategies)
    elif change == "no initial state":
        roots["winning"] = sym.bdd.false
    elif change == "fewer inputs":
        roots["env_trans"] = sym.env_trans & ~sym.bdd.var(sym.input_bits[0] + "'")
    order, nodes, refs = node_table(sym.bdd, roots)
    ctrl = SymbolicController(tuple(sym.input_bits), tuple(sym.output_bits), order, nodes, refs)
    return spec, ctrl


@pytest.mark.parametrize(("change", "problem"), [
    ("stay safe, never progress", "satisfies every environment liveness assumption "
     "infinitely often but never"),
    ("any move", "violates sys_trans"),
    ("no initial state", "an input allowed by env_init has no initial state"),
    ("fewer inputs", "a reachable state has an input the assumptions allow but no move"),
])
@pytest.mark.parametrize("name", ["patrol_2x2", "corridor_hazard"])
def test_the_verifier_rejects_broken_controllers(name: str, change: str, problem: str) -> None:
    spec, ctrl = _mutant(name, change)
    report = verify_symbolic(spec.gr1, ctrl)
    assert not report.ok
    assert any(problem in p for p in report.problems), report.problems


def _named_values(text: str) -> dict[str, int]:
    return {k: int(v) for k, v in (part.split("=") for part in text.split(", "))}


@pytest.mark.parametrize("name", ["patrol_2x2", "corridor_hazard"])
def test_a_rejected_move_names_its_witness(name: str) -> None:
    """Issue 60: symbolic verify's failures named no state, where the explicit verifier
    names the node; the witness given is checked here by evaluating the spec's clauses
    directly (no BDD): the move breaks the clause named, the input keeps the assumptions."""
    spec, ctrl = _mutant(name, "any move")
    found = [p for p in verify_symbolic(spec.gr1, ctrl).problems if "violates sys_trans" in p]
    shape = re.compile(r"goal \d+: a move from a reachable state violates sys_trans \(for "
                       r"example from the state (.*), the environment choosing (.*), moving "
                       r"to (.*); it breaks (.*)\)$")
    matched = shape.match(found[0])
    assert matched is not None, found[0]
    state, chosen, moved = (_named_values(matched.group(k)) for k in (1, 2, 3))
    values = {**state, **{k + "'": v for k, v in (chosen | moved).items()}}
    assert all(evaluate(c.formula, values) for c in spec.gr1.env_trans)
    named = [int(k) for k in re.findall(r"sys_trans clause #(\d+)", matched.group(4))]
    assert named and all(not evaluate(spec.gr1.sys_trans[k - 1].formula, values)
                         for k in named)


def test_a_missing_move_names_its_witness() -> None:
    spec, ctrl = _mutant("patrol_2x2", "fewer inputs")
    found = [p for p in verify_symbolic(spec.gr1, ctrl).problems if "no move" in p]
    shape = re.compile(r"goal \d+: a reachable state has an input the assumptions allow but "
                       r"no move \(for example from the state (.*), the environment choosing "
                       r"(.*)\)$")
    matched = shape.match(found[0])
    assert matched is not None, found[0]
    state, chosen = _named_values(matched.group(1)), _named_values(matched.group(2))
    values = {**state, **{k + "'": v for k, v in chosen.items()}}
    assert all(evaluate(c.formula, values) for c in spec.gr1.env_trans)


def test_the_unbroken_mutant_base_is_accepted() -> None:
    spec, ctrl = _mutant("corridor_hazard", "none")
    assert verify_symbolic(spec.gr1, ctrl).ok


# ---------------------------------------------------------------- commands
def test_synth_symbolic_then_verify_simulate_and_drive(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    spec, out = str(SPECS / "radial8_patrol.gait"), tmp_path / "r8.json"
    assert main(["synth", spec, "--symbolic", "-o", str(out)]) == 0
    said = capsys.readouterr().out
    assert "wrote" in said and "symbolic, " in said and "verified: symbolic strategy ok" in said
    assert main(["verify", spec, str(out)]) == 0
    assert main(["simulate", spec, str(out), "--steps", "30", "--env", "adversarial"]) == 0
    assert "guarantees:      held at every step" in capsys.readouterr().out
    assert main(["drive", spec, str(out), "--steps", "10"]) == 0
    run = tmp_path / "run.json"
    assert main(["simulate", spec, str(out), "--steps", "12", "--out", str(run)]) == 0
    assert main(["render", "map", spec, "--run", str(run), "-o", str(tmp_path / "m.svg")]) == 0


def test_synth_keeps_a_controller_symbolic_past_max_nodes(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec, out = str(SPECS / "patrol_2x2.gait"), tmp_path / "p.json"
    assert main(["synth", spec, "--max-nodes", "5", "-o", str(out)]) == 0
    assert "(symbolic, " in capsys.readouterr().out
    assert json.loads(out.read_text())["gaitc"]["format"] == "symbolic-strategy"
    assert main(["render", "automaton", spec, str(out), "-o", str(tmp_path / "a.svg")]) == 1
    assert "drawing the automaton needs an explicit controller" in capsys.readouterr().err
    assert main(["synth", spec, "-o", str(tmp_path / "e.json")]) == 0
    assert "(symbolic" not in capsys.readouterr().out


def test_the_api_gives_and_verifies_symbolic_controllers() -> None:
    spec = gaitc.load(SPECS / "corridor_hazard.gait")
    found = gaitc.synthesize(spec, form="symbolic")
    assert found.verified and isinstance(found.controller, SymbolicController)
    assert "symbolic" in repr(found) and "BDD nodes" in found._repr_html_()
    run = gaitc.simulate(spec, found, steps=20)
    assert run.summary is not None and run.summary.guarantees_held
    with pytest.raises(UsageError, match="unknown controller form"):
        gaitc.synthesize(spec, form="tabular")
