"""Resilience analysis: which failures a task survives, and what the robot needs.

1. Legs failed for good (what ``health 1`` declares; not ``start ... with L = 1``, which a
   cache mends): minimal fatal and maximal survivable sets over all subsets of legs,
   single points of failure, and the legs each compass direction depends on.
2. Legs breaking during the run: the largest k such that the robot survives any k legs
   breaking at moments of the environment's choosing (SLUGS's k-resilience, made concrete
   for legs), and the sets of k+1 legs that defeat it.
3. Health: the least uniform number of levels, and the Pareto front of per-leg levels,
   by default within each leg's own declared levels.
4. Caches and hazards: essential caches, cache placements, hazard sets survived alone, and
   for each graded hazard (``wears k``) the most wear survived and whether failing is.
5. Surprises: the most broken safety assumptions survived, up to a bound, and the one that
   limits it (:mod:`gaitc.analysis.tolerance`, ``synth --tolerate``).

The failure sets and the health front come either from one parametric game
(:mod:`gaitc.analysis.parametric`) or from lattice searches over variants
(:mod:`gaitc.analysis.lattice`), which may run in parallel (:mod:`gaitc.analysis.pool`).
"""

from __future__ import annotations

import itertools
import math
import time
from dataclasses import dataclass, field, replace
from typing import Any, Final

from gaitc.analysis.lattice import fatal_sets, minimal_vectors
from gaitc.analysis.legs_picture import legs_picture
from gaitc.analysis.parametric import failure_sets, winning_caps, winning_parameters
from gaitc.analysis.pool import Pool
from gaitc.analysis.tolerance import DEFAULT_BOUND, ToleranceReport, tolerance
from gaitc.analysis.variants import (
    anytime_spec,
    at_most,
    breakable_name,
    broken_name,
    family_legs,
    gait_families,
    with_caches,
    with_failed,
    with_hazards,
    with_health,
)
from gaitc.core.spec import Spec
from gaitc.diagnostics import GaitcError
from gaitc.ir.formula import Var
from gaitc.ir.roles import Fails, WearsUpTo, graded_levels
from gaitc.ir.spec import Semantics
from gaitc.solver.game import Game
from gaitc.solver.symbolic import Options, SymbolicSpec
from gaitc.solver.synthesis import state_bits
from ltlcompiler.encoding import EncodingName
from ltlcompiler.lowering import lower
from ltlcompiler.model import Model

METHODS: Final = ("parametric", "lattice")
MAX_PLACEMENTS = 5_000
DIRECT_DEFEATS = 64  # up to this many (k+1)-sets are checked one by one
#: State bits up to which the tolerance of surprises is solved (robot A has 59 in the
#: one-hot encoding, 27 in the binary one: 11 s with its groups, 13 games).
MAX_TOLERANCE_BITS: Final = 64
#: Health vectors (levels ** legs) up to which the health front is searched. The parametric
#: game over 3^12 vectors (radial12) takes about a minute; over 3^24 (centipede24) it did
#: not finish in ten, and the lattice search would need a solver call per front vector.
MAX_HEALTH_VECTORS = 3 ** 12


