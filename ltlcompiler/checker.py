"""Semantic checker: a .gait syntax tree becomes the checked :class:`~ltlcompiler.model.Model`.

Resolves names, expands ranges, builds τ (via :mod:`ltlcompiler.regions`) and sorts
assume/guarantee formulas into GR(1) sections (via :mod:`ltlcompiler.fragment`).
Errors raise a :class:`GaitcError` with a span; warnings come back as diagnostics.
"""

from __future__ import annotations

from gaitc.diagnostics import Diagnostic, Span, SpecSemanticError
from gaitc.ir.formula import Var, unreachable
from gaitc.ir.roles import Fails, WearsUpTo
from ltlcompiler import syntax as s
from ltlcompiler.fragment import FormulaChecker
from ltlcompiler.model import (
    NO_GAIT,
    Gait,
    GaitKind,
    Hazard,
    Leg,
    Model,
    Primitive,
    Section,
    Transition,
    UserFormula,
)
from ltlcompiler.names import Namespace, expand, expand_all
from ltlcompiler.regions import (
    RegionMap,
    add_grid,
    add_regions,
    apply_blocks,
    build_transitions,
    reachable,
)

METHODS = ("full", "random", "reset")


def _line(span: Span | None) -> int:
    return span.line if span is not None else 0


MAX_HEALTH = 100  # health levels per leg

#: The statements that declare names, checked first and in file order (a name may be used
#: before the statement that declares it).
Declaration = s.LegsDecl | s.GaitDecl | s.GridDecl | s.RegionDecl | s.HazardDecl


class _Statements:
    """The statements of a file sorted by kind, each kind in file order.

    The one dispatch over statements in the checker: a ``match`` over every kind of
    :data:`ltlcompiler.syntax.Statement`, so mypy reports a kind added to the syntax and
    not sorted here; the passes of :class:`_Checker` then read the lists they need."""

    def __init__(self, spec: s.SpecFile) -> None:
        self.declarations: list[Declaration] = []
        self.robots: list[s.RobotDecl] = []
        self.blocks: list[s.BlockDecl] = []
        self.edges: list[s.EdgeDecl] = []
        self.caches: list[s.CacheDecl] = []
        self.hazards: list[s.HazardDecl] = []
        self.starts: list[s.StartDecl] = []
        self.visits: list[s.VisitDecl] = []
        self.formulas: list[s.AssumeDecl | s.GuaranteeDecl] = []
        for st in spec.statements:
            match st:
                case s.RobotDecl():
                    self.robots.append(st)
                case s.LegsDecl() | s.GaitDecl() | s.GridDecl() | s.RegionDecl():
                    self.declarations.append(st)
                case s.HazardDecl():
                    self.declarations.append(st)
                    self.hazards.append(st)
                case s.BlockDecl():
                    self.blocks.append(st)
                case s.EdgeDecl():
                    self.edges.append(st)
                case s.CacheDecl():
                    self.caches.append(st)
                case s.StartDecl():
                    self.starts.append(st)
                case s.VisitDecl():
                    self.visits.append(st)
                case s.AssumeDecl() | s.GuaranteeDecl():
                    self.formulas.append(st)
                case _:
                    unreachable(st)


