"""Graded hazards (issue 51): ``hazard sand: b wears 2``, from the grammar to realizability.

The cross-check at the heart of this file writes the environment's one-step semantics
out by hand (eqs. 3.5, 3.6, 3.9 and the graded hazard, without the lowering), enumerates
every state and every next input of small robots, and compares the successors with those
the lowered ``env_trans`` allows, read as BDDs by the verifiers' :class:`Logic` after
bit-blasting, in both encodings.  Realizability verdicts reasoned out by hand are then
checked against the embedded solver and, when it is installed, SLUGS.
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import gaitc
from gaitc.diagnostics import SpecSemanticError
from gaitc.ir.bitblast import bitblast
from gaitc.ir.bits import encode_bits
from gaitc.ir.evaluation import evaluate
from gaitc.ir.roles import Fails, WearsUpTo
from gaitc.ir.spec import GR1Spec, Variable
from gaitc.verifier.logic import Logic
from ltlcompiler.encoding import EncodingName, health_prop, make_encoding
from ltlcompiler.frontend import model_from_text, parse_text
from ltlcompiler.lowering import lower
from ltlcompiler.model import GaitKind, Hazard, Leg, Model
from ltlcompiler.syntax import HazardDecl, Name

ENCODINGS = (EncodingName.ONEHOT, EncodingName.BINARY)


# ---------------------------------------------------------------- the language
def test_wears_is_parsed_with_its_span() -> None:
    spec = parse_text("hazard sand: e14, e24 wears 2\nhazard fire: e3\n")
    sand, fire = spec.statements
    assert sand == HazardDecl(Name("sand"), (Name("e14"), Name("e24")), 2)
    assert isinstance(sand, HazardDecl) and sand.wears_span is not None
    assert (sand.wears_span.line, sand.wears_span.column) == (1, 29)
    assert fire == HazardDecl(Name("fire"), (Name("e3"),))
    assert isinstance(fire, HazardDecl) and fire.wears is None


CORRIDOR = """\
legs L1, L2 health {health}
gait east uses L1 moves east
gait west uses L2 moves west
grid 1 x 3 cells a, b, c
cache a
hazard sand: b{wears}
start a
visit a, c infinitely often
"""


def _corridor(health: int, wears: int | None) -> str:
    return CORRIDOR.format(health=health, wears="" if wears is None else f" wears {wears}")


def test_the_model_keeps_the_wear_and_says_what_it_does() -> None:
    model, warnings = model_from_text(_corridor(4, 2))
    assert model.hazards == (Hazard("sand", ("b",), harm=WearsUpTo(2)),)
    assert model.hazards[0].effect == "wears the legs by up to 2 levels"
    assert warnings == []
    failing, _ = model_from_text(_corridor(4, None))
    assert failing.hazards == (Hazard("sand", ("b",)),)
    assert failing.hazards[0].effect == "fails the legs"
    assert Hazard("h", ("b",), harm=WearsUpTo(1)).effect == "wears the legs by up to 1 level"


def test_wears_one_warns_and_lowers_like_no_hazard() -> None:
    """``wears 1`` is eq. 3.5 itself: the graded clause's body is the eq. 3.5 body."""
    model, warnings = model_from_text(_corridor(3, 1))
    assert [w.message.split(",")[0] for w in warnings] == ["hazard 'sand' wears 1 level"]
    spec = lower(model)
    graded = [c.formula for c in spec.env_trans if c.origin is not None
              and c.origin.rule.startswith("eq. 3.9 graded")]
    normal = [c.formula for c in spec.env_trans if c.origin is not None
              and c.origin.rule.startswith("eq. 3.5: under")]
    assert len(graded) == len(normal) == 2
    for g, n in zip(graded, normal, strict=True):
        assert g.children()[1] == n.children()[1]  # same consequent


def test_wears_zero_is_an_error() -> None:
    with pytest.raises(SpecSemanticError, match=r"hazard 'sand' wears 0 levels"):
        model_from_text(_corridor(3, 0))


