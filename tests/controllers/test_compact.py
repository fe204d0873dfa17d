"""Compact controllers (issue 35): decision diagrams over the robot's words, proved and run.

Checked independently of the code that builds them: every compact controller is proved on
every state by the symbolic verifier (a tampered one is rejected, so the proof is not
vacuous); its Python run makes the moves of the symbolic runtime over the same relations
on random and adversarial runs; its file round-trips and a malformed one is one line naming
the file; generated C (``--target c``) makes the same moves as Python for 10,000 steps and
its compiled tables, read back, are proved again.
"""

from __future__ import annotations

import json
import random
import shutil
import subprocess
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import pytest

import gaitc
from gaitc.cli import main
from gaitc.codegen.build import build, read_dump
from gaitc.compact.controller import (
    CompactController,
    Runner,
    compact_from_dict,
    compact_to_dict,
    compact_to_json,
    to_symbolic,
)
from gaitc.compact.diagram import Branch
from gaitc.core.spec import Spec
from gaitc.diagnostics import ControllerError
from gaitc.forms.reader import runtime as view_of

ROOT = Path(__file__).resolve().parents[2]
needs_gcc_early = pytest.mark.skipif(shutil.which("gcc") is None, reason="gcc is not installed")
SPECS = ROOT / "specs"
ROBOT_A = SPECS / "thesis_robot_a.gait"
QUICK = ["thesis_robot_a.gait", "thesis_robot_b.gait", "corridor_hazard.gait",
         "patrol_2x2.gait", "shuttle_2leg.gait", "correction_edges.gait"]


@pytest.fixture(scope="module")
def compacts() -> dict[str, tuple[Spec, CompactController]]:
    out = {}
    for name in QUICK:
        spec = gaitc.load(SPECS / name)
        made = gaitc.synthesize(spec, form="compact")
        assert made.verified, name
        assert isinstance(made.controller, CompactController)
        out[name] = (spec, made.controller)
    return out


# ---------------------------------------------------------------------------- proofs
@pytest.mark.parametrize("name", QUICK)
def test_every_compact_controller_is_proved_on_every_state(
        compacts: dict[str, tuple[Spec, CompactController]], name: str) -> None:
    spec, ctrl = compacts[name]
    assert gaitc.verify(spec, ctrl).ok
    assert ctrl.rules >= ctrl.goal_count and ctrl.decision_nodes >= 0


def test_robot_a_fits_in_a_dozen_rules(
        compacts: dict[str, tuple[Spec, CompactController]]) -> None:
    _, ctrl = compacts["thesis_robot_a.gait"]
    assert ctrl.rules <= 12 and ctrl.decision_nodes <= 8


def _changed_move(ctrl: CompactController) -> CompactController:
    """The controller with one reachable leaf of goal 1 sent to another move."""
    root = ctrl.move_roots[0]
    if root < 0:
        other = (-root - 1 + 1) % len(ctrl.moves)
        return replace(ctrl, move_roots=(-other - 1, *ctrl.move_roots[1:]))
    nodes = list(ctrl.nodes)
    branch = nodes[root]
    value = next(v for v in range(len(branch.kids)) if v not in branch.unused)
    kid = branch.kids[value]
    if kid >= 0:
        kid = -1
    new = -((-kid - 1 + 1) % len(ctrl.moves)) - 1
    kids = list(branch.kids)
    kids[value] = new
    nodes[root] = Branch(branch.field, tuple(kids), branch.unused)
    return replace(ctrl, nodes=tuple(nodes))


@pytest.mark.parametrize("name", ["thesis_robot_a.gait", "corridor_hazard.gait"])
def test_a_changed_move_fails_the_proof(
        compacts: dict[str, tuple[Spec, CompactController]], name: str) -> None:
    spec, ctrl = compacts[name]
    assert not gaitc.verify(spec, _changed_move(ctrl)).ok


# ---------------------------------------------------------------------------- runs
def _field_values(ctrl: CompactController, valuation: dict[str, int], inputs: bool
                  ) -> dict[str, int]:
    out = {}
    for f in ctrl.vocabulary.fields:
        if f.is_input == inputs:
            value = f.value_of(valuation)
            assert value is not None, f.name
            out[f.name] = value
    return out


