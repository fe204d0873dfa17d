"""Fuzz suite (issues 9 and 48), CI size: mutants of every shipped input kind through every
command that reads it, in-process; no internal error, every located message shows its own
line, every run within its limit.  Also gaitc-run's scripts (it answers every line and never
crashes), odd output targets and codegen's options (nothing outside the fuzz folder
changes).  ``bench/fuzz.py`` is the long mode of the same cases.
"""

from __future__ import annotations

import os
import random
import shutil
from pathlib import Path

import pytest
from fuzz_cases import Fixtures, Kind, kinds, run_case
from fuzz_mutate import MUTATIONS, mutate
from fuzz_oracle import location_problems
from fuzz_runner import SCRIPTS, build_program, lines_read
from fuzz_runner import exchange as run_script
from fuzz_serial import EXCHANGES, exchange
from fuzz_targets import (
    NAMES,
    OPTIONS,
    SPECIAL,
    SPECIALS,
    VICTIM,
    Area,
    codegen_words,
    inside,
    run_codegen,
    run_target,
)
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

# slow: hundreds of mutants through every command that reads them (docs/background/testing.md)
pytestmark = pytest.mark.slow

LIMIT = 10.0  # seconds per run; generous, the machine is shared
# Mutants per kind: the whole file stays under two minutes on one core.
PER_KIND = {"gait": 60, "slugsin": 40, "structuredslugs": 40, "ltl": 40, "robot": 6,
            "scenario": 60, "controller": 60, "compact": 100, "run": 60, "map": 12,
            "sensing": 40, "calibration": 40, "curvature": 30}
SCRIPT_MUTANTS, TARGET_MUTANTS, OPTION_MUTANTS = 300, 40, 60
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


@pytest.fixture(scope="module")
def runner(fixtures: Fixtures) -> Path:
    """gaitc-run of the hazard patrol's compact controller, built once."""
    if shutil.which("gcc") is None:
        pytest.skip("gcc is missing: gaitc-run cannot be built")
    program = build_program(fixtures.hazard_compact, fixtures.folder / "runner")
    assert program is not None and program.is_file()
    return program


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


def test_gaitc_run_answers_its_seed_scripts(runner: Path) -> None:
    for name, script in SCRIPTS:
        verdicts = run_script(script, LIMIT, runner)
        assert [v.command for v in verdicts] == ["gaitc-run", "gaitc-run --names"]
        assert all(not v.problems for v in verdicts), (name, verdicts)
        # the three valid scripts are answered without an error; junk and long lines are not
        expected = 1 if name in ("junk.txt", "long.txt") else 0
        assert all(v.code == expected for v in verdicts), (name, verdicts)


@settings(FUZZ, max_examples=SCRIPT_MUTANTS)
@given(st.data())
def test_gaitc_run_scripts(runner: Path, data: st.DataObject) -> None:
    chooser = DrawChooser(data)
    _name, script = SCRIPTS[chooser.randint(0, len(SCRIPTS) - 1)]
    for verdict in run_script(mutate(script, chooser, [d for _, d in SCRIPTS]), LIMIT, runner):
        assert not verdict.problems, (verdict.command, verdict.problems)


def test_lines_read_counts_what_fgets_returns() -> None:
    assert lines_read(b"") == 0
    assert lines_read(b"d") == lines_read(b"d\n") == 1
    assert lines_read(b"\n\n") == 2
    assert lines_read(b"a" * 4094 + b"\n") == 1
    assert lines_read(b"a" * 4095 + b"\n") == 2  # the newline comes alone, second
    assert lines_read(b"a" * 4095) == 1
    assert lines_read(b"a" * 8191 + b"\nd\n") == 4


def test_the_runner_oracle_catches_a_crash_and_a_missing_answer(tmp_path: Path) -> None:
    crash, lazy = tmp_path / "crash", tmp_path / "lazy"
    crash.write_text("#!/bin/sh\nkill -SEGV $$\n", encoding="utf-8")
    lazy.write_text("#!/bin/sh\nhead -n 1\n", encoding="utf-8")
    for program in (crash, lazy):
        program.chmod(0o755)
    crashed = run_script(b"d\n", LIMIT, crash)[0]
    assert crashed.outcome == "internal" and "SIGSEGV" in crashed.problems[0]
    missing = run_script(b"one\ntwo\n", LIMIT, lazy)[0]
    assert missing.problems == ["internal: gaitc-run gave 1 answers to 2 lines"]