def test_the_rule_names_the_generalised_equation() -> None:
    model, _ = model_from_text(_corridor(4, 2))
    rules = [c.origin.rule for c in lower(model).env_trans if c.origin is not None]
    assert ("eq. 3.9 graded (eq. 3.5 with up to 2 levels): hazard sand active in b under "
            "east: leg L1 may lose up to 2 levels, the other legs keep theirs") in rules
    assert not any(r.startswith("eq. 3.9: ") for r in rules)


# ---------------------------------------------------------------- wear of one leg
@settings(max_examples=200, deadline=None)
@given(health=st.integers(1, 7), wears=st.integers(1, 9), now=st.integers(1, 7),
       after=st.integers(1, 7))
def test_wear_health_allows_exactly_the_levels_down_to_k_below(
        health: int, wears: int, now: int, after: int) -> None:
    """Both encodings' ``wear_health`` hold exactly when max(1, h - k) <= h' <= h."""
    now, after = min(now, health), min(after, health)
    model = Model("m", (Leg("L", health, health),), (), (), (), (), (), "a", (), (), ())
    expected = max(1, now - wears) <= after <= now
    for name in ENCODINGS:
        formula = make_encoding(model, name).wear_health("L", wears)
        if name is EncodingName.BINARY:
            valuation = {"L": now, "L'": after}
        else:
            valuation = {health_prop("L", j): int(j == now) for j in range(1, health + 1)}
            valuation |= {health_prop("L", j) + "'": int(j == after)
                          for j in range(1, health + 1)}
        assert evaluate(formula, valuation) is expected, (name, health, wears, now, after)


# ---------------------------------------------------------------- the brute-force cross-check
@dataclass(frozen=True)
class _State:
    region: str
    gait: str
    health: tuple[int, ...]  # in leg order
    hazard: str | None


def _hand_successors(model: Model, state: _State) -> set[tuple[tuple[int, ...], str | None]]:
    """The environment's next inputs (health, hazard) from ``state``, by the semantics as
    docs/language.md states it: a cache restores every leg; elsewhere the legs of a moving
    gait may lose one level (eq. 3.5), or, in a region of the active hazard set, fail
    (eq. 3.9) or lose up to k levels (``wears k``); other legs keep their level; the next
    hazard is any one set or none."""
    hazards = [None, *(h.name for h in model.hazards)]
    if state.region in model.caches:
        full = tuple(leg.health for leg in model.legs)
        return {(full, h) for h in hazards}
    gait = model.gait(state.gait)
    used = set(gait.legs) if gait.kind is GaitKind.MOVE else set()
    active = next((h for h in model.hazards
                   if h.name == state.hazard and state.region in h.regions), None)
    choices: list[range] = []
    for leg, level in zip(model.legs, state.health, strict=True):
        if leg.name not in used:
            choices.append(range(level, level + 1))
        elif active is not None and isinstance(active.harm, Fails):
            choices.append(range(1, 2))
        else:
            loss = 1 if active is None or not isinstance(active.harm, WearsUpTo) \
                else active.harm.levels
            choices.append(range(max(1, level - loss), level + 1))
    return {(levels, h) for levels in itertools.product(*choices) for h in hazards}


def _states(model: Model) -> Iterator[_State]:
    levels = itertools.product(*(range(1, leg.health + 1) for leg in model.legs))
    for health in levels:
        for region in model.regions:
            for gait in model.gaits:
                for hazard in [None, *(h.name for h in model.hazards)]:
                    yield _State(region.name, gait.name, health, hazard)


def _bits(variables: tuple[Variable, ...], values: Mapping[str, int], primed: bool
          ) -> dict[str, bool]:
    suffix = "'" if primed else ""
    out: dict[str, bool] = {}
    for var in variables:
        if var.name not in values:
            continue
        if var.is_integer:
            out.update(encode_bits(var, values[var.name], primed))
        else:
            out[var.name + suffix] = bool(values[var.name])
    return out


def _values(model: Model, encoding: EncodingName, state: _State) -> dict[str, int]:
    from ltlcompiler.decoding import RobotState, encode

    health = tuple((leg.name, level) for leg, level in zip(model.legs, state.health,
                                                         strict=True))
    return encode(model, encoding, RobotState(state.region, state.gait, health, state.hazard))


