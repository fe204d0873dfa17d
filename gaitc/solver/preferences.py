"""Move preferences: which of the moves a GR(1) strategy allows the controller takes.

A GR(1) strategy may take any move of the first layer that covers the current state and
input (Bloem et al., JCSS 2012, Sect. 5); every such move keeps the rank discipline, so any
non-empty subset of them is still winning.  :class:`MovePreferences` narrows the candidate
set criterion by criterion, in the order asked for, keeping at each criterion the cheapest
candidates: the costs of :mod:`gaitc.ir.costs` (weighted terms over the move), and ``goal``,
the fewest Y rings between the next state and the goal pursued (the fixpoint's own
distance measure).  Issue 13; SLUGS's cost-annotated specs are the neighbouring idea.

With ``hazard`` it also avoids the hazards themselves, one by one, the worst first (the
terms of the ``hazard`` cost, one a hazard, :func:`ltlcompiler.costs.by_severity`).  For
sets S of hazards it solves the game whose moves never enter an active hazard of S
(:class:`Avoiding`), and ranks the sets lexicographically: S is better than S' when the
worst hazard in which they differ is in S, so avoiding the forklift that breaks legs comes
before avoiding any number of spills that wear them (issue 60).  At each state and next
input the controller takes a move of the best set it can keep to: inside that game's
winning region W_S its strategy (which never leaves W_S), else a move of ρs that avoids S
and enters W_S.  So it never enters an active hazard while some move avoids it and still
wins, unless that would give up a worse one.  The set kept to only gets better along a
run (a move of S's strategy stays in W_S, an entry goes to a better set), so after
finitely many changes one strategy is played for ever and the run wins as that game's
does: the composed controller is still winning, and the verifier checks it like any
other.
"""

from __future__ import annotations

import copy
import operator
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from itertools import combinations
from typing import Any, Final

from gaitc.diagnostics import UsageError
from gaitc.ir.bddwalk import Cofactors, cofactor, holds_at
from gaitc.ir.costs import Cost
from gaitc.ir.cuddlib import cudd
from gaitc.solver.game import Game, GameResult, Limits, goal_strategies
from gaitc.solver.steps import Steps, run_through
from gaitc.solver.symbolic import BDDNode, SymbolicSpec

#: Every preference, in the default order (``--prefer`` reorders or drops them).
PREFERENCES: Final = ("hazard", "health", "goal", "switches")
MEANINGS: Final = {
    "hazard": "do not enter a region of the active hazard set",
    "health": "lose the fewest health levels; use degraded legs last",
    "goal": "take the shortest way to the next goal (the fixpoint's Y rings)",
    "switches": "switch gait as rarely as possible",
}
NONE: Final = "none"
#: Past this many hazards that can each be avoided alone, the sets of two or more that
#: :class:`MovePreferences` solves a game for are only the worst k, for each k (all the
#: sets would be 2^n games).
ALL_SETS_UP_TO: Final = 4


def preference_order(asked: str | Iterable[str] | None) -> tuple[str, ...]:
    """The preferences ``asked`` names, in order: None is the default order, ``"none"`` (or
    an empty list) none at all, else a comma-separated text or a list of names."""
    if asked is None:
        return PREFERENCES
    names = [n.strip() for n in asked.split(",")] if isinstance(asked, str) else list(asked)
    if names == [NONE] or not names:
        return ()
    for name in names:
        if name not in PREFERENCES:
            raise UsageError(f"unknown preference '{name}'; use a comma-separated order of "
                             f"{', '.join(PREFERENCES)}, or '{NONE}'")
    if len(set(names)) != len(names):
        raise UsageError(f"a preference is named twice in '{','.join(names)}'")
    return tuple(names)


def fewer_moves(sym: SymbolicSpec, allowed: BDDNode) -> SymbolicSpec:
    """``sym`` with the system's moves cut to ``allowed`` (over the state and the next
    state): the game of the hazard-avoiding strategy, whose winning region lies inside
    ``sym``'s (:meth:`Game.solve`'s ``within``)."""
    strict = copy.copy(sym)
    strict.sys_trans = sym.sys_trans & allowed
    strict.game_sys_trans = sym.game_sys_trans & allowed
    strict.sys_clusters = []
    return strict


