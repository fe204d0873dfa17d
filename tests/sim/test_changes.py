"""The one type of a change of the environment (``gaitc.core.changes``): its words are read
back by its one parser, whoever wrote them (the player's environment moves, ``--violate``,
the surprises the player offers), and an event of those words makes the change it says."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.core.changes import (
    HazardSwitch,
    LegFails,
    LegRepaired,
    LegWears,
    between,
    parse_changes,
)
from gaitc.diagnostics import UsageError
from gaitc.play.words import environment_words
from gaitc.sim.domain import State
from gaitc.sim.events import Event

LEGS = ("L1", "L2", "L3")
HAZARDS = ("spill", "acid")
FULL = {"L1": 4, "L2": 3, "L3": 2}


@pytest.mark.parametrize(("text", "changes"), [
    ("fail L1", (LegFails("L1"),)),
    ("degrade L2", (LegWears("L2"),)),
    ("degrade L2 by 3", (LegWears("L2", 3),)),
    ("repair L3", (LegRepaired("L3"),)),
    ("repair L3 to level 2", (LegRepaired("L3", 2),)),
    ("switch spill on", (HazardSwitch("spill", True),)),
    ("switch spill off, switch acid on, fail L2",
     (HazardSwitch("spill", False), HazardSwitch("acid", True), LegFails("L2"))),
])
def test_each_kind_of_change_reads_back_from_its_words(text: str, changes: tuple[object, ...]
                                                       ) -> None:
    parsed = parse_changes(text, LEGS, HAZARDS, "--violate")
    assert parsed == changes
    assert ", ".join(c.words() for c in parsed) == text


@pytest.mark.parametrize(("text", "message"), [
    ("fail L1, degrade L1", "--violate 'fail L1, degrade L1': 'fail L1' and 'degrade L1' both "
                            "change leg L1; give one of them"),
    ("switch spill on, switch acid on", "--violate 'switch spill on, switch acid on': 'switch "
     "spill on' and 'switch acid on' both change the hazard; give one of them"),
    ("switch spill on, switch spill off", "--violate 'switch spill on, switch spill off': "
     "'switch spill on' and 'switch spill off' both change the hazard; give one of them"),
    ("repair L9", "--violate 'repair L9': unknown leg 'L9'; the robot's legs are L1, L2, L3"),
    ("degrade L1 by 0", "--violate 'degrade L1 by 0': not an event; write one of 'fail LEG', "
     "'degrade LEG', 'degrade LEG by N', 'repair LEG', 'repair LEG to level N', 'switch "
     "HAZARD on', 'switch HAZARD off', or several joined by commas"),
])
def test_changes_that_cannot_be_are_refused_with_the_words_given(text: str, message: str
                                                                 ) -> None:
    with pytest.raises(UsageError) as refused:
        parse_changes(text, LEGS, HAZARDS, "--violate")
    assert str(refused.value) == message


_levels = st.tuples(*(st.integers(1, FULL[leg]) for leg in LEGS))
_hazard = st.sampled_from((None, *HAZARDS))


@settings(max_examples=300, deadline=None)
@given(_levels, _levels, _hazard, _hazard)
def test_the_players_words_of_a_move_make_that_move(before: tuple[int, ...],
                                                    after: tuple[int, ...],
                                                    on: str | None, then: str | None) -> None:
    """Whatever the environment did, the words the player shows for it parse, and an event
    of those words takes the state before to the state after."""
    here = State("r1", "g", tuple(zip(LEGS, before, strict=True)), on)
    there = State("r1", "g", tuple(zip(LEGS, after, strict=True)), then)
    text = environment_words(here, there, FULL)
    changes = between(dict(here.health), dict(there.health), FULL, on, then)
    if not changes:
        assert text == "nothing"
        return
    parsed = parse_changes(text, LEGS, HAZARDS, "the player")
    assert parsed == changes

    class _Domain:  # what Event.onto reads of a domain
        legs = LEGS
        full = FULL

    assert Event(parsed).apply(here, _Domain()) == there  # type: ignore[arg-type]
