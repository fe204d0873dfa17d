"""``render gaits`` stays bounded (issue 13): radial8 has 262 poses and 7,768 transitions
and no +y gait; the drawing keeps at most MAX_DRAWN poses and 2 x MAX_DRAWN transitions,
says so, gives Graphviz a time limit with a clear error, and writes SVG and PNG."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from gaitc.diagnostics import GaitcError
from gaitc.gaitgraph import drawing
from gaitc.gaitgraph.cycles import parse_direction
from gaitc.gaitgraph.robot import load_robot
from gaitc.gaitgraph.search import SearchResult, search

ROOT = Path(__file__).resolve().parents[2]
RADIAL8 = ROOT / "specs" / "robots" / "radial8.yaml"


@pytest.fixture(scope="module")
def radial8() -> SearchResult:
    robot = load_robot(str(RADIAL8))
    return search(robot, parse_direction("+y"), "full", 0, 4096)


def test_the_drawing_of_a_large_gait_graph_is_bounded(radial8: SearchResult) -> None:
    assert not radial8.gaits and len(radial8.graph) > drawing.MAX_DRAWN
    dot = drawing.graph_dot(radial8.graph, None, None)
    assert len(dot.get_nodes()) <= drawing.MAX_DRAWN
    assert len(dot.get_edges()) <= 2 * drawing.MAX_DRAWN
    assert f"of {len(radial8.graph)} poses" in str(dot.get("label"))


@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' is not installed")
def test_render_writes_svg_and_png_and_limits_graphviz(radial8: SearchResult, tmp_path: Path,
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    robot = load_robot(str(RADIAL8))
    written = drawing.write_drawings(robot, radial8.graph, radial8.gaits, str(tmp_path / "a"))
    assert {Path(p).suffix for p in written} >= {".dot", ".svg", ".png"}
    monkeypatch.setattr(drawing, "DOT_SECONDS", 1e-4)
    with pytest.raises(GaitcError, match="Graphviz took more than"):
        drawing.write_drawings(robot, radial8.graph, radial8.gaits, str(tmp_path / "b"))
