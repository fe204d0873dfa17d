"""Tolerance of broken assumptions: the most surprises a controller plans for (``synth
--tolerate K``, ``resilience``'s tolerance row; issue 52).

The game is that of Ehlers and Topcu, "Resilience to intermittent assumption violations in
reactive synthesis" (HSCC 2014), with a bounded count of violations: the environment gets an
integer input, the surprise counter (0..K, starting at 0), and on every step it either keeps
each of its safety assumptions (ρe) and the counter, or breaks some of the *breakable* ones
and adds one to the counter, which may not pass K. Its liveness assumptions and the whole
of the system's part stay as they were. A winning strategy of this game from counter c keeps
every guarantee through any K - c surprises; restricted to counter 0 and to steps that keep
the counter, it is a controller of the original spec (:func:`projected_controller`).

One game with counter 0..K answers every budget k <= K at once: from counter K - k the
environment has k surprises left, so the spec tolerates k surprises exactly when the initial
states with counter K - k are winning. The breakable assumptions are the pieces of ρe
(:func:`assumption_pieces`): a clause ``guard -> (a_1 & ... & a_n)`` of the compiler whose
conjuncts speak of one leg each is split into one piece per leg, so that a surprise can be
named in the robot's words ("L5 changing health while not in use"); the encoding's mutexes
are never breakable (a leg with two health levels at once is no event of the world).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Final

from dd.cudd import copy_bdd

from gaitc.core.spec import Spec
from gaitc.diagnostics import UsageError
from gaitc.diagnostics.choices import Choice
from gaitc.ir.bddfile import SymbolicController, node_table
from gaitc.ir.formula import (
    Add,
    And,
    Compare,
    Expr,
    Implies,
    IntConst,
    IntVar,
    Or,
    conj,
    unreachable,
)
from gaitc.ir.roles import (
    ClauseRole,
    Fails,
    Goal,
    HazardEffect,
    LegFailure,
    Moves,
    Restores,
    Shape,
    Spares,
    StartHealth,
    UserClause,
    Wears,
    WearsUpTo,
)
from gaitc.ir.spec import Clause, GR1Spec, Origin, Semantics, Variable
from gaitc.sim.monitor import clause_rule
from gaitc.solver.canonical import spec_integers
from gaitc.solver.game import (
    ControllerTooLarge,
    Game,
    GameResult,
    GameStats,
    Limits,
    Progress,
    goal_strategies,
)
from gaitc.solver.strategy import extract_strategy
from gaitc.solver.symbolic import Options, SymbolicSpec
from gaitc.solver.synthesis import memory_guard
from ltlcompiler.encoding import make_encoding

if TYPE_CHECKING:
    from gaitc.ir.bddfile import SymbolicController
    from gaitc.ir.controller import Controller
    from gaitc.solver.game import Game, GameResult
    from gaitc.solver.symbolic import BDDNode, SymbolicSpec
    from ltlcompiler.encoding import Encoding

#: The name the surprise counter takes (with ``_`` appended while the spec uses it).
COUNTER: Final = "surprises"
#: The most surprises ``resilience`` asks about unless told otherwise.
DEFAULT_BOUND: Final = 2
#: The subjects (legs) tried one by one to name the surprise that breaks a limiting group.
MAX_SUBJECTS: Final = 12
#: The groups solved one by one to find the limiting one (a SLUGS file has one a clause).
MAX_GROUPS: Final = 24


class PieceKind(Choice):
    """What a breakable piece of ρe says; the value is the group's name in reports."""

    UNUSED_LEG_KEEPS = "eq. 3.5: a leg not in use keeps its health"
    USED_LEG_WEARS = "eq. 3.5: a leg in use loses at most one level a step"
    CACHE_RESTORES = "eq. 3.6: a cache restores every leg"
    HAZARD_FAILS = "eq. 3.9: an active hazard fails the legs in use"
    HAZARD_WEARS = "eq. 3.9: a graded hazard wears the legs in use by at most its levels"
    CLAUSE = "an assumption of its own"  # no robot words known: the group is the clause's rule


