"""The map lays explicit regions out by their edges' compass directions (issue 13)."""

from __future__ import annotations

import gaitc
from gaitc.sim.map_view import map_view
from gaitc.sim.placement import directed_cells, positions
from ltlcompiler.model import Model

ROOMS = """robot "rooms"
legs L1..L2 health 2
gait up uses L1 moves north
gait down uses L1 moves south
gait left uses L2 moves west
gait right uses L2 moves east
region G, I, K, M, Z
edge G <-> I north
edge G <-> K east
edge K <-> M south
edge G -> Z by right
start G
visit I, M infinitely often
"""


def _model() -> Model:
    spec = gaitc.parse(ROOMS, "rooms.gait")
    assert spec.model is not None
    return spec.model


def test_north_edges_put_the_northern_region_above() -> None:
    model = _model()
    cells = directed_cells(model)
    assert cells["I"][0] == cells["G"][0] - 1 and cells["I"][1] == cells["G"][1]
    assert cells["K"] == (cells["G"][0], cells["G"][1] + 1)
    assert cells["M"] == (cells["K"][0] + 1, cells["K"][1])
    assert "Z" not in cells  # no direction: the spring layout places it
    pos = positions(model, 1.6)
    assert pos["I"][1] > pos["G"][1] and abs(pos["I"][0] - pos["G"][0]) < 1e-6
    assert pos["K"][0] > pos["G"][0] and pos["M"][1] < pos["K"][1]
    assert len({pos[r] for r in pos}) == len(pos)


def test_the_drawn_map_pins_the_directed_positions() -> None:
    dot = map_view(_model()).graph.to_string()
    pos = positions(_model(), 1.6)
    for name in ("G", "I"):
        x, y = pos[name]
        assert f'pos="{x},{y}!"' in dot
