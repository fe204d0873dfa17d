"""What the environment needs to win: a minimal set of its freedoms, in robot terms.

The environment of a ``.gait`` spec may degrade leg Li while gait g is in use (eq. 3.5)
and switch hazard sets on (eqs. 3.8-3.9). Taking a freedom away adds an assumption: leg Li
keeps its health under g outside caches and active hazards, or hazard set H stays off.
Removing freedoms only weakens the environment, so ddmin finds a 1-minimal set with which it
still wins when every other freedom is taken away.
"""

from __future__ import annotations

from dataclasses import dataclass

from gaitc.analysis.ddmin import ddmin
from gaitc.analysis.oracle import Oracle
from gaitc.analysis.units import with_clauses
from gaitc.core.changes import HazardSwitch, LegWears
from gaitc.core.spec import Spec
from gaitc.ir.formula import Expr, Implies, Not, conj, disj, unreachable
from gaitc.ir.spec import Clause, GR1Spec, Origin
from ltlcompiler.encoding import Encoding, make_encoding
from ltlcompiler.model import GaitKind, Model


@dataclass(frozen=True)
class Freedom:
    """One freedom of the environment: a change it may make (:mod:`gaitc.core.changes`),
    a leg losing a level while ``gait`` is in use, or a hazard set switching on."""

    change: LegWears | HazardSwitch
    gait: str = ""

    @property
    def kind(self) -> str:
        """``degrade`` or ``hazard``: the freedom's kind in ``--json``."""
        return "degrade" if isinstance(self.change, LegWears) else "hazard"

    def describe(self) -> str:
        match self.change:
            case LegWears(leg):
                return f"degrade leg {leg} while gait {self.gait} is in use"
            case HazardSwitch(hazard):
                return f"switch hazard set {hazard} on"
            case _:
                unreachable(self.change)

    def to_json(self) -> dict[str, str]:
        out = {"kind": self.kind, "text": self.describe()}
        match self.change:
            case LegWears(leg):
                out.update(leg=leg, gait=self.gait)
            case HazardSwitch(hazard):
                out.update(hazard=hazard)
        return out


def freedoms(model: Model) -> tuple[Freedom, ...]:
    """Every freedom the spec gives its environment, in declaration order."""
    health = {leg.name: leg.health for leg in model.legs}
    out = [Freedom(LegWears(leg), gait.name)
           for gait in model.gaits if gait.kind is GaitKind.MOVE
           for leg in gait.legs if health[leg] > 1]
    out.extend(Freedom(HazardSwitch(h.name, True)) for h in model.hazards)
    return tuple(out)


def _restrictions(model: Model, enc: Encoding, taken: tuple[Freedom, ...]
                  ) -> dict[str, list[Clause]]:
    extra: dict[str, list[Clause]] = {"env_init": [], "env_trans": []}
    hot: Expr = disj(conj((enc.hazard(h.name), disj(enc.region(r) for r in h.regions)))
                     for h in model.hazards)
    away = [Not(enc.region(c)) for c in model.caches]
    for f in taken:
        origin = Origin(f"freedom taken away: {f.describe()}")
        match f.change:
            case LegWears(leg):
                guard = conj([enc.gait(f.gait), *away, *([Not(hot)] if model.hazards else [])])
                extra["env_trans"].append(Clause(Implies(guard, enc.keep_health(leg)), origin))
            case HazardSwitch(hazard):
                extra["env_init"].append(Clause(Not(enc.hazard(hazard)), origin))
                extra["env_trans"].append(Clause(Not(enc.hazard(hazard, True)), origin))
            case _:
                unreachable(f.change)
    return extra


def restricted(spec: Spec, taken: tuple[Freedom, ...]) -> GR1Spec:
    """The IR of ``spec`` (a ``.gait`` spec) with the freedoms ``taken`` away from the
    environment."""
    model = spec.robot
    return with_clauses(spec.gr1, _restrictions(model, make_encoding(model, spec.robot_encoding),
                                                taken))


def needed_freedoms(spec: Spec, oracle: Oracle, within: GR1Spec | None = None
                    ) -> tuple[Freedom, ...]:
    """A 1-minimal set of freedoms with which the environment still wins (``spec``, a
    ``.gait`` spec, must be unrealizable); every freedom outside it is taken away in the
    test. ``within``: the game to win instead of ``spec``'s own (a core of its guarantees,
    so that the freedoms are those the core needs); the environment then wins ``spec``
    with them too, since ``spec`` only adds guarantees."""
    every = freedoms(spec.robot)
    model = spec.robot
    enc = make_encoding(model, spec.robot_encoding)
    game = within if within is not None else spec.gr1

    def wins(kept: tuple[Freedom, ...]) -> bool:
        taken = tuple(f for f in every if f not in kept)
        return not oracle.realizable(with_clauses(game, _restrictions(model, enc, taken)))

    if wins(()):
        return ()
    return ddmin(every, wins)