#: The short names of the kinds (``synth --tolerate K --breakable NAME``).
KIND_KEYS: Final = {
    "unused": PieceKind.UNUSED_LEG_KEEPS,
    "wear": PieceKind.USED_LEG_WEARS,
    "cache": PieceKind.CACHE_RESTORES,
    "hazard": PieceKind.HAZARD_FAILS,
    "hazard-wear": PieceKind.HAZARD_WEARS,
}

#: The robot's words for breaking a piece of each kind, with ``{leg}`` for its leg.
_WORDS: Final = {
    PieceKind.UNUSED_LEG_KEEPS: "{leg} changing health while not in use",
    PieceKind.USED_LEG_WEARS: "{leg} losing more than one level in one step",
    PieceKind.CACHE_RESTORES: "{leg} not restored at a cache",
    PieceKind.HAZARD_FAILS: "{leg} not failing in an active hazard",
    PieceKind.HAZARD_WEARS: "{leg} wearing more than the hazard's levels",
}

#: The words for breaking the pieces of several legs at once, by kind.
_SEVERAL: Final = {
    PieceKind.UNUSED_LEG_KEEPS: "several legs changing health at once while not in use",
    PieceKind.USED_LEG_WEARS: "several legs in use losing more than one level at once",
    PieceKind.CACHE_RESTORES: "several legs not restored at a cache at once",
    PieceKind.HAZARD_FAILS: "several legs not failing in an active hazard at once",
    PieceKind.HAZARD_WEARS: "several legs wearing more than the hazard's levels at once",
}


@dataclass(frozen=True)
class Piece:
    """One breakable piece of ρe: ``formula`` (a clause, or ``guard -> conjunct`` of one),
    its clause's index in ``env_trans``, its group, the leg it speaks of and the words for
    breaking it."""

    formula: Expr
    clause: int
    group: str
    subject: str = ""
    words: str = ""
    line: int | None = None


@dataclass(frozen=True)
class Assumptions:
    """ρe split for the tolerance game: the clauses that never break (by index) and the
    breakable pieces of the others."""

    fixed: tuple[int, ...]
    pieces: tuple[Piece, ...]

    @property
    def groups(self) -> tuple[str, ...]:
        """The groups of the pieces, in the order they first appear."""
        return tuple(dict.fromkeys(p.group for p in self.pieces))

    def lines(self, group: str) -> tuple[int, ...]:
        return tuple(sorted({p.line for p in self.pieces if p.group == group and p.line}))

    def subjects(self, group: str) -> tuple[str, ...]:
        return tuple(dict.fromkeys(p.subject for p in self.pieces
                                   if p.group == group and p.subject))


def _never_breaks(clause: Clause) -> bool:
    """The encoding's well-formedness clauses (exactly one health level, at most one
    hazard set): the state's shape, which no event breaks."""
    return clause.origin is not None and isinstance(clause.origin.role, Shape)


def assumption_pieces(spec: Spec | GR1Spec) -> Assumptions:
    """The breakable pieces of ``spec``'s ρe and the clauses that never break.

    With a ``.gait`` spec, a clause of eqs. 3.5, 3.6 or 3.9 becomes one piece per leg, each
    recognised by comparing it with the encoding's own formula for that leg; any other
    clause is one piece, grouped by its rule (:func:`gaitc.sim.monitor.clause_rule`)."""
    gr1 = spec.gr1 if isinstance(spec, Spec) else spec
    known = _leg_formulas(spec) if isinstance(spec, Spec) else {}
    fixed: list[int] = []
    pieces: list[Piece] = []
    for index, clause in enumerate(gr1.env_trans):
        rule = clause_rule(clause, "env_trans", index)
        if _never_breaks(clause):
            fixed.append(index)
            continue
        line = clause.origin.span.line if clause.origin and clause.origin.span else None
        split = _split(clause.formula, clause.origin.role if clause.origin else None, known)
        if split is None:  # one group per clause: a SLUGS file's share one rule
            group = rule if line is None or f"line {line}" in rule else f"{rule}, line {line}"
            pieces.append(Piece(clause.formula, index, group, "",
                                f"the assumption '{rule}' broken", line))
            continue
        for formula, kind, leg in split:
            pieces.append(Piece(formula, index, str(kind), leg,
                                _WORDS[kind].format(leg=leg), line))
    return Assumptions(tuple(fixed), tuple(pieces))


