"""Independent checker: proves that an explicit controller satisfies a GR(1) specification.

Shares no code with the solver's fixpoint: formulas get their own BDD translation (dd.cudd)
here, safety is checked node by node (every ρe-allowed input has a successor, every edge keeps
ρs), and liveness by SCC analysis (networkx) in the style of Bloem et al., JCSS 78(3) 2012, §5.
"""

from __future__ import annotations

import html
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import networkx as nx

from gaitc.ir.bitblast import bitblast
from gaitc.ir.bits import bits_mismatch
from gaitc.ir.controller import Controller, ControllerKind
from gaitc.ir.spec import SEMANTICS, GR1Spec, Semantics
from gaitc.verifier.logic import Bits, Logic

if TYPE_CHECKING:
    from dd.cudd import Function

MAX_PROBLEMS = 60


@dataclass(frozen=True)
class VerificationReport:
    """The verdict: ``ok`` when no problem was found; counterexamples and statistics."""

    ok: bool
    problems: tuple[str, ...]
    notes: tuple[str, ...] = ()
    nodes: int = 0
    edges: int = 0
    sccs: int = 0
    kind: ControllerKind = ControllerKind.STRATEGY
    semantics: Semantics = Semantics.DEFAULT
    symbolic: bool = False  # checked by fixpoints over BDDs (gaitc.verifier.symbolic), no graph

    def __repr__(self) -> str:
        return f"<VerificationReport: {self.summary()}>"

    def _repr_html_(self) -> str:
        items = "".join(f"<li>{html.escape(p)}</li>" for p in self.problems)
        head = "verified" if self.ok else "NOT verified"
        return f"<p><b>{head}</b>: {html.escape(self.summary())}</p>" + (
            f"<ul>{items}</ul>" if items else "")

    def to_json(self) -> dict[str, Any]:
        """The report for ``gaitc verify --json`` (docs/json.md)."""
        return {"ok": self.ok, "problems": list(self.problems), "notes": list(self.notes),
                "nodes": self.nodes, "edges": self.edges, "sccs": self.sccs,
                "kind": self.kind, "semantics": self.semantics, "symbolic": self.symbolic,
                "summary": self.summary()}

    def summary(self) -> str:
        verdict = "ok" if self.ok else f"{len(self.problems)} problem(s)"
        if self.symbolic:
            return (f"symbolic {self.kind} {verdict}: {self.nodes} reachable (state, goal) "
                    "pairs, safety and fair goal-avoiding cycles checked by fixpoints "
                    f"({self.semantics} semantics)")
        return (f"{self.kind} {verdict}: {self.nodes} reachable nodes, {self.edges} edges, "
                f"{self.sccs} goal-avoiding cycle component(s) examined for fairness "
                f"({self.semantics} semantics)")


