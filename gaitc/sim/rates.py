"""Rates: how likely the environment's moves are, in the robot's words, and the one law that
turns them into the chances of each next input (leg levels and active hazard).

Where the GR(1) spec leaves the environment free (thesis eqs. 3.5, 3.8, 3.9: a leg in use
may lose a level, a hazard set may switch, a graded hazard wears by up to k), a rates file
(YAML, ``gaitc chances --rates``) gives a probability; :class:`StepLaw` is what both the
Markov model of :mod:`gaitc.analysis.markov` and the stochastic environment of
:mod:`gaitc.sim.environments` read, so Storm's numbers and the Monte Carlo runs sample the
same distribution.  A wear chance left out is the worst case (the level is always lost),
which is exact for the specs whose only health clauses are eqs. 3.4-3.6 and 3.9: a leg's
lower level only takes gaits away from the robot.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import yaml

from gaitc.diagnostics import RatesError, Span
from gaitc.diagnostics.files import decode_text, read_input
from gaitc.diagnostics.yamltext import compose, node_span
from gaitc.ir.roles import Fails, WearsUpTo
from gaitc.sim.domain import State
from ltlcompiler.model import GaitKind, Model

TOP_KEYS = ("wear", "fail", "hazards")
WEAR_KEYS = ("every", "legs", "gaits")
HAZARD_KEYS = ("on", "off", "wears")


@dataclass(frozen=True)
class HazardRates:
    """A hazard set's chances per step: switching on while no set is active, switching off
    while it is, and for a graded hazard (``wears k``) the chances that a leg in use there
    loses exactly 1, 2, ..., k levels (the rest: none)."""

    on: float
    off: float
    wears: tuple[float, ...] | None = None


@dataclass(frozen=True)
class Rates:
    """The chances of the environment's moves; ``None`` where the file gives none."""

    every: float | None = None  # a leg in use loses a level on a move (eq. 3.5)
    legs: Mapping[str, float] = field(default_factory=dict)  # per leg, over ``every``
    gaits: Mapping[str, float] = field(default_factory=dict)  # per gait, over ``legs``
    fail: float = 0.0  # a leg in use fails outright on a move: beyond the spec's eq. 3.5
    hazards: Mapping[str, HazardRates] = field(default_factory=dict)
    file: str | None = None

    def with_wear(self, chance: float | None) -> Rates:
        """These rates with ``every`` leg in use wearing at ``chance`` (``--wear P``)."""
        return self if chance is None else replace(self, every=chance)

    def wear(self, gait: str, leg: str) -> float | None:
        """The chance that ``leg`` loses a level on a move by ``gait`` (None: unrated)."""
        if gait in self.gaits:
            return self.gaits[gait]
        return self.legs.get(leg, self.every)

    def words(self, model: Model) -> list[str]:
        """Every rate in the robot's words, the unrated moves named as the worst case."""
        out = []
        if self.every is not None:
            out.append(f"a leg in use loses a level on a move with chance {self.every:g}")
        out += [f"leg {leg} loses a level on a move with chance {p:g}"
                for leg, p in self.legs.items()]
        out += [f"a leg of gait {gait} loses a level on a move with chance {p:g}"
                for gait, p in self.gaits.items()]
        if self.every is None and any(leg.name not in self.legs for leg in model.legs
                                      if leg.health > 1):
            out.append("legs without a wear chance lose a level on every move (the worst case)")
        if self.fail:
            out.append(f"a leg in use fails outright on a move with chance {self.fail:g} "
                       "(more than eq. 3.5 allows: it breaks the spec's assumptions)")
        for name, h in self.hazards.items():
            out.append(f"hazard {name} switches on with chance {h.on:g} a step while no "
                       f"hazard is active, and off with chance {h.off:g} a step")
            if h.wears is not None:
                chances = ", ".join(f"{k} level{'s' if k > 1 else ''}: {p:g}"
                                    for k, p in enumerate(h.wears, 1))
                out.append(f"in an active {name} region a leg in use loses {chances}")
        for hazard in model.hazards:
            rated = self.hazards.get(hazard.name)
            if isinstance(hazard.harm, WearsUpTo) and (rated is None or rated.wears is None):
                out.append(f"in an active {hazard.name} region a leg in use loses "
                           f"{hazard.harm.levels} levels (the worst case: no chances given)")
        out.append("every hazard set starts off")
        return out

    def to_json(self) -> dict[str, Any]:
        return {"every": self.every, "legs": dict(self.legs), "gaits": dict(self.gaits),
                "fail": self.fail, "file": self.file,
                "hazards": {name: {"on": h.on, "off": h.off,
                                   "wears": None if h.wears is None else list(h.wears)}
                            for name, h in self.hazards.items()}}


