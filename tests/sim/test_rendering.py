"""Rendering: automata (with quotients), maps with runs, spec views; DOT always, SVG via dot."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from gaitc.api.simulation import Session, session
from gaitc.cli import main
from gaitc.diagnostics import UsageError
from gaitc.ir.controller import controller_to_json
from gaitc.sim import graphics
from gaitc.sim.automaton_view import automaton_view, input_change
from gaitc.sim.domain import State
from gaitc.sim.environments import AdversarialEnvironment
from gaitc.sim.map_view import map_view, spec_view
from gaitc.sim.run import Run, save_run
from gaitc.sim.simulator import simulate
from gaitc.solver.synthesis import synthesize

ROOT = Path(__file__).resolve().parents[2]
PATROL = str(ROOT / "specs" / "patrol_2x2.gait")
SVG = "{http://www.w3.org/2000/svg}"
needs_dot = pytest.mark.skipif(not graphics.have_dot(),
                               reason="Graphviz 'dot' is not installed (apt-get install graphviz)")


@pytest.fixture(scope="module")
def patrol() -> Session:
    loaded = session(PATROL, None)
    assert loaded is not None
    return loaded


@pytest.fixture(scope="module")
def run(patrol: Session) -> Run:
    return simulate(patrol.strategy, patrol.domain, patrol.monitor, AdversarialEnvironment(), 12)


def _svg_nodes(svg: str) -> list[list[str]]:
    """The text lines of every Graphviz node in an SVG document (parsed, so well formed)."""
    root = ET.fromstring(svg)
    out = []
    for group in root.iter(f"{SVG}g"):
        if group.get("class") == "node":
            out.append([t.text or "" for t in group.iter(f"{SVG}text")])
    return out


def test_input_change_speaks_domain_terms() -> None:
    before = State("nw", "south", (("L1", 3), ("L2", 2)), None)
    assert input_change(before, State("sw", "noGait", (("L1", 2), ("L2", 1)), "h")) == \
        "L1 3→2, L2 fails, hazard h on"
    assert input_change(before, State("sw", "noGait", (("L1", 3), ("L2", 3)), None)) == \
        "repair L2"
    assert input_change(before, before) == "no change"


def test_automaton_dot_has_one_node_per_state(patrol: Session) -> None:
    view = automaton_view(patrol.strategy, patrol.domain, "none")
    dot = view.dot()
    assert len(view.groups) == len(patrol.strategy)
    for node in range(len(patrol.strategy)):
        state = patrol.domain.decode(patrol.strategy.valuation(node))
        assert f"n{node}\\n{state.region} · {state.gait}" in dot
    edges = sum(len(s) for s in patrol.strategy.successors) + len(patrol.strategy.initial)
    assert dot.count(" -> ") == edges


def test_quotients_partition_the_nodes_and_report_merges(patrol: Session) -> None:
    total = len(patrol.strategy)
    for quotient in ("region-gait", "region"):
        view = automaton_view(patrol.strategy, patrol.domain, quotient)
        members = sorted(n for nodes in view.groups.values() for n in nodes)
        assert members == list(range(total))
        assert view.notes[0] == f"merged {total} nodes into {len(view.groups)}:"
    assert len(automaton_view(patrol.strategy, patrol.domain, "region").groups) == 4


def test_automatic_quotient_above_the_threshold(patrol: Session) -> None:
    small = automaton_view(patrol.strategy, patrol.domain, None, max_nodes=10**6)
    assert small.quotient == "none" and small.notes == ()
    big = automaton_view(patrol.strategy, patrol.domain, None, max_nodes=5)
    assert big.quotient in ("region-gait", "region")
    assert big.notes[0].startswith(f"the automaton has {len(patrol.strategy)} nodes, more than "
                                   "--max-nodes 5: showing the quotient by ")


@needs_dot
def test_automaton_svg_is_well_formed_with_expected_labels(patrol: Session) -> None:
    view = automaton_view(patrol.strategy, patrol.domain, "region-gait")
    nodes = _svg_nodes(view.svg())
    assert len(nodes) == len(view.groups) + 1  # plus the start point
    labels = {" ".join(lines) for lines in nodes}
    for node in patrol.strategy.initial:
        state = patrol.domain.decode(patrol.strategy.valuation(node))
        assert any(label.startswith(f"{state.region} · {state.gait}") for label in labels)
    assert view._repr_svg_().lstrip().startswith("<?xml")


@needs_dot
def test_map_svg_with_run_shows_regions_path_and_timeline(patrol: Session, run: Run) -> None:
    svg = map_view(patrol.model, run).svg()
    nodes = _svg_nodes(svg)
    assert len(nodes) == 4 + 2 + ("moves (steps)" in svg)  # regions, timeline, legend, moves
    texts = [t for lines in nodes for t in lines]
    for region in ("nw", "ne", "sw", "se"):
        assert region in texts
    assert "● cache" in texts and "◆ goal" in texts and "▶ start" in texts
    root = ET.fromstring(svg)
    edge_labels = " ".join(t.text or "" for g in root.iter(f"{SVG}g") if g.get("class") == "edge"
                           for t in g.iter(f"{SVG}text"))
    edge_labels += " " + " ".join(texts)  # busy edges list their steps in the moves table
    moves = [s for a, s in zip(run.steps, run.steps[1:], strict=False) if a.region != s.region]
    for step in moves:
        assert str(step.index) in edge_labels
    failing = [s for s in run.steps if s.failed]
    assert failing and f"{failing[0].index}✗" in edge_labels
    assert texts.count("✗") >= len(failing)  # timeline marks each failure
    assert run._repr_svg_() == svg


@needs_dot
def test_spec_view_lists_every_gait(patrol: Session) -> None:
    nodes = _svg_nodes(spec_view(patrol.model).svg())
    texts = [t for lines in nodes for t in lines]
    for gait in ("north", "south", "east", "west"):
        assert gait in texts


def test_output_formats_and_missing_graphviz(monkeypatch: pytest.MonkeyPatch,
                                             patrol: Session, tmp_path: Path) -> None:
    assert graphics.output_format("a.svg") == "svg"
    assert graphics.output_format("a.gv") == "dot"
    assert graphics.output_format("a.svg", "pdf") == "pdf"
    with pytest.raises(UsageError) as info:
        graphics.output_format("a.jpg")
    assert info.value.message == ("cannot write format 'jpg'; choose one of dot, svg, png, pdf "
                                  "(from the -o extension or --format)")
    monkeypatch.setattr(graphics.shutil, "which", lambda name: None)
    picture = spec_view(patrol.model)
    assert picture.save(tmp_path / "spec.dot") == "dot"
    assert (tmp_path / "spec.dot").read_text(encoding="utf-8").startswith("digraph spec {")
    with pytest.raises(UsageError) as info:
        picture.save(tmp_path / "spec.svg")
    assert "apt-get install graphviz" in info.value.message
    assert "brew install graphviz" in info.value.message


@needs_dot
def test_cli_render_commands(patrol: Session, run: Run, tmp_path: Path,
                             capsys: pytest.CaptureFixture[str]) -> None:
    controller = synthesize(patrol.spec.gr1)
    assert controller is not None
    ctrl = tmp_path / "c.json"
    ctrl.write_text(controller_to_json(controller), encoding="utf-8")
    runs = tmp_path / "run.jsonl"
    save_run(run, runs)
    assert main(["render", "automaton", PATROL, str(ctrl), "-o", str(tmp_path / "a.svg"),
                 "--max-nodes", "5"]) == 0
    assert "gaitc: merged" in capsys.readouterr().err
    assert main(["render", "map", PATROL, "--run", str(runs), "-o", str(tmp_path / "m.svg")]) == 0
    assert main(["render", "spec", PATROL, "-o", str(tmp_path / "s.png")]) == 0
    assert main(["render", "map", PATROL, "-o", str(tmp_path / "m.dot")]) == 0
    for name in ("a.svg", "m.svg"):
        ET.parse(tmp_path / name)
    assert (tmp_path / "s.png").read_bytes()[:4] == b"\x89PNG"
    assert main(["render", "map", PATROL, "-o", str(tmp_path / "m.bmp")]) == 2
