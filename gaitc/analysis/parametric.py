"""One game for all variants: per-leg health caps as rigid parameters of the spec.

Each leg L gets an integer input ``gaitc_cap_L`` that the environment chooses at the start
and can never change (``cap' = cap``). The leg starts at its cap (or lower, when the spec
starts it lower) and a cache resets it to its cap instead of to full health; every other
rule is the spec's own. Cap 1 is what ``health 1`` means: the leg is permanently failed.
Because the caps never change, the game falls apart into one sub-game per cap vector, so
one fixpoint gives every verdict: the vectors from whose initial states the robot wins are a
BDD over the cap bits (the "parametric" idea of the issue; compare the lattice searches of
:mod:`gaitc.analysis.lattice`, which solve one variant per call).
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

from gaitc.ir.formula import Compare, Expr, Implies, IntConst, IntVar, conj, disj
from gaitc.ir.roles import Restores, StartHealth
from gaitc.ir.spec import Clause, GR1Spec, Origin, Semantics, Variable
from gaitc.solver.game import Game
from gaitc.solver.ordering import variable_order
from gaitc.solver.symbolic import BDDNode, Options, SymbolicSpec
from ltlcompiler.encoding import EncodingName, health_prop, make_encoding
from ltlcompiler.lowering import lower
from ltlcompiler.model import Model

PREFIX = "gaitc_cap_"


@dataclass(frozen=True)
class ParametricResult:
    """The cap vectors (in leg order) from which the robot wins, and what it cost."""

    legs: tuple[str, ...]
    winning: frozenset[tuple[int, ...]]
    seconds: float
    peak_nodes: int


def cap_name(leg: str) -> str:
    return f"{PREFIX}{leg}"


def parametric_spec(model: Model, encoding: EncodingName, domains: Mapping[str, Sequence[int]]
                    ) -> GR1Spec:
    """The spec of ``model`` with each leg's cap a rigid parameter ranging over its domain."""
    raised = replace(model, legs=tuple(
        replace(leg, health=max(domains[leg.name]),
                initial=max(domains[leg.name]) if leg.initial == leg.health else leg.initial)
        for leg in model.legs))
    spec = lower(raised, encoding)
    enc = make_encoding(raised, encoding)
    caps = {leg.name: IntVar(cap_name(leg.name)) for leg in raised.legs}

    def at_cap(leg: str, primed: bool, start: int | None = None) -> Expr:
        return disj(conj((Compare("=", caps[leg], IntConst(k)),
                          enc.health(leg, k if start is None else min(start, k), primed)))
                    for k in domains[leg])

    env_init = [c for c in spec.env_init if not _role_is(c, StartHealth)]
    for leg, original in zip(raised.legs, model.legs, strict=True):
        start = None if original.initial == original.health else original.initial
        env_init.append(Clause(at_cap(leg.name, False, start),
                               Origin(f"parameter: leg {leg.name} starts at its cap",
                                      role=StartHealth(leg.name))))
    env_trans = [c for c in spec.env_trans if not _role_is(c, Restores)]
    for cache in raised.caches:
        reset = conj(at_cap(leg.name, True) for leg in raised.legs if leg.health > 1)
        env_trans.append(Clause(Implies(enc.region(cache), reset),
                                Origin(f"eq. 3.6 with caps: cache {cache} resets every leg "
                                       "to its cap", role=Restores(cache))))
    for leg in raised.legs:
        cap = caps[leg.name]
        env_trans.append(Clause(Compare("=", IntVar(cap.name, True), cap),
                                Origin(f"parameter: the cap of {leg.name} never changes")))
    inputs = spec.inputs + tuple(
        Variable(cap_name(leg.name), min(domains[leg.name]), max(domains[leg.name]))
        for leg in raised.legs)
    return replace(spec, inputs=inputs, env_init=tuple(env_init), env_trans=tuple(env_trans))


def _role_is(clause: Clause, kind: type[StartHealth] | type[Restores]) -> bool:
    """Whether the front end wrote ``clause`` with a role of ``kind``."""
    return clause.origin is not None and isinstance(clause.origin.role, kind)


