"""Random GR(1) games for the solver tests, and an explicit-state reference solver.

The reference solver is written here from the definitions of Bloem et al. (JCSS 2012):
sets of states and the three nested fixpoints, no BDDs, so that it shares nothing with
:mod:`gaitc.solver`. Specs are tiny (a handful of Boolean variables) so it can enumerate states.
"""

from __future__ import annotations

import itertools

from hypothesis import strategies as st

from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
    And,
    Const,
    Expr,
    Iff,
    Implies,
    Not,
    Or,
    Var,
    Xor,
)
from gaitc.ir.spec import Clause, GR1Spec, Variable


def clauses(*formulas: Expr) -> tuple[Clause, ...]:
    return tuple(Clause(f) for f in formulas)


def v(name: str, primed: bool = False) -> Var:
    return Var(name, primed)


# ---------------------------------------------------------------- an explicit reference solver
State = tuple[int, ...]


def _valuation(names: list[str], pre: State, post: State | None = None) -> dict[str, int]:
    out = dict(zip(names, pre, strict=True))
    if post is not None:
        out.update({n + "'": b for n, b in zip(names, post, strict=True)})
    return out


def explicit_realizable(spec: GR1Spec, semantics: str) -> bool:
    """Solve the GR(1) game by enumerating states (Boolean specs only)."""
    ins = [x.name for x in spec.inputs]
    outs = [y.name for y in spec.outputs]
    names = ins + outs
    states = [tuple(s) for s in itertools.product((0, 1), repeat=len(names))]
    xs = list(itertools.product((0, 1), repeat=len(ins)))
    ys = list(itertools.product((0, 1), repeat=len(outs)))

    def holds(section: tuple[Clause, ...], pre: State, post: State | None = None) -> bool:
        val = _valuation(names, pre, post)
        return all(evaluate(c.formula, val) for c in section)

    env_ok = {
        (s, x): holds(spec.env_trans, s, x + ys[0]) for s in states for x in xs
    }  # ρe may not read primed outputs in these tests
    sys_ok = {(s, t): holds(spec.sys_trans, s, t) for s in states for t in states}
    env_goals = [c.formula for c in spec.env_liveness] or [Const(True)]
    sys_goals = [c.formula for c in spec.sys_liveness] or [Const(True)]

    def goal(f: Expr, s: State, t: State) -> bool:
        return evaluate(f, _valuation(names, s, t))

    def cpre(target: object) -> set[State]:
        # ∀x'. ρe → ∃y'. ρs ∧ target(s, t)
        out = set()
        for s in states:
            if all(
                not env_ok[(s, x)] or any(sys_ok[(s, x + y)] and target(s, x + y) for y in ys)  # type: ignore[operator]
                for x in xs
            ):
                out.add(s)
        return out

    z: set[State] = set(states)
    while True:
        new_z = set(states)
        for sg in sys_goals:
            y_set: set[State] = set()
            while True:
                new_y = set(y_set)
                for eg in env_goals:
                    x_set = set(states)
                    while True:
                        zz, yy, xx = frozenset(z), frozenset(y_set), frozenset(x_set)
                        nxt = cpre(
                            lambda s, t, zz=zz, yy=yy, xx=xx, sg=sg, eg=eg: (
                                (goal(sg, s, t) and t in zz)
                                or t in yy
                                or (not goal(eg, s, t) and t in xx)
                            )
                        )
                        if nxt == x_set:
                            break
                        x_set = nxt
                    new_y |= x_set
                if new_y == y_set:
                    break
                y_set = new_y
            new_z &= y_set
        if new_z == z:
            break
        z = new_z
    for x in xs:
        starts = [x + y for y in ys]
        if not holds(spec.env_init, starts[0]):
            continue
        good = [s for s in starts if holds(spec.sys_init, s) and s in z]
        if semantics == "default" and not good:
            return False
        if semantics == "robotics" and any(holds(spec.sys_init, s) and s not in z for s in starts):
            return False
    return True


# ---------------------------------------------------------------- random tiny specs
def formulas(names: list[str], depth: int) -> st.SearchStrategy[Expr]:
    leaves = st.sampled_from(
        [Var(n.rstrip("'"), n.endswith("'")) for n in names] + [Const(True), Const(False)]
    )

    def grow(children: st.SearchStrategy[Expr]) -> st.SearchStrategy[Expr]:
        pair = st.tuples(children, children)
        return st.one_of(
            st.builds(Not, children),
            pair.map(lambda p: And(p)),
            pair.map(lambda p: Or(p)),
            pair.map(lambda p: Xor(*p)),
            pair.map(lambda p: Iff(*p)),
            pair.map(lambda p: Implies(*p)),
        )

    return st.recursive(leaves, grow, max_leaves=depth)


@st.composite
def tiny_specs(draw: st.DrawFn) -> GR1Spec:
    n_in = draw(st.integers(1, 2))
    n_out = draw(st.integers(1, 2))
    ins = [f"x{k}" for k in range(n_in)]
    outs = [f"y{k}" for k in range(n_out)]
    pre = ins + outs
    env_post = pre + [n + "'" for n in ins]
    all_post = env_post + [n + "'" for n in outs]

    def some(names: list[str], most: int) -> tuple[Clause, ...]:
        return clauses(*draw(st.lists(formulas(names, 5), max_size=most)))

    return GR1Spec(
        inputs=tuple(Variable(n) for n in ins),
        outputs=tuple(Variable(n) for n in outs),
        env_init=some(ins, 1),
        sys_init=some(pre, 1),
        env_trans=some(env_post, 1),
        sys_trans=some(all_post, 2),
        env_liveness=some(env_post, 2),
        sys_liveness=some(all_post, 2),
    )


def _exactly_one(names: list[str], primed: bool) -> Expr:
    some = Or(tuple(Var(n, primed) for n in names))
    pairs = [
        Not(And((Var(a, primed), Var(b, primed)))) for a, b in itertools.combinations(names, 2)
    ]
    return And((some, *pairs))


@st.composite
def one_hot_specs(draw: st.DrawFn) -> GR1Spec:
    """Random specs over a one-hot input pair and a one-hot output triple, as the .gait
    lowering writes them: mutexes in ρe/ρs over primed variables (invariants, a care set),
    in θe/θs only sometimes (then initial states lie outside the invariant)."""
    ins, outs = ["a", "b"], ["p", "q", "r"]
    pre = ins + outs
    all_post = pre + [n + "'" for n in pre]
    env_post = [*pre, "a'", "b'"]

    def some(names: list[str], most: int) -> tuple[Clause, ...]:
        return clauses(*draw(st.lists(formulas(names, 6), max_size=most)))

    mutex_init = draw(st.booleans())
    env_init = clauses(_exactly_one(ins, False)) if mutex_init else ()
    sys_init = clauses(_exactly_one(outs, False)) if mutex_init else ()
    return GR1Spec(
        inputs=tuple(Variable(n) for n in ins),
        outputs=tuple(Variable(n) for n in outs),
        env_init=env_init + some(ins, 1),
        sys_init=sys_init + some(pre, 1),
        env_trans=clauses(_exactly_one(ins, True)) + some(env_post, 1),
        sys_trans=clauses(_exactly_one(outs, True)) + some(all_post, 2),
        env_liveness=some(env_post, 2),
        sys_liveness=some(all_post, 2),
    )
