"""Hovering a hazard says what it does to the legs (``Hazard.effect``): a failing hazard
fails them, a graded one (``wears k``) wears them by up to k levels
(tests/golden/graded.gait: sand wears 2, spill fails, grit wears 3)."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.lsp.analysis import analyse
from gaitc.lsp.hover import describe

GRADED = Path(__file__).resolve().parents[1] / "golden" / "graded.gait"


@pytest.mark.parametrize(("name", "regions", "effect"), [
    ("sand", "ne, se", "wears the legs by up to 2 levels (those of the gait in use; thesis "
     "eq. 3.9, graded: a loss of up to 2 levels in place of a failure)"),
    ("grit", "se", "wears the legs by up to 3 levels (those of the gait in use; thesis "
     "eq. 3.9, graded: a loss of up to 3 levels in place of a failure)"),
    ("spill", "sw", "fails the legs (those of the gait in use; thesis eqs. 3.8, 3.9)"),
])
def test_hovering_a_hazard_tells_its_effect(name: str, regions: str, effect: str) -> None:
    found = analyse(GRADED.read_text(encoding="utf-8"), str(GRADED))
    assert found.model is not None and found.index is not None, found.findings
    text = describe(found.index.symbols[name], found.index, found.model)
    assert text == (f"**hazard set** `{name}`\n\nregions: {regions}\n\nwhile it is on, entering "
                    f"one of them {effect}")
