"""Sanity checks of a realizable spec: is it realizable for the right reason?

* the environment cannot satisfy its own assumptions, even choosing every variable itself
  (then any guarantee is "realizable");
* the robot can force the environment to break an assumption from every start while
  keeping its own transition rules: the spec is not well-separated, and a controller may
  win by blocking the environment (Klein and Pnueli, "Revisiting synthesis of GR(1)
  specifications", HVC 2010; Maoz and Ringert, FSE 2016); each assumption it can force
  alone is named (the environment's game of :mod:`gaitc.analysis.separation`, which
  ``lint`` and ``check`` report from any start);
* a goal that holds on every reachable transition (vacuous);
* regions, gaits and caches that no play staying in the winning region ever uses.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Final

from gaitc.analysis.ddmin import ddmin
from gaitc.analysis.oracle import Oracle
from gaitc.analysis.separation import separation
from gaitc.analysis.units import ASSUMPTION_SECTIONS, Unit, keep_only, units
from gaitc.core.spec import Spec
from gaitc.ir.cuddlib import cudd
from gaitc.ir.formula import FALSE
from gaitc.ir.spec import Clause, GR1Spec, Origin, Variable
from gaitc.solver.game import Game
from gaitc.solver.symbolic import BDDNode, SymbolicSpec
from ltlcompiler.encoding import EncodingName, make_encoding
from ltlcompiler.model import NO_GAIT, Model

_DUMMY = "gaitc_sanity_choice"
#: The code of the warning that the robot can force a broken assumption from every start
#: (``lint`` reports the same finding from the environment's game, with a forcing play).
NOT_WELL_SEPARATED: Final = "not-well-separated"


@dataclass(frozen=True)
class Warning_:
    """One sanity finding: a ``code`` (for JSON), a message and the units it concerns."""

    code: str
    message: str
    units: tuple[Unit, ...] = ()

    def to_json(self) -> dict[str, object]:
        return {"code": self.code, "message": self.message,
                "where": [u.where() for u in self.units]}


def _never_wins(spec: GR1Spec) -> GR1Spec:
    return spec.with_sections(sys_liveness=(Clause(FALSE, Origin("sanity: a goal never met")),))


def assumptions_unsatisfiable(spec: GR1Spec, oracle: Oracle) -> bool:
    """No play at all satisfies the assumptions, with every variable the environment's."""
    solo = GR1Spec(inputs=spec.inputs + spec.outputs, outputs=(Variable(_DUMMY),),
                   env_init=spec.env_init, env_trans=spec.env_trans,
                   env_liveness=spec.env_liveness, name=spec.name)
    return oracle.realizable(_never_wins(solo))


def unsatisfiable_core(spec: GR1Spec, oracle: Oracle) -> tuple[Unit, ...]:
    """A 1-minimal set of assumption units the environment cannot satisfy together (for a
    spec whose assumptions are unsatisfiable), by :func:`gaitc.analysis.ddmin.ddmin`."""

    def unsatisfiable(kept: tuple[Unit, ...]) -> bool:
        return assumptions_unsatisfiable(keep_only(spec, kept, ASSUMPTION_SECTIONS), oracle)

    return ddmin(units(spec, ASSUMPTION_SECTIONS), unsatisfiable)


def breakable_assumptions(spec: GR1Spec, oracle: Oracle) -> tuple[Unit, ...] | None:
    """None unless the robot can force a violation of the assumptions from every start
    (under the oracle's semantics); else the assumption units it can force alone (possibly
    none: only their combination).  Decided by the environment's game of
    :mod:`gaitc.analysis.separation`, the one well-separation check of gaitc."""
    found = separation(spec)
    if not found.forced_everywhere.get(oracle.semantics, False):
        return None
    named = {(a.section, a.index) for f in found.findings if f.alone for a in f.assumptions}
    return tuple(u for u in units(spec, ASSUMPTION_SECTIONS)
                 if any((u.section, i) in named for i in u.indices))


def _image(sym: SymbolicSpec, states: BDDNode, moves: BDDNode) -> BDDNode:
    """The successors of ``states`` along ``moves``, by one and_exists: the conjunction
    first, then the projection, took 56 of the 89 s of the explain tests' example specs."""
    pre = sym.pre_inputs | sym.pre_outputs
    return sym.unprime(cudd.and_exists(states, moves, pre))


def reachable(sym: SymbolicSpec, start: BDDNode, moves: BDDNode,
              settled: Callable[[BDDNode], bool] | None = None) -> BDDNode:
    """The states reachable from ``start`` along ``moves`` (a least fixpoint, breadth
    first).  ``settled`` sees each frontier (the start, then each step's new states) before
    it is explored: once it answers True, the search stops there, and the states found so
    far are returned (a caller that only asks whether something is ever reached stops as
    soon as it knows)."""
    seen = start
    frontier = start
    while frontier != sym.bdd.false:
        if settled is not None and settled(frontier):
            break
        new = _image(sym, frontier, moves) & ~seen
        seen |= new
        frontier = new
    return seen


