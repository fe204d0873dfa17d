"""Independent checker: proves that an explicit controller satisfies a GR(1) specification.

Shares no code with the solver's fixpoint: formulas get their own BDD translation (dd.cudd)
here, safety is checked node by node (every ρe-allowed input has a successor, every edge keeps
ρs), and liveness by SCC analysis (networkx) in the style of Bloem et al., JCSS 78(3) 2012, §5.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import dd.cudd as cudd
import networkx as nx

from slugs_bridge.controller import Controller
from slugs_bridge.formula import And, Const, Expr, Iff, Implies, Not, Or, Var, Xor
from slugs_bridge.spec import Clause, GR1Spec

SEMANTICS = ("default", "robotics")
MAX_PROBLEMS = 60
Bits = tuple[int, ...]


@dataclass(frozen=True)
class VerificationReport:
    """The verdict: ``ok`` when no problem was found; counterexamples and statistics."""

    ok: bool
    problems: tuple[str, ...]
    notes: tuple[str, ...] = ()
    nodes: int = 0
    edges: int = 0
    sccs: int = 0
    kind: str = "strategy"
    semantics: str = "default"

    def summary(self) -> str:
        verdict = "ok" if self.ok else f"{len(self.problems)} problem(s)"
        return (
            f"{self.kind} {verdict}: {self.nodes} reachable nodes, {self.edges} edges, "
            f"{self.sccs} SCCs checked ({self.semantics} semantics)"
        )


@dataclass(frozen=True)
class Automaton:
    """The part of a controller the checks read: bit names, node states, successors."""

    variables: tuple[str, ...]
    states: Mapping[int, Bits]
    trans: Mapping[int, tuple[int, ...]]
    initial: tuple[int, ...]


def automaton_of(controller: Controller) -> Automaton:
    """View a :class:`~slugs_bridge.controller.Controller` as an :class:`Automaton`."""
    states = {k: tuple(node.state) for k, node in enumerate(controller.nodes)}
    trans = {k: tuple(node.trans) for k, node in enumerate(controller.nodes)}
    return Automaton(tuple(controller.variables), states, trans, tuple(controller.initial))


def _boolean(spec: GR1Spec) -> GR1Spec:
    if not spec.has_integers:
        return spec
    from slugs_bridge.bitblast import bitblast

    blasted: GR1Spec = bitblast(spec)
    return blasted


def _rule(section: str, index: int, clause: Clause) -> str:
    where = ""
    if clause.origin is not None:
        where = f" '{clause.origin.rule}'"
        if clause.origin.span is not None:
            where += f" ({clause.origin.span})"
    return f"{section} clause #{index + 1}{where}"


class _Logic:
    """BDDs of the spec's clauses over unprimed and primed bits, with cached evaluation."""

    def __init__(self, spec: GR1Spec) -> None:
        self.spec = spec
        self.inputs = tuple(v.name for v in spec.inputs)
        self.outputs = tuple(v.name for v in spec.outputs)
        self.bdd = cudd.BDD()
        for name in self.inputs + self.outputs:
            self.bdd.declare(name, name + "'")
        self._memo: dict[int, Any] = {}
        self._keep: list[Expr] = []
        self._cache: dict[tuple[int, Bits], bool] = {}
        self._restrict: dict[tuple[int, Bits], Any] = {}
        self._support: dict[int, tuple[str, ...]] = {}
        self._clauses: dict[str, list[tuple[str, Any]]] = {}

    def clauses(self, section: str) -> list[tuple[str, Any]]:
        """``(description, BDD)`` of every clause of ``section``."""
        if section not in self._clauses:
            items = self.spec.section(section)
            self._clauses[section] = [
                (_rule(section, k, c), self.translate(c.formula)) for k, c in enumerate(items)
            ]
        return self._clauses[section]

    def translate(self, expr: Expr) -> Any:
        cached = self._memo.get(id(expr))
        if cached is not None:
            return cached
        b = self.bdd
        result: Any
        if isinstance(expr, Const):
            result = b.true if expr.value else b.false
        elif isinstance(expr, Var):
            name = expr.name + ("'" if expr.primed else "")
            if name not in b.vars:
                raise KeyError(f"variable '{name}' is not declared in the specification")
            result = b.var(name)
        elif isinstance(expr, Not):
            result = ~self.translate(expr.arg)
        elif isinstance(expr, (And, Or)):
            parts = [self.translate(a) for a in expr.args]
            result = b.true if isinstance(expr, And) else b.false
            for p in parts:
                result = (result & p) if isinstance(expr, And) else (result | p)
        elif isinstance(expr, (Xor, Iff, Implies)):
            left, right = self.translate(expr.left), self.translate(expr.right)
            op = {Xor: "xor", Iff: "equiv", Implies: "implies"}[type(expr)]
            result = b.apply(op, left, right)
        else:
            raise TypeError(f"the verifier cannot translate {type(expr).__name__} formulas")
        self._memo[id(expr)] = result
        self._keep.append(expr)
        return result

    def support(self, u: Any) -> tuple[str, ...]:
        key = int(u)
        if key not in self._support:
            self._support[key] = tuple(sorted(self.bdd.support(u)))
        return self._support[key]

    def holds(self, u: Any, valuation: Mapping[str, bool]) -> bool:
        """Truth of ``u`` under ``valuation`` (must cover its support); cached on the support."""
        names = self.support(u)
        if not names:
            return bool(u == self.bdd.true)
        key = (int(u), tuple(int(valuation[n]) for n in names))
        found = self._cache.get(key)
        if found is None:
            found = self.bdd.let({n: valuation[n] for n in names}, u) == self.bdd.true
            self._cache[key] = found
        return found

    def restrict(self, u: Any, current: Mapping[str, bool]) -> Any:
        """``u`` with the unprimed bits fixed to ``current`` (cached on those bits)."""
        names = tuple(n for n in self.support(u) if not n.endswith("'"))
        key = (int(u), tuple(int(current[n]) for n in names))
        found = self._restrict.get(key)
        if found is None:
            found = self.bdd.let({n: current[n] for n in names}, u) if names else u
            self._restrict[key] = found
        return found

    def cube(self, names: Iterable[str], valuation: Mapping[str, bool], primed: bool) -> Any:
        suffix = "'" if primed else ""
        return self.bdd.cube({n + suffix: valuation[n] for n in names})

    def show(self, assignment: Mapping[str, bool], names: Sequence[str], primed: bool) -> str:
        suffix = "'" if primed else ""
        return "{" + ", ".join(f"{n}={int(assignment.get(n + suffix, False))}" for n in names) + "}"