#: Cap vectors up to which the caps sit at the top of the BDD order, and up to which they
#: keep the solver's own order (one block above the health variables); beyond, each cap
#: sits right above its leg.  With every cap above every health variable, the cache's
#: reset (each leg to its cap) has a node per cap vector.  Measured (binary encoding):
#: robot A's failure sets (2^8 vectors) 0.6 s on top, 2.0 s as a block, 10.6 s
#: interleaved; radial12's health front (3^12) 134 s, 65 s, over 300 s; centipede24's
#: failure sets (2^24) out of memory on top and as a block, 3.5 s interleaved.
TOP_LIMIT = 1 << 16
BLOCK_LIMIT = 1 << 20


def cap_order(model: Model, encoding: EncodingName, spec: GR1Spec,
              domains: Mapping[str, Sequence[int]]) -> tuple[str, ...]:
    """``Options.first`` for the game of ``spec`` (see :data:`TOP_LIMIT`)."""
    vectors = 1
    for leg in model.legs:
        vectors *= len(set(domains[leg.name]))
    if vectors <= TOP_LIMIT:
        return tuple(cap_name(leg.name) for leg in model.legs)
    if vectors <= BLOCK_LIMIT:
        return ()
    owner: dict[str, str] = {}
    for leg in model.legs:
        owner[leg.name] = leg.name  # binary: the leg's integer
        for j in range(1, max(domains[leg.name]) + 1):
            owner[health_prop(leg.name, j)] = leg.name  # onehot: its levels
    placed: set[str] = set()
    order: list[str] = []
    for v in variable_order(spec, "guards"):
        if v.name.startswith(PREFIX):
            continue
        name = owner.get(v.name)
        if name is not None and name not in placed:
            placed.add(name)
            order.append(cap_name(name))
        order.append(v.name)
    return tuple(order)


@dataclass
class _Solved:
    sym: SymbolicSpec
    good: BDDNode  # the winning cap vectors, over the cap bits
    bits: list[str]  # every cap bit, leg by leg
    peak_nodes: int


def _solve(model: Model, encoding: EncodingName, domains: Mapping[str, Sequence[int]],
           semantics: Semantics) -> _Solved:
    spec = parametric_spec(model, encoding, domains)
    sym = SymbolicSpec(spec, Options(first=cap_order(model, encoding, spec, domains)))
    result = Game(sym).solve()
    param_bits = [b for leg in model.legs for b in sym.var_bits[cap_name(leg.name)]]
    good = winning_parameters(sym, result.winning, param_bits, semantics)
    return _Solved(sym, good, param_bits, result.stats.peak_nodes)


def _vectors(solved: _Solved, legs: tuple[str, ...], domains: Mapping[str, Sequence[int]],
             points: BDDNode) -> set[tuple[int, ...]]:
    """The cap vectors (within the domains) of a BDD over the cap bits."""
    sym = solved.sym
    lows = {leg: min(domains[leg]) for leg in legs}
    domain_sets = {leg: set(domains[leg]) for leg in legs}
    vectors = set()
    for point in sym.bdd.pick_iter(points, care_vars=set(solved.bits)):
        vector = tuple(lows[leg] + sum(int(point[b]) << k for k, b in
                                       enumerate(sym.var_bits[cap_name(leg)])) for leg in legs)
        if all(x in domain_sets[leg] for x, leg in zip(vector, legs, strict=True)):
            vectors.add(vector)
    return vectors


def winning_caps(model: Model, encoding: EncodingName, domains: Mapping[str, Sequence[int]],
                 semantics: Semantics = Semantics.DEFAULT,
                 minimal_only: bool = False) -> ParametricResult:
    """Every cap vector (one value per leg, in ``model.legs`` order) the robot wins from;
    with ``minimal_only``, just the minimal ones (the Pareto front of an upward-closed set
    over contiguous domains), computed on the BDD before anything is enumerated."""
    started = time.monotonic()
    solved = _solve(model, encoding, domains, semantics)
    legs = tuple(leg.name for leg in model.legs)
    good = _minimal(solved.sym, solved.good, legs, domains) if minimal_only else solved.good
    vectors = _vectors(solved, legs, domains, good)
    return ParametricResult(legs, frozenset(vectors), time.monotonic() - started,
                            solved.peak_nodes)