@dataclass(frozen=True)
class Resilience:
    """The answers; every set is a tuple of names in declaration order."""

    file: str
    legs: tuple[tuple[str, int], ...]  # (leg, health levels)
    realizable: bool
    method: str
    minimal_fatal_sets: tuple[tuple[str, ...], ...] = ()
    maximal_survivable_sets: tuple[tuple[str, ...], ...] = ()
    single_points_of_failure: tuple[str, ...] = ()
    already_failed: tuple[str, ...] = ()
    # per direction: its usable gaits (no already failed leg), their legs, the legs all use
    directions: tuple[tuple[str, tuple[str, ...], tuple[str, ...], tuple[str, ...]], ...] = ()
    any_time_k: int | None = None
    defeating_sets: tuple[tuple[str, ...], ...] = ()
    health_bound: int | None = None  # None: each leg within its own declared levels
    health_levels: tuple[tuple[str, int], ...] = ()  # the levels searched, leg by leg
    min_uniform_health: int | None = None
    health_front: tuple[tuple[tuple[str, int], ...], ...] | None = ()  # None: not searched
    essential_caches: tuple[str, ...] = ()
    cache_placements: tuple[tuple[str, ...], ...] = ()
    placed: int | None = None
    hazards_survived_alone: tuple[str, ...] = ()
    hazards_fatal_alone: tuple[str, ...] = ()
    # per graded hazard (``wears k``): (name, declared k, most wear survived, whether the task
    # survives the hazard failing the legs instead)
    hazard_wear: tuple[tuple[str, int, int, bool], ...] = ()
    # the surprises survived (broken safety assumptions); None: not solved
    tolerance: ToleranceReport | None = None
    solver_calls: int = 0
    seconds: float = 0.0
    notes: tuple[str, ...] = ()
    model: Model | None = field(default=None, repr=False, compare=False)

    def to_json(self) -> dict[str, Any]:
        return {
            "file": self.file, "realizable": self.realizable, "method": self.method,
            "legs": dict(self.legs),
            "minimal_fatal_sets": [list(s) for s in self.minimal_fatal_sets],
            "maximal_survivable_sets": [list(s) for s in self.maximal_survivable_sets],
            "single_points_of_failure": list(self.single_points_of_failure),
            "already_failed": list(self.already_failed),
            "directions": {d: {"gaits": list(g), "legs": list(some), "every_gait_uses":
                               list(every)} for d, g, some, every in self.directions},
            "any_time_k": self.any_time_k,
            "defeating_sets": [list(s) for s in self.defeating_sets],
            "health_bound": self.health_bound,
            "health_levels": dict(self.health_levels),
            "min_uniform_health": self.min_uniform_health,
            "health_front": (None if self.health_front is None
                             else [dict(v) for v in self.health_front]),
            "essential_caches": list(self.essential_caches),
            "cache_placements": [list(s) for s in self.cache_placements],
            "hazards_survived_alone": list(self.hazards_survived_alone),
            "hazard_wear": [{"hazard": n, "declared": k, "most_survived": m,
                             "survives_failing": f} for n, k, m, f in self.hazard_wear],
            "tolerance": None if self.tolerance is None else self.tolerance.to_json(),
            "solver_calls": self.solver_calls, "seconds": round(self.seconds, 3),
            "notes": list(self.notes),
        }

    def lines(self) -> list[str]:
        """The report for the terminal: one table per question."""
        out = [f"{self.file}: resilience ({self.method} method, {self.solver_calls} solver "
               f"calls, {self.seconds:.1f} s)"]
        out.append("legs: " + ", ".join(f"{leg} ({h} level{'s' if h > 1 else ''})"
                                        for leg, h in self.legs))
        if not self.realizable:
            if self.placed is not None:
                out.append("the task is unrealizable even with no failure ('gaitc explain' "
                           "says why)")
                out.append(f"caches at {self.placed} region(s) that make it realizable (the "
                           f"spec's own caches replaced): {_sets(self.cache_placements)}")
                return out
            out.append("the task is unrealizable even with no failure ('gaitc explain' says "
                       "why); nothing else to report")
            return out
        if self.already_failed:
            out.append(f"already failed (health 1): {', '.join(self.already_failed)}")
        out.append("")
        out.append("1. legs failed for good (as `health 1` declares; a cache never mends them)")
        out.append(f"   minimal fatal sets:      {_sets(self.minimal_fatal_sets)}")
        out.append(f"   maximal survivable sets: {_sets(self.maximal_survivable_sets)}")
        out.append("   single points of failure: "
                   + (", ".join(self.single_points_of_failure) or "none"))
        width = max((len(d) for d, *_ in self.directions), default=9)
        for direction, gaits, some, every in self.directions:
            need = f"; every one uses {', '.join(every)}" if every else ""
            out.append(f"   {direction:<{width}}  usable gaits {', '.join(gaits) or 'none'}: "
                       f"legs {', '.join(some)}{need}")
        out.append("")
        out.append("2. legs breaking during the run (at moments the environment chooses)")
        k = self.any_time_k or 0
        out.append(f"   survives any {k} leg(s) breaking"
                   + (f"; these sets of {k + 1} defeat it: {_sets(self.defeating_sets)}"
                      if self.defeating_sets else ""))
        out.append("")
        out.append(f"3. health ({self._levels_text()})")
        uniform = self.min_uniform_health
        if uniform:
            out.append(f"   least uniform health: {uniform}")
        else:
            top = self.health_bound or max((h for _, h in self.legs), default=1)
            out.append(f"   least uniform health: none within 1..{top}")
        front = self.health_front
        if front is None:
            out.append("   Pareto front: not searched (see the notes)")
        else:
            out.append(f"   Pareto front ({len(front)} vectors, no leg can lose a level):")
            out.extend("     " + " ".join(f"{leg}={h}" for leg, h in v) for v in front[:40])
            if len(front) > 40:
                out.append(f"     ... and {len(front) - 40} more (--json lists all)")
        out.append("")
        out.append("4. caches and hazards")
        out.append("   essential caches: " + (", ".join(self.essential_caches) or "none"))
        if self.placed is not None:
            out.append(f"   caches at {self.placed} region(s) that make the task realizable "
                       f"(the spec's own caches replaced): {_sets(self.cache_placements)}")
        out.append("   hazard sets survived alone: "
                   + (", ".join(self.hazards_survived_alone) or "none"))
        if self.hazards_fatal_alone:
            out.append("   hazard sets fatal alone: " + ", ".join(self.hazards_fatal_alone))
        for name, declared, most, fails in self.hazard_wear:
            worse = (" and survives it failing the legs" if fails
                     else "; failing the legs would be fatal")
            out.append(f"   graded hazard {name} (wears {declared}): survives it wearing up to "
                       f"{most} level{'s' if most > 1 else ''} a move{worse}")
        if self.tolerance is not None:
            out.append("")
            out.append(f"5. surprises (broken assumptions, up to {self.tolerance.requested}; "
                       "synth --tolerate)")
            out.extend("   " + line[2:] for line in self.tolerance.lines()[1:])
        out.extend(f"note: {n}" for n in self.notes)
        return out

    def _levels_text(self) -> str:
        """The health levels the front was searched over, in words."""
        if self.health_bound is not None:
            return f"levels 1..{self.health_bound} for every leg, --health-bound"
        return "each leg within its own declared levels: " + ", ".join(
            f"{leg} 1..{h}" for leg, h in self.health_levels)

    def __repr__(self) -> str:
        return (f"<Resilience {self.file!r}: {len(self.minimal_fatal_sets)} minimal fatal "
                f"sets, single points of failure {list(self.single_points_of_failure)}, "
                f"any-time k = {self.any_time_k}>")

    def picture(self) -> Any:
        return legs_picture(self)

    def _repr_svg_(self) -> str:
        svg: str = self.picture().svg()
        return svg