class _Problems:
    def __init__(self) -> None:
        self.items: list[str] = []
        self.notes: list[str] = []
        self.dropped = 0

    def add(self, message: str) -> None:
        if len(self.items) < MAX_PROBLEMS:
            self.items.append(message)
        else:
            self.dropped += 1

    def note(self, message: str) -> None:
        if len(self.notes) < MAX_PROBLEMS:
            self.notes.append(message)

    def final(self) -> tuple[str, ...]:
        extra = [f"... and {self.dropped} more problem(s)"] if self.dropped else []
        return tuple(self.items + extra)


class _Check:
    """Shared set-up of the strategy and counter-strategy checks."""

    def __init__(self, spec: GR1Spec, automaton: Automaton, semantics: str) -> None:
        if semantics not in SEMANTICS:
            raise ValueError(f"unknown semantics {semantics!r}; use 'default' or 'robotics'")
        self.semantics = semantics
        self.spec = _boolean(spec)
        self.auto = automaton
        self.logic = _Logic(self.spec)
        self.problems = _Problems()
        self.reachable: list[int] = []
        self.valuations: dict[int, dict[str, bool]] = {}
        self.graph: Any = nx.DiGraph()
        self.sccs = 0
        self._conj: dict[tuple[str, Bits | None], Any] = {}

    def well_formed(self) -> bool:
        """Variable list, state widths and node references; later checks need all three."""
        expected = self.logic.inputs + self.logic.outputs
        if self.auto.variables != expected:
            self.problems.add(
                f"the controller's variable list {list(self.auto.variables)} does not match "
                f"the specification's bits {list(expected)} (inputs first, then outputs)"
            )
            return False
        ok = True
        for node, bits in sorted(self.auto.states.items()):
            if len(bits) != len(expected) or any(b not in (0, 1) for b in bits):
                self.problems.add(f"node {node}: state {list(bits)} is not a 0/1 vector of "
                                  f"length {len(expected)}")
                ok = False
        for node, succ in sorted(self.auto.trans.items()):
            for target in succ:
                if target not in self.auto.states:
                    self.problems.add(f"node {node}: successor {target} does not exist")
                    ok = False
        for node in self.auto.initial:
            if node not in self.auto.states:
                self.problems.add(f"initial node {node} does not exist")
                ok = False
        if ok:
            self.valuations = {
                n: {v: bool(b) for v, b in zip(expected, bits, strict=True)}
                for n, bits in self.auto.states.items()
            }
            self.reachable = self._explore()
        return ok

    def _explore(self) -> list[int]:
        seen = set(self.auto.initial)
        order = sorted(seen)
        queue = list(order)
        while queue:
            node = queue.pop(0)
            for target in self.auto.trans[node]:
                if target not in seen:
                    seen.add(target)
                    order.append(target)
                    queue.append(target)
        return order

    def edge_valuation(self, src: int, dst: int) -> dict[str, bool]:
        val = dict(self.valuations[src])
        val.update({name + "'": value for name, value in self.valuations[dst].items()})
        return val

    def initial_states_hold(self, sections: Sequence[str]) -> None:
        for section in sections:
            for rule, u in self.logic.clauses(section):
                for node in self.auto.initial:
                    if not self.logic.holds(u, self.valuations[node]):
                        self.problems.add(f"initial node {node}: its state "
                                          f"{self.show_state(node)} violates {rule}")

    def show_state(self, node: int) -> str:
        names = self.logic.inputs + self.logic.outputs
        return self.logic.show(self.valuations[node], names, primed=False)

    def conj(self, section: str, node: int | None) -> Any:
        """Conjunction of a section; with ``node``, its unprimed bits fixed to the node's state."""
        key = (section, None if node is None else self.auto.states[node])
        found = self._conj.get(key)
        if found is None:
            found = self.logic.bdd.true
            for _, u in self.logic.clauses(section):
                found &= u if node is None else self.logic.restrict(u, self.valuations[node])
            self._conj[key] = found
        return found

    def label_edges(self, sections: Sequence[str], skip: Callable[[int, int], bool]) -> None:
        """Build the graph of reachable edges, each labelled with the goals it satisfies."""
        goals = {s: self.logic.clauses(s) for s in sections}
        for node in self.reachable:
            self.graph.add_node(node)
            for target in self.auto.trans[node]:
                if skip(node, target):
                    continue
                val = self.edge_valuation(node, target)
                labels = {
                    s: frozenset(k for k, (_, u) in enumerate(goals[s])
                                 if self.logic.holds(u, val))
                    for s in sections
                }
                self.graph.add_edge(node, target, **labels)

    def fair_sccs(self, avoid: str, index: int, need: str | None) -> list[list[int]]:
        """SCCs of the edges not satisfying goal ``avoid[index]`` in which every goal of
        ``need`` holds on some internal edge (a fair cycle that starves the avoided goal)."""
        count = len(self.spec.section(need)) if need is not None else 0
        keep = [(a, b) for a, b, d in self.graph.edges(data=True) if index not in d.get(avoid, ())]
        sub = nx.DiGraph(keep)
        found: list[list[int]] = []
        for component in nx.strongly_connected_components(sub):
            inner = sub.subgraph(component)
            if inner.number_of_edges() == 0:
                continue
            self.sccs += 1
            seen: set[int] = set()
            for a, b in inner.edges():
                if need is not None:
                    seen |= self.graph.edges[a, b][need]
            if len(seen) == count:
                found.append(sorted(component))
        return sorted(found)

    def report(self, kind: str) -> VerificationReport:
        problems = self.problems.final()
        return VerificationReport(
            ok=not problems, problems=problems, notes=tuple(self.problems.notes),
            nodes=len(self.reachable), edges=self.graph.number_of_edges(), sccs=self.sccs,
            kind=kind, semantics=self.semantics,
        )


