"""A compact controller that survives broken assumptions: recovery and fallback tables.

The intermittent-violation view of Ehlers and Topcu ("Resilience to intermittent assumption
violations in reactive synthesis", HSCC 2014), as :mod:`gaitc.sim.recovery` runs it on a
host, written as decision diagrams a board can hold (the extraction of
:mod:`gaitc.compact.extraction`, Bloem et al., JCSS 78(3) 2012, Sect. 5, over wider care
sets).  The spec's game is solved without the care set (``Options(care=False)``, as the
host runtime does: after a surprise the state may lie outside the invariants ρe keeps),
giving the winning region W and the per-goal relations.  Then:

* **recovered**: ``recoverable(s, x')`` is exactly ``¬ρe ∧ ∃y'. ρs ∧ W'`` on every state s
  the controller can be in, and ``recover(s, x')`` gives such a y'.  The care set of the
  move diagrams is closed under the strategy from every state a recovery lands in (a
  fixpoint: a state reached after a recovery may meet another surprise).
* **degraded**: for the single-field surprises (:class:`SurpriseClass`: a leg failing, a
  leg losing a level, the hazard switching) that are not recoverable, the largest set of
  goals K whose game has a move into its winning region W_K (sizes down, then the goals'
  order, as :meth:`gaitc.sim.recovery.Fallback.enter` chooses), each as further diagrams:
  a flag "this fallback applies", the entry move, and K's moves and goal diagrams.
* **stopped**: any other surprise, and every surprise once degraded: the robot stops (the
  board vents).  Heading for a cache first, as the host runtime may, is left out.

Every diagram shares one node table; :class:`RecoveringRunner` is the reference the
generated C (:mod:`gaitc.codegen.emitter`) must match step for step, and
:func:`gaitc.verifier.recovery.verify_recovery` proves the recovery part.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from itertools import combinations
from typing import TYPE_CHECKING, TypeAlias

from gaitc.compact.controller import CompactController, relations, to_symbolic
from gaitc.compact.diagram import (
    DONT_CARE,
    Builder,
    Ref,
    TooLarge,
    evaluate,
    leaf,
    reachable_nodes,
)
from gaitc.compact.extraction import (
    FieldOrder,
    counter_moves,
    field_domain,
    reachable_from,
    slot_order,
)
from gaitc.core.changes import Change, HazardSwitch, LegFails, LegRepaired, LegWears
from gaitc.core.modes import Outcome
from gaitc.core.vocabulary import HAZARD_FIELD, Field, Vocabulary
from gaitc.diagnostics.choices import Choice
from gaitc.ir.bddfile import materialize
from gaitc.ir.formula import unreachable
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.solver.canonical import spec_integers
from gaitc.solver.game import Game, goal_strategies
from gaitc.solver.symbolic import Options, SymbolicSpec
from gaitc.solver.symbolic_strategy import symbolic_controller
from gaitc.verifier.recovery import FallbackRelations, RecoveryRelations, verify_recovery

if TYPE_CHECKING:
    from dd.cudd import BDD, Function

    from gaitc.compact.controller import Relations
    from gaitc.ir.controller import IntegerVar
    from gaitc.solver.symbolic import SymbolicSpec
    from gaitc.verifier.recovery import RecoveryRelations
    from gaitc.verifier.strategy import VerificationReport


@dataclass(frozen=True)
class FieldSwitch:
    """A plain spec's input ``field`` taking another value (a spec with no robot words)."""

    field: str

    def told(self) -> str:
        return f"{self.field} switches"


#: A class of single-field surprises: a change of the robot's environment
#: (:mod:`gaitc.core.changes`: a leg failing or losing levels, a hazard set switching), or
#: a plain spec's input switching.  Its surprises are the (state, inputs) pairs where that
#: field makes the change, every other input stays, and ρe is broken.
SurpriseClass: TypeAlias = Change | FieldSwitch


def told(surprise: SurpriseClass) -> str:
    """A surprise class in the robot's words (``L3 fails where the assumptions forbid it``)."""
    return f"{surprise.told()} where the assumptions forbid it"


