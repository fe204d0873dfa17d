"""Well-separation: can the system force the environment to break its assumptions?

After Maoz and Ringert, "On well-separation of GR(1) specifications" (ESEC/FSE 2016): a
spec is *well-separated* when the environment can keep all its assumptions whatever the
system does within its own transition rules ρs.  Otherwise a controller may "win" by
blocking the environment (leaving it no move that keeps ρe, or starving a □◇ assumption)
instead of doing its task.

The environment's game, played on a :class:`~gaitc.solver.symbolic.SymbolicSpec` built
without a care set (every set below is exact on every state), is a generalized Büchi game
for the environment, solved with the nested fixpoint of Bloem, Jobstmann, Piterman, Pnueli
and Sa'ar ("Synthesis of Reactive(1) designs", JCSS 78(3), 2012) with the opponent's
liveness set empty:

    W = νZ. ∧_i μY. EPre((J^e_i ∧ Z') ∨ Y'),   EPre(T) = ∃x'. (∀y'. ρe) ∧ ∀y'. (ρs → T)

(the environment moves first and the system answers seeing its move, as in
:meth:`gaitc.solver.game.Game.cpre`; a system move that breaks ρs does not count, and a
system left without a ρs move has lost).  EPre is the dual of the solver's CPre:
¬EPre(T) = CPre(¬T).  The spec is well-separated when every initial state, every state of
θe ∧ θs, lies in W.  The condition does not depend on the semantics: under the robotics
semantics any state of θe ∧ θs may be the first; under the default one the environment
picks the inputs and the controller any outputs θs allows with them, so a state of θe ∧ θs
outside W is one the controller can start from.  :attr:`Separation.forced_everywhere`
tells Maoz and Ringert's stronger case, where the system can force a violation whatever
the environment's first inputs are, for each semantics.

Outside W the system wins by the dual fixpoint ¬W = μZ. ∨_i νY. CPre((¬J^e_i ∨ Z') ∧ Y')
(with the attractor of the environment's dead ends, μY. CPre(Y'), first); its rings give
a memoryless forcing strategy, played here to a short play told in the robot's words.
:func:`stay_separated` is the stricter spec synthesis tries first, whose controllers do
not rely on a broken assumption (docs/background/well-separation.md).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Final

from gaitc.core.spec import Spec as LoadedSpec
from gaitc.diagnostics import Diagnostic, Span
from gaitc.diagnostics.choices import Choice
from gaitc.ir.bddwalk import cofactor, first_assignment
from gaitc.ir.bits import decode_valuation, integer_bits
from gaitc.ir.cuddlib import cudd
from gaitc.ir.formula import FALSE, TRUE, Compare, Expr, IntConst, IntVar, Not, Var, conj, disj
from gaitc.ir.spec import Clause, GR1Spec, Origin, Semantics
from gaitc.sim.monitor import clause_rule
from gaitc.solver.symbolic import BDDNode, Options, SymbolicSpec
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from gaitc.core.spec import Spec
    from gaitc.sim.domain import Domain

__all__ = ["Assumption", "Broken", "Finding", "ForcingPlay", "Separation", "chances",
           "dead_ends", "environment_winning", "preference_note", "region_formula",
           "separation", "separation_warnings", "stay_separated"]

#: The longest forcing play told (a memoryless strategy against a memoryless environment
#: closes a loop or reaches a dead end far sooner on every spec we know).
MAX_PLAY: Final = 10_000
#: The rule of the clauses that keep a controller from relying on a broken assumption.
SEPARATED_RULE: Final = "well-separation"

Bits = tuple[int, ...]


class Broken(Choice):
    """How the system forces an assumption to break: a safety assumption (ρe) it leaves
    the environment no move to keep, or a □◇ assumption it keeps from ever holding."""

    SAFETY = "safety"
    LIVENESS = "liveness"


@dataclass(frozen=True)
class Assumption:
    """One assumption clause: its section (``env_trans`` or ``env_liveness``), position,
    rule (:func:`gaitc.sim.monitor.clause_rule`) and source span."""

    section: str
    index: int
    rule: str
    span: Span | None = field(default=None, compare=False)

    def where(self) -> str:
        return str(self.span) if self.span is not None else f"{self.section}[{self.index}]"

    def named(self) -> str:
        """The rule in quotes, with its line unless the rule says it already."""
        if self.span is None:
            return f"'{self.rule}' ({self.where()})"
        line = f"(line {self.span.line})"
        return f"'{self.rule}'" if line in self.rule else f"'{self.rule}' {line}"


@dataclass(frozen=True)
class ForcingPlay:
    """A play of the system's forcing strategy against one environment: ``states`` over
    ``names`` (the spec's variables, integers whole), ending at a dead end of the
    environment (``loop_start`` None) or closing a loop back to ``states[loop_start]``."""

    names: tuple[str, ...]
    states: tuple[tuple[int, ...], ...]
    loop_start: int | None

    def valuation(self, k: int) -> dict[str, int]:
        return dict(zip(self.names, self.states[k], strict=True))


@dataclass(frozen=True)
class Finding:
    """An assumption (or a set of them) the system can force to break, from at least one
    initial state, with a play of a strategy that forces it and that play in words.
    ``alone`` is False when no single assumption is forced: only their combination."""

    kind: Broken
    assumptions: tuple[Assumption, ...]
    play: ForcingPlay
    story: str
    alone: bool = True

    def message(self, player: str) -> str:
        names = " and ".join(a.named() for a in self.assumptions) or "an assumption"
        if self.kind is Broken.SAFETY:
            return (f"not well-separated: the {player} can force the environment to break "
                    f"{names}, leaving it no move that keeps its assumptions; a controller "
                    "may win by blocking the environment instead of doing its task")
        either = "" if self.alone else "one of "
        return (f"not well-separated: the {player} can keep {either}{names} from ever "
                "holding again; a controller may win by starving the assumption instead of "
                "doing its task")

    def to_json(self) -> dict[str, object]:
        return {"kind": self.kind, "alone": self.alone, "story": self.story,
                "assumptions": [{"section": a.section, "index": a.index, "rule": a.rule,
                                 "where": a.where()} for a in self.assumptions]}


@dataclass(frozen=True)
class Separation:
    """Whether a spec is well-separated, and if not what the system can force.

    ``forced_everywhere`` maps each semantics to whether the system can force a violation
    whatever the environment's first inputs are (Maoz and Ringert's stronger case): under
    the default semantics, for every input of θe some output of θs starts outside W; under
    the robotics semantics, every state of θe ∧ θs lies outside W."""

    file: str
    well_separated: bool
    findings: tuple[Finding, ...]
    forced_everywhere: Mapping[Semantics, bool]
    seconds: float
    player: str = "system"

    def warnings(self) -> tuple[Diagnostic, ...]:
        """One warning a finding, at the first assumption's span, the play as its hint."""
        out = []
        for finding in self.findings:
            spans = [a.span for a in finding.assumptions if a.span is not None]
            out.append(Diagnostic(finding.message(self.player), spans[0] if spans else None,
                                  hint=finding.story))
        return tuple(out)

    def to_json(self) -> dict[str, object]:
        return {"file": self.file, "well_separated": self.well_separated,
                "forced_everywhere": {str(k): v for k, v in self.forced_everywhere.items()},
                "findings": [f.to_json() for f in self.findings],
                "seconds": round(self.seconds, 3)}