LegFormulas = dict[Expr, tuple[str, str]]  # formula -> (what it says, leg)


def _leg_formulas(spec: Spec) -> LegFormulas:
    """Each leg's formulas that the lowering puts in ρe: keep, degrade, restore, fail, wear
    (the names are those of :meth:`_kind`)."""
    if spec.model is None:
        return {}

    enc: Encoding = make_encoding(spec.model, spec.robot_encoding)
    out: LegFormulas = {}
    wears = sorted({h.harm.levels for h in spec.model.hazards
                    if isinstance(h.harm, WearsUpTo)})
    for leg in spec.model.legs:
        if leg.health <= 1:
            continue
        out[enc.health(leg.name, 1, True)] = ("fail", leg.name)
        out[enc.health(leg.name, leg.health, True)] = ("restore", leg.name)
        for k in wears:
            out[enc.wear_health(leg.name, k)] = ("wear", leg.name)
        out[enc.degrade_health(leg.name)] = ("degrade", leg.name)
        out[enc.keep_health(leg.name)] = ("keep", leg.name)
    return out


def _kind(what: str, role: ClauseRole | None) -> PieceKind | None:
    """The kind of a piece that says ``what`` (of :func:`_leg_formulas`) in a clause of
    ``role``, or None when the pair is not one the lowering writes."""
    match role:
        case Spares() | Wears():  # eq. 3.5: the legs in use may lose a level, others keep
            return {"keep": PieceKind.UNUSED_LEG_KEEPS,
                    "degrade": PieceKind.USED_LEG_WEARS}.get(what)
        case HazardEffect(harm=harm):
            match harm:
                case Fails():  # eq. 3.9: the legs in use fail, the others keep
                    return {"keep": PieceKind.UNUSED_LEG_KEEPS,
                            "fail": PieceKind.HAZARD_FAILS}.get(what)
                case WearsUpTo():  # graded: the legs in use lose up to k levels
                    return {"keep": PieceKind.UNUSED_LEG_KEEPS, "fail": PieceKind.HAZARD_FAILS,
                            "wear": PieceKind.HAZARD_WEARS,
                            "degrade": PieceKind.HAZARD_WEARS}.get(what)
                case _:
                    unreachable(harm)
        case Restores():  # eq. 3.6
            return PieceKind.CACHE_RESTORES if what == "restore" else None
        case None | Shape() | StartHealth() | Moves() | LegFailure() | Goal() | UserClause():
            return None
        case _:
            unreachable(role)


def _split(formula: Expr, role: ClauseRole | None, known: LegFormulas
           ) -> list[tuple[Expr, PieceKind, str]] | None:
    """``guard -> body`` as one implication per leg formula of ``body``, or None when the
    body is not made of known leg formulas only."""
    if not known or not isinstance(formula, Implies):
        return None
    body = formula.right
    parts = [body] if body in known else list(body.args) if isinstance(body, And) else []
    out: list[tuple[Expr, PieceKind, str]] = []
    for part in parts:
        if part not in known:
            return None
        what, leg = known[part]
        kind = _kind(what, role)
        if kind is None:
            return None
        out.append((Implies(formula.left, part), kind, leg))
    return out or None


# ---------------------------------------------------------------- the tolerance game
def counter_name(spec: GR1Spec) -> str:
    """:data:`COUNTER`, with ``_`` appended until no variable of ``spec`` has the name."""
    taken = {v.name for v in spec.variables()}
    name = COUNTER
    while name in taken:
        name += "_"
    return name


Selector = Callable[[Piece], bool]


