"""State decoding: spec variable values <-> robot states (region, gait, health, hazard).

The inverse of the naming in :mod:`ltlcompiler.encoding`; the simulator and renderer
read controller states through :func:`decode` and build them with :func:`encode`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from gaitc.diagnostics import ControllerError
from ltlcompiler.encoding import (
    GAIT_VAR,
    HAZARD_VAR,
    REGION_VAR,
    EncodingName,
    health_prop,
    make_encoding,
)
from ltlcompiler.model import Model


@dataclass(frozen=True)
class RobotState:
    """One robot state: where it is, which gait brought it there, leg health, active hazard."""

    region: str
    gait: str
    health: tuple[tuple[str, int], ...]  # (leg, level) in leg declaration order
    hazard: str | None


def _get(values: Mapping[str, int], name: str) -> int:
    if name not in values:
        raise ControllerError(f"the state has no value for variable '{name}': the controller "
                              "does not belong to this specification")
    return int(values[name])


def _one_of(values: Mapping[str, int], names: list[str], what: str, allow_none: bool) -> str | None:
    true = [n for n in names if _get(values, n)]
    if len(true) > 1:
        raise ControllerError(
            f"inconsistent state: several {what} are true at once: {', '.join(true)}")
    if not true:
        if allow_none:
            return None
        raise ControllerError(
            f"inconsistent state: none of the {what} ({', '.join(names)}) is true")
    return true[0]


def _exactly_one(values: Mapping[str, int], names: list[str], what: str) -> str:
    found = _one_of(values, names, what, False)
    return found if found is not None else names[0]  # _one_of raised when none is true


def _indexed(values: Mapping[str, int], var: str, names: list[str], what: str, low: int) -> int:
    value = _get(values, var)
    if not low <= value < low + len(names):
        raise ControllerError(f"inconsistent state: {var} = {value} names no {what} "
                              f"(expected {low}..{low + len(names) - 1})")
    return value - low


def decode(model: Model, encoding: EncodingName, values: Mapping[str, int]) -> RobotState:
    """The robot state in ``values`` (spec variable name -> 0/1 or integer value).

    Raises :class:`ControllerError` for a missing variable or an inconsistent valuation
    (two regions at once, no gait, a health level out of range, ...).
    """
    make_encoding(model, encoding)  # rejects an unknown encoding name
    regions = [r.name for r in model.regions]
    gaits = [g.name for g in model.gaits]
    hazards = [h.name for h in model.hazards]
    health: list[tuple[str, int]] = []
    if encoding == EncodingName.ONEHOT:
        for leg in model.legs:
            levels = [health_prop(leg.name, j) for j in range(leg.health, 0, -1)]
            level = _exactly_one(values, levels, f"health levels of leg {leg.name}")
            health.append((leg.name, leg.health - levels.index(level)))
        return RobotState(_exactly_one(values, regions, "regions"),
                          _exactly_one(values, gaits, "gaits"), tuple(health),
                          _one_of(values, hazards, "hazards", True))
    region = regions[_indexed(values, REGION_VAR, regions, "region", 0)]
    gait = gaits[_indexed(values, GAIT_VAR, gaits, "gait", 0)]
    hazard = None
    if hazards:
        k = _indexed(values, HAZARD_VAR, ["none", *hazards], "hazard", 0)
        hazard = hazards[k - 1] if k else None
    for leg in model.legs:
        index = _indexed(values, leg.name, [""] * leg.health, f"health level of {leg.name}", 1)
        health.append((leg.name, index + 1))
    return RobotState(region, gait, tuple(health), hazard)


def encode(model: Model, encoding: EncodingName, state: RobotState) -> dict[str, int]:
    """The spec variable values of ``state`` (the inverse of :func:`decode`), sorted by name."""
    make_encoding(model, encoding)
    regions = [r.name for r in model.regions]
    gaits = [g.name for g in model.gaits]
    hazards = [h.name for h in model.hazards]
    levels = dict(state.health)
    for name, known, what in ((state.region, regions, "region"), (state.gait, gaits, "gait")):
        if name not in known:
            raise ControllerError(f"unknown {what} '{name}' in robot state")
    if state.hazard is not None and state.hazard not in hazards:
        raise ControllerError(f"unknown hazard '{state.hazard}' in robot state")
    for leg in model.legs:
        if not 1 <= levels.get(leg.name, 0) <= leg.health:
            raise ControllerError(f"leg {leg.name} needs a health level in 1..{leg.health} "
                                  f"in the robot state, got {levels.get(leg.name)}")
    out: dict[str, int] = {}
    if encoding == EncodingName.ONEHOT:
        out.update({r: int(r == state.region) for r in regions})
        out.update({g: int(g == state.gait) for g in gaits})
        out.update({h: int(h == state.hazard) for h in hazards})
        for leg in model.legs:
            for j in range(1, leg.health + 1):
                out[health_prop(leg.name, j)] = int(levels[leg.name] == j)
    else:
        out[REGION_VAR] = regions.index(state.region)
        out[GAIT_VAR] = gaits.index(state.gait)
        if hazards:
            out[HAZARD_VAR] = 0 if state.hazard is None else hazards.index(state.hazard) + 1
        for leg in model.legs:
            out[leg.name] = levels[leg.name]
    return dict(sorted(out.items()))