class Check:
    """State shared by the checks of one controller: valuations, reachable nodes, the graph."""

    def __init__(self, spec: GR1Spec, controller: Controller, semantics: Semantics) -> None:
        if semantics not in SEMANTICS:
            raise ValueError(f"unknown semantics {semantics!r}; use one of {', '.join(SEMANTICS)}")
        self.semantics, self.ctrl = semantics, controller
        self.spec = bitblast(spec)  # a format transformation, shared on purpose
        self.logic = Logic(self.spec)
        self.problems: list[str] = []
        self.notes: list[str] = []
        self.reachable: list[int] = []
        self.valuations: list[dict[str, bool]] = []
        self.graph: Any = nx.DiGraph()
        self.sccs = 0
        self._conj: dict[tuple[str, Bits | None], Function] = {}
        self._cubes: dict[tuple[int, tuple[str, ...]], Function] = {}
        self._next: dict[tuple[int, int], bool] = {}
        self.integer_of = {b: (name, iv) for name, iv in controller.integers.items()
                           for b in iv.bits}

    def trans(self, node: int) -> tuple[int, ...]:
        return tuple(self.ctrl.nodes[node].trans)

    def well_formed(self) -> bool:
        """Variable list, state vectors and node references; the other checks need them."""
        expected, c = self.logic.inputs + self.logic.outputs, self.ctrl
        mismatch = bits_mismatch(c.variables, expected)
        if mismatch is not None:
            self.problems.append(mismatch)
            return False
        count = len(c.nodes)
        for k, node in enumerate(c.nodes):
            if len(node.state) != len(expected) or any(b not in (0, 1) for b in node.state):
                self.problems.append(f"node {k}: state {list(node.state)} is not a 0/1 vector "
                                     f"of length {len(expected)}")
            self.problems += [f"node {k}: successor {t} does not exist"
                              for t in node.trans if not 0 <= t < count]
        self.problems += [f"initial node {k} does not exist" for k in c.initial
                          if not 0 <= k < count]
        if self.problems:
            return False
        self.valuations = [dict(zip(expected, map(bool, n.state), strict=True)) for n in c.nodes]
        seen = set(c.initial)
        self.reachable = sorted(seen)
        for source in self.reachable:  # the list grows while it is walked: breadth-first
            for target in self.trans(source):
                if target not in seen:
                    seen.add(target)
                    self.reachable.append(target)
        return True

    def show(self, node: int | Mapping[str, bool], names: Sequence[str] | None = None) -> str:
        """``{door1=1, x=3}``: a node's state (or an assignment); integers decoded."""
        val = self.valuations[node] if isinstance(node, int) else node
        names = self.logic.inputs + self.logic.outputs if names is None else names
        out, done = [], set()
        for n in names:
            name, iv = self.integer_of.get(n, (n, None))
            if iv is not None and set(iv.bits) <= set(names):
                if name not in done:
                    value = iv.low + sum(int(val[b]) << k for k, b in enumerate(iv.bits))
                    out.append(f"{name}={value}")
                    done.add(name)
            else:
                out.append(f"{n}={int(val[n])}")
        return "{" + ", ".join(out) + "}"

    def failing(self, section: str, src: int, dst: int | None = None) -> str:
        """The clauses of ``section`` that the node ``src`` (or the edge to ``dst``) violates;
        for an edge, followed by the successor's values of the next-state bits they read."""
        val = dict(self.valuations[src])
        if dst is not None:
            val.update({name + "'": value for name, value in self.valuations[dst].items()})
        bad = [(r, u) for r, u in self.logic.clauses(section) if not self.logic.holds(u, val)]
        read = {n[:-1] for _, u in bad for n in self.logic.support(u) if n.endswith("'")}
        names = [n for n in self.logic.inputs + self.logic.outputs if n in read]
        where = f" (next: {self.show(dst, names)})" if dst is not None and names else ""
        return ", ".join(r for r, _ in bad) + where

    def conj(self, section: str, node: int | None) -> Function:
        """Conjunction of a section; with ``node``, its unprimed bits fixed to the node's state."""
        key = (section, None if node is None else tuple(self.ctrl.nodes[node].state))
        found = self._conj.get(key)
        if found is None:
            if node is None:
                found = self.logic.bdd.true
                for _, u in self.logic.clauses(section):
                    found &= u
            else:
                found = self.logic.restrict(self.conj(section, None), self.valuations[node])
            self._conj[key] = found
        return found

    def next_cube(self, node: int, names: tuple[str, ...] | None = None) -> Function:
        """The primed cube of ``node``'s state (or of its ``names`` bits), cached per node."""
        names = self.logic.inputs + self.logic.outputs if names is None else names
        key = (node, names)
        if key not in self._cubes:
            val = self.valuations[node]
            self._cubes[key] = self.logic.bdd.cube({n + "'": val[n] for n in names})
        return self._cubes[key]

    def holds_next(self, u: Function, node: int) -> bool:
        """Truth of ``u`` (a BDD over primed bits only) for the successor ``node``."""
        key = (int(u), node)
        found = self._next.get(key)
        if found is None:
            val = self.valuations[node]
            found = self.logic.holds(u, {n: val[n[:-1]] for n in self.logic.support(u)})
            self._next[key] = found
        return found

    def label_edges(self, skip: Callable[[int, int], bool]) -> None:
        """The graph of reachable edges, each labelled with the liveness clauses it satisfies."""
        sections = ("env_liveness", "sys_liveness")
        for node in self.reachable:
            self.graph.add_node(node)
            goals = {s: [self.logic.restrict(u, self.valuations[node])
                         for _, u in self.logic.clauses(s)] for s in sections}
            for target in self.trans(node):
                if not skip(node, target):
                    labels = {s: frozenset(k for k, u in enumerate(goals[s])
                                           if self.holds_next(u, target)) for s in sections}
                    self.graph.add_edge(node, target, **labels)

    def fair_sccs(self, avoid: str, index: int, need: str | None) -> list[list[int]]:
        """SCCs of the edges not satisfying clause ``index`` of ``avoid`` in which every clause
        of ``need`` holds on some internal edge: a fair cycle that starves the avoided goal."""
        count = len(self.spec.section(need)) if need is not None else 0
        keep = [(a, b, d) for a, b, d in self.graph.edges(data=True)
                if index not in d.get(avoid, ())]
        components = nx.strongly_connected_components(nx.DiGraph((a, b) for a, b, _ in keep))
        comp = {n: i for i, component in enumerate(components) for n in component}
        seen: dict[int, set[int]] = {}  # component -> goals of `need` on its internal edges
        for a, b, d in keep:
            if comp[a] == comp[b]:
                seen.setdefault(comp[a], set()).update(d[need] if need is not None else ())
        self.sccs += len(seen)
        members: dict[int, list[int]] = {}
        for n, i in sorted(comp.items()):
            members.setdefault(i, []).append(n)
        return sorted(members[i] for i, goals in seen.items() if len(goals) == count)

    def report(self, kind: ControllerKind) -> VerificationReport:
        extra = len(self.problems) - MAX_PROBLEMS
        problems = self.problems[:MAX_PROBLEMS] + [f"... and {extra} more problem(s)"] * (extra > 0)
        return VerificationReport(
            ok=not problems,
            problems=tuple(problems),
            notes=tuple(self.notes[:MAX_PROBLEMS]),
            nodes=len(self.reachable),
            edges=self.graph.number_of_edges(),
            sccs=self.sccs,
            kind=kind,
            semantics=self.semantics,
        )


