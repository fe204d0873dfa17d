"""Recovery: where a run goes after the environment breaks an assumption.

A GR(1) controller promises its goals only while the environment keeps ρe.  When an
observed input breaks it (a leg failing while not in use, a spill where none could be),
the robot's next move is decided here, after the intermittent-violation view of Ehlers and
Topcu ("Resilience to intermittent assumption violations in reactive synthesis", HSCC
2014): the surprise is a jump of the game to another state, after which the environment
keeps its assumptions again.  So the question is only where the jump lands:

- **recovered**: some move y' that ρs allows from the state before, with the surprising
  inputs x', lands in the winning region W of the spec's game.  The robot takes it and
  goes on with the game's strategy from there (the per-goal relations of
  :func:`gaitc.solver.game.goal_strategies`, run by :class:`~gaitc.sim.symbolic_view.
  SymbolicStrategy`), which keeps every guarantee from then on.
- **degraded**: no such move exists, but one lands in the winning region of the game with
  only some of the goals (the same goal-dropped variants explain uses to say which goal is
  lost first, :mod:`gaitc.analysis.units`): the largest such set of goals, ties broken by
  the goals' order, is pursued from then on.  A goal not achievable alone from the state
  is in no such set, so the singletons are tried first and the larger sets only among the
  goals that pass (at most :data:`MAX_GOAL_SETS` sets of two or more goals; a spec with
  more goals than that allows keeps a single goal past it; docs/background/recovery.md).
- **stopped**: no goal is achievable; the robot heads for a cache when reaching one can be
  guaranteed (the game whose one goal is "in a cache"), and stops there, or stops at once.

Each game's controller keeps the run's move preferences (:mod:`gaitc.solver.preferences`,
the default order unless told): after a surprise the robot still waits out a hazard it can
wait out, and its entry into the winning region is a move of the best hazard-avoiding game
it can enter, when there is one (issue 60).

The games are solved without the care set (:class:`~gaitc.solver.options.Options`
``care=False``): after a surprise the state may lie outside the invariants ρe keeps, where
the care-set solution is not exact.  Each winning region depends on the set of goals only,
not on the state, so each game is solved once per run (at most 2^n games for n goals; in
practice n + 2).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from itertools import combinations
from typing import Any, Final

from gaitc.core.modes import Outcome
from gaitc.diagnostics import Span
from gaitc.ir.bddfile import materialize, node_table
from gaitc.ir.bddwalk import first_assignment
from gaitc.ir.costs import Cost
from gaitc.ir.formula import Or
from gaitc.ir.spec import Clause, GR1Spec, Origin, Semantics
from gaitc.sim.domain import Domain
from gaitc.sim.symbolic_view import SymbolicStrategy
from gaitc.solver.canonical import spec_integers
from gaitc.solver.game import Game
from gaitc.solver.preferences import PREFERENCES, MovePreferences
from gaitc.solver.symbolic import Options, SymbolicSpec
from gaitc.solver.symbolic_strategy import symbolic_controller
from ltlcompiler.costs import model_costs
from ltlcompiler.encoding import make_encoding

#: The most goal sets of two or more goals a surprise tries (each a game solved once per
#: run); past it, the larger sets are skipped and the best single goal is kept.
MAX_GOAL_SETS: Final = 256


@dataclass(frozen=True)
class Entry:
    """Where a run goes on after a surprise: the outcome, the goals kept (indices into the
    spec's □◇ guarantees), the strategy and its node to continue from (None: stop now), the
    cache a stopped robot heads for."""

    outcome: Outcome
    kept: tuple[int, ...]
    strategy: SymbolicStrategy | None = None
    node: int | None = None
    cache: tuple[str, ...] = ()


@dataclass(frozen=True)
class _Solved:
    """One game won somewhere: its strategy as a run steps it, and the moves that enter its
    winning region, ρs ∧ W', in the runtime's manager (the solver's manager is dropped once
    the controller is built, so no BDD outlives its manager)."""

    runtime: SymbolicStrategy
    entering: Any
    avoiding: tuple[Any, ...]  # the entries of the hazard-avoiding games, best first
    bits: Mapping[str, tuple[str, ...]]  # each spec variable's bits, least significant first
    lows: Mapping[str, int]  # each integer variable's lowest value


@dataclass
class Fallback:
    """The games a run falls back on after surprises, each solved when first needed."""

    spec: GR1Spec
    domain: Domain
    semantics: Semantics = Semantics.DEFAULT
    prefer: tuple[str, ...] = PREFERENCES  # the move preferences of the games' strategies
    _games: dict[tuple[str, ...], _Solved | None] = field(default_factory=dict, repr=False)
    _costs: tuple[Cost, ...] | None = field(default=None, repr=False)  # written once a run

    @property
    def goals(self) -> int:
        return len(self.spec.sys_liveness)

    def enter(self, before: Sequence[int], inputs: Mapping[str, int], pursuing: int = 0,
              caches: bool = True) -> Entry:
        """Where the run goes when the state was ``before`` (spec-level values, in the
        spec's variable order) and the environment gave ``inputs``: all goals if that can
        be won, else the largest set of goals, else a cache (``caches``), else stop."""
        every = tuple(range(self.goals))
        for kept in self._candidates(before, inputs):
            found = self._entry(self._liveness(kept), before, inputs, pursuing, kept)
            if found is not None:
                outcome = Outcome.RECOVERED if kept == every else Outcome.DEGRADED
                strategy, node = found
                return Entry(outcome, kept, strategy, node)
        cached = self.domain.model.caches
        if caches and cached:
            goal = Clause(Or(tuple(self._region(c) for c in cached)) if len(cached) > 1
                          else self._region(cached[0]),
                          Origin("stopping: in a cache"))
            found = self._entry((goal,), before, inputs, 0, ())
            if found is not None:
                return Entry(Outcome.STOPPED, (), found[0], found[1], tuple(cached))
        return Entry(Outcome.STOPPED, ())

    def achievable(self, before: Sequence[int], inputs: Mapping[str, int],
                   kept: Sequence[int]) -> bool:
        """Whether a move from ``before`` with ``inputs`` lands in the winning region of the
        game with the goals ``kept`` only (tests and reports re-ask this)."""
        return self._entry(self._liveness(tuple(kept)), before, inputs, 0, tuple(kept)) \
            is not None

    # ------------------------------------------------------------------ the search
    def _candidates(self, before: Sequence[int], inputs: Mapping[str, int]
                    ) -> list[tuple[int, ...]]:
        """Goal sets to try, largest first (then in the goals' order): all goals, then the
        subsets of the goals achievable alone."""
        every = tuple(range(self.goals))
        if not every:
            return []
        if self._entry(self._liveness(every), before, inputs, 0, every) is not None:
            return [every]
        alone = [j for j in every
                 if self._entry(self._liveness((j,)), before, inputs, 0, (j,)) is not None]
        out: list[tuple[int, ...]] = []
        for size in range(len(alone), 1, -1):
            sets = [kept for kept in combinations(alone, size) if len(kept) < len(every)]
            if len(out) + len(sets) > MAX_GOAL_SETS:
                break  # too many sets of this size to solve: the singletons stand in
            out.extend(sets)
        return out + [(j,) for j in alone]

    def _liveness(self, kept: tuple[int, ...]) -> tuple[Clause, ...]:
        return tuple(self.spec.sys_liveness[j] for j in kept)

    def _region(self, name: str) -> Any:
        return make_encoding(self.domain.model, self.domain.encoding).region(name)

    def _game(self, liveness: tuple[Clause, ...]) -> _Solved | None:
        key = tuple(str(c.formula) for c in liveness)
        if key in self._games:
            return self._games[key]
        variant = self.spec.with_sections(sys_liveness=liveness)
        sym = SymbolicSpec(variant, Options(care=False))
        result = Game(sym, purpose="solving the fallback game").solve(keep_layers=True)
        solved = None
        if result.winning != sym.bdd.false:
            prefer = None
            if self.prefer:
                if self._costs is None:
                    self._costs = model_costs(self.domain.model, self.domain.encoding)
                prefer = MovePreferences(sym, result, self._costs, self.prefer)
            ctrl = symbolic_controller(sym, result, self.semantics, prefer)
            avoiding = [] if prefer is None else [g.entering for g in prefer.avoiding]
            order, nodes, refs = node_table(sym.bdd, {
                "entering": sym.sys_trans & sym.prime(result.winning), "avoiding": avoiding})
            runtime = SymbolicStrategy(ctrl, variant, "<fallback>")
            extra = replace(ctrl, order=order, nodes=nodes, roots=refs)
            made = materialize(runtime.bdd, extra)
            integers = spec_integers(sym)
            solved = _Solved(runtime, made["entering"], tuple(made["avoiding"]),
                             {name: tuple(bits) for name, bits in sym.var_bits.items()},
                             {name: iv.low for name, iv in integers.items()
                              if len(iv.bits) == len(sym.var_bits.get(name, ()))})
        self._games[key] = solved
        return solved

    def _entry(self, liveness: tuple[Clause, ...], before: Sequence[int],
               inputs: Mapping[str, int], pursuing: int, kept: tuple[int, ...]
               ) -> tuple[SymbolicStrategy, int] | None:
        """The node of the game's strategy that a move from ``before`` with ``inputs``
        enters, in the winning region (None: no move ρs allows lands there): a move into
        the best hazard-avoiding game's winning region that avoids its hazards, if any."""
        solved = self._game(liveness)
        if solved is None:
            return None
        runtime = solved.runtime
        names = tuple(v.name for v in self.spec.variables())
        was = dict(zip(names, before, strict=True))
        now = was | {k: int(v) for k, v in inputs.items()}
        ins = {b for v in self.spec.inputs for b in solved.bits[v.name]}
        pre = _bits(solved, was)
        post_in = {b + "'": value for b, value in _bits(solved, now).items() if b in ins}
        outs = list(runtime.post_out)
        for entering in (*solved.avoiding, solved.entering):
            moves = runtime.bdd.let(pre | post_in, entering)
            try:
                y = first_assignment(runtime.bdd, moves, outs, runtime.rank)
            except ValueError:  # the relation reads bits outside the state: no move to take
                return None
            if y is not None:
                break
        else:
            return None
        state = {b.removesuffix("'"): bool(v) for b, v in post_in.items()}
        state |= {b.removesuffix("'"): bool(v) for b, v in zip(outs, y, strict=True)}
        goal = kept.index(pursuing) if pursuing in kept else 0
        return runtime, runtime.enter(state, goal)


def _bits(solved: _Solved, values: Mapping[str, int]) -> dict[str, bool]:
    """The bits of spec-level ``values`` (integers as offsets from their lowest value)."""
    out: dict[str, bool] = {}
    for name, bits in solved.bits.items():
        value = int(values.get(name, 0)) - solved.lows.get(name, 0)
        if name in solved.lows:
            out.update({b: bool((value >> k) & 1) for k, b in enumerate(bits)})
        else:
            out[bits[0]] = bool(value)
    return out


def fallback_span(spec: GR1Spec, index: int) -> Span | None:
    """The source of □◇ guarantee ``index`` (for reports)."""
    origin = spec.sys_liveness[index].origin
    return origin.span if origin is not None else None