def _lowered_successors(model: Model, encoding: EncodingName) -> Iterator[
        tuple[_State, set[tuple[tuple[int, ...], str | None]]]]:
    """Each state and the next inputs the lowered env_trans allows from it."""
    spec: GR1Spec = lower(model, encoding)
    logic = Logic(bitblast(spec))
    env = functools.reduce(lambda a, b: a & b, (u for _, u in logic.clauses("env_trans")))
    variables = spec.inputs + spec.outputs
    input_names = {v.name for v in spec.inputs}
    nexts = [_State("", "", health, hazard) for health in itertools.product(
        *(range(1, leg.health + 1) for leg in model.legs))
        for hazard in [None, *(h.name for h in model.hazards)]]
    primed = []
    for nxt in nexts:
        anywhere = _values(model, encoding, _State(model.regions[0].name, model.gaits[0].name,
                                                   nxt.health, nxt.hazard))
        inputs = {k: v for k, v in anywhere.items() if k in input_names}
        primed.append((nxt, _bits(spec.inputs, inputs, True)))
    for state in _states(model):
        current = _bits(variables, _values(model, encoding, state), False)
        here = logic.restrict(env, current)
        allowed = {(nxt.health, nxt.hazard) for nxt, bits in primed if logic.holds(here, bits)}
        yield state, allowed


SMALL = {
    "corridor, 2 legs of 3, wears 2": """\
legs L1, L2 health 3
gait east uses L1, L2 moves east
gait west uses L2 moves west
correction gait turn
grid 1 x 3 cells a, b, c
cache a
hazard sand: b, c wears 2
start a
""",
    "2 x 2, legs of 4 and 2, wears 2 and a failing hazard": """\
legs L1 health 4
leg L2 health 2
gait east uses L1 moves east
gait west uses L2 moves west
gait north uses L1, L2 moves north
grid 2 x 2 cells nw, ne, sw, se
hazard sand: ne, se wears 2
hazard fire: sw
start nw
""",
    "corridor, wears more than the legs have, a failed leg": """\
legs L1 health 4
leg L2 health 3
leg L3 health 1
gait east uses L1, L2 moves east
gait west uses L2 moves west
gait slide uses L3 moves west
grid 1 x 3 cells a, b, c
cache c
hazard grit: a, b wears 5
start a
""",
}


@pytest.mark.parametrize("encoding", ENCODINGS, ids=str)
@pytest.mark.parametrize("name", sorted(SMALL))
def test_env_trans_allows_exactly_the_hand_written_successors(
        name: str, encoding: EncodingName) -> None:
    model, _ = model_from_text(SMALL[name])
    graded = [h for h in model.hazards if isinstance(h.harm, WearsUpTo)]
    seen_deep_loss = False
    checked = 0
    for state, allowed in _lowered_successors(model, encoding):
        expected = _hand_successors(model, state)
        assert allowed == expected, (state, sorted(allowed ^ expected, key=str)[:6])
        checked += 1
        seen_deep_loss = seen_deep_loss or any(
            before - after >= 2 for levels, _ in allowed
            for before, after in zip(state.health, levels, strict=True)
            if state.region not in model.caches)
    assert checked == len(list(_states(model)))
    assert graded and seen_deep_loss  # the graded clause is exercised, not vacuous


@st.composite
def _corridors(draw: st.DrawFn) -> str:
    """A random robot of two legs on the corridor a - b - c with one or two hazards, at
    least one of them graded, and maybe a cache outside them."""
    cells = ["a", "b", "c"]
    health = [draw(st.integers(1, 4)) for _ in range(2)]
    legs = st.lists(st.sampled_from(["L1", "L2"]), min_size=1, max_size=2, unique=True)
    hazards = [(draw(st.lists(st.sampled_from(cells), min_size=1, max_size=3, unique=True)),
                draw(st.integers(1, 5)))]
    if draw(st.booleans()):
        hazards.append((draw(st.lists(st.sampled_from(cells), min_size=1, max_size=3,
                                      unique=True)), draw(st.sampled_from([None, 2]))))
    free = [c for c in cells if all(c not in regions for regions, _ in hazards)]
    cache = draw(st.sampled_from([None, *free]))
    lines = [f"leg L1 health {health[0]}", f"leg L2 health {health[1]}",
             f"gait east uses {', '.join(draw(legs))} moves east",
             f"gait west uses {', '.join(draw(legs))} moves west",
             "correction gait turn", "grid 1 x 3 cells a, b, c", "start a"]
    lines += [] if cache is None else [f"cache {cache}"]
    lines += [f"hazard h{i}: {', '.join(regions)}" + ("" if k is None else f" wears {k}")
              for i, (regions, k) in enumerate(hazards)]
    return "\n".join(lines) + "\n"


