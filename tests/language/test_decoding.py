"""Tests for decoding spec variable values into robot states and back (both encodings)."""

from __future__ import annotations

import itertools

import pytest
from hypothesis import given
from hypothesis import strategies as st

from gaitc.diagnostics import ControllerError, UsageError
from ltlcompiler.decoding import RobotState, decode, encode
from ltlcompiler.lowering import lower
from ltlcompiler.model import NO_GAIT, Gait, GaitKind, Hazard, Leg, Model, Region, Transition


def model() -> Model:
    return Model(
        name="m", legs=(Leg("L1", 3, 3), Leg("L2", 1, 1), Leg("L3", 2, 2)),
        gaits=(Gait("go", GaitKind.MOVE, ("L1",)), Gait(NO_GAIT, GaitKind.NONE, ())),
        regions=(Region("a"), Region("b"), Region("c")),
        transitions=(Transition("a", "b", ("go",)),), caches=(),
        hazards=(Hazard("hot", ("b",)), Hazard("cold", ("c",))), start="a",
        goals=(), assumptions=(), guarantees=(),
    )


def all_states(m: Model) -> list[RobotState]:
    levels = [range(1, leg.health + 1) for leg in m.legs]
    out = []
    for region, gait, hazard, health in itertools.product(
        [r.name for r in m.regions], [g.name for g in m.gaits],
        [None, *(h.name for h in m.hazards)], itertools.product(*levels),
    ):
        pairs = tuple(zip((leg.name for leg in m.legs), health, strict=True))
        out.append(RobotState(region, gait, pairs, hazard))
    return out


@pytest.mark.parametrize("encoding", ["onehot", "binary"])
def test_round_trip_over_every_state(encoding: str) -> None:
    m = model()
    seen = set()
    for state in all_states(m):
        values = encode(m, encoding, state)
        assert decode(m, encoding, values) == state
        seen.add(tuple(values.items()))
    assert len(seen) == len(all_states(m))  # encode is injective


@pytest.mark.parametrize("encoding", ["onehot", "binary"])
def test_encoded_names_are_exactly_the_spec_variables(encoding: str) -> None:
    m = model()
    spec = lower(m, encoding)
    values = encode(m, encoding, all_states(m)[5])
    assert sorted(values) == sorted(v.name for v in spec.variables())
    for var in spec.variables():
        low = 0 if var.low is None else var.low
        high = 1 if var.high is None else var.high
        assert low <= values[var.name] <= high


def test_onehot_values_by_name() -> None:
    state = RobotState("b", "go", (("L1", 2), ("L2", 1), ("L3", 2)), "cold")
    values = encode(model(), "onehot", state)
    assert {k for k, v in values.items() if v} == {"b", "go", "L1_h2", "L2_h1", "L3_h2", "cold"}


def test_binary_values_by_name() -> None:
    state = RobotState("c", NO_GAIT, (("L1", 1), ("L2", 1), ("L3", 2)), "hot")
    assert encode(model(), "binary", state) == {
        "L1": 1, "L2": 1, "L3": 2, "gait": 1, "hazard": 1, "region": 2}
    none = RobotState("c", NO_GAIT, (("L1", 1), ("L2", 1), ("L3", 2)), None)
    assert encode(model(), "binary", none)["hazard"] == 0


def _onehot(state: RobotState) -> dict[str, int]:
    return dict(encode(model(), "onehot", state))


START = RobotState("a", NO_GAIT, (("L1", 3), ("L2", 1), ("L3", 2)), None)


@pytest.mark.parametrize(("change", "message"), [
    ({"b": 1}, "several regions are true at once: a, b$"),
    ({"a": 0}, r"none of the regions \(a, b, c\) is true"),
    ({"go": 1}, "several gaits are true at once: go, noGait$"),
    ({"hot": 1, "cold": 1}, "several hazards are true at once: hot, cold$"),
    ({"L1_h3": 0}, r"none of the health levels of leg L1 \(L1_h3, L1_h2, L1_h1\) is true"),
    ({"L3_h1": 1}, "several health levels of leg L3 are true at once: L3_h2, L3_h1$"),
])
def test_inconsistent_onehot_valuations(change: dict[str, int], message: str) -> None:
    values = _onehot(START)
    values.update(change)
    with pytest.raises(ControllerError, match=message):
        decode(model(), "onehot", values)


@pytest.mark.parametrize(("change", "message"), [
    ({"region": 3}, "region = 3 names no region"),
    ({"gait": -1}, "gait = -1 names no gait"),
    ({"hazard": 3}, "hazard = 3 names no hazard"),
    ({"L1": 0}, "L1 = 0 names no health level of L1"),
    ({"L2": 2}, "L2 = 2 names no health level of L2"),
])
def test_inconsistent_binary_valuations(change: dict[str, int], message: str) -> None:
    values = dict(encode(model(), "binary", START))
    values.update(change)
    with pytest.raises(ControllerError, match=message):
        decode(model(), "binary", values)


def test_missing_variable_and_bad_inputs() -> None:
    values = _onehot(START)
    del values["c"]
    with pytest.raises(ControllerError, match="no value for variable 'c'"):
        decode(model(), "onehot", values)
    with pytest.raises(UsageError, match="unknown encoding 'gray'"):
        decode(model(), "gray", values)
    with pytest.raises(ControllerError, match="unknown region 'z'"):
        encode(model(), "binary", RobotState("z", NO_GAIT, START.health, None))
    with pytest.raises(ControllerError, match=r"leg L1 needs a health level in 1\.\.3"):
        encode(model(), "onehot", RobotState("a", NO_GAIT, (("L1", 4),), None))


@given(st.dictionaries(st.sampled_from(sorted(_onehot(START))), st.integers(0, 1)))
def test_decode_never_crashes_outside_the_error_family(change: dict[str, int]) -> None:
    values = _onehot(START)
    values.update(change)
    try:
        state = decode(model(), "onehot", values)
    except ControllerError:
        return
    assert encode(model(), "onehot", state) == values