def _sets(sets: tuple[tuple[str, ...], ...]) -> str:
    if not sets:
        return "none"
    return " ".join("{" + ", ".join(s) + "}" for s in sets)


def resilience(model: Model, encoding: EncodingName, file: str = "",
               semantics: Semantics = Semantics.DEFAULT, *, method: str = "parametric",
               health_bound: int | None = None, place_caches: int | None = None,
               tolerate: int | None = DEFAULT_BOUND, pool: Pool | None = None) -> Resilience:
    """Every answer of the module docstring for ``model``; ``tolerate`` bounds the
    surprises searched (None: not searched)."""
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; use one of {', '.join(METHODS)}")
    started = time.monotonic()
    owned = pool is None
    pool = pool or Pool(encoding, semantics)
    notes: list[str] = []
    param_seconds = 0.0
    try:
        legs = tuple((leg.name, leg.health) for leg in model.legs)
        realizable = pool.models([model])[0]
        failed = tuple(name for name, h in legs if h == 1)
        candidates = [name for name, h in legs if h > 1]
        usable = {g.name for g in model.gaits if not set(g.legs) & set(failed)}
        directions = tuple((d, kept, *family_legs(model, kept))
                           for d, gaits in gait_families(model).items()
                           for kept in [tuple(g for g in gaits if g in usable)])
        report = Resilience(file, legs, realizable, method, already_failed=failed,
                            directions=directions, model=model)
        if not realizable:
            notes.append("the task is unrealizable even with no failure; "
                         "'gaitc explain' says why")
            if place_caches is not None:  # caches elsewhere may still make it realizable
                report = _with(report, placed=place_caches, cache_placements=_placements(
                    model, place_caches, pool, notes))
            return _finish(report, pool, started, notes, param_seconds)
        if method == "parametric":
            found = failure_sets(model, encoding, semantics)
            param_seconds += found.seconds
            minimal = _ordered(found.minimal_fatal, candidates)
            maximal = _ordered(found.maximal_survivable, candidates)
            pool.calls += 1
        else:
            lattice = fatal_sets(candidates, lambda sets: [not ok for ok in pool.models(
                [with_failed(model, s) for s in sets])])
            minimal, maximal = lattice.minimal_fatal, lattice.maximal_survivable
        report = _with(report, minimal_fatal_sets=minimal, maximal_survivable_sets=maximal,
                       single_points_of_failure=tuple(s[0] for s in minimal if len(s) == 1))
        k, defeating = _any_time(model, encoding, candidates, pool, semantics, minimal)
        report = _with(report, any_time_k=k, defeating_sets=defeating)
        report = _health(
            report=report,
            model=model,
            encoding=encoding,
            semantics=semantics,
            method=method,
            bound=health_bound,
            pool=pool,
            notes=notes,
        )
        report = _caches_and_hazards(report, model, place_caches, pool, notes)
        if tolerate is not None:
            report = _surprises(report, model, encoding, semantics, tolerate, pool, notes)
        return _finish(report, pool, started, notes, param_seconds)
    finally:
        if owned:
            pool.close()