@pytest.mark.parametrize("special", [name for name, _ in SPECIALS])
def test_special_targets(fixtures: Fixtures, special: str) -> None:
    verdicts = run_target(SPECIAL + special, b"", fixtures, LIMIT)
    assert verdicts and all(not v.problems for v in verdicts), verdicts
    if special in ("proc-self", "dev-full", "through-a-file", "name-300",
                   "through-link-outside", "link-outside"):  # no command can write there
        assert all(v.code in (1, 2) for v in verdicts), verdicts


def test_target_seeds_write_inside_the_fuzz_folder(fixtures: Fixtures) -> None:
    area = Area.of(fixtures)
    for name, data in NAMES:
        verdicts = run_target(name, data, fixtures, LIMIT)
        assert all(not v.problems for v in verdicts), (name, verdicts)
        assert any(v.code == 0 for v in verdicts), (name, verdicts)
    assert area.victim.read_bytes() == VICTIM


@settings(FUZZ, max_examples=TARGET_MUTANTS)
@given(st.data())
def test_target_mutants(fixtures: Fixtures, data: st.DataObject) -> None:
    chooser = DrawChooser(data)
    name, seed = NAMES[chooser.randint(0, len(NAMES) - 1)]
    for verdict in run_target(name, mutate(seed, chooser, [d for _, d in NAMES]),
                              fixtures, LIMIT):
        assert not verdict.problems, (verdict.command, verdict.problems)


@settings(FUZZ, max_examples=OPTION_MUTANTS)
@given(st.data())
def test_codegen_option_mutants(fixtures: Fixtures, data: st.DataObject) -> None:
    chooser = DrawChooser(data)
    _name, seed = OPTIONS[chooser.randint(0, len(OPTIONS) - 1)]
    words = mutate(seed, chooser, [d for _, d in OPTIONS])
    for verdict in run_codegen(words, fixtures, LIMIT):
        assert not verdict.problems, (words, verdict.problems)


def test_codegen_option_seeds_are_accepted(fixtures: Fixtures) -> None:
    for name, words in OPTIONS:
        verdicts = run_codegen(words, fixtures, LIMIT)
        assert [v.code for v in verdicts] == [0] and not verdicts[0].problems, (name, verdicts)


@settings(FUZZ, max_examples=300)
@given(st.binary(max_size=80))
def test_a_mutated_name_stays_in_the_fuzz_folder(tmp_path_factory: pytest.TempPathFactory,
                                                 name: bytes) -> None:
    area = tmp_path_factory.getbasetemp() / "names"
    if not area.exists():
        area.mkdir()
        (area / "out").symlink_to("/")
        (area / "up").symlink_to("..")
    path = inside(area, name)
    root = os.path.realpath(area)
    assert os.path.commonpath([os.path.realpath(path), root]) == root, path
    assert "\0" not in str(path)


def test_codegen_words_put_every_path_in_the_fuzz_folder(tmp_path: Path) -> None:
    words = codegen_words(b"-o -1 --ou=../x --t ../c --target=/x -ogen -- /etc ..", tmp_path)
    root = str(tmp_path)
    assert words == ["-o", f"{root}/-1", f"--ou={root}/x", "--t", "../c", "--target=/x",
                     f"-o{root}/gen", "--", f"{root}/etc", f"{root}/unnamed"]


def test_the_target_oracle_catches_a_write_outside(fixtures: Fixtures) -> None:
    area = Area.of(fixtures)
    area.reset()
    assert area.escapes() == []
    (area.folder / "outside").write_bytes(b"through the link")
    assert area.escapes()[0].startswith("escaped: ")
    area.reset()
    (area.victim.parent / "beside").write_bytes(b"")
    assert "made beside" in area.escapes()[0]
    area.reset()