# ---------------------------------------------------------------- the two predecessors
def _epre(sym: SymbolicSpec, target: BDDNode) -> BDDNode:
    """States where the environment has a move keeping ρe after which every ρs answer of
    the system lands in ``target`` (over pre and post bits): ∃x'. ¬(∃y'.¬ρe) ∧ ¬∃y'. ρs ∧ ¬T."""
    escape = cudd.and_exists(sym.sys_trans, ~target, sym.post_outputs)
    return cudd.and_exists(~sym.env_blocks, ~escape, sym.post_inputs)


def _cpre(sym: SymbolicSpec, target: BDDNode) -> BDDNode:
    """The system's controllable predecessor, with no care set: ∀x'. ρe → ∃y'. ρs ∧ T."""
    sys_can = cudd.and_exists(sym.sys_trans, target, sym.post_outputs)
    return ~cudd.and_exists(~sym.env_blocks, ~sys_can, sym.post_inputs)


def environment_winning(sym: SymbolicSpec, check: Callable[[], None] | None = None) -> BDDNode:
    """The environment's winning region W of its generalized Büchi game (module docstring):
    the states from which it keeps ρe for ever and every □◇ assumption infinitely often,
    whatever the system does within ρs.  ``sym`` must have no care set
    (``Options(care=False)``); ``check`` is called between fixpoint steps (a deadline)."""
    live = [sym.translate(c.formula) for c in sym.spec.env_liveness] or [sym.bdd.true]
    z = sym.bdd.true
    while True:
        z_post = sym.prime(z)
        new = z
        for goal in live:
            reach = goal & z_post
            y = sym.bdd.false
            while True:
                if check is not None:
                    check()
                grown = _epre(sym, reach | sym.prime(y)) & new
                if grown == y:
                    break
                y = grown
            new &= y
        if new == z:
            return z
        z = new