# ---------------------------------------------------------------- strategies (system wins)
def verify(spec: GR1Spec, controller: Controller, semantics: str = "default") -> VerificationReport:
    """Prove that ``controller`` (a Mealy strategy) realizes ``spec`` under ``semantics``.

    Checks initial coverage, safety (every ρe-allowed input answered, every edge keeps ρs)
    and liveness (no fair cycle starves a system goal); see docs/solvers.md.
    """
    check = _Check(spec, automaton_of(controller), semantics)
    kind = controller.kind
    if kind != "strategy":
        check.problems.add(f"the controller is a {kind}, not a strategy for the system")
    elif check.well_formed():
        _strategy_initial(check)
        broken = _strategy_safety(check)
        check.label_edges(("env_liveness", "sys_liveness"), lambda a, b: (a, b) in broken)
        for j, (rule, _) in enumerate(check.logic.clauses("sys_liveness")):
            for component in check.fair_sccs("sys_liveness", j, "env_liveness"):
                check.problems.add(
                    f"nodes {_few(component)}: a cycle through them satisfies every environment "
                    f"liveness assumption infinitely often but never satisfies {rule}"
                )
    return check.report("strategy")


def _few(nodes: Sequence[int], limit: int = 12) -> str:
    shown = ", ".join(str(n) for n in nodes[:limit])
    return f"[{shown}{', ...' if len(nodes) > limit else ''}] ({len(nodes)} nodes)"


