"""Lowering: the checked Model to a GR1Spec, thesis chapter 3 eqs. 3.3-3.9 (region moves,
failed legs, degradation, caches, hazards) plus goals (3.7), user formulas and the mutual
exclusions the thesis omits; both encodings of :mod:`ltlcompiler.encoding`."""

from __future__ import annotations

from collections.abc import Iterable

from gaitc.diagnostics import FormulaError, Span, SpecSemanticError
from gaitc.ir.formula import (
    Add,
    Always,
    And,
    Compare,
    Const,
    Eventually,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Next,
    Not,
    Or,
    Term,
    Var,
    Xor,
    atoms,
    conj,
    disj,
    has_primes,
    node_kind,
    push_next,
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
from gaitc.ir.spec import SECTIONS, Clause, GR1Spec, Origin, section_named
from gaitc.ir.traversal import Node, Text, fold, join_text, separated
from ltlcompiler.encoding import Encoding, EncodingName, check_names, make_encoding
from ltlcompiler.model import NO_GAIT, GaitKind, Model, Section, UserFormula


def lower(model: Model, encoding: EncodingName = EncodingName.ONEHOT) -> GR1Spec:
    """The GR(1) specification of ``model`` in ``encoding`` ("onehot" or "binary").

    Sections: eqs. 3.3 and 3.4 in sys_trans; 3.5 (with 3.8's ¬φ_H in the antecedent),
    3.6 and 3.9 in env_trans; goals in sys_liveness; assumptions in env_*, guarantees in
    sys_*; "exactly one region/gait/health level per leg" and "at most one hazard" in the
    init sections and, primed, in the trans sections (onehot only: integers need none).
    Clause order follows the declaration order of the model, so output is deterministic.

    Turn order (SLUGS, Mealy): the environment picks the next health and hazard seeing
    the current state, then the robot picks its next region and gait.  The gait true at
    step t is the one that brought the robot into its region at t; the environment
    degrades its legs at t+1 (eq. 3.5), so a move is allowed while its legs are above
    level 1 and the move into a cache costs no health (eq. 3.6 wins).

    Choices beyond the thesis:

    * noGait only stays in place: every region gets "stay by noGait" even when the model
      omits it, and noGait on an edge between two regions is an error.
    * A gait moves only along τ with a gait listed in D_τ; nothing else is allowed.
    * A correction gait degrades nothing: its L_G counts as empty in eqs. 3.5 and 3.9
      (thesis section 3.4.1); eq. 3.4 still applies to any legs it lists.
    * A leg with one health level is permanently failed: eq. 3.4 keeps its gaits off
      for ever, and a cache cannot repair it (its only level is its full level).
    * Hazards are unconstrained at the start apart from "at most one"; health starts
      at each leg's declared initial level (default full).
    * A graded hazard (``wears k``) generalises eq. 3.9 towards eq. 3.5: in its active
      regions each leg of the gait may lose up to k levels (health' in
      [max(1, health - k), health], the environment choosing) instead of failing; it
      still counts in eq. 3.5's φ_H, so eq. 3.5's one level does not also apply there.
    """
    check_names(model, encoding)
    return _Lowering(model, make_encoding(model, encoding)).run()


class _Lowering:
    def __init__(self, model: Model, enc: Encoding) -> None:
        self.model = model
        self.enc = enc
        self.sections: dict[str, list[Clause]] = {name: [] for name in SECTIONS}
        self.region_span = {r.name: r.span for r in model.regions}
        self.moving = {g.name: (g.legs if g.kind is GaitKind.MOVE else ()) for g in model.gaits}

    def add(self, section: str, formula: Expr, rule: str, span: Span | None,
            role: ClauseRole) -> None:
        """A clause: its label for people (``rule``), source span and typed role."""
        self.sections[section].append(Clause(formula, Origin(rule, span, role)))

    def run(self) -> GR1Spec:
        self.init()
        self.moves()  # eq. 3.3
        self.failed_legs()  # eq. 3.4
        self.degradation()  # eqs. 3.5, 3.8, 3.9
        self.caches()  # eq. 3.6
        self.goals()  # eq. 3.7
        for uf in self.model.assumptions:
            self.user(uf, "env")
        for uf in self.model.guarantees:
            self.user(uf, "sys")
        s = self.sections
        return GR1Spec(
            inputs=self.enc.inputs(), outputs=self.enc.outputs(),
            name=self.model.name, **{name: tuple(s[name]) for name in SECTIONS},
        )

    # ------------------------------------------------------------ init and mutexes
    def init(self) -> None:
        m, enc = self.model, self.enc
        for side, rule, formula in enc.mutex(primed=False):
            self.add(section_named(side, "init"), formula, rule, None, Shape())
        for leg in m.legs:
            self.add("env_init", enc.health(leg.name, leg.initial),
                     f"init: leg {leg.name} starts at health {leg.initial} of {leg.health}",
                     leg.initial_span or leg.span, StartHealth(leg.name))
        self.add("sys_init", enc.region(m.start), f"init: start in {m.start}",
                 m.start_span or self.region_span.get(m.start), Shape())
        self.add("sys_init", enc.gait(NO_GAIT), f"init: start with {NO_GAIT}", None, Shape())
        for side, rule, formula in enc.mutex(primed=True):
            self.add(f"{side}_trans", formula, rule, None, Shape())

    # ------------------------------------------------------------ eq. 3.3
    def moves(self) -> None:
        enc = self.enc
        targets: dict[str, dict[str, list[str]]] = {r.name: {} for r in self.model.regions}
        for t in self.model.transitions:
            if t.source != t.target and NO_GAIT in t.gaits:
                raise SpecSemanticError(
                    f"{NO_GAIT} cannot move the robot from {t.source} to {t.target}: it only "
                    "stays in place; list a moving gait for this edge", t.span)
            gaits = targets[t.source].setdefault(t.target, [])
            gaits.extend(g for g in t.gaits if g not in gaits)
        for region in self.model.regions:
            out = targets[region.name]
            stay = out.setdefault(region.name, [])
            if NO_GAIT not in stay:
                stay.append(NO_GAIT)
            options: list[Expr] = []
            words: list[str] = []
            for target, gaits in sorted(out.items(), key=lambda kv: self.enc.region_index[kv[0]]):
                options.append(conj((enc.region(target, True),
                                     disj(enc.gait(g, True) for g in gaits))))
                moves = [g for g in gaits if g != NO_GAIT]
                if moves and target == region.name:
                    words.append(f"turn in place by {'|'.join(moves)}")
                elif moves:
                    words.append(f"move to {target} by {'|'.join(moves)}")
            words.append(f"or stay by {NO_GAIT}" if words else f"only stay by {NO_GAIT}")
            rule = f"eq. 3.3: from {region.name} " + ", ".join(words)
            self.add("sys_trans", Implies(enc.region(region.name), disj(options)), rule,
                     region.span, Moves(region.name))

    # ------------------------------------------------------------ eq. 3.4
    def failed_legs(self) -> None:
        for leg in self.model.legs:
            gaits = self.model.gaits_using(leg.name)
            if not gaits:
                continue
            formula = Implies(self.enc.health(leg.name, 1, True),
                              conj(Not(self.enc.gait(g, True)) for g in gaits))
            status = "is failed for ever" if leg.health == 1 else "failed"
            rule = f"eq. 3.4: leg {leg.name} {status} => gaits using {leg.name} " \
                   f"({', '.join(gaits)}) are off"
            self.add("sys_trans", formula, rule, leg.span, LegFailure(leg.name))

    # ------------------------------------------------------------ eqs. 3.5, 3.8, 3.9
    def not_in_cache(self) -> list[Expr]:
        return [Not(self.enc.region(c)) for c in self.model.caches]

    def keep_others(self, used: Iterable[str]) -> list[Expr]:
        skip = set(used)
        return [self.enc.keep_health(leg.name) for leg in self.model.legs
                if leg.name not in skip and leg.health > 1]

    def hazard_active(self, hazard: str, regions: Iterable[str]) -> Expr:
        enc = self.enc
        return conj((enc.hazard(hazard), disj(enc.region(r) for r in regions)))

    def degradation(self) -> None:
        enc, m = self.enc, self.model
        phi_h = disj(self.hazard_active(h.name, h.regions) for h in m.hazards)
        for gait in m.gaits:
            legs = [leg for leg in self.moving[gait.name] if m.leg(leg).health > 1]
            away = [enc.gait(gait.name), *self.not_in_cache()]
            if not legs:
                why = "uses only failed legs" if self.moving[gait.name] else "degrades no leg"
                self.add("env_trans", Implies(conj(away), conj(self.keep_others(()))),
                         f"eq. 3.5: {gait.name} {why}: every leg keeps its health",
                         gait.span, Spares(gait.name))
                continue
            antecedent = conj([*away, Not(phi_h)] if m.hazards else away)
            body = conj([*(enc.degrade_health(leg) for leg in legs), *self.keep_others(legs)])
            which = f"legs {', '.join(legs)}" if len(legs) > 1 else f"leg {legs[0]}"
            rule = f"eq. 3.5: under {gait.name} {which} may lose one level, the other legs " \
                   "keep theirs"
            self.add("env_trans", Implies(antecedent, body), rule, gait.span,
                     Wears(gait.name, tuple(legs)))
            for hazard in m.hazards:
                hot = conj([*away, enc.hazard(hazard.name),
                            disj(enc.region(r) for r in hazard.regions)])
                where = f"hazard {hazard.name} active in {'|'.join(hazard.regions)} " \
                        f"under {gait.name}"
                match hazard.harm:
                    case Fails():
                        lost = [enc.health(leg, 1, True) for leg in legs]
                        rule = f"eq. 3.9: {where} fails {which}"
                    case WearsUpTo(levels=k):  # eq. 3.9 with eq. 3.5's wear of up to k
                        levels = f"{k} level{'s' if k != 1 else ''}"
                        lost = [enc.wear_health(leg, k) for leg in legs]
                        rule = f"eq. 3.9 graded (eq. 3.5 with up to {levels}): {where}: " \
                               f"{which} may lose up to {levels}, the other legs keep theirs"
                    case _:
                        unreachable(hazard.harm)
                body = conj([*lost, *self.keep_others(legs)])
                self.add("env_trans", Implies(hot, body), rule, hazard.span,
                         HazardEffect(hazard.name, gait.name, tuple(legs), hazard.harm))

    # ------------------------------------------------------------ eq. 3.6
    def caches(self) -> None:
        stated = dict(zip(self.model.caches, self.model.cache_spans, strict=False))
        for cache in self.model.caches:
            full = conj(self.enc.health(leg.name, leg.health, True)
                        for leg in self.model.legs if leg.health > 1)
            self.add("env_trans", Implies(self.enc.region(cache), full),
                     f"eq. 3.6: cache {cache} resets every leg",
                     stated.get(cache) or self.region_span.get(cache), Restores(cache))

    # ------------------------------------------------------------ eq. 3.7 and user formulas
    def goals(self) -> None:
        for goal in self.model.goals:
            formula = self.translate(goal, "sys")
            what = f"visit {goal.formula.name}" if isinstance(goal.formula, Var) \
                else describe(goal.formula)
            self.add("sys_liveness", formula, f"goal{_line(goal.span)}: {what}", goal.span,
                     Goal(what))

    def user(self, uf: UserFormula, side: str) -> None:
        formula = self.translate(uf, side)
        word = "assumption" if side == "env" else "guarantee"
        self.add(section_named(side, uf.section.value), formula,
                 f"{word}{_line(uf.span)}: {describe(uf.formula)}", uf.span,
                 UserClause(assumption=side == "env"))

    def translate(self, uf: UserFormula, side: str) -> Expr:
        flat = push_next(uf.formula)
        if uf.section is Section.INIT and has_primes(flat):
            raise FormulaError("an initial condition cannot look at the next step: drop "
                               "'next' or make it an 'always' formula", uf.span)
        result = self.enc.translate(flat)
        if side == "env" and uf.section is Section.TRANS:
            outputs = self.enc.output_names()
            if any(primed and name in outputs for name, primed in atoms(result)):
                raise FormulaError(
                    "an assumption cannot constrain the robot's next region or gait: the "
                    "environment moves first; make it a guarantee or drop 'next' there",
                    uf.span)
        return result


def _line(span: Span | None) -> str:
    return f" (line {span.line})" if span is not None else ""


_BINARY = {And: " & ", Or: " | ", Xor: " ^ ", Iff: " <-> ", Implies: " -> "}
_WORDS: dict[type[Node], str] = {Next: "next", Always: "always", Eventually: "eventually"}
_SIMPLE = (Var, Const, Not, Compare, Next, Always, Eventually)  # never parenthesised


def describe(expr: Expr | Term) -> str:
    """A short human-readable text of a user formula, for clause comments."""
    return join_text(fold(expr, _describe))


def _describe(node: Node, texts: list[Text]) -> Text:
    """The text of ``node`` from the texts of its children (a step of the fold)."""
    operands = [t if isinstance(c, _SIMPLE) else ("(", t, ")")
                for c, t in zip(node.children(), texts, strict=True)]
    kind = node_kind(node)
    match kind:
        case Const():
            return "true" if kind.value else "false"
        case Var():
            return kind.name + ("'" if kind.primed else "")
        case IntVar():
            return f"health({kind.name})" + ("'" if kind.primed else "")
        case IntConst():
            return str(kind.value)
        case Not():
            return ("!", operands[0])
        case And() | Or() | Xor() | Iff() | Implies():
            return separated(_BINARY[type(kind)], operands)
        case Compare():
            return (texts[0], f" {kind.op} ", texts[1])
        case Add():
            return separated(" + ", texts)
        case Next() | Always() | Eventually():
            return (_WORDS[type(kind)], "(", separated(", ", texts), ")")
        case _:
            unreachable(kind)