@dataclass(frozen=True)
class Degraded:
    """The fallback to the goals ``kept`` (indices into the spec's □◇ guarantees): roots
    into the shared node table."""

    kept: tuple[int, ...]
    applies_root: Ref  # boolean on (s, x'): this fallback is the one to take
    entry_root: Ref  # move on (s, x'): the move into W_K
    move_roots: tuple[Ref, ...]  # per kept goal
    reached_roots: tuple[Ref, ...]  # per kept goal

    @property
    def mask(self) -> int:
        return sum(1 << j for j in self.kept)

    @property
    def roots(self) -> tuple[Ref, ...]:
        return (self.applies_root, self.entry_root, *self.move_roots, *self.reached_roots)


@dataclass(frozen=True)
class ClassReport:
    """What a surprise class gets: how many of its surprises recover, which fallbacks the
    others take and how many stop (counted as (state, inputs) pairs of the field values)."""

    surprise: SurpriseClass
    recovered: int
    degraded: Mapping[int, int]  # fallback index -> surprises taking it
    stopped: int
    included: bool = True  # False: its fallbacks left out of the tables (it stops)


@dataclass(frozen=True)
class RecoveringController:
    """A compact controller plus its recovery and fallback diagrams (one node table)."""

    base: CompactController  # its nodes and moves are the shared table
    recoverable_root: Ref
    recover_root: Ref
    fallbacks: tuple[Degraded, ...]
    classes: tuple[ClassReport, ...] = ()

    @property
    def extra_roots(self) -> tuple[Ref, ...]:
        """The roots past the base controller's, in the generated tables' order."""
        out = [self.recoverable_root, self.recover_root]
        for fb in self.fallbacks:
            out += fb.roots
        return tuple(out)

    @property
    def goal_count(self) -> int:
        return self.base.goal_count

    def decisions(self, roots: Sequence[Ref]) -> int:
        return len(reachable_nodes(self.base.nodes, roots))

    def without_fallbacks(self, count: int) -> RecoveringController:
        """Only the first ``count`` fallbacks; the surprises of the others stop.  (A prefix:
        each fallback's flag is exact on the surprises no earlier fallback takes, and may
        say anything on those, so an earlier one cannot be left out alone.)"""
        kept = self.fallbacks[:count]
        classes = tuple(replace(c, included=all(k < count for k in c.degraded))
                        for c in self.classes)
        return replace(self, fallbacks=kept, classes=classes)


# ------------------------------------------------------------------------ the runtime
@dataclass(frozen=True)
class Step:
    """One step of :class:`RecoveringRunner`: the outcome (ALLOWED: no surprise), the move
    index (None: stopped) and the goals pursued from now on (a bit per spec goal)."""

    outcome: Outcome
    move: int | None
    kept_mask: int


class RecoveringRunner:
    """A recovering controller run step by step, as the generated C runs it: the field
    values, the goal counter and the mode (-1 normal, k fallback k, STOP stopped)."""

    NORMAL = -1
    STOP = -2

    def __init__(self, rc: RecoveringController, first: Mapping[str, int]) -> None:
        ctrl = rc.base
        self.rc = rc
        self.state = dict(first) | ctrl.first(first) \
            if ctrl.semantics == Semantics.DEFAULT else dict(first)
        self.goal = 0
        self.mode = self.NORMAL

    @property
    def kept_mask(self) -> int:
        if self.mode == self.NORMAL:
            return (1 << self.rc.goal_count) - 1
        if self.mode == self.STOP:
            return 0
        return self.rc.fallbacks[self.mode].mask

    def _walk(self, root: Ref, chosen: Mapping[str, int]) -> int:
        ctrl = self.rc.base
        return evaluate(ctrl.nodes, root, ctrl.slot_values(self.state, chosen))

    def _advance(self, reached: Sequence[Ref]) -> None:
        n = len(reached)
        for _ in range(n):
            if not self._walk(reached[self.goal], {}):
                break
            self.goal = (self.goal + 1) % n

    def _move(self, move: int, chosen: Mapping[str, int]) -> None:
        outs = self.rc.base.vocabulary.outputs
        values = dict(zip((f.name for f in outs), self.rc.base.moves[move], strict=True))
        self.state = dict(self.state) | dict(chosen) | values

    def step(self, chosen: Mapping[str, int]) -> Step:
        """The environment chose ``chosen`` (field name -> value index)."""
        rc, ctrl = self.rc, self.rc.base
        if self.mode == self.STOP:
            return Step(Outcome.STOPPED, None, 0)
        assumed = ctrl.assumed_root is None or self._walk(ctrl.assumed_root, chosen) == 1
        if self.mode == self.NORMAL:
            if assumed:
                return self._play(ctrl.move_roots, ctrl.reached_roots, chosen, Outcome.ALLOWED)
            if self._walk(rc.recoverable_root, chosen):
                return self._play((rc.recover_root,) * len(ctrl.move_roots),
                                  ctrl.reached_roots, chosen, Outcome.RECOVERED)
            for k, fb in enumerate(rc.fallbacks):
                if self._walk(fb.applies_root, chosen):
                    move = self._walk(fb.entry_root, chosen)
                    self._move(move, chosen)
                    self.mode, self.goal = k, 0
                    return Step(Outcome.DEGRADED, move, fb.mask)
        elif assumed:
            fb = rc.fallbacks[self.mode]
            return self._play(fb.move_roots, fb.reached_roots, chosen, Outcome.ALLOWED)
        self.mode = self.STOP
        return Step(Outcome.STOPPED, None, 0)

    def _play(self, moves: Sequence[Ref], reached: Sequence[Ref], chosen: Mapping[str, int],
              outcome: Outcome) -> Step:
        move = self._walk(moves[self.goal], chosen)
        self._advance(reached)
        self._move(move, chosen)
        return Step(outcome, move, self.kept_mask)