# ---------------------------------------------------------------- the system's forcing rings
@dataclass(frozen=True)
class _Ring:
    """States the system first wins at this ring, the transitions it keeps to from them,
    and the assumption it starves there (-1: it moves to a lower ring)."""

    states: BDDNode
    target: BDDNode
    assumption: int


def _forcing(sym: SymbolicSpec, live: Sequence[int], check: Callable[[], None] | None
             ) -> tuple[list[_Ring], BDDNode]:
    """The rings of μZ. CPre(Z') ∨ ∨_{i ∈ live} νY. CPre((¬J^e_i ∨ Z') ∧ Y'): the states
    from which the system forces a dead end of the environment or keeps one of the
    assumptions ``live`` from holding again; and their union."""
    false = sym.bdd.false
    goals = {i: sym.translate(sym.spec.env_liveness[i].formula) for i in live}
    rings: list[_Ring] = []
    z = false
    while True:
        z_post = sym.prime(z)
        pulled = _cpre(sym, z_post) & ~z
        if pulled != false:
            rings.append(_Ring(pulled, z_post, -1))
            z |= pulled
            continue
        grew = False
        for i in live:
            keep = ~goals[i] | z_post
            y = sym.bdd.true
            while True:
                if check is not None:
                    check()
                target = keep & sym.prime(y)
                shrunk = _cpre(sym, target) & y
                if shrunk == y:
                    break
                y = shrunk
            new = y & ~z
            if new != false:
                rings.append(_Ring(new, keep & sym.prime(y), i))
                z |= new
                grew = True
                break
        if not grew:
            return rings, z