def _strategy_initial(check: _Check) -> None:
    check.initial_states_hold(("env_init", "sys_init"))
    logic, b = check.logic, check.logic.bdd
    theta = check.conj("env_init", None) & check.conj("sys_init", None)
    valid = [n for n in check.auto.initial if logic.holds(theta, check.valuations[n])]
    if check.semantics == "default":
        names, what = logic.inputs, "environment input"
        required = b.exist(set(logic.outputs), check.conj("env_init", None))
        need = "default semantics: some initial node must have these inputs and satisfy sys_init"
    else:
        names, what = logic.inputs + logic.outputs, "initial state"
        required = theta
        need = "robotics semantics: every state allowed by env_init and sys_init must be covered"
    covered = b.false
    for node in valid:
        covered |= logic.cube(names, check.valuations[node], primed=False)
    missing = required & ~covered
    if missing != b.false:
        example = b.pick(missing, care_vars=set(names))
        count = int(b.count(missing, nvars=len(names)))
        others = f" (and {count - 1} more)" if count > 1 else ""
        check.problems.add(
            f"no initial node for {what} {logic.show(example, names, primed=False)}{others} "
            f"allowed by the assumptions ({need})"
        )


def _strategy_safety(check: _Check) -> set[tuple[int, int]]:
    """Every ρe-allowed input has a successor; every edge keeps ρs. Returns ρe-breaking edges."""
    logic, b = check.logic, check.logic.bdd
    primed_outputs = {n + "'" for n in logic.outputs}
    primed_inputs = {n + "'" for n in logic.inputs}
    broken: set[tuple[int, int]] = set()
    for node in check.reachable:
        succ = check.auto.trans[node]
        allowed = b.exist(primed_outputs, check.conj("env_trans", node))
        covered = b.false
        for target in succ:
            covered |= logic.cube(logic.inputs, check.valuations[target], primed=True)
        missing = allowed & ~covered
        if missing != b.false:
            example = b.pick(missing, care_vars=primed_inputs)
            count = int(b.count(missing, nvars=len(primed_inputs)))
            others = f" (and {count - 1} other input(s))" if count > 1 else ""
            check.problems.add(
                f"node {node}: environment input {logic.show(example, logic.inputs, True)} is "
                f"allowed by the assumptions but has no successor{others}"
            )
        guarantee = check.conj("sys_trans", node)
        assumption = check.conj("env_trans", node)
        for target in succ:
            val = check.edge_valuation(node, target)
            if not logic.holds(assumption, val):
                broken.add((node, target))
                rules = [r for r, u in logic.clauses("env_trans") if not logic.holds(u, val)]
                check.problems.note(
                    f"edge {node} -> {target}: the input violates {rules[0]}; harmless, the "
                    "environment broke its assumptions there"
                )
            if not logic.holds(guarantee, val):
                rules = [r for r, u in logic.clauses("sys_trans") if not logic.holds(u, val)]
                check.problems.add(
                    f"edge {node} -> {target}: the move to state {check.show_state(target)} "
                    f"violates {', '.join(rules)}"
                )
    return broken