def _surprises(report: Resilience, model: Model, encoding: EncodingName,
               semantics: Semantics, bound: int, pool: Pool, notes: list[str]) -> Resilience:
    """Section 5: the tolerance of surprises up to ``bound``, when the game is small enough
    (:data:`MAX_TOLERANCE_BITS`)."""
    spec = Spec(report.file, lower(model, encoding), model, encoding)
    bits = state_bits(spec.gr1)
    if bits > MAX_TOLERANCE_BITS:
        notes.append(f"surprises not searched: {bits} state bits is more than the "
                     f"{MAX_TOLERANCE_BITS} searched; 'gaitc synth --tolerate' solves them")
        return report
    found = tolerance(spec, semantics, bound)
    pool.calls += found.solver_calls
    return _with(report, tolerance=found)


def _with(report: Resilience, **changes: Any) -> Resilience:
    return replace(report, **changes)


def _finish(report: Resilience, pool: Pool, started: float, notes: list[str],
            param_seconds: float) -> Resilience:
    if param_seconds:
        notes.append(f"parametric games: {param_seconds:.2f} s")
    return _with(report, solver_calls=pool.calls, seconds=time.monotonic() - started,
                 notes=tuple(notes))


def _ordered(sets: tuple[frozenset[str], ...], elements: list[str]
             ) -> tuple[tuple[str, ...], ...]:
    """Sets as tuples in declaration order, smallest first (as the lattice search gives)."""
    rank = {e: i for i, e in enumerate(elements)}
    items = [tuple(sorted(s, key=rank.__getitem__)) for s in sets]
    return tuple(sorted(items, key=lambda t: (len(t), [rank[x] for x in t])))


