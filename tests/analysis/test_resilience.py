"""``gaitc resilience`` against brute force on small purpose-built specs.

Each spec in tests/data/resilience/ (3 to 5 legs) is analysed with both methods in both
encodings, and every answer is compared with brute-force enumeration through
``gaitc check`` (:mod:`tests.brute_resilience`, which shares nothing with
:mod:`gaitc.analysis`): the failure sets over all subsets of legs, the health front over all
vectors within the bound, every cache left out, every placement, every hazard set alone,
and legs breaking during the run through the tests' own GR(1) construction. The answers
the specs' headers promise by construction are checked against both.
"""

from __future__ import annotations

import functools
import itertools
import json
from pathlib import Path

import brute_resilience as brute
import pytest

import gaitc
from gaitc.analysis.resilience import Resilience
from gaitc.cli import main

DATA = Path(__file__).resolve().parents[1] / "data" / "resilience"
#: spec -> (health bound, number of caches to place)
CASES = {"cross5": (2, 1), "corridor4": (3, 1), "rooms3": (3, 1), "hazards2": (3, 2),
         "detour4": (3, 2)}
ENCODINGS = ("onehot", "binary")
METHODS = ("parametric", "lattice")


def text_of(name: str) -> str:
    return (DATA / f"{name}.gait").read_text(encoding="utf-8")


@functools.cache
def answers(name: str, encoding: str) -> brute.Answers:
    bound, place = CASES[name]
    return brute.answers(text_of(name), encoding, bound, place)


@functools.cache
def report(name: str, encoding: str, method: str) -> Resilience:
    bound, place = CASES[name]
    spec = gaitc.parse(text_of(name), name=f"{name}.gait", encoding=encoding)
    return gaitc.resilience(spec, method=method, health_bound=bound, place_caches=place)


every_case = pytest.mark.parametrize(("name", "encoding", "method"), [
    (name, encoding, method) for name in CASES for encoding in ENCODINGS for method in METHODS])


def test_the_specs_are_small_realizable_and_cover_both_kinds_of_leg() -> None:
    assert sorted(p.stem for p in DATA.glob("*.gait")) == sorted(CASES)
    for name in CASES:
        model = brute.model_of(text_of(name))
        assert 3 <= len(model.legs) <= 5
        assert text_of(name).startswith("#")
        for encoding in ENCODINGS:
            assert brute.realizable(text_of(name), encoding)
    assert brute.model_of(text_of("rooms3")).leg("L3").health == 1  # already failed


# ---------------------------------------------------------------- against brute force
@every_case
def test_failure_sets_match_brute_force(name: str, encoding: str, method: str) -> None:
    got, table = report(name, encoding, method), answers(name, encoding).table
    assert got.realizable
    assert table.is_monotone()  # what the lattice search relies on
    assert got.minimal_fatal_sets == table.minimal_fatal()
    assert got.maximal_survivable_sets == table.maximal_survivable()
    assert got.single_points_of_failure == table.single_points()
    model = brute.model_of(text_of(name))
    assert got.already_failed == tuple(leg.name for leg in model.legs if leg.health == 1)


@every_case
def test_health_matches_brute_force(name: str, encoding: str, method: str) -> None:
    got, want = report(name, encoding, method), answers(name, encoding)
    assert got.health_bound == CASES[name][0]
    assert got.min_uniform_health == want.min_uniform_health
    assert got.health_front == want.health_front
    assert got.health_front  # every spec here has some front within its bound


@every_case
def test_caches_and_hazards_match_brute_force(name: str, encoding: str, method: str) -> None:
    got, want = report(name, encoding, method), answers(name, encoding)
    assert got.essential_caches == want.essential_caches
    assert got.placed == CASES[name][1]
    assert got.cache_placements == want.cache_placements
    assert got.hazards_survived_alone == want.hazards_survived_alone
    hazards = [h.name for h in brute.model_of(text_of(name)).hazards]
    assert got.hazards_fatal_alone == tuple(h for h in hazards
                                            if h not in want.hazards_survived_alone)


