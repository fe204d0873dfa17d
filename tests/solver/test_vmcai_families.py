"""The arbiter and lift families of the first GR(1) paper (bench/families/vmcai.py).

The tests check each text's signals and sections, compare the embedded solver with the
explicit-state solver of tests/games.py on the smallest instances, show that the clients'
fairness and the lift's reach matter, verify synthesized controllers (explicit and
symbolic), and (live, with $SLUGS) that SLUGS agrees.
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import pytest
from games import explicit_realizable

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import gaitc  # noqa: E402
from bench.families import catalogue  # noqa: E402
from bench.families.vmcai import arbiter_sections, arbiter_text, lift_sections, lift_text  # noqa: E402
from gaitc.api.compiling import emit  # noqa: E402
from gaitc.core.spec import parse  # noqa: E402
from gaitc.ir.spec import SEMANTICS, GR1Spec  # noqa: E402
from gaitc.solver.synthesis import check  # noqa: E402


def _gr1(text: str) -> GR1Spec:
    return parse(text, "family.structuredslugs").gr1


def test_the_arbiter_has_a_justice_pair_per_client() -> None:
    spec = _gr1(arbiter_text(5))
    assert [v.name for v in spec.inputs] == [f"r{i}" for i in range(5)]
    assert [v.name for v in spec.outputs] == [f"g{i}" for i in range(5)]
    assert len(spec.env_liveness) == len(spec.sys_liveness) == 5
    assert len(spec.sys_trans) == 10 + 5  # mutual exclusion of each pair, then the frames
    assert not _gr1(arbiter_text(5, fair=False)).env_liveness


def test_the_lift_declares_buttons_and_one_hot_floors() -> None:
    spec = _gr1(lift_text(4))
    assert [v.name for v in spec.inputs] == ["b0", "b1", "b2", "b3"]
    assert [v.name for v in spec.outputs] == ["f0", "f1", "f2", "f3"]
    assert len(spec.sys_liveness) == 5 and not spec.env_liveness


@pytest.mark.parametrize("semantics", SEMANTICS)
@pytest.mark.parametrize(("text", "expected"), [
    (arbiter_text(1), True), (arbiter_text(2), True), (arbiter_text(2, fair=False), False),
    (lift_text(2), True), (lift_text(3), True),
])
def test_the_embedded_solver_agrees_with_the_explicit_one(text: str, expected: bool,
                                                           semantics: str) -> None:
    spec = _gr1(text)
    assert explicit_realizable(spec, semantics) is expected
    assert check(spec, semantics, 60).realizable is expected


@pytest.mark.parametrize("n", [3, 6, 12])
def test_arbiters_need_their_clients_fairness(n: int) -> None:
    assert check(_gr1(arbiter_text(n)), "default", 60).realizable
    assert not check(_gr1(arbiter_text(n, fair=False)), "default", 60).realizable
    # one client that may keep its grant is enough to starve another
    one_unfair = replace(arbiter_sections(n), env_liveness=arbiter_sections(n).env_liveness[1:])
    assert not check(_gr1(one_unfair.text("client 0 unfair")), "default", 60).realizable


@pytest.mark.parametrize("n", [3, 8])
def test_a_lift_kept_off_its_top_floor_cannot_serve_its_call(n: int) -> None:
    assert check(_gr1(lift_text(n)), "default", 60).realizable
    full = lift_sections(n)
    text = replace(full, sys_trans=[*full.sys_trans, f"!f{n - 1}'"]).text("top floor closed")
    assert not check(_gr1(text), "default", 60).realizable


@pytest.mark.parametrize("form", ["explicit", "symbolic"])
@pytest.mark.parametrize("text", [arbiter_text(3), lift_text(4)])
def test_controllers_pass_the_verifier(text: str, form: str) -> None:
    spec = gaitc.parse(text, "family.structuredslugs")
    synthesis = gaitc.synthesize(spec, form=form)
    assert gaitc.verify(spec, synthesis).ok


def test_texts_are_deterministic_and_sizes_are_checked() -> None:
    assert arbiter_text(6) == arbiter_text(6) and lift_text(6) == lift_text(6)
    with pytest.raises(ValueError, match="at least 1 client"):
        arbiter_sections(0)
    with pytest.raises(ValueError, match="at least 2 floors"):
        lift_sections(1)


def test_the_catalogue_lists_both_families_with_their_verdicts(tmp_path: Path) -> None:
    rows = catalogue.instances(tmp_path, quick=True, families=("arbiter", "lift"))
    assert [(i.family, i.name, i.recorded) for i in rows] == [
        *(("arbiter", f"N={n}", True) for n in catalogue.QUICK_ARBITER),
        ("arbiter", f"N={catalogue.UNFAIR_ARBITER[0]} unfair", False),
        *(("lift", f"N={n}", True) for n in catalogue.QUICK_LIFT),
    ]


@pytest.mark.slugs
def test_slugs_agrees_on_small_instances(live_slugs: str) -> None:
    from slugs_bridge.runner import run_slugs_check

    for text, expected in ((arbiter_text(4), True), (arbiter_text(4, fair=False), False),
                           (lift_text(5), True)):
        slugsin = emit(parse(text, "family.structuredslugs"), "slugsin")
        assert run_slugs_check(slugsin, slugs=live_slugs, timeout=600).realizable is expected
