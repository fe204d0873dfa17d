"""Fuzz suite (issue 9), CI size: mutants of every shipped input kind through every command
that reads it, in-process; no internal error, every located message shows its own line,
every run within its limit. ``bench/fuzz.py`` is the long mode of the same cases.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest
from fuzz_cases import Fixtures, Kind, kinds, run_case
from fuzz_mutate import MUTATIONS, mutate
from fuzz_oracle import location_problems
from fuzz_serial import EXCHANGES, exchange
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

LIMIT = 10.0  # seconds per run; generous, the machine is shared
# Mutants per kind: the whole file stays under a minute on one core.
PER_KIND = {"gait": 60, "slugsin": 40, "structuredslugs": 40, "ltl": 40, "robot": 6,
            "scenario": 60, "controller": 60, "run": 60, "map": 12, "sensing": 40,
            "calibration": 40, "curvature": 30}
FUZZ = settings(deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.function_scoped_fixture])


class DrawChooser:
    """A :class:`fuzz_mutate.Chooser` over hypothesis draws (so examples shrink)."""

    def __init__(self, data: st.DataObject) -> None:
        self.data = data

    def randint(self, a: int, b: int) -> int:
        return self.data.draw(st.integers(a, b))


@pytest.fixture(scope="module")
def fixtures(tmp_path_factory: pytest.TempPathFactory) -> Fixtures:
    return Fixtures(tmp_path_factory.mktemp("fuzz"))


@pytest.fixture(scope="module")
def table(fixtures: Fixtures) -> dict[str, Kind]:
    return kinds(fixtures)


def _judge(kind: Kind, fx: Fixtures, seed: str, data: bytes) -> None:
    for verdict in run_case(kind, fx, seed, data, LIMIT):
        assert not verdict.problems, (kind.name, verdict.command, seed, data[:300],
                                      verdict.problems)


def test_every_kind_has_seeds_that_its_commands_accept(fixtures: Fixtures,
                                                       table: dict[str, Kind]) -> None:
    assert set(table) == set(PER_KIND)
    for kind in table.values():
        assert kind.seeds, kind.name
        name, data = kind.seeds[0]
        verdicts = run_case(kind, fixtures, name, data, LIMIT)
        assert verdicts and all(not v.problems for v in verdicts), (kind.name, verdicts)
        if kind.name == "sensing":  # read and accepted; then the loopback port, no board
            assert all(v.code == 1 for v in verdicts), (kind.name, verdicts)
        elif kind.name not in ("robot", "gait"):  # the first gait seed is a 24-leg spec
            assert all(v.outcome == "accepted" for v in verdicts), (kind.name, verdicts)


@pytest.mark.parametrize("kind_name", sorted(PER_KIND))
def test_mutants_of_every_kind(fixtures: Fixtures, table: dict[str, Kind],
                               kind_name: str) -> None:
    kind = table[kind_name]

    @settings(FUZZ, max_examples=PER_KIND[kind_name])
    @given(st.data())
    def run(data: st.DataObject) -> None:
        chooser = DrawChooser(data)
        name, seed = kind.seeds[chooser.randint(0, len(kind.seeds) - 1)]
        _judge(kind, fixtures, name, mutate(seed, chooser, [d for _, d in kind.seeds]))

    run()


@settings(FUZZ, max_examples=300)
@given(st.data())
def test_serial_replies(data: st.DataObject) -> None:
    chooser = DrawChooser(data)
    _name, stream = EXCHANGES[chooser.randint(0, len(EXCHANGES) - 1)]
    verdict = exchange(mutate(stream, chooser), LIMIT)
    assert not verdict.problems, verdict.problems


def test_mutations_are_deterministic_and_each_changes_something() -> None:
    seed = b"legs L1 health 2\ngait g uses L1 moves north\ngrid 2 x 1\nstart r0\n"
    first = [mutate(seed, random.Random(i)) for i in range(50)]
    assert first == [mutate(seed, random.Random(i)) for i in range(50)]
    for mutation in MUTATIONS:
        changed = {mutation(seed, random.Random(i), [seed]) for i in range(20)}
        assert changed - {seed}, mutation.__name__


def test_the_oracle_catches_a_wrong_echoed_line(tmp_path: Path) -> None:
    path = str(tmp_path / "x.gait")
    data = b"a\x0cb\nsecond\n"
    good = f"{path}:2:1: error: boom\n    second\n    ^\n"
    assert location_problems(good, {path: data}) == []
    shifted = f"{path}:2:1: error: boom\n    b\n    ^\n"
    assert location_problems(shifted, {path: data})[0].startswith("wrong line")
    past = f"{path}:3:1: error: boom\n"
    assert "has 2 lines" in location_problems(past, {path: data})[0]
