"""explain on robots unlike the shipped ones: one story, and repairs a roboticist trusts.

The robots (tests/data/explain/): a five-arm starfish in two rooms joined by a corridor
(``five_arms``), an eight-leg walker whose far station lies past a spill (``eight_legs_spill``)
and a courier on a ten-cell corridor that needs health 10 (``long_corridor``). Every answer
is checked here independently: the core and the header's goal by solving variants, each
repair by solving its edited text, a two-cache repair by solving each of its caches alone,
the least health by solving one level less, and the declared order by parsing.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import gaitc
from gaitc.analysis.explanation import Explanation
from gaitc.core.changes import LegWears

DATA = Path(__file__).resolve().parents[1] / "data" / "explain"


def _realizable(text: str) -> bool:
    return gaitc.check(gaitc.parse(text, name="variant.gait")).realizable


@pytest.fixture(scope="module")
def starfish() -> Explanation:
    return gaitc.explain(DATA / "five_arms.gait")


def test_header_core_freedoms_and_play_tell_one_story(starfish: Explanation) -> None:
    why = starfish
    assert why.kind == "liveness" and why.goals[:1] == ("visit c11",)
    goal = why.goals[0]
    # the core holds the header's goal, and the failure rule of the leg the freedoms wear
    assert any(u.section == "sys_liveness" and u.rule.endswith(f": {goal}") for u in why.core)
    failure_legs = {m.group(1) for u in why.core
                    if (m := re.match(r"eq\. 3\.4: leg (\w+) failed", u.rule))}
    worn = {f.change.leg for f in why.freedoms if isinstance(f.change, LegWears)}
    assert failure_legs and worn and worn <= failure_legs
    # the play heads for that goal and fails that leg
    assert why.story[0].startswith(f"the robot is kept from {goal}")
    assert why.run is not None
    failed_in_play = {leg for step in why.run.steps for leg in step.failed}
    assert worn <= failed_in_play
    # the summary says how they connect, in robot words
    leg = sorted(worn)[0]
    text = "\n".join(why.lines())
    assert f"the only gait that moves east (east_a) uses {leg}" in text
    assert "the robot cannot get from c09 to c11" in text
    # the spec itself, re-solved here, is unrealizable
    source = (DATA / "five_arms.gait").read_text(encoding="utf-8")
    assert not _realizable(source)


def test_every_printed_repair_is_realizable_and_keeps_the_declared_order(
        starfish: Explanation) -> None:
    source = (DATA / "five_arms.gait").read_text(encoding="utf-8")
    original = gaitc.parse(source, name="five_arms.gait").robot
    assert starfish.repairs
    for repair in starfish.repairs:
        assert _realizable(repair.text), repair.change
        edited = gaitc.parse(repair.text, name="repaired.gait").robot
        assert [leg.name for leg in edited.legs] == [leg.name for leg in original.legs]
        assert [r.name for r in edited.regions] == [r.name for r in original.regions]
        kept = [g.name for g in edited.gaits if g.name in {x.name for x in original.gaits}]
        assert kept == [g.name for g in original.gaits if g.name in kept]


def test_a_two_cache_repair_is_found_and_each_cache_alone_is_not_enough() -> None:
    why = gaitc.explain(DATA / "eight_legs_spill.gait")
    source = (DATA / "eight_legs_spill.gait").read_text(encoding="utf-8")
    pairs = [r for r in why.repairs if r.change.startswith("add caches at ")]
    assert pairs, [r.change for r in why.repairs]
    for repair in pairs:
        assert _realizable(repair.text)
        sites = repair.change.removeprefix("add caches at ").split(" and ")
        assert len(sites) == 2
        for site in sites:
            assert not _realizable(source + f"cache {site}\n"), site
    # no single cache anywhere helps (which is why the pair is offered)
    regions = [r.name for r in gaitc.parse(source, name="e.gait").robot.regions]
    assert not any(_realizable(source + f"cache {r}\n") for r in regions if r != "p3")
    assert why.repairs[-1].change.startswith("drop the goal")


def test_the_least_sufficient_health_is_exact_and_keeps_the_leg_order() -> None:
    why = gaitc.explain(DATA / "long_corridor.gait")
    source = (DATA / "long_corridor.gait").read_text(encoding="utf-8")
    first = why.repairs[0]
    assert first.change == "raise leg L2's health to 10"
    assert first.diff == ("-legs L1..L4 health 3", "+leg L1 health 3", "+leg L2 health 10",
                          "+legs L3, L4 health 3")
    assert _realizable(first.text)
    assert not _realizable(first.text.replace("leg L2 health 10", "leg L2 health 9"))
    legs = gaitc.parse(first.text, name="fixed.gait").robot.legs
    assert [(leg.name, leg.health) for leg in legs] == [("L1", 3), ("L2", 10), ("L3", 3),
                                                         ("L4", 3)]
    uniform = [r for r in why.repairs if r.change.startswith("raise every leg's")]
    assert [r.change for r in uniform] == ["raise every leg's health to 10"]
    assert not _realizable(source.replace("health 3", "health 9"))
    # the search went past the old limit of three levels up, and says how far it searches
    assert any("every level up to 100" in what for _, what in why.repairs_searched)


def test_a_failing_hazard_is_softened_to_the_most_wear_the_task_survives() -> None:
    why = gaitc.explain(DATA / "sand_hazard.gait")
    source = (DATA / "sand_hazard.gait").read_text(encoding="utf-8")
    first = why.repairs[0]
    assert first.change == ("let hazard set sand wear the legs by up to 2 levels instead of "
                            "failing them")
    assert first.diff == ("-hazard sand: b, c", "+hazard sand: b, c wears 2")
    assert _realizable(first.text)
    assert not _realizable(source.replace("hazard sand: b, c", "hazard sand: b, c wears 3"))
    assert not _realizable(source)
