"""The robot's move costs: the criteria that ``--prefer`` orders, written from the model.

Issue 13: among the moves a GR(1) controller may take, prefer those that do not enter a
region of an active hazard set (eq. 3.9 would fail the gait's legs, a graded hazard wear
them by up to k levels), that lose the fewest health levels and spare degraded legs
(eqs. 3.5, 3.6), and that switch gait least.  The
shortest way to the next goal needs no model: the solver reads it off the fixpoint's
rings (:mod:`gaitc.solver.preferences`).  The thesis has none of these; they only choose among
winning moves, so they never change what the controller guarantees.
"""

from __future__ import annotations

from collections.abc import Sequence

from gaitc.ir.costs import Cost
from gaitc.ir.formula import Expr, Not, conj, disj, unreachable
from gaitc.ir.roles import Fails, WearsUpTo
from ltlcompiler.encoding import Encoding, EncodingName, make_encoding
from ltlcompiler.model import GaitKind, Hazard, Model


def model_costs(model: Model, encoding: EncodingName = EncodingName.ONEHOT) -> tuple[Cost, ...]:
    """The ``hazard``, ``health`` and ``switches`` costs of ``model`` in ``encoding``.

    Turn order (see :func:`ltlcompiler.lowering.lower`): the next region and gait the robot
    picks, with the next hazard the environment has just chosen, decide what the
    environment may take from the legs one step later; so every term reads primed values.
    """
    enc = make_encoding(model, encoding)
    return (_hazard(model, enc), _health(model, enc), _switches(model, enc))


def _moving(model: Model) -> list[tuple[str, tuple[str, ...]]]:
    """Gaits that wear legs (eq. 3.5): moving gaits with their legs above level 1."""
    return [(g.name, tuple(leg for leg in g.legs if model.leg(leg).health > 1))
            for g in model.gaits if g.kind is GaitKind.MOVE]


def _hot(model: Model, enc: Encoding, hazards: Sequence[Hazard] | None = None) -> Expr:
    """The next region lies in the active hazard set, one of ``hazards`` (default every
    hazard of the model), and is no cache (eq. 3.9's φ_H)."""
    return conj([disj(conj((enc.hazard(h.name, True),
                            disj(enc.region(r, True) for r in h.regions)))
                      for h in (model.hazards if hazards is None else hazards)),
                 *(Not(enc.region(c, True)) for c in model.caches)])


def _levels_lost(hazard: Hazard, level: int) -> int:
    """The most levels a leg at ``level`` in use loses in a region of ``hazard`` when it
    is active: all but one when it fails the legs, at most ``wears`` when it is graded."""
    return hazard.harm.lost(level)


def by_severity(hazards: Sequence[Hazard]) -> list[Hazard]:
    """``hazards``, the worst first: those that fail the legs (eq. 3.9), then the graded
    ones by the levels they may take (most first), ties in the spec's order."""
    return sorted(hazards, key=_severity)


def _severity(hazard: Hazard) -> tuple[int, int]:
    """The sort key of :func:`by_severity`: failing first, then the most levels."""
    match hazard.harm:
        case Fails():
            return (0, 0)
        case WearsUpTo(levels=k):
            return (1, -k)
        case _:
            unreachable(hazard.harm)


def _hazard(model: Model, enc: Encoding) -> Cost:
    """One term a hazard, the worst first (:func:`by_severity`): a move with a gait that
    wears legs into (or within) a region of that hazard while it is active.  Hazard sets
    are mutually exclusive, so at most one term holds and a move's cost is 0 or 1; the
    solver also avoids the hazards one by one, the worst first
    (:class:`gaitc.solver.preferences.MovePreferences`)."""
    meaning = "do not enter (or walk in) a region of the active hazard set"
    wearing = [g for g, legs in _moving(model) if legs]
    if not model.hazards or not wearing:
        return Cost("hazard", meaning)
    gait = disj(enc.gait(g, True) for g in wearing)
    ranked = by_severity(model.hazards)
    return Cost("hazard", meaning, tuple((1, conj((_hot(model, enc, (h,)), gait)))
                                         for h in ranked),
                labels=tuple(h.name for h in ranked))


def _health(model: Model, enc: Encoding) -> Cost:
    """Worst-case levels lost first (weight ``scale`` each), then how degraded the legs in
    use are (one per level below full): a degraded leg is used when nothing else works.
    A move loses one level of each leg in use (eq. 3.5), or in an active hazard's region
    :func:`_levels_lost` (hazard sets are mutually exclusive, so at most one applies)."""
    meaning = "lose the fewest health levels; use degraded legs last"
    away = [Not(enc.region(c, True)) for c in model.caches]  # a cache restores (eq. 3.6)
    hot = _hot(model, enc) if model.hazards else None
    scale = 1 + sum(leg.health - 1 for leg in model.legs)
    terms: list[tuple[int, Expr]] = []
    for leg in model.legs:
        gaits = [g for g, legs in _moving(model) if leg.name in legs]
        if not gaits:
            continue
        using = conj([disj(enc.gait(g, True) for g in gaits), *away])
        for level in range(2, leg.health + 1):
            at = conj((using, enc.health(leg.name, level, True)))
            spare = leg.health - level
            if hot is None:
                terms.append((scale + spare, at))
                continue
            terms.append((scale + spare, conj((at, Not(hot)))))
            lost: dict[int, list[Hazard]] = {}
            for hazard in model.hazards:
                lost.setdefault(_levels_lost(hazard, level), []).append(hazard)
            if len(lost) == 1:  # one worst case for every hazard (no graded one, say)
                terms.append((scale * next(iter(lost)) + spare, conj((at, hot))))
                continue
            for levels, hazards in sorted(lost.items()):
                terms.append((scale * levels + spare, conj((at, _hot(model, enc, hazards)))))
    return Cost("health", meaning, tuple(terms))


def _switches(model: Model, enc: Encoding) -> Cost:
    terms = tuple((1, conj((enc.gait(g.name, True), Not(enc.gait(g.name)))))
                  for g in model.gaits)
    return Cost("switches", "switch gait as rarely as possible", terms)