# ---------------------------------------------------------------- reading
class _Reader:
    def __init__(self, file: str, model: Model) -> None:
        self.file = file
        self.model = model

    def fail(self, message: str, node: yaml.Node | None, hint: str | None = None) -> RatesError:
        span = node_span(self.file, node) if node is not None else Span(self.file, 1, 1)
        return RatesError(message, span, hint)

    def mapping(self, node: yaml.Node, what: str, keys: tuple[str, ...] | None
                ) -> dict[str, tuple[yaml.Node, yaml.Node]]:
        if not isinstance(node, yaml.MappingNode):
            expected = f" with keys {', '.join(keys)}" if keys else ""
            raise self.fail(f"{what} must be a mapping{expected}", node)
        out: dict[str, tuple[yaml.Node, yaml.Node]] = {}
        for key, value in node.value:
            name = str(key.value) if isinstance(key, yaml.ScalarNode) else "(a list or mapping)"
            if keys is not None and name not in keys:
                raise self.fail(f"unknown key '{name}' in {what}; expected one of "
                                f"{', '.join(keys)}", key)
            if name in out:
                raise self.fail(f"key '{name}' appears twice in {what}", key)
            out[name] = (key, value)
        return out

    def chance(self, node: yaml.Node, what: str) -> float:
        value: float | None = None
        if isinstance(node, yaml.ScalarNode) and node.style is None:
            text = node.value.strip()
            try:
                value = float(text[:-1]) / 100 if text.endswith("%") else float(text)
            except ValueError:
                value = None
        if value is None or not math.isfinite(value):
            raise self.fail(f"{what} must be a probability (a number such as 0.02 or 2%)", node)
        if not 0.0 <= value <= 1.0:
            raise self.fail(f"{what} is {value:g}, outside [0, 1]: a probability", node)
        return value

    def named(self, node: yaml.Node, what: str, known: tuple[str, ...]) -> dict[str, float]:
        out = {}
        for name, (key, value) in self.mapping(node, what, None).items():
            if name not in known:
                raise self.fail(f"unknown {what[:-1] if what.endswith('s') else what} "
                                f"'{name}'; the spec's are {', '.join(known) or '(none)'}",
                                key)
            out[name] = self.chance(value, f"the wear chance of {name}")
        return out

    def hazard(self, name: str, key: yaml.Node, node: yaml.Node) -> HazardRates:
        hazards = {h.name: h for h in self.model.hazards}
        if name not in hazards:
            raise self.fail(f"unknown hazard set '{name}'; the spec's are "
                            f"{', '.join(hazards) or '(none)'}", key)
        entries = self.mapping(node, f"hazard {name}", HAZARD_KEYS)
        for needed in ("on", "off"):
            if needed not in entries:
                raise self.fail(f"hazard {name} needs '{needed}': its chance a step of "
                                f"switching {needed}", node)
        on = self.chance(entries["on"][1], f"the chance that {name} switches on")
        off = self.chance(entries["off"][1], f"the chance that {name} switches off")
        wears = None
        if "wears" in entries:
            key_node, seq = entries["wears"]
            harm = hazards[name].harm
            if not isinstance(harm, WearsUpTo):
                raise self.fail(f"hazard {name} fails the legs (eq. 3.9): only a graded "
                                "hazard ('wears k' in the spec) takes wear chances", key_node)
            if not isinstance(seq, yaml.SequenceNode) or len(seq.value) != harm.levels:
                raise self.fail(f"'wears' of {name} must list {harm.levels} chance(s): of "
                                f"losing 1..{harm.levels} levels", seq)
            wears = tuple(self.chance(item, f"the chance of losing {k} level(s) in {name}")
                          for k, item in enumerate(seq.value, 1))
            if sum(wears) > 1.0 + 1e-12:
                raise self.fail(f"the wear chances of {name} add up to {sum(wears):g}, more "
                                "than 1", seq)
        return HazardRates(on, off, wears)

    def read(self, root: yaml.Node | None) -> Rates:
        if root is None:
            return Rates(file=self.file)
        top = self.mapping(root, "the rates file", TOP_KEYS)
        every, legs, gaits = None, {}, {}
        if "wear" in top:
            node = top["wear"][1]
            if isinstance(node, yaml.ScalarNode):
                every = self.chance(node, "the wear chance")
            else:
                wear = self.mapping(node, "'wear'", WEAR_KEYS)
                if "every" in wear:
                    every = self.chance(wear["every"][1], "the wear chance of every leg")
                if "legs" in wear:
                    legs = self.named(wear["legs"][1], "legs",
                                      tuple(leg.name for leg in self.model.legs))
                if "gaits" in wear:
                    gaits = self.named(wear["gaits"][1], "gaits",
                                       tuple(g.name for g in self.model.gaits
                                             if g.kind is GaitKind.MOVE))
        fail = self.chance(top["fail"][1], "the chance of a sudden failure") \
            if "fail" in top else 0.0
        hazards = {}
        if "hazards" in top:
            node = top["hazards"][1]
            for name, (key, value) in self.mapping(node, "'hazards'", None).items():
                hazards[name] = self.hazard(name, key, value)
            total = sum(h.on for h in hazards.values())
            if total > 1.0 + 1e-12:
                raise self.fail(f"the hazards' chances of switching on add up to {total:g}: "
                                "at most one set is active at a time, so they may add up to "
                                "1 at most", node)
        return Rates(every, legs, gaits, fail, hazards, self.file)


