"""The AMBA AHB arbiter generator of the benchmark suite (bench/families/amba.py).

Small instances are solved (realizable, and unrealizable once an assumption it needs is
dropped); larger ones are only read back and their shape checked, since solving them is
the benchmark's job, not a unit test's.
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from bench.families.amba import amba_sections, amba_text  # noqa: E402
from gaitc.api.compiling import emit  # noqa: E402
from gaitc.core.spec import parse  # noqa: E402
from gaitc.ir.spec import GR1Spec  # noqa: E402
from gaitc.solver.symbolic import Options  # noqa: E402
from gaitc.solver.synthesis import check  # noqa: E402

REORDER = Options(reordering=True)


def _gr1(text: str) -> GR1Spec:
    return parse(text, "amba.structuredslugs").gr1


@pytest.mark.parametrize("n", [1, 2])
def test_small_arbiters_are_realizable(n: int) -> None:
    assert check(_gr1(amba_text(n)), "default", 60, None, REORDER).realizable
    assert check(_gr1(amba_text(n)), "robotics", 60, None, REORDER).realizable


@pytest.mark.parametrize(("dropped", "index"), [("A1", 0), ("A2", 1)])
def test_two_masters_need_both_liveness_assumptions(dropped: str, index: int) -> None:
    full = amba_sections(2)
    kept = [line for k, line in enumerate(full.env_liveness) if k != index]
    text = replace(full, env_liveness=kept).text(f"without {dropped}")
    assert not check(_gr1(text), "default", 60, None, REORDER).realizable


def test_the_syntcomp_half_of_g7_makes_a1_vacuous() -> None:
    half = amba_sections(2, half_g7=True)
    text = replace(half, env_liveness=["hready"]).text("half G7, no A1")
    assert check(_gr1(text), "default", 60, None, REORDER).realizable
    assert "G7 halved" in amba_text(2, half_g7=True).splitlines()[0]


@pytest.mark.parametrize("n", [3, 5, 8, 10])
def test_larger_arbiters_have_the_family_shape(n: int) -> None:
    spec = _gr1(amba_text(n))
    inputs = {v.name for v in spec.inputs}
    assert inputs == {"hready", "hburst0", "hburst1",
                      *(f"hbusreq{i}" for i in range(n)), *(f"hlock{i}" for i in range(n))}
    hmaster = spec.variable("hmaster")
    assert hmaster is not None and (hmaster.low, hmaster.high) == (0, n - 1)
    counter = spec.variable("stateG3")
    assert counter is not None and (counter.low, counter.high) == (0, 4)
    outputs = {v.name for v in spec.outputs}
    assert {f"hgrant{i}" for i in range(n)} <= outputs
    assert {f"stateG10_{i}" for i in range(1, n)} <= outputs and "stateG10_0" not in outputs
    assert len(spec.env_liveness) == 2 and len(spec.sys_liveness) == n  # A1, A2; G9 per master
    assert len(spec.env_trans) == n  # A3 per master
    assert amba_text(n) == amba_text(n)


def test_out_of_range_sizes_are_refused() -> None:
    for n in (0, 17):
        with pytest.raises(ValueError, match="1 to 16 masters"):
            amba_sections(n)


@pytest.mark.slugs
def test_slugs_agrees_on_small_arbiters_and_on_the_weakened_ones(live_slugs: str) -> None:
    from slugs_bridge.runner import run_slugs_check

    full = amba_sections(2)
    cases = [(amba_text(n), True) for n in (1, 2, 3)] + [
        (replace(full, env_liveness=[line]).text("one assumption"), False)
        for line in full.env_liveness]
    for text, expected in cases:
        slugsin = emit(parse(text, "amba.structuredslugs"), "slugsin")
        assert run_slugs_check(slugsin, slugs=live_slugs, timeout=600).realizable == expected