# ---------------------------------------------------------------- playing the strategy
class _Player:
    """Plays the rings' strategy against an environment that keeps ρe, prefers moves after
    which no system answer enters ``avoid``, then keeping its inputs, then the smallest."""

    def __init__(self, sym: SymbolicSpec, rings: Sequence[_Ring], avoid: BDDNode) -> None:
        self.sym = sym
        self.rings = rings
        self.avoid_post = sym.prime(avoid)
        self.ins = list(sym.input_bits)
        self.outs = list(sym.output_bits)
        self.post_ins = [b + "'" for b in self.ins]
        self.post_outs = [b + "'" for b in self.outs]

    def _at(self, u: BDDNode, state: Bits) -> BDDNode:
        return cofactor(self.sym.bdd, dict(zip(self.ins + self.outs,
                                               (bool(b) for b in state), strict=True)), u)

    def _first(self, u: BDDNode, bits: list[str], keep: Bits) -> Bits:
        """The assignment ``keep`` to ``bits`` when ``u`` allows it, else the smallest."""
        same = cofactor(self.sym.bdd, dict(zip(bits, (bool(b) for b in keep), strict=True)), u)
        if same != self.sym.bdd.false:
            return keep
        rank = {b: self.sym.choice_rank[b[:-1]] for b in bits}
        found = first_assignment(self.sym.bdd, u, bits, rank)
        assert found is not None
        return found

    def _ring(self, state: Bits) -> _Ring | None:
        for ring in self.rings:
            if self._at(ring.states, state) == self.sym.bdd.true:
                return ring
        return None

    def step(self, state: Bits) -> Bits | None:
        """The next state of the play; None at a dead end of the environment."""
        sym, false = self.sym, self.sym.bdd.false
        legal = self._at(~sym.env_blocks, state)
        if legal == false:
            return None
        answers = self._at(sym.sys_trans, state)
        spoilt = sym.bdd.exist(sym.post_outputs, answers & self.avoid_post)
        clean = legal & ~spoilt
        moves = clean if clean != false else legal
        x = self._first(moves, self.post_ins, state[:len(self.ins)])
        ring = self._ring(state)
        assert ring is not None, "the play left the system's winning region"
        chosen = dict(zip(self.post_ins, (bool(b) for b in x), strict=True))
        at_x = cofactor(sym.bdd, chosen, answers & self._at(ring.target, state))
        wanted = at_x & ~cofactor(sym.bdd, chosen, self.avoid_post)
        y = self._first(wanted if wanted != false else at_x, self.post_outs,
                        state[len(self.ins):])
        return x + y

    def play(self, start: Bits) -> tuple[list[Bits], int | None]:
        states, seen = [start], {start: 0}
        while len(states) < MAX_PLAY:
            nxt = self.step(states[-1])
            if nxt is None:
                return states, None
            if nxt in seen:
                return states, seen[nxt]
            seen[nxt] = len(states)
            states.append(nxt)
        return states, None


# ---------------------------------------------------------------- the analysis
def separation(spec: Spec | GR1Spec, check: Callable[[], None] | None = None, *,
               symbolic: SymbolicSpec | None = None) -> Separation:
    """Whether ``spec`` is well-separated (Maoz and Ringert), and when it is not, each
    assumption the system can force to break with a forcing play (module docstring).
    ``check`` is called between fixpoint steps and may raise to stop (a deadline).

    ``symbolic``, a :class:`SymbolicSpec` of the same spec built for its own game, is used
    instead of a new one: the games here read only ρs and ∃y'.¬ρe, which every symbolic
    spec keeps exact beside the copies its care set simplifies, and the plays choose in
    the static order whatever order the manager is in, so the answer is the same.
    ``gaitc check`` decides and checks separation on one build this way (issue 59: the
    second build and translation cost 1-3 s on the published instances)."""
    return _analyse(spec, check, symbolic)[0]