class _Checker:
    def __init__(self, spec: s.SpecFile) -> None:
        self.spec = spec
        self.file = spec.file
        self.statements = _Statements(spec)
        self.ns = Namespace()
        self.rmap = RegionMap()
        self.diagnostics: list[Diagnostic] = []
        self.health: dict[str, int] = {}
        self.start_span: Span | None = None  # the start statement
        self.cache_spans: list[Span | None] = []  # each cache's name in its statement
        self.leg_spans: dict[str, Span | None] = {}
        self.gait_decls: list[s.GaitDecl] = []

    def _top(self) -> Span:
        return Span(self.file, 1, 1)

    # ------------------------------------------------------------ declarations
    def declare(self) -> None:
        """First pass, in file order: every name of every kind enters the namespace."""
        for st in self.statements.declarations:
            match st:
                case s.LegsDecl():
                    self._legs(st)
                case s.GaitDecl():
                    if st.name.text == NO_GAIT:
                        raise SpecSemanticError(
                            "noGait is built in (it keeps the robot in place); choose another "
                            "name",
                            st.name.span,
                        )
                    self.ns.declare(st.name, "gait")
                    self.gait_decls.append(st)
                case s.GridDecl():
                    add_grid(self.rmap, st, self.ns)
                case s.RegionDecl():
                    add_regions(self.rmap, st, self.ns)
                case s.HazardDecl():
                    self.ns.declare(st.name, "hazard")
                case _:
                    unreachable(st)
        self.ns.kinds[NO_GAIT] = "gait"
        self.ns.spans[NO_GAIT] = None
        if not self.health:
            raise SpecSemanticError(
                "no legs: declare the robot's legs, e.g. 'legs L1..L4 health 3'", self._top()
            )
        apply_blocks(self.rmap, self.statements.blocks, self.ns, self.file)

    def _legs(self, st: s.LegsDecl) -> None:
        if st.health < 1:
            raise SpecSemanticError(
                f"health must be at least 1 (1 means permanently failed), not {st.health}",
                st.health_span,
            )
        if st.health > MAX_HEALTH:
            raise SpecSemanticError(
                f"health {st.health} is more than the {MAX_HEALTH} levels gaitc supports",
                st.health_span, hint="the thesis's robots have at most 5 levels; every level "
                "adds a state per leg to the game")
        for name in expand_all(st.legs):
            self.ns.declare(name, "leg")
            self.health[name.text] = st.health
            self.leg_spans[name.text] = name.span

    def robot_name(self) -> str:
        robots = self.statements.robots
        if len(robots) > 1:
            raise SpecSemanticError(
                f"a second 'robot' statement (the first is at line {_line(robots[0].span)}); "
                "keep one",
                robots[1].span,
            )
        return robots[0].name if robots else ""

    # ------------------------------------------------------------ legs and gaits
    def legs(self) -> tuple[Leg, ...]:
        starts = self.statements.starts
        initial = dict(self.health)
        initial_span: dict[str, Span | None] = {}
        for st in starts[:1]:
            for init in st.health:
                for name in expand(init.legs):
                    leg = self.ns.require(name, "leg", "in start")
                    if not 1 <= init.value <= self.health[leg]:
                        raise SpecSemanticError(
                            f"initial health of {leg} is {init.value}, but {leg} has health "
                            f"levels 1..{self.health[leg]}",
                            init.value_span,
                        )
                    initial[leg] = init.value
                    initial_span[leg] = init.span
        return tuple(
            Leg(name, h, initial[name], span=self.leg_spans[name],
                initial_span=initial_span.get(name))
            for name, h in self.health.items()
        )

    def gaits(self) -> tuple[Gait, ...]:
        out = [self._gait(st) for st in self.gait_decls]
        out.append(Gait(NO_GAIT, GaitKind.NONE, ()))
        return tuple(out)

    def _gait(self, st: s.GaitDecl) -> Gait:
        name = st.name.text
        if st.correction and st.legs is not None:
            raise SpecSemanticError(
                f"correction gait '{name}' cannot use legs: correction gaits use no health "
                "(thesis section 3.4.1); remove 'uses ...' or declare it with 'gait'",
                st.span,
            )
        if not st.correction and st.legs is None:
            raise SpecSemanticError(
                f"gait '{name}' uses no legs; add 'uses L1, L2' (or declare it as "
                "'correction gait')",
                st.name.span,
            )
        used: list[str] = []
        failed: list[s.Name] = []
        for leg in expand_all(st.legs or ()):
            known = self.ns.require(leg, "leg", f"in gait {name}")
            if known in used:
                raise SpecSemanticError(
                    f"leg '{known}' is listed twice in gait {name}", leg.span
                )
            used.append(known)
            if self.health[known] == 1:
                failed.append(leg)
        if failed:
            self.diagnostics.append(Diagnostic(
                f"gait '{name}' uses leg {failed[0].text}, which has health 1 (permanently "
                "failed), so the gait can never be selected",
                failed[0].span,
            ))
        fired = tuple(used)  # the order the gait names its legs: their firing order
        order = list(self.health)
        used.sort(key=order.index)
        kind = GaitKind.CORRECTION if st.correction else GaitKind.MOVE
        gait = Gait(name, kind, tuple(used), span=st.span, primitive=self._primitive(st),
                    fired=fired)
        self._inline_valves(gait, st)
        return gait

    def _inline_valves(self, gait: Gait, st: s.GaitDecl) -> None:
        """Inline valves give one 0/1 per leg, in the order the legs are declared, and may
        fire no leg the gait does not use (none for a correction gait): every command that
        reads the spec refuses a gait whose valves would wear a leg the health reasoning
        takes as idle (:meth:`Gait.idle_fired`; issue 60)."""
        prim = st.primitive
        if gait.primitive is None or not gait.primitive.valves or isinstance(
                prim, s.RobotPrimitive) or prim is None:
            return
        legs = list(self.health)
        for state in prim.states:
            if len(state.text) != len(legs):
                raise SpecSemanticError(
                    f"valve state '{state.text}' has {len(state.text)} valves, but the robot "
                    f"has {len(legs)} legs; inline valves give one 0/1 per leg, in the order "
                    f"the legs are declared ({', '.join(legs)})",
                    state.span,
                )
        pressed = [leg for i, leg in enumerate(legs)
                   if any(t.text[i] == "1" for t in prim.states)]
        wrong = gait.idle_fired(pressed, "inline")
        if wrong is not None:
            raise SpecSemanticError(wrong[0], prim.span or st.span, wrong[1])

    def _primitive(self, st: s.GaitDecl) -> Primitive | None:
        prim = st.primitive
        if prim is None:
            return None
        if isinstance(prim, s.RobotPrimitive):  # else a list of valve states
            method = prim.method
            if method is not None and method.text not in METHODS:
                raise SpecSemanticError(
                    f"unknown gait-graph method '{method.text}'; use one of "
                    + ", ".join(METHODS),
                    method.span,
                )
            return Primitive(
                robot=prim.robot,
                direction=prim.direction,
                method=None if method is None else method.text,
                span=prim.span,
            )
        width = len(prim.states[0].text)
        for state in prim.states:
            if set(state.text) - {"0", "1"}:
                raise SpecSemanticError(
                    f"valve state '{state.text}' may contain only 0 and 1, one character per "
                    "valve",
                    state.span,
                )
            if len(state.text) != width:
                raise SpecSemanticError(
                    f"valve state '{state.text}' has {len(state.text)} valves, but the first "
                    f"state has {width}; every state needs one 0/1 per valve",
                    state.span,
                )
        return Primitive(valves=tuple(t.text for t in prim.states), span=prim.span)

    # ------------------------------------------------------------ map and task
    def transitions(self) -> tuple[Transition, ...]:
        trans = build_transitions(self.rmap, self.gait_decls, self.statements.edges, self.ns,
                                  self.diagnostics)
        used = {g for t in trans for g in t.gaits}
        for st in self.gait_decls:
            if st.name.text in used:
                continue
            if st.directions:
                ways = " or ".join(d.name for d in st.directions)
                why = f"it moves {ways}, but no grid move or edge goes {ways}"
            else:
                why = "it has no 'moves' and no edge names it"
            self.diagnostics.append(
                Diagnostic(f"gait '{st.name.text}' can never be used: {why}", st.name.span)
            )
        return trans

    def caches(self) -> tuple[str, ...]:
        out: list[str] = []
        self.cache_spans = []
        for st in self.statements.caches:
            for ref in st.regions:
                name = self.rmap.resolve(ref, self.ns, "in cache")
                if name in out:
                    raise SpecSemanticError(f"region '{name}' is a cache twice", ref.span)
                out.append(name)
                self.cache_spans.append(ref.span)
        return tuple(out)

    def hazards(self, caches: tuple[str, ...]) -> tuple[Hazard, ...]:
        out: list[Hazard] = []
        for st in self.statements.hazards:
            hazard = st.name.text
            if st.wears is not None and not st.regions:
                raise SpecSemanticError(
                    f"hazard '{hazard}' wears the legs but lists no regions; add the regions "
                    f"it covers before 'wears', e.g. 'hazard {hazard}: r2, r5 wears "
                    f"{st.wears}'",
                    st.span,
                )
            if not st.regions:
                raise SpecSemanticError(
                    f"hazard '{hazard}' lists no regions; add the regions it covers, e.g. "
                    f"'hazard {hazard}: r2, r5'",
                    st.span,
                )
            regions: list[str] = []
            for ref in st.regions:
                name = self.rmap.resolve(ref, self.ns, f"in hazard {hazard}")
                if name in caches:
                    raise SpecSemanticError(
                        f"region '{name}' is both a cache and in hazard '{hazard}'; the thesis "
                        "assumes cache and hazard regions are disjoint, so remove it from one",
                        ref.span,
                    )
                if name in regions:
                    raise SpecSemanticError(
                        f"region '{name}' is listed twice in hazard '{hazard}'", ref.span
                    )
                regions.append(name)
            self._wear(st)
            out.append(Hazard(hazard, tuple(regions), span=st.span,
                              harm=Fails() if st.wears is None else WearsUpTo(st.wears)))
        return tuple(out)

    def _wear(self, st: s.HazardDecl) -> None:
        """``wears 0`` is an error; ``wears 1`` a warning: it is eq. 3.5's normal wear."""
        hazard = st.name.text
        if st.wears == 0:
            raise SpecSemanticError(
                f"hazard '{hazard}' wears 0 levels; a hazard that wears the legs takes at "
                "least 1 level a step",
                st.wears_span,
                hint="write 'wears 2' or more, or drop 'wears' for a hazard that fails the "
                "legs at once",
            )
        if st.wears == 1:
            self.diagnostics.append(Diagnostic(
                f"hazard '{hazard}' wears 1 level, which is no worse than the normal wear of "
                "a move (eq. 3.5: a leg in use may lose one level), so the hazard changes "
                "nothing",
                st.wears_span,
                hint="write 'wears 2' or more, or drop 'wears' for a hazard that fails the "
                "legs at once",
            ))

    def start(self) -> str:
        starts = self.statements.starts
        if not starts:
            raise SpecSemanticError(
                "no start region; add 'start REGION' (e.g. 'start "
                f"{self.rmap.regions[0].name}')",
                self._top(),
            )
        if len(starts) > 1:
            raise SpecSemanticError(
                f"a second 'start' statement (the first is at line {_line(starts[0].span)}); "
                "keep one",
                starts[1].span,
            )
        self.start_span = starts[0].span
        return self.rmap.resolve(starts[0].region, self.ns, "as the start")

    def goals(self, start: str, trans: tuple[Transition, ...]) -> tuple[UserFormula, ...]:
        out: list[UserFormula] = []
        seen: set[str] = set()
        reach = reachable(start, trans)
        for st in self.statements.visits:
            for ref in st.regions:
                name = self.rmap.resolve(ref, self.ns, "in goal")
                if name in seen:
                    raise SpecSemanticError(f"region '{name}' is a goal twice", ref.span)
                seen.add(name)
                if name not in reach:
                    self.diagnostics.append(Diagnostic(
                        f"goal region '{name}' is unreachable from the start '{start}' in the "
                        "region graph, so the specification is unrealizable",
                        ref.span,
                    ))
                out.append(UserFormula(Section.LIVENESS, Var(name, span=ref.span), span=st.span))
        return tuple(out)

    def formulas(self) -> tuple[tuple[UserFormula, ...], tuple[UserFormula, ...]]:
        checker = FormulaChecker(self.ns, self.health, set(self.rmap.blocked))
        assumptions: list[UserFormula] = []
        guarantees: list[UserFormula] = []
        for st in self.statements.formulas:
            match st:
                case s.AssumeDecl():
                    assumptions.append(checker.check(st.formula, st.span, assumption=True))
                case s.GuaranteeDecl():
                    guarantees.append(checker.check(st.formula, st.span, assumption=False))
                    if checker.robot_free(st.formula):
                        self.diagnostics.append(Diagnostic(
                            "this guarantee names only what the environment chooses (hazards, "
                            "leg health), so the robot cannot make it hold: the spec is "
                            "unrealizable unless the assumptions already force it",
                            st.span, hint="write it as 'assume', or add a region or gait the "
                            "robot controls"))
                case _:
                    unreachable(st)
        return tuple(assumptions), tuple(guarantees)


def check(spec: s.SpecFile) -> tuple[Model, list[Diagnostic]]:
    """Check ``spec`` and build its :class:`Model`; warnings are returned, errors raised."""
    c = _Checker(spec)
    c.declare()
    name = c.robot_name()
    legs = c.legs()
    gaits = c.gaits()
    trans = c.transitions()
    caches = c.caches()
    hazards = c.hazards(caches)
    start = c.start()
    goals = c.goals(start, trans)
    assumptions, guarantees = c.formulas()
    model = Model(
        name=name,
        legs=legs,
        gaits=gaits,
        regions=tuple(c.rmap.regions),
        transitions=trans,
        caches=caches,
        hazards=hazards,
        start=start,
        goals=goals,
        assumptions=assumptions,
        guarantees=guarantees,
        grid=c.rmap.grid,
        file=spec.file,
        start_span=c.start_span,
        cache_spans=tuple(c.cache_spans),
    )
    order = sorted(
        c.diagnostics,
        key=lambda d: (d.span.line, d.span.column) if d.span is not None else (0, 0),
    )
    return model, order