def _any_time(model: Model, encoding: EncodingName, legs: list[str], pool: Pool,
              semantics: Semantics, minimal_fatal: tuple[tuple[str, ...], ...] = ()
              ) -> tuple[int, tuple[tuple[str, ...], ...]]:
    """The largest k with any k legs breaking survived (one game per k), and the sets of
    k + 1 breakable legs that defeat the robot: one game per candidate set when there are
    few (:func:`defeat_candidates`), else one parametric game over which legs may break,
    read for the sets of exactly k + 1."""
    # The broken flags on top of the BDD order: centipede24's k = 2 game takes 17 s there,
    # 266 s in the solver's own order.
    first = tuple(broken_name(leg) for leg in legs)
    k = 0
    while k < len(legs) and pool.specs([anytime_spec(model, encoding, k + 1, legs)], first)[0]:
        k += 1
    if k == len(legs):
        return k, ()
    combos = defeat_candidates(model, legs, k + 1, minimal_fatal)
    if len(combos) <= DIRECT_DEFEATS:
        answers = pool.specs([anytime_spec(model, encoding, k + 1, c) for c in combos], first)
        return k, tuple(c for c, ok in zip(combos, answers, strict=True) if not ok)
    pool.calls += 1
    return k, _defeating(model, encoding, legs, k + 1, semantics)


def defeat_candidates(model: Model, legs: list[str], size: int,
                      minimal_fatal: tuple[tuple[str, ...], ...],
                      prune_above: int = DIRECT_DEFEATS) -> list[tuple[str, ...]]:
    """The sets of ``size`` legs that may defeat the robot by breaking during the run.

    A set that survives failing from the start also survives breaking during the run: the
    robot plays its strategy for the failed legs, which never uses them, and the
    compiler's own rules give the environment nothing more when a leg merely breaks. So
    when the spec has no assumptions or guarantees of its own (which could speak of a
    broken leg's health), only the sets that hold a minimal fatal set are candidates; else,
    or when there are at most ``prune_above`` sets anyway, every set is.
    ``tests/analysis/test_resilience_methods.py`` solves the sets pruned away on the small specs.
    """
    combos = list(itertools.combinations(legs, size))
    if model.assumptions or model.guarantees or len(combos) <= prune_above:
        return combos
    fatal = [frozenset(s) for s in minimal_fatal]
    return [c for c in combos if any(f <= frozenset(c) for f in fatal)]


def _defeating(model: Model, encoding: EncodingName, legs: list[str], size: int,
               semantics: Semantics) -> tuple[tuple[str, ...], ...]:
    spec = anytime_spec(model, encoding, size, legs, parametric=True)
    names = [breakable_name(leg) for leg in legs]
    sym = SymbolicSpec(spec, Options(first=(*names, *(broken_name(leg) for leg in legs))))
    good = winning_parameters(sym, Game(sym).solve().winning, names, semantics)
    flags = [Var(n) for n in names]
    exactly = sym.translate(at_most(flags, size)) & ~sym.translate(at_most(flags, size - 1))
    found = []
    for point in sym.bdd.pick_iter(exactly & ~good, care_vars=set(names)):
        found.append(tuple(leg for leg, n in zip(legs, names, strict=True) if point[n]))
    rank = {leg: i for i, leg in enumerate(legs)}
    return tuple(sorted(found, key=lambda s: [rank[x] for x in s]))


def health_domains(model: Model, bound: int | None) -> dict[str, tuple[int, ...]]:
    """The levels searched for each leg's health: ``1..bound`` for every leg, or without a
    bound each leg's own declared levels (``1..h``), so a spec's own levels are always in
    the search and its verdict at them is never hidden by a smaller default."""
    return {leg.name: tuple(range(1, (bound or leg.health) + 1)) for leg in model.legs}