def _analyse(spec: Spec | GR1Spec, check: Callable[[], None] | None,
             symbolic: SymbolicSpec | None = None
             ) -> tuple[Separation, SymbolicSpec, BDDNode]:
    """:func:`separation`, with the symbolic spec and the environment's winning region."""
    started = time.monotonic()
    loaded = spec if isinstance(spec, LoadedSpec) else None
    gr1 = spec.gr1 if isinstance(spec, LoadedSpec) else spec
    model = loaded.model if loaded is not None else None
    if symbolic is not None and symbolic.spec is not gr1:
        raise ValueError("the symbolic spec given to the well-separation check is of "
                         "another spec")
    sym = symbolic if symbolic is not None else SymbolicSpec(gr1, Options(care=False), check)
    winning = environment_winning(sym, check)
    initial = sym.env_init & sym.sys_init
    bad = initial & ~winning
    false = sym.bdd.false
    name = loaded.path if loaded is not None else (gr1.name or "<spec>")
    everywhere = {
        Semantics.DEFAULT: bad != false and (sym.env_init & ~sym.bdd.exist(
            sym.pre_outputs, sym.sys_init & ~winning)) == false,
        Semantics.ROBOTICS: bad != false and (initial & winning) == false,
    }
    player = "robot" if model is not None else "system"  # as gaitc.analysis.sanity says
    if bad == false:
        return (Separation(name, True, (), everywhere, time.monotonic() - started, player),
                sym, winning)
    teller = _Teller(sym, _domain(loaded))
    findings: list[Finding] = []
    dead_rings, dead = _forcing(sym, (), check)
    if (bad & dead) != false:
        states, _ = _Player(sym, dead_rings, false).play(_smallest(sym, bad & dead))
        core = _dead_end_core(sym, states[-1])
        findings.append(teller.finding(Broken.SAFETY, core, states, None))
    covered = dead
    n_live = len(gr1.env_liveness)
    for i in range(n_live):
        rings, forced = _forcing(sym, (i,), check)
        starts = bad & forced & ~dead
        covered |= forced
        if starts != false:
            states, loop = _Player(sym, rings, dead).play(_smallest(sym, starts))
            findings.append(teller.finding(Broken.LIVENESS, (_liveness(gr1, i),), states, loop))
    rest = bad & ~covered
    if rest != false:
        rings, _ = _forcing(sym, tuple(range(n_live)), check)
        states, loop = _Player(sym, rings, dead).play(_smallest(sym, rest))
        starved = tuple(_liveness(gr1, i) for i in _starved(sym, states, loop))
        findings.append(teller.finding(Broken.LIVENESS, starved, states, loop, alone=False))
    found = Separation(name, False, tuple(findings), everywhere, time.monotonic() - started,
                       player)
    return found, sym, winning


def separation_warnings(spec: Spec | GR1Spec) -> tuple[Diagnostic, ...]:
    """The warnings of :func:`separation` (none for a well-separated spec)."""
    return separation(spec).warnings()


def _domain(loaded: Spec | None) -> Domain | None:
    if loaded is None or loaded.model is None:
        return None
    from gaitc.sim.domain import Domain  # lazy: not on the lint and check paths (start-up)

    return Domain(loaded.model, loaded.encoding or EncodingName.ONEHOT)


def _smallest(sym: SymbolicSpec, states: BDDNode) -> Bits:
    bits = list(sym.input_bits + sym.output_bits)
    found = first_assignment(sym.bdd, states, bits, sym.choice_rank)
    assert found is not None
    return found


def _liveness(gr1: GR1Spec, i: int) -> Assumption:
    clause = gr1.env_liveness[i]
    return Assumption("env_liveness", i, clause_rule(clause, "env_liveness", i),
                      clause.origin.span if clause.origin is not None else None)


def _dead_end_core(sym: SymbolicSpec, state: Bits) -> tuple[Assumption, ...]:
    """A minimal set of ρe clauses the environment cannot keep together at the dead end
    ``state`` (deletion-minimal: dropping any one leaves it a move), within the inputs'
    ranges."""
    gr1 = sym.spec
    bits = list(sym.input_bits + sym.output_bits)
    at = dict(zip(bits, (bool(b) for b in state), strict=True))
    ranged = sym.bdd.true  # the next inputs' ranges (not a clause: SLUGS's encoding)
    for v in gr1.inputs:
        if v.is_integer and v.high is not None:
            ranged &= sym.translate(Compare("<=", IntVar(v.name, primed=True),
                                            IntConst(v.high)))
    parts = [cofactor(sym.bdd, at, sym.translate(c.formula)) for c in gr1.env_trans]

    def blocked(kept: Sequence[int]) -> bool:
        allowed = ranged
        for k in kept:
            allowed &= parts[k]
        return bool(sym.bdd.exist(sym.post_outputs, allowed) == sym.bdd.false)

    kept = list(range(len(parts)))
    for k in range(len(parts)):
        trial = [j for j in kept if j != k]
        if blocked(trial):
            kept = trial
    return tuple(Assumption("env_trans", k, clause_rule(gr1.env_trans[k], "env_trans", k),
                            _span(gr1.env_trans[k])) for k in kept)