def parse_rates(text: str, model: Model, file: str = "<rates>") -> Rates:
    """Read the rates of ``text`` (YAML) against ``model``'s legs, gaits and hazards."""
    return _Reader(file, model).read(compose(text, file, RatesError, "the rates file"))


def load_rates(path: str | Path, model: Model) -> Rates:
    """Read and check a rates file."""
    file = str(path)
    return parse_rates(decode_text(read_input(path, "rates file"), file, RatesError), model,
                       file)


def unrated_hazards(model: Model, rates: Rates) -> tuple[str, ...]:
    """The spec's hazard sets the rates give no switching chances for."""
    return tuple(h.name for h in model.hazards if h.name not in rates.hazards)


# ---------------------------------------------------------------- the law of a step
@dataclass(frozen=True)
class Outcome:
    """One next input: the legs' levels and the active hazard, its chance, and whether it
    breaks the spec's assumptions (a sudden failure beyond eq. 3.5)."""

    chance: float
    levels: tuple[int, ...]  # in the order of ``legs``
    hazard: str | None
    breaks: bool = False
    legs: tuple[str, ...] = ()

    @property
    def health(self) -> tuple[tuple[str, int], ...]:
        """(leg, level) in leg order, as :class:`~gaitc.sim.domain.State` holds them."""
        return tuple(zip(self.legs, self.levels, strict=True))


