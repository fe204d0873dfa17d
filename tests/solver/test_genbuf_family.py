"""The generalized buffer family (bench/families/genbuf.py), GR(1)'s second standard benchmark.

The tests check that the text declares the published instance's signals in their order, that
small buffers are realizable and need the receivers' fairness and the FIFO's frame rule,
that synthesized controllers pass the independent verifier (explicit and symbolic), and
(live, with $SLUGS) that SLUGS agrees.
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import gaitc  # noqa: E402
from bench.families.genbuf import genbuf_sections, genbuf_text, select_bits  # noqa: E402
from gaitc.api.compiling import emit  # noqa: E402
from gaitc.core.spec import parse  # noqa: E402
from gaitc.ir.spec import GR1Spec  # noqa: E402
from gaitc.solver.synthesis import check  # noqa: E402

#: The signals of the published five-sender instance, in its declaration order.
FIVE_SENDERS_IN = ["StoB_REQ0", "StoB_REQ1", "StoB_REQ2", "StoB_REQ3", "StoB_REQ4",
                   "RtoB_ACK0", "RtoB_ACK1", "FULL", "EMPTY"]
FIVE_SENDERS_OUT = ["BtoS_ACK0", "BtoS_ACK1", "BtoS_ACK2", "BtoS_ACK3", "BtoS_ACK4",
                    "BtoR_REQ0", "BtoR_REQ1", "stateG7_0", "stateG7_1", "ENQ", "DEQ",
                    "stateG12", "SLC0", "SLC1", "SLC2"]


def _gr1(text: str) -> GR1Spec:
    return parse(text, "genbuf.structuredslugs").gr1


def test_the_five_sender_text_declares_the_published_signals_in_order() -> None:
    spec = _gr1(genbuf_text(5))
    assert [v.name for v in spec.inputs] == FIVE_SENDERS_IN
    assert [v.name for v in spec.outputs] == FIVE_SENDERS_OUT
    assert all(not v.is_integer for v in spec.variables())
    # G1 for each sender and G12; A2 for each receiver
    assert len(spec.sys_liveness) == 6 and len(spec.env_liveness) == 2


@pytest.mark.parametrize(("n", "bits"), [(2, 1), (3, 2), (4, 2), (5, 3), (8, 3), (9, 4), (64, 6)])
def test_the_select_has_ceil_log2_bits(n: int, bits: int) -> None:
    assert select_bits(n) == bits
    outputs = [v.name for v in _gr1(genbuf_text(n)).outputs]
    assert [o for o in outputs if o.startswith("SLC")] == [f"SLC{b}" for b in range(bits)]


@pytest.mark.parametrize("semantics", ["default", "robotics"])
@pytest.mark.parametrize("n", [2, 3])
def test_small_buffers_are_realizable(n: int, semantics: str) -> None:
    assert check(_gr1(genbuf_text(n)), semantics, 60).realizable


@pytest.mark.parametrize("kept", [[], ["BtoR_REQ0 <-> RtoB_ACK0"]])
def test_without_the_receivers_fairness_no_buffer_exists(kept: list[str]) -> None:
    text = replace(genbuf_sections(2), env_liveness=kept).text("receivers may stall")
    assert not check(_gr1(text), "default", 60).realizable


def test_a_stuck_fifo_defeats_the_buffer() -> None:
    """Without A4's frame rule the environment may keep the FIFO full and empty at will."""
    full = genbuf_sections(2)
    text = replace(full, env_trans=[c for c in full.env_trans if not c.startswith("(ENQ <->")],
                   env_init=[*full.env_init[:-1], "!EMPTY"]).text("FIFO flags free")
    assert not check(_gr1(text), "default", 60).realizable


@pytest.mark.parametrize("form", ["explicit", "symbolic"])
def test_a_controller_of_two_senders_passes_the_verifier(form: str) -> None:
    spec = gaitc.parse(genbuf_text(2), "genbuf.structuredslugs")
    synthesis = gaitc.synthesize(spec, form=form)
    assert gaitc.verify(spec, synthesis).ok


def test_the_text_is_deterministic_and_sizes_are_checked() -> None:
    assert genbuf_text(6) == genbuf_text(6)
    for n in (1, 65):
        with pytest.raises(ValueError, match="2 to 64 senders"):
            genbuf_sections(n)


@pytest.mark.slugs
def test_slugs_agrees_on_small_buffers(live_slugs: str) -> None:
    from slugs_bridge.runner import run_slugs_check

    for n in (2, 3, 5):
        slugsin = emit(parse(genbuf_text(n), "genbuf.structuredslugs"), "slugsin")
        assert run_slugs_check(slugsin, slugs=live_slugs, timeout=600).realizable