def _span(clause: Clause) -> Span | None:
    return clause.origin.span if clause.origin is not None else None


def _starved(sym: SymbolicSpec, states: Sequence[Bits], loop: int | None) -> list[int]:
    """The □◇ assumptions false on every transition of the play's loop."""
    if loop is None:
        return []
    bits = list(sym.input_bits + sym.output_bits)
    steps = list(zip(states[loop:], [*states[loop + 1:], states[loop]], strict=True))
    out = []
    for i, clause in enumerate(sym.spec.env_liveness):
        goal = sym.translate(clause.formula)
        if all(_holds_on(sym, goal, bits, a, b) is False for a, b in steps):
            out.append(i)
    return out


def _holds_on(sym: SymbolicSpec, u: BDDNode, bits: list[str], a: Bits, b: Bits) -> bool:
    values = {bit: bool(v) for bit, v in zip(bits, a, strict=True)}
    values.update({bit + "'": bool(v) for bit, v in zip(bits, b, strict=True)})
    return bool(cofactor(sym.bdd, values, u) == sym.bdd.true)


# ---------------------------------------------------------------- the play in words
class _Teller:
    """Turns a play of bit states into spec values and a sentence in the robot's words
    (regions, gaits, leg levels, hazards) or, without a robot model, in the variables'
    values."""

    def __init__(self, sym: SymbolicSpec, domain: Domain | None) -> None:
        self.sym = sym
        self.domain = domain
        self.bits = list(sym.input_bits + sym.output_bits)
        self.variables = sym.spec.variables()
        self.names = tuple(v.name for v in self.variables)

    def values(self, state: Bits) -> tuple[int, ...]:
        decoded = decode_valuation(self.variables, dict(zip(self.bits, state, strict=True)))
        return tuple(int(decoded[n]) for n in self.names)

    def finding(self, kind: Broken, assumptions: tuple[Assumption, ...],
                states: Sequence[Bits], loop: int | None, alone: bool = True) -> Finding:
        play = ForcingPlay(self.names, tuple(self.values(s) for s in states), loop)
        return Finding(kind, assumptions, play, self.story(kind, assumptions, play), alone)

    def story(self, kind: Broken, assumptions: Sequence[Assumption], play: ForcingPlay) -> str:
        names = " and ".join(a.named() for a in assumptions) or "an assumption"
        moves = [self._move(play, k) for k in range(1, len(play.states))]
        start = self._start(play)
        if play.loop_start is None and kind is Broken.LIVENESS:  # cut at MAX_PLAY steps
            return (f"from {start}, the {self.who} " + ", then ".join(moves[:20])
                    + f", and so on: {names} never holds again")
        if play.loop_start is None:
            done = ", then ".join(moves)
            head = f"from {start}, the {self.who} {done}" if done else f"in {start}"
            return (f"{head}: there the environment has no move that keeps "
                    f"{names}")
        back = self._move(play, play.loop_start, previous=len(play.states) - 1)
        prefix, cycle = moves[:play.loop_start], [*moves[play.loop_start:], back]
        head = f"from {start}, the {self.who} " + ", then ".join(prefix) if prefix else \
            f"from {start}, the {self.who}"
        if len(cycle) == 1 and cycle[0].startswith(("stays", "keeps")):
            tail = f"{cycle[0]} for ever"
        else:
            tail = "repeats for ever: " + ", then ".join(cycle)
        joint = ", then " if prefix else " "
        return f"{head}{joint}{tail}: {names} never holds again"

    @property
    def who(self) -> str:
        return "robot" if self.domain is not None else "system"

    def _start(self, play: ForcingPlay) -> str:
        if self.domain is None:
            return "(" + ", ".join(f"{n}={v}" for n, v in zip(play.names, play.states[0],
                                                                strict=True)) + ")"
        first = self.domain.decode(play.valuation(0))
        changes = [f"{leg} at level {level}" for leg, level in first.health
                   if level != self.domain.full.get(leg, level)]
        if first.hazard is not None:
            changes.append(f"{first.hazard} on")
        return first.region + (f" ({', '.join(changes)})" if changes else "")

    def _move(self, play: ForcingPlay, k: int, previous: int | None = None) -> str:
        """The move into ``play.states[k]`` from the one before it (or ``previous``), in
        the robot's words (its gait and region; the environment's changes after it).
        :mod:`gaitc.play.words` says the same for the player, a layer this one cannot use."""
        before = play.valuation(k - 1 if previous is None else previous)
        after = play.valuation(k)
        if self.domain is None:
            changed = [f"{n}={after[n]}" for n in play.names if after[n] != before[n]]
            return "sets " + ", ".join(changed) if changed else "keeps every value"
        # lazy: a SLUGS spec's check loads no .gait front end (start-up)
        from ltlcompiler.model import NO_GAIT

        was, now = self.domain.decode(before), self.domain.decode(after)
        moved = now.gait not in ("", NO_GAIT) and now.region != was.region
        said = f"goes {now.gait} to {now.region}" if moved else f"stays in {now.region}"
        env = []
        if now.hazard != was.hazard:
            env += [f"switches {h} {word}" for h, word in ((was.hazard, "off"),
                                                            (now.hazard, "on")) if h]
        levels = dict(now.health)
        for leg, level in was.health:
            if levels[leg] != level:
                env.append(f"takes {leg} to level {levels[leg]}")
        return f"{said} (the environment {' and '.join(env)})" if env else said


