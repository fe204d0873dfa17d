"""The AMBA arbiter in the SYNTCOMP generator's bit encoding (bench/families/amba_bits.py).

Issue 12's SLUGS times came from this encoding; the tests check that the text declares the
published instances' signals in their order, that small arbiters are realizable and need
both liveness assumptions, and (live, with $SLUGS) that SLUGS agrees.
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from bench.families.amba_bits import amba_bits_sections, amba_bits_text, master_bits  # noqa: E402
from gaitc.api.compiling import emit  # noqa: E402
from gaitc.core.spec import parse  # noqa: E402
from gaitc.ir.spec import GR1Spec  # noqa: E402
from gaitc.solver.synthesis import check  # noqa: E402

#: The signals of the published three-master instance, in its declaration order.
THREE_MASTERS_IN = ["hready", "hbusreq0", "hlock0", "hbusreq1", "hlock1", "hbusreq2",
                    "hlock2", "hburst0", "hburst1"]
THREE_MASTERS_OUT = ["hmaster0", "hmaster1", "hmastlock", "start", "decide", "locked",
                     "hgrant0", "hgrant1", "hgrant2", "busreq", "stateA1_0", "stateA1_1",
                     "stateG2", "stateG3_0", "stateG3_1", "stateG3_2", "stateG10_1",
                     "stateG10_2"]


def _gr1(text: str) -> GR1Spec:
    return parse(text, "amba_bits.structuredslugs").gr1


def test_the_three_master_text_declares_the_published_signals_in_order() -> None:
    spec = _gr1(amba_bits_text(3))
    assert [v.name for v in spec.inputs] == THREE_MASTERS_IN
    assert [v.name for v in spec.outputs] == THREE_MASTERS_OUT
    assert all(not v.is_integer for v in spec.variables())
    assert len(spec.env_liveness) == 2 and len(spec.sys_liveness) == 3


@pytest.mark.parametrize(("n", "bits"), [(2, 1), (3, 2), (4, 2), (5, 3), (8, 3), (9, 4)])
def test_hmaster_has_ceil_log2_bits(n: int, bits: int) -> None:
    assert master_bits(n) == bits
    outputs = [v.name for v in _gr1(amba_bits_text(n)).outputs]
    assert [o for o in outputs if o.startswith("hmaster")] == [f"hmaster{j}" for j in range(bits)]


@pytest.mark.parametrize("semantics", ["default", "robotics"])
def test_two_masters_are_realizable(semantics: str) -> None:
    assert check(_gr1(amba_bits_text(2)), semantics, 60).realizable


@pytest.mark.parametrize(("dropped", "index"), [("A1", 0), ("A2", 1)])
def test_two_masters_need_both_liveness_assumptions(dropped: str, index: int) -> None:
    full = amba_bits_sections(2)
    kept = [line for k, line in enumerate(full.env_liveness) if k != index]
    text = replace(full, env_liveness=kept).text(f"without {dropped}")
    assert not check(_gr1(text), "default", 60).realizable


def test_the_text_is_deterministic_and_sizes_are_checked() -> None:
    assert amba_bits_text(4) == amba_bits_text(4)
    for n in (1, 17):
        with pytest.raises(ValueError, match="2 to 16 masters"):
            amba_bits_sections(n)


@pytest.mark.slugs
def test_slugs_agrees_on_two_and_three_masters(live_slugs: str) -> None:
    from slugs_bridge.runner import run_slugs_check

    for n in (2, 3):
        slugsin = emit(parse(amba_bits_text(n), "amba_bits.structuredslugs"), "slugsin")
        assert run_slugs_check(slugsin, slugs=live_slugs, timeout=600).realizable
