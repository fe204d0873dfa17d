"""The health cost of ``--prefer`` (ltlcompiler/costs.py) under graded hazards: a leg at
level h in use loses min(k, h - 1) levels in a region of an active ``wears k`` hazard, all
h - 1 in one that fails the legs, one elsewhere (tests/golden/graded.gait: sand wears 2,
spill fails, grit wears 3; L1 and L2 have 4 levels, L3 2)."""

from __future__ import annotations

from collections import defaultdict
from dataclasses import replace
from pathlib import Path

import pytest

import gaitc
from gaitc.ir.costs import Cost
from gaitc.ir.evaluation import evaluate
from ltlcompiler.costs import model_costs
from ltlcompiler.encoding import EncodingName
from ltlcompiler.model import Model

GRADED = Path(__file__).resolve().parents[1] / "golden" / "graded.gait"
SCALE = 1 + 3 + 3 + 1  # one more than all the levels the legs can lose


def _model() -> Model:
    model = gaitc.load(GRADED).model
    assert model is not None
    return model


def _cost(cost: Cost, region: str, hazard: str | None, gait: str, levels: dict[str, int]
          ) -> int:
    """The weight of ``cost`` on the move into ``region`` by ``gait``, with ``hazard``
    active next and the legs at ``levels`` next (onehot names, primed)."""
    at: dict[str, int] = defaultdict(int)
    at[f"{region}'"] = at[f"{gait}'"] = 1
    if hazard is not None:
        at[f"{hazard}'"] = 1
    for leg, level in levels.items():
        at[f"{leg}_h{level}'"] = 1
    return sum(weight for weight, term in cost.terms if evaluate(term, at))


@pytest.mark.parametrize(("region", "hazard", "level", "lost"), [
    ("ne", None, 4, 1),      # no hazard: the normal wear
    ("ne", "sand", 4, 2),    # wears 2
    ("ne", "sand", 2, 1),    # wears 2, but one level left to lose
    ("se", "sand", 3, 2),
    ("se", "grit", 4, 3),    # wears 3
    ("se", "grit", 3, 2),
    ("sw", "spill", 4, 3),   # fails the legs: every level but the last
    ("sw", "spill", 2, 1),
    ("sw", "sand", 4, 1),    # sand is active, but sw is not one of its regions
    ("nw", "spill", 4, 1),   # the cache is no hazard region (and restores)
])
def test_a_graded_hazard_costs_the_levels_it_can_take(
        region: str, hazard: str | None, level: int, lost: int) -> None:
    health = {c.name: c for c in model_costs(_model(), EncodingName.ONEHOT)}["health"]
    weight = _cost(health, region, hazard, "east", {"L1": level, "L2": 4, "L3": 2})
    if region == "nw":  # a move into the cache wears nothing it keeps
        assert weight == 0
        return
    assert weight == SCALE * lost + (4 - level)


def test_failing_hazards_only_keep_their_cost() -> None:
    """Without graded hazards each level has one hazard term, as before graded ones."""
    model = _model()
    spill = next(h for h in model.hazards if h.name == "spill")
    failing = replace(model, hazards=(spill,))
    health = {c.name: c for c in model_costs(failing, EncodingName.ONEHOT)}["health"]
    assert _cost(health, "sw", "spill", "north", {"L1": 4, "L2": 4, "L3": 2}) == \
        (SCALE * 3 + 0) + (SCALE * 1 + 0)  # L1 loses 3, L3 its one
    # per leg and level: one term outside hazards, one in them
    assert len(health.terms) == 2 * (3 + 3 + 1)