def _walk(spec: Spec, ctrl: CompactController, steps: int, seed: int, adversarial: bool
          ) -> Iterator[tuple[dict[str, int], dict[str, int]]]:
    """(inputs chosen, outputs made) of a run of the symbolic runtime over ``ctrl``'s
    relations; the environment random, or adversarial (the lowest health levels and a
    hazard whenever it may)."""
    view = view_of(ctrl, spec)
    rng = random.Random(seed)
    node = view.initial[0]
    yield _field_values(ctrl, view.valuation(node), True), _field_values(
        ctrl, view.valuation(node), False)
    for _ in range(steps):
        options = list(view.options(node).values())
        if adversarial:
            node = min(options, key=lambda n: (sum(_field_values(
                ctrl, view.valuation(n), True).values()), rng.random()))
        else:
            node = rng.choice(options)
        values = view.valuation(node)
        yield _field_values(ctrl, values, True), _field_values(ctrl, values, False)


@pytest.mark.parametrize("adversarial", [False, True])
@pytest.mark.parametrize("name", ["thesis_robot_a.gait", "thesis_robot_b.gait",
                                  "corridor_hazard.gait"])
def test_the_python_run_makes_the_symbolic_runtimes_moves(
        compacts: dict[str, tuple[Spec, CompactController]], name: str,
        adversarial: bool) -> None:
    spec, ctrl = compacts[name]
    walk = _walk(spec, ctrl, 300, 7, adversarial)
    first_in, first_out = next(walk)
    run = Runner(ctrl, first_in)
    assert {k: run.state[k] for k in first_out} == first_out
    for chosen, made in walk:
        assert ctrl.assumes(run.state, chosen)
        assert run.step(chosen) == made


# ---------------------------------------------------------------------------- files
def test_the_file_round_trips_and_is_deterministic(
        compacts: dict[str, tuple[Spec, CompactController]]) -> None:
    _, ctrl = compacts["thesis_robot_a.gait"]
    text = compact_to_json(ctrl)
    again = compact_from_dict(json.loads(text), "a.json")
    assert again == ctrl and compact_to_json(again) == text


@pytest.mark.parametrize(("change", "message"), [
    (lambda d: d["gaitc"].update(version=9),
     "malformed compact controller: format version 9, this gaitc reads 1"),
    (lambda d: d["nodes"].insert(0, [0, [7, 7], []]),
     "malformed compact controller: node 0 has 2 children for a field of 20 values"),
    (lambda d: d["roots"].update(moves=[99999, 0]),
     "malformed compact controller: root 99999 is not a node or a leaf"),
    (lambda d: d["moves"].append([1]),
     "malformed compact controller: move [1] has no value for every output field"),
    (lambda d: d.pop("slots"), "malformed compact controller: 'slots' must be a list"),
    (lambda d: d["gaitc"].update(integers={"x": {"low": "a", "high": 3, "bits": ["r12"],
                                                 "owner": "sys"}}),
     "malformed compact controller: 'gaitc.integers.x' must give low <= high, its bits and "
     "owner"),
])
def test_a_tampered_file_is_one_line_naming_it(
        compacts: dict[str, tuple[Spec, CompactController]], tmp_path: Path,
        change: object, message: str) -> None:
    spec, ctrl = compacts["thesis_robot_a.gait"]
    data = compact_to_dict(ctrl)
    change(data)  # type: ignore[operator]
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(ControllerError) as caught:
        gaitc.api.solving.read_controller(path, spec)
    assert caught.value.message == message
    assert caught.value.span is not None and caught.value.span.file == str(path)


