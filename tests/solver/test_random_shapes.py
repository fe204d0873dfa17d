"""The random shapes of bench/families/random_shapes.py: deterministic, well-formed specs.

Each shape and seed must give the same text twice, and the text must load (names, ranges,
sections) and be decided by the embedded solver; the differential campaign
(bench/bench_random_families.py) compares those verdicts with SLUGS's.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import gaitc
from bench.families.random_shapes import SHAPES, shape_text
from gaitc.solver import synthesis


@pytest.mark.parametrize("shape", [  # the graph shape takes about 40 s
    pytest.param(s, marks=pytest.mark.slow) if s == "graph" else s for s in sorted(SHAPES)])
def test_every_shape_gives_the_same_loadable_spec_for_a_seed(shape: str, tmp_path: Path) -> None:
    for seed in range(3):
        text = shape_text(shape, seed)
        assert text == shape_text(shape, seed)
        path = tmp_path / f"{shape}_{seed}.structuredslugs"
        path.write_text(text, encoding="utf-8")
        spec = gaitc.load(path).gr1
        assert spec.inputs and spec.outputs
        verdict = synthesis.check(spec, timeout=60)
        assert verdict.realizable in (True, False)