@settings(max_examples=25, deadline=None)
@given(text=_corridors(), binary=st.booleans())
def test_random_corridors_allow_exactly_the_hand_written_successors(
        text: str, binary: bool) -> None:
    model, _ = model_from_text(text)
    encoding = EncodingName.BINARY if binary else EncodingName.ONEHOT
    for state, allowed in _lowered_successors(model, encoding):
        assert allowed == _hand_successors(model, state), (text, state)


def test_the_hand_semantics_tells_wearing_from_failing() -> None:
    """The cross-check can fail: a failing hazard's successors differ from a graded one's,
    so a lowering that ignored ``wears`` would be caught."""
    model, _ = model_from_text(SMALL["corridor, 2 legs of 3, wears 2"])
    failing = replace(model, hazards=tuple(Hazard(h.name, h.regions) for h in model.hazards))
    state = _State("b", "east", (3, 3), "sand")
    assert _hand_successors(model, state) != _hand_successors(failing, state)
    lowered = dict(_lowered_successors(failing, EncodingName.BINARY))
    assert lowered[state] == _hand_successors(failing, state)
    assert lowered[state] != _hand_successors(model, state)


# ---------------------------------------------------------------- realizability
#: The corridor a - b - c (cache a, goals a and c; east uses L1, west L2) with the hazard
#: on b left on for ever by the environment.  Crossing b eastwards costs L1 the hazard's
#: wear and then the robot must still move east from b: possible while L1 keeps a level
#: above 1, i.e. when health - wears >= 2.  A failing hazard is never survivable.
VERDICTS = [
    (4, 2, True),
    (3, 2, False),
    (4, 3, False),
    (5, 3, True),
    (4, None, False),
    (3, 1, True),
]


@pytest.mark.parametrize(("health", "wears", "expected"), VERDICTS,
                         ids=[f"health{h}-wears{w}" for h, w, _ in VERDICTS])
@pytest.mark.parametrize("encoding", ENCODINGS, ids=str)
def test_embedded_solver_verdicts(health: int, wears: int | None, expected: bool,
                                  encoding: EncodingName) -> None:
    spec = gaitc.parse(_corridor(health, wears), name="corridor.gait", encoding=encoding)
    assert gaitc.check(spec).realizable is expected


#: Two gaits each way, so that the leg a hazard takes in b is not needed to go on.  A
#: failing hazard is survivable here, and so is wearing as many levels as a leg has: with
#: no formula about health the two are equally hard (docs/language.md).
TWO_WAYS = """\
legs L1..L3 health 4
gait east uses L1 moves east
gait hop uses L2 moves east
gait west uses L3 moves west
gait back uses L2 moves west
grid 1 x 3 cells a, b, c
cache a
hazard sand: b{wears}
start a
visit a, c infinitely often
"""


@pytest.mark.parametrize("wears", [None, 3, 9, 2])
def test_wearing_everything_is_as_hard_as_failing_without_health_formulas(
        wears: int | None) -> None:
    text = TWO_WAYS.format(wears="" if wears is None else f" wears {wears}")
    for encoding in ENCODINGS:
        spec = gaitc.parse(text, name="two_ways.gait", encoding=encoding)
        assert gaitc.check(spec).realizable


@pytest.mark.slugs
@pytest.mark.parametrize(("health", "wears", "expected"), VERDICTS,
                         ids=[f"health{h}-wears{w}" for h, w, _ in VERDICTS])
@pytest.mark.parametrize("encoding", ENCODINGS, ids=str)
def test_slugs_verdicts(health: int, wears: int | None, expected: bool,
                        encoding: EncodingName, live_slugs: str) -> None:
    spec = gaitc.parse(_corridor(health, wears), name="corridor.gait", encoding=encoding)
    assert gaitc.check(spec, solver="slugs", slugs=live_slugs).realizable is expected