# ------------------------------------------------------------------------ building
class Scope(Choice):
    """Which surprises the recovery diagrams answer: every input that breaks ρe (``all``),
    or only those of the single-field classes (``classes``: far smaller diagrams on large
    specs; any other surprise stops)."""

    ALL = "all"
    CLASSES = "classes"


@dataclass(frozen=True)
class RecoveryOptions:
    """What to build: the surprises recovered from (:class:`Scope`), the surprise classes
    given fallbacks (None: every single-field class of the vocabulary), whether to build
    the fallbacks at all, and the diagrams' field order."""

    scope: Scope = Scope.ALL
    classes: tuple[SurpriseClass, ...] | None = None
    order: FieldOrder = FieldOrder.GREEDY
    fallbacks: bool = True
    #: bytes of tables the result may take (a board's flash less its firmware), or None.
    #: Building stops as soon as the diagrams pass it (:class:`~gaitc.compact.diagram.
    #: TooLarge`): when the controller and its recovery diagrams do, the error propagates;
    #: when a fallback does, it and the ones after it are left out (a prefix is kept, as
    #: :meth:`RecoveringController.without_fallbacks` keeps).
    budget: int | None = None


def surprise_classes(vocabulary: Vocabulary) -> tuple[SurpriseClass, ...]:
    """Every single-field class: per numeric input (a leg) failing and losing a level; per
    hazard set switching on and off; per other input of a plain spec switching."""
    out: list[SurpriseClass] = []
    for f in vocabulary.inputs:
        if f.numeric:
            out.append(LegFails(f.name))
            if len(f.labels) > 2:
                out.append(LegWears(f.name))
        elif vocabulary.domain == "robot" and f.name == HAZARD_FIELD:
            out.extend(HazardSwitch(h, on) for h in f.labels[1:] for on in (True, False))
        elif len(f.labels) > 1:
            out.append(FieldSwitch(f.name))
    return tuple(out)


@dataclass
class _Solved:
    """One game's functions in the shared manager."""

    winning: Function
    strategies: list[Function]
    goals: list[Function]


@dataclass
class _Work:
    """The shared manager and the spec's functions in it."""

    bdd: BDD
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    env_trans: Function
    sys_trans: Function
    valid_post: Function  # every next value (inputs and outputs) one of its field's values
    games: dict[tuple[int, ...], _Solved | None] = field(default_factory=dict)

    @property
    def pre(self) -> set[str]:
        return set(self.inputs) | set(self.outputs)

    @property
    def post_out(self) -> set[str]:
        return {b + "'" for b in self.outputs}

    def unprime(self, u: Function) -> Function:
        return self.bdd.let({b + "'": b for b in self.pre}, self.bdd.exist(self.pre, u))


def _valid(bdd: BDD, fields: Sequence[Field], primed: bool) -> Function:
    out = bdd.true
    for f in fields:
        values = bdd.false
        for k in range(len(f.labels)):
            values |= bdd.cube(f.cube(k, primed))
        out &= values
    return out


