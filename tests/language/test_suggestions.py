"""The suggestion catalogue (issue 34): a misspelt name, keyword or command, and the usual
slips of a new user (a range written L1-L4, a goal written as another tool writes it), each
with its exact message and the hint that names what was meant.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import gaitc
from gaitc.cli import main

BASE = """\
robot "lab"
legs L1..L4 health 3
gait east_a uses L1, L2 moves east
gait west_a uses L3, L4 moves west
gait north_a uses L1, L3 moves north
grid 3 x 2
hazard spill: r1
cache r2
start r0
visit r5 infinitely often
"""

#: (the line of BASE replaced, what the user wrote, the message, the hint)
CATALOGUE = [
    ('gait west_a uses L3, L4 moves west',
     'gait west_a uses L3, Ll4 moves west',
     "lab.gait:4:22: unknown leg 'Ll4' in gait west_a; declared legs are L1..L4",
     "did you mean 'L4'?"),
    ('legs L1..L4 health 3',
     'legs L1-L4 health 3',
     "lab.gait:2:8: unexpected character '-': names use letters, digits and '_', comments start "
     "with '#'",
     'a range of names is written with two dots: L1..L4'),
    ('legs L1..L4 health 3',
     'lges L1..L4 health 3',
     "lab.gait:2:1: unexpected name 'lges'; expected end of file or a new statement",
     "did you mean 'legs'?"),
    ('legs L1..L4 health 3',
     'legs L1..L4 helth 3',
     "lab.gait:2:13: unexpected name 'helth'; expected ',' or 'health'",
     "did you mean 'health'?"),
    ('gait north_a uses L1, L3 moves north',
     'gait north_a uses L1, L3 moves nroth',
     "lab.gait:5:32: 'nroth' after 'moves' is not a direction; expected north, south, east or "
     "west, or region transitions such as 'a -> b'",
     "did you mean 'north'?"),
    ('gait north_a uses L1, L3 moves north',
     'giat north_a uses L1, L3 moves north',
     "lab.gait:5:1: unexpected name 'giat'; expected ',', 'primitive', 'valves', end of file or "
     'a new statement',
     "did you mean 'gait'?"),
    ('gait north_a uses L1, L3 moves north',
     'gait north_a usse L1, L3 moves north',
     "lab.gait:5:14: unexpected name 'usse'; expected 'moves', 'primitive', 'uses', 'valves', "
     'end of file or a new statement',
     "did you mean 'uses'?"),
    ('gait north_a uses L1, L3 moves north',
     'gait north_a uses L1, L3 mvoes north',
     "lab.gait:5:26: unexpected name 'mvoes'; expected ',', '..', 'moves', 'primitive', "
     "'valves', end of file or a new statement",
     "did you mean 'moves'?"),
    ('visit r5 infinitely often',
     'vist r5 infinitely often',
     "lab.gait:10:1: unexpected name 'vist'; expected 'with', end of file or a new statement",
     "did you mean 'visit'?"),
    ('visit r5 infinitely often',
     'visit r5 infinitly often',
     "lab.gait:10:10: unexpected name 'infinitly'; expected ',' or 'infinitely'",
     "did you mean 'infinitely'?"),
    ('visit r5 infinitely often',
     'visit r5 infinitely oftne',
     "lab.gait:10:21: unexpected name 'oftne'; expected 'often'",
     "did you mean 'often'?"),
    ('visit r5 infinitely often',
     'visit r55 infinitely often',
     "lab.gait:10:7: unknown region 'r55' in goal; declared regions are r0..r5",
     "did you mean 'r5'?"),
    ('visit r5 infinitely often',
     'goal r5, r0',
     "lab.gait:10:1: unexpected name 'goal'; expected 'with', end of file or a new statement",
     "write 'visit r5, r0 infinitely often'"),
    ('start r0',
     'strat r0',
     "lab.gait:9:1: unexpected name 'strat'; expected ',', end of file or a new statement",
     "did you mean 'start'?"),
    ('start r0',
     'start rr0',
     "lab.gait:9:7: unknown region 'rr0' as the start; declared regions are r0..r5",
     "did you mean 'r0'?"),
    ('cache r2',
     'cahce r2',
     "lab.gait:8:1: unexpected name 'cahce'; expected ',', 'wears', end of file or a new statement",
     "did you mean 'cache'?"),
    ('cache r2',
     'cache r22',
     "lab.gait:8:7: unknown region 'r22' in cache; declared regions are r0..r5",
     "did you mean 'r2'?"),
    ('hazard spill: r1',
     'hazrd spill: r1',
     "lab.gait:7:1: unexpected name 'hazrd'; expected 'cells', end of file or a new statement",
     "did you mean 'hazard'?"),
    ('hazard spill: r1',
     'hazard spill: r11',
     "lab.gait:7:15: unknown region 'r11' in hazard spill; declared regions are r0..r5",
     "did you mean 'r1'?"),
    ('visit r5 infinitely often',
     'visit r5 infinitely often\nassume always eventually !spil',
     "lab.gait:11:27: unknown name 'spil' in formula; formulas may use regions, gaits, hazards, "
     'noGait and health(LEG)',
     "did you mean 'spill'?"),
    ('visit r5 infinitely often',
     'visit r5 infinitely often\nguarantee always (east_a -> nxet r1)',
     "lab.gait:11:29: name 'nxet' cannot be followed by name 'r1'; expected an operator such as "
     "& or -> or ')' after it",
     "did you mean 'next'?"),
    ('visit r5 infinitely often',
     'visit r5 infinitely often\nguarantee always (eats_a -> r1)',
     "lab.gait:11:19: unknown name 'eats_a' in formula; formulas may use regions, gaits, "
     'hazards, noGait and health(LEG)',
     "did you mean 'east_a'?"),
    ('gait east_a uses L1, L2 moves east',
     'gait east_a uses L1, L2 moves east\ngait east_b uses L3, L4 moves easst',
     "lab.gait:4:31: 'easst' after 'moves' is not a direction; expected north, south, east or "
     "west, or region transitions such as 'a -> b'",
     "did you mean 'east'?"),
    ('visit r5 infinitely often',
     'visit r5 infinitely often\navoid r1',
     "lab.gait:11:1: unexpected name 'avoid'; expected end of file or a new statement",
     "write 'guarantee always !(r1)'"),
]


@pytest.mark.parametrize(("line", "written", "message", "hint"), CATALOGUE)
def test_each_slip_names_what_was_meant(line: str, written: str, message: str,
                                        hint: str) -> None:
    assert line in BASE
    with pytest.raises(gaitc.GaitcError) as caught:
        gaitc.parse(BASE.replace(line, written), name="lab.gait")
    assert str(caught.value) == message
    assert caught.value.hint == hint


def test_the_catalogue_is_large_enough() -> None:
    assert len(CATALOGUE) >= 20
    assert len({written for _, written, _, _ in CATALOGUE}) == len(CATALOGUE)


@pytest.mark.parametrize(("argv", "meant"), [
    (["sytnh", "x.gait"], "synth"), (["explian", "x.gait"], "explain"),
    (["simualte", "x.gait"], "simulate"), (["resilence", "x.gait"], "resilience"),
    (["render", "mpa", "x.gait"], "map"), (["gait", "r.yaml"], "gaits"),
])
def test_a_mistyped_command_gets_the_nearest(argv: list[str], meant: str,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert f"invalid choice: '{argv[0] if meant != 'map' else argv[1]}'" in err
    assert err.rstrip().endswith(f"hint: did you mean '{meant}'?")


def test_the_base_spec_itself_reads(tmp_path: Path) -> None:
    assert gaitc.parse(BASE, name="lab.gait").model is not None
