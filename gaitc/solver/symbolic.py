"""The symbolic game: a CUDD BDD manager, the variable order, and a GR(1) spec as BDDs.

Each bit sits next to its primed copy and the bits of an integer stay together, as in SLUGS
(Ehlers & Raman, CAV 2016); integers follow SLUGS's little-endian encoding ``x@0.MIN.MAX``,
``x@1``, ... with value = MIN + bits, and non-power-of-two ranges get SLUGS's range constraints.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterable, Sequence
from typing import Final, TypeAlias

from gaitc.diagnostics import FormulaError
from gaitc.ir.bits import spec_bits
from gaitc.ir.cuddlib import cudd
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
    Node,
    Not,
    Or,
    Term,
    Var,
    Xor,
    formula_kind,
    term_kind,
    unreachable,
)
from gaitc.ir.manager import manager
from gaitc.ir.spec import Clause, GR1Spec, Variable
from gaitc.ir.traversal import Memo, fold
from gaitc.solver.bitvectors import add, less, xor
from gaitc.solver.clusters import clusters
from gaitc.solver.options import MEMORY_STOP, SIFT_TRIGGER, Options
from gaitc.solver.ordering import AtomCache, invariant_clauses, variable_order

__all__ = ["MEMORY_STOP", "SIFT_TRIGGER", "BDDNode", "Options", "SymbolicSpec"]
BDDNode: TypeAlias = cudd.Function  # a node of the game's manager (typings/dd/cudd.pyi)


#: Nodes of the clause products made so far past which they are joined (_conj_under).
PENDING_NODES: Final = 50_000


class _OrderTooLarge(Exception):
    """Raised inside the build when the static order does not fit (``Options.sift_above``)."""


class SymbolicSpec:
    """A GR(1) spec over a BDD manager: pre/post copies of every bit and the sections as BDDs."""

    def __init__(
        self,
        spec: GR1Spec,
        options: Options | None = None,
        deadline: Callable[[], None] | None = None,
    ) -> None:
        """``deadline`` is called between building steps; it raises to stop (a timeout)."""
        self.spec = spec
        self.options = options or Options()
        self._given_deadline = deadline or (lambda: None)
        self._budget = None if self.options.memory_mb is None else (
            self.options.memory_mb * 1024 * 1024)
        self.input_bits, self.output_bits = spec_bits(spec)
        self.var_bits: dict[str, list[str]] = {}
        ins, outs = iter(self.input_bits), iter(self.output_bits)
        for v in spec.inputs:
            self.var_bits[v.name] = [next(ins) for _ in range(v.bits if v.is_integer else 1)]
        for v in spec.outputs:
            self.var_bits[v.name] = [next(outs) for _ in range(v.bits if v.is_integer else 1)]
        self.variables = {v.name: v for v in spec.variables()}
        self._atoms = AtomCache()  # the variables of each clause, for every pass below
        self.order = self._bit_order(self.options.order)
        # Choices (the smallest move, the first initial state) are made in the static order
        # whatever the engine, so that a controller does not depend on which racer won.
        static = self.order if self.options.order == "guards" else self._bit_order("guards")
        self.choice_rank = {bit: k for k, bit in enumerate(static)}
        self.prime_map = {b: b + "'" for b in self.input_bits + self.output_bits}
        self.unprime_map = {p: b for b, p in self.prime_map.items()}
        self.pre_inputs = set(self.input_bits)
        self.pre_outputs = set(self.output_bits)
        self.post_inputs = {b + "'" for b in self.input_bits}
        self.post_outputs = {b + "'" for b in self.output_bits}
        opts = self.options
        self.restarted = False
        try:
            self._start(sift=opts.sift_build and not opts.reordering)
        except _OrderTooLarge:  # start again, sifting from the first clause on
            self._start(sift=True)
            self.restarted = True  # the game sifts again once a step is slow (Game.resume_sifting)

    @property
    def refitted(self) -> bool:
        """Whether the order was sifted for ρ because the static one misfit it (a restarted
        build, or one sifted once built); its game sifts again once a step is slow."""
        return self.restarted or self.settled

    def _static_order_may_go(self) -> bool:
        """Whether the build's order is the static one and nothing keeps it: not sifted
        already, no dynamic reordering, no variables pinned on purpose (``first``)."""
        opts = self.options
        return not self.sifted_build and not opts.reordering and not opts.first

    def _start(self, sift: bool) -> None:
        """A fresh BDD manager in the static order, and the spec built in it; with ``sift``
        CUDD sifts while building, to convergence at the end, and then keeps the order."""
        opts = self.options
        # CUDD sizes its caches from a budget and fails cleanly at its maximum
        self.bdd = manager(self._budget)
        self.bdd.declare(*self.order)
        if (opts.reorder_once or opts.reordering or opts.sift_build
                or opts.sift_above is not None or opts.sift_blowup is not None):
            for bit in self.input_bits + self.output_bits:
                self.bdd.group({bit: 2})  # sifting moves a bit and its primed copy together
        self.sifted_build = sift  # whether CUDD sifted while ρ was built
        self._memo: Memo[BDDNode] = {}
        # comparisons by structure: a map's clauses compare the same integers with the same
        # numbers over and over, each a new node (the memo above is by node)
        self._compares: dict[Compare, BDDNode] = {}
        self.bdd.configure(reordering=sift or bool(opts.reordering))
        self._build()
        self.bdd.configure(reordering=False)
        # the static order misfits ρs when it comes out far larger than its clauses
        self.settled = (opts.sift_blowup is not None and not opts.reorder_once
                        and self._static_order_may_go()
                        and self.sys_trans.dag_size > opts.sift_blowup * self._sys_parts)
        if opts.reorder_once or sift or self.settled:
            self._sift_to_convergence()
        if opts.reordering:
            self.bdd.configure(reordering=True)

    def _sift_to_convergence(self) -> None:
        """Group sifting until a run gains less than 2 % (CUDD's converging sifting)."""
        before = len(self.bdd)
        for _ in range(10):
            self._checkpoint()  # a sifting run is one CUDD call: check the deadline between
            self.bdd.reorder()
            after = len(self.bdd)
            if after > 0.98 * before:
                return
            before = after

    def _bit_order(self, how: str) -> list[str]:
        """Every bit and its primed copy, top to bottom, for variable order ``how``."""
        order: list[str] = []
        ordered = variable_order(self.spec, how, self._atoms)
        pinned = [v for name in self.options.first for v in ordered if v.name == name]
        for v in pinned + [v for v in ordered if v not in pinned]:
            for bit in self.var_bits[v.name]:
                order += [bit, bit + "'"]
        return order

    # ------------------------------------------------------------ building
    def _build(self) -> None:
        s = self.spec
        true = self.bdd.true
        env_range_init, env_range_trans, sys_range_init, sys_range_trans = [], [], [], []
        for v in s.inputs + s.outputs:
            if v.is_integer and v.low is not None and v.high is not None:
                width = v.high - v.low + 1
                if width != 1 << len(self.var_bits[v.name]):
                    now = self._range(v, width, False)
                    nxt = self._range(v, width, True)
                    if v in s.inputs:
                        env_range_init.append(now)
                        env_range_trans.append(nxt)
                    else:
                        sys_range_init.append(now)
                        sys_range_trans.append(nxt)
        self.env_init = self._conj(self._translated(s.env_init) + env_range_init)
        self.sys_init = self._conj(self._translated(s.sys_init) + sys_range_init)
        env_inv, sys_inv = invariant_clauses(s, self._atoms)
        env_next = self._conj(self._translated(env_inv) + env_range_trans)
        sys_inv_parts = self._translated(sys_inv) + sys_range_trans
        sys_next = self._conj(sys_inv_parts)
        known = {id(c) for c in env_inv + sys_inv}
        env_rest = self._translated([c for c in s.env_trans if id(c) not in known])
        sys_rest = self._translated([c for c in s.sys_trans if id(c) not in known])
        self._sys_parts = sum(p.dag_size for p in sys_inv_parts + sys_rest)  # nodes apart
        self.env_trans = self._conj_under(env_next, env_rest)
        self.sys_trans = self._conj_under(sys_next, sys_rest)
        self.sys_clusters: list[tuple[BDDNode, set[str]]] = []
        if self.options.partitioned:
            parts = [self.translate(c.formula) for c in s.sys_trans] + sys_range_trans
            self.sys_clusters = clusters(self.bdd, parts, self.post_outputs,
                                         self.options.cluster_limit)
        self.env_live = [self.translate(c.formula) for c in s.env_liveness] or [true]
        self.sys_live = [self.translate(c.formula) for c in s.sys_liveness] or [true]
        # ∃y'.¬ρe: when ρe does not mention primed outputs this is just ¬ρe.
        self.env_blocks = self.bdd.exist(self.post_outputs, ~self.env_trans)
        self._memo.clear()
        self._compares.clear()
        self._care_set(env_next, sys_next)

    def _translated(self, clauses: Sequence[Clause]) -> list[BDDNode]:
        """The BDDs of ``clauses``, checking the deadline between them."""
        out = []
        for clause in clauses:
            self._checkpoint()
            out.append(self.translate(clause.formula))
        return out

    def _care_set(self, env_next: BDDNode, sys_next: BDDNode) -> None:
        """The states the fixpoint must get right, and ρ simplified outside them.

        I = Ie ∧ Is, with ρe → Ie' and ρs → Is' (invariant clauses and range limits), holds in
        every state after the first step.  Because ∀x'. ρe → ∃y'. ρs ∧ T only looks at T inside
        Ie' ∧ Is', CPre(T) = CPre(T ∧ C') for C = I ∨ (θe ∧ θs) ⊇ I: the game's sets matter only
        on C, the fixpoints of the masked operators S ↦ G(S) ∧ C are the exact fixpoints ∧ C
        (docs/design-notes.md has the proof), and so they are exact on every state that the
        initial condition or a strategy ever looks at.  ρ itself is needed only for pre-states
        in C (and ρs only for next inputs in Ie'), so both are simplified with Coudert and
        Madre's restrict (ICCAD 1990); ``game_*`` hold the simplified copies.
        """
        self.invariant = self.unprime(env_next & sys_next)
        if not self.options.care or self.invariant == self.bdd.true:
            self.care = self.bdd.true
            self.game_env_blocks = self.env_blocks
            self.game_sys_trans = self.sys_trans
            return
        self.care = self.invariant | (self.env_init & self.sys_init)
        if self.care == self.bdd.false:  # nothing to solve; restrict needs a non-empty set
            self.game_env_blocks, self.game_sys_trans = self.env_blocks, self.sys_trans
            return
        self.game_env_blocks = cudd.restrict(self.env_blocks, self.care)
        self.game_sys_trans = cudd.restrict(self.sys_trans, self.care & env_next)

    def _conj(self, items: Iterable[BDDNode]) -> BDDNode:
        out = self.bdd.true
        for item in items:
            out &= item
        return out

    def check_memory(self) -> None:
        """Raise MemoryError once CUDD holds :data:`MEMORY_STOP` of its budget."""
        if self._budget is None:
            return
        with warnings.catch_warnings():  # dd warns that 'mem' is in bytes since 0.5.7
            warnings.simplefilter("ignore")
            used = float(self.bdd.statistics()["mem"])
        if used > MEMORY_STOP * self._budget:
            raise MemoryError(f"CUDD holds {used / 2**20:.0f} MB of its "
                              f"{self._budget / 2**20:.0f} MB")

    def _checkpoint(self) -> None:
        self._given_deadline()
        self.check_memory()

    def _conj_under(self, base: BDDNode, items: Sequence[BDDNode]) -> BDDNode:
        """``base`` ∧ every item, as a balanced tree over the products ``base ∧ item``.

        With the invariants as ``base`` every partial product stays inside the mutexes, so
        it stays small; a left fold over the 900 move clauses of a 30 x 30 grid took 34 s.
        The products are made first, then joined; but once the products made so far hold
        more than :data:`PENDING_NODES` nodes (each counted alone), they are joined into one
        part before more are made.  On the 1024 x 1024 gridworld each of the 2,049 products has
        the size of ``base`` (the obstacle's 64 cells), and all of them alive took 900,000
        live nodes for a relation of 2,000 (179 MB; issue 37).  Only in a fixed order: while
        CUDD sifts, joining as the products come changes when it sifts and so the order it
        ends in (GenBuf with 16 senders, whose build restarts sifting: a relation of 2,406
        nodes instead of 1,731, and a fixpoint three times slower).
        """
        parts: list[BDDNode] = []
        pending: list[BDDNode] = []
        held = 0  # the nodes of the pending products, each counted alone
        fixed = not (self.sifted_build or self.options.reordering)  # the order stays put
        for item in items:
            self._checkpoint()
            pending.append(self._watch(base & item))
            held += pending[-1].dag_size if fixed else 0
            if held > PENDING_NODES:
                parts.append(self._balanced(pending))
                pending, held = [], 0
        return self._balanced([*parts, self._balanced(pending)] if pending else parts or [base])

    def _balanced(self, level: list[BDDNode]) -> BDDNode:
        """The conjunction of ``level``, joined pairwise level by level."""
        while len(level) > 1:
            self._checkpoint()
            paired = [self._watch(a & b) for a, b in zip(level[::2], level[1::2], strict=False)]
            level = paired + ([level[-1]] if len(level) % 2 else [])
        return level[0]

    def _watch(self, product: BDDNode) -> BDDNode:
        """``product``, unless it is too large for the static order (``Options.sift_above``,
        :data:`~gaitc.solver.options.SIFT_TRIGGER`): then the build starts again, sifting."""
        opts = self.options
        if (opts.sift_above is not None and self._static_order_may_go()
                and product.dag_size > opts.sift_above * len(self.prime_map)):
            raise _OrderTooLarge
        return product

    def _range(self, v: Variable, width: int, primed: bool) -> BDDNode:
        bits = [self.bit(b, primed) for b in self.var_bits[v.name]]
        return less(bits, self._const_bits(width, len(bits)), self.bdd)

    # ------------------------------------------------------------ formulas
    def bit(self, name: str, primed: bool) -> BDDNode:
        return self.bdd.var(name + "'" if primed else name)

    def prime(self, u: BDDNode) -> BDDNode:
        return self.bdd.let(self.prime_map, u)

    def unprime(self, u: BDDNode) -> BDDNode:
        return self.bdd.let(self.unprime_map, u)

    def translate(self, expr: Expr) -> BDDNode:
        """The BDD of a formula; shared sub-formulas (DAGs) are translated once."""
        return fold(expr, self._translate, _operands, self._memo)

    def _translate(self, e: Node, args: list[BDDNode]) -> BDDNode:
        """The BDD of ``e`` from the BDDs of its operands (a step of the fold)."""
        b = self.bdd
        kind = formula_kind(e)
        match kind:
            case Const():
                return b.true if kind.value else b.false
            case Var():
                v = self.variables.get(kind.name)
                if v is None:
                    raise FormulaError(f"unknown variable '{kind.name}'", kind.span)
                if v.is_integer:
                    raise FormulaError(
                        f"'{kind.name}' is an integer; compare it with a number (e.g. "
                        f"{kind.name} = 0)", kind.span)
                return self.bit(self.var_bits[kind.name][0], kind.primed)
            case Not():
                return ~args[0]
            case And():
                return self._conj(args)
            case Or():
                out = b.false
                for a in args:
                    out |= a
                return out
            case Xor():
                return xor(args[0], args[1], b)
            case Iff():
                return ~xor(args[0], args[1], b)
            case Implies():
                return ~args[0] | args[1]
            case Compare():
                known = self._compares.get(kind)
                if known is None:
                    known = self._compares[kind] = self._compare(kind)
                return known
            case Next() | Always() | Eventually():
                raise FormulaError(
                    f"'{type(kind).__name__}' cannot appear in a GR(1) section; rewrite it "
                    "without temporal operators", kind.span)
            case _:
                unreachable(kind)

    # ------------------------------------------------------------ integer arithmetic
    def _const_bits(self, value: int, width: int = 0) -> list[BDDNode]:
        out: list[BDDNode] = []
        while value > 0 or len(out) < width:
            out.append(self.bdd.true if value & 1 else self.bdd.false)
            value >>= 1
        return out

    def _term(self, t: Term) -> tuple[list[BDDNode], int]:
        """A term as (unsigned little-endian bit vector, offset): value = bits + offset."""

        def combine(node: Node, kids: list[tuple[list[BDDNode], int]]) -> tuple[
            list[BDDNode], int
        ]:
            kind = term_kind(node)
            match kind:
                case IntConst():
                    return [], kind.value
                case IntVar():
                    v = self.variables.get(kind.name)
                    if v is None:
                        raise FormulaError(f"unknown variable '{kind.name}'", kind.span)
                    bits = [self.bit(bit, kind.primed) for bit in self.var_bits[kind.name]]
                    return bits, v.low if v.low is not None else 0
                case Add():
                    (lb, lo), (rb, ro) = kids
                    return add(lb, rb, self.bdd), lo + ro
                case _:
                    unreachable(kind)

        return fold(t, combine, lambda n: n.children() if isinstance(n, Add) else ())

    def _compare(self, e: Compare) -> BDDNode:
        a, oa = self._term(e.left)
        c, oc = self._term(e.right)
        d = oa - oc
        if d > 0:
            a = add(a, self._const_bits(d), self.bdd)
        elif d < 0:
            c = add(c, self._const_bits(-d), self.bdd)
        n = max(len(a), len(c))
        a = a + [self.bdd.false] * (n - len(a))
        c = c + [self.bdd.false] * (n - len(c))
        eq = self._conj(~xor(x, y, self.bdd) for x, y in zip(a, c, strict=True))
        ops: dict[str, Callable[[], BDDNode]] = {
            "=": lambda: eq,
            "!=": lambda: ~eq,
            "<": lambda: less(a, c, self.bdd),
            "<=": lambda: less(a, c, self.bdd) | eq,
            ">": lambda: less(c, a, self.bdd),
            ">=": lambda: less(c, a, self.bdd) | eq,
        }
        if e.op not in ops:
            raise FormulaError(f"unknown comparison '{e.op}'", e.span)
        return ops[e.op]()

    # ------------------------------------------------------------ helpers for the game
    def node_count(self) -> int:
        return len(self.bdd)

    def assignment_cube(self, values: dict[str, bool]) -> BDDNode:
        return self.bdd.cube(values)


def _operands(node: Node) -> Sequence[Node]:
    """The subformulas :meth:`SymbolicSpec.translate` needs first: those of the Boolean
    operators (a comparison is translated whole, any other node is rejected)."""
    return node.children() if isinstance(node, (Not, And, Or, Xor, Iff, Implies)) else ()