def vacuous_goals(sym: SymbolicSpec) -> tuple[int, ...]:
    """Goals that hold on every transition of every play (θ, then ρe ∧ ρs).

    A goal is cleared by the first reachable transition that breaks it, and the search
    stops once every goal is cleared: in most specs each goal is broken within a few steps
    of the start, long before the reachable states are all found (radial12's took 11 s)."""
    moves = sym.env_trans & sym.sys_trans
    goals = {j: sym.translate(goal.formula) for j, goal in enumerate(sym.spec.sys_liveness)}

    def settled(frontier: BDDNode) -> bool:
        steps = frontier & moves
        for j in [j for j, goal in goals.items() if (steps & ~goal) != sym.bdd.false]:
            del goals[j]
        return not goals

    reach = reachable(sym, sym.env_init & sym.sys_init, moves, settled)
    if reach == sym.bdd.false:
        return ()
    return tuple(sorted(goals))


def unused_parts(sym: SymbolicSpec, model: Model,
                 encoding: EncodingName) -> dict[str, tuple[str, ...]]:
    """Regions, gaits and caches in no state that a play inside the winning region reaches.

    The search stops once every region and gait has been seen in a reached state (none is
    unused then), rather than finding every reachable state first."""
    winning = Game(sym).solve().winning
    moves = sym.env_trans & sym.sys_trans & sym.prime(winning)
    enc = make_encoding(model, encoding)
    unseen = {("regions", r.name): sym.translate(enc.region(r.name)) for r in model.regions}
    unseen.update({("gaits", g.name): sym.translate(enc.gait(g.name)) for g in model.gaits
                   if g.name != NO_GAIT})

    def settled(frontier: BDDNode) -> bool:
        for part in [p for p, states in unseen.items() if (frontier & states) != sym.bdd.false]:
            del unseen[part]
        return not unseen

    reachable(sym, sym.env_init & sym.sys_init & winning, moves, settled)
    regions = tuple(r.name for r in model.regions if ("regions", r.name) in unseen)
    gaits = tuple(g.name for g in model.gaits if ("gaits", g.name) in unseen)
    caches = tuple(c for c in model.caches if c in regions)
    return {"regions": regions, "gaits": gaits, "caches": caches}


#: Who a spec controls, in the words of explanations and warnings: a ``.gait`` spec's robot,
#: or the system of a spec without a robot model (``.slugsin``, ``.structuredslugs``).
ROBOT: Final = "robot"
SYSTEM: Final = "system"


def player_of(model: Model | None) -> str:
    """:data:`ROBOT` for a spec with a robot model, else :data:`SYSTEM`."""
    return ROBOT if model is not None else SYSTEM


def sanity(loaded: Spec, oracle: Oracle) -> tuple[Warning_, ...]:
    """Every sanity warning of a realizable spec (a ``.gait`` one's also in its robot's
    words: the regions, gaits and caches no winning play uses)."""
    spec, model = loaded.gr1, loaded.model
    found: list[Warning_] = []
    player = player_of(model)
    if assumptions_unsatisfiable(spec, oracle):
        core = unsatisfiable_core(spec, oracle)
        which = "; ".join(f"'{u.rule}' ({u.where()})" for u in core)
        found.append(Warning_("assumptions-unsatisfiable",
                              "the environment cannot satisfy its own assumptions, so every "
                              "guarantee is realizable: the spec says nothing"
                              + (f"; these cannot hold together: {which}" if which else ""),
                              core))
    else:
        broken = breakable_assumptions(spec, oracle)
        if broken is not None:
            which = "; ".join(f"'{u.rule}' ({u.where()})" for u in broken) or \
                "only the assumptions together"
            found.append(Warning_(NOT_WELL_SEPARATED,
                                  f"the {player} can force the environment to break an "
                                  f"assumption, so a controller may win by blocking it: {which}",
                                  broken))
    sym = SymbolicSpec(spec)
    for j in vacuous_goals(sym):
        rule = spec.sys_liveness[j].origin
        label = rule.rule if rule is not None else f"goal {j + 1}"
        found.append(Warning_("vacuous-goal", f"'{label}' holds on every step of every play: "
                              f"it asks nothing of the {player}"))
    if model is not None:
        for kind, names in unused_parts(sym, model, loaded.robot_encoding).items():
            if names:
                verb = {"regions": "enters region", "gaits": "uses gait",
                        "caches": "visits cache"}[kind]
                plural = "s" if len(names) > 1 else ""
                shown = ", ".join(names[:12]) + (f" and {len(names) - 12} more"
                                                  if len(names) > 12 else "")
                found.append(Warning_(f"unused-{kind}",
                                      f"no winning play ever {verb}{plural} {shown}"))
    return tuple(found)