def recovering_controller(spec: GR1Spec, vocabulary: Vocabulary,
                          semantics: Semantics = Semantics.DEFAULT,
                          options: RecoveryOptions | None = None) -> RecoveringController:
    """The recovering compact controller of ``spec`` (see the module text)."""
    opts = options or RecoveryOptions()
    sym = SymbolicSpec(spec, Options(care=False))
    result = Game(sym, purpose="solving the recovery game").solve(keep_layers=True)
    bdd = sym.bdd
    if result.winning == bdd.false:
        raise ValueError("the spec is unrealizable: there is nothing to recover to")
    fields = vocabulary.fields
    work = _Work(bdd, tuple(sym.input_bits), tuple(sym.output_bits), sym.env_trans,
                 sym.sys_trans, _valid(bdd, fields, True))
    n = len(sym.sys_live)
    every = tuple(range(n))
    work.games[every] = _Solved(result.winning, goal_strategies(sym, result), list(sym.sys_live))
    main = work.games[every]
    assert main is not None
    moving = counter_moves(bdd, main.goals)
    start_ok = sym.sys_init & main.winning
    if semantics == Semantics.ROBOTICS:
        init = sym.env_init & start_ok
    else:
        init = bdd.exist(set(work.outputs), sym.env_init) & start_ok
    classes = opts.classes if opts.classes is not None else surprise_classes(vocabulary)
    class_sets = [_class_set(bdd, vocabulary, c) for c in classes]
    in_class = bdd.false
    for u in class_sets:
        in_class |= u
    enter = _entering(work, main)
    if opts.scope == Scope.CLASSES:
        enter &= in_class
    reach = _closure(work, [init] + [bdd.false] * (n - 1), main.strategies, moving)
    while True:  # the states recoveries land in, and what the strategy reaches from them
        surprised = [here & ~work.env_trans & enter for here in reach]
        landed = [bdd.false] * n
        for j, sur in enumerate(surprised):
            steps = sur & _into(work, main.winning)
            for k in range(n):
                if moving[j][k] != bdd.false:
                    landed[k] |= work.unprime(steps & moving[j][k])
        grown = _closure(work, [r | land for r, land in zip(reach, landed, strict=True)],
                         main.strategies, moving)
        if grown == reach:
            break
        reach = grown
    anywhere = bdd.false
    for here in reach:
        anywhere |= here
    surprises = anywhere & ~work.env_trans & _valid(bdd, vocabulary.inputs, True)
    recoverable = surprises & enter
    # the fallbacks: class surprises that do not recover, by the largest goal set K
    class_sets = [u & surprises for u in class_sets]
    remaining = in_class & surprises & ~enter
    chosen: list[tuple[tuple[int, ...], Function, _Solved]] = []
    if opts.fallbacks:
        for size in range(n - 1, 0, -1):
            for kept in combinations(every, size):
                if remaining == bdd.false:
                    break
                solved = _game(work, spec, kept)
                if solved is None:
                    continue
                here = remaining & _entering(work, solved)
                if here != bdd.false:
                    chosen.append((kept, here, solved))
                    remaining &= ~here
    # the diagrams, in one table
    slots = slot_order(vocabulary, opts.order)
    builder = Builder(bdd, slots, vocabulary.outputs, greedy=opts.order == FieldOrder.GREEDY,
                      limit=opts.budget)
    post_out = work.post_out
    move_roots = [_defined(builder.build_moves(here & work.env_trans
                                               & bdd.exist(post_out, rel), rel))
                  for here, rel in zip(reach, main.strategies, strict=True)]
    reached_roots = [_defined(builder.build_boolean(anywhere, goal), leaf(1))
                     for goal in main.goals]
    prime = {b: b + "'" for b in (*work.inputs, *work.outputs)}
    if semantics == Semantics.ROBOTICS:
        start = _defined(builder.build_boolean(bdd.true, init), leaf(0))
    else:
        first = bdd.exist(set(work.outputs), init)
        start = _defined(builder.build_moves(bdd.let(prime, first), bdd.let(prime, start_ok)))
    recover_root = _defined(builder.build_moves(recoverable, _into(work, main.winning)))
    flag_root = _defined(builder.build_boolean(surprises, enter), leaf(0))
    fallbacks: list[Degraded] = []
    everywhere = anywhere
    not_recovered = surprises & ~enter
    for kept, here, solved in chosen:
        mark = builder.mark()
        try:
            entry = _defined(builder.build_moves(here, _into(work, solved.winning)))
            applies = _defined(builder.build_boolean(not_recovered, here), leaf(0))
            k_moving = counter_moves(bdd, solved.goals)
            landing = work.unprime(here & _into(work, solved.winning))
            k_reach = _closure(work, [landing] + [bdd.false] * (len(kept) - 1),
                               solved.strategies, k_moving)
            k_any = bdd.false
            for r in k_reach:
                k_any |= r
            k_moves = tuple(_defined(builder.build_moves(r & work.env_trans
                                                         & bdd.exist(post_out, rel), rel))
                            for r, rel in zip(k_reach, solved.strategies, strict=True))
            k_reached = tuple(_defined(builder.build_boolean(k_any, g), leaf(1))
                              for g in solved.goals)
        except TooLarge:  # this fallback does not fit beside the ones before: a prefix stays
            builder.rollback(mark)
            break
        everywhere |= k_any
        fallbacks.append(Degraded(kept, applies, entry, k_moves, k_reached))
        not_recovered &= ~here
    builder.limit = None  # the monitor is chosen by size below; fit() measures the whole
    builder.greedy = False
    monitor = [_defined(builder.build_boolean(care, work.env_trans), leaf(1))
               for care in (everywhere, field_domain(bdd, slots))]
    others = [*move_roots, *reached_roots, start, recover_root, flag_root,
              *(r for fb in fallbacks for r in fb.roots)]
    sizes = [len(reachable_nodes(builder.nodes, [*others, m])) for m in monitor]
    assumed = monitor[sizes.index(min(sizes))]
    base = CompactController(
        vocabulary=vocabulary, slots=tuple(slots), nodes=tuple(builder.nodes),
        moves=tuple(builder.moves), move_roots=tuple(move_roots),
        reached_roots=tuple(reached_roots), start_root=start, assumed_root=assumed,
        inputs=tuple(work.inputs), outputs=tuple(work.outputs),
        integers=_integers(sym), semantics=semantics)
    nvars = len(work.pre) + len(work.inputs)
    reports = tuple(_class_report(bdd, c, u, enter, chosen, nvars)
                    for c, u in zip(classes, class_sets, strict=True))
    built = RecoveringController(base, flag_root, recover_root, tuple(fallbacks), reports)
    return built if len(fallbacks) == len(chosen) else built.without_fallbacks(len(fallbacks))