# ---------------------------------------------------------------- the preferred controllers
def region_formula(sym: SymbolicSpec, region: BDDNode, primed: bool) -> Expr:
    """The set of states ``region`` (over ``sym``'s pre bits) as a formula over the spec's
    variables, of the next state when ``primed``: the BDD's Shannon expansion, its nodes
    shared (integers' bits become comparisons of the whole variable)."""
    owner: dict[str, tuple[str, int]] = {}
    for v in sym.spec.variables():
        for k, bit in enumerate(integer_bits(v)):
            owner[bit] = (v.name, k)
    atoms: dict[str, Expr] = {}

    def atom(bit: str) -> Expr:
        if bit not in atoms:
            name, k = owner[bit]
            v = sym.variables[name]
            if not v.is_integer or v.low is None or v.high is None:
                atoms[bit] = Var(name, primed=primed)
            else:
                low = v.low
                atoms[bit] = disj(Compare("=", IntVar(name, primed=primed), IntConst(value))
                                  for value in range(low, v.high + 1)
                                  if (value - low) >> k & 1)
        return atoms[bit]

    memo: dict[BDDNode, Expr] = {}
    true, false = sym.bdd.true, sym.bdd.false
    memo[true], memo[false] = TRUE, FALSE
    stack: list[tuple[BDDNode, bool]] = [(region, False)]
    while stack:  # children before parents, without recursion
        u, expanded = stack.pop()
        if u in memo:
            continue
        var = u.var
        assert var is not None
        low, high = (~u.low, ~u.high) if u.negated else (u.low, u.high)
        if not expanded:
            stack.append((u, True))
            stack.extend((kid, False) for kid in (low, high) if kid not in memo)
            continue
        memo[u] = _ite(atom(var), memo[high], memo[low])
    return memo[region]


def _ite(test: Expr, then: Expr, other: Expr) -> Expr:
    if then is TRUE and other is FALSE:
        return test
    if then is FALSE and other is TRUE:
        return Not(test)
    parts = []
    for guard, value in ((test, then), (Not(test), other)):
        if value is TRUE:
            parts.append(guard)
        elif value is not FALSE:
            parts.append(conj((guard, value)))
    return disj(parts)