def _health(report: Resilience, model: Model, encoding: EncodingName, semantics: Semantics,
            *, method: str, bound: int | None, pool: Pool, notes: list[str]) -> Resilience:
    names = [leg.name for leg in model.legs]
    largest = max(leg.health for leg in model.legs)
    top = bound or largest
    uniform = None
    for h in range(1, top + 1):
        if pool.models([with_health(model, dict.fromkeys(names, h))])[0]:
            uniform = h
            break
    if uniform is None and top < largest:
        notes.append(f"no uniform health within 1..{top}; the spec uses up to {largest}: "
                     f"try --health-bound {largest}")
    domains = health_domains(model, bound)
    report = _with(report, health_bound=bound, min_uniform_health=uniform,
                   health_levels=tuple((n, len(domains[n])) for n in names))
    front: tuple[tuple[int, ...], ...] = ()
    vectors = math.prod(len(d) for d in domains.values())
    if vectors > MAX_HEALTH_VECTORS:
        notes.append(f"health front skipped: {vectors:,} health vectors is more than the "
                     f"{MAX_HEALTH_VECTORS:,} searched; a lower --health-bound narrows it")
        return _with(report, health_front=None)
    try:
        if method == "parametric":
            caps = winning_caps(model, encoding, domains, semantics, minimal_only=True)
            front = tuple(sorted(caps.winning))
            pool.calls += 1
        else:
            front = minimal_vectors([len(domains[n]) for n in names], lambda v: pool.models(
                [with_health(model, dict(zip(names, v, strict=True)))])[0]).minimal
    except GaitcError:  # a ValueError too, but the user's to see, not a skipped front
        raise
    except ValueError as err:
        notes.append(f"health front skipped: {err}")
        return _with(report, health_front=None)
    return _with(report, health_front=tuple(tuple(zip(names, v, strict=True))
                                            for v in front))


def cache_sites(model: Model) -> list[str]:
    """The regions a cache may be placed in: those no hazard covers."""
    hazardous = {r for h in model.hazards for r in h.regions}
    return [r.name for r in model.regions if r.name not in hazardous]


def _placements(model: Model, place: int | None, pool: Pool,
                notes: list[str]) -> tuple[tuple[str, ...], ...]:
    """The sets of ``place`` cache sites whose caches (instead of the spec's) make the task
    realizable; none searched when ``place`` is None or there are too many sets."""
    if place is None:
        return ()
    combos = list(itertools.combinations(cache_sites(model), place))
    if len(combos) > MAX_PLACEMENTS:
        notes.append(f"cache placement skipped: {len(combos)} sets of {place} regions "
                     f"(more than {MAX_PLACEMENTS})")
        return ()
    answers = pool.models([with_caches(model, c) for c in combos])
    return tuple(c for c, ok in zip(combos, answers, strict=True) if ok)


def _caches_and_hazards(report: Resilience, model: Model, place: int | None, pool: Pool,
                        notes: list[str]) -> Resilience:
    caches = list(model.caches)
    without = pool.models([with_caches(model, [c for c in caches if c != cache])
                           for cache in caches])
    essential = tuple(c for c, ok in zip(caches, without, strict=True) if not ok)
    placements = _placements(model, place, pool, notes)
    names = [h.name for h in model.hazards]
    alone = pool.models([with_hazards(model, [h]) for h in names])
    wear = tuple(_hazard_wear(model, h.name, levels, pool) for h in model.hazards
                 if (levels := graded_levels(h.harm)) is not None)
    return _with(report, essential_caches=essential, cache_placements=placements,
                 placed=place,
                 hazards_survived_alone=tuple(h for h, ok in zip(names, alone, strict=True)
                                              if ok),
                 hazards_fatal_alone=tuple(h for h, ok in zip(names, alone, strict=True)
                                           if not ok),
                 hazard_wear=wear)


def _hazard_wear(model: Model, name: str, declared: int, pool: Pool
                 ) -> tuple[str, int, int, bool]:
    """How much worse the graded hazard ``name`` (``wears declared``) may be: the most wear
    the task survives, found by bisection between the declared wear (survived: the task is
    realizable) and h - 1 (h the most levels a leg has; more wear changes nothing, a leg
    never drops below 1), and whether it survives the hazard failing the legs outright
    (eq. 3.9). More wear only frees the environment, so survival is monotone."""
    def variant(wears: int | None) -> Model:
        harm = Fails() if wears is None else WearsUpTo(wears)
        return replace(model, hazards=tuple(replace(h, harm=harm) if h.name == name else h
                                            for h in model.hazards))

    low, high = declared, max(declared, max(leg.health for leg in model.legs) - 1)
    while low < high:
        middle = (low + high + 1) // 2
        if pool.models([variant(middle)])[0]:
            low = middle
        else:
            high = middle - 1
    return name, declared, low, pool.models([variant(None)])[0]
