"""Tests of controller extraction (strategy.py, counter.py) and the controller file (controller.py).

Every extracted strategy and counter-strategy must pass the independent verifier.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gaitc.diagnostics import ControllerError
from gaitc.ir.controller import (
    Controller,
    ControllerNode,
    controller_to_json,
    integers_of,
    load_controller,
)
from gaitc.ir.formula import Compare, Const, IntConst, IntVar, Not, Var, Xor
from gaitc.ir.spec import Clause, GR1Spec, Variable
from gaitc.solver import synthesis
from gaitc.verifier.counterstrategy import verify_counterstrategy
from gaitc.verifier.strategy import verify
from slugs_bridge.slugsin import parse_slugsin

DATA = Path(__file__).parents[1] / "data"
EXAMPLES = sorted(
    p for p in (DATA / "slugs_examples").iterdir() if p.suffix in (".slugsin", ".txt")
)
CORPUS = sorted((DATA / "gr1_corpus").glob("rand3_00[0-3]*.slugsin"))


def load(path: Path) -> GR1Spec:
    return parse_slugsin(path.read_text(encoding="utf-8"), str(path))


@pytest.mark.parametrize("path", EXAMPLES + CORPUS, ids=lambda p: p.name)
@pytest.mark.parametrize("semantics", ["default", "robotics"])
def test_extracted_automata_pass_the_verifier(path: Path, semantics: str) -> None:
    spec = load(path)
    controller = synthesis.synthesize(spec, semantics)
    if controller is not None:
        report = verify(spec, controller, semantics)
    else:
        controller = synthesis.counterstrategy(spec, semantics)
        assert controller is not None and controller.kind == "counterstrategy"
        report = verify_counterstrategy(spec, controller, semantics)
    assert report.ok, report.problems


def test_extraction_is_deterministic_to_the_byte() -> None:
    spec = load(DATA / "slugs_examples" / "firefighting.slugsin")
    first = synthesis.synthesize(spec)
    second = synthesis.synthesize(spec)
    assert first is not None and second is not None
    assert controller_to_json(first) == controller_to_json(second)


def test_nodes_are_numbered_breadth_first_from_the_initial_nodes() -> None:
    spec = load(DATA / "slugs_examples" / "networks.slugsin")
    c = synthesis.synthesize(spec)
    assert c is not None
    assert c.initial == tuple(range(len(c.initial)))
    seen = set(c.initial)
    frontier_max = max(c.initial)
    for k in range(len(c.nodes)):
        for t in c.nodes[k].trans:
            if t not in seen:
                assert t == frontier_max + 1
                frontier_max = t
                seen.add(t)


def test_a_toggling_controller_keeps_its_goal_index() -> None:
    toggle = Clause(Xor(Var("b"), Var("b", True)))
    spec = GR1Spec(outputs=(Variable("b"),), sys_liveness=(toggle, Clause(Var("b"))))
    c = synthesis.synthesize(spec)
    assert c is not None
    assert verify(spec, c, "default").ok
    assert {n.rank for n in c.nodes} <= {0, 1}


def test_counterstrategy_is_none_for_realizable_and_strategy_none_for_unrealizable() -> None:
    ok = GR1Spec(outputs=(Variable("b"),))
    bad = GR1Spec(outputs=(Variable("b"),), sys_liveness=(Clause(Const(False)),))
    assert synthesis.counterstrategy(ok) is None
    assert synthesis.synthesize(bad) is None
    counter = synthesis.counterstrategy(bad)
    assert counter is not None and verify_counterstrategy(bad, counter, "default").ok


def test_integer_outputs_are_decoded_in_the_controller() -> None:
    r = Variable("r", 2, 6)
    spec = GR1Spec(
        inputs=(Variable("go"),),
        outputs=(r,),
        sys_liveness=(
            Clause(Compare("=", IntVar("r"), IntConst(6))),
            Clause(Compare("=", IntVar("r"), IntConst(2))),
        ),
        env_liveness=(Clause(Not(Var("go"))),),
    )
    c = synthesis.synthesize(spec)
    assert c is not None
    assert c.integers["r"].bits == ("r@0.2.6", "r@1", "r@2")
    values = {c.values(k)["r"] for k in range(len(c.nodes))}
    assert {2, 6} <= values and values <= set(range(2, 7))


# ---------------------------------------------------------------- controller files
def sample() -> Controller:
    names = ("a", "x@0.0.5", "x@1", "x@2")
    return Controller(
        variables=names,
        inputs=("a",),
        outputs=names[1:],
        nodes=(ControllerNode(0, (0, 1, 0, 1), (1,)), ControllerNode(1, (1, 0, 0, 0), (0, 1))),
        initial=(0,),
        integers=integers_of(names, frozenset({"a"})),
    )


def test_controller_json_round_trips(tmp_path: Path) -> None:
    path = tmp_path / "c.json"
    path.write_text(controller_to_json(sample()), encoding="utf-8")
    loaded = load_controller(str(path))
    assert loaded == sample()
    assert loaded.values(0) == {"a": 0, "x": 5}
    data = json.loads(path.read_text(encoding="utf-8"))
    assert data["gaitc"]["values"]["1"] == {"a": 1, "x": 0}


@pytest.mark.parametrize(
    ("mutate", "message"),
    [
        (lambda d: d.pop("nodes"), "'nodes' must be an object"),
        (lambda d: d["nodes"]["0"].update(state=[0, 1]), "one 0/1 value per variable"),
        (lambda d: d["nodes"]["1"].update(trans=[7]), "node ids between 0 and 1"),
        (lambda d: d["gaitc"].update(kind="plan"), "'gaitc.kind' must be one of"),
        (lambda d: d["gaitc"].update(inputs=[]), "split 'variables' between the players"),
    ],
)
def test_malformed_controllers_raise_controller_errors(
    tmp_path: Path, mutate: object, message: str
) -> None:
    data = json.loads(controller_to_json(sample()))
    mutate(data)  # type: ignore[operator]
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(ControllerError, match=message):
        load_controller(str(path))


def test_invalid_json_reports_line_and_column(tmp_path: Path) -> None:
    path = tmp_path / "bad.json"
    path.write_text('{\n "nodes": [,]\n}', encoding="utf-8")
    with pytest.raises(ControllerError) as err:
        load_controller(str(path))
    assert err.value.span is not None and err.value.span.line == 2