def dead_ends(sym: SymbolicSpec) -> BDDNode:
    """The environment's dead ends: states where no move of its keeps ρe."""
    return ~sym.bdd.exist(sym.post_inputs, ~sym.env_blocks)


def chances(sym: SymbolicSpec, i: int, check: Callable[[], None] | None = None) -> BDDNode:
    """The states from which the environment can force □◇ assumption ``i`` to hold on a
    coming step, whatever the system does within ρs: μY. EPre(J^e_i ∨ Y')."""
    goal = sym.translate(sym.spec.env_liveness[i].formula)
    y = sym.bdd.false
    while True:
        if check is not None:
            check()
        grown = _epre(sym, goal | sym.prime(y)) | y
        if grown == y:
            return y
        y = grown


def stay_separated(spec: Spec | GR1Spec, semantics: Semantics = Semantics.DEFAULT,
                   check: Callable[[], None] | None = None
                   ) -> tuple[GR1Spec, Separation] | None:
    """When ``spec`` is not well-separated: the spec whose controllers do not rely on the
    environment breaking an assumption, with the analysis; None for a well-separated spec.

    The system must keep out of the environment's dead ends D (ρs ∧ ¬D', and θs ∧ ¬D under
    the default semantics, where it picks the first outputs), so the environment always has
    a move keeping ρe; and each □◇ assumption J^e_i it could starve is weakened to
    □◇ (J^e_i ∨ ¬P_i), P_i = :func:`chances`: the environment owes J^e_i only while the
    system leaves it a chance.  The environment can keep these assumptions from every
    state (it forces J^e_i from P_i, and it is never stuck), so a controller of this spec
    wins against every environment that keeps what it still can; its assumptions are
    weaker and its ρs stronger than ``spec``'s, so it is also a controller of ``spec``."""
    gr1 = spec.gr1 if isinstance(spec, LoadedSpec) else spec
    found, sym, _ = _analyse(spec, check)
    if found.well_separated:
        return None
    sys_init, sys_trans = gr1.sys_init, gr1.sys_trans
    dead = dead_ends(sym)
    if dead != sym.bdd.false:
        origin = Origin(f"{SEPARATED_RULE}: never leave the environment without a move")
        sys_trans = (*sys_trans, Clause(region_formula(sym, ~dead, primed=True), origin))
        if semantics is Semantics.DEFAULT:
            sys_init = (*sys_init, Clause(region_formula(sym, ~dead, primed=False), origin))
    env_liveness = list(gr1.env_liveness)
    for i, clause in enumerate(gr1.env_liveness):
        chance = chances(sym, i, check)
        if chance != sym.bdd.true:
            weakened = disj((clause.formula, region_formula(sym, ~chance, primed=False)))
            env_liveness[i] = Clause(weakened, clause.origin)
    return gr1.with_sections(sys_init=sys_init, sys_trans=sys_trans,
                             env_liveness=tuple(env_liveness)), found


def preference_note(found: Separation, kept: bool) -> str:
    """What synthesis says of a spec that is not well-separated: whether its controller
    (of :func:`stay_separated`'s spec when ``kept``, else of the spec itself) relies on
    the environment breaking an assumption."""
    def names(kind: Broken) -> str:
        return " and ".join(a.named() for f in found.findings if f.kind is kind
                            for a in f.assumptions)

    safety, liveness = names(Broken.SAFETY), names(Broken.LIVENESS)
    if not kept:
        broken = " and ".join(n for n in (safety, liveness) if n) or "an assumption"
        return (f"the controller may win by forcing the environment to break {broken}: no "
                "controller of this spec reaches its goals without relying on that")
    parts = []
    if safety:
        parts.append(f"never forces the environment to break {safety}: it never leaves the "
                     "environment without a move that keeps its assumptions")
    if liveness:
        parts.append(f"does not rely on {liveness} failing: it reaches its goals whenever "
                     f"the environment makes it hold at every chance the {found.player} "
                     "leaves it")
    return "the controller " + "; and it ".join(parts)