@every_case
def test_any_time_k_matches_an_independent_construction(name: str, encoding: str,
                                                        method: str) -> None:
    got, want = report(name, encoding, method), answers(name, encoding)
    verdicts = want.any_time_verdicts
    assert verdicts[0]  # nothing breaking is the spec itself
    assert all(not later or earlier for earlier, later in itertools.pairwise(verdicts))
    assert got.any_time_k == want.any_time_k
    assert got.defeating_sets == want.defeating_sets


@every_case
def test_any_time_k_is_below_every_fatal_set(name: str, encoding: str, method: str) -> None:
    got = report(name, encoding, method)
    smallest = min(len(s) for s in got.minimal_fatal_sets)
    assert got.any_time_k is not None and got.any_time_k <= smallest - 1


# ---------------------------------------------------------------- known by construction
KNOWN = {
    "cross5": dict(minimal_fatal_sets=(("L3",), ("L1", "L2"), ("L1", "L4", "L5"),
                                       ("L2", "L4", "L5")),
                   maximal_survivable_sets=(("L1", "L4"), ("L1", "L5"), ("L2", "L4"),
                                            ("L2", "L5"), ("L4", "L5")),
                   single_points_of_failure=("L3",), any_time_k=0, defeating_sets=(("L3",),),
                   min_uniform_health=2, essential_caches=()),
    "corridor4": dict(minimal_fatal_sets=(("L1", "L2"), ("L3", "L4")),
                      single_points_of_failure=(), any_time_k=1,
                      defeating_sets=(("L1", "L2"), ("L3", "L4")), min_uniform_health=3,
                      essential_caches=("a",),
                      health_front=tuple(
                          (("L1", a), ("L2", b), ("L3", c), ("L4", d))
                          for a, b in ((2, 3), (3, 2)) for c, d in ((2, 3), (3, 2)))),
    "detour4": dict(minimal_fatal_sets=(("L1", "L2"), ("L3", "L4")), any_time_k=0,
                    defeating_sets=()),
    "rooms3": dict(minimal_fatal_sets=(("L1",), ("L2",)), maximal_survivable_sets=((),),
                   already_failed=("L3",), essential_caches=("dock",)),
    "hazards2": dict(hazards_survived_alone=("spill", "smoke"), essential_caches=("c",)),
}


@pytest.mark.parametrize("name", sorted(KNOWN))
def test_the_answers_known_by_construction(name: str) -> None:
    for encoding in ENCODINGS:
        for method in METHODS:
            got = report(name, encoding, method)
            for field, value in KNOWN[name].items():
                assert getattr(got, field) == value, (encoding, method, field)
        want = answers(name, encoding)
        assert want.table.minimal_fatal() == KNOWN[name].get(
            "minimal_fatal_sets", want.table.minimal_fatal())
        assert want.any_time_k == KNOWN[name].get("any_time_k", want.any_time_k)
        assert want.health_front == KNOWN[name].get("health_front", want.health_front)


# ---------------------------------------------------------------- the text variants
def test_the_brute_force_variants_are_what_they_say() -> None:
    rooms = text_of("rooms3")
    failed = brute.model_of(brute.with_failed(rooms, ["L2"]))
    assert [(leg.name, leg.health, leg.initial) for leg in failed.legs] == [
        ("L1", 3, 3), ("L2", 1, 1), ("L3", 1, 1)]
    raised = brute.model_of(brute.with_health(rooms, {"L1": 2, "L2": 3, "L3": 3}))
    assert [(leg.name, leg.health, leg.initial) for leg in raised.legs] == [
        ("L1", 2, 2), ("L2", 3, 2), ("L3", 3, 3)]
    assert brute.model_of(brute.with_caches(rooms, [])).caches == ()
    assert brute.model_of(brute.with_caches(rooms, ["hall", "lab"])).caches == ("hall", "lab")
    alone = brute.with_hazards(text_of("hazards2"), ["spill"])
    assert [h.name for h in brute.model_of(alone).hazards] == ["spill"]
    assert "!spill & !false" in alone and "next(false)" in alone