def tolerant_spec(spec: Spec | GR1Spec, bound: int, breakable: Selector | None = None,
                  assumptions: Assumptions | None = None) -> GR1Spec:
    """The game of ``spec`` in which the environment may break the pieces ``breakable``
    selects (default: every piece) on up to ``bound`` steps, counted by the counter
    :func:`counter_name` (an input, 0..bound, initially 0)."""
    if bound < 0:
        raise UsageError(f"the number of surprises is 0 or more, not {bound}")
    gr1 = spec.gr1 if isinstance(spec, Spec) else spec
    found = assumptions or assumption_pieces(spec)
    name = counter_name(gr1)
    now, nxt = IntVar(name), IntVar(name, True)
    chosen = [p for p in found.pieces if breakable is None or breakable(p)]
    kept_pieces = [Clause(p.formula, gr1.env_trans[p.clause].origin)
                   for p in found.pieces if not (breakable is None or breakable(p))]
    kept = tuple(gr1.env_trans[i] for i in found.fixed) + tuple(kept_pieces)
    stay = Compare("=", nxt, now)
    step = conj((Compare("<", now, IntConst(bound)), Compare("=", nxt, Add(now, IntConst(1)))))
    either = Or((conj([*(p.formula for p in chosen), stay]), step))
    origin = Origin(f"tolerance: up to {bound} surprise{'s' if bound != 1 else ''}")
    counter = Variable(name, 0, bound)
    return GR1Spec(
        inputs=(*gr1.inputs, counter), outputs=gr1.outputs,
        env_init=(*gr1.env_init, Clause(Compare("=", now, IntConst(0)), origin)),
        sys_init=gr1.sys_init, env_trans=(*kept, Clause(either, origin)),
        sys_trans=gr1.sys_trans, env_liveness=gr1.env_liveness,
        sys_liveness=gr1.sys_liveness, name=gr1.name)


#: Budgets up to this many surprises are solved in one game, as asked. A larger budget K
#: is approached by doubling from here, stopping once the winning region stops shrinking
#: (:attr:`_Solved.stable`): ``synth --tolerate 1000000`` grew past 560 MB before.
DIRECT_BOUND: Final = 8


@dataclass(frozen=True)
class _Solved:
    """A solved tolerance game: the budgets it tolerates (index k: k surprises, up to the
    bound solved), the budget ``asked`` for, and, when asked, its symbolic parts for the
    projected controller.

    ``stable``: the states winning with ``solved`` surprises left are those winning with
    one fewer. From counter c the game depends only on the surprises left, r, and its
    winning set W(r) is a function of W(r - 1) alone (the play stays at its counter and
    wins there, GR(1) being prefix-independent, or a surprise takes it to a state that must
    lie in W(r - 1)); so W(r) = W(r - 1) gives W(r') = W(r) for every r' > r, and every
    budget past ``solved`` is tolerated exactly when ``solved`` is. Solving stops there
    instead of at ``asked``."""

    tolerated: tuple[bool, ...]
    sym: SymbolicSpec | None = field(default=None, repr=False)
    result: GameResult | None = field(default=None, repr=False)
    asked: int = 0
    stable: bool = False

    @property
    def solved(self) -> int:
        """The bound of the game solved (at most :attr:`asked`)."""
        return len(self.tolerated) - 1

    def tolerates(self, k: int) -> bool:
        """Whether ``k`` surprises (at most :attr:`asked`) are tolerated."""
        return self.tolerated[min(k, self.solved)]

    def largest(self) -> int | None:
        """The largest k up to :attr:`asked` with every budget up to k tolerated (None:
        not even 0)."""
        best = _largest(self.tolerated)
        return self.asked if best == self.solved and self.stable else best

    def counter(self, reached: int) -> int:
        """The counter value of this game whose winning states tolerate ``reached``."""
        return self.solved - min(reached, self.solved)


def _at_counter(sym: SymbolicSpec, name: str, value: int) -> BDDNode:
    return sym.translate(Compare("=", IntVar(name), IntConst(value)))