@dataclass(frozen=True)
class FailureSets:
    """Minimal fatal and maximal survivable sets of legs failed from the start."""

    minimal_fatal: tuple[frozenset[str], ...]
    maximal_survivable: tuple[frozenset[str], ...]
    seconds: float
    peak_nodes: int


def failure_sets(model: Model, encoding: EncodingName,
                 semantics: Semantics = Semantics.DEFAULT) -> FailureSets:
    """The failure sets from one game whose caps range over {1, full}, read off the BDD.

    Flipping leg L between failed and full negates the bits of its cap that are 1 in
    ``full - 1`` (value 1 is all bits 0); a fatal vector is minimal when every flip of a
    failed leg wins, a winning one maximal when every flip of a working leg loses. Only
    those vectors are enumerated, never the whole table of survivors.
    """
    started = time.monotonic()
    domains = {leg.name: ((1, leg.health) if leg.health > 1 else (1,)) for leg in model.legs}
    solved = _solve(model, encoding, domains, semantics)
    sym, good = solved.sym, solved.good
    bdd = sym.bdd
    inside = bdd.true
    minimal = ~good
    maximal = good
    for leg in model.legs:
        bits = sym.var_bits[cap_name(leg.name)]
        failed = bdd.true
        for b in bits:
            failed &= ~bdd.var(b)
        full = bdd.true
        for k, b in enumerate(bits):
            full &= bdd.var(b) if (leg.health - 1) >> k & 1 else ~bdd.var(b)
        inside &= failed | full
        if leg.health == 1:
            continue
        flip = {b: ~bdd.var(b) for k, b in enumerate(bits) if (leg.health - 1) >> k & 1}
        flipped = bdd.let(flip, good)
        minimal &= ~failed | flipped
        maximal &= failed | ~flipped
    legs = tuple(leg.name for leg in model.legs)

    def sets(points: BDDNode) -> tuple[frozenset[str], ...]:
        return tuple(frozenset(leg.name for leg, cap in zip(model.legs, v, strict=True)
                               if cap == 1 and leg.health > 1)
                     for v in _vectors(solved, legs, domains, points & inside))

    return FailureSets(sets(minimal), sets(maximal), time.monotonic() - started,
                       solved.peak_nodes)


def winning_parameters(sym: SymbolicSpec, winning: BDDNode, param_bits: Sequence[str],
                       semantics: Semantics) -> BDDNode:
    """The parameter values (a BDD over ``param_bits``) with an admissible initial state from
    which the robot wins under ``semantics`` (SLUGS's initial condition, per parameter)."""
    bdd = sym.bdd
    others = (sym.pre_inputs | sym.pre_outputs) - set(param_bits)
    if semantics == Semantics.ROBOTICS:
        bad = sym.env_init & sym.sys_init & ~winning
    else:
        bad = sym.env_init & ~bdd.exist(sym.pre_outputs, sym.sys_init & winning)
    admissible = bdd.exist(others, sym.env_init)
    good: BDDNode = admissible & ~bdd.exist(others, bad)
    return good


def _minimal(sym: SymbolicSpec, good: BDDNode, legs: tuple[str, ...],
             domains: Mapping[str, Sequence[int]]) -> BDDNode:
    """The vectors of ``good`` none of whose coordinates can drop by one and stay good.

    ``good`` shifted down in one coordinate is ``good`` with that cap's bits replaced by
    the bits of cap - 1 (a borrow chain), a vector composition on the BDD.
    """
    bdd = sym.bdd
    out = good
    for leg in legs:
        bits = sym.var_bits[cap_name(leg)]
        if len(set(domains[leg])) < 2:
            continue
        borrow = bdd.true
        lowered: dict[str, BDDNode] = {}
        for b in bits:
            var = bdd.var(b)
            lowered[b] = (var & ~borrow) | (~var & borrow)
            borrow = borrow & ~var
        above_low = ~borrow  # the offset from the low end is not zero
        below = bdd.let(lowered, good)
        out &= ~(above_low & below)
    return out