def test_the_cli_reports_the_same_answers_as_json(capsys: pytest.CaptureFixture[str]) -> None:
    path = str(DATA / "corridor4.gait")
    assert main(["resilience", path, "--json", "--place-caches", "1", "--health-bound",
                 "3"]) == 0
    got = json.loads(capsys.readouterr().out)
    want = answers("corridor4", "binary")
    assert got["minimal_fatal_sets"] == [list(s) for s in want.table.minimal_fatal()]
    assert got["any_time_k"] == want.any_time_k
    assert got["cache_placements"] == [list(s) for s in want.cache_placements]
    assert got["health_front"] == [dict(v) for v in want.health_front]


@pytest.mark.parametrize("name", ["detour4", "rooms3"])
def test_the_default_health_front_is_within_each_legs_own_levels(name: str) -> None:
    """Without --health-bound the front is searched over each leg's declared levels (so a
    spec realizable at its own levels always has a front), re-solved by brute force."""
    spec = gaitc.parse(text_of(name), name=f"{name}.gait", encoding="binary")
    got = gaitc.resilience(spec)
    assert got.health_bound is None
    assert got.health_levels == tuple((leg.name, leg.health) for leg in spec.robot.legs)
    uniform, front = brute.health_front(text_of(name), "binary", None)
    assert got.min_uniform_health == uniform
    assert got.health_front == front and front
    assert "3. health (each leg within its own declared levels: " in "\n".join(got.lines())


SAND = """\
legs L1..L2 health 7
gait east uses L1 moves east
gait west uses L2 moves west
grid 1 x 4 cells a, b, c, d
cache a, d
hazard sand: b, c wears 2
start a
visit a, d infinitely often
"""


def test_a_graded_hazard_reports_the_most_wear_survived() -> None:
    """The sand may wear up to 2 levels a move and no more, and failing the legs is fatal:
    each answer re-solved here from the edited text."""
    got = gaitc.resilience(gaitc.parse(SAND, name="sand.gait"))
    assert got.hazard_wear == (("sand", 2, 2, False),)
    assert "graded hazard sand (wears 2): survives it wearing up to 2 levels a move; failing " \
           "the legs would be fatal" in [line.strip() for line in got.lines()]

    def realizable(text: str) -> bool:
        return gaitc.check(gaitc.parse(text, name="variant.gait")).realizable

    assert realizable(SAND)
    assert not realizable(SAND.replace("wears 2", "wears 3"))
    assert not realizable(SAND.replace(" wears 2", ""))
    gentler = gaitc.resilience(gaitc.parse(SAND.replace("health 7", "health 9"),
                                           name="sand9.gait"))
    most = gentler.hazard_wear[0][2]
    assert realizable(SAND.replace("health 7", "health 9").replace("wears 2", f"wears {most}"))
    assert most == 8 or not realizable(
        SAND.replace("health 7", "health 9").replace("wears 2", f"wears {most + 1}"))


def _without_times(value: object) -> object:
    """A report's JSON without its measured seconds."""
    if isinstance(value, dict):
        return {k: _without_times(v) for k, v in value.items()
                if "seconds" not in k and k != "notes"}
    if isinstance(value, list):
        return [_without_times(v) for v in value]
    return value


def test_a_spec_loaded_one_hot_is_analysed_in_binary_with_the_same_answers() -> None:
    """``gaitc.load`` reads one-hot by default and ``gaitc resilience`` analyses in binary:
    ``gaitc.resilience`` of a loaded spec takes the binary games too (issue 59), and asked
    for one-hot games it answers the same."""
    path = Path(__file__).resolve().parent.parent.parent / "specs" / "corridor_hazard.gait"
    loaded = gaitc.load(path)
    assert loaded.encoding == "onehot"
    from_loaded = gaitc.resilience(loaded)
    from_path = gaitc.resilience(str(path))
    one_hot = gaitc.resilience(loaded, encoding="onehot")
    want = _without_times(from_path.to_json())
    assert _without_times(from_loaded.to_json()) == want
    assert _without_times(one_hot.to_json()) == want