class StepLaw:
    """The environment's next inputs from a state, with their chances under ``rates``.

    :meth:`outcomes` lists every input the spec's physics allow (eqs. 3.5, 3.6, 3.9; chance
    0 for those the rates rule out) and the sudden failures of ``rates.fail`` beyond them.
    Every hazard set must have rates (an adversarial hazard would need a stochastic game).
    """

    def __init__(self, model: Model, rates: Rates) -> None:
        missing = unrated_hazards(model, rates)
        if missing:
            raise RatesError(
                f"hazard set{'s' if len(missing) > 1 else ''} {', '.join(missing)} "
                "ha{} no switching chances".format("ve" if len(missing) > 1 else "s"),
                Span(rates.file or "<rates>", 1, 1),
                "give them in the rates file, e.g. 'hazards: {" + missing[0] +
                ": {on: 0.05, off: 0.2}}': a hazard that switches at its worst makes the "
                "question a stochastic game, which Storm's MDP checking does not answer")
        self.model = model
        self.rates = rates
        self.full = {leg.name: leg.health for leg in model.legs}
        self.caches = frozenset(model.caches)
        self.moving = {g.name: tuple(leg for leg in g.legs if self.full[leg] > 1)
                       if g.kind is GaitKind.MOVE else () for g in model.gaits}
        self.hazards = {h.name: h for h in model.hazards}
        self._memo: dict[State, tuple[Outcome, ...]] = {}

    def hazard_chances(self, hazard: str | None) -> list[tuple[str | None, float]]:
        """The next active hazard set from ``hazard`` (every set listed, chance 0 too)."""
        names: list[str | None] = [None, *self.hazards]
        rates = self.rates.hazards
        if hazard is None:
            on = {n: rates[n].on for n in self.hazards}
            return [(n, on[n] if n is not None else 1.0 - sum(on.values())) for n in names]
        off = rates[hazard].off
        return [(n, off if n is None else (1.0 - off if n == hazard else 0.0)) for n in names]

    def _leg(self, state: State, leg: str, level: int) -> list[tuple[int, float, bool]]:
        """A leg in use: (next level, chance, beyond the spec) for every level allowed."""
        hazard = self.hazards.get(state.hazard) if state.hazard is not None else None
        if hazard is not None and state.region in hazard.regions:
            match hazard.harm:
                case Fails():
                    return [(1, 1.0, False)]
                case WearsUpTo(levels=k):
                    wears = self.rates.hazards[hazard.name].wears
                    lost = [0.0] * (k + 1)
                    if wears is None:
                        lost[k] = 1.0
                    else:
                        lost[0] = max(0.0, 1.0 - sum(wears))
                        lost[1:] = wears
                    chances: dict[int, float] = {}
                    for j, p in enumerate(lost):
                        nxt = max(1, level - j)
                        chances[nxt] = chances.get(nxt, 0.0) + p
                    allowed = [(nxt, p, False) for nxt, p in sorted(chances.items())]
                    return self._sudden(allowed)
        rated = self.rates.wear(state.gait, leg)
        wear = 1.0 if rated is None else rated
        return self._sudden([(level - 1, wear, False), (level, 1.0 - wear, False)])

    def _sudden(self, allowed: list[tuple[int, float, bool]]) -> list[tuple[int, float, bool]]:
        f = self.rates.fail
        if not f:
            return allowed
        out = [(lv, p * (1.0 - f), b) for lv, p, b in allowed]
        if any(lv == 1 for lv, _, _ in allowed):
            return [(lv, p + (f if lv == 1 else 0.0), b) for lv, p, b in out]
        return [*out, (1, f, True)]

    def outcomes(self, state: State) -> tuple[Outcome, ...]:
        """The next inputs from ``state`` (region, gait, levels and hazard of this step)."""
        found = self._memo.get(state)
        if found is not None:
            return found
        hazards = self.hazard_chances(state.hazard)
        if state.region in self.caches:
            legs = [[(self.full[leg], 1.0, False)] if self.full[leg] > 1 else
                    [(level, 1.0, False)] for leg, level in state.health]
        else:
            used = set(self.moving.get(state.gait, ()))
            legs = [self._leg(state, leg, level) if leg in used and level > 1 else
                    [(level, 1.0, False)] for leg, level in state.health]
        names = tuple(leg for leg, _ in state.health)
        base = [options[0][0] for options in legs]
        varying = [i for i, options in enumerate(legs) if len(options) > 1 or options[0][2]]
        fixed = math.prod(legs[i][0][1] for i in range(len(legs)) if i not in varying)
        out: list[Outcome] = []
        for combo in itertools.product(*(legs[i] for i in varying)):
            chance, breaks, levels = fixed, False, list(base)
            for i, (level, p, beyond) in zip(varying, combo, strict=True):
                chance *= p
                breaks = breaks or beyond
                levels[i] = level
            frozen = tuple(levels)
            out.extend(Outcome(chance * q, frozen, hazard, breaks, names)
                       for hazard, q in hazards)
        found = tuple(out)
        self._memo[state] = found
        return found
