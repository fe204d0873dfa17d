"""Merging equivalent controller nodes (gaitc/ir/quotient.py), checked against a naive
bisimulation and by the independent verifier, and as ``gaitc synth`` reports it."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import gaitc
from gaitc import cli
from gaitc.ir.controller import Controller, ControllerNode
from gaitc.ir.quotient import equivalence_blocks, merge_equivalent

ROOT = Path(__file__).resolve().parents[2]
MERGES = ROOT / "tests" / "data" / "gr1_corpus" / "rand3_0019.slugsin"  # 32 nodes, 16 merged


@st.composite
def controllers(draw: st.DrawFn) -> Controller:
    """Random deterministic Mealy controllers over one input and one output bit: each node
    has one successor for each input value some node carries."""
    states = draw(st.lists(st.tuples(st.integers(0, 1), st.integers(0, 1)), min_size=1,
                           max_size=9))
    nodes = []
    for state in states:
        successors = set()
        for x in (0, 1):
            with_x = [k for k, s in enumerate(states) if s[0] == x]
            if with_x:
                successors.add(draw(st.sampled_from(with_x)))
        nodes.append(ControllerNode(draw(st.integers(0, 2)), state, tuple(sorted(successors))))
    return Controller(variables=("x", "y"), inputs=("x",), outputs=("y",), nodes=tuple(nodes),
                      initial=(0,))


def naive_bisimilar(c: Controller) -> set[tuple[int, int]]:
    """The greatest bisimulation preserving the values, by removing pairs until stable."""
    n = len(c.nodes)
    pairs = {(a, b) for a in range(n) for b in range(n) if c.nodes[a].state == c.nodes[b].state}
    changed = True
    while changed:
        changed = False
        for a, b in sorted(pairs):
            ok = all(any((s, t) in pairs for t in c.nodes[b].trans) for s in c.nodes[a].trans)
            ok = ok and all(any((s, t) in pairs for s in c.nodes[a].trans)
                            for t in c.nodes[b].trans)
            if not ok:
                pairs.discard((a, b))
                changed = True
    return pairs


@settings(max_examples=200, deadline=None)
@given(controllers())
def test_blocks_are_the_greatest_bisimulation(c: Controller) -> None:
    blocks = equivalence_blocks(c)
    same = naive_bisimilar(c)
    n = len(c.nodes)
    assert {(a, b) for a in range(n) for b in range(n) if blocks[a] == blocks[b]} == same


@settings(max_examples=200, deadline=None)
@given(controllers())
def test_the_quotient_simulates_the_controller_and_cannot_shrink_again(c: Controller) -> None:
    q = merge_equivalent(c)
    blocks = equivalence_blocks(c)
    for k, node in enumerate(c.nodes):
        assert q.nodes[blocks[k]].state == node.state
        assert {blocks[t] for t in node.trans} == set(q.nodes[blocks[k]].trans)
    assert q.initial == tuple(sorted({blocks[k] for k in c.initial}))
    assert merge_equivalent(q) is q


def test_two_nodes_that_answer_alike_are_merged_and_others_are_not() -> None:
    nodes = (ControllerNode(0, (0, 0), (1, 2)),   # 0 and 3 answer alike
             ControllerNode(1, (0, 1), (1, 2)),
             ControllerNode(0, (1, 1), (3,)),
             ControllerNode(1, (0, 0), (1, 2)),
             ControllerNode(0, (0, 0), (4, 2)),   # same values as 0, another answer
             ControllerNode(0, (0, 1), (1, 2)))   # 1 with another goal index: merged
    c = Controller(("x", "y"), ("x",), ("y",), nodes, (0, 3, 4))
    assert equivalence_blocks(c) == [0, 1, 2, 0, 3, 1]
    q = merge_equivalent(c)
    assert len(q.nodes) == 4 and q.initial == (0, 3)
    assert q.nodes[0] == ControllerNode(0, (0, 0), (1, 2))
    assert q.nodes[1] == ControllerNode(1, (0, 1), (1, 2))  # the first member's goal
    assert q.nodes[2] == ControllerNode(0, (1, 1), (0,))
    counter = Controller(("x", "y"), ("x",), ("y",), nodes, (0,), kind="counterstrategy")
    assert merge_equivalent(counter) is counter


def test_synth_merges_equivalent_nodes_and_the_verifier_accepts_the_quotient() -> None:
    spec = gaitc.load(MERGES)
    found = gaitc.synthesize(spec, prefer="none")
    assert found.merged_from == 32 and found.controller is not None
    assert len(found.controller.nodes) == 16
    assert found.verified  # the verifier's own check of the merged automaton
    assert found.size == "16 nodes, 32 before merging"
    assert found.to_json()["nodes_before_merging"] == 32


def test_thesis_robot_controllers_have_no_equivalent_nodes() -> None:
    found = gaitc.synthesize(gaitc.load(ROOT / "specs" / "thesis_robot_b.gait"))
    assert found.merged_from is None and found.size == "195 nodes"
    assert found.to_json()["nodes_before_merging"] is None


def test_the_cli_reports_the_nodes_before_merging(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "c.json"
    assert cli.main(["synth", str(MERGES), "--prefer", "none", "-o", str(out), "--json"]) == 0
    record = json.loads(capsys.readouterr().out)
    assert record["nodes"] == 16 and record["nodes_before_merging"] == 32
    assert len(json.loads(out.read_text(encoding="utf-8"))["nodes"]) == 16