def _solve(spec: GR1Spec, semantics: Semantics, bound: int, limits: Limits,
           options: Options | None, keep: bool = False, asked: int | None = None
           ) -> _Solved:
    """Solve the tolerance game ``spec`` (of :func:`tolerant_spec` with ``bound``) once and
    read off every budget 0..bound, and whether it is :attr:`_Solved.stable` (``asked``:
    the budget this game stands for, default ``bound``)."""
    name = spec.inputs[-1].name
    tolerated = []
    with memory_guard():
        # without the care set: it is exact on the states after the first step and on the
        # initial ones, and those with the counter past 0 are not initial (a budget below
        # K is read off them)
        sym = SymbolicSpec(spec, replace(options or Options(), care=False), limits.check)
        game: Game = Game(sym, limits)
        result = game.solve(keep_layers=keep)
        start = _at_counter(sym, name, 0)
        lefts = []
        for k in range(bound + 1):
            left = sym.bdd.exist(set(sym.var_bits[name]),
                                 result.winning & _at_counter(sym, name, bound - k))
            lefts.append(left)
            tolerated.append(game.initially_winning(left & start, semantics))
    return _Solved(tuple(tolerated), sym if keep else None, result if keep else None,
                   bound if asked is None else asked,
                   stable=bound > 0 and lefts[bound] == lefts[bound - 1])


def _largest(tolerated: Sequence[bool]) -> int | None:
    """The largest k with every budget up to k tolerated (None: not even 0)."""
    best = None
    for k, ok in enumerate(tolerated):
        if not ok:
            break
        best = k
    return best


def projected_controller(spec: GR1Spec, solved: _Solved, counter: int,
                         semantics: Semantics) -> SymbolicController:
    """The tolerance game's strategy at counter value ``counter`` (kept on both sides of
    every step) with the counter's bits taken out: a symbolic controller of ``spec``."""
    sym, result = solved.sym, solved.result
    assert sym is not None and result is not None
    name = sym.spec.inputs[-1].name
    own = set(sym.var_bits[name])
    now = _at_counter(sym, name, counter)
    fixed = now & sym.prime(now)
    bits = own | {b + "'" for b in own}

    def drop(u: BDDNode, where: BDDNode) -> BDDNode:
        return sym.bdd.exist(bits, u & where)

    roots = {
        "winning": drop(result.winning, now),
        "env_init": drop(sym.env_init, _at_counter(sym, name, 0)),
        "sys_init": sym.sys_init,
        "env_trans": drop(sym.env_trans, fixed),
        "goals": [drop(g, fixed) for g in sym.sys_live],
        "strategies": [drop(s, fixed) for s in goal_strategies(sym, result)],
    }
    order, nodes, refs = node_table(sym.bdd, roots)
    inputs = tuple(b for b in sym.input_bits if b not in own)
    integers = {k: v for k, v in spec_integers(sym).items() if k != name}
    rank = sym.choice_rank
    return SymbolicController(
        inputs=inputs, outputs=tuple(sym.output_bits), order=order, nodes=nodes, roots=refs,
        integers=integers, semantics=semantics,
        choice=tuple(sorted(inputs + tuple(sym.output_bits), key=rank.__getitem__)))


def projected_automaton(spec: GR1Spec, solved: _Solved, counter: int, semantics: Semantics,
                        opts: ToleranceOptions, *, limits: Limits) -> Controller | None:
    """The same strategy as :func:`projected_controller`, as an explicit automaton: the
    winning region and the strategy's layers, projected alike, are carried into the game
    of ``spec`` itself and unrolled by the solver's extraction (cofactoring at a constant
    counter commutes with every step of it); None past ``opts.max_nodes`` nodes."""
    sym, result = solved.sym, solved.result
    assert sym is not None and result is not None
    name = sym.spec.inputs[-1].name
    own = set(sym.var_bits[name]) | {b + "'" for b in sym.var_bits[name]}
    now = _at_counter(sym, name, counter)
    fixed = now & sym.prime(now)
    target = SymbolicSpec(spec, replace(opts.options or Options(), care=False),
                          limits.check)

    def carried(u: BDDNode, where: BDDNode) -> BDDNode:
        return copy_bdd(sym.bdd.exist(own, u & where), target.bdd)

    projected = GameResult(
        winning=carried(result.winning, now),
        layers=[[carried(layer, fixed) for layer in goal] for goal in result.layers],
        stats=GameStats(), care=target.bdd.true)
    try:
        return extract_strategy(target, projected, semantics, limits, opts.max_nodes)
    except ControllerTooLarge:
        return None


