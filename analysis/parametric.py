"""One game for all variants: per-leg health caps as rigid parameters of the spec.

Each leg L gets an integer input ``gaitc_cap_L`` that the environment chooses at the start
and can never change (``cap' = cap``). The leg starts at its cap (or lower, when the spec
starts it lower) and a cache resets it to its cap instead of to full health; every other
rule is the spec's own. Cap 1 is what ``health 1`` means: the leg is permanently failed.
Because the caps never change, the game falls apart into one sub-game per cap vector, so
one fixpoint gives every verdict: the vectors from whose initial states the robot wins are a
BDD over the cap bits (the "parametric" idea of the issue; compare the lattice searches of
:mod:`analysis.lattice`, which solve one variant per call).
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

from gr1.formula import Compare, Expr, Implies, IntConst, IntVar, conj, disj
from gr1.spec import Clause, GR1Spec, Origin, Variable
from ltlcompiler.encoding import make_encoding
from ltlcompiler.lowering import lower
from ltlcompiler.model import Model
from solver.game import Game
from solver.symbolic import BDDNode, Options, SymbolicSpec

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


def parametric_spec(model: Model, encoding: str, domains: Mapping[str, Sequence[int]]
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

    env_init = [c for c in spec.env_init if not _rule(c).startswith("init: leg ")]
    for leg, original in zip(raised.legs, model.legs, strict=True):
        start = None if original.initial == original.health else original.initial
        env_init.append(Clause(at_cap(leg.name, False, start),
                               Origin(f"parameter: leg {leg.name} starts at its cap")))
    env_trans = [c for c in spec.env_trans if not _rule(c).startswith("eq. 3.6:")]
    for cache in raised.caches:
        reset = conj(at_cap(leg.name, True) for leg in raised.legs if leg.health > 1)
        env_trans.append(Clause(Implies(enc.region(cache), reset),
                                Origin(f"eq. 3.6 with caps: cache {cache} resets every leg "
                                       "to its cap")))
    for leg in raised.legs:
        cap = caps[leg.name]
        env_trans.append(Clause(Compare("=", IntVar(cap.name, True), cap),
                                Origin(f"parameter: the cap of {leg.name} never changes")))
    inputs = spec.inputs + tuple(
        Variable(cap_name(leg.name), min(domains[leg.name]), max(domains[leg.name]))
        for leg in raised.legs)
    return replace(spec, inputs=inputs, env_init=tuple(env_init), env_trans=tuple(env_trans))


def _rule(clause: Clause) -> str:
    return clause.origin.rule if clause.origin is not None else ""


def winning_caps(model: Model, encoding: str, domains: Mapping[str, Sequence[int]],
                 semantics: str = "default", minimal_only: bool = False) -> ParametricResult:
    """Every cap vector (one value per leg, in ``model.legs`` order) the robot wins from;
    with ``minimal_only``, just the minimal ones (the Pareto front of an upward-closed set
    over contiguous domains), computed on the BDD before anything is enumerated."""
    started = time.monotonic()
    spec = parametric_spec(model, encoding, domains)
    sym = SymbolicSpec(spec, Options(first=tuple(cap_name(leg.name) for leg in model.legs)))
    result = Game(sym).solve()
    winning = result.winning
    bdd = sym.bdd
    legs = tuple(leg.name for leg in model.legs)
    param_bits = [b for leg in legs for b in sym.var_bits[cap_name(leg)]]
    good = winning_parameters(sym, winning, param_bits, semantics)
    if minimal_only:
        good = _minimal(sym, good, legs, domains)
    vectors = set()
    lows = {leg: min(domains[leg]) for leg in legs}
    for point in bdd.pick_iter(good, care_vars=set(param_bits)):
        vector = []
        for leg in legs:
            bits = sym.var_bits[cap_name(leg)]
            vector.append(lows[leg] + sum(int(point[b]) << k for k, b in enumerate(bits)))
        vectors.add(tuple(vector))
    domain_sets = {leg: set(domains[leg]) for leg in legs}
    vectors = {v for v in vectors if all(x in domain_sets[leg]
                                         for x, leg in zip(v, legs, strict=True))}
    return ParametricResult(legs, frozenset(vectors), time.monotonic() - started,
                            result.stats.peak_nodes)


def winning_parameters(sym: SymbolicSpec, winning: BDDNode, param_bits: Sequence[str],
                       semantics: str) -> BDDNode:
    """The parameter values (a BDD over ``param_bits``) with an admissible initial state from
    which the robot wins under ``semantics`` (SLUGS's initial condition, per parameter)."""
    bdd = sym.bdd
    others = (sym.pre_inputs | sym.pre_outputs) - set(param_bits)
    if semantics == "robotics":
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