# ---------------------------------------------------------------- counter-strategies
def verify_counterstrategy(
    spec: GR1Spec, controller: Controller, semantics: str = "default"
) -> VerificationReport:
    """Prove that ``controller`` (an environment counter-strategy) makes ``spec`` unrealizable.

    Every run must either reach a position where the system has no move allowed by ρs, or
    satisfy every environment liveness assumption while missing some system goal forever.
    """
    check = _Check(spec, automaton_of(controller), semantics)
    kind = controller.kind
    if kind != "counterstrategy":
        check.problems.add(f"the controller is a {kind}, not a counter-strategy")
    elif check.well_formed():
        _counter_initial(check)
        _counter_safety(check)
        check.label_edges(("env_liveness", "sys_liveness"), lambda a, b: False)
        for i, (rule, _) in enumerate(check.logic.clauses("env_liveness")):
            for component in check.fair_sccs("env_liveness", i, None):
                check.problems.add(f"nodes {_few(component)}: a cycle through them never "
                                   f"satisfies {rule}, so the environment loses there")
        for component in check.fair_sccs("none", -1, "sys_liveness"):
            check.problems.add(f"nodes {_few(component)}: a cycle through them lets the system "
                               "satisfy every system goal infinitely often")
    return check.report("counterstrategy")


def _counter_initial(check: _Check) -> None:
    logic, b = check.logic, check.logic.bdd
    theta_e, theta_s = check.conj("env_init", None), check.conj("sys_init", None)
    for node in check.auto.initial:
        if not logic.holds(theta_e, check.valuations[node]):
            check.problems.add(f"initial node {node}: its state {check.show_state(node)} "
                               "violates env_init")
    if not check.auto.initial:
        stuck = b.exist(set(logic.inputs), theta_e & ~b.exist(set(logic.outputs), theta_s))
        if stuck == b.false:
            check.problems.add("the counter-strategy has no initial node, but the system can "
                               "always start")
        return
    if check.semantics == "robotics":
        return
    groups: dict[Bits, Any] = {}
    for node in check.auto.initial:
        key = tuple(int(check.valuations[node][n]) for n in logic.inputs)
        cube = logic.cube(logic.outputs, check.valuations[node], primed=False)
        groups[key] = groups.get(key, b.false) | cube
    for key, covered in sorted(groups.items()):
        start = dict(zip(logic.inputs, (bool(v) for v in key), strict=True))
        required = b.let(start, theta_e & theta_s)
        if required & ~covered == b.false:
            return
    key = min(groups)
    start = dict(zip(logic.inputs, (bool(v) for v in key), strict=True))
    example = b.pick(b.let(start, theta_e & theta_s) & ~groups[key], care_vars=set(logic.outputs))
    check.problems.add(
        f"default semantics: no initial input of the counter-strategy covers every system "
        f"start; e.g. input {logic.show(start, logic.inputs, False)} lacks outputs "
        f"{logic.show(example, logic.outputs, False)}"
    )


def _counter_safety(check: _Check) -> None:
    logic, b = check.logic, check.logic.bdd
    primed_outputs = {n + "'" for n in logic.outputs}
    markers = set()
    for node in check.reachable:
        succ = check.auto.trans[node]
        rho_e, rho_s = check.conj("env_trans", node), check.conj("sys_trans", node)
        if not succ:
            if node not in markers:
                stuck = b.exist({n + "'" for n in logic.inputs},
                                rho_e & ~b.exist(primed_outputs, rho_s))
                if stuck == b.false:
                    check.problems.add(f"node {node}: it has no successor, but the system has a "
                                       "move allowed by the guarantees for every input")
            continue
        inputs = {tuple(int(check.valuations[t][n]) for n in logic.inputs) for t in succ}
        if len(inputs) > 1:
            check.problems.add(f"node {node}: the environment must choose one input, but its "
                               f"successors carry {len(inputs)} different inputs")
            continue
        first = check.valuations[succ[0]]
        chosen = {n + "'": first[n] for n in logic.inputs}
        answers = b.let(chosen, rho_s)
        covered = b.false
        for target in succ:
            val = check.edge_valuation(node, target)
            if not logic.holds(rho_e, val):
                check.problems.add(f"edge {node} -> {target}: the environment's input "
                                   "violates env_trans")
            if answers == b.false:
                markers.add(target)
            elif not logic.holds(rho_s, val):
                check.problems.add(f"edge {node} -> {target}: the system answer violates "
                                   "sys_trans, so the environment need not consider it")
            covered |= logic.cube(logic.outputs, check.valuations[target], primed=True)
        missing = answers & ~covered
        if missing != b.false:
            example = b.pick(missing, care_vars=primed_outputs)
            check.problems.add(
                f"node {node}: system answer {logic.show(example, logic.outputs, True)} to input "
                f"{logic.show(chosen, logic.inputs, True)} is allowed by the guarantees but has "
                "no successor"
            )