# ---------------------------------------------------------------- the report
@dataclass(frozen=True)
class ToleranceOptions:
    """How :func:`tolerance` runs: ``breakable`` names the one group that may break (a short
    name of :data:`KIND_KEYS` or a group's name; None: every piece), ``groups`` whether
    each group is solved alone to find the limiting one, ``controller`` whether the
    controller of the largest budget reached is kept."""

    breakable: str | None = None
    groups: bool = True
    controller: bool = False
    explicit: bool = False  # the controller as an automaton too (None when over max_nodes)
    #: keep the controller only when at least one surprise is planned for: the caller
    #: writes synthesis's own controller when none is (gaitc.tolerate), and unrolling the
    #: counter game's strategy only to drop it took 30 s of a six-legged robot's 72 s
    planned_only: bool = False
    max_nodes: int | None = None
    options: Options | None = None
    timeout: float | None = None
    progress: Progress | None = None


@dataclass(frozen=True)
class GroupTolerance:
    """The most surprises of one group the spec tolerates when only that group may break:
    ``largest`` (None: not even 0), searched up to ``bound``."""

    group: str
    lines: tuple[int, ...]
    largest: int | None
    bound: int

    @property
    def reaches_bound(self) -> bool:
        return self.largest is not None and self.largest >= self.bound


@dataclass(frozen=True)
class Limit:
    """A surprise at which one more breaks the spec: its group and, when one leg's alone
    does it, that leg and the robot's words."""

    group: str
    words: str
    lines: tuple[int, ...]
    subject: str = ""


@dataclass(frozen=True)
class ToleranceReport:
    """What :func:`tolerance` found: ``reached`` is the largest K (None: the spec is not
    realizable even without surprises) within ``requested``; ``limits`` the groups that
    alone break the spec at ``reached + 1``."""

    file: str
    requested: int
    reached: int | None
    breakable: str | None
    counter: str
    groups: tuple[GroupTolerance, ...] = ()
    limits: tuple[Limit, ...] = ()
    solver_calls: int = 0
    seconds: float = 0.0
    notes: tuple[str, ...] = ()
    controller: SymbolicController | None = field(default=None, repr=False, compare=False)
    automaton: Controller | None = field(default=None, repr=False, compare=False)

    @property
    def realizable(self) -> bool:
        """Whether the spec is realizable without surprises."""
        return self.reached is not None

    @property
    def complete(self) -> bool:
        """Whether every budget asked for is tolerated."""
        return self.reached is not None and self.reached >= self.requested

    def summary(self) -> str:
        """One sentence in the robot's terms."""
        if self.reached is None:
            return "unrealizable even without surprises"
        head = f"survives {_count(self.reached)}"
        if self.complete:
            head += f" (all {self.requested} asked)" if self.requested else ""
        nxt = _ordinal(self.reached + 1)
        if self.limits:
            first = self.limits[0]
            equation = first.group.split(":")[0] if first.group.startswith("eq. ") else ""
            where = ", ".join(w for w in (equation, line_list(first.lines) if first.lines
                                          else "") if w)
            where = f" ({where})" if where else ""
            verb = "would break" if self.complete else "breaks"
            return f"{head}; the {nxt} {verb} it: {first.words}{where}"
        if self.groups and not self.complete:
            return f"{head}; the {nxt} breaks it only when surprises of several kinds combine"
        if self.groups and self.breakable is not None:
            return f"{head}; a {nxt} is survived too"
        if self.groups:
            return f"{head}; a {nxt} surprise of any one kind is survived too"
        return head

    def lines(self) -> list[str]:
        """The report for the terminal."""
        what = "every assumption" if self.breakable is None else f"only '{self.breakable}'"
        out = [f"{self.file}: tolerance of up to {_count(self.requested)} "
               f"({what} may break; {self.solver_calls} solver calls, {self.seconds:.1f} s)",
               f"  {self.summary()}"]
        for g in self.groups:
            named = len(g.lines) == 1 and f"line {g.lines[0]}" in g.group
            where = f" ({line_list(g.lines)})" if g.lines and not named else ""
            most = ("unrealizable" if g.largest is None else f"at least {g.largest}"
                    if g.reaches_bound else str(g.largest))
            out.append(f"    {g.group}{where}: {most}")
        out.extend(f"  note: {n}" for n in self.notes)
        return out

    def to_json(self) -> dict[str, Any]:
        """The ``tolerance`` object of ``synth --tolerate --json`` and ``resilience --json``
        (docs/json.md)."""
        return {
            "requested": self.requested, "reached": self.reached,
            "realizable": self.realizable, "complete": self.complete,
            "breakable": self.breakable, "counter": self.counter,
            "summary": self.summary(),
            "groups": [{"group": g.group, "lines": list(g.lines), "largest": g.largest,
                        "bound": g.bound, "at_least": g.reaches_bound} for g in self.groups],
            "limits": [{"group": lim.group, "leg": lim.subject or None, "words": lim.words,
                        "lines": list(lim.lines)} for lim in self.limits],
            "solver_calls": self.solver_calls, "seconds": round(self.seconds, 3),
            "notes": list(self.notes),
        }