def few_nodes(nodes: Sequence[int], limit: int = 12) -> str:
    shown = ", ".join(str(n) for n in nodes[:limit])
    return f"[{shown}{', ...' if len(nodes) > limit else ''}] ({len(nodes)} nodes)"


# ---------------------------------------------------------------- strategies (system wins)
def verify(spec: GR1Spec, controller: Controller,
           semantics: Semantics = Semantics.DEFAULT) -> VerificationReport:
    """Prove that ``controller`` (a Mealy strategy) realizes ``spec`` under ``semantics``.

    Checks initial coverage, safety (every ρe-allowed input answered, every edge keeps ρs)
    and liveness (no fair cycle starves a system goal); see docs/solvers.md.
    """
    check = Check(spec, controller, semantics)
    if controller.kind != ControllerKind.STRATEGY:
        check.problems.append(f"the controller is a {controller.kind}, not a strategy for the "
                              "system")
    elif check.well_formed():
        _strategy_initial(check)
        broken = _strategy_safety(check)
        check.label_edges(lambda a, b: (a, b) in broken)
        for j, (rule, _) in enumerate(check.logic.clauses("sys_liveness")):
            check.problems += [
                f"nodes {few_nodes(c)}: a cycle through them satisfies every environment liveness "
                f"assumption infinitely often but never satisfies {rule}"
                for c in check.fair_sccs("sys_liveness", j, "env_liveness")
            ]
    return check.report(ControllerKind.STRATEGY)


def _strategy_initial(check: Check) -> None:
    logic, b = check.logic, check.logic.bdd
    theta = check.conj("env_init", None) & check.conj("sys_init", None)
    valid = []
    for node in check.ctrl.initial:
        val = check.valuations[node]
        if logic.holds(theta, val):
            valid.append(node)
        else:
            rules = check.failing("env_init", node) or check.failing("sys_init", node)
            check.problems.append(f"initial node {node}: its state {check.show(node)} "
                                  f"violates {rules}")
    if check.semantics == Semantics.DEFAULT:
        names, what = logic.inputs, "environment input"
        required = b.exist(set(logic.outputs), check.conj("env_init", None))
        need = "default semantics: some initial node must have these inputs and satisfy sys_init"
    else:
        names, what, required = logic.inputs + logic.outputs, "initial state", theta
        need = "robotics semantics: every state allowed by env_init and sys_init must be covered"
    covered = b.false
    for node in valid:
        covered |= b.cube({n: check.valuations[node][n] for n in names})
    if required & ~covered != b.false:
        example, count = logic.pick(required & ~covered, names, primed=False)
        others = f" (and {count - 1} more)" if count > 1 else ""
        shown = check.show(example, names)
        check.problems.append(f"no initial node for {what} {shown}{others} allowed by the "
                              f"assumptions ({need})")


def _strategy_safety(check: Check) -> set[tuple[int, int]]:
    """Every ρe-allowed input has a successor; every edge keeps ρs. Returns ρe-breaking edges."""
    logic, b = check.logic, check.logic.bdd
    primed_outputs = {n + "'" for n in logic.outputs}
    broken: set[tuple[int, int]] = set()
    for node in check.reachable:
        succ = check.trans(node)
        assumption, guarantee = check.conj("env_trans", node), check.conj("sys_trans", node)
        covered, moves = b.false, b.false
        for target in succ:
            covered |= check.next_cube(target, logic.inputs)
            moves |= check.next_cube(target)
        missing = b.exist(primed_outputs, assumption) & ~covered
        if missing != b.false:
            example, count = logic.pick(missing, logic.inputs, primed=True)
            others = f" (and {count - 1} other input(s))" if count > 1 else ""
            shown = check.show(example, logic.inputs)
            check.problems.append(f"node {node}: environment input {shown} is allowed by the "
                                  f"assumptions but has no successor{others}")
        if moves & ~(assumption & guarantee) == b.false:
            continue  # every edge keeps both ρe and ρs: nothing to report per edge
        for target in succ:
            if not check.holds_next(assumption, target):
                # the play is the system's once the environment breaks ρe: whatever the
                # move (ρs kept or not), the edge is harmless, and no run that keeps the
                # assumptions takes it
                broken.add((node, target))
                check.notes.append(f"edge {node} -> {target}: the input violates "
                                   f"{check.failing('env_trans', node, target)}; harmless, the "
                                   "environment broke its assumptions there")
            elif not check.holds_next(guarantee, target):
                check.problems.append(f"edge {node} -> {target}: the system's move violates "
                                      f"{check.failing('sys_trans', node, target)}")
    return broken