def _integers(sym: SymbolicSpec) -> dict[str, IntegerVar]:
    return dict(spec_integers(sym))


def _into(work: _Work, winning: Function) -> Function:
    """The moves ρs allows into ``winning`` (next values in range)."""
    prime = {b: b + "'" for b in (*work.inputs, *work.outputs)}
    return work.sys_trans & work.bdd.let(prime, winning) & work.valid_post


def _entering(work: _Work, solved: _Solved) -> Function:
    """(s, x') with some move ρs allows into the game's winning region."""
    return work.bdd.exist(work.post_out, _into(work, solved.winning))


def _game(work: _Work, spec: GR1Spec, kept: tuple[int, ...]) -> _Solved | None:
    """The game with only the goals ``kept`` (solved once), in the shared manager."""
    if kept in work.games:
        return work.games[kept]

    variant = spec.with_sections(sys_liveness=tuple(spec.sys_liveness[j] for j in kept))
    sym = SymbolicSpec(variant, Options(care=False))
    result = Game(sym, purpose="solving a fallback game").solve(keep_layers=True)
    solved = None
    if result.winning != sym.bdd.false:
        roots = materialize(work.bdd, symbolic_controller(sym, result, Semantics.DEFAULT))
        solved = _Solved(roots["winning"], list(roots["strategies"]), list(roots["goals"]))
    work.games[kept] = solved
    return solved


def _closure(work: _Work, starts: Sequence[Function], strategies: Sequence[Function],
             moving: Sequence[Sequence[Function]]) -> list[Function]:
    """Per goal j, the states a run pursuing goal j can be in from ``starts`` (per goal),
    any move of ``strategies`` taken (:func:`gaitc.compact.extraction.reachable_from`)."""
    return reachable_from(work.bdd, starts, strategies, work.env_trans, moving, work.inputs,
                          work.outputs)