@dataclass(frozen=True)
class Avoiding:
    """The game in which the robot never enters an active hazard of a set: ``hazards``
    (indices into the ``hazard`` terms, worst first), its winning region (over the
    state), each goal's strategy, ``entering``: the moves of ρs that avoid those hazards
    and land in the winning region (over the state and the next state), and ``reach``:
    the states and next inputs where one of the two has a move (the strategy has one for
    every input ρe allows inside the winning region)."""

    hazards: tuple[int, ...]
    winning: BDDNode
    strategies: tuple[BDDNode, ...]
    entering: BDDNode
    reach: BDDNode  # a state and next input where it can be kept to: W ∨ ∃y'. entering

    def rank(self, count: int) -> tuple[bool, ...]:
        """The sort key that puts better sets first (see the module's docstring)."""
        return tuple(i not in self.hazards for i in range(count))


class MovePreferences:
    """The preferences of one extraction: term BDDs and the primed Y rings, built once."""

    def __init__(self, sym: SymbolicSpec, result: GameResult, costs: Sequence[Cost],
                 order: Sequence[str], limits: Limits | None = None) -> None:
        self.sym = sym
        self.order = tuple(order)
        self.winning = result.winning
        self.care: BDDNode | None = None  # where runs can be: see _simplified
        by_name = {c.name: c for c in costs}
        self.terms: dict[str, list[tuple[int, BDDNode]]] = {}
        for name in self.order:
            if name == "goal":
                continue
            cost = by_name.get(name)
            terms = [] if cost is None else cost.terms
            self.terms[name] = [(w, sym.translate(t)) for w, t in terms]
        self.goals = list(sym.sys_live)
        self.rings: list[list[BDDNode]] = []
        if "goal" in self.order:
            self.rings = [[sym.prime(y) for y in _distinct(rings)] for rings in result.rings]
        # The same cofactors, asked for at one state and input after another.
        self._fixed = {*sym.input_bits, *sym.output_bits, *sym.post_inputs}
        self._levels: dict[str, list[Cofactors]] = {}  # see levels
        self._goals_at = [Cofactors(sym.bdd, g, self._fixed) for g in self.goals]
        self._post_inputs = sorted(sym.post_inputs)
        self._relations: dict[int, tuple[BDDNode, BDDNode]] = {}  # goal: (strategy, moves)
        from gaitc.solver.canonical import REMEMBERED  # lazy: not on the path that only decides

        self._chosen: dict[tuple[int, BDDNode, Any], BDDNode] = {}  # see choose
        self._chosen_limit = REMEMBERED
        self._read_by_goal: dict[int, Callable[[Mapping[str, bool]], Any]] = {}
        #: The hazard-avoiding games won somewhere, the best set first (see the module's
        #: docstring): :meth:`allowed` and :meth:`relation` take, at each state and next
        #: input, the first one the robot can keep to.
        self.avoiding: list[Avoiding] = []
        hazard = self.terms.get("hazard", [])
        if hazard:
            found = by_name.get("hazard")
            names = (found.labels if found is not None and found.labels
                     else tuple(str(k + 1) for k in range(len(hazard))))
            self.avoiding = self._avoiding_games([t for _, t in hazard], names, limits)

    def _avoiding_games(self, hazards: Sequence[BDDNode], names: Sequence[str],
                        limits: Limits | None) -> list[Avoiding]:
        """The games that avoid sets of ``hazards`` (moves, worst first), each won
        somewhere, the best set first.  A set's winning region lies inside each of its
        subsets' (fewer moves win no more states), so a set is tried only when all of its
        one-smaller subsets are won somewhere, and its fixpoint starts from their
        intersection (:meth:`Game.solve`'s ``within``)."""
        solved: dict[tuple[int, ...], Avoiding] = {}
        alone = [i for i in range(len(hazards))
                 if self._avoiding((i,), hazards, names, self.winning, limits, solved)]
        for size in range(2, len(alone) + 1):
            sets = (combinations(alone, size) if len(alone) <= ALL_SETS_UP_TO
                    else [tuple(alone[:size])])
            for chosen in sets:
                within = self.winning
                for smaller in combinations(chosen, size - 1):
                    found = solved.get(smaller)
                    within = within & found.winning if found is not None else self.sym.bdd.false
                if within != self.sym.bdd.false:
                    self._avoiding(chosen, hazards, names, within, limits, solved)
        return sorted(solved.values(), key=lambda a: a.rank(len(hazards)))

    def _avoiding(self, chosen: tuple[int, ...], hazards: Sequence[BDDNode],
                  names: Sequence[str], within: BDDNode, limits: Limits | None,
                  solved: dict[tuple[int, ...], Avoiding]) -> bool:
        """Solve the game that avoids the hazards ``chosen`` (its winning region inside
        ``within``); keep it in ``solved`` when it is won somewhere."""
        sym = self.sym
        avoid = sym.bdd.true
        for i in chosen:
            avoid &= ~hazards[i]
        strict = fewer_moves(sym, avoid)
        purpose = "solving the game without entries into active hazards"
        if len(hazards) > 1:
            purpose += f" {', '.join(names[i] for i in chosen)}"
        result = Game(strict, limits, purpose).solve(keep_layers=True, within=within)
        if result.winning == sym.bdd.false:
            return False
        kept = sym.sys_trans & avoid
        landing = sym.prime(result.winning)
        entering = kept & landing
        reach = result.winning | cudd.and_exists(kept, landing, sym.post_outputs)
        solved[chosen] = Avoiding(chosen, result.winning,
                                  tuple(goal_strategies(strict, result)), entering, reach)
        return True

    def allowed(self, at: Mapping[str, bool], goal: int, moves: BDDNode) -> BDDNode:
        """The moves to choose from at the state ``at`` (pre variables) for goal ``goal``,
        a BDD over the next inputs and outputs: for each next input, those of the best
        hazard-avoiding game the robot can keep to (its strategy's inside its winning
        region, else its entries), else ``moves``, the strategy's own."""
        bdd = self.sym.bdd
        chosen, met = bdd.false, bdd.false  # the moves taken, and the next inputs they cover
        for game in self.avoiding:
            if holds_at(game.winning, at):  # a move for every input ρe allows
                return chosen | (bdd.let(dict(at), game.strategies[goal]) & ~met)
            here = bdd.let(dict(at), game.entering) & ~met
            if here != bdd.false:
                chosen |= here
                met |= bdd.exist(self.sym.post_outputs, here)
        return chosen | (moves & ~met)

    def choose(self, at: Mapping[str, bool], goal: int, choices: BDDNode) -> BDDNode:
        """The preferred non-empty part of ``choices`` (a BDD over the primed outputs, the
        moves allowed at the state and next input ``at``) for the goal index ``goal``.

        Remembered by the goal, ``choices`` and the values in ``at`` of the bits the
        criteria read (:meth:`_reads`): nothing else of ``at`` reaches the answer, so a
        remembered one is the one :meth:`_choose` would compute (five-arm courier: 29,476
        calls, 15,775 distinct)."""
        key = (goal, choices, self._reads(goal)(at))
        found = self._chosen.get(key)
        if found is None:
            if len(self._chosen) >= self._chosen_limit:
                self._chosen.clear()
            found = self._chosen[key] = self._choose(at, goal, choices)
        return found

    def _reads(self, goal: int) -> Callable[[Mapping[str, bool]], Any]:
        """The values :meth:`_choose` reads of a state and next input, for goal ``goal``:
        the bits of the cost levels' cofactors (:meth:`_cheapest`), and of the goal's and
        the next inputs (:meth:`_nearest`)."""
        found = self._read_by_goal.get(goal)
        if found is None:
            bits: set[str] = set()
            for name in self.order:
                if name == "goal":
                    bits |= {*self._goals_at[goal].names, *self._post_inputs}
                else:
                    bits |= {n for level in self._levels_at(name) for n in level.names}
            names = sorted(bits)
            found = self._read_by_goal[goal] = (
                operator.itemgetter(*names) if names else lambda _: ())
        return found

    def _choose(self, at: Mapping[str, bool], goal: int, choices: BDDNode) -> BDDNode:
        """:meth:`choose`, computed."""
        for name in self.order:
            if name == "goal":
                choices = self._nearest(at, goal, choices)
            else:
                choices = self._cheapest(at, name, choices)
        return choices

    # ------------------------------------------------------------ whole relations
    def relation(self, goal: int, strategy: BDDNode) -> BDDNode:
        """The preferred part of goal ``goal``'s move relation ``strategy`` (over the state
        and the primed inputs and outputs), for a symbolic controller: at every state and
        input it holds exactly the moves :meth:`allowed` and :meth:`choose` leave an
        explicit extraction.  So a runtime
        that takes the smallest move of this relation makes the explicit controller's
        moves (tests/solver/test_symbolic_controller.py compares them step by step)."""
        return run_through(self.relation_steps(goal, strategy))

    def relation_steps(self, goal: int, strategy: BDDNode) -> Steps[BDDNode]:
        """:meth:`relation` in steps of a few BDD operations each (for a census running
        alongside an extraction, :mod:`gaitc.solver.census`); kept per goal, so that a census
        and then a symbolic controller pay for it once."""
        known = self._relations.get(goal)
        if known is not None and known[0] == strategy:
            return known[1]
        moves = self._simplified(strategy)
        if self.avoiding:
            moves = yield from self._avoiding_relation(goal, moves)
        # ρe never names a next output (gaitc.solver.synthesis checks it), so every move of the
        # strategy keeps it: the explicit extraction's preference for such moves is moot.
        for name in self.order:
            if name == "goal":
                moves = yield from self._nearest_relation(goal, moves)
            else:
                moves = yield from self._first_met(moves, self.levels(name))
            moves = self._simplified(moves)
        self._relations[goal] = (strategy, moves)
        return moves

    def _avoiding_relation(self, goal: int, strategy: BDDNode) -> Steps[BDDNode]:
        """:meth:`allowed` at every state and input at once: per game, best first, its moves
        where the robot can keep to it and no better game, else ``strategy``'s.

        Built from the worst game outwards as if-then-elses (the halves as conjunctions can
        be a hundred times larger: thesis 10 x 10 health 3, 3 million nodes each, 10 s),
        every part, the conditions too, simplified where it decides: where a run can be
        and no better game can be kept to.  The best game is usually kept to almost
        everywhere, so the worse ones shrink to little.  Hexapod warehouse, 3 games: the
        best game's if-then-else had 1.1 million nodes and took 6.5 s with unsimplified
        conditions, and has 13,228 and takes 0.2 s so."""
        bdd = self.sym.bdd
        self._simplified(bdd.false)  # makes self.care
        assert self.care is not None
        cares = [self.care]  # where the i-th game decides, if it can be kept to
        for game in self.avoiding:
            cares.append(cares[-1] & ~game.reach)
            yield
        deciding = len(self.avoiding)
        while deciding > 0 and cares[deciding - 1] == bdd.false:
            deciding -= 1  # no state is left for this game: the better ones cover all
        moves = _kept(strategy, cares[deciding])
        for k in range(deciding - 1, -1, -1):
            game, care = self.avoiding[k], cares[k]
            where = care & game.reach
            inside = bdd.ite(_kept(game.winning, where),
                             _kept(game.strategies[goal], where & game.winning),
                             _kept(game.entering, where & ~game.winning))
            yield
            moves = _kept(bdd.ite(_kept(game.reach, care), _kept(inside, where), moves), care)
            yield
        return moves

    def _simplified(self, moves: BDDNode) -> BDDNode:
        """``moves`` unchanged where a run can be (a winning state, an input ρe allows),
        free elsewhere: CUDD's restrict often shrinks the BDD there, else it is kept."""
        if self.care is None:
            sym = self.sym
            self.care = self.winning & sym.bdd.exist(sym.post_outputs, sym.env_trans)
        return _kept(moves, self.care)

    def levels(self, name: str) -> list[BDDNode]:
        """The moves by the cost criterion ``name`` gives them, cheapest first: per cost, the
        assignments to the variables its terms read (a leg's health, the gait outputs) on
        which the weights of the terms that hold add up to it, among those some move of ρs
        makes (every strategy's moves are moves of ρs).

        Built once, on that projection of ρs, where each split is of a small BDD: splitting
        the strategy's move relation itself took 12 s for thesis 10 x 10 health 3's 32
        health terms."""
        return [level.u for level in self._levels_at(name)]

    def _levels_at(self, name: str) -> list[Cofactors]:
        """:meth:`levels`, each with its remembered cofactors (built on the first call)."""
        known = self._levels.get(name)
        if known is None:
            bdd, trans = self.sym.bdd, self.sym.sys_trans
            read: set[str] = set()
            for _, term in self.terms[name]:
                read |= bdd.support(term)
            buckets: dict[int, BDDNode] = {0: bdd.exist(bdd.support(trans) - read, trans)}
            for weight, term in self.terms[name]:
                moved: dict[int, BDDNode] = {}
                for cost, part in buckets.items():
                    for key, piece in ((cost + weight, part & term), (cost, part & ~term)):
                        if piece != bdd.false:
                            moved[key] = moved.get(key, bdd.false) | piece
                buckets = moved
            known = self._levels[name] = [Cofactors(bdd, buckets[c], self._fixed)
                                          for c in sorted(buckets)]
        return known

    def _nearest_relation(self, goal: int, moves: BDDNode) -> Steps[BDDNode]:
        """:meth:`_nearest` at every state and input at once."""
        rings = self.rings[goal] if goal < len(self.rings) else []
        return (yield from self._first_met(moves, [self.goals[goal], *rings, self.sym.bdd.true]))

    def _first_met(self, moves: BDDNode, parts: Sequence[BDDNode]) -> Steps[BDDNode]:
        """Per state and input, the moves of the first ``moves ∧ part`` that has any there.

        Each tier and the moves chosen so far are kept simplified (thesis robot A, all
        preferences of both goals: 5 s instead of 17 s; an and_exists for the states met,
        or the choice as one if-then-else, was slower)."""
        bdd = self.sym.bdd
        chosen, met = bdd.false, bdd.false
        for part in parts:
            tier = self._simplified(moves & part)
            chosen = self._simplified(chosen | (tier & ~met))
            met |= bdd.exist(self.sym.post_outputs, tier)
            yield
        return chosen

    # ------------------------------------------------------------ one state and input
    def _cheapest(self, at: Mapping[str, bool], name: str, choices: BDDNode) -> BDDNode:
        """The candidates of least cost by criterion ``name`` (:meth:`levels`)."""
        false = self.sym.bdd.false
        for level in self._levels_at(name):
            cheapest = choices & level.at(at)
            if cheapest != false:
                return cheapest
        return choices

    def _nearest(self, at: Mapping[str, bool], goal: int, choices: BDDNode) -> BDDNode:
        """The candidates that reach the goal on this move, else those whose next state
        lies in the lowest Y ring (rings grow, so a binary search finds it)."""
        bdd = self.sym.bdd
        reach = choices & self._goals_at[goal].at(at)
        if reach != bdd.false:
            return reach
        rings = self.rings[goal] if goal < len(self.rings) else []
        if not rings:
            return choices
        # The rings are large BDDs over the next inputs and outputs, and cofactors of them
        # by the next input are rarely asked twice: the choices are cut to the input's cube
        # instead, and each test is a conjunction whose result stays small (thesis 10 x 10
        # health 4: 3.2 s of 10.6 s went to those cofactors).
        inputs = {k: at[k] for k in self._post_inputs}
        here = choices & bdd.cube(inputs)
        low, high = 0, len(rings)  # the answer is the first ring meeting choices (or none)
        while low < high:
            mid = (low + high) // 2
            if here & rings[mid] != bdd.false:
                high = mid
            else:
                low = mid + 1
        if low == len(rings):
            return choices
        met = here & rings[low]
        return cofactor(bdd, inputs, met)


def _kept(moves: BDDNode, care: BDDNode) -> BDDNode:
    """``moves`` where ``care`` holds, free elsewhere: CUDD's restrict when it is smaller."""
    smaller = cudd.restrict(moves, care)
    return smaller if len(smaller) < len(moves) else moves


def _distinct(rings: Sequence[BDDNode]) -> list[BDDNode]:
    """The rings without repeats (the last Y iteration repeats the fixpoint)."""
    out: list[BDDNode] = []
    for ring in rings:
        if not out or ring != out[-1]:
            out.append(ring)
    return out