def _count(k: int) -> str:
    return f"{k} surprise{'s' if k != 1 else ''}"


_ORDINALS: Final = ("first", "second", "third", "fourth", "fifth", "sixth", "seventh",
                    "eighth", "ninth", "tenth")


def _ordinal(k: int) -> str:
    return _ORDINALS[k - 1] if 1 <= k <= len(_ORDINALS) else f"{k}th"


def tolerance(spec: Spec | GR1Spec, semantics: Semantics = Semantics.DEFAULT, k: int = 1,
              opts: ToleranceOptions | None = None) -> ToleranceReport:
    """Whether ``spec`` keeps every guarantee through up to ``k`` surprises (broken safety
    assumptions), the largest number it does, and the assumptions that limit it."""
    opts = opts or ToleranceOptions()
    if k < 0:
        raise UsageError(f"--tolerate takes a number of surprises, 0 or more, not {k}")
    started = time.monotonic()
    limits = Limits(opts.timeout, opts.progress)
    gr1 = spec.gr1 if isinstance(spec, Spec) else spec
    found = assumption_pieces(spec)
    breakable = None if opts.breakable is None else group_named(found, opts.breakable)
    calls = 0

    def solve(bound: int, chosen: Selector | None, keep: bool = False) -> _Solved:
        """The game for ``bound`` surprises: past :data:`DIRECT_BOUND`, games of twice the
        bound each time until one is stable or has the bound."""
        nonlocal calls
        tried = min(bound, DIRECT_BOUND)
        while True:
            calls += 1
            game = tolerant_spec(spec, tried, chosen, found)
            solved = _solve(game, semantics, tried, limits, opts.options, keep, bound)
            if tried == bound or solved.stable:
                return solved
            tried = min(2 * tried, bound)

    limits.report("solving the game with surprises", f"up to {_count(k)}")
    wanted = None if breakable is None else _in_group(breakable)
    overall = solve(k, wanted, keep=opts.controller)
    reached = overall.largest()
    controller, automaton = None, None
    notes = []
    if overall.solved < k:
        notes.append(f"budgets past {_count(overall.solved - 1)} all behave alike: the states "
                     f"winning with {_count(overall.solved)} left are those winning with "
                     f"{_count(overall.solved - 1)}, so the game was solved up to "
                     f"{_count(overall.solved)}, not {_count(k)}")
    if opts.controller and reached is not None and not (opts.planned_only and reached == 0):
        at = overall.counter(reached)
        controller = projected_controller(gr1, overall, at, semantics)
        if opts.explicit:
            limits.report("extracting the controller")
            automaton = projected_automaton(gr1, overall, at, semantics, opts,
                                            limits=limits)
            if automaton is None:
                notes.append(f"the automaton would pass {opts.max_nodes} nodes: kept "
                             "symbolic")
    groups: list[GroupTolerance] = []
    limiting: list[Limit] = []
    names = found.groups if breakable is None else (breakable,)
    if len(names) > MAX_GROUPS:
        notes.append(f"{len(names) - MAX_GROUPS} of the {len(names)} groups were not solved "
                     f"alone (the first {MAX_GROUPS} were); --breakable solves one")
        names = names[:MAX_GROUPS]
    if opts.groups and reached is not None:
        bound = reached + 1
        for n, group in enumerate(names):
            limits.report("solving each kind of surprise alone", group, n / len(names))
            alone = solve(bound, _in_group(group))
            largest = alone.largest()
            groups.append(GroupTolerance(group, found.lines(group), largest, bound))
            if largest is not None and largest < bound:

                def breaks(leg: str, group: str = group) -> bool:
                    return not solve(bound, _in_group(group, leg)).tolerates(bound)

                limiting.append(_limit(group, found, breaks))
    return ToleranceReport(
        file=spec.path if isinstance(spec, Spec) else gr1.name or "<spec>", requested=k,
        reached=reached, breakable=breakable, counter=counter_name(gr1),
        groups=tuple(groups), limits=tuple(limiting), solver_calls=calls,
        seconds=time.monotonic() - started, notes=tuple(notes), controller=controller,
        automaton=automaton)