def _class_set(bdd: BDD, vocabulary: Vocabulary, c: SurpriseClass) -> Function:
    """(x, x') where the class's field makes its change and every other input stays."""
    name = _field(c)
    out = bdd.true
    for f in vocabulary.inputs:
        if f.name != name:
            same = bdd.false
            for k in range(len(f.labels)):
                same |= bdd.cube(f.cube(k) | f.cube(k, True))
            out &= same
            continue
        pairs = bdd.false
        for k in range(len(f.labels)):
            for after in _changed(c, k, f.labels):
                pairs |= bdd.cube(f.cube(k) | f.cube(after, True))
        out &= pairs
    return out


def _field(c: SurpriseClass) -> str:
    match c:
        case LegFails(leg) | LegWears(leg) | LegRepaired(leg):
            return leg
        case HazardSwitch():
            return HAZARD_FIELD
        case FieldSwitch(name):
            return name
        case _:
            unreachable(c)


def _changed(c: SurpriseClass, value: int, labels: Sequence[str]) -> list[int]:
    """The values the class's field takes from ``value`` (an index into ``labels``; a
    numeric field's lowest value is a failed leg's level)."""
    top = len(labels) - 1
    match c:
        case LegFails():
            return [0] if value > 0 else []
        case LegWears(_, levels):
            return [max(0, value - levels)] if value > 0 else []
        case LegRepaired(_, level):
            to = top if level is None else labels.index(str(level))
            return [to] if to > value else []
        case HazardSwitch(hazard, on):
            if not on:  # to value 0, none
                return [0] if labels[value] == hazard else []
            to = labels.index(hazard)
            return [to] if value != to else []
        case FieldSwitch():
            return [v for v in range(len(labels)) if v != value]
        case _:
            unreachable(c)


def _class_report(bdd: BDD, c: SurpriseClass, u: Function, enter: Function,
                  chosen: Sequence[tuple[tuple[int, ...], Function, _Solved]], nvars: int
                  ) -> ClassReport:
    recovered = u & enter
    left = u & ~enter
    degraded: dict[int, int] = {}
    for k, (_, here, _) in enumerate(chosen):
        taken = left & here
        if taken != bdd.false:
            degraded[k] = _pairs(bdd, taken, nvars)
        left &= ~here
    return ClassReport(c, _pairs(bdd, recovered, nvars), degraded, _pairs(bdd, left, nvars))


def _pairs(bdd: BDD, u: Function, nvars: int) -> int:
    """The (state, inputs) pairs of ``u``, a set of field states and in-range inputs over
    the ``nvars`` current bits and next input bits (one assignment per pair)."""
    return 0 if u == bdd.false else int(bdd.count(u, nvars=nvars))


def _defined(ref: int, otherwise: int | None = None) -> int:
    if ref != DONT_CARE:
        return ref
    return otherwise if otherwise is not None else leaf(0)


# ------------------------------------------------------------------------ the proof
def recovery_relations(bdd: BDD, rc: RecoveringController) -> RecoveryRelations:
    """The recovery diagrams of ``rc`` as BDDs of ``bdd`` over the spec's bits, for
    :func:`gaitc.verifier.recovery.verify_recovery`."""
    base = rc.base

    def built(moves: Sequence[Ref], flags: Sequence[Ref]) -> Relations:
        return relations(bdd, replace(base, move_roots=tuple(moves), reached_roots=tuple(flags)))

    main = built([rc.recover_root], [rc.recoverable_root])
    fallbacks = []
    for fb in rc.fallbacks:
        made = built([fb.entry_root, *fb.move_roots], [fb.applies_root, *fb.reached_roots])
        fallbacks.append(FallbackRelations(fb.kept, made["goals"][0], made["strategies"][0],
                                           made["strategies"][1:], made["goals"][1:]))
    return RecoveryRelations(main["goals"][0], main["strategies"][0], main["assumed"],
                             tuple(fallbacks))


def prove_recovery(spec: GR1Spec, rc: RecoveringController) -> VerificationReport:
    """The verifier's report on ``rc``'s surprise handling (:mod:`gaitc.verifier.recovery`);
    the ordinary part is proved by :meth:`gaitc.forms.compact.CompactForm.verify`."""
    inputs = rc.base.vocabulary.inputs
    return verify_recovery(spec, to_symbolic(rc.base), lambda b: recovery_relations(b, rc),
                           lambda b: _valid(b, inputs, True), rc.base.semantics)
