"""Variants of a robot model for the resilience questions, and what the map says statically.

Each variant is a new checked :class:`~ltlcompiler.model.Model`: legs failed from the start
(health 1, what the language means by a permanently failed leg), other health levels,
caches removed or placed, hazard sets kept alone. :func:`anytime_spec` is the one variant
on the GR(1) level: the environment may break up to k legs at moments of its choosing.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import replace

from gaitc.ir.formula import (
    FALSE,
    TRUE,
    And,
    Const,
    Expr,
    Iff,
    Implies,
    Not,
    Or,
    Var,
    conj,
    substitute,
)
from gaitc.ir.spec import Clause, GR1Spec, Origin, Variable
from ltlcompiler.encoding import EncodingName, make_encoding
from ltlcompiler.lowering import lower
from ltlcompiler.model import GaitKind, Model, UserFormula

BROKEN = "gaitc_broken_"
BREAKABLE = "gaitc_breakable_"


def with_failed(model: Model, legs: Iterable[str]) -> Model:
    """``model`` with ``legs`` permanently failed (health 1) from the start."""
    failed = set(legs)
    return replace(model, legs=tuple(replace(leg, health=1, initial=1) if leg.name in failed
                                     else leg for leg in model.legs))


def with_health(model: Model, levels: Mapping[str, int]) -> Model:
    """``model`` with the given numbers of health levels (initial health capped)."""
    return replace(model, legs=tuple(
        replace(leg, health=levels[leg.name], initial=(
            levels[leg.name] if leg.initial == leg.health
            else min(leg.initial, levels[leg.name])))
        if leg.name in levels else leg for leg in model.legs))


def with_caches(model: Model, caches: Iterable[str]) -> Model:
    return replace(model, caches=tuple(caches))


def with_hazards(model: Model, keep: Iterable[str]) -> Model:
    """``model`` with only the hazard sets ``keep``: the others are never active, so the
    assumptions and guarantees that name them read them as false."""
    names = set(keep)
    gone: dict[tuple[str, bool], Expr] = {(h.name, primed): Const(False)
                                          for h in model.hazards if h.name not in names
                                          for primed in (False, True)}

    def drop(formulas: tuple[UserFormula, ...]) -> tuple[UserFormula, ...]:
        return tuple(replace(uf, formula=substitute(uf.formula, gone)) for uf in formulas)

    return replace(model, hazards=tuple(h for h in model.hazards if h.name in names),
                   assumptions=drop(model.assumptions), guarantees=drop(model.guarantees))


_DIRECTIONS = {(-1, 0): "north", (1, 0): "south", (0, 1): "east", (0, -1): "west"}


def gait_families(model: Model) -> dict[str, tuple[str, ...]]:
    """The gaits of each compass direction of the grid moves they make, and of each gait
    that only moves along explicit edges (its own family)."""
    cells = {r.name: (r.row, r.col) for r in model.regions if r.row is not None}
    families: dict[str, list[str]] = {}
    for t in model.transitions:
        if t.source == t.target:
            continue
        a, b = cells.get(t.source), cells.get(t.target)
        step = None
        if a is not None and b is not None and a[0] is not None and b[0] is not None \
                and a[1] is not None and b[1] is not None:
            step = _DIRECTIONS.get((b[0] - a[0], b[1] - a[1]))
        for gait in t.gaits:
            if model.gait(gait).kind is not GaitKind.MOVE:
                continue
            name = step or f"gait {gait}"
            if gait not in families.setdefault(name, []):
                families[name].append(gait)
    order = {g.name: i for i, g in enumerate(model.gaits)}
    return {k: tuple(sorted(v, key=order.__getitem__)) for k, v in sorted(families.items())}


def family_legs(model: Model, gaits: tuple[str, ...]) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(legs some gait of the family uses, legs every gait of it uses)."""
    sets = [set(model.gait(g).legs) for g in gaits]
    order = [leg.name for leg in model.legs]
    some = set().union(*sets) if sets else set()
    every = set.intersection(*sets) if sets else set()
    return (tuple(x for x in order if x in some), tuple(x for x in order if x in every))


def at_most(items: Sequence[Expr], k: int) -> Expr:
    """"At most ``k`` of ``items`` hold", as a DAG of n·k shared nodes: F(i, j) = "at most
    j of items[i:]" is (items[i] & F(i+1, j-1)) | (!items[i] & F(i+1, j))."""
    memo: dict[tuple[int, int], Expr] = {}
    n = len(items)
    for i in range(n, -1, -1):
        for j in range(k + 1):
            if i == n:
                memo[(i, j)] = TRUE
                continue
            take = memo[(i + 1, j - 1)] if j > 0 else FALSE
            memo[(i, j)] = Or((And((items[i], take)), And((Not(items[i]), memo[(i + 1, j)]))))
    return memo[(0, k)]


def broken_name(leg: str) -> str:
    return f"{BROKEN}{leg}"


def breakable_name(leg: str) -> str:
    return f"{BREAKABLE}{leg}"


def anytime_spec(model: Model, encoding: EncodingName, k: int,
                 breakable: Iterable[str] | None = None, parametric: bool = False) -> GR1Spec:
    """The spec in which the environment may, at any step, break legs for good (at most
    ``k`` of those in ``breakable``, default all): a broken leg's gaits are off from the
    step it breaks on, whatever its health, and no cache mends it. With ``parametric``,
    which legs may break is itself a rigid parameter per leg (``gaitc_breakable_L``)."""
    spec = lower(model, encoding)
    enc = make_encoding(model, encoding)
    legs = [leg.name for leg in model.legs] if breakable is None else list(breakable)
    flags = {leg: Var(broken_name(leg)) for leg in legs}
    env_init = [Clause(Not(flags[leg]), Origin(f"resilience: {leg} starts unbroken"))
                for leg in legs]
    env_trans = [Clause(Implies(flags[leg], Var(broken_name(leg), True)),
                        Origin(f"resilience: a broken {leg} stays broken")) for leg in legs]
    if k < len(legs):
        bound = at_most([Var(broken_name(x), True) for x in legs], k)
        env_trans.append(Clause(bound, Origin(f"resilience: at most {k} legs break")))
    sys_trans = []
    for leg in legs:
        gaits = model.gaits_using(leg)
        if gaits:
            off = conj(Not(enc.gait(g, True)) for g in gaits)
            sys_trans.append(Clause(Implies(Var(broken_name(leg), True), off),
                                    Origin(f"resilience: gaits using a broken {leg} are off")))
    inputs = spec.inputs + tuple(Variable(broken_name(leg)) for leg in legs)
    if parametric:
        for leg in legs:
            may = Var(breakable_name(leg))
            env_trans.append(Clause(Implies(Var(broken_name(leg), True), may),
                                    Origin(f"parameter: {leg} breaks only if breakable")))
            env_trans.append(Clause(Iff(Var(breakable_name(leg), True), may),
                                    Origin(f"parameter: whether {leg} may break never "
                                           "changes")))
        inputs += tuple(Variable(breakable_name(leg)) for leg in legs)
    return replace(spec, inputs=inputs, env_init=spec.env_init + tuple(env_init),
                   env_trans=spec.env_trans + tuple(env_trans),
                   sys_trans=spec.sys_trans + tuple(sys_trans))
