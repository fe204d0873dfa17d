"""Brute-force answers to the resilience questions, for tests and the benchmark.

Nothing here uses :mod:`gaitc.analysis`: every variant is a new ``.gait`` text (leg lines
rewritten, cache lines replaced, hazard lines dropped and the dropped hazards read as
``false`` in formulas), decided with :func:`gaitc.parse` and :func:`gaitc.check`, and the
answers are read off the full table of verdicts with no monotonicity assumed. Legs breaking
during the run get their own GR(1) construction: one 0/1 integer input per breakable leg
that never goes back to 0, "at most k" as a sum of those integers, and the gaits using a
broken leg off from the step it breaks on.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from functools import reduce

import gaitc
from gaitc.ir.formula import Add, Compare, Expr, Implies, IntConst, IntVar, Not, Term
from gaitc.ir.spec import Clause, GR1Spec, Variable
from ltlcompiler.encoding import make_encoding
from ltlcompiler.model import Model

Sets = tuple[tuple[str, ...], ...]
_LEG_LINE = re.compile(r"^\s*legs?\s")
_CACHE_LINE = re.compile(r"^\s*caches?\s")
_START_LINE = re.compile(r"^(\s*start\s+\w+)")
_FORMULA_LINE = re.compile(r"^\s*(assume|guarantee)\s")


# ---------------------------------------------------------------- variant texts
def model_of(text: str) -> Model:
    model = gaitc.parse(text, name="original.gait").model
    assert model is not None
    return model


def with_health(text: str, levels: Mapping[str, int]) -> str:
    """``text`` with the legs of ``levels`` given that many health levels (1 = failed).

    Every leg declaration becomes one ``leg`` line; a lower initial level in ``start ...
    with`` is kept, capped at the new number of levels (the full level needs no mention).
    """
    model = model_of(text)
    health = {leg.name: levels.get(leg.name, leg.health) for leg in model.legs}
    starts = {}
    for leg in model.legs:
        if leg.initial != leg.health:
            level = min(leg.initial, health[leg.name])
            if level != health[leg.name]:
                starts[leg.name] = level
    out: list[str] = []
    placed = False
    for line in text.splitlines():
        if _LEG_LINE.match(line):
            if not placed:
                out.extend(f"leg {name} health {h}" for name, h in health.items())
                placed = True
            continue
        start = _START_LINE.match(line)
        if start:
            line = start.group(1) + (" with " + ", ".join(
                f"{name} = {level}" for name, level in starts.items()) if starts else "")
        out.append(line)
    return "\n".join(out) + "\n"


def with_failed(text: str, legs: Iterable[str]) -> str:
    return with_health(text, dict.fromkeys(legs, 1))


def with_caches(text: str, caches: Iterable[str]) -> str:
    """``text`` with its cache statements replaced by one listing ``caches`` (or none)."""
    lines = [line for line in text.splitlines() if not _CACHE_LINE.match(line)]
    names = list(caches)
    if names:
        lines.append("cache " + ", ".join(names))
    return "\n".join(lines) + "\n"


def with_hazards(text: str, keep: Iterable[str]) -> str:
    """``text`` with only the hazard sets ``keep``; formulas read the others as false."""
    kept = set(keep)
    dropped = [h.name for h in model_of(text).hazards if h.name not in kept]
    out = []
    for line in text.splitlines():
        if any(re.match(rf"^\s*hazard\s+{name}\s*:", line) for name in dropped):
            continue
        if _FORMULA_LINE.match(line):
            for name in dropped:
                line = re.sub(rf"\b{name}\b", "false", line)
        out.append(line)
    return "\n".join(out) + "\n"


def realizable(text: str, encoding: str) -> bool:
    """``gaitc check`` of a ``.gait`` text."""
    return gaitc.check(gaitc.parse(text, name="variant.gait", encoding=encoding)).realizable


# ---------------------------------------------------------------- order of the answers
def ordered_sets(sets: Iterable[Iterable[str]], order: Sequence[str]) -> Sets:
    """Sets as tuples in declaration order, smallest first, then by declaration order."""
    rank = {name: i for i, name in enumerate(order)}
    items = {tuple(sorted(s, key=rank.__getitem__)) for s in sets}
    return tuple(sorted(items, key=lambda t: (len(t), [rank[x] for x in t])))


def subsets(elements: Sequence[str]) -> list[frozenset[str]]:
    return [frozenset(c) for n in range(len(elements) + 1)
            for c in itertools.combinations(elements, n)]


# ---------------------------------------------------------------- legs failed from the start
@dataclass(frozen=True)
class FailureTable:
    """The verdict of every set of candidate legs failed from the start."""

    candidates: tuple[str, ...]
    survives: Mapping[frozenset[str], bool]

    def minimal_fatal(self) -> Sets:
        fatal = [s for s, ok in self.survives.items() if not ok]
        return ordered_sets([s for s in fatal if not any(t < s for t in fatal)],
                            self.candidates)

    def maximal_survivable(self) -> Sets:
        alive = [s for s, ok in self.survives.items() if ok]
        return ordered_sets([s for s in alive if not any(s < t for t in alive)],
                            self.candidates)

    def single_points(self) -> tuple[str, ...]:
        return tuple(leg for leg in self.candidates if not self.survives[frozenset({leg})])

    def is_monotone(self) -> bool:
        return all(self.survives[s] or not self.survives[t]
                   for s in self.survives for t in self.survives if s <= t)


def candidates(text: str) -> tuple[str, ...]:
    """The legs that can still fail: those with more than one health level."""
    return tuple(leg.name for leg in model_of(text).legs if leg.health > 1)


def failure_table(text: str, encoding: str) -> FailureTable:
    legs = candidates(text)
    return FailureTable(legs, {s: realizable(with_failed(text, s), encoding)
                               for s in subsets(legs)})


# ---------------------------------------------------------------- health
def health_front(text: str, encoding: str, bound: int | None
                 ) -> tuple[int | None, tuple[tuple[tuple[str, int], ...], ...]]:
    """(least uniform health, the minimal good vectors over ``1..bound`` per leg, or with no
    bound over each leg's own declared levels)."""
    legs = model_of(text).legs
    names = [leg.name for leg in legs]
    tops = [bound or leg.health for leg in legs]
    good = {v: realizable(with_health(text, dict(zip(names, v, strict=True))), encoding)
            for v in itertools.product(*(range(1, t + 1) for t in tops))}
    top = bound or max(tops)
    uniform = next((h for h in range(1, top + 1) if realizable(
        with_health(text, dict.fromkeys(names, h)), encoding)), None)
    goods = [v for v, ok in good.items() if ok]
    minimal = sorted(v for v in goods if not any(
        w != v and all(a <= b for a, b in zip(w, v, strict=True)) for w in goods))
    return uniform, tuple(tuple(zip(names, v, strict=True)) for v in minimal)


# ---------------------------------------------------------------- caches and hazards
def essential_caches(text: str, encoding: str) -> tuple[str, ...]:
    caches = model_of(text).caches
    return tuple(c for c in caches
                 if not realizable(with_caches(text, [x for x in caches if x != c]), encoding))


def cache_placements(text: str, encoding: str, size: int) -> Sets:
    """The sets of ``size`` regions outside every hazard whose caches (replacing the
    spec's own) make the task realizable, in region order."""
    model = model_of(text)
    hot = {r for h in model.hazards for r in h.regions}
    regions = [r.name for r in model.regions if r.name not in hot]
    return tuple(c for c in itertools.combinations(regions, size)
                 if realizable(with_caches(text, c), encoding))


def hazards_alone(text: str, encoding: str) -> tuple[str, ...]:
    return tuple(h.name for h in model_of(text).hazards
                 if realizable(with_hazards(text, [h.name]), encoding))


# ---------------------------------------------------------------- legs breaking during the run
def flag(leg: str) -> str:
    return f"test_broken_{leg}"


def breaking_spec(text: str, encoding: str, breakable: Sequence[str], k: int | None
                  ) -> GR1Spec:
    """The spec of ``text`` in which the environment may break legs of ``breakable`` for
    good at any step, at most ``k`` of them (no limit for None)."""
    spec = gaitc.parse(text, name="breaking.gait", encoding=encoding)
    assert spec.model is not None
    enc = make_encoding(spec.model, encoding)
    now = {leg: IntVar(flag(leg)) for leg in breakable}
    nxt = {leg: IntVar(flag(leg), True) for leg in breakable}
    env_init = [Clause(Compare("=", now[leg], IntConst(0))) for leg in breakable]
    env_trans = [Clause(Compare(">=", nxt[leg], now[leg])) for leg in breakable]
    if k is not None and breakable:
        total: Term = reduce(Add, [nxt[leg] for leg in breakable])
        env_trans.append(Clause(Compare("<=", total, IntConst(k))))
    sys_trans = []
    for leg in breakable:
        for gait in spec.model.gaits:
            if leg in gait.legs:
                off: Expr = Not(enc.gait(gait.name, True))
                sys_trans.append(Clause(Implies(Compare("=", nxt[leg], IntConst(1)), off)))
    gr1 = spec.gr1
    return replace(gr1, inputs=gr1.inputs + tuple(Variable(flag(leg), 0, 1)
                                                   for leg in breakable),
                   env_init=gr1.env_init + tuple(env_init),
                   env_trans=gr1.env_trans + tuple(env_trans),
                   sys_trans=gr1.sys_trans + tuple(sys_trans))


def any_time(text: str, encoding: str) -> tuple[list[bool], int, Sets]:
    """(the verdict for each k = 0..n, the largest k with every smaller k survived, and
    the sets of k + 1 legs whose breaking alone defeats the robot)."""
    legs = candidates(text)
    verdicts = [gaitc.check(breaking_spec(text, encoding, legs, k)).realizable
                for k in range(len(legs) + 1)]
    k = 0
    while k < len(legs) and verdicts[k + 1]:
        k += 1
    if k == len(legs):
        return verdicts, k, ()
    defeating = [c for c in itertools.combinations(legs, k + 1)
                 if not gaitc.check(breaking_spec(text, encoding, c, None)).realizable]
    return verdicts, k, ordered_sets(defeating, legs)


# ---------------------------------------------------------------- everything at once
@dataclass(frozen=True)
class Answers:
    """Every brute-force answer, in the order and form of the report's fields."""

    table: FailureTable
    min_uniform_health: int | None
    health_front: tuple[tuple[tuple[str, int], ...], ...]
    essential_caches: tuple[str, ...]
    cache_placements: Sets
    hazards_survived_alone: tuple[str, ...]
    any_time_verdicts: list[bool]
    any_time_k: int
    defeating_sets: Sets


def answers(text: str, encoding: str, bound: int, place: int) -> Answers:
    uniform, front = health_front(text, encoding, bound)
    verdicts, k, defeating = any_time(text, encoding)
    return Answers(failure_table(text, encoding), uniform, front,
                   essential_caches(text, encoding), cache_placements(text, encoding, place),
                   hazards_alone(text, encoding), verdicts, k, defeating)