def group_named(found: Assumptions, name: str) -> str:
    """The group ``name`` stands for: a short name of :data:`KIND_KEYS` or a group's full
    name; a :class:`UsageError` lists the spec's groups otherwise."""
    group = str(KIND_KEYS[name]) if name in KIND_KEYS else name
    if group in found.groups:
        return group
    keys = {str(kind): key for key, kind in KIND_KEYS.items()}
    listed = "; ".join(f"{keys[g]} ({g})" if g in keys else f"'{g}'" for g in found.groups)
    raise UsageError(f"no breakable assumptions '{name}' in this spec; its groups are: "
                     f"{listed or 'none'}")


def _in_group(group: str, subject: str | None = None) -> Selector:
    return lambda p: p.group == group and (subject is None or p.subject == subject)


def _limit(group: str, found: Assumptions, breaks: Callable[[str], bool]) -> Limit:
    """The limit of ``group``: the first leg whose pieces alone break the spec (``breaks``)
    names it in the robot's words; else the group's own name."""
    for leg in found.subjects(group)[:MAX_SUBJECTS]:
        if breaks(leg):
            piece = next(p for p in found.pieces if p.group == group and p.subject == leg)
            lines = tuple(sorted({p.line for p in found.pieces
                                  if p.group == group and p.subject == leg and p.line}))
            return Limit(group, piece.words, lines, leg)
    words = next((p.words for p in found.pieces if p.group == group and not p.subject),
                 None)
    if words is None:  # every leg alone is survived: it takes several at once
        several = {str(kind): text for kind, text in _SEVERAL.items()}
        words = several.get(group, f"several surprises of '{group}' at once")
    return Limit(group, words, found.lines(group))


def line_list(lines: Sequence[int]) -> str:
    """``lines 6, 7`` or ``lines 23-34, 53`` (runs of three or more joined), or ``line 9``."""
    runs: list[list[int]] = []
    for n in sorted(lines):
        if runs and n == runs[-1][-1] + 1:
            runs[-1].append(n)
        else:
            runs.append([n])
    parts = [f"{r[0]}-{r[-1]}" if len(r) > 2 else ", ".join(map(str, r)) for r in runs]
    return f"line{'s' if len(lines) > 1 else ''} {', '.join(parts)}"
