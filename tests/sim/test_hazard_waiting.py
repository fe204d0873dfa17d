"""The robot waits out a hazard it can wait out (issue 60, item 3), in every run loop.

A fresh monitor counts the moves into an active hazard that had a winning alternative, and
the count must be 0 in ``simulate``, ``play``, ``drive`` and after a recovery.  It shares no
code with :mod:`gaitc.solver.preferences`: the alternatives come from omega's own GR(1)
fixpoint (``omega.games.gr1``, through :mod:`peers.omega_game`) on the spec plus a
guarantee written here, stricter than the preference's: after a move the robot is in no
region of an active hazard, whatever its gait.  The hazards are avoided worst first
(those that fail the legs, then the graded ones by the levels they take), so a move into
hazard h counts when some move keeps to that guarantee for h and every worse hazard and
lands in the winning region of that game: then the preference, which ranks sets of
hazards worst first, had a move at least as good and had to take it.

The spec, tests/data/hazards/yard.gait: a forklift that breaks legs crosses the corridor
now and then (the robot survives a broken leg, so the plain strategy walks into it), a
graded spill may lie in front of a goal for good.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import pytest

import gaitc
from gaitc.api.driving import DriveOptions, SimulatedBoard
from gaitc.ir.formula import And, Not, Or, Var
from gaitc.ir.roles import Fails, WearsUpTo
from gaitc.ir.spec import Clause, GR1Spec
from gaitc.play.player import Autopilot
from gaitc.sim.run import Step
from ltlcompiler.model import GaitKind, Hazard, Model

omega_gr1 = pytest.importorskip("omega.games.gr1")
from peers.game import peer_game  # noqa: E402
from peers.omega_game import build_automaton, omega_names  # noqa: E402

YARD = Path(__file__).resolve().parents[1] / "data" / "hazards" / "yard.gait"


def worst_first(model: Model) -> list[Hazard]:
    """The hazards as the issue ranks them: failing ones first, then by the levels taken."""
    failing = [h for h in model.hazards if isinstance(h.harm, Fails)]
    graded = [h for h in model.hazards if isinstance(h.harm, WearsUpTo)]
    return failing + sorted(graded, key=lambda h: -_levels(h))


def _levels(hazard: Hazard) -> int:
    assert isinstance(hazard.harm, WearsUpTo)
    return hazard.harm.levels


class Alternatives:
    """Per hazard, omega's game of the spec in which the robot is never in a region of an
    active hazard of that one or a worse one; :meth:`exists` asks whether a move keeps to
    it from a state with a next input."""

    def __init__(self, spec: gaitc.Spec) -> None:
        assert spec.model is not None
        self.model = spec.model
        self.gr1 = spec.gr1
        self.inputs = [v.name for v in spec.gr1.inputs]
        self.walking = {g.name for g in self.model.gaits if g.kind is GaitKind.MOVE}
        self.regions = {h.name: set(h.regions) for h in self.model.hazards}
        ranked = worst_first(spec.model)
        self.games: dict[str, tuple[Any, Any, dict[str, str]]] = {}
        for k, hazard in enumerate(ranked):
            strict = _never_in(spec.gr1, ranked[:k + 1])
            game = peer_game(strict)
            aut = build_automaton(strict)
            winning, _, _ = omega_gr1.solve_streett_game(aut)
            names = omega_names(game)
            primed = aut.replace(winning, {n: n + "'" for n in names.values()})
            self.games[hazard.name] = (aut, aut.action["sys"] & primed, names)

    def exists(self, hazard: str, before: Step, after: Step) -> bool:
        """Whether, from ``before``'s state with ``after``'s inputs, a move keeps out of the
        active regions of ``hazard`` and every worse hazard and still wins."""
        aut, moves, names = self.games[hazard]
        was, now = dict(before.values), dict(after.values)
        values: dict[str, Any] = {names[n]: bool(v) for n, v in was.items()}
        values |= {names[n] + "'": bool(now[n]) for n in self.inputs}
        return bool(aut.let(values, moves) != aut.false)

    def _walks_in(self, step: Step) -> str | None:
        """The active hazard into one of whose regions ``step`` walks (with a gait that
        moves), or None."""
        hazard = step.hazard
        if hazard in self.regions and step.region in self.regions[hazard] \
                and step.gait in self.walking:
            return hazard
        return None

    def entries(self, steps: Sequence[Step]) -> dict[str, int]:
        """Per hazard, the moves of ``steps`` into one of its active regions with a gait
        that walks, that had an alternative (:meth:`exists`)."""
        count = {h.name: 0 for h in self.model.hazards}
        for before, after in itertools.pairwise(steps):
            hazard = self._walks_in(after)
            if hazard is not None and self.exists(hazard, before, after):
                count[hazard] += 1
        return count

    def walks_into(self, steps: Sequence[Step]) -> dict[str, int]:
        """Per hazard, every move into one of its active regions with a gait that walks."""
        count = {h.name: 0 for h in self.model.hazards}
        for step in steps[1:]:
            hazard = self._walks_in(step)
            if hazard is not None:
                count[hazard] += 1
        return count


def _never_in(spec: GR1Spec, hazards: Sequence[Hazard]) -> GR1Spec:
    """``spec`` with the guarantee that after each move the robot is in no region of an
    active hazard of ``hazards`` (onehot: a Boolean per hazard and per region)."""
    names = {v.name for v in spec.variables()}
    hot = []
    for hazard in hazards:
        assert hazard.name in names and set(hazard.regions) <= names
        hot += [And((Var(hazard.name, True), Var(region, True))) for region in hazard.regions]
    guarantee = Clause(Not(Or(tuple(hot)) if len(hot) > 1 else hot[0]))
    return spec.with_sections(sys_trans=(*spec.sys_trans, guarantee))


@pytest.fixture(scope="module")
def yard() -> gaitc.Spec:
    return gaitc.load(YARD)


@pytest.fixture(scope="module")
def alternatives(yard: gaitc.Spec) -> Alternatives:
    return Alternatives(yard)


NONE = {"forklift": 0, "spill": 0}


def test_the_monitor_sees_the_plain_strategy_walk_into_the_forklift(
        yard: gaitc.Spec, alternatives: Alternatives) -> None:
    """Without preferences the robot walks into the active forklift where it could wait:
    the monitor counts those moves (so it can fail), and the spill, which may lie on d for
    good, is never avoidable."""
    run = gaitc.simulate(yard, env="adversarial", steps=60, prefer="none")
    counted = alternatives.entries(run.steps)
    assert counted["forklift"] > 0
    assert counted["spill"] == 0


@pytest.mark.parametrize(("env", "seed"), [("random", 0), ("random", 1), ("adversarial", 0)])
def test_simulate_waits_out_the_forklift(yard: gaitc.Spec, alternatives: Alternatives,
                                         env: str, seed: int) -> None:
    run = gaitc.simulate(yard, env=env, steps=120, seed=seed)
    assert alternatives.entries(run.steps) == NONE
    walked = alternatives.walks_into(run.steps)
    assert walked["forklift"] == 0 and walked["spill"] > 0  # the spill is crossed


@pytest.mark.parametrize("env", ["random", "adversarial"])
def test_after_a_recovery_the_robot_still_waits(yard: gaitc.Spec, alternatives: Alternatives,
                                               env: str) -> None:
    run = gaitc.simulate(yard, env=env, steps=120, violate=["4:fail L4", "30:fail L1"])
    assert [s.outcome.value for s in run.surprises] == ["recovered", "recovered"]
    assert alternatives.entries(run.steps) == NONE


def test_play_waits_out_the_forklift(yard: gaitc.Spec, alternatives: Alternatives) -> None:
    player = gaitc.player(yard)
    player.autoplay(40, Autopilot.RANDOM, seed=3)
    player.break_assumption("fail L5")
    player.autoplay(40, Autopilot.RANDOM, seed=4)
    assert alternatives.entries(player.steps) == NONE
    assert alternatives.walks_into(player.steps)["spill"] > 0


def test_drive_waits_out_the_forklift(yard: gaitc.Spec, alternatives: Alternatives) -> None:
    driven = gaitc.drive(yard, board=SimulatedBoard(),
                         options=DriveOptions(steps=80, violate=("6:fail L6",)))
    assert driven.run is not None and len(driven.surprises) == 1
    assert alternatives.entries(driven.run.steps) == NONE


def test_the_symbolic_form_waits_too(yard: gaitc.Spec, alternatives: Alternatives) -> None:
    """The symbolic controller keeps the same moves as whole relations
    (:meth:`~gaitc.solver.preferences.MovePreferences.relation`)."""
    made = gaitc.synthesize(yard, form="symbolic")
    run = gaitc.simulate(yard, made, env="adversarial", steps=120,
                         violate=["4:fail L4"])
    assert alternatives.entries(run.steps) == NONE


def test_both_hazards_are_waited_out_when_both_go_away(tmp_path: Path) -> None:
    """With the spill promised to go away too, the robot waits out both hazards, the
    spill's alternatives being those that keep out of the forklift as well."""
    path = tmp_path / "yard_fair.gait"
    path.write_text(YARD.read_text(encoding="utf-8") + "assume always eventually !spill\n",
                    encoding="utf-8")
    spec = gaitc.load(path)
    alternatives = Alternatives(spec)
    for env in ("random", "adversarial"):
        run = gaitc.simulate(spec, env=env, steps=120, violate=["4:fail L4"])
        assert alternatives.entries(run.steps) == NONE
        assert alternatives.walks_into(run.steps) == NONE
    plain = gaitc.simulate(spec, env="random", steps=120, prefer="none")
    assert alternatives.entries(plain.steps)["spill"] > 0
