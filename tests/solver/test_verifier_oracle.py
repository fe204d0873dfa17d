"""The independent controller verifier against a brute-force oracle on random controllers.

The oracle unrolls the GR(1) acceptance condition over the explicit automaton (no BDDs);
random specs and random controllers, right or wrong, must get the same verdict from both.
"""

from __future__ import annotations

import random
from dataclasses import replace

import pytest

from gaitc.ir.controller import Controller
from gaitc.ir.formula import And, Expr, Iff, Not, Or, Var
from gaitc.ir.spec import Clause, GR1Spec, Variable
from gaitc.verifier.strategy import verify


def _oracle(spec: GR1Spec, ctrl: Controller, semantics: str) -> bool:
    """The verifier's verdict recomputed by enumerating every valuation (tiny specs only)."""
    from itertools import product

    from gaitc.ir.evaluation import evaluate
    from gaitc.ir.formula import conj

    ins, outs = [v.name for v in spec.inputs], [v.name for v in spec.outputs]
    names = ins + outs
    sec = {s: conj(c.formula for c in spec.section(s)) for s in
           ("env_init", "sys_init", "env_trans", "sys_trans")}
    state = [dict(zip(names, n.state, strict=True)) for n in ctrl.nodes]

    def edge(a: int, b: int) -> dict[str, int]:
        return {**state[a], **{k + "'": v for k, v in state[b].items()}}

    starts = [k for k in ctrl.initial if evaluate(sec["env_init"], state[k])
              and evaluate(sec["sys_init"], state[k])]
    if len(starts) != len(ctrl.initial):
        return False
    for bits in product((0, 1), repeat=len(names)):
        val = dict(zip(names, bits, strict=True))
        if not (evaluate(sec["env_init"], val) and (semantics == "default"
                                                      or evaluate(sec["sys_init"], val))):
            continue
        keys = ins if semantics == "default" else names
        if not any(all(state[k][n] == val[n] for n in keys) for k in starts):
            return False
    seen, todo = set(starts), list(starts)
    while todo:
        node = todo.pop()
        for t in ctrl.nodes[node].trans:
            if t not in seen:
                seen.add(t)
                todo.append(t)
    live_edges = []
    for node in seen:
        for x in product((0, 1), repeat=len(ins)):
            allowed = any(evaluate(sec["env_trans"], {**state[node], **{
                n + "'": v for n, v in zip(names, x + y, strict=True)}})
                for y in product((0, 1), repeat=len(outs)))
            if allowed and not any(tuple(state[t][n] for n in ins) == x
                                   for t in ctrl.nodes[node].trans):
                return False
        for t in ctrl.nodes[node].trans:
            if not evaluate(sec["env_trans"], edge(node, t)):
                continue
            if not evaluate(sec["sys_trans"], edge(node, t)):
                return False
            live_edges.append((node, t))

    def reach(edges: list[tuple[int, int]], start: int) -> set[int]:
        out, todo = set(), [start]
        while todo:
            a = todo.pop()
            for x, y in edges:
                if x == a and y not in out:
                    out.add(y)
                    todo.append(y)
        return out

    for goal in spec.sys_liveness:
        rest = [(a, b) for a, b in live_edges if not evaluate(goal.formula, edge(a, b))]
        for a, b in rest:  # an edge on a cycle of `rest`, and the cycle's SCC is fair?
            if a in reach(rest, b):
                scc = {n for n in reach(rest, a) if a in reach(rest, n)}
                inner = [(x, y) for x, y in rest if x in scc and y in scc]
                if all(any(evaluate(c.formula, edge(x, y)) for x, y in inner)
                       for c in spec.env_liveness):
                    return False
    return True


def _random_formula(rng: random.Random, names: list[str], primes: str, depth: int = 2) -> Expr:
    """A small random formula; only the variables named in ``primes`` may appear primed."""
    if depth == 0 or rng.random() < 0.3:
        name = rng.choice(names)
        return Var(name, name in primes and rng.random() < 0.6)
    kind = rng.choice(["not", "and", "or", "iff"])
    if kind == "not":
        return Not(_random_formula(rng, names, primes, depth - 1))
    left, right = (_random_formula(rng, names, primes, depth - 1) for _ in range(2))
    return {"and": And((left, right)), "or": Or((left, right)), "iff": Iff(left, right)}[kind]


@pytest.mark.parametrize("seed", range(40))
def test_verifier_agrees_with_brute_force_oracle(seed: int) -> None:
    synthesis = pytest.importorskip("gaitc.solver.synthesis")
    rng = random.Random(seed)
    names = ["a", "b", "x", "y"]

    def clauses(count: int, primes: str) -> tuple[Clause, ...]:
        return tuple(Clause(_random_formula(rng, names, primes)) for _ in range(count))

    spec = GR1Spec(
        inputs=(Variable("a"), Variable("b")), outputs=(Variable("x"), Variable("y")),
        env_init=clauses(rng.randint(0, 1), ""), sys_init=clauses(rng.randint(0, 1), ""),
        env_trans=clauses(rng.randint(0, 1), "ab"), sys_trans=clauses(rng.randint(0, 2), "abxy"),
        env_liveness=clauses(rng.randint(0, 1), "ab"),
        sys_liveness=clauses(rng.randint(1, 2), "abxy"),
    )
    for semantics in ("default", "robotics"):
        ctrl = synthesis.synthesize(spec, semantics)
        if ctrl is None:
            continue
        candidates = [ctrl]
        # mutants: a dropped edge, a redirected edge, a flipped bit
        for _ in range(6 if ctrl.nodes else 0):
            nodes = list(ctrl.nodes)
            k = rng.randrange(len(nodes))
            n = nodes[k]
            choice = rng.randrange(3)
            if choice == 0 and n.trans:
                n = replace(n, trans=tuple(t for t in n.trans if t != rng.choice(n.trans)))
            elif choice == 1 and n.trans:
                n = replace(n, trans=tuple(sorted(set(n.trans[1:]) | {rng.randrange(len(nodes))})))
            else:
                bit = rng.randrange(len(n.state))
                n = replace(n, state=(*n.state[:bit], 1 - n.state[bit], *n.state[bit + 1:]))
            nodes[k] = n
            candidates.append(replace(ctrl, nodes=tuple(nodes)))
        for candidate in candidates:
            report = verify(spec, candidate, semantics)
            assert report.ok == _oracle(spec, candidate, semantics), (semantics, report.problems)