def test_a_truncated_file_and_another_specs_controller_are_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    controller = tmp_path / "a.json"
    assert main(["synth", str(ROBOT_A), "--compact", "-o", str(controller)]) == 0
    capsys.readouterr()
    cut = tmp_path / "cut.json"
    cut.write_text(controller.read_text(encoding="utf-8")[:400], encoding="utf-8")
    assert main(["codegen", str(ROBOT_A), str(cut), "--target", "c", "-o",
                 str(tmp_path / "out")]) == 1
    assert str(cut) in capsys.readouterr().err
    assert not (tmp_path / "out").exists()
    assert main(["codegen", str(SPECS / "thesis_robot_b.gait"), str(controller), "--target",
                 "c", "-o", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert err.startswith(f"{controller}:1:1: error: controller does not belong to this spec: ")
    assert not (tmp_path / "out").exists()


@needs_gcc_early
def test_codegen_reports_its_sizes_and_can_leave_the_monitor_out(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = SPECS / "corridor_hazard.gait"
    controller = tmp_path / "c.json"
    assert main(["synth", str(spec), "--compact", "-o", str(controller)]) == 0
    capsys.readouterr()
    sizes = []
    for extra in ([], ["--no-monitor"]):
        assert main(["codegen", str(spec), str(controller), "--target", "c", "-o",
                     str(tmp_path / f"out{len(extra)}"), "--json", *extra]) == 0
        found = json.loads(capsys.readouterr().out)
        assert found["target"] == "c" and found["flash"] is None
        sizes.append(found["table_bytes"])
    assert sizes[1] < sizes[0]


def test_render_policy_prints_the_tables_whole(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    controller = tmp_path / "a.json"
    assert main(["synth", str(ROBOT_A), "--compact", "-o", str(controller)]) == 0
    capsys.readouterr()
    assert main(["render", "policy", str(ROBOT_A), str(controller)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("compact controller: ")
    assert "pursuing r11 (" in out and "pursuing r12 (" in out
    assert "in r14" in out and " to r8" in out
    tables = gaitc.compact_policy(ROBOT_A, controller)
    assert tables is not None and "<table>" in tables._repr_html_()


# ---------------------------------------------------------------------------- generated C
needs_gcc = pytest.mark.skipif(shutil.which("gcc") is None, reason="gcc is not installed")


@needs_gcc
@pytest.mark.parametrize("name", ["thesis_robot_a.gait", "corridor_hazard.gait"])
def test_generated_c_makes_the_python_moves_for_10000_steps(
        compacts: dict[str, tuple[Spec, CompactController]], tmp_path: Path,
        name: str) -> None:
    spec, ctrl = compacts[name]
    built = build(ctrl, tmp_path, "c")
    assert built.program is not None
    fields = ctrl.vocabulary.fields
    lines, expected = [], []
    for adversarial, seed in ((False, 1), (True, 2)):
        walk = _walk(spec, ctrl, 5000, seed, adversarial)
        first_in, _ = next(walk)
        run = Runner(ctrl, first_in)
        lines.append("s " + " ".join(str(first_in[f.name]) for f in ctrl.vocabulary.inputs))
        expected.append(" ".join(str(run.state[f.name]) for f in fields) + " 0")
        for chosen, _ in walk:
            run.step(chosen)
            lines.append("x " + " ".join(str(chosen[f.name]) for f in ctrl.vocabulary.inputs))
            expected.append(" ".join(str(run.state[f.name]) for f in fields)
                            + f" {run.goal}")
    done = subprocess.run([str(built.program)], input="\n".join(lines) + "\n", text=True,
                          capture_output=True, check=True)
    answers = done.stdout.splitlines()
    assert len(answers) == len(expected) >= 10_000
    # step answers start with the move index; compare the state and goal after it
    got = [a if line.startswith("s") else a.split(" ", 1)[1]
           for line, a in zip(lines, answers, strict=True)]
    assert got == expected


@needs_gcc
def test_the_compiled_tables_are_proved_again(
        compacts: dict[str, tuple[Spec, CompactController]], tmp_path: Path) -> None:
    spec, ctrl = compacts["thesis_robot_a.gait"]
    built = build(ctrl, tmp_path, "c")
    assert built.program is not None
    done = subprocess.run([str(built.program)], input="d\n", text=True, capture_output=True,
                          check=True)
    tables = read_dump(done.stdout)
    rebuilt = from_tables(ctrl, tables)
    assert gaitc.verify(spec, rebuilt).ok
    assert to_symbolic(rebuilt).roots == to_symbolic(ctrl).roots or gaitc.verify(spec, rebuilt).ok


def from_tables(template: CompactController, tables: dict[str, list[int]]) -> CompactController:
    """A compact controller read from compiled tables (the fields from ``template``)."""
    leaf_bit = 0x8000
    outputs = len(template.vocabulary.outputs)

    def ref(r: int) -> int:
        return -(r - leaf_bit) - 1 if r >= leaf_bit else r

    nodes = []
    for n, slot in enumerate(tables["node_slot"]):
        first = tables["node_first"][n]
        size = tables["field_size"][tables["slot_field"][slot]]
        nodes.append(Branch(slot, tuple(ref(k) for k in tables["kids"][first:first + size])))
    moves = tables["moves"]
    goals = template.goal_count
    roots = [ref(r) for r in tables["roots"]]
    return replace(template, nodes=tuple(nodes),
                   moves=tuple(tuple(moves[k:k + outputs]) for k in range(0, len(moves),
                                                                          outputs)),
                   move_roots=tuple(roots[:goals]), reached_roots=tuple(roots[goals:2 * goals]),
                   start_root=roots[2 * goals], assumed_root=roots[2 * goals + 1])
